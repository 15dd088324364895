"""Pulley with curved contour (library/belt_curved.py, seed eq. 4.100-4.122)
and the non-circular toothed belt drive (models/noncircular_belt_drive.py,
seed ch. 7.3.2)."""
import math

import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.belt import Belt, Drum, Pulley, RopeDrive, connect_band, tangent_any
from acausal2d.library.belt.curved import (Contour, CurvedDrum, CurvedPulley, SupportContour,
                                           _ContourGeometry)
from acausal2d.library.planar import Body, Fixed, Prismatic
from conftest import load_model_class

R1, R2 = 0.1, 0.05
C2 = (0.5, 0.1)


def smooth_angle(t):
    return 2.0 * (t - ca.sin(2 * t) / 2)


class TwoPulleys(Component):
    """Driven pulley p1 and free pulley p2 (J 1e-4) with a closed elastic
    belt (as tests/test_belt.py); ``kind`` selects the pulley element."""

    def __init__(self, kind="circular", c=1e6, **kw):
        super().__init__(**kw)
        eps0 = 100.0 / c
        if kind == "circular":
            self.p1 = Pulley(r=R1, x10=0.0, y10=0.0, w_i=-1)
            self.p2 = Pulley(r=R2, x10=C2[0], y10=C2[1], w_i=-1, J=1e-4)
        else:
            make = Contour.circle if kind == "polar" else SupportContour
            self.p1 = CurvedPulley(make(R1), x10=0.0, y10=0.0, w_i=-1)
            self.p2 = CurvedPulley(make(R2), x10=C2[0], y10=C2[1], w_i=-1, J=1e-4)
        self.span_a = Belt(c=c, d=c * 1e-4, eps=start(eps0, fixed=True))
        self.span_b = Belt(c=c, d=c * 1e-4, eps=start(eps0, fixed=True))
        connect_band(self, self.span_a, 1, self.p1, 2)
        connect_band(self, self.span_a, 2, self.p2, 1)
        connect_band(self, self.span_b, 1, self.p2, 2)
        connect_band(self, self.span_b, 2, self.p1, 1)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(smooth_angle)
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.p1.ctrR2)


@pytest.fixture(scope="module")
def circular_result():
    return acausal2d.simulate(TwoPulleys("circular"), stop_time=2.0, rtol=1e-10,
                              output_times=np.linspace(0.0, 2.0, 101))


@pytest.mark.parametrize("kind", ["polar", "support"])
def test_circle_contour_reproduces_circular_pulley(circular_result, kind):
    ref = circular_result
    res = acausal2d.simulate(TwoPulleys(kind), stop_time=2.0, rtol=1e-10,
                             output_times=np.linspace(0.0, 2.0, 101))
    for name in ("span_a.F", "span_b.F", "span_a.l", "span_b.l", "span_a.gamma", "span_b.gamma",
                 "p1.beta", "p2.beta", "p2.w_rel", "p1.ctrK1.x", "p1.ctrK1.y", "p2.ctrK2.x",
                 "p2.ctrK2.y", "p1.ctrB1.L", "p2.ctrB2.L", "p1.F_bear"):
        assert np.max(np.abs(res[name] - ref[name])) < 1e-8, name
    # the free pulley's angle (~9.5 rad) agrees to the integration tolerance
    assert np.max(np.abs(res["p2.phi"] - ref["p2.phi"])) < 1e-8 * 10
    # contact angles: pulley frame (curved) versus world frame (circular)
    for k in (1, 2):
        assert np.max(np.abs(res["p1.kappa%d" % k] + res["p1.phi"] - ref["p1.kappa%d" % k])) \
            < 1e-9


A_ELL, B_ELL = 0.1, 0.08


def ellipse(k):
    return A_ELL * B_ELL / ca.sqrt((B_ELL * ca.cos(k)) ** 2 + (A_ELL * ca.sin(k)) ** 2)


