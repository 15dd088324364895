"""Numeric evaluation of a compiled system's functions at (t, z, p, d),
through :class:`~acausal2d.runtime.buffered.Buffered` (about 1 us a call):
the residuals E of all index-reduced equations, their Jacobian dE/dz
(dense below :data:`~acausal2d.compiler.index1.SPARSE_FROM` nodes, else
sparse) and the relations' crossing functions."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..compiler.index1 import SPARSE_FROM
from .buffered import Buffered

if TYPE_CHECKING:
    from ..compiler.system import System


class Evaluator:
    """Buffered E, dE/dz and g of ``system`` for the parameter vector ``p``."""

    def __init__(self, system: System, p: NDArray[np.float64]) -> None:
        s = system.structure
        self.system = system
        self.n, self.n_eq = s.n_var, s.n_eq
        self.n_rel = len(system.relations)
        args = [np.zeros(1), np.zeros(s.n_var), np.asarray(p, float), np.zeros(self.n_rel)]
        self.E = Buffered(system.residual_fn, args)
        self.J = Buffered(system.jacobian_fn, args)
        self.G = Buffered(system.crossing_fn, args) if system.crossing_fn is not None else None
        self.G0 = self.G if system.start_crossing_fn is system.crossing_fn else \
            Buffered(system.start_crossing_fn, args)
        self.p = np.asarray(p, float)
        self.rows, self.cols = system.jacobian_pattern
        self.sparse = s.n_var >= SPARSE_FROM

    @staticmethod
    def _call(b, t, z, d):
        a = b.args
        a[0][0] = t
        a[1][:] = z
        a[3][:] = d
        b.eval()
        return b.outs[0]

    def residual(self, t, z, d):
        """E(t, z, p, d) (a new array)."""
        return self._call(self.E, t, z, d).copy()

    def J_values(self, t, z, d):
        """The nonzeros of dE/dz at (rows, cols) (a buffer the next call
        overwrites)."""
        return self._call(self.J, t, z, d)

    def jacobian(self, t, z, d, dense=None):
        """dE/dz: a dense array (small systems, or ``dense=True``) or a CSR
        matrix."""
        nz = self._call(self.J, t, z, d)
        if dense if dense is not None else not self.sparse:
            M = np.zeros((self.n_eq, self.n))
            M[self.rows, self.cols] = nz
            return M
        import scipy.sparse as sp     # large systems only: a small run needs no scipy
        return sp.csr_matrix((nz.copy(), (self.rows, self.cols)), shape=(self.n_eq, self.n))

    def crossings(self, t, z, d):
        """Values of the relations' crossing functions (a new array)."""
        if self.G is None:
            return np.zeros(0)
        return self._call(self.G, t, z, d).copy()

    def start_crossings(self, t, z, d):
        """Values of the crossing functions that decide the relations and
        latches at the start (a new array)."""
        if self.G0 is None:
            return np.zeros(0)
        return self._call(self.G0, t, z, d).copy()
