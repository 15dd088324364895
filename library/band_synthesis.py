"""Synthesis of band mechanisms (seed ch. 4.3): the elements DB~BD, DB~SD and
Bandkurve, and the band geometry they share with the functional API
(:mod:`acausal2d.library.band_functional`).

Concept (seed ch. 4.3 intro, 4.3.1)
-----------------------------------
Synthesis is purely kinematic.  The inversion is split in two phases: an
element computes, in world coordinates, the path of a material point P3 of
the band ("Spurpunkt") from the prescribed motions of the cam plane and of
the output link; :class:`Bandkurve` turns that path back about the cam axis
(the involute, "Evolvente", eq. 4.50/4.51) and computes its evolute, the
sought cam contour ("Bandkurve", eq. 3.7/3.8).  Every mechanical port
transmits no force and no torque (seed Tabelle 4.3, 4.5, 4.7).

- :class:`DB_BD` -- cam and circular roller ("DB~BD", eq. 4.2-4.34);
- :class:`DB_SD` -- cam and a tension spring in the band or a draw-off
  nozzle ("DB~SD", eq. 4.35-4.49);
- :class:`Bandkurve` -- involute, evolute and optionally the criteria of
  seed ch. 5 (eq. 5.1-5.17).

A band fastened to a rocker, a slider or a coupler point of any linkage
(seed Bild 4.7; DB~DS, DBDD structures) needs no special element: connect
that point's frame of the linkage model (e.g. ``SAN.ctr2D2``,
``DDD.ctr2D3`` with an FGP for a coupler point) directly to
``Bandkurve.ctr2D2`` -- the point *is* the material point of the band.

Ports and flows
---------------
Input ports (``ctr2D1``, ``ctr2D2`` of DB~BD and DB~SD, both ports of
Bandkurve) must be connected; the element reads their potentials and sets
their flows to zero (no reaction on the mechanism that prescribes the
motion).  The output port ``ctr2D3`` of DB~BD / DB~SD prescribes the
material point (x, y, phi = 0); its flows come from the connection, i.e.
zero when it is connected to Bandkurve.  Prescribe the motions with the
library's drives, e.g. the cam plane (the seed's preset "Drehpunkt A0") as
``planar.Fixed`` + ``planar.Revolute(use_flange=True)`` driven by a
``linkage_drives.Preset`` or ``rotational.Position``, and a ground point
(spring pivot "Drehpunkt B0") as ``planar.Fixed``.

The cam must turn (``der(ctr2D1.phi) != 0``): the derivatives with respect
to the cam angle are ``der(x)/der(phi_P1)`` (seed ch. 4.3.4: the cam is
driven at constant speed, 1 rad/s in example 7.2.1).  The prescribed motions
must be C2 for the evolute and C3 for the criteria of ch. 5 (the compiler
differentiates them exactly; the seed's fourth derivatives for the radius
of curvature of the cam are avoided, see :class:`Bandkurve`).

Differences from the printed equations (verified numerically against the
spec transcription ``spec_synthesis.md`` and its checks)
-----------------------------------------------------------------------
- DB~BD: 4.12 ``H6 = sqrt(H5 - r4^2)``, 4.13 ``H7 = H6^2 - r4^2 + H5``, 4.16
  ``H10 = ...``, the swapped H13/H14 of 4.31-4.34 and the K-signed 4.24
  ``x_s = x_s0 + K r4 (dphi_P2 - dgamma_B)``.  The pole construction
  4.6-4.22 and the special case 4.29-4.34 are replaced by their common
  homogeneous form (:func:`dbbd_band`): no switch, no singularity at i = 1.
- DB~SD: 4.37 ``H3 = H1^2 + H2^2`` and the K-signed 4.47/4.48 ``P3 = P2 +
  K (x + x0) e(gamma_B)``; 4.39-4.46 in explicit form (:func:`dbsd_band`),
  smooth through h = 0 (no sign(h) relation).
"""
import math

import casadi as ca
import numpy as np

from acausal2d import Component, der, Frame, Parameter, RealInput, Variable
from acausal2d.errors import ModelDefinitionError

