"""Output points made consistent: IDA returns the values at an output time
by interpolating its last steps; the runtime keeps the interpolated states
and solves all equations E(t, z) = 0 for the other unknowns (Newton, in
batches of output points: the residuals and Jacobians of a batch are one
mapped CasADi call, the linear systems one stacked LAPACK solve).  So every
output row satisfies every equation - loop closure, force balances - to
Newton's tolerance, whatever step sizes the error test of the states
allowed.  A row whose Newton does not converge (at a singular position)
keeps the interpolated values.
"""
import numpy as np

from .buffered import Buffered

CHUNK = 64
TOL = 1e-10
SIMPLIFIED_ITERATIONS = 6


def _solve_rows(M, rhs):
    """Solutions of the stacked systems M[i] x = rhs[i]; NaN rows where a
    matrix is singular."""
    with np.errstate(all="ignore"):
        try:
            return np.linalg.solve(M, rhs[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            out = np.full(rhs.shape[:1] + M.shape[2:], np.nan)
            for i in range(len(M)):
                try:
                    out[i] = np.linalg.solve(M[i], rhs[i])
                except np.linalg.LinAlgError:
                    pass
            return out


class _LU:
    """LU factors of a square matrix, for solving with many right-hand sides."""

    def __init__(self, M):
        import scipy.linalg as sla
        if not np.all(np.isfinite(M)):
            raise np.linalg.LinAlgError("not finite")
        with np.errstate(all="ignore"):
            self.factors = sla.lu_factor(M, check_finite=False)
        if np.min(np.abs(np.diag(self.factors[0]))) == 0.0:
            raise np.linalg.LinAlgError("singular")
        self._solve = sla.lu_solve

    def solve(self, B):
        return self._solve(self.factors, B, check_finite=False)


class Projector:
    """Projection of output rows of one formulation (see module docstring)."""

    def __init__(self, system, form, p):
        s = system.structure
        n, K = s.n_var, CHUNK
        self.n_eq = s.n_eq
        self.free = np.nonzero(~form.differential)[0]
        self.scale = system.nominal
        r, c = system.jacobian_pattern
        pos = {j: k for k, j in enumerate(self.free)}
        keep = np.array([cc in pos for cc in c], dtype=bool)
        self.jrows, self.jcols = np.asarray(r)[keep], np.array([pos[cc] for cc in c[keep]],
                                                                 dtype=int)
        self.jkeep = keep
        args = [np.zeros(K), np.zeros(K * n), np.asarray(p, float),
                np.zeros(system.d.numel())]
        self.E = Buffered(system.residual_fn.map("E_rows", "serial", K, [2, 3], []), args)
        self.J = Buffered(system.jacobian_fn.map("J_rows", "serial", K, [2, 3], []), args)
        self.nnz = system.jacobian_fn.nnz_out(0)

    def _eval(self, b, T, Z, d):
        m = len(T)
        b.args[0][:m] = T
        b.args[1].reshape(CHUNK, -1)[:m] = Z
        b.args[3][:] = d
        b.eval()
        return b.outs[0]

    def _residuals(self, T, Z, d):
        m = len(T)
        return self._eval(self.E, T, Z, d).reshape(CHUNK, self.n_eq)[:m].copy()

    def _matrices(self, T, Z, d):
        """Jacobians of E with respect to the free unknowns, one per row."""
        m = len(T)
        nz = self._eval(self.J, T, Z, d).reshape(CHUNK, self.nnz)[:m]
        M = np.zeros((m, self.n_eq, len(self.free)))
        M[:, self.jrows, self.jcols] = nz[:, self.jkeep]
        return M

    def _simplified(self, T, Z, d, E):
        """Newton with the Jacobian of the chunk's middle row for all rows
        (the rows lie close together on the motion): (Z, E, converged)."""
        mid = len(T) // 2
        M = self._matrices(T[mid:mid + 1], Z[mid:mid + 1], d)[0]
        try:
            lu = _LU(M)
        except np.linalg.LinAlgError:
            return Z, E, np.zeros(len(T), dtype=bool)
        for _ in range(SIMPLIFIED_ITERATIONS):
            done = np.max(np.abs(E), axis=1) < TOL
            if done.all():
                break
            Z[:, self.free] -= lu.solve(E.T).T * ~done[:, None]
            E = self._residuals(T, Z, d)
        return Z, E, np.max(np.abs(E), axis=1) < TOL

    def _chunk(self, T, Z, d):
        Z = Z.copy()
        E = self._residuals(T, Z, d)
        Z, E, done = self._simplified(T, Z, d, E)
        if done.all():
            return Z, done
        rows = np.nonzero(~done)[0]
        for _ in range(3):          # full Newton for the rows left
            dz = _solve_rows(self._matrices(T[rows], Z[rows], d), -E[rows])
            good = np.all(np.isfinite(dz), axis=1)
            Z[rows[good][:, None], self.free[None, :]] += dz[good]
            E[rows] = self._residuals(T[rows], Z[rows], d)
            rows = rows[np.max(np.abs(E[rows]), axis=1) >= TOL]
            if not len(rows):
                break
        return Z, np.max(np.abs(E), axis=1) < 1e3 * TOL

    def project(self, T, Z, d):
        """Rows of Z (at times T, relation values d) solved for the
        non-state unknowns; rows that do not converge are left as given."""
        out = np.array(Z, dtype=float)
        if not len(self.free) or not len(T):
            return out
        for s in range(0, len(T), CHUNK):
            sl = slice(s, min(s + CHUNK, len(T)))
            Zc, ok = self._chunk(np.asarray(T[sl]), out[sl], d)
            out[sl][ok] = Zc[ok]
        return out
