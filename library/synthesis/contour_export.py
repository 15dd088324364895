"""Cam contours from a band synthesis: a closed outline to manufacture
(CSV, SVG, DXF -- the dissertation's cams were laser-cut, ch. 7.2.1, 7.2.2) and a
closed :class:`~acausal2d.library.belt.curved.Contour` for the analysis
elements (CurvedDrum, CurvedPulley), which closes the loop synthesis ->
analysis.

Both take a :class:`~acausal2d.library.synthesis.functional.BandSynthesis`: the
synthesised arc is the evolute (x_u, y_u) in the cam frame BKS (origin at
the cam pivot, axes parallel to the world's at cam angle 0).  The band runs
only on that arc; the rest of the disc is free, and two closures are used:

- :func:`cam_outline` (manufacturing): the arc, the two tangents from its
  ends to a hub circle about the pivot and the hub arc between them (or the
  chord between the arc ends where that passes outside the hub); for an arc
  that turns by less than a half turn this is the convex hull of arc and
  hub.  A hub radius below the smallest lever arm keeps the hub inside
  every band line of the range; the closure is checked not to cross the
  arc nor any free band of the range (contact point -> material point), so
  the band touches the plate only on the arc.  The arc is sampled
  adaptively from the exact expressions so that no chord departs from the
  contour by more than ``tol`` (default 1 micrometre).
- :func:`analysis_contour` (simulation): the arc in polar form r(kappa)
  about the pivot, closed over the free angles by a quintic Hermite
  interpolation of ln r (positive, C2 at both ends, from the exact
  derivatives of the evolute), as a table for
  :meth:`Contour.from_table <acausal2d.library.belt.curved.Contour.from_table>`.
  The contour must be star-shaped about the pivot over the arc.

Files are written atomically (temporary file + rename).  Lengths in the
files: CSV in metres; SVG and DXF in millimetres (DXF header ``$INSUNITS`` =
4, mm), the usual unit of laser cutters.
"""
import csv
import math
import os

import numpy as np

from acausal2d.errors import ModelDefinitionError
from acausal2d.io.files import atomic_path, write_text
from acausal2d.library.belt.contour import Contour

__all__ = ["CamOutline", "cam_outline", "analysis_contour", "write_csv", "write_svg",
           "write_dxf", "export_contour"]


# --------------------------------------------------------------------------
# the synthesised arc
# --------------------------------------------------------------------------
def _ccw(syn):
    """+1 if the arc runs counter-clockwise about the pivot with increasing
    phi, -1 if clockwise; raises if it is not star-shaped about the pivot."""
    cross = syn.x_u[:-1] * syn.y_u[1:] - syn.y_u[:-1] * syn.x_u[1:]
    if np.all(cross > 0):
        return 1
    if np.all(cross < 0):
        return -1
    raise ModelDefinitionError("the synthesised contour is not star-shaped about the cam pivot "
                               "(its polar angle turns back); it cannot be closed into a cam "
                               "disc -- see the assessment (GF1, S_Bf)")


def _arc_vertices(syn, tol):
    """Parameter values of the arc vertices such that every chord departs
    from the exact contour by at most ``tol`` (checked at the chord
    midpoints, refined by bisection)."""
    p = np.array(syn.phi, dtype=float)
    for _ in range(30):
        v = syn.evaluate(p)
        pm = 0.5 * (p[1:] + p[:-1])
        m = syn.evaluate(pm)
        ax, ay, bx, by = v["x_u"][:-1], v["y_u"][:-1], v["x_u"][1:], v["y_u"][1:]
        L = np.hypot(bx - ax, by - ay)
        dev = np.abs((bx - ax) * (m["y_u"] - ay) - (by - ay) * (m["x_u"] - ax)) / \
            np.where(L > 0, L, 1.0)
        bad = dev > 0.5 * tol
        if not np.any(bad):
            return p, v
        p = np.sort(np.concatenate([p, pm[bad]]))
    raise ModelDefinitionError("the contour could not be sampled to %g m" % tol)