class EllipseDrive(Component):
    """An elliptic pulley (polar contour from a Python function) driven at
    one revolution per second drives a circular free pulley with a soft
    belt, whose length changes with the ellipse's orientation."""

    def __init__(self, contour, **kw):
        super().__init__(**kw)
        self.p1 = CurvedPulley(contour, x10=0.0, y10=0.0, w_i=-1)
        self.p2 = CurvedPulley(Contour.circle(0.06), x10=0.6, y10=-0.05, w_i=-1, J=2e-4)
        self.span_a = Belt(c=2e3, d=2.0, eps=start(0.05, fixed=True))
        self.span_b = Belt(c=2e3, d=2.0, eps=start(0.05, fixed=True))
        connect_band(self, self.span_a, 1, self.p1, 2)
        connect_band(self, self.span_a, 2, self.p2, 1)
        connect_band(self, self.span_b, 1, self.p2, 2)
        connect_band(self, self.span_b, 2, self.p1, 1)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(lambda t: 2 * math.pi * (t - ca.sin(2 * t) / 2))
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.p1.ctrR2)


def test_elliptic_contour_contacts_and_tangency():
    con = Contour.from_function(ellipse, symmetry=2)
    # arc length: closed-form series against the exact perimeter of the ellipse
    from scipy.special import ellipe
    perim = 4 * A_ELL * ellipe(1 - (B_ELL / A_ELL) ** 2)
    assert abs(con.perimeter - perim) < 1e-13
    k = np.linspace(-7.0, 7.0, 2001)
    ds = np.gradient(con.s(k), k, edge_order=2)
    assert np.max(np.abs(ds - np.hypot(con.r(k), con.dr(k)))) < 1e-5   # FD of a smooth s
    T = 3.5
    res = acausal2d.simulate(EllipseDrive(con), stop_time=T, rtol=1e-10,
                             output_times=np.linspace(0.0, T, 351))
    assert res.events == []
    phi = res["p1.phi"]
    assert phi[-1] > 2 * math.pi * 3          # more than three revolutions
    for kk in (1, 2):
        kap = res["p1.kappa%d" % kk]
        # unwrapped contact angle (pulley frame) runs backwards over the turns
        assert kap[0] - kap[-1] > 2 * math.pi * 3
        assert np.max(np.abs(np.diff(kap))) < 1.0
        # contact point lies on the contour
        x = res["p1.ctrK%d.x" % kk]
        y = res["p1.ctrK%d.y" % kk]
        xb = np.cos(phi) * x + np.sin(phi) * y
        yb = -np.sin(phi) * x + np.cos(phi) * y
        r = con.r(kap)
        assert np.max(np.abs(xb - r * np.cos(kap))) < 1e-9
        assert np.max(np.abs(yb - r * np.sin(kap))) < 1e-9
        # span tangent to the contour: normalised cross product of the contour
        # tangent (world) and the span direction
        dr = con.dr(kap)
        tx = dr * np.cos(kap + phi) - r * np.sin(kap + phi)
        ty = dr * np.sin(kap + phi) + r * np.cos(kap + phi)
        g = res["p1.ctrB%d.gamma" % kk]
        cross = (tx * np.sin(g) - ty * np.cos(g)) / np.hypot(tx, ty)
        assert np.max(np.abs(cross)) < 1e-9
    # the free span geometry equals an independent tangent construction
    i = len(res.time) - 1
    geo1 = _ContourGeometry(0.0, 0.0, float(phi[i]), con, -1)     # p1 K2, start of span_a
    geo2 = _ContourGeometry(0.6, -0.05, 0.0, Contour.circle(0.06), 1)
    gam, l = tangent_any(geo1, geo2)
    assert abs(math.remainder(res["span_a.gamma"][i] - gam, 2 * math.pi)) < 1e-9
    assert abs(res["span_a.l"][i] - l) < 1e-9
    # both spans stay taut
    assert np.all(res["span_a.F"] > 0) and np.all(res["span_b.F"] > 0)


def test_table_contour_fits_the_spline():
    k = np.linspace(0, 2 * math.pi, 72, endpoint=False)
    r = A_ELL * B_ELL / np.sqrt((B_ELL * np.cos(k)) ** 2 + (A_ELL * np.sin(k)) ** 2)
    con = Contour.from_table(k, r, n_harm=64)
    assert con.kind == "table"
    assert con.fit_error < 1e-6
    assert np.max(np.abs(con.r(k) - r)) < 1e-6
    ref = Contour.from_function(ellipse, symmetry=2)
    assert abs(con.perimeter - ref.perimeter) < 1e-6


