"""Wiring and start values of belt drives: :func:`connect_band` joins a span
end to a pulley contact, :func:`tangent`/:func:`tangent_any` construct the
common tangents of two wheels (circular or curved), and :func:`belt_layout`
evaluates the tangent construction of all belts of a model at t0 for the
start values of the unwrapped span angles and wrap angles (Ebert 2015, ch. 4.4,
eq. 4.57 without its branch cut).
"""
import math

import numpy as np


from acausal2d.errors import ModelDefinitionError, StartPoseError
from acausal2d.library import planar

from .placement import StartPoses


_PI = math.pi


def _num(comp, name):
    """Numeric value of parameter ``name`` of ``comp`` as a float array."""
    return np.asarray(comp.parameter_value(name), dtype=float)


def connect_band(model, span, end, wheel, contact):
    """Connect end ``end`` (1 or 2) of ``span`` to contact ``contact`` (1 or
    2) of ``wheel`` (a :class:`Pulley` or :class:`Drum`): joins the frame
    ``span.ctr2D<end>`` with ``wheel.ctrK<contact>`` and the band ports
    ``span.ctrB<end>`` with ``wheel.ctrB<contact>``."""
    model.connect(getattr(span, "ctr2D%d" % end), getattr(wheel, "ctrK%d" % contact))
    model.connect(getattr(span, "ctrB%d" % end), getattr(wheel, "ctrB%d" % contact))


