"""Synthesis element DB~SD: cam and a tension spring in the band or a draw-off
nozzle (Ebert 2015, ch. 4.3.3, eq. 4.35-4.49).  :func:`dbsd_band` is the explicit
band geometry (shared with :mod:`.functional`), :class:`DB_SD` the element;
the corrections of the printed equations are listed in
:mod:`acausal2d.library.synthesis`.
"""
import casadi as ca

from acausal2d import Component, der, Frame, Parameter, RealInput, Variable
from .base import _check_K, _direction_guess, _zero_flows


def dbsd_band(x1, y1, x2, y2, h, K, sqrt=ca.sqrt):
    """Band of DB~SD (Ebert 2015, eq. 4.35-4.46) in explicit form.

    The band runs through P2 (spring pivot or nozzle) at the signed lever
    arm ``h`` from the cam pivot P1; with u the unit vector P1 -> P2 and v
    its left normal, the band direction from P2 towards the cam is

        e(gamma_B) = -sqrt(1 - (h/l1)^2) u + K (h/l1) v          (4.39-4.46)

    and the foot point F ("pole 23", 4.44/4.45) is ``P2 + l2 e`` with
    ``l2 = sqrt(l1^2 - h^2)`` (4.39).  For K = +1 and h > 0, F lies left of
    P1 -> P2; it changes sides with the sign of h (torque reversal) without
    a sign() relation.  Returns a dict ``cg, sg, l2, x23, y23``."""
    H1, H2 = x2 - x1, y2 - y1                       # 4.35, 4.36
    l1 = sqrt(H1 * H1 + H2 * H2)                    # 4.37, 4.38
    ux, uy = H1 / l1, H2 / l1
    q = h / l1
    c = sqrt(1 - q * q)
    cg, sg = -c * ux - K * q * uy, -c * uy + K * q * ux
    l2 = l1 * c                                     # 4.39
    return {"cg": cg, "sg": sg, "l2": l2, "x23": x2 + l2 * cg, "y23": y2 + l2 * sg}


class DB_SD(Component):
    """Synthesis element DB~SD: cam with a tension spring in the band or a
    draw-off nozzle (Ebert 2015, ch. 4.3.3, eq. 4.35-4.49, Tabelle 4.4, 4.5, Bild
    4.10, 6.2).

    ``DB_SD(K=1, x0=...)``.  The cam plane turns about P1 (port ``ctr2D1``);
    the band runs in a straight line from the cam through P2 (port
    ``ctr2D2``: the ground pivot of the spring, or the nozzle) at the
    effective lever arm ``h`` = ``in1.u`` from P1 (the diagonal
    Drehschubstrecke, ch. 6: h = x_S'(phi)).  Output ``ctr2D3`` is the
    material point P3 of the band (phi = 0).

    Equations: band direction and foot point F (pole 23) from
    :func:`dbsd_band` (4.35-4.46, explicit); travel ``der(x) = h
    der(phi_P1)`` with x = 0 at the start (4.49: any deviation gives a
    non-tangential band entry); ``P3 = P2 + K (x + x0) e(gamma_B)`` (4.47,
    4.48 with the verified K sign; the printed minus sign is the K = -1
    case of example 7.2.1).

    ``K`` (structural): +1 puts F left of the directed line P1 -> P2 for h >
    0, -1 right; when h changes sign F changes sides (torque reversal at the
    cam axis), smoothly.  For K = +1 a positive cam turn winds the band up
    when h > 0 (the material point moves towards the cam), for K = -1 it
    pays the band out.  ``x0``: signed distance of the material point from
    P2 at the start, measured towards the cam for K = +1 and away from it for
    K = -1 (Tabelle 4.4: free band end -> P2, needed for the nozzle).  The
    contour does not depend on it, the free band length of ch. 5 does: make
    P3 the real band fixing point (spring eye) when assessing the curve.

    Outputs: ``x`` (4.49), ``gamma_B`` (unwrapped direction P2 -> F; start
    guess from the parameters, ``gamma_B=start(...)`` otherwise), ``x23,
    y23`` (F), ``l2`` (|P2 F|, 4.39).
    """
    x0 = Parameter(0.0, "m", "distance of the material point from P2 at the start (Anfangsweg)")

    x = Variable(fixed=True, unit="m", doc="travel, integral of h over phi_P1 (eq. 4.49)")
    gamma_B = Variable(unit="rad", state_select="avoid",
                       doc="band angle, direction P2 -> F, unwrapped (eq. 4.46)")
    x23 = Variable(unit="m", doc="foot point F (pole 23), x (eq. 4.44)")
    y23 = Variable(unit="m", doc="foot point F (pole 23), y (eq. 4.45)")
    l2 = Variable(unit="m", doc="distance P2 -> F (eq. 4.39)")

    def __init__(self, K=1, **kw):
        super().__init__(**kw)
        self.K = _check_K(type(self).__name__, K)
        self.ctr2D1 = Frame(required=True, doc="cam plane at P1 (pole 12)")
        self.ctr2D2 = Frame(required=True, doc="spring pivot / nozzle P2 (pole 14)")
        self.ctr2D3 = Frame(doc="material point P3 of the band (to Bandkurve)")
        self.in1 = RealInput(doc="effective lever arm h [m]")

    def guesses(self, context):
        """Start guess of gamma_B: the direction P2 -> P1."""
        g = _direction_guess(context, self.ctr2D2, self.ctr2D1)
        return {} if g is None else {"gamma_B": g}

    def equations(self):
        a, b, p = self.ctr2D1, self.ctr2D2, self.ctr2D3
        band = dbsd_band(a.x, a.y, b.x, b.y, self.in1.u, self.K)
        cg, sg = band["cg"], band["sg"]
        s = self.K * (self.x + self.x0)
        return _zero_flows(a, b) + [
            der(self.x) == self.in1.u * der(a.phi),                           # 4.49
            cg * ca.sin(self.gamma_B) - sg * ca.cos(self.gamma_B) == 0,       # 4.46 unwrapped
            self.l2 == band["l2"], self.x23 == band["x23"], self.y23 == band["y23"],
            p.x == b.x + s * cg, p.y == b.y + s * sg, p.phi == 0]             # 4.47, 4.48

    def shapes(self):
        """The band from the foot point F through P2, P2 as a joint and the
        material point P3."""
        return [{"type": "belt", "points": [["x23", "y23"], ["ctr2D2.x", "ctr2D2.y"]]},
                {"type": "joint", "x": "ctr2D2.x", "y": "ctr2D2.y"},
                {"type": "joint", "x": "ctr2D3.x", "y": "ctr2D3.y"}]
