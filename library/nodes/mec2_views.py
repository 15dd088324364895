"""mec2 views and shapes (goessner/mec2, src/mec.view.js and src/mec.shape.js
over their history): both spellings of a view, what the animation draws of
them, and warnings for what it does not know.

Views and shapes only draw; they never stop a model from loading.  A view
kind, view field, shape type or shape field this module does not know is
collected into one warning (:class:`Mec2Warning`, issued once per file) and
the view or shape is left out -- unlike unknown fields of nodes,
constraints and loads, which change the motion and stay errors.

Spellings (mec.view.js):

* older (commits 8545ba3 .. 0790336, 2018; mec2's test pages until
  b94dc82): ``{"type": "vector", "p": "A", "value": "vel"}``, ``{"type":
  "trace", "p": "B", "t0", "Dt", "fill", "stroke", "mode"}``, ``{"type":
  "info", "elem": "a", "value": "w", "name"}``, ``{"type": "chart", "xval",
  "yval"}`` (later ``"xaxis"``, ``"yaxis"``);
* newer (222aacd "version 6.7" and "new views api" eaa48c4, 2019 on):
  ``{"as": kind, "show": property, "of": element}`` with ``at`` (vector
  anchor), ``ref``, ``mode``, ``t0``, ``Dt``, ``stroke``, ``fill``, and for
  charts ``x``, ``y``, ``b``, ``h``, ``canvas``, ``cnv``, ``against``.

Drawn: traces of node positions (``show: "pos"`` without ``ref``) and
vector views of a node's ``vel``, ``acc`` and ``force`` as arrows (mec2's
colours steelblue, firebrick, saddlebrown; anchored at ``at`` when given).
A ``force`` view draws the loads on the node one arrow each (force loads,
springs, gravity; mec2 draws their sum Q).  Everything else (points,
infos, charts, pole and relative traces, vectors of constraints) is listed
in the model's ``mec2_views_not_drawn`` with the reason.
"""
import math
import warnings

__all__ = ["Mec2Warning", "VIEW_KINDS", "normalized_view", "check_cosmetics", "vector_arrows"]


class Mec2Warning(UserWarning):
    """A view or shape field of a mec2 file that the importer does not know
    (the view or shape is left out; the model loads)."""


VIEW_KINDS = ("point", "vector", "trace", "info", "chart")
_NUMBER, _TEXT, _ANY = "a number", "a string", None
_VIEW_FIELDS = dict({k: _TEXT for k in ("as", "type", "show", "of", "p", "value", "elem", "name",
                                        "ref", "mode", "stroke", "fill", "at", "id", "wref")},
                    **{k: _NUMBER for k in ("t0", "Dt", "x", "y", "h", "b")},
                    **{k: _ANY for k in ("canvas", "cnv", "against", "xaxis", "yaxis", "xval",
                                         "yval")})
_SHAPE_TYPES = {"fix", "flt", "slider", "bar", "beam", "wheel", "poly", "img"}
_SHAPE_FIELDS = dict({k: _TEXT for k in ("type", "p", "p1", "p2", "wref", "fill", "stroke",
                                         "uri", "id")},
                     **{k: _NUMBER for k in ("w0", "len", "r", "xoff", "yoff", "scl")},
                     pts=_ANY)
_COLORS = {"vel": "steelblue", "acc": "firebrick", "force": "saddlebrown"}
_UNITS = {"vel": "m/s", "acc": "m/s2", "force": "N"}


def normalized_view(view):
    """The newer spelling of a view: ``as``, ``show``, ``of`` (and the other
    fields unchanged); the older ``type``/``p``/``value``/``elem`` read as
    mec2 read them."""
    v = dict(view)
    v.setdefault("as", v.get("type"))
    if "of" not in v:
        v["of"] = v.get("p", v.get("elem"))
    if "show" not in v:
        v["show"] = v.get("value", "pos" if v["as"] == "trace" else None)
    return v


