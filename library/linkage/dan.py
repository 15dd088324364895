"""Rotary drive DAN (Ebert 2015, Anhang B.1, Tabellen B.1-B.3, eqs. B.1-B.9)."""
import casadi as ca

from acausal2d import der, Parameter, Variable

from .base import _Linkage, _moment, MassData, element, housing, plug, rotational, triangle

__all__ = ["DAN"]


@element((1,), MassData("L", "the link", "LKS", half_of="lL"),
         connectors={"ctr2D1": triangle("housing at P1"),
                     "ctr2D2": plug("link plane at P"),
                     "ctrR1": rotational("housing (support) flange"),
                     "ctrR2": rotational("link flange")}, outputs=(2,))
class DAN(_Linkage):
    """Rotary drive DAN (Ebert 2015, Anhang B.1, Tabellen B.1-B.3, eqs. B.1-B.9).

    A crank (Link) of length ``lL`` turns about the bearing point P1; its end
    point P moves on a circle.  Ports: ``ctr2D1`` bearing housing at P1
    (triangle: ground-fixed at ``(x10, y10)`` while unconnected),
    ``ctr2D2`` crank plane at P (angle phiL; placed by ``x20, y20, phi20``,
    the offset of P in the port's connection frame, A.7-A.9 with the
    connection frame as the unknown, forces by A.16-A.18; ``frameRef2``
    'relative' only), ``ctrR1`` 1D rotational flange
    on the housing (support torque, angle = housing angle), ``ctrR2`` 1D
    rotational flange on the crank (angle = phiL, torque T_R2 on the crank).
    Drive the crank by connecting a motion preset or a torque to ``ctrR2``
    (see :mod:`acausal2d.library.linkage.drives`); with ``ctrR2`` unconnected
    the crank is free.

    Kinematics B.1/B.2: ``x_P = x_P1 + lL cos(phiL)``, ``y_P = y_P1 + lL
    sin(phiL)``.  Forces B.7-B.9 (balance of the crank, moment about P1).
    Parameters (Tabelle B.2 defaults): ``mL = 1 kg``, ``JL = 0.1 kg m²``
    about the centre of gravity, ``xSLrel = lL/2`` (when not given),
    ``ySLrel = 0``; ``phiL0``, ``omL0`` are the start angle/speed (guesses;
    fix them with ``DAN(phiL=start(fixed=True), omL=start(fixed=True))`` for
    a force-driven crank).
    """
    lL = Parameter(1.0, "m", "link (crank) length l_L", positive=True)
    phiL0 = Parameter(0.0, "rad", "start angle of the link")
    omL0 = Parameter(0.0, "rad/s", "start angular velocity of the link")

    phiL = Variable(unit="rad", doc="link angle (absolute)", state_select="prefer")
    omL = Variable(unit="rad/s", doc="link angular velocity", state_select="prefer")

    def _assemble_at(self, asm, p1):
        x1, y1, a1 = p1
        r = asm.get(self.ctrR2)
        phi = r["phi"] if r and "phi" in r else self._start("phiL", self.phiL0)
        om = r["w"] if r and "w" in r else self._start("omL", self.omL0)
        xP, yP = x1 + self.lL * ca.cos(phi), y1 + self.lL * ca.sin(phi)
        asm.start(self, {"phiL": phi, "omL": om, **self._mass_start("L", (x1, y1), phi)})
        self._set_port(asm, self.ctr2D2, {"x": xP, "y": yP, "phi": phi})
        self._set_port(asm, self.ctrR2, {"phi": phi})
        self._set_port(asm, self.ctrR1, {"phi": a1})

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        phi = self.phiL
        P1 = (x1, y1)
        P = (x1 + self.lL * ca.cos(phi), y1 + self.lL * ca.sin(phi))          # B.1, B.2
        L, cg = self._mass("L", P1, phi)                                     # A.21, A.22
        port2, C2 = self._output(2, (P[0], P[1], phi))       # Tabelle B.3, A.7-A.9
        return [
            self.omL == der(phi),
            *cg,
            *port2,
            self.ctrR2.phi == phi, self.ctrR1.phi == a1,
            # B.7, B.8: forces on the link (joint force housing -> link = f1)
            f1.fx + f2.fx + L.F[0] == 0,
            f1.fy + f2.fy + L.F[1] == 0,
            # B.9: moments about P1 (the port force acts at C2, A.18)
            f2.t + self.ctrR2.tau + _moment(C2, P1, (f2.fx, f2.fy)) + L.moment(P1) == 0,
            # massless housing, moments about the connection point (A.18)
            housing(f1, P1, C1, self.ctrR1.tau),
        ]

    def shapes(self):
        P1, _ = self._port_point(1)
        P = ["ctr2D2.x", "ctr2D2.y"]
        return (self._housing_shapes(1, P1)
                + [{"type": "link", "points": [P1, P]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P[0], "y": P[1]}]
                + self._body_shape("L"))

    def topology(self):
        # housing plane (ctr2D1) -- revolute at P1 -- crank (ctr2D2)
        return self._ground_ports(1) + [("joint", self.ctr2D1, self.ctr2D2, 1)]