def test_support_contour_arc_length_and_polar_form():
    c = SupportContour(0.2, a=[0.03, 0.004], b=[0.0, 0.001], base=2)
    psi = np.linspace(0.0, 2 * math.pi, 40001)
    x, y = c.point(psi)
    seg = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    assert np.max(np.abs(c.s(psi) - c.s(0.0) - seg)) < 1e-8        # chord error ~ h^2
    assert abs(c.s(2 * math.pi) - c.perimeter) < 1e-14
    pol = c.polar()
    kap = np.arctan2(y, x)
    assert np.max(np.abs(pol.r(kap) - np.hypot(x, y))) < 1e-12
    m1, J1, s1 = c.mass_properties(0.02, 7850.0)
    m2, J2, s2 = pol.mass_properties(0.02, 7850.0)
    assert abs(m1 - m2) < 1e-10 * m1 and abs(J1 - J2) < 1e-10 * J1
    with pytest.raises(acausal2d.ModelDefinitionError):
        SupportContour(0.1, a=[0.05], base=2)          # p + p'' < 0: not convex


class Hoist(Component):
    """Drum (circular, or curved with a circular contour) lifting a body."""

    def __init__(self, curved, **kw):
        super().__init__(**kw)
        if curved:
            self.drum = CurvedDrum(Contour.circle(0.1), x10=-0.1, y10=0.0, w_i=-1, J=0.01)
        else:
            self.drum = Drum(r=0.1, x10=-0.1, y10=0.0, w_i=-1, J=0.01)
        self.rope = Belt(c=1e6, d=1e3, eps=start(2 * 9.81 / 1e6, fixed=True))
        self.guide = Fixed()
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0, fixed=True), v=start(0.0, fixed=True))
        self.body = Body(m=2.0, I=0.01, x=start(0.0), y=start(-1.0))
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        connect_band(self, self.rope, 1, self.drum, 1)
        self.connect(self.rope.ctr2D2, self.body.frame_a)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(lambda t: 0.5 * (t - ca.sin(2 * t) / 2))
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.drum.ctrR2)


def test_curved_drum_with_circle_matches_drum():
    out = [acausal2d.simulate(Hoist(curved), stop_time=1.5, rtol=1e-10,
                              output_times=np.linspace(0.0, 1.5, 31)) for curved in (False, True)]
    for name in ("rope.F", "body.y", "drum.F_bear"):
        assert np.max(np.abs(out[0][name] - out[1][name])) < 1e-8, name
    lw = out[1]["drum.l_wound"]
    assert np.max(np.abs((lw - lw[0]) - (out[0]["drum.l_wound"] - out[0]["drum.l_wound"][0]))) \
        < 1e-9


# --------------------------------------------------------------------------
# non-circular toothed belt drive (seed ch. 7.3.2)
# --------------------------------------------------------------------------
design = load_model_class("noncircular_belt_drive.py", "design")
belt_length = load_model_class("noncircular_belt_drive.py", "belt_length")
g_ratio = load_model_class("noncircular_belt_drive.py", "g_ratio")
NonCircularBeltDrive = load_model_class("noncircular_belt_drive.py", "NonCircularBeltDrive")


def test_noncircular_design_keeps_belt_length():
    des = design()
    assert des.residual < 1e-9
    phi = np.linspace(0.0, 2 * math.pi, 61)
    L, lev = belt_length(des, phi)
    # constant belt length (tangent construction on the final contours)
    assert np.max(L) - np.min(L) < 1e-9
    # both spans transmit the designed ratio (lever arms through the pole)
    g = g_ratio(phi)
    assert np.max(np.abs(lev[:, 0] / lev[:, 1] - g)) < 1e-8
    assert np.max(np.abs(lev[:, 2] / lev[:, 3] - g)) < 1e-8
    i = 1 / g
    assert i.max() / i.min() == pytest.approx(1.5, abs=1e-12)
    assert np.mean(g[:-1]) == pytest.approx(0.5, abs=1e-12)
    # 80 and 160 teeth of 8 mm; convex contours
    assert des.contour1.perimeter == pytest.approx(0.64, abs=1e-12)
    assert des.contour2.perimeter == pytest.approx(1.28, abs=1e-9)
    assert des.contour1.rho_min > 0 and des.contour2.rho_min > 0


