"""Self-contained HTML animations of planar mechanisms.

:func:`render_html` turns a *scene* -- simulation results plus a list of
shapes whose coordinates refer to result signals -- into one HTML page that
animates the mechanism in any web browser.  The page needs no network access:
there are no external scripts, style sheets, fonts or images; the JavaScript
and CSS are inline and the data is embedded as JSON in
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
    units; default 38 pixels), drawn on the dashed ``guide`` line (optional).
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

Any shape may also have a ``"color"`` (a CSS colour string) that replaces its
main colour.  Other keys are ignored.  A signal value that is NaN (written
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
``#frame=N`` (it also follows later changes of the fragment).
For scripting and tests it exposes ``window.acausal2d`` with ``frame`` (the
current frame index), ``nframes``, ``playing``, ``setFrame(i)``, ``play()``,
``pause()``, ``errors`` (messages of uncaught errors on the page) and
``scene`` (the embedded data).

Long results are subsampled to at most ``max_frames`` frames (default 2000),
evenly in time, always keeping the first and the last sample; numbers are
rounded to 6 significant digits, and only signals used by shapes are embedded.
"""
import html
import json
import math
import numbers
import os
import pathlib

import numpy as np

from ..errors import Acausal2dError

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
    "slider": (("x", "value", True), ("y", "value", True), ("phi", "value", True),
               ("length", "value", False), ("guide", "guide", False)),
    "pulley": (("x", "value", True), ("y", "value", True), ("r", "value", True),
               ("phi", "value", True), ("contour", "contour", False)),
    "belt": (("points", "points:2", True),),
    "spring": (("a", "point", True), ("b", "point", True)),
    "trace": (("x", "value", True), ("y", "value", True)),
    "label": (("x", "value", True), ("y", "value", True), ("text", "text", True)),
}
"""The shape types a scene may contain and their fields."""

_SCENE_KEYS = ("title", "time", "signals", "shapes")


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


def _check_shape(i, shape, signals):
    if not isinstance(shape, dict):
        raise Acausal2dError(f"shape {i} must be a dict with a 'type', not {type(shape).__name__}")
    kind = shape.get("type")
    if kind not in SHAPE_TYPES:
        raise Acausal2dError(
            f"shape {i} has unknown type {kind!r}; known types: {', '.join(SHAPE_TYPES)}")
    for field, fkind, required in SHAPE_TYPES[kind]:
        where = f"shape {i} ({kind}) field {field!r}"
        if field not in shape or shape[field] is None:
            if required:
                raise Acausal2dError(f"shape {i} ({kind}) is missing the required field {field!r}")
            continue
        v = shape[field]
        if fkind == "value":
            _check_value(v, where, signals)
        elif fkind == "point":
            _check_point(v, where, signals)
        elif fkind.startswith("points:"):
            _check_points(v, where, signals, int(fkind.split(":")[1]))
        elif fkind == "guide":
            _check_points(v, where, signals, 2, exact=True)
        elif fkind == "contour":
            _check_points(v, where, {}, 3)  # no signals allowed: constants in the pulley frame
        elif fkind == "text":
            if not isinstance(v, str):
                raise Acausal2dError(f"{where} must be a string, not {type(v).__name__}")
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
    time = _numeric_array(scene["time"], "scene['time']")
    if time.size == 0:
        raise Acausal2dError("scene['time'] is empty; a scene needs at least one sample")
    if not np.all(np.isfinite(time)):
        raise Acausal2dError("scene['time'] contains NaN or infinite values")
    if time.size > 1 and np.any(np.diff(time) < 0):
        k = int(np.argmax(np.diff(time) < 0))
        raise Acausal2dError(f"scene['time'] must be non-decreasing, but time[{k + 1}] = "
                             f"{time[k + 1]} < time[{k}] = {time[k]}")
    if not isinstance(scene["signals"], dict):
        raise Acausal2dError("scene['signals'] must be a dict {name: list of values}")
    signals = {}
    for name, values in scene["signals"].items():
        if not isinstance(name, str):
            raise Acausal2dError(f"signal names must be strings, got {name!r}")
        arr = _numeric_array(values, f"signal {name!r}")
        if arr.size != time.size:
            raise Acausal2dError(f"signal {name!r} has {arr.size} values but scene['time'] "
                                 f"has {time.size}; every signal needs one value per time")
        signals[name] = arr
    shapes = scene["shapes"]
    if isinstance(shapes, (str, bytes, dict)) or not hasattr(shapes, "__iter__"):
        raise Acausal2dError("scene['shapes'] must be a list of shape dicts")
    for i, shape in enumerate(shapes):
        _check_shape(i, shape, signals)
    return time, signals


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
    if "color" in shape:
        out["color"] = shape["color"]
    return out


