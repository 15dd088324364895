"""Dyad with prismatic joints as outer joints SDS (Ebert 2015, Anhang B.8, Tabellen
B.22-B.24, eqs. B.195-B.236)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .two_sliders import _TwoSliders
from .base import (_cross, _moment, MassData, axes, element, plug, port_moment,
                   triangle)

__all__ = ["SDS", "solve_sds"]


def solve_sds(x1, y1, a1, x2, y2, a2, v1, v2):
    """Closed-form travels (xG1, xG2) of SDS (B.197-B.216 solved, linear)."""
    (e1, n1), (e2, n2) = axes(a1), axes(a2)
    # xG1 e1 - xG2 e2 = r
    rx = x2 + v2 * n2[0] - x1 - v1 * n1[0]
    ry = y2 + v2 * n2[1] - y1 - v1 * n1[1]
    det = _cross(e1[0], e1[1], -e2[0], -e2[1])
    return _cross(rx, ry, -e2[0], -e2[1]) / det, _cross(e1[0], e1[1], rx, ry) / det


@element((1, 2), MassData("S1", "slider 1", "SKS1"), MassData("S2", "slider 2", "SKS2"),
         connectors={"ctr2D1": triangle("guide 1 at P1"),
                     "ctr2D2": triangle("guide 2 at P2"),
                     "ctr2D3": plug("slider 1 plane at P"),
                     "ctr2D4": plug("slider 2 plane at PS2")}, outputs=(3, 4))
class SDS(_TwoSliders):
    """Dyad with prismatic joints as outer joints SDS (Ebert 2015, Anhang B.8,
    Tabellen B.22-B.24, eqs. B.195-B.236).

    Slider 1 slides on the massless guide 1 at P1 (direction phiU1), slider 2
    on guide 2 at P2 (phiU2); they are joined by a revolute joint at P:
    ``PS1 = P1 + xG1 e1``, ``P = PS1 + v1 n1`` (B.197, B.209) and ``PS2 = P2 +
    xG2 e2``, ``P = PS2 + v2 n2`` (B.203, B.215).  Linear in the travels: no
    assembly parameter; the guides must not be parallel.

    Ports (Tabelle B.24): ``ctr2D1`` guide 1 at P1 and ``ctr2D2`` guide 2 at
    P2 (triangles, rigid), ``ctr2D3`` slider 1 plane at P (angle phiU1),
    ``ctr2D4`` slider 2 plane at PS2 (angle phiU2).  Outputs ``xP, yP``.
    Parameters (Tabelle B.23): ``v1 = v2 = 0.1 m``, CoG offsets 0 in SKS1 (at
    PS1) and SKS2 (at PS2), ``mS1 = mS2 = 1 kg``, ``JS1 = JS2 = 0.1 kg m²``.
    """
    v2 = Parameter(0.1, "m", "offset of P from guide 2")

    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force slider 2 -> slider 1 at P, x")
    FPy = Variable(unit="N", doc="joint force slider 2 -> slider 1 at P, y")

    def _assemble_at(self, asm, p1, p2):
        (x1, y1, a1), (x2, y2, a2) = p1, p2
        asm.check(self, ca.fabs(ca.sin(a2 - a1)) - 1e-9,
                  "guides 1 and 2 not parallel at the start (B.197-B.216)",
                  "Turn a guide (phi10, phi20) or start where the guides cross.")
        xG1, xG2 = solve_sds(x1, y1, a1, x2, y2, a2, self.v1, self.v2)
        PS1, P, start1 = self._slider1_start(x1, y1, a1, xG1)
        e2, _ = axes(a2)
        PS2 = (x2 + xG2 * e2[0], y2 + xG2 * e2[1])
        asm.start(self, {**start1, "xG2": xG2, "phiS2": a2, "xP": P[0], "yP": P[1],
                         **self._mass_start("S2", PS2, a2)})
        self._set_port(asm, self.ctr2D3, {"x": P[0], "y": P[1], "phi": a1})
        self._set_port(asm, self.ctr2D4, {"x": PS2[0], "y": PS2[1], "phi": a2})

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        (x2, y2, a2), C2 = self._place(2)
        f2, f3, f4 = self.ctr2D2, self.ctr2D3, self.ctr2D4
        (e1, n1), (e2, n2) = axes(a1), axes(a2)
        PS1 = (x1 + self.xG1 * e1[0], y1 + self.xG1 * e1[1])               # B.197, B.198
        PS2 = (x2 + self.xG2 * e2[0], y2 + self.xG2 * e2[1])               # B.203, B.204
        P = (self.xP, self.yP)
        S1, cg1 = self._mass("S1", PS1, a1, self.phiS1)
        S2, cg2 = self._mass("S2", PS2, a2, self.phiS2)
        N1 = (self.Fn1 * n1[0], self.Fn1 * n1[1])
        N2 = (self.Fn2 * n2[0], self.Fn2 * n2[1])
        FP = (self.FPx, self.FPy)
        port3, C3 = self._output(3, (P[0], P[1], a1))                      # A.7-A.9
        port4, C4 = self._output(4, (PS2[0], PS2[1], a2))
        return [
            self.phiS1 == a1, self.phiS2 == a2,                            # B.195, B.196
            self.xP == PS1[0] + self.v1 * n1[0],                           # B.209
            self.yP == PS1[1] + self.v1 * n1[1],                           # B.210
            self.xP == PS2[0] + self.v2 * n2[0],                           # B.215
            self.yP == PS2[1] + self.v2 * n2[1],                           # B.216
            *cg1, *cg2,
            self.xPS1 == PS1[0], self.yPS1 == PS1[1],
            *port3, *port4,                                                # Tabelle B.24, A.7-A.9
            # massless guides B.221-B.226
            *self._guide1(C1, PS1, N1),
            f2.fx - N2[0] == 0, f2.fy - N2[1] == 0,
            f2.t - self.T2 + _moment(PS2, C2, (-N2[0], -N2[1])) == 0,
            # slider 1 B.227-B.229 (moments about PS1)
            N1[0] + FP[0] + f3.fx + S1.F[0] == 0,
            N1[1] + FP[1] + f3.fy + S1.F[1] == 0,
            self.T1 + f3.t + _moment(P, PS1, FP) + port_moment(C3, PS1, f3)
            + S1.moment(PS1) == 0,
            # slider 2 B.230-B.232 (moments about PS2)
            N2[0] - FP[0] + f4.fx + S2.F[0] == 0,
            N2[1] - FP[1] + f4.fy + S2.F[1] == 0,
            self.T2 + f4.t + _moment(P, PS2, (-FP[0], -FP[1])) + S2.moment(PS2)
            + port_moment(C4, PS2, f4) == 0,
        ]

    def shapes(self):
        P2, _ = self._port_point(2)
        P, PS1, PS2 = ["xP", "yP"], ["xPS1", "yPS1"], ["ctr2D4.x", "ctr2D4.y"]
        return (self._slider_shapes(PS1, PS2, P, guide2_port=2)
                + self._housing_shapes(2, P2, "phiS2")
                + [{"type": "link", "points": [PS2, P]},
                   {"type": "joint", "x": P[0], "y": P[1]}])

    def topology(self):
        # links: slider 1 = ctr2D3, slider 2 = ctr2D4; prismatic guide 1
        # (ctr2D1) - slider 1 and guide 2 (ctr2D2) - slider 2, revolute at P
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]

