"""Import of mec2 models (goessner/mec2 v0.9.5, MIT; the JSON format of
``<mec-2>`` elements and mec2's documentation).

:func:`load_mec2` reads a ``.json`` file (``acausal2d simulate|check
model.json`` and ``acausal2d.load_model("x.json")`` call it) and returns a
:class:`~acausal2d.library.nodes.NodeModel`.  The file is parsed with
:mod:`json` (never evaluated); every field is checked, and an unknown or
malformed field raises :class:`~acausal2d.errors.ModelDefinitionError`
naming its JSON path (``$.constraints[2].ori.type``).

Mapping (mec2 -> acausal2d):

* units: positions and lengths in mec2's user unit u = 1 cm (``m_u =
  0.01``), so ``length_unit = 0.01``; masses kg (default 1), angles rad,
  time s, force loads in N, spring rates ``k`` in N/m (as mec2's code
  uses them; its documentation says N/cm), ``len0`` in u.
* ``gravity: true`` -> (0, -10) m/s^2 (mec.gravity); an object ``{x, y,
  active}`` counts only with ``active: true``, as in mec2.
* ``tolerance`` low/medium/high -> the position correction's lentol
  1e-5/1e-3/0.1 u (mec.tol.len), used for the assembly and dragging.
* nodes ``{id, x, y, m, base}`` -> nodes (``idloc``, ``label``: drawing).
* constraints ``{id, p1, p2, ori, len}``: ``type`` free / const / drive
  (the legacy ``"type": "ref"`` is const with ``ref``); const without ref
  holds the value (``w0``/``r0`` if given: node p2 is first moved to
  ``p1 + r0 e(w0)``, as mec2's initVector does); const with ``ref`` couples
  ``q = q0 + ratio (q_ref - q_ref0)`` (``reftype`` for the cross types,
  ``passive`` for one-way coupling); drive -> the mec2 drive law (``func``,
  ``args``, ``t0``, ``Dt``, ``Dw``/``Dr``, ``bounce``, ``repeat``; with
  ``ref`` a drive relative to the reference).  ``input: true`` (a slider on
  mec2's page) drives over time like any drive.
* loads: ``force {p, value, w0, wref}``, ``spring {p1, p2, k, len0}``.
* views (both spellings, :mod:`acausal2d.library.nodes.mec2_views`): traces of
  node positions and vectors of a node's vel/acc/force become traces and
  arrows of the animation; the other views (points, charts, infos,
  relative and pole traces) have no counterpart and are listed in the
  model's ``mec2_views_not_drawn``.  Shapes ``fix`` and ``flt`` draw
  ground symbols; the other shapes are cosmetic and not drawn.  Unknown
  view or shape fields give one warning and are left out: they never stop
  a model from loading.

The experiment runs until the last drive ends (mec2 drives stop after
``t0 + Dt`` times bounce and repeat), else for the longest view duration,
else 1 s, with 60 output points per second (mec2's timer step 1/60 s)."""
import json
import math
import os
import re
from typing import Any

from acausal2d.errors import ModelDefinitionError
from acausal2d.io.files import read_json

from .mec2_views import check_cosmetics, vector_arrows, warn_once
from .model import NodeModel
from .specs import mec2_drive, ref

__all__ = ["load_mec2", "model_from_mec2", "Mec2Model"]

_NUM, _STR, _BOOL = "number", "string", "boolean"
_TOP = {"id": _STR, "title": _STR, "gravity": "gravity", "tolerance": _STR, "labels": "object",
        "nodes": "list", "constraints": "list", "loads": "list", "shapes": "any",
        "views": "any"}                  # views and shapes: checked by mec2_views
_NODE = {"id": _STR, "x": _NUM, "y": _NUM, "m": _NUM, "base": _BOOL, "idloc": "any",
         "label": "any"}
_CSTR = {"id": _STR, "p1": _STR, "p2": _STR, "ori": "object", "len": "object", "idloc": "any",
         "label": "any", "lw": "any", "ls": "any", "ld": "any"}    # lw, ls, ld: line style