class CamOutline:
    """A closed cam outline in the cam frame (metres, pivot at the origin):
    ``x, y`` the vertices (counter-clockwise, not repeated at the end),
    ``part`` per vertex ('arc' or 'closure'), ``phi`` the drive parameter of
    the arc vertices (NaN on the closure), ``hub_radius`` and ``tol``."""

    def __init__(self, x, y, part, phi, hub_radius, tol, name=""):
        self.x, self.y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        self.part, self.phi = list(part), np.asarray(phi, dtype=float)
        self.hub_radius, self.tol, self.name = float(hub_radius), float(tol), name

    @property
    def arc(self):
        """(x, y) of the synthesised arc's vertices."""
        k = np.array([p == "arc" for p in self.part])
        return self.x[k], self.y[k]


def _tangent_point(A, r, side):
    """Tangent point on the circle |X| = r seen from A (|A| > r): the one at
    the polar angle of A plus ``side`` * acos(r/|A|)."""
    d = math.hypot(A[0], A[1])
    if d <= r:
        raise ModelDefinitionError("the hub circle (r = %g m) reaches the contour; choose a "
                                   "smaller hub_radius" % r)
    ang = math.atan2(A[1], A[0]) + side * math.acos(r / d)
    return ang


def _closure(A, B, r, n=90):
    """Points from the arc end A (counter-clockwise end) around the hub
    circle of radius r to the arc start B: tangent A -> hub, hub arc, tangent
    hub -> B; or nothing (the chord) when the chord AB passes outside the hub
    with the pivot on the inner side."""
    cross = A[0] * B[1] - A[1] * B[0]      # chord A -> B seen from the pivot
    L = math.hypot(B[0] - A[0], B[1] - A[1])
    if L > 0 and cross > 0 and cross / L >= r:
        return []
    a0 = _tangent_point(A, r, +1)
    a1 = _tangent_point(B, r, -1)
    while a1 <= a0:
        a1 += 2 * math.pi
    k = max(2, int(n * (a1 - a0) / math.pi))
    ang = np.linspace(a0, a1, k)
    return list(zip(r * np.cos(ang), r * np.sin(ang)))


def cam_outline(syn, hub_radius=None, tol=1e-6):
    """Closed manufacturing outline of the synthesised cam (module
    docstring): the arc sampled to ``tol`` [m] plus the closure over a hub
    circle of radius ``hub_radius`` (default: half the smallest lever arm of
    the range).  Returns a :class:`CamOutline`; raises if the closure would
    cross the arc or a free band."""
    sense = _ccw(syn)
    h_min = float(np.min(syn.criteria["h"]))
    r = 0.5 * h_min if hub_radius is None else float(hub_radius)
    if not 0 < r <= h_min:
        raise ModelDefinitionError("hub_radius = %g m must lie in (0, %g m] (the smallest lever "
                                   "arm), else the plate reaches into the band" % (r, h_min))
    p, v = _arc_vertices(syn, tol)
    x, y = v["x_u"], v["y_u"]
    if sense < 0:
        p, x, y = p[::-1], x[::-1], y[::-1]
    close = _closure((x[-1], y[-1]), (x[0], y[0]), r)
    xs = np.concatenate([x, [c[0] for c in close]])
    ys = np.concatenate([y, [c[1] for c in close]])
    part = ["arc"] * len(x) + ["closure"] * len(close)
    phi = np.concatenate([p, np.full(len(close), np.nan)])
    _check_closure(np.column_stack([xs, ys]), len(x),
                   np.column_stack([v["x_u"], v["y_u"]]), np.column_stack([v["x_e"], v["y_e"]]))
    return CamOutline(xs, ys, part, phi, r, tol, syn.structure.name)


