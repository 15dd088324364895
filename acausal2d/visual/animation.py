"""Self-contained HTML animations of planar mechanisms.

:func:`render_html` turns a *scene* -- simulation results plus a list of
shapes whose coordinates refer to result signals -- into one HTML page that
animates the mechanism in any web browser.  The page needs no network access:
there are no external scripts, style sheets, fonts or images; the JavaScript
and CSS (package data in ``acausal2d/visual/assets/``) are inlined and the data is embedded as JSON in
``<script id="acausal2d-data" type="application/json">``.

The scene
---------
::

    scene = {
        "title": "Piston engine",
        "time": [t0, t1, ...],                      # floats, non-decreasing
        "signals": {"name": [v0, v1, ...], ...},    # each as long as "time"
        "shapes": [shape, ...],
    }

Every coordinate of a shape (and every other numeric field such as ``r``,
``phi``, ``width`` or ``length``) is either a number (a constant) or a string
naming a signal.  Points are ``[X, Y]`` pairs; angles are in radians,
counter-clockwise, with the y axis pointing up.  Shape kinds:

``{"type": "ground", "x": X, "y": Y, "phi": P}``
    hatched ground symbol of a fixed pivot or support (``phi`` optional,
    default 0: the hatching is below the point).
``{"type": "joint", "x": X, "y": Y}``
    revolute joint, a small white circle.
``{"type": "link", "points": [[X, Y], ...], "width": W}``
    rigid bar through two or more points (``width`` optional, world units;
    default 7 pixels).
``{"type": "body", "x": X, "y": Y, "r": R}``
    a mass, a filled disc (``r`` optional, world units; default 9 pixels).
``{"type": "slider", "x": X, "y": Y, "phi": P, "length": L, "guide": [[X1, Y1], [X2, Y2]]}``
    slider block, a rectangle rotated by ``phi`` (``length`` optional, world
    units; default 38 pixels), drawn on the dashed ``guide`` line (optional);
    ``travel`` (optional): the ends of its travel range, marked on the guide.
``{"type": "pulley", "x": X, "y": Y, "r": R, "phi": P, "contour": [[x, y], ...]}``
    wheel with spokes so that its rotation ``phi`` is visible; the optional
    ``contour`` (constant numbers, in the pulley frame) draws a non-circular
    pulley.
``{"type": "belt", "points": [[X, Y], [X, Y]]}``
    straight belt or rope span (more than two points draw a polyline).
``{"type": "spring", "a": [X, Y], "b": [X, Y]}``
    zig-zag spring between two points.
``{"type": "trace", "x": X, "y": Y}``
    path of a point (e.g. a coupler curve): the whole path faintly plus the
    current point.
``{"type": "label", "x": X, "y": Y, "text": "..."}``
    a text label next to a point.
``{"type": "damper", "a": [X, Y], "b": [X, Y], "offset": O}``
    viscous damper between two points: a pot (open cylinder) from ``a``
    and a piston rod from ``b`` (``offset`` optional, pixels: shifts the
    damper sideways, e.g. beside a spring between the same points).
``{"type": "box", "a": [X, Y], "b": [X, Y], "width": W}``
    a rectangular link from ``a`` to ``b`` with square ends (``width``
    optional, world units; default 12 pixels).
``{"type": "sensor", "points": [[X, Y], ...]}``
    a sensor: a small square mark at each point, a dotted line between
    them (one point: an absolute sensor, two: a relative one).
``{"type": "arrow", "x": X, "y": Y, "fx": FX, "fy": FY, "phi": P, "angle": A, "scale": S, "label": "...", "unit": "N"}``
    a force arrow whose head touches the point (x, y) where it pushes; the
    vector is (fx, fy) turned by ``phi + angle`` (both optional, default
    0: world components).  Its length is ``scale`` world units per unit of
    force, or, without ``scale``, 60 pixels for the largest force of the
    run.  A zero force draws nothing.  With ``label`` the arrow shows the
    label and the force's magnitude in N (in ``unit`` when given: a
    velocity or acceleration vector); ``anchor: "tail"`` starts the arrow
    at the point instead (a vector drawn from where it is measured).
``{"type": "torque", "x": X, "y": Y, "t": T, "scale": S, "label": "..."}``
    a torque as a curved arrow around the point, counter-clockwise for
    t > 0; its sweep grows with |t| up to 300 degrees at the largest
    torque of the run (or at |t| = 1/``scale``).  A zero torque draws
    nothing; ``label`` adds the label and the torque's magnitude in N.m.

``{"type": "pole", "x": X, "y": Y, "text": "P13"}``
    an instantaneous pole (ring and label; left out of the bounding box).

Any shape may also have a ``"color"`` (a CSS colour string) that replaces its
main colour, and a ``"layer"`` name: the page shows a check box per layer.  Other keys are ignored.
A signal value that is NaN (written
as ``null`` in the JSON) hides the shape in that frame.

The page
--------
A canvas (``id="view"``) fills the window and shows the scene with equal
scales in x and y, fitted to the bounding box of all shapes over all frames.
Below it are a play/pause button (``id="play"``), a scrubbing slider
(``id="scrub"``, ``0 .. nframes-1``), a playback speed selector
(``id="speed"``, 0.25x to 4x real time), a loop check box and a time readout
(``id="time"``).  Space toggles playback, the arrow keys step.  The page
starts paused at frame 0, or at frame ``N`` when the URL ends in
``#frame=N`` (it also follows later changes of the fragment); it starts
playing if the scene says ``"autoplay": true`` or the URL has ``?autoplay``
(or ``#autoplay``).  The grid spacing is shown with the scene's length
``"unit"`` (default ``m``).  A scene with ``"plot": {"signal": name,
"label": text}`` shows that signal in a strip under the mechanism
(``id="plot"``) with a cursor at the current time.
For scripting and tests it exposes ``window.acausal2d`` with ``frame`` (the
current frame index), ``nframes``, ``playing``, ``setFrame(i)``, ``play()``,
``pause()``, ``errors`` (messages of uncaught errors on the page) and
``scene`` (the embedded data).

Drag mode (node models)
-----------------------
A scene may carry ``"nodes"``: the description of a node/constraint model
(:meth:`acausal2d.library.nodes.NodeModel.drag_system`: ``nodes`` with
x, y, m, base; ``constraints`` with their length/angle values; ``lentol``,
``itrmax``; ``signals``, the result signals that are node coordinates or
constraint lengths/angles).  The page then offers a "drag" check box
(``id="drag"``): while it is on, playback pauses, the nodes start where the
current frame has them, and grabbing a moving node with the mouse moves
it; after every move the page corrects the positions by Schnabel and Gössner's eq.
3-16 (the position correction of cstr.js, written out in the page's own
script, ``visual/assets/animation_drag.js``), driven values being left to
the hand.  Shapes follow the dragged nodes.  ``window.acausal2d.drag``
exposes ``active``, ``enable()``, ``disable()``, ``positions()`` (world
coordinates), ``screenOf(id)`` (canvas pixels), ``lengths()`` (constraint
lengths), ``move(id, x, y)`` (one drag step: place the node and correct)
and ``last`` (the last correction: iterations, converged).

Long results are subsampled to at most ``max_frames`` frames (default 2000),
evenly in time, always keeping the first and the last sample; numbers are
rounded to 6 significant digits, and only signals used by shapes are embedded.
"""
from typing import Any
import html
import importlib.resources
import json
import math
import numbers
import os
import pathlib