_SUB = {"type": _STR, "ref": _STR, "reftype": _STR, "ratio": _NUM, "passive": _BOOL,
        "func": _STR, "args": "list", "t0": _NUM, "Dt": _NUM, "bounce": _BOOL,
        "repeat": _NUM, "input": _BOOL}
_LOADS = {"force": {"type": _STR, "id": _STR, "p": _STR, "value": _NUM, "w0": _NUM,
                    "wref": _STR, "mode": _STR},
          "spring": {"type": _STR, "id": _STR, "p1": _STR, "p2": _STR, "k": _NUM,
                     "len0": _NUM}}
_TOLERANCE = {"low": 1e-5, "medium": 1e-3, "high": 0.1}
_UNIT = 0.01            # m per mec2 user unit (mec.m_u)


def _error(path, message):
    return ModelDefinitionError("%s: %s" % (path, message))


def _kind_ok(value, kind):
    if kind == _NUM:
        return isinstance(value, (int, float)) and not isinstance(value, bool) \
            and math.isfinite(value)
    if kind == _STR:
        return isinstance(value, str)
    if kind == _BOOL:
        return isinstance(value, bool)
    if kind == "list":
        return isinstance(value, list)
    if kind == "object":
        return isinstance(value, dict)
    if kind == "gravity":
        return isinstance(value, (bool, dict))
    return True


def _fields(obj, schema, path, required=()):
    """Check that ``obj`` is an object with known, well-typed fields."""
    if not isinstance(obj, dict):
        raise _error(path, "must be an object {...}, not %s" % json.dumps(obj)[:40])
    for key, value in obj.items():
        if key not in schema:
            raise _error("%s.%s" % (path, key), "unknown field (known here: %s)"
                         % ", ".join(sorted(schema)))
        if not _kind_ok(value, schema[key]):
            raise _error("%s.%s" % (path, key), "must be a %s, not %s"
                         % (schema[key], json.dumps(value)[:40]))
    for key in required:
        if key not in obj:
            raise _error(path, "the required field %r is missing" % key)
    return obj


def _items(data, key):
    return [("$.%s[%d]" % (key, i), item) for i, item in enumerate(data.get(key) or [])]


def _ids(items, path_kind):
    seen = {}
    for path, item in items:
        nid = item["id"]
        if not re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", nid):
            raise _error(path + ".id", "%r is no usable id (letters, digits and _, not "
                         "starting with a digit)" % nid)
        if nid in seen:
            raise _error(path + ".id", "%r is used twice (also %s)" % (nid, seen[nid]))
        seen[nid] = path
    return seen


def validate_mec2(data):
    """Check a parsed mec2 model (see module doc); raises errors naming the
    JSON path.  Returns ``data``."""
    _fields(data, _TOP, "$")
    if "tolerance" in data and data["tolerance"] not in _TOLERANCE:
        raise _error("$.tolerance", "must be one of low, medium, high, not %r"
                     % data["tolerance"])
    if isinstance(data.get("gravity"), dict):
        _fields(data["gravity"], {"x": _NUM, "y": _NUM, "active": _BOOL}, "$.gravity")
    nodes = _items(data, "nodes")
    for path, node in nodes:
        _fields(node, _NODE, path, ("id",))          # x, y default to 0 (mec.node.js)
        if "m" in node and not node["m"] > 0:
            raise _error(path + ".m", "the mass must be > 0 (a base node is fixed by "
                         "\"base\": true)")
    node_ids = _ids(nodes, "node")
    cstrs = _items(data, "constraints")
    for path, c in cstrs:
        _check_constraint(c, path, node_ids)
    cstr_ids = _ids(cstrs, "constraint")
    _check_refs(cstrs, cstr_ids)
    for path, load in _items(data, "loads"):
        _check_load(load, path, node_ids, cstr_ids)
    _ids([(p, x) for p, x in nodes + cstrs + [(p, l) for p, l in _items(data, "loads")]
          if "id" in x], "element")
    return data


