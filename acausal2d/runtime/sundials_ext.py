"""IDA settings that scikit-sundae does not expose, set on its IDA memory
through the SUNDIALS library it ships.

Used on the Python path only: the native driver (:mod:`.native`, wherever a
C compiler is found) owns its IDA memory and sets ``IDASetSuppressAlg``
itself.  scikit-sundae (1.2, and its sources up to the unreleased version
after 1.1.0) has no public route to its IDA memory (the pointer is a
``cdef`` attribute; no option sets suppressalg), so on the Python path the
guarded read below stays.

Its public substitute, an absolute tolerance vector that is huge on the
algebraic unknowns (:data:`~acausal2d.runtime.ida.ALGEBRAIC_ATOL`, the
fallback of :func:`~acausal2d.runtime.ida.start_solver`), weights them out
of IDA's local error test as suppressalg does, but IDA's Newton convergence
test uses the same weights (suppressalg leaves them in it): the iteration
then stops before the algebraic unknowns converge, and the error test of
the following steps pays for it.  Measured (Python path, rtol
1e-8, Dymola's output grid; steps / residual evaluations, largest deviation
from Dymola's reference):

- suppressalg (as here): pendulum 579 / 1453, piston engine 1463 / 3624;
  deviation 3.3e-5 and 1.1e-4;
- atol 1e10 atol/rtol on the algebraic unknowns (the fallback): 1105 / 1670
  and 2625 / 3992, the same deviations;
- 1e3 ... 1e-1 atol/rtol there: 993 ... 1153 and 2562 ... 2741 steps;
- every unknown tested with atol: 1715 / 2387 and 4186 / 5948.

No atol gives today's steps (+70 % or more), so the setting stays.

scikit-sundae keeps the IDA memory pointer in its Cython object; it is read
at its place in the object (after the Python object header and the Cython
method table) and accepted only if IDA itself confirms it: the time IDA
reports through ``IDAGetCurrentTime`` must equal the time of the last
``init_step``.  Otherwise nothing is set and :func:`suppress_algebraic`
returns False, and the caller uses its fallback.
"""
import ctypes
import glob
import os

_lib = None


def _library():
    global _lib
    if _lib is None:
        from .sundae import sksundae      # the Python path only: it imports scipy
        folder = os.path.join(os.path.dirname(sksundae.__file__), "..", "scikit_sundae.libs")
        found = glob.glob(os.path.join(folder, "libsundials_ida-*.so*"))
        _lib = ctypes.CDLL(found[0]) if found else False
        if _lib:
            _lib.IDAGetCurrentTime.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_double)]
            _lib.IDASetSuppressAlg.argtypes = [ctypes.c_void_p, ctypes.c_int]
    return _lib


def ida_memory(solver, t0):
    """The IDA memory pointer of an initialized scikit-sundae IDA object
    (after ``init_step(t0, ...)``), or None if it cannot be confirmed."""
    lib = _library()
    obj = getattr(solver, "_IDA__IDA", None)
    if not lib or obj is None:
        return None
    mem = ctypes.c_void_p.from_address(id(obj) + 3 * ctypes.sizeof(ctypes.c_void_p)).value
    if not mem:
        return None
    t = ctypes.c_double(float("nan"))
    if lib.IDAGetCurrentTime(ctypes.c_void_p(mem), ctypes.byref(t)) != 0 or t.value != t0:
        return None
    return mem


def suppress_algebraic(mem):
    """Leave the algebraic unknowns out of IDA's local error test
    (``IDASetSuppressAlg``); True if set."""
    lib = _library()
    return bool(lib) and mem is not None and \
        lib.IDASetSuppressAlg(ctypes.c_void_p(mem), 1) == 0
