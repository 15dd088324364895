"""Issue 32: the pulley "Bandrolle" with the seed's interface (Tabelle
4.14-4.17, eq. 4.87-4.99): axis placement by offset (x10, y10, phi10,
frameRef; Anhang A.1, eq. A.1-A.18), the flanges ctrR1/ctrR2, the
half-planes enumHE1/enumHE2 (Tabelle 4.16), the winding direction w_i of
eq. 4.95/4.96, the start geometry taken from the body the pulley sits on,
and the errors naming a missing or contradictory placement.  The fuzz
classes are in fuzz_cases_pulley.py."""
import math
import re
import warnings

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError, start
from acausal2d.library import rotational
from acausal2d.library.belt import Band, Belt, Pulley, connect_band
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute

G = 9.81
RTOL = 1e-9
ARM, R, PHI0 = 0.3, 0.05, 0.2        # lever length, pulley radius, lever start angle


class LeverPulley(Component):
    """A lever (1 kg at its pivot frame, I = 0.05 kg m^2) pivoted at the
    origin, starting at PHI0, carries a pulley (r = 0.05 m, J = 1e-3 kg m^2)
    at its tip; a band runs from an anchor below the left side of the
    pulley, over it, down to a 2 kg mass below its right side.

    ``style``: 'seed' -- the SimulationX transcription, the pulley on the
    lever's frame with the offset x10 = ARM (frameRef='relative', A.1-A.3),
    w_i = +1 and the half-planes; 'global' -- the same with the axis' world
    start pose (frameRef='global', A.4-A.6); 'legacy' -- today's model: a
    rigid rod to the tip and the pulley with x0, y0, w = -1."""

    def __init__(self, style="seed", spring=False, **kw):
        super().__init__(**kw)
        tip = (ARM * math.cos(PHI0), ARM * math.sin(PHI0))
        self.pivot = Fixed(r=(0.0, 0.0))
        self.lever = Revolute(phi=start(PHI0, fixed=True), w=start(0.0, fixed=True))
        self.mass = Body(m=1.0, I=0.05)
        self.connect(self.pivot.frame, self.lever.frame_a)
        self.connect(self.lever.frame_b, self.mass.frame_a)
        common = dict(r=R, J=0.0 if spring else 1e-3)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            if style == "legacy":
                self.rod = FixedTranslation(r=(ARM, 0.0))
                self.connect(self.lever.frame_b, self.rod.frame_a)
                self.pulley = Pulley(x0=tip[0], y0=tip[1], w=-1, **common)
                self.connect(self.rod.frame_b, self.pulley.ctr2D1)
            else:
                place = (dict(x10=ARM, y10=0.0) if style == "seed"
                         else dict(x10=tip[0], y10=tip[1], phi10=PHI0, frameRef="global"))
                self.pulley = Pulley(w_i=1, enumHE1="left", enumHE2="right", **place, **common)
                self.connect(self.lever.frame_b, self.pulley.ctr2D1)
        self.anchor = Fixed(r=(tip[0] - R, tip[1] - 1.0))
        self.load = Body(m=2.0, I=0.01, x=start(tip[0] + R), y=start(tip[1] - 1.0))
        self.band1, self.band2 = Band(), Band()
        self.connect(self.anchor.frame, self.band1.ctr2D1)
        connect_band(self, self.band1, 2, self.pulley, 1)
        connect_band(self, self.band2, 1, self.pulley, 2)
        self.connect(self.band2.ctr2D2, self.load.frame_a)
        if spring:      # a torsion spring-damper between housing and pulley
            self.brake = rotational.SpringDamper(c=50.0, d=2.0)
            self.connect(self.pulley.ctrR1, self.brake.flange_a)
            self.connect(self.pulley.ctrR2, self.brake.flange_b)


def _run(model, stop=0.4):
    return acausal2d.simulate(model, stop_time=stop, rtol=RTOL,
                              output_times=np.linspace(0.0, stop, 21))


@pytest.fixture(scope="module")
def legacy_run():
    return _run(LeverPulley("legacy"))


