"""Newton's method for consistent values: all index-reduced equations
E(t, z) = 0 with some node values held.  Dense or sparse LU with a line
search; a minimum-norm least-squares step where the Jacobian is singular."""
import numpy as np


_WATCHDOG = 3   # Newton iterations whose full step is accepted even if the residual grows


class NoConvergence(Exception):
    """Newton did not converge; ``z`` is the last iterate, ``residual`` its
    residuals of E (without the held conditions), at time ``t`` with the
    relation values ``d``."""

    def __init__(self, z, residual, t=0.0, d=None):
        super().__init__("Newton did not converge")
        self.z, self.residual, self.t, self.d = z, residual, t, d


def _step(J, r, square):
    """Newton step -J^-1 r (least squares where J is singular or not square);
    None where J or r is not finite."""
    values = J if isinstance(J, np.ndarray) else J.data
    if not (np.all(np.isfinite(values)) and np.all(np.isfinite(r))):
        return None
    if square:
        with np.errstate(all="ignore"):
            try:
                dz = -(np.linalg.solve(J, r) if isinstance(J, np.ndarray) else _splu(J).solve(r))
            except (np.linalg.LinAlgError, RuntimeError):
                dz = None
        if dz is not None and np.all(np.isfinite(dz)):
            return dz
    Jd = J if isinstance(J, np.ndarray) else (J.toarray() if J.shape[1] <= 4000 else None)
    if Jd is None:
        return None
    with np.errstate(all="ignore"):
        return -np.linalg.lstsq(Jd, r, rcond=1e-12)[0]


def _splu(J):
    import scipy.sparse.linalg as spla    # sparse systems only: a small run needs no scipy
    return spla.splu(J.tocsc())


def _held_rows(held, n, sparse):
    """The rows z[held] = ... of the Jacobian: CSR where the system is
    sparse, else a dense array (the same values; no scipy)."""
    if sparse:
        import scipy.sparse as sp
        return sp.csr_matrix((np.ones(len(held)), (np.arange(len(held)), held)),
                             shape=(len(held), n))
    H = np.zeros((len(held), n))
    np.add.at(H, (np.arange(len(held)), held), 1.0)
    return H


def _stack(J, H):
    """[J; H] (J dense or CSR; H as :func:`_held_rows` made it)."""
    if isinstance(J, np.ndarray):
        return np.vstack([J, H if isinstance(H, np.ndarray) else H.toarray()])
    import scipy.sparse as sp
    return sp.vstack([J, H])


def _line_search(F, z, dz, norm, it, tol, full_only=False):
    """(z, r, norm) after a damped step, or None if no step reduces the
    residual (``full_only``: only the full step is tried)."""
    step = 1.0
    while step > (0.75 if full_only else 1e-8):
        zn = z + step * dz
        rn = F(zn)
        nn = np.max(np.abs(rn)) if rn.size else 0.0
        if np.isfinite(nn) and (nn < (1 - 1e-4 * step) * norm or nn < tol):
            return zn, rn, nn
        # watchdog: the first full steps may raise the residual for a while
        # (velocity cross terms from zero start values); allow it, within bounds
        if step == 1.0 and it < _WATCHDOG and np.isfinite(nn) and nn < 1e6 * max(norm, 1.0):
            return zn, rn, nn
        step *= 0.5
    return None


def solve_consistent(ev, t, z0, d, held, held_values, tol=1e-10, max_iter=60):
    """Solve E(t, z, p, d) = 0 with z[held] = held_values by Newton from z0
    (``ev``: an :class:`~acausal2d.runtime.evaluator.Evaluator`); returns z
    or raises :class:`NoConvergence`.

    Below :data:`POLISHED` (a residual every caller accepts; with ``tol``
    0 the iteration polishes down to rounding) a step reuses the last LU
    where there is one and only the full step is tried: there damping
    cannot help, and a fresh LU and 27 halved steps per iteration were
    most of the time of an event (compressor: 1046 of 1338 iterations,
    each with a sparse LU; 287 line searches halving down to 1e-8)."""
    z = np.array(z0, dtype=float)
    held = np.asarray(held, dtype=int)
    held_values = np.asarray(held_values, dtype=float)
    z[held] = held_values
    step = _stepper(ev, held, len(z))

    def F(zz):
        return np.concatenate([ev.residual(t, zz, d), zz[held] - held_values])

    r = F(z)
    norm = np.max(np.abs(r)) if r.size else 0.0
    solve = None
    for it in range(max_iter):
        if norm < tol:
            return z
        polish = norm < POLISHED
        if polish and solve is not None:
            with np.errstate(all="ignore"):
                dz = -solve(r)
        else:
            dz, solve = step(t, z, d, r)
        found = _line_search(F, z, dz, norm, it, tol, polish) \
            if dz is not None and np.all(np.isfinite(dz)) else None
        if found is None:
            break
        z, r, norm = found
    if norm < tol * 10:
        return z
    raise NoConvergence(z, r[:ev.n_eq], t, d)


POLISHED = 1e-10


def _stepper(ev, held, n):
    """A function (t, z, d, r) -> (Newton step, the LU's solve or None) for
    the stacked system [E; z[held] - values] of ``ev``: SuperLU on the
    cached stacked layout where the system is sparse and square, else the
    general path (dense or sparse, a least-squares step where singular)."""
    if ev.sparse and ev.n_eq + len(held) == n:
        from .stacked import StackedJacobian       # scipy's SuperLU: sparse systems only
        stacked = StackedJacobian.of(ev, held)
        if stacked is not None:
            return stacked.step_and_solver
    H = _held_rows(held, n, ev.sparse)
    square = ev.n_eq + len(held) == n

    def step(t, z, d, r):
        return _step(_stack(ev.jacobian(t, z, d), H), r, square), None
    return step
