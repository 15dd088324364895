"""Complete static balancing with spring-band mechanisms (Ebert 2015, ch. 6, eq.
6.1-6.8): from a required torque T(phi) at the cam axis to the spring travel
x_S(phi) (transfer function of order 0) and the effective lever arm h(phi) =
x_S'(phi) (order 1, the diagonal Drehschubstrecke) that a DB~SD cam (or a
band with the spring outside, Bild 6.1: x_S only) must realise.

A linear tension spring of rate c_S with travel (extension) x_S pulls the
band with F_S = c_S x_S on the lever arm h (6.1-6.4), so

    T(phi) = c_S x_S(phi) x_S'(phi)                                  (6.5)

with the sign convention of the dissertation: T > 0 where the spring is stretched
as phi grows.  (For a cam that pays the band out as phi grows -- DB~SD with
K = -1 and h > 0 -- solve in the angle that runs the other way, or pass -T;
see models/cabinet_door.py.)

- :func:`spring_band_transfer` -- the dissertation's method: least squares (6.6)
  over a polynomial (6.7) or Fourier (6.8) ansatz x_A, with side constraints
  ``h_min <= x_A' <= h_max`` and a fixed start travel, solved by IPOPT
  (CasADi) and accepted by its KKT conditions
  (:mod:`acausal2d.analysis.optimality`), never by an exit flag; the spring
  rate fixed or free (run 1 of example 7.2.1).
- :func:`exact_spring_travel` -- the exact solution of 6.5 (derived here;
  the dissertation calls 6.5 closed-form solvable only for few T): since T =
  (c_S/2) d(x_S^2)/dphi,

      x_S(phi) = sqrt(x_S(phi0)^2 + (2/c_S) integral_phi0^phi T dpsi),  h = T/(c_S x_S),

  a one-parameter family in x_S(phi0) (the spring must stay in tension,
  x_S^2 > 0).  It is the reference for the fit: with r = T - c_S x_A x_A'
  the fit's torque residual, ``x_A^2 - x_S^2 = x_A(phi0)^2 - x_S(phi0)^2 -
  (2/c_S) integral r``, so the fit departs from the exact member through its
  start value by at most ``(2/c_S) integral |r| / (x_A + x_S)``
  (:meth:`SpringBandFit.deviation_bound`).
- :func:`softest_spring` -- the smallest c_S whose exact solution keeps h
  below h_max for a given start travel.
"""
import math

import casadi as ca
import numpy as np
from scipy.integrate import quad
from scipy.interpolate import CubicSpline

from acausal2d.analysis.optimality import kkt_check
from acausal2d.errors import ModelDefinitionError

__all__ = ["spring_band_transfer", "exact_spring_travel", "softest_spring", "SpringBandFit",
           "torque_integral"]


