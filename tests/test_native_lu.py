"""The sparse LU of the native driver (acausal2d/runtime/native_lu.c, the
"sparse-lu" linear solver) built alone and called through ctypes: solutions
against numpy.linalg.solve on random sparse matrices, on matrices that need
row exchanges, after refactorizations; a singular matrix gives a flag."""
import ctypes
import os

import numpy as np
import pytest

from acausal2d.runtime import cbuild, ordering

HERE = os.path.dirname(os.path.abspath(__file__))
LU_C = os.path.join(HERE, "..", "acausal2d", "runtime", "native_lu.c")
_P, _I = ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_int)

pytestmark = pytest.mark.skipif(cbuild.find_compiler() is None, reason="no C compiler")


@pytest.fixture(scope="module")
def lib():
    with open(LU_C, encoding="utf-8") as fh:
        path = cbuild.build({"native_lu.c": fh.read()}, flags=["-O1"], libraries=["m"],
                            name="a2d_splu_test")
    lib = ctypes.CDLL(path)
    lib.a2d_splu_new.restype = ctypes.c_void_p
    lib.a2d_splu_new.argtypes = [ctypes.c_int, ctypes.c_int, _I, _I]
    lib.a2d_splu_free.argtypes = [ctypes.c_void_p]
    for name in ("a2d_splu_factor", "a2d_splu_refactor"):
        getattr(lib, name).argtypes = [ctypes.c_void_p, _I, _I, _P]
    lib.a2d_splu_solve.argtypes = [ctypes.c_void_p, _P, _P, _P]
    lib.a2d_splu_count.restype = ctypes.c_long
    lib.a2d_splu_count.argtypes = [ctypes.c_void_p, ctypes.c_int]
    lib.a2d_splu_nnz.restype = ctypes.c_long
    lib.a2d_splu_nnz.argtypes = [ctypes.c_void_p]
    return lib


class LU:
    """One factorization object of native_lu.c on the pattern of ``a``."""

    def __init__(self, lib, a):
        self.lib, self.n = lib, a.shape[0]
        self.colind, self.row = _ccs(a != 0)
        q, prefer = ordering.lu_order(self.n, self.colind, self.row)
        self.handle = lib.a2d_splu_new(self.n, len(self.row), _ptr(q, _I), _ptr(prefer, _I))

    def values(self, a):
        return np.ascontiguousarray([a[r, c] for c in range(self.n)
                                     for r in self.row[self.colind[c]:self.colind[c + 1]]])

    def factor(self, a, refactor=False):
        fn = self.lib.a2d_splu_refactor if refactor else self.lib.a2d_splu_factor
        self._x = self.values(a)
        return fn(self.handle, _ptr(self.colind, _I), _ptr(self.row, _I), _ptr(self._x))

    def solve(self, b):
        x = np.array(b, dtype=float)
        w = np.zeros(self.n)
        assert self.lib.a2d_splu_solve(self.handle, _ptr(x), _ptr(x), _ptr(w)) == 0
        return x

    def count(self, which):
        return self.lib.a2d_splu_count(self.handle, which)

    def __del__(self):
        self.lib.a2d_splu_free(self.handle)


def _ptr(a, kind=_P):
    return a.ctypes.data_as(kind)


def _ccs(mask):
    cols = [np.nonzero(mask[:, c])[0] for c in range(mask.shape[1])]
    colind = np.r_[0, np.cumsum([len(c) for c in cols])].astype(np.intc)
    return colind, np.ascontiguousarray(np.concatenate(cols), dtype=np.intc)


def _random(rng, n, density, dominant=True):
    """A random sparse n x n matrix, rows and columns shuffled."""
    a = rng.standard_normal((n, n)) * (rng.random((n, n)) < density)
    if dominant:
        a += np.diag(np.sum(np.abs(a), axis=1) + 1.0)
    p, q = rng.permutation(n), rng.permutation(n)
    return a[p][:, q]


def _check(lu, a, rng, tol=1e-12):
    for _ in range(3):
        b = rng.standard_normal(lu.n)
        x = lu.solve(b)
        ref = np.linalg.solve(a, b)
        assert np.max(np.abs(x - ref)) <= tol * np.max(np.abs(ref)), lu.n