@pytest.fixture(scope="module")
def drive_result():
    return acausal2d.simulate(NonCircularBeltDrive(), stop_time=2.0, rtol=1e-8,
                              output_times=np.linspace(0.0, 2.0, 721))


def test_noncircular_drive_follows_designed_ratio(drive_result):
    res = drive_result
    model = NonCircularBeltDrive()
    des = model.des
    dev = np.max(np.abs(res["ratio"] / res["ratio_design"] - 1.0))
    # Tolerance: the belt is elastic, so the large pulley lags behind the
    # rigid motion by its accelerating torque over the torsional stiffness of
    # the two spans, dphi2 = J2 alpha2 / k_t with alpha2 = g'(phi1) w1^2 and
    # k_t = 2 (c / l) h2^2.  The ratio error is then about
    # J2 max|g''| w1^2 / (k_t g_min) (quasi-static; the excitation is far
    # below the drive's natural frequency of ~25 Hz).
    J2 = des.contour2.mass_properties(0.02, 7850.0)[1]
    lam, bet, w1 = des.lam, des.bet, 2 * math.pi
    h2_min = des.contour2.p(np.linspace(0, math.pi, 2001)).min()
    k_t = 2 * (1e5 / des.a) * h2_min ** 2
    est = J2 * 0.5 * (lam + 4 * bet) * w1 ** 2 / (k_t * 0.5 * (1 - lam + bet))
    assert 2e-4 < est < 3e-3
    assert dev < 2 * est
    # the large pulley turns exactly once per two turns of the small one
    assert res["large.phi"][-1] == pytest.approx(2 * math.pi, abs=1e-3)


def test_noncircular_drive_span_forces(drive_result):
    res = drive_result
    for span in ("upper", "lower"):
        F = res[span + ".F"]
        assert np.all(F > 50.0) and np.all(F < 150.0)
        assert abs(np.mean(F) - 100.0) < 5.0
    # no load torque: the spans only carry the accelerating torque of the large
    # pulley, so their forces swing in opposite directions
    assert np.corrcoef(res["upper.F"], res["lower.F"])[0, 1] < 0


# --------------------------------------------------------------------------
# curved drum winding a rope: wound length = contour arc length (quadrature)
# --------------------------------------------------------------------------
# Fourier contour r = c0 + a1 cos k + a2 cos 2k + b2 sin 2k (no symmetry,
# convex: checked in the test) and the ellipse A_D x B_D (polar function).
FOURIER_DRUM = (0.1, 0.006, 0.010, 0.004)
A_D, B_D = 0.1, 0.07


def fourier_drum_np(k):
    """r, r', r'' of the Fourier drum contour, written out by hand (numpy)."""
    c0, a1, a2, b2 = FOURIER_DRUM
    r = c0 + a1 * np.cos(k) + a2 * np.cos(2 * k) + b2 * np.sin(2 * k)
    dr = -a1 * np.sin(k) - 2 * a2 * np.sin(2 * k) + 2 * b2 * np.cos(2 * k)
    d2r = -a1 * np.cos(k) - 4 * a2 * np.cos(2 * k) - 4 * b2 * np.sin(2 * k)
    return r, dr, d2r


def ellipse_drum(k):
    return A_D * B_D / ca.sqrt((B_D * ca.cos(k)) ** 2 + (A_D * ca.sin(k)) ** 2)


def ellipse_param(kappa):
    """Parameter t of the ellipse point (A_D cos t, B_D sin t) at the polar
    angle kappa, on the branch of kappa (|t - kappa| < pi/2)."""
    t = np.arctan2(A_D * np.sin(kappa), B_D * np.cos(kappa))
    return kappa + np.remainder(t - kappa + math.pi, 2 * math.pi) - math.pi