@pytest.mark.parametrize("style", ["seed", "global"])
def test_transcribed_pulley_moves_as_todays_model(style, legacy_run):
    """The seed-named model (offset placement on the lever, w_i, enumHE)
    and today's (rod + x0, y0, w) are the same system: lever angle and
    load position agree to the integration error (rtol 1e-9; bound 1e-6
    of the motion's scale, 1000 rtol, for the global error of two runs
    with different variables)."""
    res = _run(LeverPulley(style))
    for name in ("lever.phi", "load.x", "load.y", "pulley.phi"):
        scale = max(1.0, float(np.max(np.abs(legacy_run[name]))))
        assert np.max(np.abs(res[name] - legacy_run[name])) < 1e3 * RTOL * scale, name
    # the lever swings: the comparison is not between two resting systems
    assert np.ptp(legacy_run["lever.phi"]) > 0.05


@pytest.mark.parametrize("style", ["seed", "global"])
def test_axis_follows_the_lever_by_A7_A8(style):
    """P1 = C + R(phi_C) (x_rel, y_rel) with C the pivot (A.7, A.8); the
    global start pose gives the same offset (ARM, 0) by A.4-A.6.  Position
    equations hold to the rows' tolerance (bound 1e3 rtol of ARM)."""
    res = _run(LeverPulley(style))
    phi = res["lever.phi"]
    assert np.max(np.abs(res["pulley.xP1"] - ARM * np.cos(phi))) < 1e3 * RTOL * ARM
    assert np.max(np.abs(res["pulley.yP1"] - ARM * np.sin(phi))) < 1e3 * RTOL * ARM
    # the housing turns with the lever (A.9): the pulley's relative angle
    assert np.max(np.abs(res["pulley.ctrR1.phi"] - phi)) < 1e3 * RTOL


def test_ctrR1_reaction_is_minus_the_torque_on_the_pulley():
    """A torsion spring-damper between housing (ctrR1) and a massless
    pulley (ctrR2): the housing receives minus the torque on the pulley,
    and the balance of housing and pulley about the connection point C
    (4.99 with A.16-A.18: C.t + sum (K - C) x F_K + T_R1 + T_R2 = 0) holds
    at every output time to the rows' tolerance (1e-6 of the band-moment
    scale r m g)."""
    res = _run(LeverPulley("seed", spring=True))
    scale = R * 2.0 * G
    t1, t2 = res["pulley.ctrR1.tau"], res["pulley.ctrR2.tau"]
    assert np.max(np.abs(t1 + t2)) < 1e-6 * scale
    assert np.max(np.abs(t2)) > 0.1 * scale            # the spring carries torque
    xC, yC = res["lever.frame_b.x"], res["lever.frame_b.y"]
    mom = res["pulley.ctr2D1.t"] + t1 + t2
    for k in (1, 2):
        mom = mom + ((res["pulley.ctrK%d.x" % k] - xC) * res["pulley.ctrK%d.fy" % k]
                     - (res["pulley.ctrK%d.y" % k] - yC) * res["pulley.ctrK%d.fx" % k])
    assert np.max(np.abs(mom)) < 1e-6 * scale


# ------------------------------------------------ enumHE against the closed form
def _tangent_point(P, r, Q, side):
    """Contact of the tangent from Q to the circle (P, r) (spec 1.8):
    K = P + r (cos, sin)(theta +- alpha), the one for which (K - P) x (Q - K)
    has the sign ``side``."""
    d = math.hypot(Q[0] - P[0], Q[1] - P[1])
    theta, alpha = math.atan2(Q[1] - P[1], Q[0] - P[0]), math.acos(r / d)
    for a in (theta + alpha, theta - alpha):
        K = (P[0] + r * math.cos(a), P[1] + r * math.sin(a))
        if side * ((K[0] - P[0]) * (Q[1] - K[1]) - (K[1] - P[1]) * (Q[0] - K[0])) > 0:
            return K, a
    raise AssertionError("no tangent")


