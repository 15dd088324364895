"""Synthesis element DB~BD: cam and circular roller (Ebert 2015, ch. 4.3.2, eq.
4.2-4.34).  :func:`dbbd_band` is the band geometry in the homogeneous pole
form (shared with :mod:`.functional`), :class:`DB_BD` the element; the
corrections of the printed equations are listed in :mod:`acausal2d.library.synthesis`.
"""
import casadi as ca

from acausal2d import Component, der, Frame, Parameter, Variable
from .base import _check_K, _direction_guess, _zero_flows


def dbbd_band(x1, y1, x2, y2, i, r4, K, sqrt=ca.sqrt):
    """Band of DB~BD (Ebert 2015, eq. 4.3-4.23 and 4.29-4.34) in homogeneous pole form.

    Cam pivot P1 = pole 12, roller pivot P2 = pole 14, velocity ratio
    ``i = omega_P2/omega_P1`` (4.2), roller radius ``r4``, mounting ``K``
    (+1: roller contact left of the directed ground line P1 -> P2).  The
    pole 24 = (P1 - i P2)/(1 - i) (4.6-4.8) lies on the band; written with
    the band's unit normal n = (-sin gamma_B, cos gamma_B), the band through
    24 tangent to the roller is ``n . (P2 - P1) = (i - 1) K r4``, i.e.

        sin(gamma_B - theta) = (1 - i) K r4 / l1     (theta: angle of P1 -> P2),

    the roller contact (pole 34) is ``P2 + K r4 n`` and the cam-side pole 23
    = 24 + i (34 - 24) (4.21, 4.22) is ``P1 + i K r4 n``, the foot of the
    perpendicular from P1 (lever arm |i| r4).  This equals the circle
    intersection 4.9-4.18 with the fixes listed in the module docstring for
    i != 1 and the special case 4.29-4.34 at i = 1, without the switch.

    Returns a dict: ``cg, sg`` (cos, sin of gamma_B, direction cam ->
    roller), ``sd`` (sin(gamma_B - theta)), ``x34, y34, x23, y23``."""
    H1, H2 = x2 - x1, y2 - y1                       # 4.3, 4.4
    l1 = sqrt(H1 * H1 + H2 * H2)                    # 4.5
    ux, uy = H1 / l1, H2 / l1
    sd = (1 - i) * K * r4 / l1
    cd = sqrt(1 - sd * sd)
    cg, sg = cd * ux - sd * uy, cd * uy + sd * ux   # 4.23
    nx, ny = -sg, cg
    return {"cg": cg, "sg": sg, "sd": sd,
            "x34": x2 + K * r4 * nx, "y34": y2 + K * r4 * ny,        # 4.17, 4.18 / 4.31, 4.32
            "x23": x1 + i * K * r4 * nx, "y23": y1 + i * K * r4 * ny}  # 4.21, 4.22 / 4.33, 4.34


