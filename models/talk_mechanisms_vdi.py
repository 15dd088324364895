"""Schnabel and Gössner's needle-bar drive and deep-drawing press built from the VDI
2729 elements of the dissertation (DAN, DDD, FGP, DDS; library/linkage.py), with
the same coordinates as the node models in talk_mechanisms.py, so that both
descriptions of one mechanism can be compared (they agree on every point
to solver accuracy over a crank turn; tests/test_talk_mechanisms.py).

Decompositions (sequential VDI order):

* Needle-bar drive (Schnabel and Gössner's example 9): DAN (crank A0A) +
  DDD (A, B0 -> B) + FGP (C on the coupler AB) + DDD (C, D0 -> D) + FGP
  (E on the rocker D0D) + DDS (E -> F on the vertical guide through F0) +
  FGP (the needle point G on the needle bar).
* Deep-drawing press (example 10): DAN (crank A0A) + DDD (A, B0 -> B) +
  FGP (C on the rocker B0B) + DDD (C, D0 -> D) + FGP (E) and FGP (I) on
  the rocker D0D + DDD (I, A -> J) + FGP (J at the end of the link IJ,
  the dyad's joint as a frame) + DDS (J -> K on the vertical guide
  through K0) + DDD (E, A0 -> F) + FGP (G on the link A0F) + DDS (G -> H on
  the vertical guide through H0): 13 moving links, 14 with the ground.

Each FGP sits on the plane of the link it belongs to, at that link's pivot
(x10 = y10 = 0) turned by the angle between the link and the point
(phi10); each dyad's assembly parameter K is the side the coordinates put
its joint on.  The crank turns at 1 turn/s from the angle of the given
crank pin; no gravity (Schnabel and Gössner's Q = 0)."""
import math

from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD, DDS, FGP
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import PlanarWorld

from talk_mechanisms import NEEDLE_BAR, PRESS_BASE, PRESS_MOVING, TURN

MM = 1e-3


def _angle(p, q):
    return math.atan2(q[1] - p[1], q[0] - p[0])


def _dist(p, q):
    return math.hypot(q[0] - p[0], q[1] - p[1]) * MM


def _side(p1, p2, p):
    """DDD's K: +1 if p lies left of the line p1 -> p2."""
    cross = (p2[0] - p1[0]) * (p[1] - p1[1]) - (p2[1] - p1[1]) * (p[0] - p1[0])
    return 1.0 if cross > 0 else -1.0


def _along(p1, p2, phi, p):
    """DDS's K: +1 if p lies beyond the foot of p1 on the guide through p2
    in the guide's direction phi."""
    e = (math.cos(phi), math.sin(phi))
    foot = (p1[0] - p2[0]) * e[0] + (p1[1] - p2[1]) * e[1]
    return 1.0 if (p[0] - p2[0]) * e[0] + (p[1] - p2[1]) * e[1] > foot else -1.0


class _VDI(Component):
    """Coordinates in mm; helpers that place the elements."""
    experiment = {"stop_time": 1.0, "intervals": 360, "rtol": 1e-8}

    def __init__(self, points, **kw):
        super().__init__(**kw)
        self.pts = points
        self.world = PlanarWorld(g=(0.0, 0.0))

    def crank(self, name, pivot, pin):
        """DAN from ``pivot`` to ``pin``, turned at 1 turn/s by a preset."""
        P0, P = self.pts[pivot], self.pts[pin]
        dan = DAN(x10=P0[0] * MM, y10=P0[1] * MM, lL=_dist(P0, P), phiL0=_angle(P0, P))
        setattr(self, name, dan)
        self.preset = Preset(kind="speed", om=TURN, phi0=_angle(P0, P))
        self.connect(self.preset.flange, dan.ctrR2)
        return dan

    def dyad(self, name, p1, p2, p, port1=None, port2=None):
        """DDD with its housings at p1 (on ``port1``) and p2 (on ``port2``,
        or fixed there) and its joint at p (K from the side of p)."""
        P1, P2, P = self.pts[p1], self.pts[p2], self.pts[p]
        kw = {}
        if port2 is None:
            kw.update(x20=P2[0] * MM, y20=P2[1] * MM)
        ddd = DDD(lL1=_dist(P1, P), lL2=_dist(P2, P), K=_side(P1, P2, P), **kw)
        setattr(self, name, ddd)
        self.connect(port1, ddd.ctr2D1)
        if port2 is not None:
            self.connect(port2, ddd.ctr2D2)
        return ddd

    def point(self, name, plane, pivot, towards, p):
        """FGP for point p on the link pivot -> towards, mounted on ``plane``
        (that link's frame at its pivot)."""
        P0, T, P = self.pts[pivot], self.pts[towards], self.pts[p]
        fgp = FGP(lL=_dist(P0, P), phi10=_angle(P0, P) - _angle(P0, T))
        setattr(self, name, fgp)
        self.connect(plane, fgp.ctr2D1)
        return fgp

    def slider(self, name, port1, p1, guide, p, phi):
        """DDS from p1 (on ``port1``) to the slider p on the guide through
        ``guide`` with direction phi."""
        P1, P2, P = self.pts[p1], self.pts[guide], self.pts[p]
        dds = DDS(lL=_dist(P1, P), v=0.0, x20=P2[0] * MM, y20=P2[1] * MM, phi20=phi,
                  K=_along(P1, P2, phi, P))
        setattr(self, name, dds)
        self.connect(port1, dds.ctr2D1)
        return dds