def _plane(a):
    c, s = math.cos(a), math.sin(a)
    return ("right" if c > 0 else "left") if abs(c) > abs(s) else ("upper" if s > 0 else "lower")


class TwoAnchors(Component):
    """Pulley at P1 = (0.2, 0.1), r = 0.1 m, between two elastic spans to
    the fixed points Q1 (at K1) and Q2 (at K2), pretensioned equally."""

    def __init__(self, Q1, Q2, w_i, he1=None, he2=None, **kw):
        super().__init__(**kw)
        self.pulley = Pulley(r=0.1, x10=0.2, y10=0.1, w_i=w_i, enumHE1=he1, enumHE2=he2, J=1e-3)
        self.a1, self.a2 = Fixed(r=Q1), Fixed(r=Q2)
        self.s1 = Belt(c=1e4, d=10.0, eps=start(1e-3, fixed=True))
        self.s2 = Belt(c=1e4, d=10.0, eps=start(1e-3, fixed=True))
        self.connect(self.a1.frame, self.s1.ctr2D1)
        connect_band(self, self.s1, 2, self.pulley, 1)
        connect_band(self, self.s2, 1, self.pulley, 2)
        self.connect(self.s2.ctr2D2, self.a2.frame)


CASES = [((-0.5, -0.8), (0.9, -0.7), 1), ((-0.5, 0.9), (0.9, 0.8), -1),
         ((-0.6, 0.2), (0.3, -0.9), 1), ((1.0, 0.0), (0.1, 1.0), 1),
         ((0.2, -1.0), (-0.9, 0.1), -1), ((0.25, 1.2), (1.1, 0.05), -1)]


@pytest.mark.parametrize("Q1, Q2, w_i", CASES)
def test_enumHE_variant_matches_the_closed_form_tangents(Q1, Q2, w_i):
    """For each case the contacts from the closed form (w_i = +1 pays out
    at K1: (K1 - P1) x (Q1 - K1) has the sign of w_i, and winds up at K2:
    sign -w_i) name the half-planes; the pulley with those enumHE starts
    at exactly these contacts (the position rows hold to 1e-9 m), and with
    the opposite half-plane for K1 compilation stops naming enumHE1."""
    P = (0.2, 0.1)
    K1, a1 = _tangent_point(P, 0.1, Q1, w_i)
    K2, a2 = _tangent_point(P, 0.1, Q2, -w_i)
    he1, he2 = _plane(a1), _plane(a2)
    res = acausal2d.simulate(TwoAnchors(Q1, Q2, w_i, he1, he2), stop_time=1e-3, rtol=RTOL)
    for k, K in ((1, K1), (2, K2)):
        assert abs(res["pulley.ctrK%d.x" % k][0] - K[0]) < 1e-9
        assert abs(res["pulley.ctrK%d.y" % k][0] - K[1]) < 1e-9
    other = {"upper": "lower", "lower": "upper", "left": "right", "right": "left"}[he1]
    with pytest.raises(ModelDefinitionError,
                       match=re.escape("enumHE1=%r, but with w_i=%+d" % (other, w_i))):
        acausal2d.check(TwoAnchors(Q1, Q2, w_i, other, he2))


# ------------------------------------------------ start geometry from the body
class LoosePulley(Component):
    """A loose pulley ("lose Rolle", ch. 2.5.1): a 2 kg body carries a
    massless pulley (r = 0.1 m) at the offset (0, 0.05) in its frame; the
    rope runs from the anchor (-0.1, 0) down around the pulley's bottom and
    up to the anchor (0.1, 0).  No x0/y0: the start geometry comes from the
    body's start values (its angle fixed: with the body's height held, a
    free angle would start on the double root cos(phi) = 1 of A.8)."""

    def __init__(self, body_start=True, **kw):
        super().__init__(**kw)
        st = dict(x=start(0.0), y=start(-1.05), phi=start(0.0, fixed=True)) if body_start else {}
        self.body = Body(m=2.0, I=0.02, **st)
        self.pulley = Pulley(r=0.1, x10=0.0, y10=0.05, w_i=-1, J=1e-4)
        self.connect(self.body.frame_a, self.pulley.ctr2D1)
        self.left, self.right = Fixed(r=(-0.1, 0.0)), Fixed(r=(0.1, 0.0))
        self.s1 = Belt(c=1e5, d=50.0, eps=start(G / 1e5, fixed=True))
        self.s2 = Belt(c=1e5, d=50.0, eps=start(G / 1e5, fixed=True))
        self.connect(self.left.frame, self.s1.ctr2D1)
        connect_band(self, self.s1, 2, self.pulley, 1)
        connect_band(self, self.s2, 1, self.pulley, 2)
        self.connect(self.s2.ctr2D2, self.right.frame)


