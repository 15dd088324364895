"""Toothed belt drive with non-circular pulleys (Ebert 2015, ch. 7.3.2, Bild 7.25-7.27).

Two non-circular toothed pulleys, rotating in the ground at a centre distance
of 800 mm, coupled by an open toothed belt (two elastic spans, Ebert (2015), eq.
4.52-4.66, on two pulleys with curved contour, eq. 4.100-4.122).  The small
pulley is driven at 360 deg/s for 0..720 deg (2 s); the large pulley runs
without load torque ("lastmomentfreier Abtrieb"), so the span forces vary
only with the accelerating torque of the large pulley (Bild 7.27).

Values from the dissertation (Bild 7.25): centre distance 800 mm, drive speed
360 deg/s, drive angle 0..720 deg, belt stiffness c = 100 000 N per unit
strain, damping d = 50 N s per unit strain, mean ratio i = 2:1, ratio swing
i_max/i_min = 1.5, drive on the smaller pulley.

Design of the pulley pair (the dissertation's pulley geometry, synthesised with
Wyrwa's method in Mathcad, is not given; we synthesise our own)
----------------------------------------------------------------------
Prescribed transmission function (omega2/omega1 = 1/i):

    g(phi1) = 1/i = 1/2 (1 + lam cos(phi1) + bet cos(2 phi1)),
    phi2 = f(phi1) = phi1/2 + lam/2 sin(phi1) + bet/4 sin(2 phi1),

with bet = 0.05 and lam = 0.2 (1 + bet) = 0.21, so that i_max/i_min =
(1 + lam + bet)/(1 - lam + bet) = 1.5 exactly and the mean of g is 1/2 (the
large pulley turns exactly once per two turns of the small one).  The
cos(2 phi1) term was chosen (scan over bet) because it keeps the large
contour convex; a pure cosine (bet = 0) makes its flanks concave.

Both contours are described by support functions p_k(psi) (distance from the
axis to the tangent with outward normal angle psi, pulley frame):
p1 with all harmonics (small pulley, one ratio period per turn), p2 with even
harmonics only (large pulley, two-fold symmetric).  For a toothed belt both
spans must transmit the same speed ratio, i.e. both spans pass through the
relative pole of the pulleys on the centre line, at x_P = -a g/(1 - g)
(small pulley axis at the origin, large at (a, 0)).  With nu(phi1), mu(phi1)
the normal angles of the upper and lower span, the conditions are, for all
phi1 (O2 = (a, 0)):

    p1(nu - phi1)    = x_P cos(nu),       p1(mu - phi1)    = x_P cos(mu),
    p2(nu - f(phi1)) = (x_P - a) cos(nu), p2(mu - f(phi1)) = (x_P - a) cos(mu).

The unknowns p1, p2, nu, mu are Fourier series (K = 24 harmonics each; p1's
mean is fixed, see below); the conditions are collocated at M = 256 drive
angles and solved by Gauss-Newton (:func:`gauss_newton`), continuing from
K = 8.  The residual reached is ~4e-11 m.  The synthesis takes ~0.05 s and
is kept in acausal2d's disk cache, keyed by its inputs and this file.  The size of the
pair is a free parameter of this family: we fix the mean support value of
the small pulley to R1 = 80 teeth * 8 mm / (2 pi) (an 8 mm pitch belt; the
small perimeter is 640 mm); the solution then has the large perimeter
1280 mm = 160 teeth (twice, as the mean ratio requires).  Because both
spans pass through the pole at every instant, the belt length (the
perimeter of the convex hull of both pulleys) stays constant: with
dL/dt = (h1a - h1b) omega1 - (h2a - h2b) omega2 (h = lever arms of the spans)
and h1a/h2a = h1b/h2b = omega2/omega1 it vanishes.  The pulleys are
CurvedPulley elements with these support functions as contours
(:class:`SupportContour`: explicit tangency, closed-form arc length; the
equivalent polar series r_C(kappa) of the large pulley would need ~300
harmonics for 1e-10, see ``SupportContour.polar()``).  Sine coefficients
below 1e-14 m (zero by symmetry) are dropped.  :func:`belt_length` checks
the constant length with the final contours by the tangent construction of
the library (variation ~5e-12 m over a revolution, lever-arm ratios equal
g to ~2e-10).

Other chosen values
-------------------
- pulleys: plain steel discs (7850 kg/m^3) 20 mm thick with the contour as
  outline (mass, inertia, centre of gravity from the contour); the small
  pulley is moved kinematically, its mass only loads its bearing;
- initial belt pretension F0 = 100 N in both spans (strain 1e-3);
- start: phi1 = phi2 = 0, large pulley speed omega2(0) = g(0) omega1 (the
  designed speed; since g'(0) = 0 no initial acceleration torque is
  needed, so the drive starts without a transient);
- tolerances: rtol 1e-8, 721 output points (every degree of drive angle).

``acausal2d simulate models/noncircular_belt_drive.py`` writes the ratio and
the span forces over the drive angle (Bild 7.27, the model's ``figures``);
``acausal2d study models/noncircular_belt_drive.py`` draws the designed
pulleys and reports the design (running the file does both, into ./out).
"""
import functools
import hashlib
import math
import sys