class NeedleBarDriveVDI(_VDI):
    """The needle-bar drive of Schnabel and Gössner's talk (NeedleBarDrive in
    talk_mechanisms.py) from VDI 2729 elements (module doc).  Points:
    A = crank.ctr2D2, B = ab.xP/yP, C = c.ctr2D2, D = cd.xP/yP, E =
    e.ctr2D2, F = ef.xP/yP, G = g.ctr2D2."""
    outputs = ["ef.xP", "ef.yP"]

    def __init__(self, **kw):
        super().__init__({k: v[:2] for k, v in NEEDLE_BAR.items()}, **kw)
        crank = self.crank("crank", "A0", "A")
        ab = self.dyad("ab", "A", "B0", "B", port1=crank.ctr2D2)
        c = self.point("c", ab.ctr2D3, "A", "B", "C")
        cd = self.dyad("cd", "C", "D0", "D", port1=c.ctr2D2)
        e = self.point("e", cd.ctr2D4, "D0", "D", "E")
        ef = self.slider("ef", e.ctr2D2, "E", "F0", "F", math.pi / 2)
        g = FGP(lL=_dist(self.pts["F"], self.pts["G"]),
                phi10=_angle(self.pts["F"], self.pts["G"]) - math.pi / 2)
        self.g = g
        self.connect(ef.ctr2D4, g.ctr2D1)


class DeepDrawingPressVDI(_VDI):
    """The 14-link deep-drawing press of Schnabel and Gössner's talk (DeepDrawingPress in
    talk_mechanisms.py) from VDI 2729 elements (module doc).  Rams:
    H = gh.xP/yP, K = jk.xP/yP."""
    outputs = ["gh.yP", "jk.yP"]

    def __init__(self, **kw):
        pts = dict(PRESS_BASE, **{k: v[:2] for k, v in PRESS_MOVING.items()})
        super().__init__(pts, **kw)
        crank = self.crank("crank", "A0", "A")
        ab = self.dyad("ab", "A", "B0", "B", port1=crank.ctr2D2)
        c = self.point("c", ab.ctr2D4, "B0", "B", "C")
        cd = self.dyad("cd", "C", "D0", "D", port1=c.ctr2D2)
        e = self.point("e", cd.ctr2D4, "D0", "D", "E")
        i = self.point("i", cd.ctr2D4, "D0", "D", "I")
        ij = self.dyad("ij", "I", "A", "J", port1=i.ctr2D2, port2=crank.ctr2D2)
        j = self.point("j", ij.ctr2D3, "I", "J", "J")
        self.slider("jk", j.ctr2D2, "J", "K0", "K", -math.pi / 2)
        ef = self.dyad("ef", "E", "A0", "F", port1=e.ctr2D2)
        g = self.point("g", ef.ctr2D4, "A0", "F", "G")
        self.slider("gh", g.ctr2D2, "G", "H0", "H", -math.pi / 2)
