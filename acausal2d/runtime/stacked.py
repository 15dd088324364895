"""The square Newton matrix [dE/dz; H] of :func:`~acausal2d.runtime.newton.
solve_consistent` (H: one row per held node) factorized by SuperLU without
building scipy.sparse matrices per iteration.

The CSC layout of the stacked matrix is worked out once per evaluator and
set of held nodes; each iteration only gathers the Jacobian's values into
it and calls SuperLU's factorization directly.  The arrays handed to SuperLU
(values, row indices, column pointers, options) are exactly those that
``splu(sp.vstack([J, H]).tocsc())`` hands it, so the steps are the same to
the last bit (event counts and times depend on that rounding)."""
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
try:                 # scipy's own binding of SuperLU (what splu calls); private, so guarded
    from scipy.sparse.linalg._dsolve import _superlu
except ImportError:  # another scipy layout: the general path of newton.py is used
    _superlu = None

# what scipy's splu passes with its defaults (SuperLU chooses: COLAMD, threshold 1)
_OPTIONS = dict(DiagPivotThresh=None, ColPerm=None, PanelSize=None, Relax=None)


class StackedJacobian:
    """[dE/dz; H] in CSC form for ``ev`` with the nodes ``held`` kept."""

    def __init__(self, ev, held):
        n_held = len(held)
        rows = np.concatenate([ev.rows, ev.n_eq + np.arange(n_held)])
        cols = np.concatenate([ev.cols, np.asarray(held, dtype=int)])
        self.ev, self.n = ev, ev.n
        self.order = np.lexsort((rows, cols))          # column-major, rows sorted
        self.indices = rows[self.order].astype(np.intc)
        self.indptr = np.searchsorted(cols[self.order], np.arange(ev.n + 1)).astype(np.intc)
        self.values = np.concatenate([np.zeros(len(ev.rows)), np.ones(n_held)])
        self.unique = len(np.unique(rows * (ev.n + 1) + cols)) == len(rows)

    @classmethod
    def of(cls, ev, held):
        """The cached layout for ``held`` (None where the pattern has
        duplicate entries: the general path sums them)."""
        if _superlu is None:
            return None
        cache = ev.__dict__.setdefault("_stacked", {})
        key = tuple(int(h) for h in held)
        if key not in cache:
            cache[key] = cls(ev, held)
        found = cache[key]
        return found if found.unique else None

    def matrix(self, t, z, d):
        """The CSC values of the stacked matrix at (t, z, d)."""
        self.values[:len(self.ev.rows)] = self.ev.J_values(t, z, d)
        return self.values[self.order]

    def _factor(self, data):
        """SuperLU's factorization of the stacked matrix with values ``data``."""
        try:
            return _superlu.gstrf(self.n, len(data), data, self.indices, self.indptr,
                                  csc_construct_func=sp.csc_array, ilu=False,
                                  options=_OPTIONS)
        except TypeError:      # another signature: through splu (same arrays)
            return spla.splu(sp.csc_array((data, self.indices, self.indptr),
                                          shape=(self.n, self.n)))

    def step(self, t, z, d, r):
        """Newton step -A^-1 r, or the least-squares step where A is
        singular; None where A or r is not finite."""
        return self.step_and_solver(t, z, d, r)[0]

    def step_and_solver(self, t, z, d, r):
        """(:meth:`step`, the LU's solve for more right-hand sides or None
        where the step is not an LU step)."""
        data = self.matrix(t, z, d)
        if not (np.all(np.isfinite(data)) and np.all(np.isfinite(r))):
            return None, None
        with np.errstate(all="ignore"):
            try:
                lu = self._factor(data)
                dz = -lu.solve(r)
            except RuntimeError:
                dz = None
        if dz is not None and np.all(np.isfinite(dz)):
            return dz, lu.solve
        return self._least_squares(data, r), None

    def _least_squares(self, data, r):
        """The minimum-norm least-squares step where A is singular."""
        if self.n > 4000:
            return None
        A = sp.csc_array((data, self.indices, self.indptr), shape=(self.n, self.n)).toarray()
        with np.errstate(all="ignore"):
            return -np.linalg.lstsq(A, r, rcond=1e-12)[0]