import numpy as np

from acausal2d import Component, Variable, start, study
from acausal2d.io.cache import cached_arrays
from acausal2d.library import rotational, signals
from acausal2d.library.belt import Belt, connect_band, tangent_any
from acausal2d.library.belt.curved import CurvedPulley, SupportContour, _ContourGeometry

A_DIST = 0.8                       # centre distance [m]
OMEGA1 = 2 * math.pi               # 360 deg/s
PITCH = 0.008                      # belt pitch [m]
TEETH1 = 80                        # teeth of the small pulley
R1_MEAN = TEETH1 * PITCH / (2 * math.pi)
BET = 0.05
LAM = 0.2 * (1 + BET)
C_BELT = 1e5                       # N per unit strain
D_BELT = 50.0                      # N s per unit strain
F0 = 100.0                         # pretension [N]
THICKNESS = 0.02
DENSITY = 7850.0


def g_ratio(phi1, lam=LAM, bet=BET):
    """Designed omega2/omega1 = 1/i over the drive angle (numbers or arrays)."""
    return 0.5 * (1 + lam * np.cos(phi1) + bet * np.cos(2 * phi1))


def f_motion(phi1, lam=LAM, bet=BET):
    """Designed angle of the large pulley phi2 = f(phi1)."""
    return 0.5 * phi1 + 0.5 * lam * np.sin(phi1) + 0.25 * bet * np.sin(2 * phi1)


def _basis(x, K, m):
    """[cos(m k x), sin(m k x)], k = 1..K, as an (len(x), 2K) matrix, and
    its derivative with respect to x."""
    k = m * np.arange(1, K + 1)
    C, S = np.cos(np.outer(x, k)), np.sin(np.outer(x, k))
    return np.hstack([C, S]), np.hstack([-S * k, C * k])


class Design:
    """Result of :func:`design`: support functions (p0, a, b, base) of both
    pulleys, their polar contours, the collocation residual and the data."""

    def __init__(self, **kw):
        self.__dict__.update(kw)


def _unpack(z, K):
    """(p1c, p2m, p2c, nu0, nuc, mu0, muc) of the unknown vector ``z``."""
    n = 2 * K
    return (z[:n], z[n], z[n + 1:2 * n + 1], z[2 * n + 1], z[2 * n + 2:3 * n + 2],
            z[3 * n + 2], z[3 * n + 3:4 * n + 3])


class _Fit:
    """Residuals (contact conditions at M angles) of the pulley-pair fit
    with K harmonics, and their Jacobian."""

    def __init__(self, phi, xP, f, r1_mean, a):
        self.phi, self.xP, self.f, self.r1_mean, self.a = phi, xP, f, r1_mean, a

    def __call__(self, z, K, jac):
        n, M = 2 * K, self.phi.size
        p1c, p2m, p2c, nu0, nuc, mu0, muc = _unpack(z, K)
        Bphi, _ = _basis(self.phi, K, 1)
        Bn = np.hstack([np.ones((M, 1)), Bphi])            # d(nu)/d(nu0, nuc)
        res, rows = [], []
        for ang, col in ((nu0 + Bphi @ nuc, 2 * n + 1), (mu0 + Bphi @ muc, 3 * n + 2)):
            # small pulley: p1(ang - phi) = x_P cos(ang)
            B1, dB1 = _basis(ang - self.phi, K, 1)
            res.append(self.r1_mean + B1 @ p1c - self.xP * np.cos(ang))
            if jac:
                J = np.zeros((M, len(z)))
                J[:, :n] = B1
                J[:, col:col + n + 1] = (dB1 @ p1c + self.xP * np.sin(ang))[:, None] * Bn
                rows.append(J)
            # large pulley: p2(ang - f) = (x_P - a) cos(ang)
            B2, dB2 = _basis(ang - self.f, K, 2)
            res.append(p2m + B2 @ p2c - (self.xP - self.a) * np.cos(ang))
            if jac:
                J = np.zeros((M, len(z)))
                J[:, n] = 1.0
                J[:, n + 1:2 * n + 1] = B2
                J[:, col:col + n + 1] = (dB2 @ p2c + (self.xP - self.a) * np.sin(ang))[:, None] \
                    * Bn
                rows.append(J)
        return np.vstack(rows) if jac else np.concatenate(res)