def check_cosmetics(data):
    """``(views, shapes, warning)``: the usable views (path, normalized)
    and shapes (path, shape), and one warning text naming every unknown
    kind or field (None when all are known)."""
    unknown, views, shapes = [], [], []
    for i, view in enumerate(_list(data.get("views"))):
        path = "$.views[%d]" % i
        bad = _unknown(view, _VIEW_FIELDS, path)
        kind = normalized_view(view).get("as") if isinstance(view, dict) else None
        if kind not in VIEW_KINDS and not bad:
            bad = ["%s.%s = %r (known kinds: %s)" % (path, "as" if "as" in view else "type",
                                                      kind, ", ".join(VIEW_KINDS))]
        unknown += bad
        if not bad:
            views.append((path, normalized_view(view)))
    for i, shape in enumerate(_list(data.get("shapes"))):
        path = "$.shapes[%d]" % i
        bad = _unknown(shape, _SHAPE_FIELDS, path)
        if not bad and shape.get("type") not in _SHAPE_TYPES:
            bad = ["%s.type = %r (known: %s)" % (path, shape.get("type"),
                                                 ", ".join(sorted(_SHAPE_TYPES)))]
        unknown += bad
        if not bad:
            shapes.append((path, shape))
    text = None if not unknown else (
        "views and shapes left out (they only draw; the model is loaded): unknown %s"
        % "; ".join(unknown))
    return views, shapes, text


def _list(value):
    return value if isinstance(value, list) else []


def _unknown(obj, known, path):
    """Unknown fields of ``obj`` and known ones of the wrong type."""
    if not isinstance(obj, dict):
        return ["%s (not an object)" % path]
    out = []
    for key, value in obj.items():
        kind = known.get(key, "unknown")
        if kind == "unknown":
            out.append("%s.%s" % (path, key))
        elif kind == _NUMBER and (isinstance(value, bool) or not isinstance(value, (int, float))
                                  or not math.isfinite(value)):
            out.append("%s.%s (must be %s)" % (path, key, kind))
        elif kind == _TEXT and not isinstance(value, str):
            out.append("%s.%s (must be %s)" % (path, key, kind))
    return out


def warn_once(text):
    """Issue the file's one warning (a :class:`Mec2Warning`)."""
    if text:
        warnings.warn(text, Mec2Warning, stacklevel=3)


def vector_arrows(view, nodes, loads, gravity, names=None):
    """Arrow shapes of a vector view of a node's ``vel``, ``acc`` or
    ``force`` (see module doc), or a reason string why it is not drawn.
    ``nodes``: {id: node component}; ``loads``: the file's load objects;
    ``gravity``: (gx, gy) in m/s^2."""
    show, of = view.get("show"), view.get("of")
    if show not in _COLORS:
        return "a vector of %r has no counterpart (vel, acc and force are drawn)" % (show,)
    if of not in nodes:
        return "vector of %s: %r is no node (vectors of nodes are drawn)" % (show, of)
    at = view.get("at") if view.get("at") in nodes else of
    base = {"type": "arrow", "x": at + ".x", "y": at + ".y", "color": _COLORS[show],
            "unit": _UNITS[show], "anchor": "tail"}
    if show == "vel":
        return [dict(base, fx="der(%s.x)" % of, fy="der(%s.y)" % of, label="v " + of)]
    if show == "acc":
        return [dict(base, fx="der(der(%s.x))" % of, fy="der(der(%s.y))" % of,
                     label="a " + of)]
    return _force_arrows(base, of, nodes[of], loads, gravity) or \
        "force of %s: no load acts on the node" % of


def _force_arrows(base, of, node, loads, gravity):
    """One arrow per load on the node: a force load (its port carries minus
    the force: drawn turned by pi), a spring end, the weight."""
    out = []
    for load in loads:
        if load.get("type", "force") == "force" and load.get("p") == of:
            end = load["id"] + ".port"
        elif load.get("type") == "spring" and of in (load.get("p1"), load.get("p2")):
            end = load["id"] + (".a" if load.get("p1") == of else ".b")
        else:
            continue
        out.append(dict(base, fx=end + ".fx", fy=end + ".fy", angle=math.pi,
                        label="F %s" % load["id"], anchor="head"))
    m = float(node.parameter_value("m")) if not node.base else 0.0
    if m and any(gravity):
        out.append(dict(base, fx=m * gravity[0], fy=m * gravity[1], label="G " + of,
                        anchor="head"))
    return out