def _bbox(shapes, signals, n):
    """World bounding box ``[xmin, ymin, xmax, ymax]`` of all shapes over all
    frames (point extents plus world-sized radii)."""
    lo = [math.inf, math.inf]
    hi = [-math.inf, -math.inf]

    def val(v):
        if isinstance(v, str):
            return signals[v]
        if isinstance(v, np.ndarray):
            return v
        return np.full(n, np.nan if v is None else float(v))

    def add(x, y, rad=0.0):
        x = val(x)
        y = val(y)
        rad = np.abs(val(rad)) if rad is not None else 0.0
        with np.errstate(invalid="ignore"):
            for d, c in ((0, x), (1, y)):
                a = c - rad
                b = c + rad
                if np.any(np.isfinite(a)):
                    lo[d] = min(lo[d], float(np.nanmin(a)))
                if np.any(np.isfinite(b)):
                    hi[d] = max(hi[d], float(np.nanmax(b)))

    for sh in shapes:
        kind = sh["type"]
        if kind in ("ground", "joint", "trace", "label"):
            add(sh["x"], sh["y"])
        elif kind == "body":
            add(sh["x"], sh["y"], sh.get("r", 0.0))
        elif kind in ("link", "belt"):
            width = sh.get("width")
            half = 0.0 if width is None else val(width) / 2
            for p in sh["points"]:
                add(p[0], p[1], half)
        elif kind == "spring":
            add(sh["a"][0], sh["a"][1])
            add(sh["b"][0], sh["b"][1])
        elif kind == "slider":
            length = sh.get("length")
            if length is None:
                add(sh["x"], sh["y"])
            else:
                length = val(length)
                add(sh["x"], sh["y"], np.hypot(length / 2, 0.3 * length))
            for p in sh.get("guide") or ():
                add(p[0], p[1])
        elif kind == "pulley":
            rad = np.abs(val(sh["r"]))
            if sh.get("contour"):
                cmax = max(math.hypot(float(c[0]), float(c[1])) for c in sh["contour"])
                rad = np.fmax(rad, cmax)
            add(sh["x"], sh["y"], rad)
    if not all(map(math.isfinite, lo + hi)):
        return [-1.0, -1.0, 1.0, 1.0]
    return [lo[0], lo[1], hi[0], hi[1]]


def _scene_data(scene, max_frames):
    time, signals = _validated(scene)
    idx = _frame_indices(time, int(max_frames))
    shapes = [_clean_shape(s) for s in scene["shapes"]]
    used = set()
    for s in scene["shapes"]:
        used |= _used_signals(s)
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
    }


def _json_for_script(data):
    """JSON that is safe inside a <script> element."""
    text = json.dumps(data, separators=(",", ":"), allow_nan=False, ensure_ascii=False)
    return (text.replace("&", "\\u0026").replace("<", "\\u003c").replace(">", "\\u003e")
            .replace("\u2028", "\\u2028").replace("\u2029", "\\u2029"))


# --------------------------------------------------------------------------
# the page

def render_html(scene, *, max_frames=MAX_FRAMES):
    """Return a self-contained HTML page (a string) that animates ``scene``.

    The scene is validated first (see :func:`validate_scene`).  Results
    longer than ``max_frames`` samples are subsampled evenly in time (first and
    last sample kept); numbers are rounded to 6 significant digits.
    """
    data = _scene_data(scene, max_frames)
    title = html.escape(data["title"] or "acausal2d animation")
    return (_TEMPLATE
            .replace("%%TITLE%%", title)
            .replace("%%SCRUB_MAX%%", str(data["nframes"] - 1))
            .replace("%%CSS%%", _CSS)
            .replace("%%JS%%", _JS)
            .replace("%%DATA%%", _json_for_script(data)))


