"""Functional band synthesis (Ebert 2015, ch. 4.3, 5): involute, evolute and the
criteria of ch. 5 as CasADi expressions of the drive parameter, evaluated on
a grid -- exact derivatives by automatic differentiation, no time
integration.

It uses the same band geometry as the elements of
:mod:`acausal2d.library.synthesis` (:func:`dbbd_band`,
:func:`dbsd_band`, :func:`involute`, :func:`band_criteria`) and agrees with
a DB~BD / DB~SD / linkage + Bandkurve model to the integration tolerance.
The dissertation warns that the fourth derivatives of the transfer function a
simulation tool differentiates numerically carry noise (ch. 7.2.2); here
every derivative is exact.

Usage::

    import casadi as ca, numpy as np
    from acausal2d.library.synthesis.functional import BandStructure, synthesize

    s = BandStructure.dbsd(cam_pivot=(0, 0), spring_pivot=(-0.296, 0), K=-1, x0=-0.2,
                           travel=lambda p: 0.05 * p + 0.02 * (1 - ca.cos(p)))
    res = synthesize(s, np.linspace(0.0, 1.5, 301))
    res.x_u, res.y_u          # cam contour in the cam frame (eq. 3.7, 3.8)
    res.criteria["l_Bf"]      # free band length (eq. 5.3)
    print(res.assess().report())

A structure is a :class:`BandStructure`: the material point P3 of the band
(world coordinates) and the cam motion as Python functions of a CasADi
symbol ``p`` (the drive parameter; by default the cam angle itself).
"""
import casadi as ca
import numpy as np

from acausal2d.errors import ModelDefinitionError

from .bandkurve import CRITERIA, band_criteria, involute
from .base import _check_K
from .dbbd import dbbd_band
from .dbsd import dbsd_band
from acausal2d.io.files import write_text
from .assessment import assess

__all__ = ["BandStructure", "BandSynthesis", "synthesize"]


def _identity(p):
    return p


def _at(expr, p, value):
    """``expr`` with the symbol ``p`` replaced by the number ``value``."""
    return ca.substitute(ca.SX(expr), p, ca.SX(float(value)))


class BandStructure:
    """A band mechanism to synthesise: ``point(p) -> (x, y)`` the material
    point P3 of the band in world coordinates, ``cam_pivot`` (x, y) of P1
    (numbers or functions of p), ``cam_angle(p)`` the angle of the cam plane
    (default: p itself) and, for the pre-check of ch. 5.3, ``transfer(p)``
    the prescribed transfer function.  Build it directly for a band fastened
    to any linkage point (Ebert 2015, Bild 4.7: give the point's closed-form
    position, e.g. :func:`acausal2d.library.linkage.vdi_ddd`), or with
    :meth:`dbbd`, :meth:`dbsd`, :meth:`slider`."""

    def __init__(self, point, cam_pivot=(0.0, 0.0), cam_angle=None, transfer=None, name=""):
        self.point = point
        self.cam_pivot = cam_pivot
        self.cam_angle = cam_angle or _identity
        self.transfer = transfer
        self.name = name

    def pivot(self, p):
        """Cam pivot P1 as expressions of p."""
        return tuple(c(p) if callable(c) else ca.SX(float(c)) for c in self.cam_pivot)

    def derivative(self, expr, p, order=1):
        """``order``-th derivative of ``expr`` with respect to the cam angle
        (chain rule through ``cam_angle(p)``; exact, by CasADi)."""
        dc = ca.jacobian(self.cam_angle(p), p)
        out = ca.SX(expr)
        for _ in range(order):
            out = ca.jacobian(out, p) / dc
        return out

    @classmethod
    def dbbd(cls, cam_pivot, roller_pivot, roller_angle, r4, K, x_s0, cam_angle=None, phi0=0.0):
        """DB~BD (Ebert 2015, ch. 4.3.2, eq. 4.2-4.34; element :class:`DB_BD`): cam
        about ``cam_pivot``, circular roller of radius ``r4`` about
        ``roller_pivot`` (both fixed in the ground) whose angle is
        ``roller_angle(p)``; ``K``, ``x_s0`` as the element's; ``phi0`` the
        drive parameter at which x_s = x_s0 (the start of the element's run).
        The ratio i = d roller_angle / d cam_angle comes from CasADi."""
        K = _check_K("BandStructure.dbbd", K)
        cam_angle = cam_angle or _identity

        def point(p):
            x1, y1 = (float(v) for v in cam_pivot)
            x2, y2 = (float(v) for v in roller_pivot)
            i = ca.jacobian(roller_angle(p), p) / ca.jacobian(cam_angle(p), p)     # 4.2
            band = dbbd_band(x1, y1, x2, y2, i, r4, K)
            delta = ca.asin(band["sd"])              # gamma_B - theta (pivots fixed)
            dgamma = delta - _at(delta, p, phi0)                                  # 4.25
            dphi2 = roller_angle(p) - _at(roller_angle(p), p, phi0)               # 4.26
            x_s = x_s0 + K * r4 * (dphi2 - dgamma)                                # 4.24
            return band["x34"] - x_s * band["cg"], band["y34"] - x_s * band["sg"]  # 4.27, 4.28
        return cls(point, cam_pivot, cam_angle, roller_angle, "DB~BD")

    @classmethod
    def dbsd(cls, cam_pivot, spring_pivot, travel, K, x0, cam_angle=None, phi0=0.0):
        """DB~SD (Ebert 2015, ch. 4.3.3, eq. 4.35-4.49; element :class:`DB_SD`): cam
        about ``cam_pivot``, band through ``spring_pivot`` (spring pivot or
        nozzle, fixed in the ground).  ``travel(p)`` is the dissertation's x of eq.
        4.49 (any additive constant; x = travel(p) - travel(phi0)), so the
        lever arm is h = d travel / d cam_angle; ``K``, ``x0`` as the
        element's."""
        K = _check_K("BandStructure.dbsd", K)
        cam_angle = cam_angle or _identity

        def point(p):
            x1, y1 = (float(v) for v in cam_pivot)
            x2, y2 = (float(v) for v in spring_pivot)
            h = ca.jacobian(travel(p), p) / ca.jacobian(cam_angle(p), p)
            band = dbsd_band(x1, y1, x2, y2, h, K)
            s = K * (travel(p) - _at(travel(p), p, phi0) + x0)
            return x2 + s * band["cg"], y2 + s * band["sg"]                        # 4.47, 4.48
        return cls(point, cam_pivot, cam_angle, travel, "DB~SD")

    @classmethod
    def slider(cls, cam_pivot, guide_point, guide_angle, travel, v=0.0, cam_angle=None):
        """DB~DS (Ebert 2015, ch. 7.2.2): the band is fastened to a slider (as
        :class:`~acausal2d.library.linkage.SAN`): ``P = G + x_S e + v n`` with
        G = ``guide_point``, e the guide direction ``guide_angle``, n its left
        normal and ``travel(p)`` the slider travel x_S."""
        c, s = float(np.cos(guide_angle)), float(np.sin(guide_angle))
        gx, gy = (float(q) for q in guide_point)

        def point(p):
            x = travel(p)
            return gx + x * c - v * s, gy + x * s + v * c
        return cls(point, cam_pivot, cam_angle, travel, "DB~DS")