__all__ = ["DB_BD", "DB_SD", "Bandkurve", "dbbd_band", "dbsd_band", "involute",
           "evolute_terms", "band_criteria", "CRITERIA", "start_xy"]


# --------------------------------------------------------------------------
# geometry shared with the functional API (CasADi expressions or numpy)
# --------------------------------------------------------------------------
def _check_K(owner, K):
    if K not in (1, -1):
        raise ModelDefinitionError("%s: mounting parameter K must be +1 or -1, got %r"
                                   % (owner, K))
    return K


def dbbd_band(x1, y1, x2, y2, i, r4, K, sqrt=ca.sqrt):
    """Band of DB~BD (seed eq. 4.3-4.23 and 4.29-4.34) in homogeneous pole form.

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


def dbsd_band(x1, y1, x2, y2, h, K, sqrt=ca.sqrt):
    """Band of DB~SD (seed eq. 4.35-4.46) in explicit form.

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


def involute(xP1, yP1, phiP1, xP2, yP2, cos=ca.cos, sin=ca.sin):
    """Involute point (x_e, y_e) in the cam frame BKS: the material point P2
    turned back about the cam pivot P1 by -phi_P1 (seed eq. 4.50, 4.51)."""
    dx, dy = xP2 - xP1, yP2 - yP1
    c, s = cos(phiP1), sin(phiP1)
    return c * dx + s * dy, -s * dx + c * dy


def evolute_terms(xe1, ye1, xe2, ye2):
    """(Z, E2) of the evolute (seed eq. 3.7, 3.8): ``Z = x_e' y_e'' - y_e'
    x_e''`` (= GF1, eq. 5.7) and ``E2 = x_e'^2 + y_e'^2``; the evolute is
    ``x_u = x_e - y_e' E2/Z``, ``y_u = y_e + x_e' E2/Z``."""
    return xe1 * ye2 - ye1 * xe2, xe1 * xe1 + ye1 * ye1


CRITERIA = ("Z", "N", "rho_k", "l_Bf", "GF2", "dl_Bf", "S_Bf", "a", "h", "u_PS", "v_PS",
            "rho_cam")
"""Names of the ch. 5 quantities of :func:`band_criteria` (outputs of
:class:`Bandkurve` with ``criteria=True``)."""


def band_criteria(xe, ye, xe1, ye1, xe2, ye2, xe3, ye3, xu, yu, sqrt=ca.sqrt, fabs=ca.fabs,
                  sign=ca.sign):
    """The geometric quantities of seed ch. 5 from the involute (x_e, y_e),
    its first three derivatives with respect to the cam angle and the
    evolute (x_u, y_u): CasADi expressions, or numpy arrays with
    ``sqrt=np.sqrt, fabs=np.abs, sign=np.sign``.  Returns a dict with the
    keys :data:`CRITERIA` (e' = (x_e', y_e'), E2 = |e'|^2):

    - ``Z`` = GF1 (eq. 5.7), ``N = E2^(3/2)``, curvature of the involute
      ``rho_k = Z/N`` (5.2);
    - free band length ``l_Bf = |r_k| = N/|Z|`` (5.1, 5.3);
    - ``GF2 = Z' N - Z N'`` (5.9) with ``Z' = x_e' y_e(3) - y_e' x_e(3)`` and
      ``N' = 3 E2^(1/2) (x_e' x_e'' + y_e' y_e'')``;
    - ``dl_Bf`` = dl_Bf/dphi = -GF2/(Z |Z|) (5.10, the exact derivative of
      N/|Z|) and ``S_Bf = sign(dl_Bf)`` (5.11);
    - space ``a = |(x_u, y_u)|`` (5.12);
    - effective lever arm ``h`` (5.13-5.15, reconstructed): the band is the
      involute's normal through (x_e, y_e), so its distance from the cam
      axis is ``|e . e'| / E2^(1/2)`` and the foot point PS is ``(u_PS,
      v_PS) = ((e . e')/E2) e'``;
    - radius of curvature of the cam contour (5.17) ``rho_cam = |dl_Bf|
      E2/|Z|``: the evolute's arc length is the change of l_Bf and its
      tangent turns with the involute's normal (third derivatives instead of
      the seed's fourth)."""
    Z, E2 = evolute_terms(xe1, ye1, xe2, ye2)
    root = sqrt(E2)
    N = E2 * root
    GF2 = (xe1 * ye3 - ye1 * xe3) * N - Z * 3 * root * (xe1 * xe2 + ye1 * ye2)
    dl = -GF2 / (Z * fabs(Z))
    proj = xe * xe1 + ye * ye1
    return {"Z": Z, "N": N, "rho_k": Z / N, "l_Bf": N / fabs(Z), "GF2": GF2, "dl_Bf": dl,
            "S_Bf": sign(dl), "a": sqrt(xu * xu + yu * yu), "h": fabs(proj) / root,
            "u_PS": proj * xe1 / E2, "v_PS": proj * ye1 / E2,
            "rho_cam": fabs(dl) * E2 / fabs(Z)}


