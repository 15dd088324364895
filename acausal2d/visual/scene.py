"""Builds the animation scene of a result from the components' drawing
declarations.

A component declares how it is drawn by returning shape dicts from
``shapes()`` (see :mod:`acausal2d.visual.animation` for the kinds), with signal
names relative to the component (``"frame_a.x"``); this module qualifies
them with the component's path and collects the signals from the result.
"""
from .animation import write_html

from ..errors import Acausal2dError

_SCALAR_KEYS = ("x", "y", "phi", "r", "length", "width", "fx", "fy", "t", "angle", "scale",
                "offset")
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
    from ..errors import Acausal2dError
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


def build_scene(result, traces=(), title=None, arrows=(), signal=None, autoplay=False):
    """Scene dict for :func:`acausal2d.visual.animation.render_html` from a result
    of a compiled model; ``traces`` are points whose path is drawn (coupler
    curves): frame names or ``"x_name:y_name"`` pairs, see
    :func:`trace_signals`; ``arrows`` frames or flanges whose forces and
    torques are drawn (:func:`arrow_signals`); ``signal`` a signal plotted
    under the mechanism with a cursor synced to the time slider;
    ``autoplay`` starts the page playing."""
    model = result.model.model if result.model is not None else None
    shapes = _available(model_shapes(model) if model is not None else [], result.names)
    for x, y in trace_signals(traces, result.names):
        shapes.append({"type": "trace", "x": x, "y": y})
    shapes += arrow_signals(arrows, result.names)
    signals = {}
    for shape in shapes:
        for name in _signal_names(shape):
            if name not in signals:
                signals[name] = [float(v) for v in result[name]]
    scene = {"title": title or (type(model).__name__ if model is not None else "acausal2d"),
             "time": [float(t) for t in result.time], "signals": signals, "shapes": shapes,
             "unit": "m", "autoplay": bool(autoplay)}
    if signal:
        from .plotting import axis_label, unit_of
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
    in ``model``, see :meth:`acausal2d.language.nodes.NodeModel.drag_system`),
    or None."""
    for comp in model.components() if model is not None else ():
        if hasattr(comp, "drag_system"):
            return comp.drag_system()
    return None


def animate(result, path, traces=(), title=None, arrows=(), signal=None, autoplay=False):
    """Write the self-contained HTML animation of ``result`` to ``path``
    (options as for :func:`build_scene`)."""
    return write_html(build_scene(result, traces, title, arrows, signal, autoplay), path)
