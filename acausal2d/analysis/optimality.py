"""First-order optimality (Karush-Kuhn-Tucker) check of a constrained
minimum, independent of the optimiser that found it.

The problem is

    minimise f(x)  subject to  c(x) = 0,  g(x) <= 0,  lower <= x <= upper

and a point x* is a KKT point when multipliers lambda (free), mu >= 0 and
nu_lo, nu_up >= 0 exist with

    grad f + J_c^T lambda + J_g^T mu - nu_lo + nu_up = 0      (stationarity)
    c = 0, g <= 0, lower <= x <= upper                        (primal feasibility)
    mu_i g_i = 0, nu (x - bound) = 0                          (complementarity)

:func:`kkt_check` is given the gradient, the constraint values and their
Jacobians at the point; it decides which inequalities and bounds are
active (within ``active_tol`` of their boundary, measured as a distance in
x), estimates the multipliers by bounded linear least squares (lambda free,
mu, nu >= 0; only active constraints carry a multiplier, so
complementarity holds up to the distance of the active ones from their
boundary) and reports three scale-free numbers:

* ``stationarity``: ||residual||_inf / gradient scale, the gradient scale
  being the largest of ||grad f||_inf, the largest single term |multiplier|
  ||row||_inf, ``|f| / x_scale`` when the objective value is given (a
  function of size |f| that varies over lengths x_scale has gradients of
  that size) and ``gradient_scale`` when given;
* ``feasibility``: the largest violation as a distance in x (violation /
  ||row||_2) over ``x_scale``;
* ``complementarity``: the largest |multiplier * constraint value| over
  gradient scale * x_scale (both of the objective's units).

``x_scale`` defaults to ||x||_inf (1 when x is not given or zero).  The
point passes when each number is at most ``tol``.  Given the Hessian of the
Lagrangian (or of the objective when the constraints are linear), the check
also tests second-order necessity: the smallest eigenvalue of the Hessian
reduced to the null space of the active constraints, scaled by gradient
scale / x_scale, must not be below ``-tol``.
"""
from typing import Optional
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import lsq_linear

__all__ = ["KKTResult", "kkt_check"]


@dataclass
class KKTResult:
    """Outcome of :func:`kkt_check`: the three scaled measures (and
    ``curvature``, the scaled smallest reduced-Hessian eigenvalue, or None),
    the tolerance, the active sets (indices), the multipliers
    (``eq``, ``ineq``, ``lower``, ``upper``; zeros for inactive ones) and
    ``ok``."""
    stationarity: float
    feasibility: float
    complementarity: float
    tol: float
    curvature: Optional[float] = None
    active: dict = field(default_factory=dict)
    multipliers: dict = field(default_factory=dict)

    @property
    def ok(self):
        """True when every measure is within ``tol``."""
        second = self.curvature is None or self.curvature >= -self.tol
        return (self.stationarity <= self.tol and self.feasibility <= self.tol
                and self.complementarity <= self.tol and second)

    def message(self):
        """One line naming each measure against the tolerance."""
        curv = "" if self.curvature is None else ", curvature %.2e" % self.curvature
        return ("%s: stationarity %.2e, feasibility %.2e, complementarity %.2e%s (tol %.1e)"
                % ("KKT point" if self.ok else "not a KKT point", self.stationarity,
                   self.feasibility, self.complementarity, curv, self.tol))


def _matrix(J, n, name):
    if J is None:
        return np.zeros((0, n))
    J = np.atleast_2d(np.asarray(J, dtype=float))
    if J.shape[1] != n:
        raise ValueError("kkt_check: %s has %d columns, the gradient %d entries"
                         % (name, J.shape[1], n))
    return J


def _values(v, m, name):
    if v is None:
        return np.zeros(m)
    v = np.atleast_1d(np.asarray(v, dtype=float))
    if v.shape != (m,):
        raise ValueError("kkt_check: %s has %d entries, its Jacobian %d rows" % (name, v.size, m))
    return v


def _bound_rows(x, lower, upper, n):
    """Bounds as inequality rows g <= 0: (rows, values, kinds, indices)."""
    rows, vals, kinds, idx = [], [], [], []
    for kind, bound, sign in (("lower", lower, -1.0), ("upper", upper, 1.0)):
        if bound is None:
            continue
        if x is None:
            raise ValueError("kkt_check: bounds need the point x")
        b = np.broadcast_to(np.asarray(bound, dtype=float), (n,))
        for i in np.flatnonzero(np.isfinite(b)):
            row = np.zeros(n)
            row[i] = sign
            rows.append(row)
            vals.append(sign * (x[i] - b[i]))
            kinds.append(kind)
            idx.append(i)
    return np.array(rows).reshape(-1, n), np.array(vals), kinds, idx


def _distance(values, J):
    """Constraint values as distances in x (value / row 2-norm)."""
    norms = np.linalg.norm(J, axis=1) if len(J) else np.zeros(0)
    return values / np.where(norms > 0, norms, 1.0)