@pytest.mark.parametrize("n,density", [(1, 1.0), (5, 0.4), (40, 0.08), (217, 0.015),
                                       (400, 0.006)])
def test_random_sparse_matrices_solve_as_numpy(lib, n, density):
    rng = np.random.default_rng(n)
    a = _random(rng, n, density)
    lu = LU(lib, a)
    assert lu.factor(a) == 0
    _check(lu, a, rng)
    assert lib.a2d_splu_nnz(lu.handle) >= np.count_nonzero(a)


def test_matrices_that_need_row_exchanges(lib):
    """Tiny preferred pivots (1e-9 against entries of order 1): the pivoting
    takes another row, and the solution is as accurate as numpy's."""
    rng = np.random.default_rng(7)
    for n in (2, 3, 30, 120):
        a = rng.standard_normal((n, n)) * (rng.random((n, n)) < 6.0 / n)
        a[np.arange(n), np.arange(n)] = 1e-9
        a[np.arange(n), np.roll(np.arange(n), 1)] += 1.0 + rng.random(n)
        if np.linalg.cond(a) > 1e8:
            continue
        lu = LU(lib, a)
        assert lu.factor(a) == 0
        _check(lu, a, rng, tol=1e-12 * max(1.0, np.linalg.cond(a) / 1e3))


def test_refactor_reuses_the_pivots_and_falls_back_where_they_go_stale(lib):
    rng = np.random.default_rng(3)
    a = _random(rng, 60, 0.07)
    lu = LU(lib, a)
    assert lu.factor(a) == 0
    b = a * (1.0 + 1e-3 * rng.standard_normal(a.shape))      # same pattern, new values
    assert lu.factor(b, refactor=True) == 0
    _check(lu, b, rng)
    assert (lu.count(0), lu.count(1)) == (1, 1)
    # a pivot gone to zero: refactor declines, a full factorization
    # exchanges the rows
    a2 = np.array([[2.0, 1.0], [1.0, 2.0]])
    c2 = np.array([[0.0, 1.0], [1.0, 0.0]])
    lu2 = LU(lib, a2)
    assert lu2.factor(a2) == 0
    assert lu2.factor(c2, refactor=True) == 1
    assert lu2.factor(c2, refactor=True) == 1          # nothing valid to reuse now
    assert lu2.factor(c2) == 0
    _check(lu2, c2, rng)
    assert (lu2.count(0), lu2.count(1)) == (2, 0)


def test_a_singular_matrix_is_a_flag(lib):
    a = np.array([[1.0, 2.0, 0.0], [2.0, 4.0, 0.0], [0.0, 1.0, 3.0]])
    lu = LU(lib, a)
    status = lu.factor(a)
    assert status > 0
    x = np.zeros(3)
    assert lib.a2d_splu_solve(lu.handle, _ptr(x), _ptr(x), _ptr(np.zeros(3))) == -1
    structurally = np.array([[1.0, 0.0], [1.0, 0.0]])
    lu = LU(lib, structurally)
    assert lu.factor(structurally) > 0


# --- the LU as IDA's linear solver in the native driver -----------------------

def _chain_problem(links, solver):
    """(library, NativeIDA with ``solver``, formulation, y0, yp0, times) of
    a chain of pendulum links (76 unknowns for 4 links: a sparse size)."""
    import sys
    sys.path.insert(0, os.path.join(HERE, "..", "benchmarks"))
    from bench_core import PendulumChain

    import acausal2d
    from acausal2d.runtime import native
    from acausal2d.runtime.simulation import Simulation
    if not native.enabled():
        pytest.skip("another SUNDIALS: no native driver")
    cm = acausal2d.compile_model(PendulumChain(links))
    opts = cm.run_options(stop_time=1.0, intervals=100, rtol=1e-8)
    times, rtol, atol = opts.times(), opts.rtol, opts.atol
    sim = Simulation(cm.system, cm.parameter_values(None), times, rtol, atol)
    sim.run()
    form, prob = sim._solver()[:2]
    atol = np.broadcast_to(rtol * cm.system.nominal, (form.n,)).copy()
    drv = native.native_ida(prob, rtol, atol, solver=solver)
    y0, yp0 = form.y_from(sim.out[0][1])
    return native.library(form), drv, form, y0, yp0, times