def _start(Kc, prev, r1_mean, xP):
    """Start vector with Kc harmonics: circles, or the previous solution
    ``prev`` (fewer harmonics) padded with zeros."""
    n = 2 * Kc
    z = np.zeros(4 * n + 3)
    nu_c = math.pi - np.arccos(r1_mean / np.abs(xP))
    z[n], z[2 * n + 1], z[3 * n + 2] = 2 * r1_mean, nu_c.mean(), -nu_c.mean()
    if prev is not None:
        Kp = len(prev[0]) // 2
        for off, c in ((0, prev[0]), (n + 1, prev[2]), (2 * n + 2, prev[4]),
                       (3 * n + 3, prev[6])):
            z[off:off + Kp] = c[:Kp]
            z[off + Kc:off + Kc + Kp] = c[Kp:]
        z[n], z[2 * n + 1], z[3 * n + 2] = prev[1], prev[3], prev[5]
    return z


def gauss_newton(fun, jac, z, max_iter=50):
    """Minimise ||fun(z)||^2 from ``z`` by Gauss-Newton steps (the normal
    equations J^T J dz = -J^T r of jac(z) dz = -fun(z); J has full column
    rank here, cond(J) ~ 200), each halved until the sum of squares
    decreases; stops when a step lowers it by less than 1e-10 of itself or
    no halved step lowers it.  Returns the last z."""
    r = fun(z)
    f = r @ r
    for _ in range(max_iter):
        J = jac(z)
        dz = np.linalg.solve(J.T @ J, -(J.T @ r))
        for halving in range(12):
            zn = z + 0.5 ** halving * dz
            rn = fun(zn)
            if rn @ rn < f:
                break
        else:
            return z
        done = rn @ rn > f * (1.0 - 1e-10)
        z, r, f = zn, rn, rn @ rn
        if done:
            break
    return z


def synthesise(a=A_DIST, r1_mean=R1_MEAN, lam=LAM, bet=BET, K=24, M=256):
    """Solve the collocated contact conditions of the pulley pair (module
    docstring) by Gauss-Newton, continuing from K = 8 harmonics.  Returns
    the support coefficients p1c (small pulley, cos then sin), p2m, p2c
    (large pulley) and the largest residual [m], as a dict of arrays."""
    phi = np.linspace(0.0, 2 * math.pi, M, endpoint=False)
    g = g_ratio(phi, lam, bet)
    xP = -a * g / (1 - g)
    fit = _Fit(phi, xP, f_motion(phi, lam, bet), r1_mean, a)
    prev = None
    for Kc in (8, K):
        z = gauss_newton(lambda z: fit(z, Kc, False), lambda z: fit(z, Kc, True),
                         _start(Kc, prev, r1_mean, xP))
        prev = _unpack(z, Kc)
    res = float(np.max(np.abs(fit(z, K, False))))
    # the collocation is solved when its residual vanishes, not by a solver's exit flag
    if not res <= 1e-9:
        raise RuntimeError("noncircular pulley design: the collocation residual stays "
                           "%.3g m (> 1e-9 m); change K or M" % res)
    return {"p1c": prev[0], "p2m": np.array(prev[1]), "p2c": prev[2],
            "residual": np.array(res)}


def _source_hash():
    """sha256 of this file (part of the disk-cache key of the design), or
    None when the module has no file (then the design is not cached)."""
    try:
        with open(__file__, "rb") as fh:
            return hashlib.sha256(fh.read()).hexdigest()
    except (NameError, OSError):
        return None


_SOURCE = _source_hash()