def _estimate(grad, Je, Ja):
    """Multipliers (lambda free, mu >= 0) minimising the stationarity
    residual; returns (lambda, mu, residual)."""
    A = np.vstack([Je, Ja]).T
    if A.shape[1] == 0:
        return np.zeros(0), np.zeros(0), grad.copy()
    lb = np.concatenate([np.full(len(Je), -np.inf), np.zeros(len(Ja))])
    sol = lsq_linear(A, -grad, bounds=(lb, np.full(A.shape[1], np.inf)), method="bvls",
                     tol=1e-15, lsmr_tol=None)
    y = np.maximum(sol.x, lb)
    return y[:len(Je)], y[len(Je):], grad + A @ y


def _curvature(hessian, J_active, gscale, xs):
    H = np.atleast_2d(np.asarray(hessian, dtype=float))
    H = 0.5 * (H + H.T)
    if len(J_active):
        u, s, vt = np.linalg.svd(J_active)
        rank = int(np.sum(s > s.max() * 1e-12)) if s.size else 0
        Z = vt[rank:].T
    else:
        Z = np.eye(H.shape[0])
    if Z.shape[1] == 0:
        return 0.0
    return float(np.min(np.linalg.eigvalsh(Z.T @ H @ Z))) * xs / gscale


def _point(gradient, x, x_scale):
    grad = np.atleast_1d(np.asarray(gradient, dtype=float)).ravel()
    x = None if x is None else np.atleast_1d(np.asarray(x, dtype=float)).ravel()
    if x is not None and x.size != grad.size:
        raise ValueError("kkt_check: x has %d entries, the gradient %d" % (x.size, grad.size))
    xs = x_scale if x_scale is not None else (float(np.max(np.abs(x))) if x is not None else 1.0)
    return grad, x, (xs if xs > 0 else 1.0)


def _gradient_scale(grad, mults, rows, objective, xs, floor):
    terms = [np.max(np.abs(grad)), floor or 0.0]
    terms += [abs(m) * np.max(np.abs(row)) for m, row in zip(mults, rows)]
    if objective is not None:
        terms.append(abs(float(objective)) / xs)
    return max(max(terms), 1e-300)


def _sorted(act, ng, kinds, bidx, mu, lam, n):
    """Active sets and multipliers by kind (inequality, lower, upper)."""
    active = {"ineq": [int(i) for i in act if i < ng],
              "lower": [bidx[i - ng] for i in act if i >= ng and kinds[i - ng] == "lower"],
              "upper": [bidx[i - ng] for i in act if i >= ng and kinds[i - ng] == "upper"]}
    mult = {"eq": lam, "ineq": mu[:ng], "lower": np.zeros(n), "upper": np.zeros(n)}
    for k, (kind, i) in enumerate(zip(kinds, bidx)):
        mult[kind][i] = mu[ng + k]
    return active, mult


def kkt_check(gradient, x=None, *, objective=None, eq_values=None, eq_jacobian=None,
              ineq_values=None, ineq_jacobian=None, lower=None, upper=None, hessian=None,
              x_scale=None, tol=1e-8, active_tol=None, gradient_scale=None):
    """KKT check of the point ``x`` (module docstring).

    ``gradient`` of f at x (length n); ``eq_values``/``eq_jacobian`` c(x)
    and dc/dx (m x n); ``ineq_values``/``ineq_jacobian`` g(x) (<= 0 is
    feasible) and dg/dx; ``lower``/``upper`` bounds on x (scalars or
    arrays, +-inf for none; need ``x``); ``objective`` f(x) for the
    gradient scale; ``hessian`` of the Lagrangian for the second-order
    test; ``x_scale`` the length scale of x; ``tol`` the pass level of the
    scaled measures; ``active_tol`` (default ``sqrt(tol)``) the scaled
    distance below which an inequality or bound counts as active;
    ``gradient_scale`` a further term of the gradient scale where the
    others may vanish (a least-squares fit that matches exactly: ||J||
    times the residual norm, floored at round-off).
    Returns a :class:`KKTResult`."""
    grad, x, xs = _point(gradient, x, x_scale)
    n = grad.size
    Je = _matrix(eq_jacobian, n, "eq_jacobian")
    ce = _values(eq_values, len(Je), "eq_values")
    Jg = _matrix(ineq_jacobian, n, "ineq_jacobian")
    g = _values(ineq_values, len(Jg), "ineq_values")
    Jb, gb, kinds, bidx = _bound_rows(x, lower, upper, n)
    J_all, g_all = np.vstack([Jg, Jb]), np.concatenate([g, gb])
    d_all = _distance(g_all, J_all)
    act = np.flatnonzero(d_all >= -(np.sqrt(tol) if active_tol is None else active_tol) * xs)
    lam, mu_a, r = _estimate(grad, Je, J_all[act])
    mu = np.zeros(len(g_all))
    mu[act] = mu_a
    gscale = _gradient_scale(grad, np.concatenate([lam, mu]), np.vstack([Je, J_all]),
                             objective, xs, gradient_scale)
    feas = np.concatenate([np.abs(_distance(ce, Je)), np.maximum(d_all, 0.0), [0.0]])
    comp = np.abs(mu * g_all)
    curv = None if hessian is None else _curvature(hessian, np.vstack([Je, J_all[act]]),
                                                   gscale, xs)
    active, mult = _sorted(act, len(g), kinds, bidx, mu, lam, n)
    return KKTResult(float(np.max(np.abs(r))) / gscale, float(np.max(feas)) / xs,
                     float(np.max(comp, initial=0.0)) / (gscale * xs), tol, curv, active, mult)
