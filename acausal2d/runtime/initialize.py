"""Consistent initialization.

Solves all equations of the index-reduced system (every derivative order)
for all variable nodes at t0, together with the fixed start values.  When
fewer values are fixed than the system has degrees of freedom, start values
of further state candidates are held, chosen by priority and by structural
matching so that the initial system is square and structurally regular.
Newton's method with sparse LU and a line search; a minimum-norm
least-squares step where the Jacobian is singular.  On failure the message
lists the equations whose residuals stay nonzero.
"""
import casadi as ca
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..language.dsl import STATE_SELECT
from ..errors import InitializationError

_WATCHDOG = 3   # Newton iterations whose full step is accepted even if the residual grows


class InitialSystem:
    """Residuals of all index-reduced equations as functions of all variable
    nodes: E(t, z, p, d) and its sparse Jacobian dE/dz."""

    def __init__(self, R, t, p, d):
        z = ca.vertcat(*R.var_sym)
        E = ca.vertcat(*R.eq_expr)
        self.R = R
        self.E = ca.Function("E", [t, z, p, d], [E])
        J = ca.jacobian(E, z)
        self.J = ca.Function("dEdz", [t, z, p, d], [J])
        sp_ = J.sparsity()
        self.rows, self.cols = sp_.get_triplet()
        self.shape = (sp_.size1(), sp_.size2())

    def residual(self, t, z, p, d):
        return self.E(t, z, p, d).full().ravel()

    def jacobian(self, t, z, p, d):
        nz = np.asarray(self.J(t, z, p, d).nonzeros(), dtype=float)
        return sp.csr_matrix((nz, (self.rows, self.cols)), shape=self.shape)


def choose_initial_conditions(R, fixed_nodes, priority, has_start, states=()):
    """Which node values to hold at t0: the user's ``fixed_nodes`` plus, if
    the system has more freedom, start values of state candidates picked by
    priority, then by having a start value, then by being among ``states``
    (the states a selection at the start guess would integrate), and by
    structural matching.  Returns the list of held nodes."""
    n_var, n_eq = R.n_var, R.n_eq
    need = n_var - n_eq
    held = list(dict.fromkeys(fixed_nodes))
    if len(held) >= need:
        return held
    # matching of the equations + held conditions against the nodes
    inc = [list(R.eq_inc[i]) for i in range(n_eq)] + [[j] for j in held]
    match_var = [-1] * n_var
    match_eq = [-1] * len(inc)

    def augment(e0):
        seen = set()
        stack = [(e0, iter(inc[e0]))]
        path = []
        while stack:
            e, it = stack[-1]
            for j in it:
                if j in seen:
                    continue
                seen.add(j)
                if match_var[j] < 0:
                    path.append((e, j))
                    for ee, jj in path:
                        match_var[jj] = ee
                        match_eq[ee] = jj
                    return True
                path.append((e, j))
                stack.append((match_var[j], iter(inc[match_var[j]])))
                break
            else:
                stack.pop()
                if path:
                    path.pop()
        return False

    for e in range(len(inc)):
        augment(e)
    cands = [j for j in range(n_var) if R.A[j] >= 0 and j not in set(held)]
    states = set(states)
    cands.sort(key=lambda j: (-STATE_SELECT.index(priority[j]), 0 if has_start[j] else 1,
                              0 if j in states else 1, R.var_level[j], str(R.var_sym[j])))
    for j in cands:
        if len(held) >= need:
            break
        inc.append([j])
        match_eq.append(-1)
        if augment(len(inc) - 1):
            held.append(j)
        else:
            inc.pop()
            match_eq.pop()
    return held


def _failure(z, message):
    """InitializationError carrying the last Newton iterate (``.last``)."""
    exc = InitializationError(message)
    exc.last = z
    return exc


def solve_consistent(system, t, z0, p, d, held, held_values, describe_eq, node_name,
                     tol=1e-10, max_iter=60):
    """Newton solve of E(t, z) = 0 with z[held] = held_values, from z0."""
    z = np.array(z0, dtype=float)
    held = np.asarray(held, dtype=int)
    held_values = np.asarray(held_values, dtype=float)
    z[held] = held_values
    n = len(z)
    m = system.shape[0] + len(held)
    H = sp.csr_matrix((np.ones(len(held)), (np.arange(len(held)), held)), shape=(len(held), n))

    def F(zz):
        return np.concatenate([system.residual(t, zz, p, d), zz[held] - held_values])

    r = F(z)
    norm = np.max(np.abs(r)) if r.size else 0.0
    for it in range(max_iter):
        if norm < tol:
            return z
        J = sp.vstack([system.jacobian(t, z, p, d), H]).tocsc()
        dz = None
        if m == n:
            try:
                with np.errstate(all="ignore"):
                    lu = spla.splu(J)
                    dz = -lu.solve(r)
                if not np.all(np.isfinite(dz)):
                    dz = None
            except RuntimeError:
                dz = None
        if dz is None:
            if n > 4000:
                break
            dz = -np.linalg.lstsq(J.toarray(), r, rcond=1e-12)[0]
        step = 1.0
        while step > 1e-8:
            zn = z + step * dz
            rn = F(zn)
            nn = np.max(np.abs(rn))
            if np.isfinite(nn) and (nn < (1 - 1e-4 * step) * norm or nn < tol):
                break
            # watchdog: the first full Newton steps may raise the residual for a while
            # (velocity cross terms from zero start values); allow it, within bounds
            if step == 1.0 and it < _WATCHDOG and np.isfinite(nn) and nn < 1e6 * max(norm, 1.0):
                break
            step *= 0.5
        else:
            break
        z, r, norm = zn, rn, nn
    if norm < tol * 10:
        return z
    res = r[:system.shape[0]]
    worst = np.argsort(-np.abs(res))[:6]
    lines = ["  - %s   (residual %.3g)" % (describe_eq(i), res[i]) for i in worst if abs(res[i]) > tol]
    raise _failure(z,
                   "No consistent initial values found (the mechanism cannot assemble, or "
                   "start values are too far from a solution). Largest remaining residuals:\n%s\n"
                   "Check the geometry (link lengths that cannot close a loop) and the start "
                   "values of %s." % ("\n".join(lines), ", ".join(node_name(j) for j in held[:8])))
