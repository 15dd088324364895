"""Output points made consistent: IDA returns the values at an output time
by interpolating its last steps; the runtime keeps the interpolated states
and solves all equations E(t, z) = 0 for the other unknowns (Newton, in
batches of output points: the residuals of a batch are one mapped CasADi
call; one LU factorization serves the batch; the rows where that does not
converge are regrouped in smaller batches, down to single rows with their
own Jacobian).  So every output row satisfies
every equation - loop closure, force balances - to Newton's tolerance,
whatever step sizes the error test of the states allowed.  A row whose
Newton does not converge (at a singular position) keeps the interpolated
values.
"""
import weakref

import numpy as np

from ..compiler.index1 import SPARSE_FROM
from . import tiers
from .buffered import Buffered
from .capi import engine_projector
from .native import compiled, too_large

CHUNKS = (64, 16, 4, 1)         # batch sizes of the mapped evaluations
RES_TOL = 1e-12                 # residual, relative to the equation's scale
SIMPLIFIED_ITERATIONS = 6       # Newton iterations of a row with one LU, at most
NEW_LU_FROM = 150
"""The C projector (``native_project.c``) factors dE/dz_free in its block
lower-triangular form and refactors it with the pivots of its last LU, so
a new LU costs little more than the Jacobian each row evaluates anyway
(for the equations' scales).  It takes a new LU at the next row after a
row that needed more than one iteration with the LU it had; from this many
unknowns after any row that needed an iteration at all.  Measured (rows
alone, CPU s per run, median of 3; a new LU after more than 0 / 1 / 3
iterations): piston engine, 37 unknowns, 0.0039 / 0.0033 / 0.0045; belt
drive, 80: 0.0198 / 0.0181 / 0.0210; compressor, 202: 0.0229 / 0.0326 /
0.0338 (its old policy, up to 16 iterations: 0.0390 with the first block LU); chain of
20 links, 356: 0.0398 / 0.0448 / 0.0496.  With a new LU a chain row takes
one iteration, with the LU of an earlier row mostly 3 or 4."""


_MAPS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()     # system -> its mapped functions


def _mapped_functions(system, native, chosen=None):
    """{name: function} of E and dE/dz of a system mapped over each of
    :data:`CHUNKS` rows (``E_rows_K``, ``J_rows_K``), compiled to C where
    ``native`` and the engine ``chosen`` compiles them (:func:`~acausal2d.
    runtime.native.compiled`).  Only a formulation that the C projector cannot serve asks
    for them compiled: compiling them beside the C projector's library
    doubled the background compile of a new structure (chain of 81 links:
    8 maps of 0.8-9 MB serialized, 0.43 s of the first run spent on their
    fingerprint alone)."""
    native = native and tiers.mode(chosen) != "off"
    fns = _MAPS.setdefault(system, {}).get(native)
    if fns is None:
        fns = {}
        for K in CHUNKS:
            for name, fn in (("E_rows_%d" % K, system.residual_fn),
                             ("J_rows_%d" % K, system.jacobian_fn)):
                fns[name] = fn.map(name, "serial", K, [2, 3], [])
        if native and not too_large(system.residual_fn, system.jacobian_fn):
            fns = compiled(fns, chosen, getattr(system, "model_name", None)) or fns
        _MAPS[system][native] = fns
    return fns


def _in_c(system, form):
    """True where the C projector can serve the rows of ``form``: its
    non-state unknowns are as many as the system's equations."""
    return 0 < int(np.count_nonzero(~form.differential)) == system.structure.n_eq


class _Mapped:
    """E and dE/dz of a system mapped over K rows, bound to buffers."""

    def __init__(self, system, K, p, native, chosen=None):
        args = [np.zeros(K), np.zeros(K * system.structure.n_var), np.asarray(p, float),
                np.zeros(system.d.numel())]
        self.K = K
        fns = _mapped_functions(system, native, chosen)
        self.E = Buffered(fns["E_rows_%d" % K], args)
        self.J = Buffered(fns["J_rows_%d" % K], args)

    def __call__(self, b, T, Z, d):
        m = len(T)
        b.args[0][:m] = T
        b.args[1].reshape(self.K, -1)[:m] = Z
        b.args[3][:] = d
        b.eval()
        return b.outs[0].reshape(self.K, -1)[:m]