class CurvedDrumRope(Component):
    """A curved drum at the origin with a rope hanging from its right side.

    ``hoist``: Fourier contour, the drum is turned by an angle drive (w=+1:
    winds up) and lifts a 2 kg body on a vertical guide.
    ``pull``: elliptic contour, the rope end is pulled down by a RopeDrive
    and unwinds the drum (J 1e-3) against a constant winding torque of 5 N m
    that keeps the rope taut."""

    def __init__(self, variant, **kw):
        super().__init__(**kw)
        if variant == "hoist":
            c0, a1, a2, b2 = FOURIER_DRUM
            con = Contour.fourier(c0, a=[a1, a2], b=[0.0, b2])
            self.drum = CurvedDrum(con, w_i=-1, x10=0.0, y10=0.0, J=0.01, n_wound=1.0)
            self.rope = Belt(c=1e5, d=300.0, eps=start(2 * 9.81 / 1e5, fixed=True))
            self.guide = Fixed(r=(0.1, 0.0))
            self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.5, fixed=True),
                                    v=start(0.0, fixed=True))
            self.body = Body(m=2.0, I=0.01, x=start(0.1), y=start(-1.5))
            self.connect(self.guide.frame, self.slider.frame_a)
            self.connect(self.slider.frame_b, self.body.frame_a)
            self.connect(self.rope.ctr2D2, self.body.frame_a)
            self.drive = rotational.Position()
            self.sig = signals.TimeFunction(lambda t: 3.0 * (t - ca.sin(2 * t) / 2))
            self.connect(self.sig.y, self.drive.phi_in)
            self.connect(self.drive.flange, self.drum.ctrR2)
        else:
            con = Contour.from_function(ellipse_drum, symmetry=2)
            self.drum = CurvedDrum(con, w_i=-1, x10=0.0, y10=0.0, J=1e-3, n_wound=3.0,
                                   phi=start(0.0, fixed=True), w_rel=start(0.0, fixed=True))
            self.rope = Belt(c=1e6, d=1e3, eps=start(60.0 / 1e6, fixed=True))
            self.hold = rotational.ConstantTorque(tau_constant=5.0)
            self.connect(self.hold.flange, self.drum.ctrR2)
            self.pull = RopeDrive(x0=0.085, y0=-1.0, angle=-math.pi / 2)
            self.sig = signals.TimeFunction(lambda t: 0.5 * (t - ca.sin(2 * t) / 2))
            self.connect(self.sig.y, self.pull.s_in)
            self.connect(self.rope.ctr2D2, self.pull.frame)
        connect_band(self, self.rope, 1, self.drum, 1)