import numpy as np

from ..errors import Acausal2dError
from ..io.files import write_text

__all__ = ["validate_scene", "render_html", "write_html", "SHAPE_TYPES", "MAX_FRAMES"]

MAX_FRAMES = 2000
"""Default upper limit of the number of frames embedded in a page."""

_SIG_DIGITS = 6

# For each shape type: (field, kind, required).  Kinds: "value" (number or
# signal name), "point" ([X, Y]), "points:N" (list of at least N points),
# "guide" (exactly two points), "contour" (constant points), "text".
SHAPE_TYPES = {
    "ground": (("x", "value", True), ("y", "value", True), ("phi", "value", False)),
    "joint": (("x", "value", True), ("y", "value", True)),
    "link": (("points", "points:2", True), ("width", "value", False)),
    "body": (("x", "value", True), ("y", "value", True), ("r", "value", False)),
    "slider": (("x", "value", True), ("y", "value", True), ("phi", "value", True), ("s", "value",
               False), ("length", "value", False), ("guide", "guide", False), ("travel", "guide", False)),
    "pulley": (("x", "value", True), ("y", "value", True), ("r", "value", True),
               ("phi", "value", True), ("contour", "contour", False)),
    "belt": (("points", "points:2", True),),
    "spring": (("a", "point", True), ("b", "point", True)),
    "trace": (("x", "value", True), ("y", "value", True)),
    "pole": (("x", "value", True), ("y", "value", True), ("text", "text", False)),
    "label": (("x", "value", True), ("y", "value", True), ("text", "text", True)),
    "damper": (("a", "point", True), ("b", "point", True), ("offset", "value", False)),
    "box": (("a", "point", True), ("b", "point", True), ("width", "value", False)),
    "sensor": (("points", "points:1", True),),
    "arrow": (("x", "value", True), ("y", "value", True), ("fx", "value", True),
              ("fy", "value", True), ("phi", "value", False), ("angle", "value", False),
              ("scale", "value", False), ("label", "text", False), ("unit", "text", False),
              ("anchor", "text", False)),
    "torque": (("x", "value", True), ("y", "value", True), ("t", "value", True),
               ("scale", "value", False), ("label", "text", False)),
}
"""The shape types a scene may contain and their fields."""

