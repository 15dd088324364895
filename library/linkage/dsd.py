"""Dyad with a prismatic joint as inner joint DSD (Ebert 2015, Anhang B.6, Tabellen
B.16-B.18, eqs. B.119-B.148)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .base import (_Linkage, _moment, MassData, element, housing, plug, port_moment,
                   translational, triangle)

__all__ = ["DSD", "vdi_dsd"]


def vdi_dsd(x1, y1, x2, y2, v, sqrt=ca.sqrt):
    """VDI 2729 DSD start solution (B.119-B.125): (phiU, xG)."""
    H1 = x2 - x1                                    # B.119
    H2 = y2 - y1                                    # B.120
    H3 = H1 ** 2 + H2 ** 2                          # B.121
    H4 = sqrt(H3 - v ** 2)                          # B.122
    H5 = (H1 * H4 + v * H2) / H3                    # B.123
    H6 = (H2 * H4 - v * H1) / H3                    # B.124 (sign, see package doc)
    return ca.atan2(H6, H5), H4                     # B.125


@element((1, 2), MassData("U", "the guide", "UKS"), MassData("S", "the slider", "SKS"),
         connectors={"ctr2D1": triangle("housing at P1"),
                     "ctr2D2": triangle("housing at P2"),
                     "ctr2D3": plug("guide plane at P1"),
                     "ctr2D4": plug("slider plane at P2"),
                     "ctrT1": translational("slider flange"),
                     "ctrT2": translational("guide flange")}, outputs=(3, 4))
class DSD(_Linkage):
    """Dyad with a prismatic joint as inner joint DSD (Ebert 2015, Anhang B.6,
    Tabellen B.16-B.18, eqs. B.119-B.148).

    A guide with mass turns about P1; a slider with mass slides on it and
    turns about P2.  ``PS = P1 + xG e(phiU)`` (B.126, B.127) and ``P2 = PS +
    v n(phiU)`` (B.132, B.133); the slider angle equals phiU (B.138).  The
    start direction follows B.119-B.125 with ``xG > 0``; VDI's K would only
    move an auxiliary point and is not needed (ch. 4.2.1).  The distance
    P1-P2 must exceed ``|v|``.

    Ports: ``ctr2D1``/``ctr2D2`` housings at P1/P2 (triangles), ``ctr2D3``
    guide plane at P1 (angle phiU), ``ctr2D4`` slider plane at P2 (angle
    phiU), ``ctrT1`` slider flange (s = xG, tangential force on the slider),
    ``ctrT2`` guide flange (s = 0, tangential force on the guide) as in
    Tabelle B.18.  Parameters (Tabelle B.17): ``v = 0.1 m``, ``xSUrel =
    ySUrel = xSSrel = ySSrel = 0`` (guide CoG in UKS at P1, slider CoG in SKS
    at PS), ``mU = mS = 1 kg``, ``JU = JS = 0.1 kg m²``.
    """
    v = Parameter(0.1, "m", "offset of P2 from the guide line")

    phiU = Variable(unit="rad", doc="guide angle (= slider angle)")
    xG = Variable(unit="m", doc="slider travel P1 -> PS")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")
    xPS = Variable(unit="m", doc="slider foot point PS on the guide, x (for drawing)")
    yPS = Variable(unit="m", doc="slider foot point PS on the guide, y (for drawing)")

    def _assemble_at(self, asm, p1, p2):
        (x1, y1, _), (x2, y2, _) = p1, p2
        asm.check(self, (x2 - x1) ** 2 + (y2 - y1) ** 2 - self.v ** 2,
                  "|P1 P2| >= |v| (B.122)", "Increase the distance P1-P2 or reduce v.")
        asm.check(self, ca.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2) - 1e-9,
                  "P1 != P2 (the guide's pivot P1 is not on the slider's pivot P2)",
                  "Move P1 (x10, y10) or P2 (x20, y20): the guide direction is undefined.")
        a, xG = vdi_dsd(x1, y1, x2, y2, self.v, sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        xPS, yPS = x1 + xG * ca.cos(a), y1 + xG * ca.sin(a)
        asm.start(self, {"phiU": a, "xG": xG, "xPS": xPS, "yPS": yPS,
                         **self._mass_start("U", (x1, y1), a),
                         **self._mass_start("S", (xPS, yPS), a)})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": a})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": a})
        self._set_port(asm, self.ctrT1, {"s": xG})
        self._set_port(asm, self.ctrT2, {"s": 0.0})

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, _), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        a = self.phiU
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        P1, P2 = (x1, y1), (x2, y2)
        PS = (x1 + self.xG * c, y1 + self.xG * s)                   # B.126, B.127
        U, cgU = self._mass("U", P1, a)
        S, cgS = self._mass("S", PS, a)
        Fn, Ft, Fu = self.Fn, self.ctrT1.f, self.ctrT2.f
        FS = (Fn * n[0] + Ft * e[0], Fn * n[1] + Ft * e[1])   # guide -> slider at PS
        port3, C3 = self._output(3, (x1, y1, a))
        port4, C4 = self._output(4, (x2, y2, a))
        return [
            x2 == PS[0] - self.v * s,                               # B.132
            y2 == PS[1] + self.v * c,                               # B.133
            *cgU, *cgS,
            self.xPS == PS[0], self.yPS == PS[1],
            *port3, *port4,                                         # Tabelle B.18, A.7-A.9
            self.ctrT1.s == self.xG, self.ctrT2.s == 0,
            # guide B.141-B.143 (moments about P1)
            f1.fx + f3.fx - Fn * n[0] + Fu * e[0] + U.F[0] == 0,
            f1.fy + f3.fy - Fn * n[1] + Fu * e[1] + U.F[1] == 0,
            f3.t - self.TPS + _moment(PS, P1, (-Fn * n[0], -Fn * n[1])) + U.moment(P1)
            + port_moment(C3, P1, f3) == 0,
            # slider B.144-B.146 (moments about P2)
            f2.fx + f4.fx + FS[0] + S.F[0] == 0,
            f2.fy + f4.fy + FS[1] + S.F[1] == 0,
            f4.t + self.TPS + _moment(PS, P2, FS) + S.moment(P2) + port_moment(C4, P2, f4) == 0,
            # massless housings
            housing(f1, P1, C1),
            housing(f2, P2, C2),
        ]

    def shapes(self):
        P1, P2, PS = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xPS", "yPS"]
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2)
                + [{"type": "link", "points": [P1, PS]},
                   self._guided_slider(P1, PS),
                   {"type": "link", "points": [PS, P2]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P2[0], "y": P2[1]}]
                + self._body_shape("U"))

    def _guided_slider(self, P1, PS):
        """The slider on its guide from the guide's pivot P1 (the plane
        port ``ctr2D3`` sits at P1 unless it is placed with an offset; then
        the placed point of port 1 where it is a result signal, see
        :meth:`_port_point`), so that its travel xG is a slider range."""
        if self._output_offset(3) is None:
            return dict(self._slider_shape(PS, "phiU"), guide=[P1, PS])
        return self._slider_shape(PS, "phiU", 1, "xG")

    def topology(self):
        # links: guide = ctr2D3, slider = ctr2D4; revolutes at P1 and P2,
        # prismatic between guide and slider
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]