def torque_integral(phi, T):
    """W(phi) = integral_phi0^phi T dpsi on the grid ``phi``: ``T`` a
    function (adaptive quadrature per interval, ~1e-13) or samples on the
    grid (integral of their not-a-knot cubic spline)."""
    phi = np.asarray(phi, dtype=float)
    if callable(T):
        steps = [quad(lambda s: float(T(s)), a, b, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
                 for a, b in zip(phi[:-1], phi[1:])]
        return np.concatenate([[0.0], np.cumsum(steps)])
    spline = CubicSpline(phi, np.asarray(T, dtype=float))
    return spline.antiderivative()(phi) - spline.antiderivative()(phi[0])


def _torque_values(phi, T):
    return np.array([float(T(p)) for p in phi]) if callable(T) else np.asarray(T, dtype=float)


def exact_spring_travel(phi, T, c_S, x_start):
    """Exact solution of eq. 6.5 on the grid ``phi`` for the start travel
    ``x_start`` = x_S(phi[0]): returns (x_S, h) arrays (module docstring).
    Raises if the spring would have to push (x_S^2 <= 0)."""
    W = torque_integral(phi, T)
    x2 = x_start ** 2 + 2.0 * W / c_S
    if np.min(x2) <= 0:
        raise ModelDefinitionError("exact_spring_travel: x_S^2 = x_start^2 + 2 W/c_S reaches "
                                   "%.3g m^2: the spring would have to push; raise x_start or "
                                   "c_S" % np.min(x2))
    x = np.sqrt(x2)
    return x, _torque_values(phi, T) / (c_S * x)


def softest_spring(phi, T, x_start, h_max):
    """Smallest spring rate c_S for which the exact solution with start
    travel ``x_start`` keeps the lever arm at or below ``h_max`` on the grid
    (h = T/(c_S x_S) falls with c_S, since c_S x_S = sqrt(c_S^2 x_start^2 + 2
    c_S W) grows).  Bisection on c_S; requires T >= 0."""
    Tv, W = _torque_values(phi, T), torque_integral(phi, T)
    if np.min(Tv) < 0:
        raise ModelDefinitionError("softest_spring: the torque changes sign; give c_S")

    def hmax(c):
        x2 = x_start ** 2 + 2.0 * W / c
        return np.max(Tv / (c * np.sqrt(np.maximum(x2, 1e-300))))
    lo, hi = 1e-9, 1.0
    while hmax(hi) > h_max:
        lo, hi = hi, hi * 10.0
        if hi > 1e12:
            raise ModelDefinitionError("softest_spring: no spring rate keeps h <= %g m" % h_max)
    for _ in range(200):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if hmax(mid) > h_max else (lo, mid)
        if hi / lo - 1 < 1e-13:
            break
    return hi


class _Basis:
    """Ansatz functions (6.7, 6.8) and their derivatives on a grid."""

    def __init__(self, kind, n, phi0, phi1):
        if kind not in ("poly", "fourier"):
            raise ModelDefinitionError("ansatz must be ('poly', n) or ('fourier', n), got %r"
                                       % (kind,))
        if not (isinstance(n, int) and 1 <= n <= 12):
            raise ModelDefinitionError("ansatz degree must be an integer 1..12, got %r" % (n,))
        self.kind, self.n, self.phi0, self.scale = kind, n, float(phi0), float(phi1 - phi0)
        self.size = n + 1 if kind == "poly" else 2 * n + 1

    def matrices(self, phi):
        """(B, D): values and derivatives of the basis, shape (k, size)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        if self.kind == "poly":       # scaled monomials tau^k, tau = (phi - phi0)/scale
            tau = (phi - self.phi0) / self.scale
            k = np.arange(self.n + 1)
            B = tau[:, None] ** k
            D = np.zeros_like(B)
            D[:, 1:] = k[1:] * tau[:, None] ** (k[1:] - 1) / self.scale
            return B, D
        m = np.arange(1, self.n + 1)
        C, S = np.cos(np.outer(phi, m)), np.sin(np.outer(phi, m))
        B = np.hstack([0.5 * np.ones((len(phi), 1)), C, S])
        D = np.hstack([np.zeros((len(phi), 1)), -S * m, C * m])
        return B, D

    def expression(self, coef, p):
        """x_A(p) as a CasADi expression."""
        if self.kind == "poly":
            tau = (p - self.phi0) / self.scale
            out = 0.0
            for c in coef[::-1]:
                out = out * tau + float(c)
            return out
        n = self.n
        return 0.5 * float(coef[0]) + sum(float(coef[m]) * ca.cos(m * p)
                                          + float(coef[n + m]) * ca.sin(m * p)
                                          for m in range(1, n + 1))

    def seed_coefficients(self, coef):
        """Coefficients in the dissertation's form: polynomial a0..an in phi (6.7),
        or Fourier a0, a1..an, b1..bn (6.8)."""
        if self.kind == "fourier":
            return np.asarray(coef, dtype=float)
        P = np.polynomial.Polynomial(coef)
        lin = np.polynomial.Polynomial([-self.phi0 / self.scale, 1.0 / self.scale])
        return P(lin).coef


class SpringBandFit:
    """Result of :func:`spring_band_transfer`.

    Arrays on the grid ``phi``: ``T`` required torque, ``x`` = x_A (spring
    travel), ``h`` = x_A' (lever arm), ``F_S`` = c_S x_A, ``residual`` = T -
    c_S x_A x_A' (6.6); numbers ``c_S``, ``rms``, ``max_abs`` (torque
    residual), ``coefficients`` (form of Ebert 2015, eq.  6.7/6.8), ``ansatz``; the exact
    solution of 6.5 with the fit's start travel in ``x_exact``, ``h_exact``.
    Functions of the angle: :meth:`x_at`, :meth:`h_at` (numpy) and
    :meth:`x_expr`, :meth:`h_expr` (CasADi, exact derivatives)."""

    def __init__(self, phi, T, c_S, basis, coef, status, torque=None):
        self.phi, self.T, self.c_S = phi, T, float(c_S)
        self._torque = torque if callable(torque) else CubicSpline(phi, T)
        self._basis, self._coef = basis, np.asarray(coef, dtype=float)
        self.ansatz = (basis.kind, basis.n)
        self.coefficients = basis.seed_coefficients(self._coef)
        self.success, self.message = status
        self.x, self.h = self.x_at(phi), self.h_at(phi)
        self.F_S = self.c_S * self.x
        self.residual = T - self.c_S * self.x * self.h
        self.rms = float(np.sqrt(np.mean(self.residual ** 2)))
        self.max_abs = float(np.max(np.abs(self.residual)))
        self.x_exact, self.h_exact = exact_spring_travel(phi, T, self.c_S, float(self.x[0]))

    def x_at(self, phi):
        """Spring travel x_A at the angles ``phi``."""
        return self._basis.matrices(phi)[0] @ self._coef

    def h_at(self, phi):
        """Lever arm h = x_A' at the angles ``phi``."""
        return self._basis.matrices(phi)[1] @ self._coef

    def x_expr(self, p):
        """x_A as a CasADi expression of the symbol (or expression) ``p``."""
        return self._basis.expression(self._coef, p)

    def h_expr(self, p):
        """h = x_A' as a CasADi expression (exact derivative)."""
        q = ca.SX.sym("q")
        return ca.substitute(ca.jacobian(self.x_expr(q), q), q, ca.SX(p))

    def residual_at(self, phi):
        """Torque residual T - c_S x_A x_A' (6.6) between the samples too (T
        as given, or the cubic spline through its samples -- as the exact
        solution integrates it)."""
        phi = np.asarray(phi, dtype=float)
        return self._torque(phi) - self.c_S * self.x_at(phi) * self.h_at(phi)

    def deviation_bound(self):
        """Bound on |x_A - x_exact| on the grid from the torque residual
        (module docstring): (2/c_S) int |r| / (x_A + x_exact)."""
        W = torque_integral(self.phi, lambda p: abs(float(self.residual_at([p])[0])))
        return 2.0 * W / self.c_S / (self.x + self.x_exact)