_SCENE_KEYS = ("title", "time", "signals", "shapes")
_NODE_KEYS = ("nodes", "constraints", "signals", "lentol", "itrmax")


# --------------------------------------------------------------------------
# validation

def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, (bool, np.bool_))


def _numeric_array(values, what):
    if isinstance(values, (str, bytes, dict)):
        raise Acausal2dError(f"{what} must be a list of numbers, not {type(values).__name__}")
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise Acausal2dError(f"{what} must be a list of numbers: {exc}") from None
    if arr.ndim != 1:
        raise Acausal2dError(f"{what} must be a one-dimensional list of numbers, "
                             f"got an array of shape {arr.shape}")
    return arr


def _available(signals):
    names = sorted(signals)
    text = ", ".join(repr(n) for n in names[:12])
    if len(names) > 12:
        text += f", ... ({len(names)} signals)"
    return text or "none"


def _check_value(v, where, signals):
    if isinstance(v, str):
        if v not in signals:
            raise Acausal2dError(
                f"{where} refers to signal {v!r}, which is not in scene['signals'] "
                f"(available: {_available(signals)})")
    elif _is_number(v):
        if not math.isfinite(float(v)):
            raise Acausal2dError(f"{where} is {v}; constants must be finite numbers")
    else:
        raise Acausal2dError(f"{where} must be a number or a signal name (string), "
                             f"not {type(v).__name__} {v!r}")


def _check_point(p, where, signals):
    if isinstance(p, (str, bytes, dict)) or not hasattr(p, "__len__") or len(p) != 2:
        raise Acausal2dError(f"{where} must be a point [X, Y], got {p!r}")
    _check_value(p[0], f"{where}[0] (x)", signals)
    _check_value(p[1], f"{where}[1] (y)", signals)


def _check_points(pts, where, signals, minimum, exact=False):
    if isinstance(pts, (str, bytes, dict)) or not hasattr(pts, "__len__"):
        raise Acausal2dError(f"{where} must be a list of points [[X, Y], ...], got {pts!r}")
    if len(pts) < minimum or (exact and len(pts) != minimum):
        need = f"exactly {minimum}" if exact else f"at least {minimum}"
        raise Acausal2dError(f"{where} needs {need} points, got {len(pts)}")
    for j, p in enumerate(pts):
        _check_point(p, f"{where}[{j}]", signals)


def _check_text(v, where, signals):
    if not isinstance(v, str):
        raise Acausal2dError(f"{where} must be a string, not {type(v).__name__}")


_FIELD_CHECKS = {
    "value": _check_value,
    "point": _check_point,
    "guide": lambda v, where, signals: _check_points(v, where, signals, 2, exact=True),
    # no signals in a contour: constants in the pulley frame
    "contour": lambda v, where, signals: _check_points(v, where, {}, 3),
    "text": _check_text,
}
"""Checks of a shape field by its kind (``points:n`` is handled apart)."""


def _check_shape(i, shape, signals):
    if not isinstance(shape, dict):
        raise Acausal2dError(f"shape {i} must be a dict with a 'type', not {type(shape).__name__}")
    kind = shape.get("type")
    if kind not in SHAPE_TYPES:
        raise Acausal2dError(
            f"shape {i} has unknown type {kind!r}; known types: {', '.join(SHAPE_TYPES)}")
    for field, fkind, required in SHAPE_TYPES[kind]:
        if field not in shape or shape[field] is None:
            if required:
                raise Acausal2dError(f"shape {i} ({kind}) is missing the required field {field!r}")
            continue
        where = f"shape {i} ({kind}) field {field!r}"
        if fkind.startswith("points:"):
            _check_points(shape[field], where, signals, int(fkind.split(":")[1]))
        else:
            _FIELD_CHECKS[fkind](shape[field], where, signals)
    if "color" in shape and not isinstance(shape["color"], str):
        raise Acausal2dError(f"shape {i} ({kind}) field 'color' must be a CSS colour string")


