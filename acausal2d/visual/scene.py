"""Builds the animation scene of a result from the components' drawing
declarations.

A component declares how it is drawn by returning shape dicts from
``shapes()`` (see :mod:`acausal2d.visual.animation` for the kinds), with signal
names relative to the component (``"frame_a.x"``); this module qualifies
them with the component's path and collects the signals from the result.
"""
from __future__ import annotations

import os
import pathlib
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any
import numpy as np

from .animation import write_html

from ..analysis.poles import cartesian, pole_homogeneous, poles
from ..analysis.slider_ranges import travel_shapes
from ..errors import Acausal2dError
from .plotting import axis_label, unit_of

if TYPE_CHECKING:
    from ..protocols import ResultData

_SCALAR_KEYS = ("x", "y", "phi", "r", "length", "width", "fx", "fy", "t", "angle", "scale",
                "offset", "s")
_POINT_KEYS = ("a", "b")
_POINTS_KEYS = ("points", "guide")


def _qualify(value, prefix):
    if isinstance(value, str):
        return prefix + value if prefix else value
    return value


def qualify_shape(shape, prefix):
    """Copy of ``shape`` with signal names prefixed by ``prefix``."""
    out = dict(shape)
    for k in _SCALAR_KEYS:
        if k in out:
            out[k] = _qualify(out[k], prefix)
    for k in _POINT_KEYS:
        if k in out:
            out[k] = [_qualify(v, prefix) for v in out[k]]
    for k in _POINTS_KEYS:
        if k in out:
            out[k] = [[_qualify(v, prefix) for v in pt] for pt in out[k]]
    return out


def _signal_names(shape):
    names = []
    for k in _SCALAR_KEYS:
        if isinstance(shape.get(k), str):
            names.append(shape[k])
    for k in _POINT_KEYS:
        names += [v for v in shape.get(k, ()) if isinstance(v, str)]
    for k in _POINTS_KEYS:
        for pt in shape.get(k, ()):
            names += [v for v in pt if isinstance(v, str)]
    return names


def trace_signals(traces, names):
    """The (x, y) signal names of traced points: each entry of ``traces`` is
    a frame (``"dyad.ctr2D3"``: its ``.x`` and ``.y``) or a pair of signals
    ``"x_name:y_name"`` (``"dyad.xP:dyad.yP"``).  ``names``: the signals
    available; an unknown entry raises an error listing the frames."""
    available = set(names)
    pairs = []
    for entry in traces:
        entry = entry.strip()
        if ":" in entry:
            x, y = (part.strip() for part in entry.split(":", 1))
        else:
            x, y = entry + ".x", entry + ".y"
        missing = [n for n in (x, y) if n not in available]
        if missing:
            frames = sorted({n[:-2] for n in available
                             if n.endswith(".x") and n[:-2] + ".y" in available})
            raise Acausal2dError(
                "cannot trace %r: no signal %s.  Trace a frame (%s%s) or a pair of "
                "signals x_name:y_name." % (entry, " or ".join(repr(n) for n in missing),
                                            ", ".join(frames[:12]),
                                            ", ..." if len(frames) > 12 else ""))
        pairs.append((x, y))
    return pairs


def _frames_of(prefix, available):
    return sorted({n[:-2] for n in available if n.endswith(".x") and n.startswith(prefix)
                   and n[:-2] + ".fx" in available})


def _torque_position(flange, at, available):
    """The frame a flange's torque arrow is drawn at: ``at`` if given, else
    the owner's frame_a/frame, else its only frame."""
    if at:
        if at + ".x" not in available:
            raise Acausal2dError("cannot draw the torque of %r at %r: no frame %r" % (
                flange, at, at))
        return at
    owner = flange.rsplit(".", 1)[0] + "." if "." in flange else ""
    frames = _frames_of(owner, available)
    for name in (owner + "frame_a", owner + "frame"):
        if name in frames:
            return name
    if len(frames) == 1:
        return frames[0]
    raise Acausal2dError("cannot place the torque arrow of %r: its component has %s; give "
                         "the frame as %s@FRAME" % (flange, "the frames " + ", ".join(frames)
                                                   if frames else "no frame", flange))


