"""Linear drive SAN (Ebert 2015, Anhang B.2, Tabellen B.4-B.6, eqs. B.10-B.32)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .base import (_Body, _Linkage, _rot, element, guide_balance, plug, port_moment,
                   translational, triangle)

__all__ = ["SAN"]


@element((1,),
         connectors={"ctr2D1": triangle("guide at P1"),
                     "ctr2D2": plug("slider plane at P"),
                     "ctrT1": translational("guide support flange"),
                     "ctrT2": translational("slider flange")}, outputs=(2,))
class SAN(_Linkage):
    """Linear drive SAN (Ebert 2015, Anhang B.2, Tabellen B.4-B.6, eqs. B.10-B.32).

    A slider with mass moves on a massless straight guide through P1 with
    direction phiU (angle of the placed frame at P1).  The slider travel
    ``xG`` is measured from P1 to the foot point PS; the driven point P lies
    at the constant offset ``v`` perpendicular to the guide (B.16, B.17):
    ``PS = P1 + xG (cos phiU, sin phiU)``, ``P = PS + v (-sin phiU, cos phiU)``.

    Ports: ``ctr2D1`` guide at P1 (triangle: ground-fixed while unconnected),
    ``ctr2D2`` slider plane at P, ``ctrT1`` guide support flange (s = 0,
    force on the guide), ``ctrT2`` slider flange (s = xG, tangential force on
    the slider Ft_S).  Connect a translational motion preset to ``ctrT2`` to
    drive the slider.  Parameters (Tabelle B.5): ``v = 0``, ``xS0`` start
    travel, ``xSrel = ySrel = 0``, ``mS`` (no default in Ebert 2015; 1 kg), ``JS``
    (0.1 kg m²).
    """
    v = Parameter(0.0, "m", "offset of P from the guide line")
    xS0 = Parameter(0.0, "m", "start travel of the slider (guess unless driven)")
    xSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, x")
    ySrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, y")
    mS = Parameter(1.0, "kg", "mass of the slider", min=0.0)
    JS = Parameter(0.1, "kg.m2", "moment of inertia of the slider about its centre of gravity", min=0.0)

    xG = Variable(unit="m", doc="slider travel P1 -> PS", state_select="prefer")
    phiS = Variable(unit="rad", doc="slider angle (= guide angle)")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")
    xSS = Variable(unit="m", doc="centre of gravity of the slider, x")
    ySS = Variable(unit="m", doc="centre of gravity of the slider, y")
    xPS = Variable(unit="m", doc="slider foot point PS on the guide, x (for drawing)")
    yPS = Variable(unit="m", doc="slider foot point PS on the guide, y (for drawing)")

    def _assemble_at(self, asm, p1):
        x1, y1, a = p1
        t = asm.get(self.ctrT2)
        xG = t["s"] if t and "s" in t else self._start("xG", self.xS0)
        c, s = ca.cos(a), ca.sin(a)
        xPS, yPS = x1 + xG * c, y1 + xG * s
        dx, dy = _rot(a, self.xSrel, self.ySrel)
        asm.start(self, {"xG": xG, "phiS": a, "xSS": xPS + dx, "ySS": yPS + dy,
                          "xPS": xPS, "yPS": yPS})
        self._set_port(asm, self.ctr2D2, {"x": xPS - self.v * s, "y": yPS + self.v * c, "phi": a})
        self._set_port(asm, self.ctrT2, {"s": xG})
        self._set_port(asm, self.ctrT1, {"s": 0.0})

    def equations(self):
        (x1, y1, a), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        PS = (x1 + self.xG * c, y1 + self.xG * s)          # B.10, B.11 (sign see module doc)
        P = (PS[0] - self.v * s, PS[1] + self.v * c)       # B.16, B.17
        dx, dy = _rot(a, self.xSrel, self.ySrel)
        S = _Body(self.mS, self.JS, self.xSS, self.ySS, self.phiS, self._g())
        Ft, Fu = self.ctrT2.f, self.ctrT1.f
        Fn = self.Fn
        port2, C2 = self._output(2, (P[0], P[1], a))       # A.7-A.9
        return [
            self.phiS == a,                                 # B.22
            self.xSS == PS[0] + dx, self.ySS == PS[1] + dy,
            self.xPS == PS[0], self.yPS == PS[1],
            *port2,                                         # Tabelle B.6, A.7-A.9
            self.ctrT2.s == self.xG, self.ctrT1.s == 0,
            # slider B.28-B.30 (joint: normal force, moment; drive force Ft along e)
            Fn * n[0] + Ft * e[0] + f2.fx + S.F[0] == 0,
            Fn * n[1] + Ft * e[1] + f2.fy + S.F[1] == 0,
            self.TPS + f2.t + port_moment(C2, PS, f2) + S.moment(PS) == 0,
            # massless guide B.25-B.27
            *guide_balance(f1, Fn, Fu, self.TPS, e, n, PS, (x1, y1), C1),
        ]

    def shapes(self):
        P1, _ = self._port_point(1)
        PS, P = ["xPS", "yPS"], ["ctr2D2.x", "ctr2D2.y"]
        return (self._housing_shapes(1, P1, "phiS")
                + [self._slider_shape(PS, "phiS", 1, "xG"),
                   {"type": "link", "points": [PS, P]},
                   {"type": "joint", "x": P[0], "y": P[1]}])

    def topology(self):
        # guide plane (ctr2D1) -- prismatic -- slider (ctr2D2)
        return self._ground_ports(1) + [("joint", self.ctr2D1, self.ctr2D2, 1)]