def _check_constraint(c, path, node_ids):
    _fields(c, _CSTR, path, ("id", "p1", "p2"))
    for end in ("p1", "p2"):
        if c[end] not in node_ids:
            raise _error("%s.%s" % (path, end), "%r is no node (nodes: %s)"
                         % (c[end], ", ".join(node_ids) or "none"))
    for sub, extra in (("ori", {"w0": _NUM, "Dw": _NUM}), ("len", {"r0": _NUM, "Dr": _NUM})):
        if sub not in c:
            continue
        spath = "%s.%s" % (path, sub)
        value = _fields(c[sub], dict(_SUB, **extra), spath)
        kind = value.get("type", "free")
        if kind not in ("free", "const", "drive", "ref"):
            raise _error(spath + ".type", "unknown constraint type %r (known: free, const, "
                         "drive, ref)" % kind)
        if value.get("reftype", "ori") not in ("ori", "len"):
            raise _error(spath + ".reftype", "must be 'ori' or 'len', not %r"
                         % value["reftype"])
        if kind == "ref" and "ref" not in value:
            raise _error(spath, "type 'ref' needs the field 'ref'")
        if "Dt" in value and not value["Dt"] > 0:
            raise _error(spath + ".Dt", "the drive duration must be > 0")
        if "repeat" in value and not (value["repeat"] >= 1 and value["repeat"] ==
                                      int(value["repeat"])):
            raise _error(spath + ".repeat", "must be a whole number >= 1")


def _check_refs(cstrs, cstr_ids):
    for path, c in cstrs:
        for sub in ("ori", "len"):
            target = (c.get(sub) or {}).get("ref")
            if target is not None and target not in cstr_ids:
                raise _error("%s.%s.ref" % (path, sub), "%r is no constraint (constraints: %s)"
                             % (target, ", ".join(cstr_ids)))
            if target == c["id"]:
                raise _error("%s.%s.ref" % (path, sub), "a constraint cannot reference itself")


def _check_load(load, path, node_ids, cstr_ids):
    kind = load.get("type", "force") if isinstance(load, dict) else None
    if kind not in _LOADS:
        raise _error(path + ".type", "unknown load type %r (known: force, spring)" % kind)
    _fields(load, _LOADS[kind], path, ("id",) + (("p",) if kind == "force" else ("p1", "p2")))
    for end in ("p", "p1", "p2"):
        if end in load and load[end] not in node_ids:
            raise _error("%s.%s" % (path, end), "%r is no node" % load[end])
    if "wref" in load and load["wref"] not in cstr_ids:
        raise _error(path + ".wref", "%r is no constraint" % load["wref"])
    for key in ("value", "k", "len0"):
        if key in load and load[key] < 0:
            raise _error("%s.%s" % (path, key), "must not be negative")


def _order(cstrs):
    """Constraints with every referenced one before the constraints using
    it (mec2 initializes references first); a cycle is an error."""
    by_id = {c["id"]: (p, c) for p, c in cstrs}
    done, out, busy = set(), [], set()

    def visit(cid):
        if cid in done:
            return
        path, c = by_id[cid]
        if cid in busy:
            raise _error(path, "the references of constraint %r form a cycle" % cid)
        busy.add(cid)
        for sub in ("ori", "len"):
            target = (c.get(sub) or {}).get("ref")
            if target is not None:
                visit(target)
        busy.discard(cid)
        done.add(cid)
        out.append((path, c))
    for _, c in cstrs:
        visit(c["id"])
    return out


def _gravity(data):
    g = data.get("gravity")
    if g is True:
        return (0.0, -10.0)
    if isinstance(g, dict) and g.get("active"):
        return (float(g.get("x", 0.0)), float(g.get("y", -10.0)))
    return (0.0, 0.0)


