"""QR with column pivoting (LAPACK ``dgeqp3``) without importing scipy.

The dummy-derivative choice needs ``scipy.linalg.qr(M, pivoting=True,
mode="economic")`` for R's diagonal and the pivot order.  Importing
``scipy.linalg`` costs 0.1-0.15 s (scipy 1.17's array-API layer clones the
numpy namespace, which imports numpy.f2py, numpy.testing, ...), more than
compiling and simulating a small model.  So :func:`qr_pivoted` calls
``dgeqp3`` of the OpenBLAS that the scipy wheel ships (the very library
``scipy.linalg`` calls, with the same workspace query and the same
arguments, so the results are identical bit for bit) through ctypes.  Where
that library is not found (another scipy build), it calls
``scipy.linalg.qr``.
"""
import ctypes
import glob
import importlib.util
import os

import numpy as np

_lapack = None


def _find_dgeqp3():
    """``dgeqp3`` of the OpenBLAS in the scipy wheel (``scipy.libs``), or
    False: ``scipy_dgeqp3_`` of ``libscipy_openblas-*.so`` (scipy >= 1.13)
    or ``dgeqp3_`` of ``libopenblasp-*.so`` (older wheels, e.g. the floor
    scipy 1.10; both 32-bit integers)."""
    spec = importlib.util.find_spec("scipy")
    if spec is None or not spec.submodule_search_locations:
        return False
    libs = os.path.join(os.path.dirname(list(spec.submodule_search_locations)[0]), "scipy.libs")
    for pattern, symbol in (("libscipy_openblas-*.so", "scipy_dgeqp3_"),
                            ("libopenblasp-*.so", "dgeqp3_")):
        for path in sorted(glob.glob(os.path.join(libs, pattern))):
            try:
                f = getattr(ctypes.CDLL(path), symbol)
            except (OSError, AttributeError):
                continue
            f.restype = None
            return f
    return False


def _geqp3(f, M):
    """(packed QR, 0-based pivots) of the float array M by ``dgeqp3`` ``f``
    (lwork from a workspace query, as scipy does)."""
    m, n = M.shape
    a = np.array(M, dtype=np.float64, order="F")
    jpvt = np.zeros(n, dtype=np.int32)
    tau = np.zeros(min(m, n))
    info = ctypes.c_int(0)
    iv = ctypes.c_int
    ptr = ctypes.c_double

    def call(work, lwork):
        f(ctypes.byref(iv(m)), ctypes.byref(iv(n)), a.ctypes.data_as(ctypes.POINTER(ptr)),
          ctypes.byref(iv(max(m, 1))), jpvt.ctypes.data_as(ctypes.POINTER(ctypes.c_int)),
          tau.ctypes.data_as(ctypes.POINTER(ptr)), work.ctypes.data_as(ctypes.POINTER(ptr)),
          ctypes.byref(iv(lwork)), ctypes.byref(info))
    query = np.zeros(1)
    call(query, -1)
    lwork = int(query[0])
    call(np.zeros(max(lwork, 1)), lwork)
    if info.value < 0:
        raise ValueError("illegal value in argument %d of dgeqp3" % -info.value)
    return a, jpvt - 1


def qr_pivoted(M):
    """(R, pivots) of ``scipy.linalg.qr(M, pivoting=True, mode="economic")``
    (M: a finite 2-D float array)."""
    global _lapack
    if _lapack is None:
        _lapack = _find_dgeqp3()
    M = np.asarray(M, dtype=np.float64)
    m, n = M.shape
    if M.size == 0:                # as scipy >= 1.11 (1.10's qr fails on empty input)
        return np.zeros((min(m, n), n)), np.arange(n, dtype=np.int32)
    if not _lapack:
        import scipy.linalg as sla
        _, r, piv = sla.qr(M, pivoting=True, mode="economic")
        return r, piv
    qr, piv = _geqp3(_lapack, M)
    return (np.triu(qr) if m < n else np.triu(qr[:n, :])), piv