@pytest.mark.parametrize("variant", ["hoist", "pull"])
def test_curved_drum_wound_length_is_contour_arc_length(variant):
    """The rope wound onto (or off) a non-circular drum over a rotation equals
    the arc length of the contour between the first and the current contact
    point, by numerical quadrature of the contour in the test."""
    from scipy.integrate import quad
    T = 2.0
    res = acausal2d.simulate(CurvedDrumRope(variant), stop_time=T, rtol=1e-9,
                             output_times=np.linspace(0.0, T, 41))
    assert res.events == []
    t = res.time
    phi, kap = res["drum.phi"], res["drum.kappa1"]
    Kx, Ky = res["drum.ctrK1.x"], res["drum.ctrK1.y"]
    if variant == "hoist":
        ex, ey = res["body.x"], res["body.y"]
        k = np.linspace(0.0, 2 * math.pi, 3601)
        r, dr, d2r = fourier_drum_np(k)
        assert np.min(r * r + 2 * dr * dr - r * d2r) > 0      # convex contour

        def speed(x):
            r, dr, _ = fourier_drum_np(x)
            return math.hypot(r, dr)
        arc = [quad(speed, kap[0], kk, epsabs=1e-14, epsrel=1e-13, limit=200)[0] for kk in kap]
        r_k, dr_k, _ = fourier_drum_np(kap)
        # contour tangent in the pulley frame (d/dkappa of r (cos, sin))
        tx = dr_k * np.cos(kap) - r_k * np.sin(kap)
        ty = dr_k * np.sin(kap) + r_k * np.cos(kap)
        assert phi[-1] > 7.0 and kap[0] - kap[-1] > 2 * math.pi      # winds > 1 turn
    else:
        # rope end: prescribed by the drive function, computed here
        ex, ey = 0.085 + 0.0 * t, -1.0 - 0.5 * (t - np.sin(2 * t) / 2)
        # parametric ellipse (A cos u, B sin u): ds = sqrt(A^2 sin^2 u + B^2 cos^2 u) du
        u = ellipse_param(kap)
        arc = [quad(lambda x: math.hypot(A_D * math.sin(x), B_D * math.cos(x)), u[0], uu,
                    epsabs=1e-14, epsrel=1e-13, limit=200)[0] for uu in u]
        r_k = np.hypot(A_D * np.cos(u), B_D * np.sin(u))
        tx, ty = -A_D * np.sin(u), B_D * np.cos(u)
        assert phi[-1] < -4 * math.pi and kap[-1] - kap[0] > 4 * math.pi   # unwinds > 2 turns
    arc = np.array(arc)
    scale = abs(arc[-1])
    assert scale > 0.7
    # (a) the drum's own wound-length outputs against the quadrature: the
    # closed-form Fourier arc length is spectrally accurate (~1e-14 of the
    # mean radius) and quad is asked for 1e-13, so what remains is the
    # Newton tolerance of the algebraic variables kappa1, ctrB1.L (~rtol);
    # observed 2e-11 relative, bound 1e-9 relative.
    dL = res["drum.ctrB1.L"] - res["drum.ctrB1.L"][0]
    assert np.max(np.abs(dL - arc)) < 1e-9 * scale                  # ctrB1.L = w s(kappa1)
    dW = res["drum.l_wound"] - res["drum.l_wound"][0]
    assert np.max(np.abs(dW + arc)) < 1e-9 * scale
    # (b) physically: the unstretched length of the free rope, from the
    # geometric distance contact point -> rope end and the strain, changes by
    # exactly the arc length.  Belt material is conserved to the integration
    # tolerance (Belt docstring: ~1e-6 relative at rtol 1e-8); observed
    # 1e-10 .. 1e-9 relative at rtol 1e-9, bound 1e-6 relative.
    l_u = np.hypot(ex - Kx, ey - Ky) / (1.0 + res["rope.eps"])
    assert np.max(np.abs((l_u - l_u[0]) - arc)) < 1e-6 * scale
    assert np.all(res["rope.F"] > 10.0)                               # taut throughout
    # the contact point lies on the contour: world -> pulley frame, polar
    # radius and angle against the contour formula.  These are algebraic
    # equations, solved by IDA's Newton iteration to ~rtol (1e-9) times the
    # nominal values: observed <= 2e-11 m and 3e-10 rad; bounds 1e-8.
    xb = np.cos(phi) * Kx + np.sin(phi) * Ky
    yb = -np.sin(phi) * Kx + np.cos(phi) * Ky
    assert np.max(np.abs(np.hypot(xb, yb) - r_k)) < 1e-8
    assert np.max(np.abs(np.remainder(np.arctan2(yb, xb) - kap + math.pi, 2 * math.pi)
                         - math.pi)) < 1e-8
    # ... and the rope is tangent there: the unit rope direction (from the
    # positions, pulley frame) is parallel to the contour tangent (sine of
    # the angle between them; same Newton tolerance: observed 7e-10, bound 1e-8)
    dx, dy = ex - Kx, ey - Ky
    n = np.hypot(dx, dy)
    ux = (np.cos(phi) * dx + np.sin(phi) * dy) / n
    uy = (-np.sin(phi) * dx + np.cos(phi) * dy) / n
    assert np.max(np.abs(tx * uy - ty * ux) / np.hypot(tx, ty)) < 1e-8


# --------------------------------------------------------------------------
# bearing friction on a curved pulley
# --------------------------------------------------------------------------
MU_CP, RPIN_CP, M_CP = 0.3, 0.01, 2.0


def pull_ramp(t, V=0.2, Ta=0.5):
    """Rope travel: cosine velocity ramp to V over Ta, then constant speed."""
    up = V * (t / 2 - Ta / (2 * math.pi) * ca.sin(math.pi * t / Ta))
    return ca.if_else(t < Ta, up, V * Ta / 2 + V * (t - Ta))