def _crossing(P, Q, R, S):
    """True if any segment P[i]Q[i] properly crosses any segment R[j]S[j]."""
    def orient(a, b, c):
        return ((b[..., 0] - a[..., 0]) * (c[..., 1] - a[..., 1])
                - (b[..., 1] - a[..., 1]) * (c[..., 0] - a[..., 0]))
    P, Q = P[:, None, :], Q[:, None, :]
    R, S = R[None, :, :], S[None, :, :]
    d1, d2 = orient(R, S, P), orient(R, S, Q)
    d3, d4 = orient(P, Q, R), orient(P, Q, S)
    return bool(np.any((d1 * d2 < 0) & (d3 * d4 < 0)))


def _check_closure(poly, n_arc, contact, material):
    """The closure segments of the outline ``poly`` (after the first
    ``n_arc`` arc vertices) must not cross the arc nor a free band."""
    closed = np.vstack([poly, poly[:1]])
    C0, C1 = closed[n_arc - 1:-1], closed[n_arc:]
    if _crossing(C0, C1, poly[:n_arc - 1], poly[1:n_arc]) or \
            _crossing(C0, C1, contact, material):
        raise ModelDefinitionError("the closure of the cam plate crosses the contour or a free "
                                   "band of the range; choose another hub_radius")


# --------------------------------------------------------------------------
# closed contour for the analysis elements
# --------------------------------------------------------------------------
def _polar_derivatives(U):
    """r, dr/dkappa, d2r/dkappa2 and kappa' of a curve from its point and
    first two derivatives U (n, 3, 2) with respect to the parameter."""
    u, u1, u2 = U[:, 0], U[:, 1], U[:, 2]
    r = np.hypot(u[:, 0], u[:, 1])
    dot1 = np.sum(u * u1, axis=1)
    cr1 = u[:, 0] * u1[:, 1] - u[:, 1] * u1[:, 0]
    cr2 = u[:, 0] * u2[:, 1] - u[:, 1] * u2[:, 0]
    r1 = dot1 / r
    r2 = (np.sum(u1 * u1, axis=1) + np.sum(u * u2, axis=1)) / r - dot1 ** 2 / r ** 3
    k1 = cr1 / r ** 2
    k2 = cr2 / r ** 2 - 2 * cr1 * dot1 / r ** 4
    return r, r1 / k1, (r2 * k1 - r1 * k2) / k1 ** 3


def _closure_log_radius(t, end_a, end_b, gap, level):
    """ln r over the free angles t in (0, gap): the quintic Hermite
    polynomial matching value, slope and curvature of ln r at the arc end a
    (t = 0) and the arc start b (t = gap), plus the bump 64 x^3 (1 - x)^3
    (x = t/gap; it leaves the end conditions alone) scaled so that the
    closure passes through ``level`` halfway.  One smooth polynomial over the
    gap: its Fourier series converges fast."""
    x = t / gap
    ya, da, ca_ = end_a[0], end_a[1] * gap, end_a[2] * gap ** 2
    yb, db, cb = end_b[0], end_b[1] * gap, end_b[2] * gap ** 2

    def hermite(x):
        return ((1 - 10 * x ** 3 + 15 * x ** 4 - 6 * x ** 5) * ya
                + (x - 6 * x ** 3 + 8 * x ** 4 - 3 * x ** 5) * da
                + 0.5 * (x ** 2 - 3 * x ** 3 + 3 * x ** 4 - x ** 5) * ca_
                + (10 * x ** 3 - 15 * x ** 4 + 6 * x ** 5) * yb
                + (-4 * x ** 3 + 7 * x ** 4 - 3 * x ** 5) * db
                + 0.5 * (x ** 3 - 2 * x ** 4 + x ** 5) * cb)
    return hermite(x) + (level - hermite(0.5)) * 64 * x ** 3 * (1 - x) ** 3


