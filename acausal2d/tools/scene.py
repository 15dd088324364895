"""Builds the animation scene of a result from the components' drawing
declarations.

A component declares how it is drawn by returning shape dicts from
``shapes()`` (see :mod:`acausal2d.tools.animation` for the kinds), with signal
names relative to the component (``"frame_a.x"``); this module qualifies
them with the component's path and collects the signals from the result.
"""
from .animation import write_html

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


def build_scene(result, traces=(), title=None):
    """Scene dict for :func:`acausal2d.tools.animation.render_html` from a result
    of a compiled model; ``traces`` are points whose path is drawn (coupler
    curves): frame names or ``"x_name:y_name"`` pairs, see
    :func:`trace_signals`."""
    model = result.model.model if result.model is not None else None
    shapes = []
    if model is not None:
        for comp in model.components():
            prefix = comp.path + "." if comp.path else ""
            for shape in comp.shapes():
                shapes.append(qualify_shape(shape, prefix))
    for x, y in trace_signals(traces, result.names):
        shapes.append({"type": "trace", "x": x, "y": y})
    signals = {}
    for shape in shapes:
        for name in _signal_names(shape):
            if name not in signals:
                signals[name] = [float(v) for v in result[name]]
    return {"title": title or (type(model).__name__ if model is not None else "acausal2d"),
            "time": [float(t) for t in result.time], "signals": signals, "shapes": shapes}


def animate(result, path, traces=(), title=None):
    """Write the self-contained HTML animation of ``result`` to ``path``."""
    return write_html(build_scene(result, traces, title), path)