# --------------------------------------------------------------------------
# start positions for the unwrapped band angles
# --------------------------------------------------------------------------
def _pose_assembly(context):
    """The linkage pre-assembly (library/linkage.py) extended across
    planar.Revolute (same point on both frames) and planar.FixedTranslation."""
    from acausal2d.library import planar
    from acausal2d.library.linkage import _Assembly
    asm = context.shared("linkage assembly", lambda: _Assembly(context))
    comps = list(context.model.components())
    for _ in range(len(comps)):
        progress = False
        for comp in comps:
            if isinstance(comp, planar.Revolute):
                progress |= _copy_xy(asm, comp.frame_a, comp.frame_b)
                progress |= _copy_xy(asm, comp.frame_b, comp.frame_a)
            elif isinstance(comp, planar.FixedTranslation):
                a = asm.get(comp.frame_a)
                b = asm.get(comp.frame_b)
                if a and all(k in a for k in ("x", "y", "phi")) and not (b and "x" in b):
                    c, s = ca.cos(a["phi"]), ca.sin(a["phi"])
                    asm.put(comp.frame_b, {"x": a["x"] + c * comp.r[0] - s * comp.r[1],
                                           "y": a["y"] + s * comp.r[0] + c * comp.r[1],
                                           "phi": a["phi"]})
                    progress = True
        if not progress:
            break
    return asm


def _copy_xy(asm, src, dst):
    a, b = asm.get(src), asm.get(dst)
    if a and "x" in a and "y" in a and not (b and "x" in b):
        asm.put(dst, {"x": a["x"], "y": a["y"]})
        return True
    return False


def start_xy(context, conn):
    """Numeric start position (x, y) of the frame ``conn`` from the
    parameters (fixed frames, linkage pre-assembly, revolute joints), or
    None when it cannot be found without solving the model."""
    asm = context.shared("band synthesis poses", lambda: _pose_assembly(context))
    vals = asm.get(conn)
    if not vals or "x" not in vals or "y" not in vals:
        return None
    x, y = context.evaluate([vals["x"], vals["y"]])
    return float(x), float(y)


def _direction_guess(context, a, b):
    """Angle of the direction a -> b at the start, or None."""
    pa, pb = start_xy(context, a), start_xy(context, b)
    if pa is None or pb is None or (pa[0] == pb[0] and pa[1] == pb[1]):
        return None
    return math.atan2(pb[1] - pa[1], pb[0] - pa[0])


def _zero_flows(*frames):
    out = []
    for f in frames:
        out += [f.fx == 0, f.fy == 0, f.t == 0]
    return out


