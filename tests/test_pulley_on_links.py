"""A pulley placed with the interface of Ebert (2015) (x10, y10, phi10,
frameRef; Anhang A.1, eq. A.1-A.9) on a moving carrier: the crank of a
DAN, the coupler of a four-bar DAN + DDD, the slider of a SAN, and a planar
Body.  The start pose of the carrier's frame follows from the linkage's
closed-form start solution (ch. 4.2.1) or the planar joints; the axis P1
and both tangent points K1, K2 of the belt are checked against their
closed forms along the motion, for both frameRef values."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library.belt import Belt, Pulley, connect_band
from acausal2d.library.belt.contour import Contour
from acausal2d.library.belt.curved import CurvedPulley
from acausal2d.library.linkage import DAN, DDD, SAN
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute

RTOL = 1e-9
R = 0.05                          # pulley radius
OFF = (0.04, 0.03)                # axis P1 in the carrier's frame (x10, y10, relative)
Q1, Q2 = (-0.6, -0.7), (1.1, -0.6)      # belt anchors at K1 and K2
TIMES = np.linspace(0.0, 0.5, 11)

# carriers: start pose (x, y, phi) of the frame as a closed form of t
CRANK = dict(l=0.3, phi0=0.2, om=1.0)
FOURBAR = dict(l_crank=0.1, phi0=0.4, om=2.0, l1=0.35, l2=0.3, B=(0.4, 0.0), K=1.0)
SLIDER = dict(alpha=0.3, v=0.05, s0=0.2, vs=0.2)
LEVER = dict(arm=0.3, phi0=0.2)


def crank_pose(t):
    """DAN crank end P (B.1, B.2) and the crank angle."""
    phi = CRANK["phi0"] + CRANK["om"] * t
    return CRANK["l"] * math.cos(phi), CRANK["l"] * math.sin(phi), phi


def coupler_pose(t):
    """Four-bar: the crank tip A = P1 of the DDD, the joint P as the
    intersection of the circles (A, l1) and (B, l2) on the left of A -> B
    (K = +1), written without the VDI auxiliaries; the coupler frame sits
    at A with the angle of A -> P."""
    f = FOURBAR
    a = f["phi0"] + f["om"] * t
    A = (f["l_crank"] * math.cos(a), f["l_crank"] * math.sin(a))
    d = math.hypot(f["B"][0] - A[0], f["B"][1] - A[1])
    u = ((f["B"][0] - A[0]) / d, (f["B"][1] - A[1]) / d)
    along = (f["l1"] ** 2 - f["l2"] ** 2 + d * d) / (2 * d)
    h = f["K"] * math.sqrt(f["l1"] ** 2 - along ** 2)
    P = (A[0] + along * u[0] - h * u[1], A[1] + along * u[1] + h * u[0])
    return A[0], A[1], math.atan2(P[1] - A[1], P[0] - A[0])


def slider_pose(t):
    """SAN: P = P1 + s e + v n (B.10, B.11, B.16, B.17), angle of the guide."""
    f = SLIDER
    s, c, n = f["s0"] + f["vs"] * t, math.cos(f["alpha"]), math.sin(f["alpha"])
    return s * c - f["v"] * n, s * n + f["v"] * c, f["alpha"]


def axis(pose):
    """P1 = C + R(phi_C) OFF (A.7, A.8)."""
    x, y, phi = pose
    c, s = math.cos(phi), math.sin(phi)
    return x + c * OFF[0] - s * OFF[1], y + s * OFF[0] + c * OFF[1]


def placement(pose0, ref):
    """The same axis by frameRef='relative' (offset in the carrier frame,
    A.1-A.3) or 'global' (its start pose in the world, A.4-A.6)."""
    if ref == "relative":
        return dict(x10=OFF[0], y10=OFF[1])
    P = axis(pose0)
    return dict(x10=P[0], y10=P[1], phi10=pose0[2], frameRef="global")


class OnCarrier(Component):
    """A pulley (r = 0.05 m, J = 1e-3 kg m^2, w_i = +1) on the frame of a
    driven carrier, between two elastic spans to the anchors Q1, Q2."""

    def __init__(self, carrier, ref, mass=None, curved=False, **kw):
        super().__init__(**kw)
        frame, pose0 = getattr(self, "_" + carrier)()
        kw = dict(w_i=1, **(mass or dict(J=1e-3)), **placement(pose0, ref))
        self.pulley = CurvedPulley(Contour.circle(R), **kw) if curved else Pulley(r=R, **kw)
        self.connect(frame, self.pulley.ctr2D1)
        self.a1, self.a2 = Fixed(r=Q1), Fixed(r=Q2)
        self.s1 = Belt(c=1e4, d=10.0, eps=start(1e-3, fixed=True))
        self.s2 = Belt(c=1e4, d=10.0, eps=start(1e-3, fixed=True))
        self.connect(self.a1.frame, self.s1.ctr2D1)
        connect_band(self, self.s1, 2, self.pulley, 1)
        connect_band(self, self.s2, 1, self.pulley, 2)
        self.connect(self.s2.ctr2D2, self.a2.frame)

    def _dan(self):
        self.crank = DAN(lL=CRANK["l"], mL=0.5, JL=0.01)
        self.drive = Preset(kind="speed", om=CRANK["om"], phi0=CRANK["phi0"])
        self.connect(self.drive.flange, self.crank.ctrR2)
        return self.crank.ctr2D2, crank_pose(0.0)

    def _ddd(self):
        f = FOURBAR
        self.crank = DAN(lL=f["l_crank"], mL=0.2, JL=1e-3)
        self.drive = Preset(kind="speed", om=f["om"], phi0=f["phi0"])
        self.dyad = DDD(lL1=f["l1"], lL2=f["l2"], K=f["K"], x20=f["B"][0], y20=f["B"][1],
                        mL1=0.3, JL1=3e-3, mL2=0.3, JL2=3e-3)
        self.connect(self.drive.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        return self.dyad.ctr2D3, coupler_pose(0.0)

    def _san(self):
        f = SLIDER
        self.slider = SAN(phi10=f["alpha"], v=f["v"], mS=0.5, JS=0.01)
        self.drive = Preset(kind="speed", om=f["vs"], phi0=f["s0"], translational=True)
        self.connect(self.drive.flange, self.slider.ctrT2)
        return self.slider.ctr2D2, slider_pose(0.0)

    def _body(self):
        f = LEVER
        self.pivot = Fixed(r=(0.0, 0.0))
        self.joint = Revolute(phi=start(f["phi0"], fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(f["arm"], 0.0))
        self.body = Body(m=1.0, I=0.05)
        self.connect(self.pivot.frame, self.joint.frame_a)
        self.connect(self.joint.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)
        tip = (f["arm"] * math.cos(f["phi0"]), f["arm"] * math.sin(f["phi0"]), f["phi0"])
        return self.body.frame_a, tip


CLOSED = {"dan": crank_pose, "ddd": coupler_pose, "san": slider_pose}


def tangent_point(P, Q, side):
    """Contact of the tangent from Q to the circle (P, R): K = P + R
    (cos, sin)(theta +- alpha) with cos(alpha) = R / |Q - P|, the one for
    which (K - P) x (Q - K) has the sign ``side`` (w_i = +1 pays out at K1:
    +1; winds up at K2: -1)."""
    d = math.hypot(Q[0] - P[0], Q[1] - P[1])
    theta, alpha = math.atan2(Q[1] - P[1], Q[0] - P[0]), math.acos(R / d)
    for a in (theta + alpha, theta - alpha):
        K = (P[0] + R * math.cos(a), P[1] + R * math.sin(a))
        if side * ((K[0] - P[0]) * (Q[1] - K[1]) - (K[1] - P[1]) * (Q[0] - K[0])) > 0:
            return K
    raise AssertionError("no tangent")


def carrier_poses(carrier, res):
    """Closed-form carrier poses at the output times; the lever body's
    pose is the run's own (its swing has no closed form)."""
    if carrier == "body":
        return list(zip(res["body.x"], res["body.y"], res["body.phi"]))
    return [CLOSED[carrier](t) for t in res["time"]]


