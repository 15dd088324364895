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


def _line_search(F, z, dz, norm, it, tol):
    """(z, r, norm) after a damped step, or None if no step reduces the residual."""
    step = 1.0
    while step > 1e-8:
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
    or raises :class:`NoConvergence`."""
    z = np.array(z0, dtype=float)
    held = np.asarray(held, dtype=int)
    held_values = np.asarray(held_values, dtype=float)
    z[held] = held_values
    n, m = len(z), ev.n_eq + len(held)
    stacked = None
    if ev.sparse and m == n:
        from .stacked import StackedJacobian       # scipy's SuperLU: sparse systems only
        stacked = StackedJacobian.of(ev, held)
    if stacked is None:
        H = _held_rows(held, n, ev.sparse)

    def F(zz):
        return np.concatenate([ev.residual(t, zz, d), zz[held] - held_values])

    r = F(z)
    norm = np.max(np.abs(r)) if r.size else 0.0
    for it in range(max_iter):
        if norm < tol:
            return z
        if stacked is not None:
            dz = stacked.step(t, z, d, r)
        else:
            J = _stack(ev.jacobian(t, z, d), H)
            dz = _step(J, r, m == n)
        found = _line_search(F, z, dz, norm, it, tol) if dz is not None else None
        if found is None:
            break
        z, r, norm = found
    if norm < tol * 10:
        return z
    raise NoConvergence(z, r[:ev.n_eq], t, d)