def validate_scene(scene):
    """Check that ``scene`` follows the scene contract (see the module
    documentation); return None or raise :class:`~acausal2d.errors.Acausal2dError`.

    Errors name the problem: a missing key, a signal whose length differs
    from ``time``, a shape of unknown type or without a required field, or a
    coordinate naming a signal that does not exist (with the shape index).
    """
    _validated(scene)


def _validated(scene):
    """Validate and return ``(time, signals)`` as float arrays."""
    if not isinstance(scene, dict):
        raise Acausal2dError(f"a scene must be a dict with keys {', '.join(_SCENE_KEYS)}; "
                             f"got {type(scene).__name__}")
    missing = [k for k in _SCENE_KEYS if k not in scene]
    if missing:
        raise Acausal2dError(f"scene is missing the key(s) {', '.join(map(repr, missing))} "
                             f"(a scene needs {', '.join(map(repr, _SCENE_KEYS))})")
    if not isinstance(scene["title"], str):
        raise Acausal2dError("scene['title'] must be a string")
    time = _scene_time(scene["time"])
    signals = _scene_signals(scene["signals"], time.size)
    shapes = scene["shapes"]
    if isinstance(shapes, (str, bytes, dict)) or not hasattr(shapes, "__iter__"):
        raise Acausal2dError("scene['shapes'] must be a list of shape dicts")
    for i, shape in enumerate(shapes):
        _check_shape(i, shape, signals)
    _check_options(scene, signals)
    _check_nodes(scene.get("nodes"))
    return time, signals


def _scene_time(values):
    """scene['time'] as a finite, non-decreasing float array."""
    time = _numeric_array(values, "scene['time']")
    if time.size == 0:
        raise Acausal2dError("scene['time'] is empty; a scene needs at least one sample")
    if not np.all(np.isfinite(time)):
        raise Acausal2dError("scene['time'] contains NaN or infinite values")
    if time.size > 1 and np.any(np.diff(time) < 0):
        k = int(np.argmax(np.diff(time) < 0))
        raise Acausal2dError(f"scene['time'] must be non-decreasing, but time[{k + 1}] = "
                             f"{time[k + 1]} < time[{k}] = {time[k]}")
    return time


def _scene_signals(values, n):
    """scene['signals'] as {name: float array of ``n`` values}."""
    if not isinstance(values, dict):
        raise Acausal2dError("scene['signals'] must be a dict {name: list of values}")
    signals = {}
    for name, column in values.items():
        if not isinstance(name, str):
            raise Acausal2dError(f"signal names must be strings, got {name!r}")
        arr = _numeric_array(column, f"signal {name!r}")
        if arr.size != n:
            raise Acausal2dError(f"signal {name!r} has {arr.size} values but scene['time'] "
                                 f"has {n}; every signal needs one value per time")
        signals[name] = arr
    return signals


def _check_options(scene, signals):
    """The optional scene keys: unit, autoplay, plot."""
    if not isinstance(scene.get("unit", "m"), str):
        raise Acausal2dError("scene['unit'] must be a string such as 'm'")
    if not isinstance(scene.get("autoplay", False), bool):
        raise Acausal2dError("scene['autoplay'] must be true or false")
    plot = scene.get("plot")
    if plot is not None:
        if not isinstance(plot, dict) or not isinstance(plot.get("signal"), str):
            raise Acausal2dError("scene['plot'] must be a dict {'signal': name, 'label': text}")
        _check_value(plot["signal"], "scene['plot']['signal']", signals)


def _check_nodes(nodes):
    """The optional node description of a scene (drag mode)."""
    if nodes is None:
        return
    if not isinstance(nodes, dict) or any(k not in nodes for k in _NODE_KEYS):
        raise Acausal2dError(f"scene['nodes'] must be a dict with the keys "
                             f"{', '.join(_NODE_KEYS)} (NodeModel.drag_system())")
    ids = set()
    for i, n in enumerate(nodes["nodes"]):
        if not isinstance(n, dict) or not isinstance(n.get("id"), str) or \
                not all(_is_number(n.get(k)) for k in ("x", "y")):
            raise Acausal2dError(f"scene['nodes']['nodes'][{i}] needs an id and numbers x, y")
        ids.add(n["id"])
    _check_node_constraints(nodes, ids)