class DB_BD(Component):
    """Synthesis element DB~BD: cam with a circular roller (Ebert 2015, ch. 4.3.2,
    eq. 4.2-4.34, Tabelle 4.2, 4.3, Bild 4.8, 4.9).

    ``DB_BD(K=1, r4=..., x_s0=...)``.  The cam plane turns about P1 (pole
    12, port ``ctr2D1``: x, y, phi), the circular roller of radius ``r4``
    about P2 (pole 14, port ``ctr2D2``: x, y and its absolute angle phi); the
    band runs from the cam to the roller.  Output ``ctr2D3`` is the material
    point P3 of the band (phi = 0), to be connected to
    ``Bandkurve.ctr2D2``.

    Equations: velocity ratio ``i der(ctr2D1.phi) = der(ctr2D2.phi)`` (4.2);
    band direction, roller contact 34 and cam-side pole 23 from
    :func:`dbbd_band` (homogeneous pole form of 4.3-4.23 and 4.29-4.34);
    unwound length ``x_s = x_s0 + K r4 (dphi_P2 - dgamma_B)`` (4.24 with the
    verified K sign) with ``dgamma_B``, ``dphi_P2`` the changes since the
    start (4.25, 4.26); ``P3 = 34 - x_s e(gamma_B)`` (4.27, 4.28).

    The four mounting variants of Bild 4.9 are the sign of the prescribed
    ratio (open belt i > 0, crossed belt i < 0) times ``K`` (+1: roller
    contact left of the directed ground line P1 -> P2, -1 right; a
    structural constructor argument like a wheel's winding direction).  The
    ratio may pass through i = 1 (band parallel to the ground line).  The
    band must reach the roller: ``|1 - i| r4 < l1``.

    ``gamma_B`` is an unwrapped angle (no atan2): its start guess is the
    direction P1 -> P2 found from the parameters; give ``gamma_B=start(...)``
    when the pivots are not fixed frames of the model.  The dissertation's element
    assumes both pivots in the ground (poles 12 and 14); ``dgamma_B`` then
    only holds the change of the band's inclination.

    Parameters: ``r4`` roller radius, ``x_s0`` initial unwound band length
    (any value selects one involute of the family).  Outputs: ``i``,
    ``gamma_B``, ``x_s``, ``x34, y34``, ``x23, y23``.
    """
    r4 = Parameter(0.05, "m", "roller radius", positive=True)
    x_s0 = Parameter(0.5, "m", "initial unwound band length x_s0 (Anfangsweg)")

    i = Variable(unit="1", doc="velocity ratio omega_P2/omega_P1 (eq. 4.2)")
    gamma_B = Variable(unit="rad", state_select="avoid",
                       doc="band angle, direction cam -> roller, unwrapped (eq. 4.23)")
    gamma_B0 = Variable(unit="rad", state_select="avoid", doc="gamma_B at the start")
    dgamma_B = Variable(fixed=True, unit="rad", doc="change of gamma_B (eq. 4.25)")
    phi_P20 = Variable(unit="rad", state_select="avoid", doc="roller angle at the start")
    dphi_P2 = Variable(fixed=True, unit="rad", doc="change of the roller angle (eq. 4.26)")
    x_s = Variable(unit="m", doc="unwound band length (eq. 4.24)")
    x34 = Variable(unit="m", doc="roller contact, pole 34, x (eq. 4.17)")
    y34 = Variable(unit="m", doc="roller contact, pole 34, y (eq. 4.18)")
    x23 = Variable(unit="m", doc="pole 23 on the band (foot of P1), x (eq. 4.21)")
    y23 = Variable(unit="m", doc="pole 23 on the band (foot of P1), y (eq. 4.22)")

    def __init__(self, K=1, **kw):
        super().__init__(**kw)
        self.K = _check_K(type(self).__name__, K)
        self.ctr2D1 = Frame(required=True, doc="cam plane at P1 (pole 12)")
        self.ctr2D2 = Frame(required=True, doc="roller plane at P2 (pole 14)")
        self.ctr2D3 = Frame(doc="material point P3 of the band (to Bandkurve)")

    def guesses(self, context):
        """Start guess of gamma_B: the direction P1 -> P2 (the band angle
        differs from it by less than 90 degrees)."""
        g = _direction_guess(context, self.ctr2D1, self.ctr2D2)
        return {} if g is None else {"gamma_B": g, "gamma_B0": g}

    def equations(self):
        a, b, p = self.ctr2D1, self.ctr2D2, self.ctr2D3
        K, r4 = self.K, self.r4
        band = dbbd_band(a.x, a.y, b.x, b.y, self.i, r4, K)
        cg, sg = band["cg"], band["sg"]
        return _zero_flows(a, b) + [
            self.i * der(a.phi) == der(b.phi),                               # 4.2
            cg * ca.sin(self.gamma_B) - sg * ca.cos(self.gamma_B) == 0,      # 4.23 unwrapped
            self.x34 == band["x34"], self.y34 == band["y34"],
            self.x23 == band["x23"], self.y23 == band["y23"],
            self.dgamma_B == self.gamma_B - self.gamma_B0, der(self.gamma_B0) == 0,   # 4.25
            self.dphi_P2 == b.phi - self.phi_P20, der(self.phi_P20) == 0,             # 4.26
            self.x_s == self.x_s0 + K * r4 * (self.dphi_P2 - self.dgamma_B),         # 4.24
            p.x == self.x34 - self.x_s * cg, p.y == self.y34 - self.x_s * sg,         # 4.27, 4.28
            p.phi == 0]

    def shapes(self):
        """The band from pole 23 over the roller contact 34 to nowhere else,
        the roller contact as a joint and the material point P3."""
        return [{"type": "belt", "points": [["x23", "y23"], ["x34", "y34"]]},
                {"type": "belt", "points": [["ctr2D3.x", "ctr2D3.y"], ["x23", "y23"]],
                 "color": "#999999"},
                {"type": "joint", "x": "ctr2D3.x", "y": "ctr2D3.y"}]