def _drive_end(sub):
    if sub.get("type") != "drive":
        return 0.0
    return sub.get("t0", 0.0) + sub.get("Dt", 1.0) * (2 if sub.get("bounce") else 1) \
        * sub.get("repeat", 1)


def _experiment(data, views):
    ends = [_drive_end(c.get(s) or {}) for c in data.get("constraints") or () for s in ("ori", "len")]
    stop = max(ends, default=0.0)
    if stop <= 0:
        stop = max([v.get("t0", 0.0) + v.get("Dt", 0.0) for _, v in views],
                   default=0.0) or 1.0
    return {"stop_time": stop, "intervals": max(100, int(round(60 * stop))), "rtol": 1e-8}


class Mec2Model(NodeModel):
    """A node model built from a validated mec2 model (see the module doc);
    subclasses made by :func:`model_from_mec2` carry the class attributes
    (gravity, lentol, experiment).  ``mec2_traces``: the traced nodes;
    ``mec2_views_not_drawn``: the views without counterpart, with why."""
    length_unit = _UNIT

    def __init__(self, data, views=None, shapes=None, **kw):
        super().__init__(**kw)
        if views is None:
            views, shapes, text = check_cosmetics(data)
            warn_once(text)
        self.__dict__.update(mec2_traces=[], mec2_views_not_drawn=[], _grounds=[],
                             mec2_arrows=[], pole_views=[])
        coords = {n["id"]: [float(n.get("x", 0.0)), float(n.get("y", 0.0))]
                  for n in data.get("nodes") or ()}
        cstrs = _order(_items(data, "constraints"))
        _initial_vectors(cstrs, coords)
        for n in data.get("nodes") or ():
            self.node(n["id"], *coords[n["id"]], m=n.get("m", 1.0), base=n.get("base", False))
        for path, c in cstrs:
            self._constraint(path, c)
        for path, load in _items(data, "loads"):
            self._load(load)
        self._views(views, data.get("loads") or [])
        self._grounds.extend(s["p"] for _, s in shapes
                             if s["type"] in ("fix", "flt") and "p" in s)

    def _constraint(self, path, c):
        values = {}
        for sub, kind in (("ori", "ang"), ("len", "len")):
            values[kind] = _value(c.get(sub) or {}, kind)
        self.n2(c["id"], c["p1"], c["p2"], len=values["len"], ang=values["ang"])

    def _load(self, load):
        if load.get("type", "force") == "force":
            self.force(load["id"], load["p"], load.get("value", 1.0), load.get("w0", 0.0),
                       load.get("wref"))
        else:
            self.spring(load["id"], load["p1"], load["p2"], load.get("k", 0.01),
                        load.get("len0"))

    def _views(self, views, loads):
        """Traces and vector arrows of the views (both spellings, already
        normalized by :func:`~acausal2d.library.nodes.mec2_views.normalized_view`)."""
        for path, v in views:
            kind, node = v["as"], v.get("of")
            why = "no counterpart in the animation"
            if kind == "trace" and v.get("show") == "pos" and node in self._nodes \
                    and "ref" not in v:
                self.mec2_traces.append(node)
                continue
            if v.get("show") == "pole" and node in self._cstrs and "ref" not in v:
                self.pole_views.append({"link": node, "text": "P(%s)" % node,
                                        "trace": kind == "trace"})
                continue
            if kind == "vector":
                arrows = vector_arrows(v, self._nodes, loads, self.gravity)
                if not isinstance(arrows, str):
                    self.mec2_arrows.extend(dict(a, optional=True) for a in arrows)
                    continue
                why = arrows
            self.mec2_views_not_drawn.append("%s (%s of %s): %s"
                                             % (path, kind, v.get("show") or "?", why))

    def shapes(self):
        out = super().shapes()
        out += [{"type": "trace", "x": n + ".x", "y": n + ".y"} for n in self.mec2_traces]
        out += [dict(a) for a in self.mec2_arrows]
        out += [{"type": "ground", "x": n + ".x", "y": n + ".y"} for n in self._grounds
                if n in self._nodes and not self._nodes[n].base]
        return out