def _check_node_constraints(nodes, ids):
    for i, c in enumerate(nodes["constraints"]):
        ends = [c.get(k) for k in ("n1", "n2", "n3") if k in c] if isinstance(c, dict) else []
        if len(ends) < 2 or any(e not in ids for e in ends):
            raise Acausal2dError(f"scene['nodes']['constraints'][{i}] must join nodes of "
                                 f"scene['nodes']['nodes']")
    try:
        json.dumps(nodes, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise Acausal2dError(f"scene['nodes'] must be plain JSON data: {exc}") from None


# --------------------------------------------------------------------------
# data preparation

def _round(x):
    """Round to 6 significant digits; NaN/inf become None (JSON null)."""
    x = float(x)
    if not math.isfinite(x):
        return None
    return float(f"{x:.{_SIG_DIGITS}g}")


def _round_list(arr):
    return [_round(v) for v in arr]


def _frame_indices(time, max_frames):
    """Indices of at most ``max_frames`` samples, spread evenly in time,
    including the first and the last."""
    n = time.size
    if n <= max_frames:
        return np.arange(n)
    if max_frames < 2:
        raise Acausal2dError("max_frames must be at least 2")
    t0, t1 = time[0], time[-1]
    if t1 > t0:
        targets = np.linspace(t0, t1, max_frames)
        right = np.clip(np.searchsorted(time, targets), 1, n - 1)
        left = right - 1
        idx = np.where(targets - time[left] <= time[right] - targets, left, right)
    else:
        idx = np.round(np.linspace(0, n - 1, max_frames)).astype(int)
    idx = np.unique(np.concatenate(([0], idx, [n - 1])))
    return idx


def _used_signals(shape):
    names = set()

    def walk(v):
        if isinstance(v, str):
            names.add(v)
        elif isinstance(v, (list, tuple)):
            for w in v:
                walk(w)

    for field, fkind, _ in SHAPE_TYPES[shape["type"]]:
        if fkind not in ("text", "contour") and shape.get(field) is not None:
            walk(shape[field])
    return names


def _normalize(value):
    """Constants rounded, signal names kept, points as lists."""
    if isinstance(value, str):
        return value
    if _is_number(value):
        return _round(value)
    return [_normalize(v) for v in value]


def _clean_shape(shape):
    out = {"type": shape["type"]}
    for field, fkind, _ in SHAPE_TYPES[shape["type"]]:
        if shape.get(field) is None:
            continue
        out[field] = shape[field] if fkind == "text" else _normalize(shape[field])
    for key in ("color", "layer"):
        if key in shape:
            out[key] = str(shape[key])
    return out


class _Extent:
    """Running world bounding box of shapes over all frames: points given
    as numbers, signal names or arrays, each with a world-sized radius."""

    def __init__(self, signals, n):
        self.signals, self.n = signals, n
        self.lo, self.hi = [math.inf, math.inf], [-math.inf, -math.inf]

    def val(self, v):
        if isinstance(v, str):
            return self.signals[v]
        if isinstance(v, np.ndarray):
            return v
        return np.full(self.n, np.nan if v is None else float(v))

    def add(self, x, y, rad=0.0):
        rad = np.abs(self.val(rad)) if rad is not None else 0.0
        with np.errstate(invalid="ignore"):
            for d, c in ((0, self.val(x)), (1, self.val(y))):
                a, b = c - rad, c + rad
                if np.any(np.isfinite(a)):
                    self.lo[d] = min(self.lo[d], float(np.nanmin(a)))
                if np.any(np.isfinite(b)):
                    self.hi[d] = max(self.hi[d], float(np.nanmax(b)))

    def box(self):
        if not all(map(math.isfinite, self.lo + self.hi)):
            return [-1.0, -1.0, 1.0, 1.0]
        return [self.lo[0], self.lo[1], self.hi[0], self.hi[1]]


def _extent_of_strip(ext, sh):
    """Links, belts, springs, ...: their points widened by half the width."""
    width = sh.get("width")
    half = 0.0 if width is None else ext.val(width) / 2
    for p in sh.get("points") or (sh["a"], sh["b"]):
        ext.add(p[0], p[1], half)


def _extent_of_slider(ext, sh):
    length = sh.get("length")
    if length is None:
        ext.add(sh["x"], sh["y"])
    else:
        length = ext.val(length)
        ext.add(sh["x"], sh["y"], np.hypot(length / 2, 0.3 * length))
    for p in sh.get("guide") or ():
        ext.add(p[0], p[1])


def _extent_of_pulley(ext, sh):
    rad = np.abs(ext.val(sh["r"]))
    if sh.get("contour"):
        cmax = max(math.hypot(float(c[0]), float(c[1])) for c in sh["contour"])
        rad = np.fmax(rad, cmax)
    ext.add(sh["x"], sh["y"], rad)


_EXTENTS = dict(
    {k: lambda ext, sh: ext.add(sh["x"], sh["y"])
     for k in ("ground", "joint", "trace", "label", "arrow", "torque")},
    body=lambda ext, sh: ext.add(sh["x"], sh["y"], sh.get("r", 0.0)),
    slider=_extent_of_slider, pulley=_extent_of_pulley,
    **{k: _extent_of_strip for k in ("link", "belt", "sensor", "spring", "damper", "box")})
"""How each shape type extends the bounding box."""


def _bbox(shapes, signals, n):
    """World bounding box ``[xmin, ymin, xmax, ymax]`` of all shapes over all
    frames (point extents plus world-sized radii)."""
    ext = _Extent(signals, n)
    for sh in shapes:
        extend = _EXTENTS.get(sh["type"])
        if extend is not None:
            extend(ext, sh)
    return ext.box()


def _scene_data(scene, max_frames):
    time, signals = _validated(scene)
    idx = _frame_indices(time, int(max_frames))
    shapes = [_clean_shape(s) for s in scene["shapes"]]
    used = set()
    for s in scene["shapes"]:
        used |= _used_signals(s)
    plot = scene.get("plot")
    if plot is not None:
        used.add(plot["signal"])
        plot = {"signal": plot["signal"], "label": str(plot.get("label", plot["signal"]))}
    sub = {name: signals[name][idx] for name in sorted(used)}
    bbox = _bbox(shapes, sub, idx.size)
    return {
        "title": scene["title"],
        "time": _round_list(time[idx]),
        "signals": {name: _round_list(v) for name, v in sub.items()},
        "shapes": shapes,
        "bbox": [_round(v) for v in bbox],
        "nframes": int(idx.size),
        "source_samples": int(time.size),
        "unit": scene.get("unit", "m"),
        "autoplay": bool(scene.get("autoplay", False)),
        "plot": plot,
        "nodes": scene.get("nodes"),
    }


def _json_for_script(data):
    """JSON that is safe inside a <script> element."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False, ensure_ascii=False)
    return (text.replace("&", "\\u0026").replace("<", "\\u003c").replace(">", "\\u003e")
            .replace("\u2028", "\\u2028").replace("\u2029", "\\u2029"))


# --------------------------------------------------------------------------
# the page

def render_html(scene: dict[str, Any], *, max_frames: int = MAX_FRAMES) -> str:
    """Return a self-contained HTML page (a string) that animates ``scene``.

    The scene is validated first (see :func:`validate_scene`).  Results
    longer than ``max_frames`` samples are subsampled evenly in time (first and
    last sample kept); numbers are rounded to 6 significant digits.
    """
    data = _scene_data(scene, max_frames)
    title = html.escape(data["title"] or "acausal2d animation")
    template, css, js = (_asset("animation." + ext) for ext in ("html", "css", "js"))
    js += "\n" + _asset("animation_drag.js")
    return (template
            .replace("%%TITLE%%", title)
            .replace("%%SCRUB_MAX%%", str(data["nframes"] - 1))
            .replace("%%CSS%%", css)
            .replace("%%JS%%", js)
            .replace("%%DATA%%", _json_for_script(data)))


def _asset(name):
    """Text of a page asset shipped with the package (``visual/assets``)."""
    return (importlib.resources.files("acausal2d.visual") / "assets" / name).read_text("utf-8")


def write_html(scene, path, **options):
    """Write :func:`render_html` of ``scene`` to ``path`` (UTF-8, parent
    directories created) and return the path as a :class:`pathlib.Path`."""
    path = pathlib.Path(os.fspath(path))
    write_text(path, render_html(scene, **options))
    return path