def tangent(a, b):
    """Tangent construction for one span.

    ``a`` and ``b`` are ``(cx, cy, rho)``: a circle centre and its signed
    radius ``rho = s*r`` where ``s`` says on which side of the span the
    wheel lies (the contact is at ``C + rho*perp(e)`` at the start and
    ``C - rho*perp(e)`` at the end of the span, ``e`` the span direction,
    ``perp`` the counter-clockwise normal); ``rho = 0`` is a point.
    Returns ``(gamma, l)``: the span angle in (-pi, pi] and the free length."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    rho = a[2] + b[2]
    d2 = dx * dx + dy * dy
    if d2 <= rho * rho:
        raise ModelDefinitionError("no tangent between %r and %r: the wheels overlap" % (a, b))
    l = math.sqrt(d2 - rho * rho)
    g = math.atan2(dy, dx) - math.atan2(rho, l)
    g = math.atan2(math.sin(g), math.cos(g))
    return g, l


def tangent_any(a, b):
    """:func:`tangent` for span ends that may also be curved contours.

    ``a`` and ``b`` are ``(cx, cy, rho)`` tuples as in :func:`tangent` or
    geometry objects of curved wheels (``library/belt_curved.py``) with the
    methods ``approx()`` (an equivalent ``(cx, cy, rho)`` circle) and
    ``support(ux, uy)`` (the world contact point whose outward normal is the
    unit vector ``u``).  Starting from the circle approximation, the span
    angle is refined by fixed-point iteration: contact points for the
    current span direction, new direction from the contact points.  Returns
    ``(gamma, l)`` like :func:`tangent`."""
    if isinstance(a, tuple) and isinstance(b, tuple):
        return tangent(a, b)
    ta = a if isinstance(a, tuple) else a.approx()
    tb = b if isinstance(b, tuple) else b.approx()
    g, l = tangent(ta, tb)

    def end(geo, g, sign):
        px, py = -math.sin(g), math.cos(g)
        if isinstance(geo, tuple):
            return geo[0] + sign * geo[2] * px, geo[1] + sign * geo[2] * py
        return geo.support(sign * geo.side * px, sign * geo.side * py)

    for _ in range(200):
        ax, ay = end(a, g, 1.0)
        bx, by = end(b, g, -1.0)
        g_new = math.atan2(by - ay, bx - ax)
        g_new = g + math.remainder(g_new - g, 2 * _PI)
        l = math.hypot(bx - ax, by - ay)
        if abs(g_new - g) < 1e-13:
            g = g_new
            break
        g = g_new
    else:
        raise ModelDefinitionError("no common tangent found between %r and %r" % (a, b))
    return math.atan2(math.sin(g), math.cos(g)), l


def open_belt_closed_form(r1, r2, d):
    """Closed form of the open belt around two circles (centre distance d):
    wrap angles ``(beta1, beta2)`` = (pi + 2 asin((r1-r2)/d),
    pi - 2 asin((r1-r2)/d)) and free span length sqrt(d^2 - (r1-r2)^2)."""
    a = math.asin((r1 - r2) / d)
    return _PI + 2 * a, _PI - 2 * a, math.sqrt(d * d - (r1 - r2) ** 2)


def _frame_geometry(conn, poses):
    """Initial geometry (cx, cy, rho) of the part a span end is connected to
    (see :func:`tangent`), or None; ``poses``: the model's
    :class:`~acausal2d.library.belt.placement.StartPoses`."""
    owner = conn.owner
    name = conn._name
    if hasattr(owner, "_band_geometry"):        # wheels and rope ends of this library
        return owner._band_geometry(name, poses)
    if isinstance(owner, planar.Fixed):
        r = _num(owner, "r")
        return (float(r[0]), float(r[1]), 0.0)
    if isinstance(owner, planar.Body) and name == "frame_a" \
            and (owner.is_given("x") or owner.is_given("y")):
        return (owner.start_value("x"), owner.start_value("y"), 0.0)
    return None


class Layout:
    """Result of :func:`belt_layout`: ``guesses[id(element)]`` and
    ``params[id(element)]`` map variable / parameter names to values."""

    def __init__(self):
        self.guesses, self.params = {}, {}

    def guess(self, comp, name, value):
        self.guesses.setdefault(id(comp), {})[name] = value

    def param(self, comp, name, value):
        self.params.setdefault(id(comp), {})[name] = value


def _partners(model):
    """partners(conn): the other connectors connected to ``conn``."""
    parent, conns = {}, {}

    def find(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for comp in model.components():
        for a, b in comp._connections:
            for c in (a, b):
                conns[id(c)] = c
                parent.setdefault(id(c), id(c))
            ra, rb = find(id(a)), find(id(b))
            if ra != rb:
                parent[ra] = rb
    groups = {}
    for k in parent:
        groups.setdefault(find(k), []).append(conns[k])

    def partners(conn):
        return [c for c in groups[find(id(conn))] if c is not conn] if id(conn) in parent else []
    return partners


def _nozzle_layout(span, ends, layout):
    a, b, n = ends("ctr2D1"), ends("ctr2D2"), ends("ctr2D3")
    if a is None or b is None or n is None:
        return None
    g1, l1 = tangent_any(a, (n[0], n[1], 0.0))
    g2, l2 = tangent_any((n[0], n[1], 0.0), b)
    for name, val in (("gamma1", g1), ("gamma2", g2), ("l1", l1), ("l2", l2),
                      ("l", l1 + l2), ("l_u", l1 + l2), ("l_u0", l1 + l2)):
        layout.guess(span, name, val)
    return g1, g2 + _PI


def _span_layout(span, ends, layout):
    if span.is_given("gamma"):
        gam = span.start_value("gamma")
        return gam, gam + _PI
    a, b = ends("ctr2D1"), ends("ctr2D2")
    if a is None or b is None:
        return None
    gam, length = _named_tangent(span, ends, a, b)
    layout.guess(span, "gamma", gam)
    names = set(span.variable_names())
    for name in ("l", "l_u", "l_u0", "l_x", "l_x0"):
        if name in names:
            layout.guess(span, name, length)
    return gam, gam + _PI


def _named_tangent(span, ends, a, b):
    """:func:`tangent_any` of a span's two ends; wheels that overlap, or
    that leave no tangent, are refused naming the span and both parts."""
    one, two = ends.owner("ctr2D1"), ends.owner("ctr2D2")
    where = "%s runs from %s to %s" % (span.describe(), one.describe(), two.describe())
    if isinstance(a, tuple) and isinstance(b, tuple) and a[2] and b[2]:
        dist = math.hypot(b[0] - a[0], b[1] - a[1])
        if dist < abs(a[2]) + abs(b[2]):
            raise StartPoseError(      # often: a housing connected to nothing, at the origin
                "%s, which overlap: centre distance %.6g m < sum of the radii %.6g m; move "
                "them apart (x10, y10) or make them smaller (r)" % (where, dist,
                                                                 abs(a[2]) + abs(b[2])))
    try:
        return tangent_any(a, b)
    except ModelDefinitionError as exc:
        raise ModelDefinitionError("%s: %s" % (where, exc)) from None


def _wheel_layout(wheel, g1, g2, layout):
    """Contact-angle guesses and wrap turns of a circular wheel (curved
    wheels compute their own: ``_layout_start``), and the check of its
    half-planes enumHE1/enumHE2 (Tabelle 4.16)."""
    if hasattr(wheel, "_layout_start"):
        guesses, params = wheel._layout_start(g1, g2)
        for name, v in guesses.items():
            layout.guess(wheel, name, v)
        for name, v in params.items():
            layout.param(wheel, name, v)
        return
    w = wheel.w
    if g1 is None:
        return
    k1 = g1 + w * _PI / 2
    wheel._check_half_plane(1, k1)
    if "kappa1" in wheel.variable_names():
        layout.guess(wheel, "kappa1", k1)
    if "kappa2" in wheel.variable_names() and g2 is not None:     # two contacts
        k2 = g2 - w * _PI / 2
        wheel._check_half_plane(2, k2)
        layout.guess(wheel, "kappa2", k2)
        if wheel.is_given("kappa2"):
            k2 = wheel.start_value("kappa2")
        raw = w * (k2 - k1)
        n = float(-math.floor(raw / (2 * _PI)))
        layout.param(wheel, "n_beta", n + 1.0 if raw + 2 * _PI * n == 0.0 else n)


class _SpanEnds:
    """The parts a span's ends are connected to: ``ends(frame_name)`` is
    the start geometry of that end (see :func:`_frame_geometry`) or None,
    ``ends.owner(frame_name)`` the component it belongs to."""

    def __init__(self, span, partners, poses):
        self.span, self.partners, self.poses = span, partners, poses

    def _find(self, frame_name):
        for c in self.partners(getattr(self.span, frame_name)):
            g = _frame_geometry(c, self.poses)
            if g is not None:
                return g, c.owner
        return None, None

    def __call__(self, frame_name):
        return self._find(frame_name)[0]

    def owner(self, frame_name):
        return self._find(frame_name)[1]


def belt_layout(model):
    """Start values and wrap-angle offsets of all belt elements in ``model``
    from the tangent construction at t0 (see the module docstring), as a
    :class:`Layout`; a start value the model gives wins."""
    partners = _partners(model)
    layout = Layout()
    poses = StartPoses(model)

    def end_geometry(span):
        return _SpanEnds(span, partners, poses)

    leaving = {}   # (id(wheel), contact) -> leaving angle at t0
    comps = list(model.components())
    for span in comps:
        if getattr(span, "_layout_kind", None) == "nozzle":
            gams = _nozzle_layout(span, end_geometry(span), layout)
        elif getattr(span, "_layout_kind", None) == "span":
            gams = _span_layout(span, end_geometry(span), layout)
        else:
            continue
        if gams is None:
            continue
        for frame_name, gam in zip(("ctr2D1", "ctr2D2"), gams):
            for c in partners(getattr(span, frame_name)):
                if getattr(c.owner, "_layout_kind", None) == "wheel" \
                        and c._name in ("ctrK1", "ctrK2"):
                    leaving[(id(c.owner), int(c._name[-1]))] = gam
    for wheel in comps:
        if getattr(wheel, "_layout_kind", None) == "wheel":
            xy, params = wheel._axis_start(poses, need=False)
            for name, v in params.items():                          # A.4-A.6
                layout.param(wheel, name, v)
            if xy is not None:
                layout.guess(wheel, "xP1", xy[0])
                layout.guess(wheel, "yP1", xy[1])
            _wheel_layout(wheel, leaving.get((id(wheel), 1)), leaving.get((id(wheel), 2)),
                          layout)
    return layout