def arrow_signals(arrows, names, model=None):
    """Shapes of the force and torque arrows for the entries of ``arrows``:
    a frame (``"revolute.frame_a"``: a force arrow fx, fy and a torque arrow
    t at its origin) or a rotational flange (``"drive.flange"``: a torque
    arrow tau at its component's frame; ``"flange@frame"`` chooses the
    frame).  ``names``: the signals available; unknown entries raise an
    error listing the frames."""
    available = set(names)
    shapes = []
    for entry in arrows:
        entry = entry.strip()
        name, _, at = entry.partition("@")
        if name + ".fx" in available and name + ".x" in available:
            shapes.append({"type": "arrow", "x": name + ".x", "y": name + ".y",
                           "fx": name + ".fx", "fy": name + ".fy", "label": name})
            if name + ".t" in available:
                shapes.append({"type": "torque", "x": name + ".x", "y": name + ".y",
                               "t": name + ".t", "label": name})
        elif name + ".tau" in available:
            frame = _torque_position(name, at, available)
            shapes.append({"type": "torque", "x": frame + ".x", "y": frame + ".y",
                           "t": name + ".tau", "label": name})
        else:
            frames = _frames_of("", available)
            raise Acausal2dError(
                "cannot draw arrows for %r: it is neither a frame (with fx, fy) nor a "
                "rotational flange (with tau).  Frames: %s%s" % (
                    entry, ", ".join(frames[:12]), ", ..." if len(frames) > 12 else ""))
    return shapes


def model_shapes(model):
    """The shapes of all components of ``model``, signal names qualified."""
    shapes = []
    for comp in model.components():
        prefix = comp.path + "." if comp.path else ""
        shapes += [qualify_shape(shape, prefix) for shape in comp.shapes()]
    return shapes


def pole_shapes(result, links, joints=None):
    """(shapes, signals) drawing the instantaneous poles of ``links``
    ({label: link}, see :func:`acausal2d.analysis.poles.poles`) on the layer
    "poles" of the page, each labelled P<i><j>; a pole at infinity is hidden
    in that frame."""
    shapes, signals = [], {}
    for (i, j), pts in poles(result, links, joints).items():
        name = "pole P%s%s" % (i, j)
        signals[name + ".x"] = [float(v) for v in pts[:, 0]]
        signals[name + ".y"] = [float(v) for v in pts[:, 1]]
        shapes.append({"type": "pole", "x": name + ".x", "y": name + ".y",
                       "text": "P%s%s" % (i, j), "layer": "poles"})
    return shapes, signals


def declared_pole_views(result, model, signals):
    """(shapes, signals) of the pole views the components of ``model``
    declare as ``pole_views``: dicts {"link": link of the component,
    "ref": reference link (default the ground), "text": label, "trace":
    draw its path (the fixed centrode)} (the mec2 importer makes them from
    mec2's ``pole`` views).  A path is drawn only where it stays within
    three times the extent of the other ``signals`` (.x/.y) around their
    centre: a pole runs off to infinity where the link translates."""
    shapes, out = [], {}
    box = _clip_box(signals)
    for comp in model.components() if model is not None else ():
        prefix = comp.path + "." if comp.path else ""
        for view in getattr(comp, "pole_views", ()):
            ref = view.get("ref", "ground")
            pts = cartesian(pole_homogeneous(result, prefix + view["link"],
                                             ref if ref == "ground" else prefix + ref))
            name = "pole %s%s" % (prefix, view["text"])
            out[name + ".x"], out[name + ".y"] = ([float(v) for v in pts[:, k]] for k in (0, 1))
            shapes.append({"type": "pole", "x": name + ".x", "y": name + ".y",
                           "text": view["text"], "layer": "poles"})
            if view.get("trace"):
                far = ((pts < box[0]) | (pts > box[1])).any(axis=1) | np.isnan(pts).any(axis=1)
                path = np.where(far[:, None], np.nan, pts)
                out[name + " path.x"], out[name + " path.y"] = path[:, 0].tolist(), \
                    path[:, 1].tolist()
                shapes.append({"type": "trace", "x": name + " path.x", "y": name + " path.y",
                               "layer": "poles", "color": "#16a085"})
    return shapes, out


def _clip_box(signals):
    """(low, high) corners: the extent of the .x/.y signals, widened to
    three times its size about its centre."""
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    for k, tail in enumerate((".x", ".y")):
        for name, values in signals.items():
            if name.endswith(tail) and values:
                v = np.asarray(values, dtype=float)
                lo[k], hi[k] = min(lo[k], np.nanmin(v)), max(hi[k], np.nanmax(v))
    if not np.isfinite(lo).all():
        return np.full(2, -np.inf), np.full(2, np.inf)
    mid, half = (lo + hi) / 2, max(float((hi - lo).max()), 1e-9) * 1.5
    return mid - half, mid + half