def _start_coefficients(B, D, x_target, eq):
    """Least-squares projection of a travel curve on the ansatz (respecting
    the start-value constraint ``eq`` = (row, value))."""
    if eq is None:
        return np.linalg.lstsq(B, x_target, rcond=None)[0]
    A = np.vstack([B, 1e6 * eq[0]])
    return np.linalg.lstsq(A, np.concatenate([x_target, [1e6 * eq[1]]]), rcond=None)[0]


def _nlp(B, D, T, c, ap, N):
    """The fit (6.6) as a CasADi problem in the free coefficients z (a = ap
    + N z): residual r (scaled by max |T|), objective 0.5 |r|^2, and a
    function giving f, grad f, Hessian and the residual Jacobian."""
    scale = max(np.max(np.abs(T)), 1e-300)
    z = ca.SX.sym("z", N.shape[1])
    a = ca.DM(ap) + ca.DM(N) @ z
    r = (ca.DM(T) - c * (ca.DM(B) @ a) * (ca.DM(D) @ a)) / scale
    f = 0.5 * ca.dot(r, r)
    H = ca.hessian(f, z)[0]
    return z, f, ca.Function("fgh", [z], [f, ca.gradient(f, z), H, ca.jacobian(r, z), r])


def _polish(fgh, z, A, b):
    """Newton on the KKT system of the fit with the active lever-arm bounds
    A z = b as equalities: from IPOPT's interior point to the vertex of the
    active set, where the bounds hold to round-off."""
    n = len(z)
    for _ in range(30):
        _, g, H = (np.asarray(v, dtype=float) for v in fgh(z)[:3])
        K = np.block([[H, A.T], [A, np.zeros((len(A), len(A)))]])
        step = np.linalg.lstsq(K, np.concatenate([-g.ravel(), b - A @ z]), rcond=None)[0][:n]
        z = z + step
        if np.linalg.norm(step) <= 1e-15 * (1.0 + np.linalg.norm(z)):
            break
    return z


def _optimality(fgh, z, DN, Dap, bounds):
    """KKT check (acausal2d.analysis.optimality) of the fit at z: the
    lever-arm bounds as inequalities, the exact Hessian for the
    second-order test, the gradient scale ||J|| |r| of a least-squares
    problem (floored at round-off for an exact fit)."""
    f, g, H, J, r = (np.asarray(v, dtype=float) for v in fgh(z))
    rows, vals = [], []
    lo, hi = bounds
    h = Dap + DN @ z
    if hi is not None:
        rows.append(DN)
        vals.append(h - hi)
    if lo is not None:
        rows.append(-DN)
        vals.append(lo - h)
    gs = np.linalg.norm(J, 2) * max(np.linalg.norm(r), 1e-13 * math.sqrt(len(r)))
    return kkt_check(g.ravel(), z, objective=f.item(), hessian=H, gradient_scale=gs,
                     ineq_values=np.concatenate(vals) if vals else None,
                     ineq_jacobian=np.vstack(rows) if rows else None)


def _active_rows(z, DN, Dap, bounds):
    """Lever-arm bounds within 1e-7 (relative) of IPOPT's point, as rows A z = b."""
    h = Dap + DN @ z
    lo, hi = bounds
    size = max(np.max(np.abs(h)), abs(hi or 0.0), abs(lo or 0.0), 1e-300)
    A, b = [], []
    for bound in (hi, lo):
        if bound is not None:
            near = np.abs(h - bound) <= 1e-7 * size
            A.append(DN[near])
            b.append(bound - Dap[near])
    return (np.vstack(A), np.concatenate(b)) if A else (np.zeros((0, len(z))), np.zeros(0))