def write_html(scene, path, **options):
    """Write :func:`render_html` of ``scene`` to ``path`` (UTF-8, parent
    directories created) and return the path as a :class:`pathlib.Path`."""
    path = pathlib.Path(os.fspath(path))
    text = render_html(scene, **options)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")
    return path


_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="acausal2d">
<title>%%TITLE%%</title>
<link rel="icon" href="data:,">
<style>
%%CSS%%
</style>
</head>
<body>
<canvas id="view" aria-label="%%TITLE%%"></canvas>
<div id="bar">
  <button id="play" type="button" title="Play / pause (space)">Play</button>
  <input id="scrub" type="range" min="0" max="%%SCRUB_MAX%%" step="1" value="0" aria-label="frame">
  <span id="time">t = 0</span>
  <label>speed
    <select id="speed" title="Playback speed relative to real time">
      <option value="0.25">0.25x</option>
      <option value="0.5">0.5x</option>
      <option value="1" selected>1x</option>
      <option value="2">2x</option>
      <option value="4">4x</option>
    </select>
  </label>
  <label title="Restart at the end"><input id="loop" type="checkbox" checked> loop</label>
</div>
<script id="acausal2d-data" type="application/json">%%DATA%%</script>
<script>
%%JS%%
</script>
</body>
</html>
"""

_CSS = """
html, body { margin: 0; padding: 0; height: 100%; overflow: hidden; background: #fbfbfc; }
body { display: flex; flex-direction: column;
       font: 13px system-ui, -apple-system, "Segoe UI", Roboto, Helvetica, Arial, sans-serif;
       color: #2d3436; }
#view { display: block; flex: 1 1 auto; min-height: 0; width: 100%; }
#bar { flex: 0 0 auto; display: flex; align-items: center; gap: 12px; padding: 6px 12px;
       background: #eef0f3; border-top: 1px solid #d5d9de; }
#bar button { min-width: 64px; padding: 4px 10px; border: 1px solid #9aa5b1; border-radius: 4px;
              background: #ffffff; color: #2d3436; font: inherit; cursor: pointer; }
#bar button:hover { background: #e3ecf5; }
#scrub { flex: 1 1 auto; min-width: 80px; accent-color: #4682b4; }
#time { font-variant-numeric: tabular-nums; min-width: 150px; white-space: nowrap; }
#bar select { font: inherit; }
#bar label { white-space: nowrap; }
"""

_JS = r"""
(function () {
  "use strict";
  var errors = [];
  window.addEventListener("error", function (e) {
    errors.push(String(e && e.message ? e.message : e));
  });

  var D = JSON.parse(document.getElementById("acausal2d-data").textContent);
  var T = D.time, N = T.length, S = D.signals, shapes = D.shapes;
  var canvas = document.getElementById("view");
  var ctx = canvas.getContext("2d");
  var playBtn = document.getElementById("play");
  var scrub = document.getElementById("scrub");
  var speedSel = document.getElementById("speed");
  var timeOut = document.getElementById("time");
  var loopBox = document.getElementById("loop");

  var COLORS = {
    background: "#fbfbfc", grid: "#eceef1", axis: "#dde1e6", text: "#2d3436",
    ground: "#6b6f75", groundFill: "#d5d8dc", link: "#4682b4", linkEdge: "#2b4f6e",
    joint: "#ffffff", jointEdge: "#1f2933", body: "#2d3436", slider: "#a9c3db",
    sliderEdge: "#2b4f6e", guide: "#8a9099", pulley: "#e9edf1", pulleyEdge: "#555d66",
    spoke: "#7b858f", belt: "#e07b00", spring: "#2e9e4f", trace: "rgba(240,128,128,0.8)",
    tracePoint: "#e74c3c", label: "#1f2933"
  };

  var frame = 0, playing = false, rafId = null, anchorWall = 0, anchorSim = 0;
  var view = { s: 1, ox: 0, oy: 0, w: 1, h: 1 };

  // Playback clock: the time vector, or 30 frames/s if it does not advance.
  var duration = N > 1 ? T[N - 1] - T[0] : 0;
  var clock = new Array(N);
  for (var q = 0; q < N; q++) clock[q] = duration > 0 ? T[q] : q / 30;

  function val(x, k) {
    var y = x;
    if (typeof x === "string") { var a = S[x]; y = a ? a[k] : null; }
    return (y === null || y === undefined) ? NaN : +y;
  }
  function finite() {
    for (var i = 0; i < arguments.length; i++) if (!isFinite(arguments[i])) return false;
    return true;
  }
  function P(x, y) { return [view.ox + view.s * x, view.oy - view.s * y]; }
  function pt(p, k) {
    var x = val(p[0], k), y = val(p[1], k);
    return finite(x, y) ? P(x, y) : null;
  }
  function pts(list, k) {
    var out = [];
    for (var i = 0; i < list.length; i++) { var p = pt(list[i], k); if (!p) return null; out.push(p); }
    return out;
  }
  function polyline(ps) {
    ctx.beginPath(); ctx.moveTo(ps[0][0], ps[0][1]);
    for (var i = 1; i < ps.length; i++) ctx.lineTo(ps[i][0], ps[i][1]);
  }
  function worldLen(v, k, dflt, minimum) {
    if (v === undefined || v === null) return dflt;
    var L = Math.abs(val(v, k)) * view.s;
    return isFinite(L) ? Math.max(minimum, L) : NaN;
  }
  function circle(x, y, r) { ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI); }

  // ---- shape drawers: function (shape, frameIndex) ----
  function drawGround(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), phi = sh.phi === undefined ? 0 : val(sh.phi, k);
    if (!finite(x, y, phi)) return;
    var p = P(x, y), c = sh.color || COLORS.ground;
    ctx.save(); ctx.translate(p[0], p[1]); ctx.rotate(-phi);
    ctx.beginPath(); ctx.moveTo(0, 0); ctx.lineTo(-9, 13); ctx.lineTo(9, 13); ctx.closePath();
    ctx.fillStyle = COLORS.groundFill; ctx.fill();
    ctx.strokeStyle = c; ctx.lineWidth = 1.5; ctx.lineJoin = "round"; ctx.stroke();
    ctx.beginPath(); ctx.moveTo(-17, 13); ctx.lineTo(17, 13); ctx.lineWidth = 2; ctx.stroke();
    ctx.beginPath();
    for (var hx = -13; hx <= 19; hx += 5) { ctx.moveTo(hx, 13); ctx.lineTo(hx - 6, 20); }
    ctx.lineWidth = 1.2; ctx.stroke();
    ctx.restore();
  }
  function drawJoint(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    circle(p[0], p[1], 4.5);
    ctx.fillStyle = COLORS.joint; ctx.fill();
    ctx.strokeStyle = sh.color || COLORS.jointEdge; ctx.lineWidth = 1.6; ctx.stroke();
  }
  function drawLink(sh, k) {
    var ps = pts(sh.points, k), w = worldLen(sh.width, k, 7, 1.5);
    if (!ps || !isFinite(w)) return;
    ctx.lineCap = "round"; ctx.lineJoin = "round";
    polyline(ps); ctx.strokeStyle = COLORS.linkEdge; ctx.lineWidth = w + 2.5; ctx.stroke();
    polyline(ps); ctx.strokeStyle = sh.color || COLORS.link; ctx.lineWidth = w; ctx.stroke();
  }
  function drawBody(sh, k) {
    var p = pt([sh.x, sh.y], k), r = worldLen(sh.r, k, 9, 2);
    if (!p || !isFinite(r)) return;
    circle(p[0], p[1], r); ctx.fillStyle = sh.color || COLORS.body; ctx.fill();
    circle(p[0] - 0.3 * r, p[1] - 0.3 * r, 0.35 * r);
    ctx.fillStyle = "rgba(255,255,255,0.22)"; ctx.fill();
  }
  function drawGuide(sh, k) {
    if (!sh.guide) return;
    var ps = pts(sh.guide, k); if (!ps) return;
    ctx.save(); ctx.setLineDash([7, 5]); ctx.lineCap = "butt";
    polyline(ps); ctx.strokeStyle = COLORS.guide; ctx.lineWidth = 1.5; ctx.stroke();
    ctx.restore();
  }
  function drawSlider(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), phi = val(sh.phi, k);
    var L = worldLen(sh.length, k, 38, 4);
    if (!finite(x, y, phi, L)) return;
    var H = 0.6 * L, p = P(x, y);
    ctx.save(); ctx.translate(p[0], p[1]); ctx.rotate(-phi);
    ctx.beginPath(); ctx.rect(-L / 2, -H / 2, L, H);
    ctx.fillStyle = sh.color || COLORS.slider; ctx.fill();
    ctx.strokeStyle = COLORS.sliderEdge; ctx.lineWidth = 1.6; ctx.lineJoin = "round"; ctx.stroke();
    ctx.restore();
  }
  function drawPulley(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), r = val(sh.r, k), phi = val(sh.phi, k);
    if (!finite(x, y, r, phi)) return;
    var p = P(x, y), R = Math.max(3, Math.abs(r) * view.s), rin = R;
    var c = Math.cos(phi), s = Math.sin(phi);
    ctx.lineJoin = "round";
    if (sh.contour && sh.contour.length >= 3) {
      ctx.beginPath();
      rin = Infinity;
      for (var i = 0; i < sh.contour.length; i++) {
        var cx = +sh.contour[i][0], cy = +sh.contour[i][1];
        rin = Math.min(rin, Math.sqrt(cx * cx + cy * cy) * view.s);
        var q = P(x + c * cx - s * cy, y + s * cx + c * cy);
        if (i === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
      }
      ctx.closePath();
      rin = Math.max(3, Math.min(rin, R));
    } else {
      circle(p[0], p[1], R);
    }
    ctx.fillStyle = COLORS.pulley; ctx.fill();
    ctx.strokeStyle = sh.color || COLORS.pulleyEdge; ctx.lineWidth = 2; ctx.stroke();
    if (!(sh.contour && sh.contour.length >= 3)) {
      circle(p[0], p[1], 0.84 * R); ctx.lineWidth = 1; ctx.strokeStyle = COLORS.spoke; ctx.stroke();
    }
    var hub = Math.max(2.5, 0.15 * rin), spoke = 0.84 * rin;
    for (var j = 0; j < 5; j++) {
      var a = -phi - j * 2 * Math.PI / 5, ca = Math.cos(a), sa = Math.sin(a);
      ctx.beginPath();
      ctx.moveTo(p[0] + hub * ca, p[1] + hub * sa);
      ctx.lineTo(p[0] + spoke * ca, p[1] + spoke * sa);
      ctx.lineCap = "round";
      ctx.strokeStyle = j === 0 ? (sh.color || COLORS.pulleyEdge) : COLORS.spoke;
      ctx.lineWidth = j === 0 ? 3 : 1.8; ctx.stroke();
    }
    circle(p[0], p[1], hub); ctx.fillStyle = sh.color || COLORS.pulleyEdge; ctx.fill();
  }
  function drawBelt(sh, k) {
    var ps = pts(sh.points, k); if (!ps) return;
    ctx.lineCap = "round"; ctx.lineJoin = "round";
    polyline(ps); ctx.strokeStyle = sh.color || COLORS.belt; ctx.lineWidth = 3; ctx.stroke();
  }
  function drawSpring(sh, k) {
    var a = pt(sh.a, k), b = pt(sh.b, k); if (!a || !b) return;
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.sqrt(dx * dx + dy * dy);
    if (L < 1) return;
    var ux = dx / L, uy = dy / L, nx = -uy, ny = ux, lead = 0.15 * L, m = 12, amp = 6;
    ctx.beginPath(); ctx.moveTo(a[0], a[1]);
    for (var j = 0; j <= m; j++) {
      var d = lead + (L - 2 * lead) * j / m, o = (j === 0 || j === m) ? 0 : (j % 2 ? amp : -amp);
      ctx.lineTo(a[0] + ux * d + nx * o, a[1] + uy * d + ny * o);
    }
    ctx.lineTo(b[0], b[1]);
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    ctx.strokeStyle = sh.color || COLORS.spring; ctx.lineWidth = 2; ctx.stroke();
  }
  function drawTracePath(sh) {
    ctx.beginPath();
    var pen = false;
    for (var k = 0; k < N; k++) {
      var p = pt([sh.x, sh.y], k);
      if (!p) { pen = false; continue; }
      if (pen) ctx.lineTo(p[0], p[1]); else ctx.moveTo(p[0], p[1]);
      pen = true;
    }
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    ctx.strokeStyle = sh.color || COLORS.trace; ctx.lineWidth = 1.5;
    ctx.save(); if (sh.color) ctx.globalAlpha = 0.5; ctx.stroke(); ctx.restore();
  }
  function drawTracePoint(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    circle(p[0], p[1], 4); ctx.fillStyle = sh.color || COLORS.tracePoint; ctx.fill();
    ctx.strokeStyle = "#ffffff"; ctx.lineWidth = 1.2; ctx.stroke();
  }
  function drawLabel(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    ctx.font = "13px system-ui, -apple-system, 'Segoe UI', Roboto, Helvetica, Arial, sans-serif";
    ctx.textBaseline = "bottom"; ctx.textAlign = "left"; ctx.lineJoin = "round";
    ctx.strokeStyle = "rgba(251,251,252,0.9)"; ctx.lineWidth = 3;
    ctx.strokeText(String(sh.text), p[0] + 7, p[1] - 5);
    ctx.fillStyle = sh.color || COLORS.label; ctx.fillText(String(sh.text), p[0] + 7, p[1] - 5);
  }

  // Layers, drawn bottom to top; unknown shape types are ignored.
  var LAYERS = {
    trace: [[0, drawTracePath], [90, drawTracePoint]], pulley: [[10, drawPulley]],
    slider: [[15, drawGuide], [60, drawSlider]], ground: [[20, drawGround]],
    belt: [[30, drawBelt]], spring: [[40, drawSpring]], link: [[50, drawLink]],
    body: [[70, drawBody]], joint: [[80, drawJoint]], label: [[100, drawLabel]]
  };
  var ops = [];
  shapes.forEach(function (sh, i) {
    (LAYERS[sh && sh.type] || []).forEach(function (l) { ops.push({ z: l[0], i: i, sh: sh, fn: l[1] }); });
  });
  ops.sort(function (a, b) { return a.z - b.z || a.i - b.i; });

  function niceStep(raw) {
    var p = Math.pow(10, Math.floor(Math.log10(raw))), m = [1, 2, 5, 10];
    for (var i = 0; i < m.length; i++) if (m[i] * p >= raw) return m[i] * p;
    return 10 * p;
  }
  function fmt(x) { return Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(0) : String(+x.toPrecision(6)); }

  function drawGrid() {
    var step = niceStep(70 / view.s);
    var x0 = -view.ox / view.s, x1 = (view.w - view.ox) / view.s;
    var y0 = (view.oy - view.h) / view.s, y1 = view.oy / view.s;
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (var gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
      var sx = Math.round(view.ox + view.s * gx) + 0.5; ctx.moveTo(sx, 0); ctx.lineTo(sx, view.h);
    }
    for (var gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
      var sy = Math.round(view.oy - view.s * gy) + 0.5; ctx.moveTo(0, sy); ctx.lineTo(view.w, sy);
    }
    ctx.strokeStyle = COLORS.grid; ctx.stroke();
    ctx.beginPath();
    if (x0 <= 0 && 0 <= x1) { var ax = Math.round(view.ox) + 0.5; ctx.moveTo(ax, 0); ctx.lineTo(ax, view.h); }
    if (y0 <= 0 && 0 <= y1) { var ay = Math.round(view.oy) + 0.5; ctx.moveTo(0, ay); ctx.lineTo(view.w, ay); }
    ctx.strokeStyle = COLORS.axis; ctx.stroke();
    ctx.font = "11px system-ui, sans-serif"; ctx.fillStyle = "#8a9099";
    ctx.textAlign = "left"; ctx.textBaseline = "bottom";
    ctx.fillText("grid " + fmt(step), 10, view.h - 8);
  }

  function fit() {
    var dpr = window.devicePixelRatio || 1;
    var w = Math.max(1, canvas.clientWidth), h = Math.max(1, canvas.clientHeight);
    canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    var b = D.bbox, pad = 34, top = D.title ? 44 : pad;
    var bw = b[2] - b[0], bh = b[3] - b[1], size = Math.max(bw, bh) || 1;
    if (!(bw > 0)) { bw = size * 1e-3; }
    if (!(bh > 0)) { bh = size * 1e-3; }
    var aw = Math.max(10, w - 2 * pad), ah = Math.max(10, h - pad - top);
    var s = Math.min(aw / bw, ah / bh);
    view = { s: s, w: w, h: h,
             ox: pad + (aw - s * bw) / 2 - s * b[0],
             oy: top + (ah - s * bh) / 2 + s * b[3] };
  }

  function draw() {
    ctx.fillStyle = COLORS.background; ctx.fillRect(0, 0, view.w, view.h);
    drawGrid();
    for (var i = 0; i < ops.length; i++) {
      ctx.save();
      try { ops[i].fn(ops[i].sh, frame); } finally { ctx.restore(); }
    }
    if (D.title) {
      ctx.font = "600 15px system-ui, -apple-system, 'Segoe UI', Roboto, Helvetica, Arial, sans-serif";
      ctx.fillStyle = COLORS.text; ctx.textAlign = "left"; ctx.textBaseline = "top";
      ctx.fillText(D.title, 12, 12);
    }
    timeOut.textContent = "t = " + (N ? T[frame].toFixed(3) : "0") + " s  (" + (frame + 1) + "/" + N + ")";
    scrub.value = String(frame);
  }

  function findFrame(simT) {  // last frame with clock <= simT
    var lo = 0, hi = N - 1;
    if (simT <= clock[0]) return 0;
    if (simT >= clock[hi]) return hi;
    while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (clock[mid] <= simT) lo = mid; else hi = mid; }
    return lo;
  }
  function speed() { var v = parseFloat(speedSel.value); return v > 0 ? v : 1; }
  function anchor() { anchorWall = performance.now(); anchorSim = clock[frame]; }

  function setFrame(i) {
    i = Math.round(+i);
    if (!isFinite(i)) i = 0;
    frame = Math.max(0, Math.min(N - 1, i));
    if (playing) anchor();
    draw();
    return frame;
  }
  function tick(now) {
    rafId = null;
    if (!playing) return;
    var simT = anchorSim + (now - anchorWall) / 1000 * speed();
    if (simT >= clock[N - 1]) {
      if (loopBox.checked && N > 1) {
        frame = 0; anchorWall = now; anchorSim = clock[0];
      } else {
        frame = N - 1; draw(); pause(); return;
      }
    } else {
      frame = findFrame(simT);
    }
    draw();
    rafId = window.requestAnimationFrame(tick);
  }
  function play() {
    if (playing || N < 2) return;
    if (frame >= N - 1) frame = 0;
    playing = true; playBtn.textContent = "Pause";
    anchor();
    rafId = window.requestAnimationFrame(tick);
  }
  function pause() {
    playing = false; playBtn.textContent = "Play";
    if (rafId !== null) { window.cancelAnimationFrame(rafId); rafId = null; }
  }

  function frameFromHash() {
    var m = /(?:^#|&)frame=(-?\d+)/.exec(window.location.hash || "");
    return m ? parseInt(m[1], 10) : null;
  }

  playBtn.addEventListener("click", function () { if (playing) pause(); else play(); });
  scrub.addEventListener("input", function () { setFrame(parseInt(scrub.value, 10)); });
  speedSel.addEventListener("change", function () {
    if (playing) { anchorSim = anchorSim + (performance.now() - anchorWall) / 1000 * speed(); anchor(); }
  });
  window.addEventListener("resize", function () { fit(); draw(); });
  window.addEventListener("hashchange", function () {
    var h = frameFromHash(); if (h !== null) setFrame(h);
  });
  document.addEventListener("keydown", function (e) {
    var tag = e.target && e.target.tagName;
    if (tag === "INPUT" || tag === "SELECT" || tag === "BUTTON" || tag === "TEXTAREA") return;
    if (e.key === " ") { e.preventDefault(); if (playing) pause(); else play(); }
    else if (e.key === "ArrowRight") { setFrame(frame + 1); }
    else if (e.key === "ArrowLeft") { setFrame(frame - 1); }
    else if (e.key === "Home") { setFrame(0); }
    else if (e.key === "End") { setFrame(N - 1); }
  });

  scrub.max = String(Math.max(0, N - 1));
  var h0 = frameFromHash();
  frame = h0 === null ? 0 : Math.max(0, Math.min(N - 1, h0));
  fit();
  draw();

  window.acausal2d = {
    get frame() { return frame; },
    nframes: N,
    get playing() { return playing; },
    setFrame: setFrame,
    play: play,
    pause: pause,
    errors: errors,
    scene: D
  };
})();
"""