def parse_links(text):
    """``"1=ground,2=A0A,4=B.x:B.y:GB.w"`` -> {label: link} (the
    ``--poles`` option: frames, node constraints, x:y:phi signal triples)."""
    links = {}
    for item in (t.strip() for t in text.split(",") if t.strip()):
        label, sep, spec = item.partition("=")
        if not sep or not label.strip() or not spec.strip():
            raise Acausal2dError("--poles takes label=link pairs, e.g. 1=ground,2=A0A,"
                                 "3=crank.frame_b,4=B.x:B.y:GB.w; got %r" % item)
        if label.strip() in links:
            raise Acausal2dError("--poles: the label %s is given twice (%s); give each link "
                                 "its own label" % (label.strip(), text))
        parts = [p.strip() for p in spec.split(":")]
        links[label.strip()] = tuple(parts) if len(parts) == 3 else spec.strip()
    return links


def build_scene(result: ResultData, traces: Iterable[str] = (), title: str | None = None,
                arrows: Iterable[str] = (), signal: str | None = None, autoplay: bool = False,
                poles: Mapping[str, str] | None = None) -> dict[str, Any]:
    """Scene dict for :func:`acausal2d.visual.animation.render_html` from a result
    of a compiled model; ``traces`` are points whose path is drawn (coupler
    curves): frame names or ``"x_name:y_name"`` pairs, see
    :func:`trace_signals`; ``arrows`` frames or flanges whose forces and
    torques are drawn (:func:`arrow_signals`); ``signal`` a signal plotted
    under the mechanism with a cursor synced to the time slider;
    ``autoplay`` starts the page playing; ``poles`` ({label: link}) draws
    the instantaneous poles of those links on a layer (:func:`pole_shapes`)."""
    model = result.model.model if result.model is not None else None
    shapes = _available(model_shapes(model) if model is not None else [], result.names)
    for x, y in trace_signals(traces, result.names):
        shapes.append({"type": "trace", "x": x, "y": y})
    shapes += arrow_signals(arrows, result.names)
    signals = {}
    if poles:
        more, signals = pole_shapes(result, poles)
        shapes += more
    for shape in shapes:
        for name in _signal_names(shape):
            if name not in signals:
                signals[name] = [float(v) for v in result[name]]
    travel_shapes(shapes, signals)
    more, pole_signals = declared_pole_views(result, model, signals)
    shapes += more
    signals.update(pole_signals)
    scene = {"title": title or (type(model).__name__ if model is not None else "acausal2d"),
             "time": [float(t) for t in result.time], "signals": signals, "shapes": shapes,
             "unit": "m", "autoplay": bool(autoplay)}
    if signal:
        signals[signal] = [float(v) for v in result[signal]]
        scene["plot"] = {"signal": signal, "label": axis_label(signal, unit_of(result, signal))}
    nodes = _drag_system(model)
    if nodes is not None:
        scene["nodes"] = nodes
    return scene


def _available(shapes, names):
    """The shapes, without those marked ``optional`` whose signals the
    result does not hold (a mec2 acceleration arrow of a node whose
    acceleration was eliminated); the mark itself is dropped."""
    names, out = set(names), []
    for shape in shapes:
        if shape.get("optional"):
            shape = {k: v for k, v in shape.items() if k != "optional"}
            if not all(n in names for n in _signal_names(shape)):
                continue
        out.append(shape)
    return out


def _drag_system(model):
    """The node description for the page's drag mode (the first node model
    in ``model``, see :meth:`acausal2d.library.nodes.NodeModel.drag_system`),
    or None."""
    for comp in model.components() if model is not None else ():
        if hasattr(comp, "drag_system"):
            return comp.drag_system()
    return None


NO_GEOMETRY = ("no animation: %s has no planar geometry to draw (its elements declare no "
               "shapes, as in a drive train or a hydraulic circuit)")
"""The one line said instead of an animation of a model without geometry."""


def has_geometry(model: Any) -> bool:
    """Whether ``model`` (a compiled model's own copy) has anything to draw:
    a component with :meth:`~acausal2d.language.dsl.Component.shapes`.  A
    model without (a drive train, a hydraulic circuit) gets no animation,
    never an empty grid."""
    return model is not None and bool(model_shapes(model))


def _check_geometry(result: ResultData) -> None:
    model = result.model.model if result.model is not None else None
    if model is not None and not has_geometry(model):
        raise Acausal2dError(NO_GEOMETRY % type(model).__name__)


def animate(result: ResultData, path: str | os.PathLike[str], traces: Iterable[str] = (),
            title: str | None = None, arrows: Iterable[str] = (), signal: str | None = None,
            autoplay: bool = False, poles: Mapping[str, str] | None = None) -> pathlib.Path:
    """Write the self-contained HTML animation of ``result`` to ``path``
    (options as for :func:`build_scene`); a model without geometry
    (:func:`has_geometry`) is an error saying so, never an empty grid."""
    _check_geometry(result)
    return write_html(build_scene(result, traces, title, arrows, signal, autoplay, poles), path)
