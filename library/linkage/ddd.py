"""Dyad with three revolute joints DDD (Ebert 2015, Anhang B.4, Tabellen B.10-B.12,
eqs. B.42-B.70)."""
import casadi as ca

from acausal2d import Parameter, Variable

from .base import (_Linkage, MassData, element, housing, link_balance, off_point, plug,
                   rotational, triangle)

__all__ = ["DDD", "vdi_ddd"]


def vdi_ddd(x1, y1, x2, y2, l1, l2, K, sqrt=ca.sqrt):
    """VDI 2729 DDD start solution (B.42-B.52): (xP, yP, phiL1, phiL2)."""
    H1 = x2 - x1                                    # B.42
    H2 = y2 - y1                                    # B.43
    H3 = H1 ** 2 + H2 ** 2                          # B.44
    H4 = l1 ** 2 - l2 ** 2 + H3                     # B.45
    H5 = K * sqrt(4 * H3 * l1 ** 2 - H4 ** 2)       # B.46
    H6 = (H1 * H4 - H2 * H5) / (2 * H3)             # B.47
    H7 = (H2 * H4 + H1 * H5) / (2 * H3)             # B.48
    return (x1 + H6, y1 + H7,                       # B.49, B.50
            ca.atan2(H7, H6), ca.atan2(H7 - H2, H6 - H1))   # B.51, B.52


@element((1, 2), MassData("L1", "link 1", "LKS1", half_of="lL1"),
         MassData("L2", "link 2", "LKS2", half_of="lL2"),
         connectors={"ctr2D1": triangle("housing at P1"),
                     "ctr2D2": triangle("housing at P2"),
                     "ctr2D3": plug("link 1 plane at P1"),
                     "ctr2D4": plug("link 2 plane at P2"),
                     "ctrR1": rotational("housing 2 (support) flange"),
                     "ctrR2": rotational("link 2 flange")}, outputs=(3, 4))
class DDD(_Linkage):
    """Dyad with three revolute joints DDD (Ebert 2015, Anhang B.4, Tabellen
    B.10-B.12, eqs. B.42-B.70).

    Link 1 (length ``lL1``) turns about P1, link 2 (``lL2``) about P2; they
    are joined at P.  Position equations in point-direction form (B.53,
    B.54, B.59, B.60): ``P = P1 + lL1 e(phiL1) = P2 + lL2 e(phiL2)``.
    ``K = +1`` puts P on the left of the line P1 -> P2 at the start, ``K =
    -1`` on the right (VDI 2729, B.42-B.52 give the start angles).

    Ports: ``ctr2D1``/``ctr2D2`` bearing housings at P1/P2 (triangles:
    ground-fixed while unconnected), ``ctr2D3`` plane of link 1 at P1 (angle
    phiL1), ``ctr2D4`` plane of link 2 at P2 (angle phiL2) -- both placed by
    ``x30, y30, phi30`` / ``x40, y40, phi40`` (offset of the point in the
    port's connection frame, A.7-A.9 with the connection frame as the
    unknown, forces by A.16-A.18; 'relative' only) --, ``ctrR1`` flange
    on housing 2 (support), ``ctrR2`` flange on link 2 (angle phiL2).
    Outputs ``xP, yP``: the joint point P.  Parameters (Tabelle B.11):
    ``lL1 = lL2 = 1 m``, ``K``, ``xSL1rel = lL1/2``, ``xSL2rel = lL2/2``,
    ``ySL1rel = ySL2rel = 0``, ``mL1 = mL2 = 1 kg``, ``JL1 = JL2 = 0.1 kg m²``.
    """
    lL1 = Parameter(1.0, "m", "length of link 1 (P1 -> P)", positive=True)
    lL2 = Parameter(1.0, "m", "length of link 2 (P2 -> P)", positive=True)
    K = Parameter(1.0, "", "assembly parameter: +1 P left of P1->P2, -1 right (start only)")

    phiL1 = Variable(unit="rad", doc="angle of link 1 (P1 -> P)")
    phiL2 = Variable(unit="rad", doc="angle of link 2 (P2 -> P)")
    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force link 2 -> link 1 at P, x")
    FPy = Variable(unit="N", doc="joint force link 2 -> link 1 at P, y")

    def _assemble_at(self, asm, p1, p2):
        (x1, y1, _), (x2, y2, a2) = p1, p2
        l1, l2 = self.lL1, self.lL2
        d2 = (x2 - x1) ** 2 + (y2 - y1) ** 2
        asm.check(self, 4 * d2 * l1 ** 2 - (l1 ** 2 - l2 ** 2 + d2) ** 2,
                  "|lL1 - lL2| <= |P1 P2| <= lL1 + lL2 (B.46)",
                  "The links cannot reach between P1 and P2; change lL1, lL2 or the "
                  "positions of P1/P2 (or the start angle of the drive).")
        xP, yP, p1, p2 = vdi_ddd(x1, y1, x2, y2, l1, l2, self.K,
                                 sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        asm.start(self, {"phiL1": p1, "phiL2": p2, "xP": xP, "yP": yP,
                         **self._mass_start("L1", (x1, y1), p1),
                         **self._mass_start("L2", (x2, y2), p2)})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": p1})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": p2})
        self._set_port(asm, self.ctrR2, {"phi": p2})
        self._set_port(asm, self.ctrR1, {"phi": a2})

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, a2), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        p1, p2 = self.phiL1, self.phiL2
        P1, P2, P = (x1, y1), (x2, y2), (self.xP, self.yP)
        L1, cg1 = self._mass("L1", P1, p1)
        L2, cg2 = self._mass("L2", P2, p2)
        FP = (self.FPx, self.FPy)
        port3, C3 = self._output(3, (x1, y1, p1))         # Tabelle B.12, A.7-A.9
        port4, C4 = self._output(4, (x2, y2, p2))
        return [
            self.xP == x1 + self.lL1 * ca.cos(p1),             # B.53
            self.yP == y1 + self.lL1 * ca.sin(p1),             # B.54
            self.xP == x2 + self.lL2 * ca.cos(p2),             # B.59
            self.yP == y2 + self.lL2 * ca.sin(p2),             # B.60
            *cg1, *cg2,                                        # A.21, A.22
            *port3, *port4,
            self.ctrR2.phi == p2, self.ctrR1.phi == a2,
            # link 1, B.65-B.67 (moments about P1)
            *link_balance(f1, f3, FP, P, P1, L1, plane_at=off_point(C3, P1)),
            # link 2, B.68-B.70 (moments about P2)
            *link_balance(f2, f4, (-FP[0], -FP[1]), P, P2, L2, self.ctrR2.tau,
                          plane_at=off_point(C4, P2)),
            # massless housings (A.18)
            housing(f1, P1, C1),
            housing(f2, P2, C2, self.ctrR1.tau),
        ]

    def shapes(self):
        P1, P2, P = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xP", "yP"]
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2)
                + [{"type": "link", "points": [P1, P]},
                   {"type": "link", "points": [P2, P]}]
                + [{"type": "joint", "x": q[0], "y": q[1]} for q in (P1, P2, P)]
                + self._body_shape("L1") + self._body_shape("L2"))

    def topology(self):
        # links: link 1 = ctr2D3, link 2 = ctr2D4; revolutes at P1, P2, P
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]