def test_pulley_on_a_body_takes_its_start_geometry_from_the_body():
    """Each rope section carries half the load, m g / 2 (ch. 2.5.1), and
    the sections hang vertically: the start is the static equilibrium, so
    it stays there (bounds: 1e-6 of m g and 1e-9 m, far above rtol 1e-9)."""
    res = acausal2d.simulate(LoosePulley(), stop_time=0.2, rtol=RTOL)
    for s in ("s1", "s2"):
        assert np.max(np.abs(res[s + ".F"] - G)) < 1e-6 * 2 * G
    assert abs(res["pulley.ctrK1.x"][0] + 0.1) < 1e-9
    assert abs(res["pulley.yP1"][0] + 1.0) < 1e-9


# ------------------------------------------------ errors naming the placement
def test_unknown_start_position_is_named():
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.check(LoosePulley(body_start=False))
    text = str(err.value)
    assert text.startswith("Pulley 'pulley': the start position of its axis P1 is not known")
    assert "Body(x=start(...)" in text and "overlap" not in text


class Contradiction(LoosePulley):
    def __init__(self, **kw):
        Component.__init__(self, **kw)
        self.body = Body(m=2.0, I=0.02, x=start(0.0), y=start(-1.05), phi=start(0.0))
        with pytest.warns(DeprecationWarning, match="write x10=0.2, y10=-1.0, frameRef='global'"):
            self.pulley = Pulley(r=0.1, x0=0.2, y0=-1.0, w=1, J=1e-4)
        self.connect(self.body.frame_a, self.pulley.ctr2D1)
        self.left, self.right = Fixed(r=(-0.1, 0.0)), Fixed(r=(0.1, 0.0))
        self.s1, self.s2 = Belt(c=1e5), Belt(c=1e5)
        self.connect(self.left.frame, self.s1.ctr2D1)
        connect_band(self, self.s1, 2, self.pulley, 1)
        connect_band(self, self.s2, 1, self.pulley, 2)
        self.connect(self.s2.ctr2D2, self.right.frame)


def test_contradictory_legacy_placement_is_named():
    with pytest.raises(ModelDefinitionError, match=r"Pulley 'pulley': contradictory placement: "
                       r"x0=0.2, y0=-1 \(deprecated\).*starts at \(0, -1.05\) m"):
        acausal2d.check(Contradiction())


@pytest.mark.parametrize("kw, match", [
    (dict(frameRef="world"), "frameRef must be 'relative'"),
    (dict(enumHE1="top"), "enumHE1 must be one of 'upper'"),
    (dict(w=1, w_i=-1), "as w_i .* or \\(deprecated\\) as w = -w_i, not both"),
    (dict(w_i=0), "w_i must be \\+1 or -1, got 0"),
    (dict(x0=0.1, x10=0.1), "either as x10 or \\(deprecated\\) as x0, not both"),
    (dict(x0=0.1, frameRef="relative"), "x0, y0, phi0 are always global"),
])
def test_bad_arguments_are_named(kw, match):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ModelDefinitionError, match="Pulley: .*" + match):
            Pulley(r=0.1, **kw)


def test_deprecated_w_and_ctrR_say_what_to_write():
    with pytest.warns(DeprecationWarning, match=r"Pulley\(w=1\): w is deprecated; write w_i=-1"):
        p = Pulley(r=0.1, w=1)
    assert p.w_i == -1