@functools.lru_cache(maxsize=4)
def design(a=A_DIST, r1_mean=R1_MEAN, lam=LAM, bet=BET, K=24, M=256):
    """The pulley pair of :func:`synthesise` as a :class:`Design`.  The
    synthesis is kept in acausal2d's disk cache (:mod:`acausal2d.io.cache`),
    keyed by the inputs and the text of this file."""
    key = ("noncircular pulley pair", a, r1_mean, lam, bet, K, M, _SOURCE)
    arrays = cached_arrays("noncircular-pulley-pair", key,
                           lambda: synthesise(a, r1_mean, lam, bet, K, M)) if _SOURCE \
        else synthesise(a, r1_mean, lam, bet, K, M)
    # coefficients below 1e-14 m (the sine terms vanish by the symmetry of
    # the design about the centre line) are dropped from the contours
    p1c, p2c = (np.where(np.abs(arrays[k]) < 1e-14, 0.0, arrays[k]) for k in ("p1c", "p2c"))
    sup1 = (r1_mean, p1c[:K], p1c[K:], 1)
    sup2 = (float(arrays["p2m"]), p2c[:K], p2c[K:], 2)
    return Design(a=a, lam=lam, bet=bet, K=K, M=M, residual=float(arrays["residual"]),
                  support1=sup1, support2=sup2, contour1=SupportContour(*sup1),
                  contour2=SupportContour(*sup2))


def belt_length(des, phi1, phi2=None):
    """Belt length around both (final, polar) contours by the tangent
    construction: upper span + lower span + wrapped arcs (arc-length
    functions of the contours), for drive angles ``phi1`` and large pulley
    angles ``phi2`` (default: the designed motion f(phi1)).  Also returns
    the lever arms (h1a, h2a, h1b, h2b) of the upper (a) and lower (b) span
    about both axes."""
    phi1 = np.atleast_1d(np.asarray(phi1, dtype=float))
    phi2 = f_motion(phi1, des.lam, des.bet) if phi2 is None else np.atleast_1d(phi2)
    C1, C2 = des.contour1, des.contour2
    L, levers = [], []
    for p1, p2 in zip(phi1, phi2):
        # upper span: from the large pulley's K2 to the small pulley's K1 (w_i = -1)
        g1 = _ContourGeometry(des.a, 0.0, p2, C2, -1)    # K2 of the large pulley
        s1 = _ContourGeometry(0.0, 0.0, p1, C1, 1)       # K1 of the small pulley
        gu, lu = tangent_any(g1, s1)
        # lower span: from the small pulley's K2 to the large pulley's K1
        s2 = _ContourGeometry(0.0, 0.0, p1, C1, -1)
        g2 = _ContourGeometry(des.a, 0.0, p2, C2, 1)
        gl, ll = tangent_any(s2, g2)
        k1a = s1.kappa(-math.sin(gu + math.pi), math.cos(gu + math.pi))   # small, K1
        k1b = s2.kappa(math.sin(gl), -math.cos(gl))                       # small, K2
        k2b = g2.kappa(-math.sin(gl + math.pi), math.cos(gl + math.pi))   # large, K1
        k2a = g1.kappa(math.sin(gu), -math.cos(gu))                       # large, K2
        # wrapped arcs: counter-clockwise from K1 to K2 on both pulleys
        w1 = C1.s(np.array([k1b + 2 * math.pi * math.ceil((k1a - k1b) / (2 * math.pi))]))[0] \
            - C1.s(np.array([k1a]))[0]
        w2 = C2.s(np.array([k2a + 2 * math.pi * math.ceil((k2b - k2a) / (2 * math.pi))]))[0] \
            - C2.s(np.array([k2b]))[0]
        L.append(lu + ll + w1 + w2)
        eu = (math.cos(gu), math.sin(gu))
        el = (math.cos(gl), math.sin(gl))
        xa, ya = s1.support(-math.sin(gu + math.pi), math.cos(gu + math.pi))
        xb, yb = s2.support(math.sin(gl), -math.cos(gl))
        h1a = abs(xa * eu[1] - ya * eu[0])
        h1b = abs(xb * el[1] - yb * el[0])
        h2a = abs((xa - des.a) * eu[1] - ya * eu[0])
        h2b = abs((xb - des.a) * el[1] - yb * el[0])
        levers.append((h1a, h2a, h1b, h2b))
    return np.array(L), np.array(levers)