def _probe(lib, drv, values, b):
    lib.a2d_probe.argtypes = [ctypes.c_void_p, _P, _P, ctypes.POINTER(ctypes.c_long)]
    info = np.zeros(6, dtype=np.dtype(ctypes.c_long))
    x = np.array(b, dtype=float)
    lib.a2d_probe(drv.handle, _ptr(np.ascontiguousarray(values, float)), _ptr(x),
                  info.ctypes.data_as(ctypes.POINTER(ctypes.c_long)))
    return info, x


def test_the_driver_gives_ida_the_lu_through_the_op_slots_it_found():
    """SUNDIALS' generic SUNLinSolSetup/Solve/GetType reach the LU (the op
    slots were found, no fallback to SuperLU_MT): a direct solver (type 0)
    that solves the chain's iteration matrix as numpy does; an all-zero
    matrix gives setup the recoverable flag SUNLS_LUFACT_FAIL (9) that
    makes IDA cut its step, not a crash."""
    lib, drv, form, y0, yp0, _ = _chain_problem(4, "sparse-lu")
    assert form.n >= 64
    jac = form.jac_fn(0.0, y0, yp0, drv.prob.res.args[3], drv.prob.res.args[4], 1e3)
    values, a = np.array(jac.nonzeros()), np.array(jac.full())
    b = np.random.default_rng(1).standard_normal(form.n)
    info, x = _probe(lib, drv, values, b)
    assert list(info[[0, 1, 2, 3, 5]]) == [0, 0, 0, 0, 3]
    assert info[4] >= 2 * len(values)
    ref = np.linalg.solve(a, b)
    assert np.max(np.abs(x - ref)) <= 1e-12 * np.linalg.cond(a) * np.max(np.abs(ref))
    info, _ = _probe(lib, drv, np.zeros_like(values), b)
    assert info[1] == 9 and info[2] > 0 and info[5] == 3
    info, x = _probe(lib, drv, values, b)                   # and it recovers
    assert info[1] == 0
    assert np.max(np.abs(x - ref)) <= 1e-12 * np.linalg.cond(a) * np.max(np.abs(ref))


def test_a_chain_runs_through_the_lu_by_default_as_through_superlu_mt():
    """The default linear solver of a sparse-size system is the LU; its IDA
    run over 1 s of the chain of 4 links (rtol 1e-8) gives SuperLU_MT's
    output rows to 1e-6 of each unknown's scale (measured 4.9e-8; 773 and
    774 steps: the step sequences differ by rounding)."""
    from acausal2d.runtime import native
    lib, lu, form, y0, yp0, times = _chain_problem(4, None)
    assert native.default_solver(form.n) == "sparse-lu"
    info, _ = _probe(lib, lu, np.ones(form.jac_sparsity.nnz()), np.ones(form.n))
    assert info[5] == 3                    # the driver made the LU, not the fallback
    _, superlu, *_ = _chain_problem(4, "sparse")
    a, b = lu.run(times, y0, yp0), superlu.run(times, y0, yp0)
    assert a[0] >= 0 and b[0] >= 0 and len(a[1]) == len(b[1]) == len(times) - 1
    scale = 1.0 + np.max(np.abs(b[2]), axis=0)       # per unknown
    assert np.max(np.abs(a[2] - b[2]) / scale) <= 1e-6
    assert abs(a[-1] - b[-1]) <= 0.1 * b[-1]        # steps within 10 %


def test_the_lu_is_found_in_a_process_that_loaded_scikit_sundae_first():
    """scikit-sundae's import loads the dense solver's own library before
    the driver's: its op slots then hold that library's copy of the dense
    solver's functions, not the IDA library's (the driver found no slot
    and fell back to SuperLU_MT in every process that had run the Python
    path first).  The slots are found by the functions' names."""
    import subprocess
    import sys
    code = ("import sksundae.ida\n"
            "import sys\n"
            "sys.path[:0] = [%r]\n"
            "import test_native_lu as t\n"
            "lib, drv, *_ = t._chain_problem(4, 'sparse-lu')\n"
            "print(lib.a2d_lu_usable(), t._probe(lib, drv, t.np.ones(drv.prob.form.jac_sparsity"
            ".nnz()), t.np.ones(drv.n))[0][5])\n" % HERE)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=600, cwd=HERE)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["1", "3"], out.stdout + out.stderr[-2000:]
