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

    def _chunk(self, T, Z, d):
        m = len(T)
        Z = Z.copy()
        ok = np.ones(m, dtype=bool)
        for _ in range(3):
            E = self._eval(self.E, T, Z, d).reshape(CHUNK, self.n_eq)[:m]
            done = np.max(np.abs(E), axis=1) < TOL
            if done.all():
                break
            nz = self._eval(self.J, T, Z, d).reshape(CHUNK, self.nnz)[:m]
            M = np.zeros((m, self.n_eq, len(self.free)))
            M[:, self.jrows, self.jcols] = nz[:, self.jkeep]
            dz = _solve_rows(M, -E)
            dz[done] = 0.0
            ok &= np.all(np.isfinite(dz), axis=1)
            dz[~ok] = 0.0
            Z[:, self.free] += dz
        E = self._eval(self.E, T, Z, d).reshape(CHUNK, self.n_eq)[:m]
        return Z, ok & (np.max(np.abs(E), axis=1) < 1e3 * TOL)

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
