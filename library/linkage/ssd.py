"""Dyad with prismatic joints as outer and inner joint SSD (Ebert 2015, Anhang B.7,
Tabellen B.19-B.21, eqs. B.149-B.194)."""
import math

import casadi as ca

from acausal2d import Parameter, Variable

from .two_sliders import _TwoSliders
from .base import (_cross, _moment, MassData, axes, element, housing, plug,
                   port_moment, triangle)

__all__ = ["SSD", "solve_ssd"]


def solve_ssd(x1, y1, a1, x2, y2, v1, v2, phiv):
    """Closed-form travels (xG1, xG2) of SSD (B.158-B.177 solved, linear)."""
    (e1, n1), (e2, n2) = axes(a1), axes(a1 + phiv)
    rx = x2 - x1 - v1 * n1[0] - v2 * n2[0]
    ry = y2 - y1 - v1 * n1[1] - v2 * n2[1]
    det = _cross(e1[0], e1[1], e2[0], e2[1])
    return _cross(rx, ry, e2[0], e2[1]) / det, _cross(e1[0], e1[1], rx, ry) / det


@element((1, 2), MassData("S1", "slider 1", "SKS1"), MassData("S2", "slider 2", "SKS2"),
         connectors={"ctr2D1": triangle("guide 1 at P1"),
                     "ctr2D2": triangle("housing at P2"),
                     "ctr2D3": plug("slider 1 plane at P"),
                     "ctr2D4": plug("slider 2 plane at P2")}, outputs=(3, 4))
