"""The three mechanisms of Ebert (2015), Bild 2.1 (ch. 2.2, eq. 2.1): momentarily the
same transfer from rocker 2 (pivot A0) to rocker 6 (pivot B0).

==========  ==============================================  ===================
model       structure                                       eq. 2.1
==========  ==============================================  ===================
Bild21a     six-link linkage, 7 revolute joints: couplers   3(6-1) - 7(3-1) = 1
            3 and 5 and link 4 turning about C0
Bild21b     the couplers replaced by a band (sections 3,    3(5-1) - [4(3-1) +
            4) sliding over a contour fixed at C0            2(3-2) + 1] = 1
Bild21c     the contour replaced by a pulley turning about  3(6-1) - [5(3-1) +
            C0 (the band slips: an identical freedom)       2(3-2) + 1] = 2
==========  ==============================================  ===================

``acausal2d check models/dof_bild_2_1.py --model Bild21b`` prints these
counts.  Rocker 2 is driven (0.4 rad in 1 s); rocker 6 is loaded by a
torque that keeps the band taut.  In (b) and (c) the band length
``|A K1| + r beta + |K2 B|`` is constant (the test checks it against the
tangent construction), and (c) moves rocker 6 exactly as (b): the pulley's
turn does not change the transfer.  Lengths in metres.
"""
import math

from acausal2d import Component, start
from acausal2d.library.belt import Band, GuideContour, connect_band, tangent
from acausal2d.library.linkage import DAN, DDD, FGP
from acausal2d.library.linkage.drives import Preset, TorqueSource
from acausal2d.library.planar import Body, Revolute

A0, C0, B0 = (0.0, 0.0), (0.3, 0.4), (0.62, 0.03)
R_ROCKER, R_ROCKER6, R_CONTOUR = 0.15, 0.12, 0.08
PHI2, PHI6 = 0.3, math.pi - 0.3         # start angles of rockers 2 and 6


def rocker_tip(pivot, phi, length=R_ROCKER):
    """Tip of a rocker of ``length`` at ``pivot`` turned to ``phi``."""
    return (pivot[0] + length * math.cos(phi), pivot[1] + length * math.sin(phi))


def contact_angle(tip, side):
    """Angle (at C0) of the point where the tangent from ``tip`` touches the
    contour: side -1 the touch point clockwise of the line C0 -> tip, +1
    counter-clockwise."""
    dx, dy = tip[0] - C0[0], tip[1] - C0[1]
    return math.atan2(dy, dx) + side * math.acos(R_CONTOUR / math.hypot(dx, dy))


def band_start(a, b):
    """Start values of a band section from the tangent construction (the
    layout does not know the rocker tips of the linkage elements)."""
    gam, length = tangent(a, b)
    return {"gamma": start(gam), "l": start(length), "l_x": start(length),
            "l_x0": start(length)}


class _Rockers(Component):
    """Rocker 2 at A0 driven by a preset, rocker 6 at B0 (free, loaded)."""
    experiment = {"stop_time": 1.0, "intervals": 100, "rtol": 1e-8}
    outputs = ["rocker2.phiL", "rocker6.phiL"]
    figures = [{"name": "transfer", "signals": ["rocker6.phiL"], "x": "rocker2.phiL",
                "title": "rocker 6 over rocker 2 (Bild 2.1)"}]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.preset = Preset(kind="polynomial", a=(PHI2, 0.4, 0.0, 0.0, 0.0, 0.0))
        self.rocker2 = DAN(lL=R_ROCKER, x10=A0[0], y10=A0[1], mL=0.2, JL=1e-3)
        self.connect(self.preset.flange, self.rocker2.ctrR2)