CASES = [(c, r, False) for c in ("dan", "ddd", "san", "body") for r in ("relative", "global")]
CASES += [("ddd", r, True) for r in ("relative", "global")]      # a curved pulley (a circle)


@pytest.mark.parametrize("carrier, ref, curved", CASES)
def test_pulley_on_a_moving_carrier_follows_the_closed_form(carrier, ref, curved):
    """P1 from A.7/A.8 on the carrier's closed-form pose and K1, K2 from
    the tangent construction agree with the run: at t0 (Newton on the
    position rows, bound 1e-9 m) and along the motion (position rows of an
    IDA run at rtol 1e-9, bound 1e3 rtol of the 1 m scale).  The curved
    pulley with a circular contour on the coupler: the same closed form."""
    res = acausal2d.simulate(OnCarrier(carrier, ref, curved=curved), stop_time=TIMES[-1],
                             rtol=RTOL, output_times=TIMES)
    for i, pose in enumerate(carrier_poses(carrier, res)):
        P = axis(pose)
        bound = 1e-9 if i == 0 else 1e3 * RTOL
        assert abs(res["pulley.xP1"][i] - P[0]) < bound, (i, "xP1")
        assert abs(res["pulley.yP1"][i] - P[1]) < bound, (i, "yP1")
        for k, Q, side in ((1, Q1, 1), (2, Q2, -1)):
            K = tangent_point(P, Q, side)
            assert abs(res["pulley.ctrK%d.x" % k][i] - K[0]) < bound, (i, k)
            assert abs(res["pulley.ctrK%d.y" % k][i] - K[1]) < bound, (i, k)
    # the carrier moves: the axis travels more than a radius
    assert math.hypot(np.ptp(res["pulley.xP1"]), np.ptp(res["pulley.yP1"])) > R


