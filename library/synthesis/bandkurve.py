"""Bandkurve (Ebert 2015, ch. 4.3.4, eq. 4.50/4.51 with 3.7-3.9): the involute of the
material point by kinematic inversion about the cam axis, its evolute (the
cam contour) and, optionally, the criteria of Ebert (2015), ch. 5 (eq. 5.1-5.17).
:func:`involute`, :func:`evolute_terms` and :func:`band_criteria` are shared
with :mod:`.functional`.
"""
import casadi as ca

from acausal2d import Component, der, Frame, Variable
from .base import _zero_flows


def involute(xP1, yP1, phiP1, xP2, yP2, cos=ca.cos, sin=ca.sin):
    """Involute point (x_e, y_e) in the cam frame BKS: the material point P2
    turned back about the cam pivot P1 by -phi_P1 (Ebert 2015, eq. 4.50, 4.51)."""
    dx, dy = xP2 - xP1, yP2 - yP1
    c, s = cos(phiP1), sin(phiP1)
    return c * dx + s * dy, -s * dx + c * dy


def evolute_terms(xe1, ye1, xe2, ye2):
    """(Z, E2) of the evolute (Ebert 2015, eq. 3.7, 3.8): ``Z = x_e' y_e'' - y_e'
    x_e''`` (= GF1, eq. 5.7) and ``E2 = x_e'^2 + y_e'^2``; the evolute is
    ``x_u = x_e - y_e' E2/Z``, ``y_u = y_e + x_e' E2/Z``."""
    return xe1 * ye2 - ye1 * xe2, xe1 * xe1 + ye1 * ye1


CRITERIA = ("Z", "N", "rho_k", "l_Bf", "GF2", "dl_Bf", "S_Bf", "a", "h", "u_PS", "v_PS",
            "rho_cam")
"""Names of the ch. 5 quantities of :func:`band_criteria` (outputs of
:class:`Bandkurve` with ``criteria=True``)."""


def band_criteria(xe, ye, xe1, ye1, xe2, ye2, xe3, ye3, xu, yu, sqrt=ca.sqrt, fabs=ca.fabs,
                  sign=ca.sign):
    """The geometric quantities of Ebert (2015), ch. 5 from the involute (x_e, y_e),
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
      the dissertation's fourth)."""
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


class Bandkurve(Component):
    """Synthesis element Bandkurve: involute and evolute (cam contour) of a
    material point of the band (Ebert 2015, ch. 4.3.4, eq. 4.50, 4.51 with 3.7-3.9,
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

    With ``criteria=True`` (Ebert 2015, end of 4.3.4, ch. 5; all finite product
    forms):

    - ``Z`` = GF1 (5.7), ``N = E2^(3/2)``, curvature ``rho_k N = Z`` (5.2);
    - free band length ``l_Bf |Z| = N`` (5.1, 5.3: |r_k|);
    - ``GF2 = Z' N - Z N'`` (5.9) with ``Z' = x_e1 y_e3 - y_e1 x_e3``,
      ``N' = 3 E2^(1/2) (x_e1 x_e2 + y_e1 y_e2)``;
    - ``dl_Bf`` = l_Bf' (5.10) from ``dl_Bf Z |Z| = -GF2`` (exact
      derivative of N/|Z|), and the flag ``S_Bf = sign(dl_Bf)`` (5.11): a
      relation, so every sign change is an event of the run (the dissertation's
      comparison with the previous value; C0 and C1 breaks of the contour
      show as such a change);
    - space ``a = |(x_u, y_u)|`` (5.12);
    - effective lever arm ``h`` (5.13-5.15, reconstructed): distance from the
      cam axis to the band line, which is the involute's normal through
      (x_e, y_e): ``h E2^(1/2) = |x_e x_e1 + y_e y_e1|``, foot point ``u_PS,
      v_PS`` = ((e.e')/E2) e';
    - radius of curvature of the cam contour (5.17) ``rho_cam |Z| = |dl_Bf|
      E2`` (the evolute's arc length is the change of l_Bf; third instead of
      the dissertation's fourth derivatives).

    The band stresses (5.16-5.18) need the band force: see
    :mod:`acausal2d.library.synthesis.assessment`, which also gives the report.
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
        """Ebert (2015), ch. 5 quantities (:func:`band_criteria`), explicit in the
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