class Bild21a(_Rockers):
    """Bild 2.1 a: six links, seven revolute joints (F = 1).  Link 4 turns
    about C0; its pins C and D lie where the band of (b) touches the contour
    at the start, so that (a) and (b) have the same ratio there."""

    def __init__(self, **kw):
        super().__init__(**kw)
        a, b = rocker_tip(A0, PHI2), rocker_tip(B0, PHI6, R_ROCKER6)
        th_c, th_d = contact_angle(a, -1), contact_angle(b, +1)
        c = (C0[0] + R_CONTOUR * math.cos(th_c), C0[1] + R_CONTOUR * math.sin(th_c))
        d = (C0[0] + R_CONTOUR * math.cos(th_d), C0[1] + R_CONTOUR * math.sin(th_d))
        self.dyad1 = DDD(lL1=math.dist(a, c), lL2=R_CONTOUR, x20=C0[0], y20=C0[1], K=1,
                         mL1=0.1, JL1=1e-3, mL2=0.1, JL2=1e-4)
        self.arm = FGP(lL=R_CONTOUR, phi10=th_d - th_c, mL=0.1, JL=1e-4)
        self.dyad2 = DDD(lL1=math.dist(d, b), lL2=R_ROCKER6, x20=B0[0], y20=B0[1], K=-1,
                         mL1=0.1, JL1=1e-3, mL2=0.2, JL2=1e-3)
        self.connect(self.rocker2.ctr2D2, self.dyad1.ctr2D1)
        self.connect(self.dyad1.ctr2D4, self.arm.ctr2D1)
        self.connect(self.arm.ctr2D2, self.dyad2.ctr2D1)
    outputs = ["rocker2.phiL", "dyad2.phiL2"]
    figures = [{"name": "transfer", "signals": ["dyad2.phiL2"], "x": "rocker2.phiL",
                "title": "rocker 6 over rocker 2 (Bild 2.1 a)"}]


class _Banded(_Rockers):
    """Rocker 6 and the two band sections over the contour at C0."""

    def _band(self, contour):
        self.rocker6 = DAN(lL=R_ROCKER6, x10=B0[0], y10=B0[1], mL=0.2, JL=1e-3,
                           phiL0=PHI6, phiL=start(PHI6, fixed=True))
        self.load = TorqueSource(tau=1.0)
        self.connect(self.load.flange, self.rocker6.ctrR2)
        tip2, tip6 = rocker_tip(A0, PHI2), rocker_tip(B0, PHI6, R_ROCKER6)
        # contour on the right of band 3 (rho = w r) and of band 4 (-w r), w = -1
        self.band3 = Band(**band_start((*tip2, 0.0), (*C0, -R_CONTOUR)))
        self.band4 = Band(**band_start((*C0, R_CONTOUR), (*tip6, 0.0)))
        self.contour = contour
        self.connect(self.rocker2.ctr2D2, self.band3.ctr2D1)
        connect_band(self, self.band3, 2, contour, 1)
        connect_band(self, self.band4, 1, contour, 2)
        self.connect(self.band4.ctr2D2, self.rocker6.ctr2D2)


class Bild21b(_Banded):
    """Bild 2.1 b: the band slides over a circular contour fixed at C0
    (five links: ground, rockers 2 and 6, band sections 3 and 4; F = 1)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self._band(GuideContour(w_i=1, r=R_CONTOUR, x10=C0[0], y10=C0[1],
                                phi=start(0.0, fixed=True)))


class Bild21c(_Banded):
    """Bild 2.1 c: the contour is a pulley turning about C0 (a revolute
    joint); the band slips over it without friction, so the pulley keeps
    its own speed (an identical freedom: six links, F = 2)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.bearing = Revolute(phi=start(0.0, fixed=True), w=start(1.0, fixed=True))
        self.wheel = Body(m=0.5, I=2e-3)
        from acausal2d.library.planar import Fixed
        self.ground = Fixed(r=C0)
        self.connect(self.ground.frame, self.bearing.frame_a)
        self.connect(self.bearing.frame_b, self.wheel.frame_a)
        contour = GuideContour(w_i=1, r=R_CONTOUR,      # axis on the bearing, at C0
                               phi=start(0.0, fixed=True))
        self._band(contour)
        self.connect(self.bearing.frame_b, contour.ctr2D1)
    outputs = ["rocker2.phiL", "rocker6.phiL", "bearing.w"]


MODELS = [Bild21a, Bild21b, Bild21c]