def _polar_table(syn, n_arc, n_gap):
    """(kappa, r) table over one turn: arc samples and the ln r closure
    through 0.8 of the smallest arc radius halfway."""
    sense = _ccw(syn)
    p = np.linspace(syn.phi[0], syn.phi[-1], n_arc)
    U = syn.evolute_derivatives(p, 2)
    kap = np.unwrap(np.arctan2(U[:, 0, 1], U[:, 0, 0]))
    r, R1, R2 = _polar_derivatives(U)
    if sense < 0:
        kap, r, R1, R2 = kap[::-1], r[::-1], R1[::-1], R2[::-1]
    gap = kap[0] + 2 * math.pi - kap[-1]
    if gap <= 0.3:
        raise ModelDefinitionError("the synthesised arc covers %.3g rad of the cam, too much "
                                   "to close it" % (kap[-1] - kap[0]))
    # ln r: value, first and second derivative at the ends
    la = (math.log(r[-1]), R1[-1] / r[-1], R2[-1] / r[-1] - (R1[-1] / r[-1]) ** 2)
    lb = (math.log(r[0]), R1[0] / r[0], R2[0] / r[0] - (R1[0] / r[0]) ** 2)
    t = np.linspace(0.0, gap, n_gap + 2)[1:-1]
    rg = np.exp(_closure_log_radius(t, la, lb, gap, math.log(0.8 * np.min(r))))
    kappa = np.concatenate([kap, kap[-1] + t])
    return kappa, np.concatenate([r, rg]), (kap[0], kap[-1]), sense


class AnalysisContour:
    """Result of :func:`analysis_contour`: ``contour`` (a
    :class:`~acausal2d.library.belt.curved.Contour`), ``kappa_range`` (polar
    angles of the arc ends), ``arc_error`` (largest radial deviation of the
    contour from the exact arc, at the table points and halfway between
    them) and :meth:`kappa`."""

    def __init__(self, contour, kappa_range, arc_error, syn):
        self.contour, self.kappa_range, self.arc_error = contour, kappa_range, arc_error
        self._syn = syn

    def kappa(self, phi):
        """Polar angle (cam frame) of the contact point at the drive
        parameter values ``phi``, on the branch of ``kappa_range``."""
        v = self._syn.evaluate(phi)
        k = np.arctan2(v["y_u"], v["x_u"])
        mid = 0.5 * (self.kappa_range[0] + self.kappa_range[1])
        return k + 2 * math.pi * np.round((mid - k) / (2 * math.pi))


def analysis_contour(syn, n_harm=400, n_arc=800, n_gap=400):
    """Closed contour of the synthesised cam for CurvedDrum/CurvedPulley
    (module docstring): the polar table of the arc (``n_arc`` points) and
    the ln r closure (``n_gap`` points) through
    :meth:`Contour.from_table` with ``n_harm`` harmonics.  Returns an
    :class:`AnalysisContour`."""
    kappa, r, krange, _ = _polar_table(syn, n_arc, n_gap)
    con = Contour.from_table(kappa, r, n_harm=n_harm)
    res = AnalysisContour(con, krange, 0.0, syn)
    pm = np.linspace(syn.phi[0], syn.phi[-1], 2 * n_arc + 1)
    v = syn.evaluate(pm)
    res.arc_error = float(np.max(np.abs(con.r(res.kappa(pm)) - np.hypot(v["x_u"], v["y_u"]))))
    return res


# --------------------------------------------------------------------------
# files
# --------------------------------------------------------------------------
def write_csv(path, outline):
    """CSV of the outline: columns part (pivot / arc / closure), phi (drive
    parameter of arc vertices), x, y in metres in the cam frame; the first
    row is the pivot (0, 0)."""
    with atomic_path(path) as tmp, open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["part", "phi_rad", "x_m", "y_m"])
        w.writerow(["pivot", "", "0", "0"])
        for part, p, x, y in zip(outline.part, outline.phi, outline.x, outline.y):
            w.writerow([part, "" if np.isnan(p) else "%.17g" % p, "%.17g" % x, "%.17g" % y])
    return path