class Projector:
    """Projection of output rows of one formulation (see module docstring);
    ``chosen``: the run's engine (:func:`~acausal2d.runtime.tiers.mode`)."""

    def __init__(self, system, form, p, chosen=None):
        self.system, self.p, self.chosen = system, p, chosen
        self.n_eq = system.structure.n_eq
        self.free = np.nonzero(~form.differential)[0]
        r, c = system.jacobian_pattern
        pos = {j: k for k, j in enumerate(self.free)}
        self.jkeep = np.array([cc in pos for cc in c], dtype=bool)
        self.jrows = np.asarray(r)[self.jkeep]
        self.jcols = np.array([pos[cc] for cc in np.asarray(c)[self.jkeep]], dtype=int)
        self.nominal = system.nominal[self.free]
        self._maps = {}
        n = len(self.free)         # compressed columns of the free-unknown Jacobian
        order = np.lexsort((self.jrows, self.jcols))
        self.csc_order, self.csc_rows = order, self.jrows[order].astype(np.int32)
        self.csc_ptr = np.searchsorted(self.jcols[order], np.arange(n + 1)).astype(np.int32)
        self.in_c = _in_c(system, form)
        self.native = engine_projector(system, self.free, chosen) if self.in_c else None
        self.native_iterations = SIMPLIFIED_ITERATIONS
        self.native_slow = 0 if self.n_eq >= NEW_LU_FROM else 1
        self._to_rows = None

    @property
    def to_rows(self):
        """The sparse sum of Jacobian entries into their rows (the Python
        path only; scipy is imported here, not on the native path)."""
        if self._to_rows is None:
            import scipy.sparse as sp
            nnz = len(self.jrows)
            self._to_rows = sp.csr_matrix((np.ones(nnz), (self.jrows, np.arange(nnz))),
                                          shape=(self.n_eq, nnz))
        return self._to_rows

    def _map(self, K):
        if K not in self._maps:
            self._maps[K] = _Mapped(self.system, K, self.p, not self.in_c, self.chosen)
        return self._maps[K]

    def _converged(self, E, scale):
        """Rows whose residuals are within RES_TOL of each equation's scale."""
        return np.all(np.abs(E) <= RES_TOL * scale, axis=-1)

    def _factor(self, f, T, Z, d):
        """(solve, scale) at one row: LU factors of the free-unknown Jacobian
        (dense or sparse) as a function of right-hand sides (columns), and
        each equation's scale (its Jacobian row times the unknowns' sizes);
        None where the Jacobian is not finite or singular."""
        nz = f(f.J, T, Z, d)[0, self.jkeep]
        if not np.all(np.isfinite(nz)):
            return None
        size = self.nominal + np.abs(Z[0, self.free])
        scale = np.zeros(self.n_eq)
        np.add.at(scale, self.jrows, np.abs(nz) * size[self.jcols])
        solve = self._lu(nz)
        return None if solve is None else (solve, np.maximum(scale, 1e-300))

    def _lu(self, nz):
        import scipy.linalg as sla        # the Python path only
        import scipy.sparse as sp
        import scipy.sparse.linalg as spla
        n = len(self.free)
        with np.errstate(all="ignore"):
            try:
                if n >= SPARSE_FROM:
                    M = sp.csc_matrix((nz[self.csc_order], self.csc_rows, self.csc_ptr),
                                      shape=(n, n))
                    return spla.splu(M).solve
                M = np.zeros((self.n_eq, n))
                M[self.jrows, self.jcols] = nz
                factors = sla.lu_factor(M, check_finite=False)
            except (RuntimeError, ValueError):
                return None
        if not np.all(np.abs(np.diag(factors[0])) > 0):
            return None
        return lambda B: sla.lu_solve(factors, B, check_finite=False)

    def _scales(self, f, T, Z, d):
        """Each equation's scale at each row (rows, equations)."""
        nz = np.abs(f(f.J, T, Z, d)[:, self.jkeep])
        size = self.nominal[None, :] + np.abs(Z[:, self.free])
        with np.errstate(all="ignore"):
            scale = np.asarray(self.to_rows @ (nz * size[:, self.jcols]).T).T
        return np.maximum(np.nan_to_num(scale, nan=0.0), 1e-300)

    def _newton(self, f, T, Z, d, factored):
        """Newton iterations with one factorization for the rows (T, Z):
        (Z, converged rows); each row is tested against its own equation
        scales."""
        solve = factored[0]
        scale = self._scales(f, T, Z, d) if len(T) > 1 else factored[1]
        done = np.zeros(len(T), dtype=bool)
        for _ in range(SIMPLIFIED_ITERATIONS + 1):
            E = f(f.E, T, Z, d)
            done = self._converged(E, scale)
            if done.all():
                break
            with np.errstate(all="ignore"):
                dz = -np.asarray(solve(np.ascontiguousarray(E.T))).T.reshape(E.shape)
            dz[done | ~np.all(np.isfinite(dz), axis=1)] = 0.0
            Z[:, self.free] += dz
        return Z, done

    def _chunk(self, T, Z, d):
        """Newton on the rows (T, Z) in groups of :data:`CHUNKS` sizes, each
        group with the Jacobian of its middle row for all its rows (they lie
        close together on the motion); the rows left are regrouped in
        smaller groups, down to a row with its own Jacobian."""
        Z = Z.copy()
        done = np.zeros(len(T), dtype=bool)
        pending = np.arange(len(T))
        one = self._map(1)
        for K in CHUNKS:
            if K > len(pending) and K > 1:
                continue
            for s in range(0, len(pending), K):
                g = pending[s:s + K]
                mid = g[len(g) // 2:len(g) // 2 + 1]
                factored = self._factor(one, T[mid], Z[mid], d)
                if factored is not None:
                    Zg, ok = self._newton(self._map(K), T[g], Z[g], d, factored)
                    Z[g[ok]] = Zg[ok]
                    done[g[ok]] = True
            pending = np.nonzero(~done)[0]
            if not len(pending):
                break
        return Z, done

    def project(self, T, Z, d, overwrite=False):
        """Rows of Z (at times T, relation values d) solved for the
        non-state unknowns; rows that do not converge are left as given.
        Where it can be built, the C projector (``native_project.c``,
        Newton with an LU of the block lower-triangular form reused from
        row to row) goes first.  The result is a new array, or with
        ``overwrite`` (the caller gives Z up, as a run does with IDA's
        output) Z itself where it is a C-ordered array of floats: the rows
        of the chain of 20 links, 16 MB, are not copied."""
        out = np.require(Z, float, ["C", "W"]) if overwrite else np.array(Z, dtype=float, order="C")
        if self.native is not None and len(T):
            out, ok = self.native(T, out, self.p, d, RES_TOL, self.native_iterations,
                                  self.native_slow, True)
            if ok.all():
                return out
            rest = np.nonzero(~ok)[0]
            out[rest] = self._project(np.asarray(T)[rest], out[rest], d)
            return out
        if not len(self.free) or not len(T):
            return out
        return self._project(T, out, d)

    def _project(self, T, out, d):
        """:meth:`project` in batches of mapped CasADi evaluations."""
        s = 0
        while s < len(T):
            K = next(k for k in CHUNKS if k <= len(T) - s)
            sl = slice(s, s + K)
            Zc, ok = self._chunk(np.asarray(T[sl]), out[sl], d)
            out[sl][ok] = Zc[ok]
            s += K
        return out