class BandSynthesis:
    """Result of :func:`synthesize` on the grid ``phi`` (drive parameter):

    - ``cam`` cam angle, ``dcam`` its derivative with respect to the drive
      parameter, ``x_P3, y_P3`` the material point (world);
    - ``x_e, y_e`` involute (cam frame BKS, eq. 4.50/4.51), ``d1, d2, d3``
      its derivatives with respect to the cam angle as (n, 2) arrays;
    - ``x_u, y_u`` evolute = cam contour (BKS, eq. 3.7/3.8);
    - ``criteria``: dict of the ch. 5 quantities (:data:`CRITERIA`);
    - ``transfer``: (n, 4) array of the transfer function and its first
      three derivatives with respect to the cam angle (None if the
      structure gives none);
    - ``structure``: the :class:`BandStructure`.

    :meth:`evaluate` evaluates the exact expressions at other parameter
    values; :meth:`evolute_derivatives` gives derivatives of the contour;
    :meth:`table` and :meth:`to_csv` give all of it as a table;
    :meth:`assess` runs the assessment of ch. 5."""

    def __init__(self, structure, phi, fn, deriv_fn):
        self.structure = structure
        self.phi = np.asarray(phi, dtype=float)
        self._fn, self._deriv_fn = fn, deriv_fn
        self._maps = {}
        vals = self.evaluate(self.phi)
        for name in ("cam", "dcam", "x_P3", "y_P3", "x_e", "y_e", "x_u", "y_u"):
            setattr(self, name, vals[name])
        self.d1, self.d2, self.d3 = (np.column_stack([vals["xe%d" % k], vals["ye%d" % k]])
                                     for k in (1, 2, 3))
        self.criteria = {name: vals[name] for name in CRITERIA}
        self.transfer = (np.column_stack([vals["f%d" % k] for k in range(4)])
                         if "f0" in vals else None)

    def evaluate(self, phi):
        """All quantities at the parameter values ``phi`` (dict of arrays)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        out = self._mapped(self._fn, len(phi))(phi.reshape(1, -1))
        names = self._fn.name_out()
        return {n: np.asarray(v).ravel() for n, v in zip(names, out)}

    def evolute_derivatives(self, phi, order=2):
        """(x_u, y_u) and their derivatives with respect to the cam angle up
        to ``order`` (<= 2) at ``phi``: array (len(phi), order + 1, 2)."""
        phi = np.atleast_1d(np.asarray(phi, dtype=float))
        out = self._mapped(self._deriv_fn, len(phi))(phi.reshape(1, -1))
        arr = np.stack([np.asarray(v).ravel() for v in out], axis=1)
        return arr.reshape(len(phi), 3, 2)[:, :order + 1, :]

    def _mapped(self, fn, n):
        key = (fn.name(), n)
        if key not in self._maps:
            self._maps[key] = fn.map(n)
        return self._maps[key]

    def table(self):
        """The synthesis as a table: dict of equally long columns -- drive
        parameter ``phi``, ``cam`` angle, material point ``x_P3, y_P3``
        (world), involute ``x_e, y_e`` and evolute = cam contour ``x_u,
        y_u`` (cam frame) and the ch. 5 quantities of :data:`CRITERIA`."""
        cols = {"phi": self.phi, "cam": self.cam, "x_P3": self.x_P3, "y_P3": self.y_P3,
                "x_e": self.x_e, "y_e": self.y_e, "x_u": self.x_u, "y_u": self.y_u}
        cols.update(self.criteria)
        return cols

    def to_csv(self, path):
        """Write :meth:`table` as CSV (header row of the column names, full
        precision), atomically; returns ``path``."""
        cols = self.table()
        rows = [",".join(cols)] + [",".join("%.17g" % v for v in row)
                                   for row in zip(*cols.values())]
        return write_text(path, "\n".join(rows) + "\n")

    def assess(self, **kw):
        """Assessment of the band curve after Ebert (2015), ch. 5 (see
        :func:`acausal2d.library.synthesis.assessment.assess`)."""
        return assess(self, **kw)


def _expressions(structure, p):
    """Named CasADi expressions of everything :class:`BandSynthesis` holds."""
    x1, y1 = structure.pivot(p)
    xP, yP = structure.point(p)
    cam = structure.cam_angle(p)
    xe, ye = involute(x1, y1, cam, xP, yP)                          # 4.50, 4.51
    e = [ca.vertcat(xe, ye)]
    for k in range(3):                                              # 3.9
        e.append(structure.derivative(e[-1], p))
    (xe1, ye1), (xe2, ye2), (xe3, ye3) = ([d[0], d[1]] for d in e[1:])
    Z = xe1 * ye2 - ye1 * xe2
    E2 = xe1 * xe1 + ye1 * ye1
    xu, yu = xe - ye1 * E2 / Z, ye + xe1 * E2 / Z                   # 3.7, 3.8
    named = {"cam": cam, "dcam": ca.jacobian(cam, p), "x_P3": xP, "y_P3": yP,
             "x_e": xe, "y_e": ye, "x_u": xu, "y_u": yu,
             "xe1": xe1, "ye1": ye1, "xe2": xe2, "ye2": ye2, "xe3": xe3, "ye3": ye3}
    named.update(band_criteria(xe, ye, xe1, ye1, xe2, ye2, xe3, ye3, xu, yu))
    if structure.transfer is not None:
        f = [ca.SX(structure.transfer(p))]
        for k in range(3):
            f.append(structure.derivative(f[-1], p))
        named.update({"f%d" % k: f[k] for k in range(4)})
    return named, (xu, yu)


def synthesize(structure, phi):
    """Band synthesis of ``structure`` (a :class:`BandStructure`) at the
    drive parameter values ``phi`` (increasing); returns a
    :class:`BandSynthesis`.  Involute (eq. 4.50, 4.51), evolute (3.7, 3.8) and
    the criteria of ch. 5 (:func:`band_criteria`) are CasADi expressions of
    the parameter with exact derivatives (3.9); nothing is integrated."""
    phi = np.asarray(phi, dtype=float)
    if phi.ndim != 1 or len(phi) < 2 or np.any(np.diff(phi) <= 0):
        raise ModelDefinitionError("synthesize: phi must be an increasing 1-D grid of at least "
                                   "two values")
    p = ca.SX.sym("p")
    try:
        named, (xu, yu) = _expressions(structure, p)
    except (RuntimeError, TypeError, ValueError) as exc:
        raise ModelDefinitionError("synthesize: building the expressions of %s failed: %s"
                                   % (structure.name or "the structure", exc)) from None
    names = list(named)
    fn = ca.Function("band", [p], [ca.SX(named[n]) for n in names], ["p"], names)
    u = ca.vertcat(xu, yu)
    du = structure.derivative(u, p)
    deriv_fn = ca.Function("evolute_derivatives", [p],
                           [u[0], u[1], du[0], du[1]] + list(ca.vertsplit(
                               structure.derivative(du, p))))
    return BandSynthesis(structure, phi, fn, deriv_fn)