class SSD(_TwoSliders):
    """Dyad with prismatic joints as outer and inner joint SSD (Ebert 2015, Anhang
    B.7, Tabellen B.19-B.21, eqs. B.149-B.194).

    Slider 1 slides on a massless guide 1 fixed to the plane at P1 (direction
    phiU1 = angle of the placed frame); it carries the point P at the offset
    ``v1`` and a second guide at the angle ``phiv`` against guide 1.  Slider 2
    slides on guide 2 and turns about P2 at the offset ``v2``:
    ``PS1 = P1 + xG1 e1`` (B.158), ``P = PS1 + v1 n1`` (B.164), ``PS2 = P +
    xG2 e2`` (B.170), ``P2 = PS2 + v2 n2`` (B.176), ``phiU2 = phiU1 + phiv``
    (B.152).  Linear in the travels: no assembly parameter.

    Ports: ``ctr2D1`` guide 1 at P1 (triangle, rigid), ``ctr2D2`` housing at
    P2 (triangle, revolute), ``ctr2D3`` slider 1 plane at P (angle phiU1),
    ``ctr2D4`` slider 2 plane at P2 (angle phiU2).  Parameters (Tabelle
    B.20): ``v1 = v2 = 0.1 m``, ``phiv = 15°``, CoG offsets 0 in SKS1 (at PS1)
    and SKS2 (at PS2), ``mS1 = mS2 = 1 kg``, ``JS1 = JS2 = 0.1 kg m²``.
    Guide 2 is part of slider 1: ``Fn2``, ``T2`` act from slider 1 on slider 2.
    """
    v2 = Parameter(0.1, "m", "offset of P2 from guide 2")
    phiv = Parameter(math.radians(15.0), "rad", "angle of guide 2 against guide 1")

    xPS2 = Variable(unit="m", doc="foot point PS2 of slider 2 on guide 2, x (for drawing)")
    yPS2 = Variable(unit="m", doc="foot point PS2 of slider 2 on guide 2, y (for drawing)")

    def _assemble_at(self, asm, p1, p2):
        (x1, y1, a1), (x2, y2, _) = p1, p2
        a2 = a1 + self.phiv
        asm.check(self, ca.fabs(ca.sin(self.phiv)) - 1e-9,
                  "guides 1 and 2 not parallel, sin(phiv) != 0 (B.158-B.177)",
                  "Give phiv a value other than 0 or 180 degrees.")
        xG1, xG2 = solve_ssd(x1, y1, a1, x2, y2, self.v1, self.v2, self.phiv)
        PS1, P, start1 = self._slider1_start(x1, y1, a1, xG1)
        PS2 = (P[0] + xG2 * ca.cos(a2), P[1] + xG2 * ca.sin(a2))
        asm.start(self, {**start1, "xG2": xG2, "phiS2": a2, "xPS2": PS2[0], "yPS2": PS2[1],
                         **self._mass_start("S2", PS2, a2)})
        self._set_port(asm, self.ctr2D3, {"x": P[0], "y": P[1], "phi": a1})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": a2})

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        (x2, y2, _), C2 = self._place(2)
        f2, f3, f4 = self.ctr2D2, self.ctr2D3, self.ctr2D4
        a2 = self.phiS2
        (e1, n1), (e2, n2) = axes(a1), axes(a2)
        P2 = (x2, y2)
        PS1 = (x1 + self.xG1 * e1[0], y1 + self.xG1 * e1[1])               # B.158, B.159
        P = (PS1[0] + self.v1 * n1[0], PS1[1] + self.v1 * n1[1])           # B.164, B.165
        PS2 = (P[0] + self.xG2 * e2[0], P[1] + self.xG2 * e2[1])           # B.170, B.171
        S1, cg1 = self._mass("S1", PS1, a1, self.phiS1)
        S2, cg2 = self._mass("S2", PS2, a2)
        N1 = (self.Fn1 * n1[0], self.Fn1 * n1[1])
        N2 = (self.Fn2 * n2[0], self.Fn2 * n2[1])
        port3, C3 = self._output(3, (P[0], P[1], a1))
        port4, C4 = self._output(4, (x2, y2, a2))
        return [
            self.phiS1 == a1,                                             # B.149
            self.phiS2 == a1 + self.phiv,                                 # B.152, B.155
            x2 == PS2[0] + self.v2 * n2[0],                               # B.176
            y2 == PS2[1] + self.v2 * n2[1],                               # B.177
            *cg1, *cg2,
            self.xPS1 == PS1[0], self.yPS1 == PS1[1],
            self.xPS2 == PS2[0], self.yPS2 == PS2[1],
            *port3, *port4,                                               # Tabelle B.21, A.7-A.9
            # massless guide 1 (B.182-B.184), moments about C1
            *self._guide1(C1, PS1, N1),
            # slider 1 (B.185-B.187), moments about PS1
            N1[0] - N2[0] + f3.fx + S1.F[0] == 0,
            N1[1] - N2[1] + f3.fy + S1.F[1] == 0,
            self.T1 - self.T2 + f3.t + _moment(PS2, PS1, (-N2[0], -N2[1]))
            + port_moment(C3, PS1, f3) + S1.moment(PS1) == 0,
            # slider 2 (B.188-B.190), moments about PS2
            N2[0] + f2.fx + f4.fx + S2.F[0] == 0,
            N2[1] + f2.fy + f4.fy + S2.F[1] == 0,
            self.T2 + f4.t + _moment(P2, PS2, (f2.fx, f2.fy)) + port_moment(C4, PS2, f4)
            + S2.moment(PS2) == 0,
            # massless housing at P2
            housing(f2, P2, C2),
        ]

    def shapes(self):
        P, P2 = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"]
        PS1, PS2 = ["xPS1", "yPS1"], ["xPS2", "yPS2"]
        return (self._slider_shapes(PS1, PS2, P) + self._housing_shapes(2, P2)
                + [{"type": "link", "points": [PS2, P2]},
                   {"type": "joint", "x": P2[0], "y": P2[1]}])

    def topology(self):
        # links: slider 1 = ctr2D3, slider 2 = ctr2D4; prismatic guide 1
        # (ctr2D1) - slider 1, prismatic slider 1 - slider 2, revolute at P2
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1)]