def write_svg(path, outline, margin_mm=5.0):
    """SVG drawing of the outline at 1:1 scale in millimetres (y upwards),
    with the pivot marked by a cross and the hub circle."""
    x, y = outline.x * 1e3, outline.y * 1e3
    xmin, xmax = min(np.min(x), -outline.hub_radius * 1e3), max(np.max(x), 0.0)
    ymin, ymax = min(np.min(y), -outline.hub_radius * 1e3), max(np.max(y), 0.0)
    xmin, ymin, xmax, ymax = xmin - margin_mm, ymin - margin_mm, xmax + margin_mm, ymax + margin_mm
    w, h = xmax - xmin, ymax - ymin
    d = "M " + " L ".join("%.6f,%.6f" % (a, b) for a, b in zip(x, y)) + " Z"
    c = 0.15 * outline.hub_radius * 1e3 + 1.0
    text = "\n".join([
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<svg xmlns="http://www.w3.org/2000/svg" width="%.3fmm" height="%.3fmm" '
        'viewBox="%.6f %.6f %.6f %.6f">' % (w, h, xmin, -ymax, w, h),
        '<title>cam contour %s (cam frame, mm, pivot at the origin)</title>' % outline.name,
        '<g transform="scale(1,-1)" fill="none" stroke-linecap="round">',
        '<path id="contour" d="%s" fill="#dde6f0" stroke="#1f4e79" stroke-width="0.3"/>' % d,
        '<circle id="hub" cx="0" cy="0" r="%.6f" stroke="#888888" stroke-width="0.15" '
        'stroke-dasharray="1,1"/>' % (outline.hub_radius * 1e3),
        '<path id="pivot" d="M %.3f,0 L %.3f,0 M 0,%.3f L 0,%.3f" stroke="#c00000" '
        'stroke-width="0.3"/>' % (-c, c, -c, c),
        '</g>', '</svg>', ""])

    return write_text(path, text)


def write_dxf(path, outline):
    """DXF (R2010, millimetres) of the outline: a closed LWPOLYLINE on layer
    CONTOUR, the pivot as a POINT with a cross and the hub circle on layer
    PIVOT.  Written with ezdxf."""
    import ezdxf
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4           # millimetres
    doc.layers.add("CONTOUR", color=5)
    doc.layers.add("PIVOT", color=1)
    msp = doc.modelspace()
    pts = [(float(a) * 1e3, float(b) * 1e3) for a, b in zip(outline.x, outline.y)]
    msp.add_lwpolyline(pts, format="xy", close=True, dxfattribs={"layer": "CONTOUR"})
    c = 0.15 * outline.hub_radius * 1e3 + 1.0
    msp.add_point((0.0, 0.0), dxfattribs={"layer": "PIVOT"})
    msp.add_line((-c, 0.0), (c, 0.0), dxfattribs={"layer": "PIVOT"})
    msp.add_line((0.0, -c), (0.0, c), dxfattribs={"layer": "PIVOT"})
    msp.add_circle((0.0, 0.0), outline.hub_radius * 1e3, dxfattribs={"layer": "PIVOT"})
    with atomic_path(path) as tmp:
        doc.saveas(tmp)
    return path


def export_contour(syn, folder, name, hub_radius=None, tol=1e-6):
    """Write ``<name>.csv``, ``<name>.svg`` and ``<name>.dxf`` of the cam
    outline of ``syn`` (:func:`cam_outline`) into ``folder``; returns the
    list of paths."""
    outline = cam_outline(syn, hub_radius, tol)
    base = os.path.join(folder, name)
    return [write_csv(base + ".csv", outline), write_svg(base + ".svg", outline),
            write_dxf(base + ".dxf", outline)]