class FrictionOverEllipse(Component):
    """A rope runs over a massless elliptic CurvedPulley (bearing friction mu
    0.3, pin radius 10 mm): its left end is pulled down at 0.2 m/s by a
    RopeDrive, its right end carries a 2 kg body on a vertical guide."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.p = CurvedPulley(Contour.from_function(ellipse_drum, symmetry=2), w_i=1,
                              x10=0.0, y10=0.0, mu=MU_CP, r_pin=RPIN_CP, friction=True)
        eps0 = M_CP * 9.81 / 1e6
        self.span1 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.span2 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.pull = RopeDrive(x0=-0.085, y0=-1.0, angle=-math.pi / 2)
        self.sig = signals.TimeFunction(pull_ramp)
        self.connect(self.sig.y, self.pull.s_in)
        self.guide = Fixed(r=(0.085, 0.0))
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0, fixed=True), v=start(0.0, fixed=True))
        self.body = Body(m=M_CP, I=0.01, x=start(0.085), y=start(-1.0))
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        self.connect(self.pull.frame, self.span1.ctr2D1)
        connect_band(self, self.span1, 2, self.p, 1)
        connect_band(self, self.span2, 1, self.p, 2)
        self.connect(self.span2.ctr2D2, self.body.frame_a)


def test_curved_pulley_bearing_friction_torque_balance():
    """Massless elliptic pulley: the moment of the two rope forces about the
    axis (lever arms from the contact points and rope directions) is taken
    by the bearing friction mu r_pin |F_bear|, with F_bear the resultant of
    the rope forces, computed here from the geometry."""
    T = 2.0
    res = acausal2d.simulate(FrictionOverEllipse(), stop_time=T, rtol=1e-9,
                             output_times=np.linspace(0.0, T, 81))
    t = res.time
    quasi = t >= 0.75              # constant pull speed (ramp ends at 0.5 s)
    ends = [(res["pull.frame.x"], res["pull.frame.y"]), (res["body.x"], res["body.y"])]
    mom = fx = fy = 0.0
    for k, (ex, ey) in zip((1, 2), ends):
        Kx, Ky = res["p.ctrK%d.x" % k], res["p.ctrK%d.y" % k]
        dx, dy = ex - Kx, ey - Ky
        n = np.hypot(dx, dy)
        F = res["span%d.F" % k]
        mom = mom + F * (Kx * dy - Ky * dx) / n       # (K - P) x F e, P at the origin
        fx, fy = fx + F * dx / n, fy + F * dy / n
    F_rad = np.hypot(fx, fy)       # massless pulley: the bearing takes the resultant
    w = res["p.w_rel"][quasi]
    # the elliptic pulley turns at 2.0 .. 2.9 rad/s: far above omega_s = 1e-3,
    # so the regularised sign w/sqrt(w^2 + omega_s^2) differs from 1 by
    # 0.5 (omega_s/w)^2 <= 1.3e-7
    assert np.min(w) > 1.9 and np.max(w) - np.min(w) > 0.5
    T_coulomb = MU_CP * RPIN_CP * F_rad[quasi]
    assert np.all(T_coulomb > 0.1)                   # ~7 % of the rope moments F h
    assert np.max(np.abs(res["p.F_bear"][quasi] / F_rad[quasi] - 1.0)) < 1e-9   # obs. 4e-13
    # torque balance (J = 0): moment of the rope forces = Coulomb friction
    # torque opposing the rotation.  Observed 1.25e-7 relative, which is
    # exactly the regularisation at the slowest speed; bound 1e-6.
    assert np.max(np.abs(mom[quasi] / T_coulomb - 1.0)) < 1e-6
    # with the regularised sign the balance is exact up to the Newton
    # tolerance of the algebraic forces: observed 5e-14 N m (T_f) and 6e-11
    # N m (moment), bounds 1e-9 and 1e-8 N m (friction torque ~0.12 N m)
    reg = w / np.sqrt(w ** 2 + 1e-3 ** 2)
    assert np.max(np.abs(res["p.T_f"][quasi] + T_coulomb * reg)) < 1e-9
    assert np.max(np.abs(mom[quasi] - T_coulomb * reg)) < 1e-8
    # friction makes the pulled span carry more than the load span
    assert np.all(res["span1.F"][quasi] > res["span2.F"][quasi])