def _value(sub, kind):
    """The front end's value for a mec2 ``ori``/``len`` object."""
    t = sub.get("type", "free")
    if t == "ref":
        t = "const"                     # legacy form (before mec2 commit c0f3a17)
    reftype = sub.get("reftype", kind.replace("ang", "ori")).replace("ori", "ang")
    if t == "free":
        return None
    if t == "drive":
        rng = sub.get("Dw" if kind == "ang" else "Dr")
        law = mec2_drive(func=sub.get("func", "linear"), Dz=rng, Dt=sub.get("Dt", 1.0),
                         t0=sub.get("t0", 0.0), repeat=sub.get("repeat"),
                         bounce=sub.get("bounce", False), args=sub.get("args"))
        if "ref" in sub:
            return ref(sub["ref"], of=reftype, relative=True, passive=sub.get("passive", False),
                       drive=law)
        return law
    if "ref" in sub:
        return ref(sub["ref"], ratio=sub.get("ratio", 1.0), of=reftype, relative=True,
                   passive=sub.get("passive", False))
    return "const"


def _initial_vectors(cstrs, coords):
    """mec2's initVector: where ``r0`` or ``w0`` is given, node p2 moves to
    ``p1 + r0 e(w0)`` (with a reference: relative to its start value)."""
    start = {}
    for path, c in cstrs:
        (x1, y1), (x2, y2) = coords[c["p1"]], coords[c["p2"]]
        r, w = math.hypot(x2 - x1, y2 - y1), math.atan2(y2 - y1, x2 - x1)
        ln, ori = c.get("len") or {}, c.get("ori") or {}
        if "r0" in ln:
            r = ln["r0"] + (ln.get("ratio", 1.0) * start[ln["ref"]][0]
                            if "ref" in ln and ln.get("reftype", "len") == "len" else 0.0)
        if "w0" in ori:
            w = ori["w0"] + (ori.get("ratio", 1.0) * start[ori["ref"]][1]
                             if "ref" in ori and ori.get("reftype", "ori") == "ori" else 0.0)
        if "r0" in ln or "w0" in ori:
            coords[c["p2"]] = [x1 + r * math.cos(w), y1 + r * math.sin(w)]
        start[c["id"]] = (r, w)


def model_from_mec2(data, name="Mec2Model", source=None):
    """A node model instance from the parsed mec2 model ``data`` (a dict);
    ``name`` becomes the model's class name, ``source`` (a file name) its
    documentation.  Raises errors naming the JSON path."""
    validate_mec2(data)
    views, shapes, text = check_cosmetics(data)
    warn_once(text)
    cls_name = re.sub(r"\W", "_", name) or "Mec2Model"
    doc = "mec2 model %s%s." % (data.get("title") or data.get("id") or cls_name,
                               " (from %s)" % source if source else "")
    attrs = {"__doc__": doc, "gravity": _gravity(data), "experiment": _experiment(data, views),
             "lentol": _TOLERANCE[data.get("tolerance", "medium")],
             "outputs": [n["id"] + "." + xy for n in data.get("nodes") or ()
                         if not n.get("base") for xy in ("x", "y")][:8]}
    cls = type(cls_name, (Mec2Model,), attrs)
    return cls(data, views, shapes)


def load_mec2(path: str) -> Any:
    """Read the mec2 model file ``path`` (JSON) into a node model; syntax
    errors name line and column, wrong fields their JSON path."""
    if not os.path.isfile(path):
        raise ModelDefinitionError("model file %s does not exist" % path)
    data = read_json(path, ModelDefinitionError, "mec2 model file")
    try:
        stem = os.path.splitext(os.path.basename(path))[0]
        return model_from_mec2(data, name=data.get("id") if isinstance(data, dict) and
                               isinstance(data.get("id"), str) else stem, source=path)
    except ModelDefinitionError as exc:
        raise ModelDefinitionError("%s: %s" % (path, exc)) from None