# --------------------------------------------------------------------------
# elements
# --------------------------------------------------------------------------
class DB_BD(Component):
    """Synthesis element DB~BD: cam with a circular roller (seed ch. 4.3.2,
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
    when the pivots are not fixed frames of the model.  The seed's element
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


class DB_SD(Component):
    """Synthesis element DB~SD: cam with a tension spring in the band or a
    draw-off nozzle (seed ch. 4.3.3, eq. 4.35-4.49, Tabelle 4.4, 4.5, Bild
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


class Bandkurve(Component):
    """Synthesis element Bandkurve: involute and evolute (cam contour) of a
    material point of the band (seed ch. 4.3.4, eq. 4.50, 4.51 with 3.7-3.9,
    Tabelle 4.6, 4.7, Bild 4.11); optionally the criteria of ch. 5.

    ``Bandkurve(criteria=False)``.  Ports: ``ctr2D1`` the cam plane (x_P1,
    y_P1, phi_P1), ``ctr2D2`` the material point of the band (x_P2, y_P2;
    from DB~BD/DB~SD ``ctr2D3`` or any linkage point).  No parameters; all
    flows zero.  Coordinates in the cam frame BKS: origin P1, axes turned
    with the cam so that they are parallel to the world axes at phi_P1 = 0
    (the frame in which the cam contour is drawn and cut).

    Equations: involute ``x_e, y_e`` (4.50, 4.51, :func:`involute`); its
    derivatives with respect to the cam angle (3.9) from the compiler's
    exact time derivatives, ``der(x_e) = x_e1 der(phi_P1)``, ``der(x_e1) =
    x_e2 der(phi_P1)`` (and ``x_e3`` with criteria); evolute (3.7, 3.8) in
    the product form ``Z (x_u - x_e) = -y_e1 E2``, ``Z (y_u - y_e) = x_e1 E2``
    (:func:`evolute_terms`; Z = GF1).  ``xK, yK``: the contact point in the
    world (the evolute point turned forward).

    With ``criteria=True`` (seed end of 4.3.4, ch. 5; all finite product
    forms):

    - ``Z`` = GF1 (5.7), ``N = E2^(3/2)``, curvature ``rho_k N = Z`` (5.2);
    - free band length ``l_Bf |Z| = N`` (5.1, 5.3: |r_k|);
    - ``GF2 = Z' N - Z N'`` (5.9) with ``Z' = x_e1 y_e3 - y_e1 x_e3``,
      ``N' = 3 E2^(1/2) (x_e1 x_e2 + y_e1 y_e2)``;
    - ``dl_Bf`` = l_Bf' (5.10) from ``dl_Bf Z |Z| = -GF2`` (exact
      derivative of N/|Z|), and the flag ``S_Bf = sign(dl_Bf)`` (5.11): a
      relation, so every sign change is an event of the run (the seed's
      comparison with the previous value; C0 and C1 breaks of the contour
      show as such a change);
    - space ``a = |(x_u, y_u)|`` (5.12);
    - effective lever arm ``h`` (5.13-5.15, reconstructed): distance from the
      cam axis to the band line, which is the involute's normal through
      (x_e, y_e): ``h E2^(1/2) = |x_e x_e1 + y_e y_e1|``, foot point ``u_PS,
      v_PS`` = ((e.e')/E2) e';
    - radius of curvature of the cam contour (5.17) ``rho_cam |Z| = |dl_Bf|
      E2`` (the evolute's arc length is the change of l_Bf; third instead of
      the seed's fourth derivatives).

    The band stresses (5.16-5.18) need the band force: see
    :mod:`acausal2d.library.band_assessment`, which also gives the report.
    """
    xe = Variable(unit="m", doc="involute x_e in BKS (eq. 4.50)")
    ye = Variable(unit="m", doc="involute y_e in BKS (eq. 4.51)")
    xe1 = Variable(unit="m", doc="dx_e/dphi (eq. 3.9)")
    ye1 = Variable(unit="m", doc="dy_e/dphi (eq. 3.9)")
    xe2 = Variable(unit="m", doc="d2x_e/dphi2 (eq. 3.9)")
    ye2 = Variable(unit="m", doc="d2y_e/dphi2 (eq. 3.9)")
    xu = Variable(unit="m", doc="evolute = cam contour x_u in BKS (eq. 3.7)")
    yu = Variable(unit="m", doc="evolute = cam contour y_u in BKS (eq. 3.8)")
    xK = Variable(unit="m", doc="contact point (evolute point) in the world, x")
    yK = Variable(unit="m", doc="contact point (evolute point) in the world, y")

    _CRITERIA = (("xe3", "m", "d3x_e/dphi3"), ("ye3", "m", "d3y_e/dphi3"),
                 ("Z", "m2", "GF1 = Z (eq. 5.7)"), ("N", "m3", "N (eq. 5.2)"),
                 ("rho_k", "1/m", "curvature of the involute (eq. 5.2)"),
                 ("l_Bf", "m", "free band length |r_k| (eq. 5.3)"),
                 ("GF2", "m5", "GF2 = Z'N - ZN' (eq. 5.9)"),
                 ("dl_Bf", "m", "change of the free band length dl_Bf/dphi (eq. 5.10)"),
                 ("S_Bf", "1", "sign of dl_Bf (eq. 5.11)"),
                 ("a", "m", "distance contact point - cam axis (eq. 5.12)"),
                 ("h", "m", "effective lever arm (eq. 5.13)"),
                 ("u_PS", "m", "foot point PS in BKS, u (eq. 5.14)"),
                 ("v_PS", "m", "foot point PS in BKS, v (eq. 5.15)"),
                 ("rho_cam", "m", "radius of curvature of the cam contour (eq. 5.17)"))

    def __init__(self, criteria=False, **kw):
        super().__init__(**kw)
        self.criteria = bool(criteria)
        # start guesses off the singular points of the evolute (Z = 0) and
        # of |(x_u, y_u)|; Newton finds the consistent values from there
        for name, value in (("xe1", 1.0), ("ye2", 1.0), ("xu", 0.1)):
            self.variable(name).start = value
        if self.criteria:
            for name, unit, doc in self._CRITERIA:
                self.add_variable(name, unit=unit, doc=doc)
        self.ctr2D1 = Frame(required=True, doc="cam plane at P1")
        self.ctr2D2 = Frame(required=True, doc="material point of the band P2")

    def equations(self):
        a, b = self.ctr2D1, self.ctr2D2
        w = der(a.phi)
        xe, ye = involute(a.x, a.y, a.phi, b.x, b.y)
        Z, E2 = evolute_terms(self.xe1, self.ye1, self.xe2, self.ye2)
        c, s = ca.cos(a.phi), ca.sin(a.phi)
        eqs = _zero_flows(a, b) + [
            self.xe == xe, self.ye == ye,                                     # 4.50, 4.51
            der(self.xe) == self.xe1 * w, der(self.ye) == self.ye1 * w,       # 3.9
            der(self.xe1) == self.xe2 * w, der(self.ye1) == self.ye2 * w,
            Z * (self.xu - self.xe) == -self.ye1 * E2,                        # 3.7
            Z * (self.yu - self.ye) == self.xe1 * E2,                         # 3.8
            self.xK == a.x + c * self.xu - s * self.yu,
            self.yK == a.y + s * self.xu + c * self.yu]
        if self.criteria:
            eqs += self._criteria_equations()
        return eqs

    def _criteria_equations(self):
        """Seed ch. 5 quantities (:func:`band_criteria`), explicit in the
        involute's derivatives (not in the output variables), so that the
        outputs do not couple back into the initialization."""
        crit = band_criteria(self.xe, self.ye, self.xe1, self.ye1, self.xe2, self.ye2,
                             self.xe3, self.ye3, self.xu, self.yu)
        w = der(self.ctr2D1.phi)
        return ([der(self.xe2) == self.xe3 * w, der(self.ye2) == self.ye3 * w]
                + [getattr(self, name) == crit[name] for name in CRITERIA])

    def shapes(self):
        """The free band from the contact point to the material point, the
        contact point and the path of the material point (k_PS, Bild 7.11)."""
        return [{"type": "belt", "points": [["xK", "yK"], ["ctr2D2.x", "ctr2D2.y"]]},
                {"type": "trace", "x": "ctr2D2.x", "y": "ctr2D2.y"},
                {"type": "joint", "x": "xK", "y": "yK"}]