# ------------------------------------------------ P_T, P_R (Anhang A.30, A.31)
A_POLY = (0.1, 0.8, 1.5)          # pulley angle a0 + a1 t + a2 t^2 (rad), prescribed


class DrivenOnCoupler(OnCarrier):
    """:class:`OnCarrier` on the four-bar's coupler with a pulley of mass
    0.4 kg and J = 2e-3 kg m^2 whose absolute angle is prescribed."""

    def __init__(self, **kw):
        super().__init__("ddd", "relative", mass=dict(m=0.4, J=2e-3), **kw)
        self.turn = Preset(kind="polynomial", a=A_POLY + (0.0, 0.0, 0.0))
        self.connect(self.turn.flange, self.pulley.ctrR2)


def test_wheel_inertia_powers_against_the_closed_form():
    """P_T = m a.v of the axis (the centre of gravity, cog = 0) and P_R =
    J phi'' phi' of a massive pulley on the moving coupler: the axis'
    velocity and acceleration by central differences of the closed-form
    four-bar (step 1e-4 s: error ~1e-8 of the values) and the prescribed
    angle's derivatives in closed form.  Bound: 1e-6 of the power scale
    m |a| |v| + J |phi''| |phi'| (differences and rtol 1e-9 with room)."""
    model = DrivenOnCoupler()
    res = acausal2d.simulate(model, stop_time=TIMES[-1], rtol=RTOL, output_times=TIMES)
    h, m, J = 1e-4, 0.4, 2e-3
    for i, t in enumerate(res["time"]):
        p = [np.array(axis(coupler_pose(t + k * h))) for k in (-1, 0, 1)]
        v, a = (p[2] - p[0]) / (2 * h), (p[2] - 2 * p[1] + p[0]) / h ** 2
        w, z = A_POLY[1] + 2 * A_POLY[2] * t, 2 * A_POLY[2]
        scale = m * np.linalg.norm(a) * np.linalg.norm(v) + J * abs(z * w)
        assert abs(res["pulley.P_T"][i] - m * a.dot(v)) < 1e-6 * scale, (i, "P_T")
        assert abs(res["pulley.P_R"][i] - J * z * w) < 1e-6 * scale, (i, "P_R")
    assert np.ptp(res["pulley.P_T"]) > 0.1 * np.max(np.abs(res["pulley.P_T"]))   # not constant


def test_phidot_is_the_speed_in_the_world_frame():
    """phidot_0 of Tabelle 4.15 is given in GKS: ``phidot=start(5,
    fixed=True)`` on the pulley of the DAN crank (turning at 1 rad/s) starts
    it at 5 rad/s in the world, 4 rad/s against its housing; phidot - w_rel
    is the housing's speed over the whole run (rows' tolerance)."""
    res = acausal2d.simulate(OnCarrier("dan", "relative",
                                       mass=dict(J=1e-3, phidot=start(5.0, fixed=True))),
                             stop_time=TIMES[-1], rtol=RTOL, output_times=TIMES)
    assert abs(res["pulley.phidot"][0] - 5.0) < 1e3 * RTOL
    assert abs(res["pulley.w_rel"][0] - (5.0 - CRANK["om"])) < 1e3 * RTOL
    assert np.max(np.abs(res["pulley.phidot"] - res["pulley.w_rel"] - CRANK["om"])) < 1e3 * RTOL