def _solve(B, D, T, c, a0, eq, bounds):
    """Minimise sum (T - c (B a)(D a))^2 (6.6) from a0; equality eq (linear
    start value, eliminated), inequality bounds (lo, hi) on D a.  IPOPT
    (shipped with CasADi) finds the minimum, Newton on the active set makes
    the bounds hold to round-off, and success is decided by the KKT check,
    not by an optimiser's exit flag.  Returns (a, KKTResult)."""
    if eq is not None:                     # eliminate the start value: a = ap + N z
        row, val = eq
        ap = row * val / (row @ row)
        N = np.linalg.svd(row[None, :])[2][1:].T
    else:
        ap, N = np.zeros(B.shape[1]), np.eye(B.shape[1])
    z, f, fgh = _nlp(B, D, T, c, ap, N)
    DN, Dap = D @ N, D @ ap
    lo, hi = bounds
    nlp = {"x": z, "f": f, "g": ca.DM(DN) @ z + ca.DM(Dap)}
    opts = {"print_time": False, "ipopt.print_level": 0, "ipopt.sb": "yes",
            "ipopt.tol": 1e-14, "ipopt.max_iter": 3000, "ipopt.bound_relax_factor": 0.0}
    solver = ca.nlpsol("spring_band_fit", "ipopt", nlp, opts)
    z0 = np.linalg.lstsq(N, a0 - ap, rcond=None)[0]
    sol = solver(x0=z0, lbg=-np.inf if lo is None else lo, ubg=np.inf if hi is None else hi)
    zs = np.asarray(sol["x"], dtype=float).ravel()
    zs = _polish(fgh, zs, *_active_rows(zs, DN, Dap, bounds))
    return ap + N @ zs, _optimality(fgh, zs, DN, Dap, bounds)


def spring_band_transfer(phi, T, c_S=None, ansatz=("poly", 3), x_start=None, h_max=None,
                         h_min=None):
    """Transfer function of a spring-band balancer (Ebert 2015, ch. 6.2, eq. 6.6-6.8).

    ``phi`` grid of the k samples (6.6), ``T`` the required torque (function
    of phi or samples on the grid), ``c_S`` the spring rate [N/m] (None:
    free, run 1 of example 7.2.1 -- then ``x_start`` and ``h_max`` are
    required and c_S is the softest spring whose exact solution keeps h <=
    h_max, :func:`softest_spring`; the fit then runs at that rate),
    ``ansatz`` ``("poly", n)`` (6.7) or ``("fourier", n)`` (6.8), ``x_start``
    the spring travel at phi[0] (a side constraint; None leaves it free),
    ``h_max``/``h_min`` bounds on the lever arm x_A' at the samples.
    The optimisation starts from the exact solution projected on the ansatz.
    Returns a :class:`SpringBandFit`; its ``success`` is the KKT check's
    verdict (``fit.kkt``, :func:`acausal2d.analysis.optimality.kkt_check`)."""
    phi = np.asarray(phi, dtype=float)
    if phi.ndim != 1 or len(phi) < 3 or np.any(np.diff(phi) <= 0):
        raise ModelDefinitionError("spring_band_transfer: phi must be an increasing grid")
    Tv = _torque_values(phi, T)
    if c_S is None:
        if x_start is None or h_max is None:
            raise ModelDefinitionError("spring_band_transfer: a free spring rate needs x_start "
                                       "and h_max (otherwise every c_S balances equally well)")
        c_S = softest_spring(phi, T, x_start, h_max)
    if not c_S > 0:
        raise ModelDefinitionError("spring_band_transfer: c_S must be > 0, got %r" % (c_S,))
    basis = _Basis(ansatz[0], ansatz[1], phi[0], phi[-1])
    B, D = basis.matrices(phi)
    W = torque_integral(phi, T)
    x0 = x_start if x_start is not None else math.sqrt(max(2.0 * (W.max() - W.min()) / c_S,
                                                           -2.0 * W.min() / c_S + 1e-12))
    x_ref = np.sqrt(np.maximum(x0 ** 2 + 2.0 * W / c_S, 1e-300))
    eq = None if x_start is None else (basis.matrices([phi[0]])[0][0], float(x_start))
    a0 = _start_coefficients(B, D, x_ref, eq)
    coef, kkt = _solve(B, D, Tv, c_S, a0, eq, (h_min, h_max))
    fit = SpringBandFit(phi, Tv, c_S, basis, coef, (kkt.ok, kkt.message()), T)
    fit.kkt = kkt
    return fit
