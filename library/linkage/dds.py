"""Dyad with a prismatic joint as outer joint DDS (Ebert 2015, Anhang B.5, Tabellen
B.13-B.15, eqs. B.71-B.118)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .base import (_Linkage, _moment, MassData, element, guide_balance, housing, link_balance,
                   off_point, port_moment,
                   plug, translational, triangle)

__all__ = ["DDS", "vdi_dds"]


def vdi_dds(x1, y1, x2, y2, phiU, l, v, K, sqrt=ca.sqrt):
    """VDI 2729 DDS start solution (B.71-B.86): (xP0, yP0, phiL0)."""
    xPH, yPH = x2 + ca.cos(phiU), y2 + ca.sin(phiU)        # B.71, B.72
    H1 = xPH - x2                                          # B.73
    H2 = yPH - y2                                          # B.74
    H3 = H1 ** 2 + H2 ** 2                                 # B.75
    H4 = H1 / ca.sqrt(H3)                                  # B.76
    H5 = H2 / ca.sqrt(H3)                                  # B.77
    H6 = x2 - x1                                           # B.78
    H7 = y2 - y1                                           # B.79
    H8 = H4 * H7 - H5 * H6 + v                             # B.80
    H9 = H6 ** 2 + H7 ** 2 + v ** 2 - l ** 2 + 2 * v * (H8 - v)   # B.81
    H10 = H4 * H6 + H5 * H7                                # B.82
    H11 = K * sqrt(H10 ** 2 - H9) - H10                    # B.83
    xP0 = x2 + H4 * H11 - H5 * v                           # B.84
    yP0 = y2 + H5 * H11 + H4 * v                           # B.85
    return xP0, yP0, ca.atan2(y1 - yP0, x1 - xP0), H11     # B.86 (and x_G)


@element((1, 2), MassData("L", "the link", "LKS", half_of="lL"),
         MassData("S", "the slider", "SKS"),
         connectors={"ctr2D1": triangle("housing at P1"),
                     "ctr2D2": triangle("guide at P2"),
                     "ctr2D3": plug("link plane at P1"),
                     "ctr2D4": plug("slider plane at PS"),
                     "ctrT1": translational("guide support flange"),
                     "ctrT2": translational("slider flange")}, outputs=(3, 4))
class DDS(_Linkage):
    """Dyad with a prismatic joint as outer joint DDS (Ebert 2015, Anhang B.5,
    Tabellen B.13-B.15, eqs. B.71-B.118).

    A link of length ``lL`` turns about P1; at its other end P it carries,
    by a revolute joint, a slider guided on a massless straight guide through
    P2 with direction phiU (the placed frame at P2).  P lies at the offset
    ``v`` from the guide line:
    ``P = P1 - lL e(phiL)`` (B.87, B.88; the link frame LKS sits in P and
    points to P1), ``PS = P2 + xG e(phiU)`` (B.99, B.100), ``P = PS + v
    n(phiU)`` (B.93, B.94).  ``K = +1`` puts P, at the start, on the side of
    the perpendicular from P1 onto the guide towards which the guide's
    x-axis points; ``K = -1`` on the other side (B.71-B.86).

    Ports: ``ctr2D1`` housing at P1 (triangle), ``ctr2D2`` guide at P2
    (triangle), ``ctr2D3`` link plane at P1 (angle phiL), ``ctr2D4`` slider
    plane at PS (angle phiU), ``ctrT1`` guide support flange (s = 0),
    ``ctrT2`` slider flange (s = xG, tangential force on the slider).
    Outputs ``xP, yP``.  Parameters (Tabelle B.14): ``lL = 1 m``, ``v = 0.1
    m``, ``K``, ``xSLrel = lL/2``, ``ySLrel = 0``, ``xSSrel = ySSrel = 0``,
    ``mL = mS = 1 kg``, ``JL = JS = 0.1 kg m²``.
    """
    lL = Parameter(1.0, "m", "link length (P1 - P)", positive=True)
    v = Parameter(0.1, "m", "offset of P from the guide line")
    K = Parameter(1.0, "", "assembly parameter (start only), see class doc")

    phiL = Variable(unit="rad", doc="link angle (direction P -> P1)")
    xG = Variable(unit="m", doc="slider travel P2 -> PS")
    phiS = Variable(unit="rad", doc="slider angle (= guide angle)")
    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force slider -> link at P, x")
    FPy = Variable(unit="N", doc="joint force slider -> link at P, y")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")

    def _assemble_at(self, asm, p1, p2):
        (x1, y1, _), (x2, y2, a) = p1, p2
        dist = -ca.sin(a) * (x1 - x2) + ca.cos(a) * (y1 - y2) - self.v
        asm.check(self, self.lL ** 2 - dist ** 2,
                  "distance of P1 from the offset guide line <= lL (B.83)",
                  "The link cannot reach the guide; change lL, v or the positions.")
        xP, yP, phiL, xG = vdi_dds(x1, y1, x2, y2, a, self.lL, self.v, self.K,
                                   sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        xPS, yPS = x2 + xG * ca.cos(a), y2 + xG * ca.sin(a)
        asm.start(self, {"phiL": phiL, "xG": xG, "phiS": a, "xP": xP, "yP": yP,
                         **self._mass_start("L", (xP, yP), phiL),
                         **self._mass_start("S", (xPS, yPS), a)})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": phiL})
        self._set_port(asm, self.ctr2D4, {"x": xPS, "y": yPS, "phi": a})
        self._set_port(asm, self.ctrT2, {"s": xG})
        self._set_port(asm, self.ctrT1, {"s": 0.0})

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, a), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        phiL = self.phiL
        P1, P2, P = (x1, y1), (x2, y2), (self.xP, self.yP)
        PS = (x2 + self.xG * c, y2 + self.xG * s)                   # B.99, B.100
        L, cgL = self._mass("L", P, phiL)
        S, cgS = self._mass("S", PS, a, self.phiS)
        FP = (self.FPx, self.FPy)
        Fn, Ft, Fu = self.Fn, self.ctrT2.f, self.ctrT1.f
        port3, C3 = self._output(3, (x1, y1, phiL))
        port4, C4 = self._output(4, (PS[0], PS[1], a))
        return [
            self.xP == x1 - self.lL * ca.cos(phiL),                # B.87
            self.yP == y1 - self.lL * ca.sin(phiL),                # B.88
            self.xP == PS[0] - self.v * s,                          # B.93
            self.yP == PS[1] + self.v * c,                          # B.94
            self.phiS == a,                                         # B.105
            *cgL, *cgS,
            *port3, *port4,                                         # Tabelle B.15, A.7-A.9
            self.ctrT2.s == self.xG, self.ctrT1.s == 0,
            # link B.108-B.110 (moments about P1)
            *link_balance(f1, f3, FP, P, P1, L, plane_at=off_point(C3, P1)),
            # slider B.111-B.113 (moments about PS)
            -FP[0] + Fn * n[0] + Ft * e[0] + f4.fx + S.F[0] == 0,
            -FP[1] + Fn * n[1] + Ft * e[1] + f4.fy + S.F[1] == 0,
            self.TPS + f4.t + _moment(P, PS, (-FP[0], -FP[1])) + S.moment(PS)
            + port_moment(C4, PS, f4) == 0,
            # massless guide B.114-B.116
            *guide_balance(f2, Fn, Fu, self.TPS, e, n, PS, P2, C2),
            # massless housing at P1
            housing(f1, P1, C1),
        ]

    def shapes(self):
        P1, PS, P = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xP", "yP"]
        P2, _ = self._port_point(2)
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2, "phiS")
                + [{"type": "link", "points": [P1, P]}, self._slider_shape(PS, "phiS", 2, "xG"),
                   {"type": "link", "points": [PS, P]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P[0], "y": P[1]}]
                + self._body_shape("L"))

    def topology(self):
        # links: link = ctr2D3, slider = ctr2D4; revolutes at P1 and P,
        # prismatic between the guide plane (ctr2D2) and the slider
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1)]
