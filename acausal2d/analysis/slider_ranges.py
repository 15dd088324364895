"""Slider travel ranges of a run (Ebert 2015, ch. 7.1, Bild 7.4: "the motion
ranges of the sliders are recognised automatically and visualised").

A slider is what a component draws as a ``"slider"`` shape with a
``guide``, or with its travel signal ``s`` where its guide's start point is
no result signal (a linkage element's guide placed with an offset on a
moving link) (the linkage elements SAN, DDS, DSD, SDS, SSD; see
:mod:`acausal2d.visual.animation`): a block at the foot point PS with the
guide angle phi on a guide through the point G.  Its travel along the guide
is ``s(t) = (PS - G) . (cos phi, sin phi)``, measured from G in the guide
frame (a guide of two constant points, the planar Prismatic's, gives the
direction itself), so a guide on a moving link (the slotted crank's rocker) gives the
travel relative to that link.  The range of a run is ``[min s, max s]``;
its length is the stroke (2 r for a centric slider crank of crank radius
r).  The animation draws the guide over the whole range and marks its ends
(:func:`travel_shapes`); ``acausal2d simulate`` prints the ranges in its
summary.
"""
from collections import namedtuple

import numpy as np

__all__ = ["SliderRange", "slider_ranges", "travel_shapes", "range_lines"]

SliderRange = namedtuple("SliderRange", "name s_min s_max stroke")
SliderRange.__doc__ = """Travel range of one slider: ``name`` the component
path (with ``[k]`` for the k-th slider of a component that has several),
``s_min``, ``s_max`` the least and largest travel along the guide from the
guide point (m), ``stroke = s_max - s_min``."""


def _values(get, v, n):
    """A shape field as an array of n values (a constant or a signal)."""
    if isinstance(v, str):
        return np.asarray(get(v), dtype=float)
    return np.full(n, float(v))


def _travel(get, sh, n):
    """(G, u, s): guide point, unit direction (n x 2 arrays) and the travel
    s(t) of the slider shape ``sh`` (a shape without a drawn guide gives its
    travel ``s`` itself; the guide point is then PS - s u)."""
    if not sh.get("guide"):
        phi = _values(get, sh["phi"], n)
        u = np.column_stack([np.cos(phi), np.sin(phi)])
        PS = np.column_stack([_values(get, sh["x"], n), _values(get, sh["y"], n)])
        s = _values(get, sh["s"], n)
        return PS - s[:, None] * u, u, s
    G = np.column_stack([_values(get, c, n) for c in sh["guide"][0]])
    far = sh["guide"][1]
    if all(not isinstance(c, str) for c in list(sh["guide"][0]) + list(far)) \
            and np.hypot(far[0] - G[0, 0], far[1] - G[0, 1]) > 0:
        d = np.array([far[0] - G[0, 0], far[1] - G[0, 1]], dtype=float)
        u = np.tile(d / np.hypot(*d), (n, 1))       # a constant guide: its own direction
    else:
        phi = _values(get, sh["phi"], n)
        u = np.column_stack([np.cos(phi), np.sin(phi)])
    PS = np.column_stack([_values(get, sh["x"], n), _values(get, sh["y"], n)])
    return G, u, np.sum((PS - G) * u, axis=1)


def _qualified(sh, prefix):
    """The fields of a slider shape that :func:`_travel` reads, with their
    signal names prefixed by the component path."""
    def q(v):
        return prefix + v if isinstance(v, str) else v
    out = {"x": q(sh["x"]), "y": q(sh["y"]), "phi": q(sh["phi"]),
           "guide": [[q(c) for c in p] for p in sh.get("guide") or []]}
    if "s" in sh:
        out["s"] = q(sh["s"])
    return out


def _slider_shapes(model):
    """(name, qualified shape) of every slider with a guide in ``model``."""
    out = []
    for comp in model.components():
        prefix = comp.path + "." if comp.path else ""
        mine = [sh for sh in comp.shapes() if sh.get("type") == "slider"
                and (sh.get("guide") or sh.get("s"))]
        for k, sh in enumerate(mine):
            name = comp.path or type(comp).__name__
            out.append((name + ("[%d]" % (k + 1) if len(mine) > 1 else ""),
                        _qualified(sh, prefix)))
    return out


def slider_ranges(result):
    """The travel range of every slider of the model of ``result`` (a
    :class:`~acausal2d.result.Result` of a compiled model), as a list of
    :class:`SliderRange` in the order of the components; empty for a model
    without sliders.  Over the output points of the run: refine
    ``intervals`` to catch a reversal between them."""
    model = result.model.model if result.model is not None else None
    if model is None:
        return []
    n = len(result.time)
    out = []
    for name, sh in _slider_shapes(model):
        s = _travel(result.__getitem__, sh, n)[2]
        lo, hi = float(np.min(s)), float(np.max(s))
        out.append(SliderRange(name, lo, hi, hi - lo))
    return out


def range_lines(ranges, indent="  "):
    """Summary lines of :func:`slider_ranges` (one per slider)."""
    return ["%sslider %s: travel %.6g .. %.6g m along its guide from its start (stroke %.6g m)"
            % (indent, r.name, r.s_min, r.s_max, r.stroke) for r in ranges]


def travel_shapes(shapes, signals):
    """Add to every slider shape in ``shapes`` (in place) its whole travel
    range over the run as ``travel``: the range's end points, new signals
    in ``signals`` (which holds the shapes' signals as lists), drawn as a
    solid bar with end marks over the dashed guide in every frame.  A guide
    that follows a moving frame (a linkage element's, drawn up to the
    slider's current position) is widened to run from G (or the nearest
    range end beyond it) to the farthest range end; a fixed guide (a
    planar Prismatic's) stays as the model gives it."""
    n = len(next(iter(signals.values()))) if signals else 0
    k = 0
    for sh in shapes:
        if sh.get("type") != "slider" or not (sh.get("guide") or sh.get("s")) or n == 0:
            continue
        G, u, s = _travel(signals.__getitem__, sh, n)
        ends = {"min": float(np.min(s)), "max": float(np.max(s))}
        lo, hi = min(0.0, ends["min"]), max(0.0, ends["max"])
        names = []
        for tag, value in (("min", ends["min"]), ("max", ends["max"]), ("lo", lo), ("hi", hi)):
            p = G + value * u
            base = "slider travel %d %s" % (k, tag)
            signals[base + ".x"], signals[base + ".y"] = p[:, 0].tolist(), p[:, 1].tolist()
            names.append([base + ".x", base + ".y"])
        sh["travel"] = names[:2]
        if not sh.get("guide") or any(isinstance(v, str) for pt in sh["guide"] for v in pt):
            sh["guide"] = names[2:]        # a guide drawn up to the moving slider: the whole range
        k += 1
    return shapes