class NonCircularBeltDrive(Component):
    """Toothed belt drive with non-circular pulleys (module docstring).

    Components: ``small`` and ``large`` (CurvedPulley, fixed axes at (0, 0)
    and (0.8 m, 0)), ``upper`` and ``lower`` belt spans (the upper span is
    the tight side: the small pulley drives counter-clockwise), the drive
    ``drive`` (angle 2 pi t on the small pulley's flange).  Outputs: the
    transmission ratio ``ratio = omega_small/omega_large``, the designed
    ratio ``ratio_design = 1/g(phi1)``, the drive angle ``drive_deg`` and
    the span forces ``upper.F``, ``lower.F``."""
    experiment = {"stop_time": 2.0, "intervals": 720, "rtol": 1e-8}
    outputs = ["ratio", "ratio_design", "drive_deg", "upper.F", "lower.F", "large.w_rel"]
    figures = [{"name": "ratio", "x": "small.phi_rel", "signals": ["ratio", "ratio_design"],
                "title": "transmission ratio over the drive angle (Bild 7.27)"},
               {"name": "span_forces", "x": "small.phi_rel", "signals": ["upper.F", "lower.F"],
                "title": "span forces over the drive angle (Bild 7.27)"}]

    ratio = Variable(start=2.0, doc="transmission ratio omega1/omega2")
    ratio_design = Variable(start=2.0, doc="designed ratio 1/g(phi1)")
    drive_deg = Variable(unit="deg", doc="drive angle in degrees")

    def __init__(self, des=None, c=C_BELT, d=D_BELT, F0=F0, **kw):
        super().__init__(**kw)
        des = des or design()
        self.des = des
        m1, J1, cog1 = des.contour1.mass_properties(THICKNESS, DENSITY)
        m2, J2, cog2 = des.contour2.mass_properties(THICKNESS, DENSITY)
        w2_0 = float(g_ratio(0.0, des.lam, des.bet)) * OMEGA1
        self.small = CurvedPulley(des.contour1, w_i=-1, x10=0.0, y10=0.0, m=m1, J=J1, cog=cog1)
        self.large = CurvedPulley(des.contour2, w_i=-1, x10=des.a, y10=0.0, m=m2, J=J2, cog=cog2,
                                  phi=start(0.0, fixed=True), w_rel=start(w2_0, fixed=True))
        eps0 = F0 / c
        self.upper = Belt(c=c, d=d, eps=start(eps0, fixed=True))
        self.lower = Belt(c=c, d=d, eps=start(eps0, fixed=True))
        connect_band(self, self.upper, 1, self.large, 2)
        connect_band(self, self.upper, 2, self.small, 1)
        connect_band(self, self.lower, 1, self.small, 2)
        connect_band(self, self.lower, 2, self.large, 1)
        self.drive = rotational.Position()
        self.angle = signals.TimeFunction(lambda t: OMEGA1 * t)
        self.connect(self.angle.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.small.ctrR2)

    def equations(self):
        import casadi as ca
        p1 = self.small.phi_rel
        g = 0.5 * (1 + self.des.lam * ca.cos(p1) + self.des.bet * ca.cos(2 * p1))
        return [self.ratio * self.large.w_rel == self.small.w_rel,
                self.ratio_design * g == 1.0,
                self.drive_deg == p1 * 180.0 / math.pi]

    @study
    def pulleys(ctx):
        """The designed pulley pair: contours, collocation residual and the
        belt length over a revolution."""
        des = ctx.model.des
        L, _ = belt_length(des, np.linspace(0, 2 * math.pi, 37))
        ctx.note("design residual %.2e m, perimeters %.6f / %.6f m" % (
            des.residual, des.contour1.perimeter, des.contour2.perimeter))
        ctx.note("belt length %.9f m, variation %.2e m over a revolution" % (
            L.mean(), L.max() - L.min()))
        res = ctx.result
        ctx.note("simulated ratio %.4f .. %.4f (designed 1/g %.4f .. %.4f)" % (
            res["ratio"].min(), res["ratio"].max(), res["ratio_design"].min(),
            res["ratio_design"].max()))
        ctx.save(pulley_figure(des), "noncircular_belt_drive_pulleys")


def pulley_figure(des):
    """Outline of both designed pulleys at the start (phi = 0) as a
    matplotlib Figure (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8, 3.5))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    k = np.linspace(0, 2 * math.pi, 721)
    for C, x0, label in ((des.contour1, 0.0, "small (driving)"), (des.contour2, des.a, "large")):
        x, y = C.point(k)
        ax.plot(x + x0, y, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("NonCircularBeltDrive: designed pulley contours (phi = 0)")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
