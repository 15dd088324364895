"""Guided link point FGP (Ebert 2015, Anhang B.3, Tabellen B.7-B.9, eqs. B.33-B.41)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .base import _Linkage, MassData, element, plug, port_moment, triangle

__all__ = ["FGP"]


@element((1,), MassData("L", "the link", "LKS", half_of="lL"),
         connectors={"ctr2D1": triangle("connection to the predecessor plane"),
                     "ctr2D2": plug("guided point P")}, outputs=(2,))
class FGP(_Linkage):
    """Guided link point FGP (Ebert 2015, Anhang B.3, Tabellen B.7-B.9, B.33-B.41).

    A rigid link with mass, fixed to the plane of its predecessor at
    ``ctr2D1``: its start point P1 and direction phiL are the placed frame
    (``x10, y10, phi10`` relative to the connection, Anhang A.1); the guided
    point P lies at ``lL`` along phiL (B.33, B.34).  Use it for coupler
    points and for the second arm of a bell crank.  Ports: ``ctr2D1``
    (triangle: ground-fixed while unconnected), ``ctr2D2`` plane at P (angle
    phiL).  Parameters (Tabelle B.8): ``lL``, ``xSLrel = lL/2``, ``ySLrel =
    0``, ``mL = 1 kg``, ``JL = 0.1 kg m²`` (set both to 0 for the dissertation's
    "masselos").
    """
    lL = Parameter(1.0, "m", "link length l_L (P1 -> P)", positive=True)

    phiL = Variable(unit="rad", doc="link angle")

    def _assemble_at(self, asm, p1):
        x1, y1, a = p1
        asm.start(self, {"phiL": a, **self._mass_start("L", (x1, y1), a)})
        self._set_port(asm, self.ctr2D2, {"x": x1 + self.lL * ca.cos(a),
                                          "y": y1 + self.lL * ca.sin(a), "phi": a})

    def equations(self):
        (x1, y1, a), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        P = (x1 + self.lL * ca.cos(self.phiL), y1 + self.lL * ca.sin(self.phiL))   # B.33, B.34
        L, cg = self._mass("L", (x1, y1), self.phiL)
        port2, C2 = self._output(2, (P[0], P[1], self.phiL))                         # A.7-A.9
        return [
            self.phiL == a,
            *cg,
            *port2,                                                                  # Tab. B.9
            f1.fx + f2.fx + L.F[0] == 0,                                             # B.39
            f1.fy + f2.fy + L.F[1] == 0,                                             # B.40
            f1.t + f2.t + port_moment(C2, C1, f2) + L.moment(C1) == 0,                # B.41
        ]

    def shapes(self):
        P1, _ = self._port_point(1)
        P = ["ctr2D2.x", "ctr2D2.y"]
        return (self._housing_shapes(1, P1, "phiL")
                + [{"type": "link", "points": [P1, P]}]
                + self._body_shape("L"))

    def topology(self):
        # part of the predecessor's plane: no joint, one rigid link
        return self._ground_ports(1) + [("rigid", [self.ctr2D1, self.ctr2D2])]
