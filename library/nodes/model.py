"""Nodes and constraints: the modelling style of Schnabel and Gössner's talk "Lightweight
prototypal mechanism simulation on the web" (Schnabel, Goessner; the
libraries cstr.js and mec2), compiled into the same DAE as every other
model.

A :class:`NodeModel` holds nodes (point masses with x, y, m, base) and
constraints between them::

    class FourBar(NodeModel):
        length_unit = 1e-3                        # coordinates in mm
        def __init__(self, **kw):
            super().__init__(**kw)
            A0 = self.node("A0", 0, 0, base=True)
            A = self.node("A", 0, 60, m=10)
            B = self.node("B", 120, 60)
            B0 = self.node("B0", 180, -60, base=True)
            self.n2("A0A", A0, A, len="const", ang=speed(2 * pi))
            self.n2("AB", A, B, len="const")
            self.n2("B0B", B0, B, len="const")

``n2(id, n1, n2, len=..., ang=..., dir=...)`` constrains the vector from
n1 to n2 (talk eq. 3: ``p2 - p1 = r e(w)``) by its length r and angle w,
each one of

* absent / ``None`` / ``"free"``: free;
* ``"const"``: held at the value the given coordinates have;
* a number: held at that value (length in the model's coordinate unit,
  angle in rad);
* :func:`speed` (Schnabel and Gössner's drives: ``+pi/180`` per tick), :func:`drive`
  (a function of time) or :func:`mec2_drive` (mec2's drive functions): a
  prescribed value, the model's input;
* :func:`ref` (cstr.js ``from``, mec2 ``ref`` with ``ratio``) and
  :func:`delta` (cstr.js ``ang.delta``): coupled to other constraints;
* :func:`between`, :func:`at_least`, :func:`at_most` (cstr.js ``range``,
  ``min``, ``max``): unilateral.  With a ``source`` (a drive or a
  reference) the source's value is clamped into the range; the motion
  stops at the limit and resumes when the source comes back (events).
  Without a source the value is free inside the range, and where the
  motion would carry it out of the range the model's drive (or the one
  named by ``stops``) is stopped: the mechanism rests at the limit (a
  state event), as cstr.js's correction fails beyond it.

``dir=+1/-1`` with a held angle (cstr.js) keeps the vector pointing along
/ against the angle (a range ``r >= 0`` / ``r <= 0``).  ``n3(id, n1, n2, n3,
ang)`` holds the angle between the lines n1->n2 and n1->n3.  Loads:
:meth:`NodeModel.force`, :meth:`NodeModel.spring`; gravity: the class
attribute ``gravity``.

Every node becomes a :class:`~acausal2d.library.nodes.Node`, every
constraint a :class:`~acausal2d.library.nodes.Link` (or
:class:`~acausal2d.library.nodes.IncludedAngle`) with the elements that
hold, drive or couple its values; their frames (``node.frame``,
``link.frame``) connect library elements, so a node model can carry a
pulley or a VDI element.  Schnabel and Gössner's degree of freedom (eq. 1) and loop
count (eq. 2) are :meth:`NodeModel.node_counts`, printed by ``acausal2d
check``.  The start values come from the position correction of eq. 3-16
(:mod:`acausal2d.library.nodes.correction`) applied to the given
coordinates, so rough coordinates are enough."""
import math
import re

from acausal2d.errors import ModelDefinitionError
from acausal2d.language.dsl import Component
from acausal2d.library.planar import PlanarWorld

from .correction import PositionCorrection
from .drives import BASE_FUNCTIONS, is_full_turn, seq_law
from .elements import (AngleDrive, AngleHold, Coupling, IncludedAngle, LengthDrive, LengthHold,
                       Link, Node, NodeForce, NodeSpring)
from .specs import (NodeAssemblyError,
                    _ang_from_len_source, _Delta, _delta_source, _Drive,
                    _is_number, _len_from_ang_source, _linear_source, _link_start, _mec2_law,
                    _quantity, _Range, _Ref, _relative_source, _scaled, _spec_dict)

__all__ = ["NodeModel"]

_ID = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


class NodeModel(Component):
    """Base class of node/constraint models (see the module doc).

    Class attributes: ``length_unit`` (metres per coordinate unit of
    :meth:`node` and of lengths given as numbers; 1e-3 for coordinates in
    mm, mec2's 0.01 for cm), ``gravity`` ((gx, gy) in m/s^2; Schnabel and Gössner's talk
    neglects impressed forces, Q = 0, so the default is (0, 0)),
    ``lentol`` (coordinate units) and ``itrmax``: the position
    correction's tolerance and sweep limit (cstr.js: 0.1, 256)."""
    length_unit = 1.0
    gravity = (0.0, 0.0)
    lentol = 0.1
    itrmax = 256

    def __init__(self, **kw):
        super().__init__(**kw)
        self.__dict__.update(_nodes={}, _cstrs={}, _lines=[], _ranges=[], _ports={})
        self.world = PlanarWorld(g=tuple(float(g) for g in self.gravity))

    # ------------------------------------------------------------ building
    def _check_id(self, nid, what):
        if not isinstance(nid, str) or not _ID.match(nid):
            raise ModelDefinitionError(
                "%s: %s id %r is not a name (letters, digits and _, not starting with a digit)"
                % (type(self).__name__, what, nid))
        if nid in self._children or hasattr(type(self), nid) or nid in self.__dict__:
            raise ModelDefinitionError("%s: %s id %r is already used (ids of nodes, "
                                       "constraints and loads share one namespace)"
                                       % (type(self).__name__, what, nid))

    def _node(self, n):
        nid = n if isinstance(n, str) else getattr(n, "_name", None)
        if nid not in self._nodes:
            raise ModelDefinitionError("%s: %r is no node of the model (nodes: %s)" % (
                type(self).__name__, n, ", ".join(self._nodes) or "none"))
        return nid, self._nodes[nid]

    def node(self, nid, x, y, m=1.0, base=False, counted=True):
        """Add the node ``nid`` at (x, y) (coordinate units); ``m`` [kg]
        (0: massless), ``base``: fixed to ground, ``counted=False``: left out
        of eq. 1/2 (see :class:`~acausal2d.library.nodes.Node`)."""
        self._check_id(nid, "node")
        u = self.length_unit
        node = Node(x0=float(x) * u, y0=float(y) * u, m=m, base=base, counted=counted)
        setattr(self, nid, node)
        self._nodes[nid] = node
        return node

    def _start(self, nid):
        n = self._nodes[nid]
        return float(n.parameter_value("x0")), float(n.parameter_value("y0"))

    def _geometry(self, id1, id2):
        (x1, y1), (x2, y2) = self._start(id1), self._start(id2)
        return math.hypot(x2 - x1, y2 - y1), math.atan2(y2 - y1, x2 - x1)

    def n2(self, cid, n1, n2, len=None, ang=None, dir=0, draw="auto"):
        """Constraint ``cid`` on the vector from node ``n1`` to ``n2`` (talk
        eq. 3); ``len``/``ang``: see the module doc; ``dir``: +1/-1 with a
        held angle; ``draw``: 'bar', 'slider', None or 'auto' (a bar where
        the length is held, a slider on a guide where only the angle is)."""
        self._check_id(cid, "constraint")
        (id1, a), (id2, b) = self._node(n1), self._node(n2)
        if draw == "auto":
            draw = "bar" if len not in (None, "free") else \
                "slider" if ang not in (None, "free") else None
        link = Link(draw=draw)
        setattr(self, cid, link)
        self.connect(a.port, link.a)
        self.connect(b.port, link.b)
        self._ports.update({cid + ".a": id1, cid + ".b": id2})
        rec = {"id": cid, "type": "n2", "link": link, "n1": id1, "n2": id2, "dir": int(dir)}
        self._cstrs[cid] = rec
        rec["len"] = self._value(rec, "len", len)
        rec["ang"] = self._value(rec, "ang", ang)
        if dir:
            if rec["ang"]["kind"] == "free":
                raise ModelDefinitionError("%s: dir needs a held angle (cstr.js)" % link.describe())
            self._ranges.append((rec, "len", 0.0 if dir > 0 else None,
                                 0.0 if dir < 0 else None, None))
        return link

    def n3(self, cid, n1, n2, n3, ang="const"):
        """Three-node constraint (cstr.js ``n3``): the angle from the line
        n1->n2 to the line n1->n3 is held at ``ang`` ('const': as the
        coordinates give it, or a number in rad)."""
        self._check_id(cid, "constraint")
        ids = [self._node(n)[0] for n in (n1, n2, n3)]
        if ang == "const":
            w12, w13 = self._geometry(ids[0], ids[1])[1], self._geometry(ids[0], ids[2])[1]
            ang = math.remainder(w13 - w12, 2 * math.pi)
        elif not _is_number(ang):
            raise ModelDefinitionError("%s: n3 %s takes ang='const' or a number, not %r"
                                       % (type(self).__name__, cid, ang))
        elem = IncludedAngle(value=float(ang))
        setattr(self, cid, elem)
        for port, nid in zip((elem.a, elem.b, elem.c), ids):
            self.connect(self._nodes[nid].port, port)
            self._ports[cid + "." + port._name] = nid
        self._cstrs[cid] = {"id": cid, "type": "n3", "link": elem, "n1": ids[0], "n2": ids[1],
                            "n3": ids[2]}
        return elem

    # ------------------------------------------------------------ values
    def _value(self, rec, kind, spec):
        """Create the element for one value of a constraint; returns its
        record {kind, element, ...}."""
        link, u = rec["link"], self.length_unit
        if spec is None or spec == "free":
            return {"kind": "free"}
        r0, w0 = self._geometry(rec["n1"], rec["n2"])
        start = r0 if kind == "len" else w0
        if spec == "const" or _is_number(spec):
            value = start if spec == "const" else float(spec) * (u if kind == "len" else 1.0)
            return self._hold(link, kind, value)
        if isinstance(spec, _Range):
            return self._range(rec, kind, spec, start)
        return self._source(rec, kind, spec, start)

    def _hold(self, link, kind, value):
        elem = (LengthHold if kind == "len" else AngleHold)(value=value)
        setattr(link, kind + "_hold", elem)
        self.connect(getattr(link, kind), elem.flange)
        return {"kind": "hold", "element": elem}

    def _source(self, rec, kind, spec, start, clamp=(None, None)):
        if isinstance(spec, _Drive):
            return self._drive(rec, kind, spec, start, clamp)
        if isinstance(spec, (_Ref, _Delta)):
            return self._coupling(rec, kind, spec, clamp)
        raise ModelDefinitionError(
            "%s: %s=%r is no constraint value; use None, 'const', a number, speed(), drive(), "
            "mec2_drive(), ref(), delta(), between(), at_least() or at_most()"
            % (rec["link"].describe(), kind, spec))

    def _range(self, rec, kind, spec, start):
        scale = self.length_unit if kind == "len" else 1.0
        lo = None if spec.lo is None else float(spec.lo) * scale
        hi = None if spec.hi is None else float(spec.hi) * scale
        if spec.source is not None:
            out = self._source(rec, kind, spec.source, start, clamp=(lo, hi))
            out.update(lo=lo, hi=hi)
            return out
        self._ranges.append((rec, kind, lo, hi, spec.stops))
        return {"kind": "range", "lo": lo, "hi": hi}

    def _law(self, rec, kind, spec):
        """(law, parameters) of a drive spec in SI units (see
        :class:`~acausal2d.library.nodes.AngleDrive`)."""
        scale = self.length_unit if kind == "len" else 1.0
        params = {k: float(v) for k, v in spec.params.items() if v is not None}
        if "om" in params:
            params["om"] *= scale
        if spec.label == "function":
            return (_scaled(spec.law, scale) if kind == "len" else spec.law), params
        if spec.label != "mec2":
            return spec.law, params
        where = "%s.%s" % (rec["id"], kind)
        name = spec.extra["func"]
        func = seq_law(spec.extra.get("args"), where + ".args") if name == "seq" else \
            BASE_FUNCTIONS.get(name)
        if func is None:
            raise ModelDefinitionError("%s: unknown drive function %r (known: %s)" % (
                where, name, ", ".join(sorted(list(BASE_FUNCTIONS) + ["seq"]))))
        params["Dz"] = params.get("Dz", 2 * math.pi if kind == "ang" else 100.0) * scale
        repeat, bounce = spec.extra["repeat"], bool(spec.extra["bounce"])
        join = kind == "ang" and repeat is not None and is_full_turn(func, params["Dz"])
        return _mec2_law(func, repeat, bounce, join), params

    def _drive(self, rec, kind, spec, start, clamp):
        scale = self.length_unit if kind == "len" else 1.0
        law, params = self._law(rec, kind, spec)
        z0 = start if spec.extra.get("start") is None else float(spec.extra["start"]) * scale
        params.update(z0=z0, **{k: v for k, v in zip(("lo", "hi"), clamp) if v is not None})
        elem = (LengthDrive if kind == "len" else AngleDrive)(
            law, clamp=(clamp[0] is not None, clamp[1] is not None), **params)
        setattr(rec["link"], kind + "_drive", elem)
        self.connect(getattr(rec["link"], kind), elem.flange)
        return {"kind": "drive", "element": elem}

    def _ref_record(self, rec, cid):
        if cid not in self._cstrs or self._cstrs[cid]["type"] != "n2":
            raise ModelDefinitionError(
                "%s: the reference %r is no two-node constraint declared before it (declared: "
                "%s)" % (rec["link"].describe(), cid,
                         ", ".join(k for k, v in self._cstrs.items() if v["type"] == "n2")
                         or "none"))
        return self._cstrs[cid]

    def _coupling(self, rec, kind, spec, clamp):
        link = rec["link"]
        if isinstance(spec, _Delta):
            refs = [self._ref_record(rec, spec.frm), self._ref_record(rec, spec.to)]
            kinds, ports = ["ang", "ang", "ang"], [r["link"].ang for r in refs]
            source, params = _delta_source, {"ratio": spec.scl}
            out = {"kind": "delta", "refs": [spec.frm, spec.to], "scl": spec.scl}
            if kind != "ang":
                raise ModelDefinitionError("%s: delta() couples angles only" % link.describe())
        else:
            kinds, ports, source, params, out = self._ref_parts(rec, kind, spec)
        params.update({k: v for k, v in zip(("lo", "hi"), clamp) if v is not None})
        law = None
        if getattr(spec, "drive", None) is not None:
            law, extra = self._law(rec, kind, spec.drive)
            params.update(extra)
            out["drive"] = True
        elem = Coupling(kinds, source, passive=getattr(spec, "passive", False),
                        clamp=(clamp[0] is not None, clamp[1] is not None), drive=law, **params)
        setattr(link, kind + "_ref", elem)
        self.connect(getattr(link, kind), elem.q0)
        for k, port in enumerate(ports, start=1):
            self.connect(getattr(elem, "q%d" % k), port)
        out["element"] = elem
        return out

    def _ref_parts(self, rec, kind, spec):
        """(kinds, reference ports, source, parameters, record) of a ref()."""
        other = self._ref_record(rec, spec.cid)
        of = spec.of or kind
        own_start = self._geometry(rec["n1"], rec["n2"])[0 if kind == "len" else 1]
        ref_start = self._geometry(other["n1"], other["n2"])[0 if of == "len" else 1]
        out = {"kind": "ref", "ref": spec.cid, "of": of, "ratio": spec.ratio}
        if of == kind:
            ports = [getattr(other["link"], of)]
            if spec.relative:
                params = {"ratio": spec.ratio, "base": own_start, "ref0": ref_start}
                return [kind, of], ports, _relative_source, params, out
            scale = self.length_unit if kind == "len" else 1.0
            params = {"ratio": spec.ratio, "offset": spec.offset * scale}
            return [kind, of], ports, _linear_source, params, out
        if not spec.relative:
            raise ModelDefinitionError(
                "%s: a %s coupled to a %s needs ref(..., relative=True) (mec2's cross types)"
                % (rec["link"].describe(), kind, of))
        params = {"ratio": spec.ratio, "base": own_start, "ref0": ref_start}
        out.update(kind=kind + "_from_" + of, base=own_start, ref0=ref_start)
        if kind == "ang":       # w = w0 + ratio (r_ref - r_ref0) / r
            return ["ang", "len", "len"], [other["link"].len, rec["link"].len], \
                _ang_from_len_source, params, out
        return ["len", "ang", "len"], [other["link"].ang, other["link"].len], \
            _len_from_ang_source, params, out


    # ------------------------------------------------------------ loads, drawing
    def force(self, lid, node, value, w0=0.0, wref=None):
        """Force load of ``value`` N on ``node`` in the direction ``w0``
        (rad), or ``w0`` against the angle of the constraint ``wref`` (mec2
        ``force``)."""
        self._check_id(lid, "load")
        nid, n = self._node(node)
        elem = NodeForce(value=value, w0=w0, relative=wref is not None)
        setattr(self, lid, elem)
        self.connect(n.port, elem.port)
        self._ports[lid + ".port"] = nid
        if wref is not None:
            self.connect(elem.ang, self._ref_record({"link": elem}, wref)["link"].ang)
        return elem

    def spring(self, lid, n1, n2, k, len0=None):
        """Linear spring of rate ``k`` [N/m] between two nodes (mec2
        ``spring``); ``len0`` (coordinate units) defaults to the distance
        the coordinates give."""
        self._check_id(lid, "load")
        (id1, a), (id2, b) = self._node(n1), self._node(n2)
        length = self._geometry(id1, id2)[0] if len0 is None else float(len0) * self.length_unit
        elem = NodeSpring(k=k, len0=length)
        setattr(self, lid, elem)
        self.connect(a.port, elem.a)
        self.connect(b.port, elem.b)
        self._ports.update({lid + ".a": id1, lid + ".b": id2})
        return elem

    def line(self, n1, n2):
        """A bar drawn between two nodes that is no constraint (e.g. a
        coupler whose length the other constraints keep)."""
        self._lines.append((self._node(n1)[0], self._node(n2)[0]))

    def shapes(self):
        return [{"type": "link", "points": [[a + ".x", a + ".y"], [b + ".x", b + ".y"]],
                 "color": "#8fa9c4"} for a, b in self._lines]

    # ------------------------------------------------------------ ranges
    def derived_parameters(self, context):
        """Attach the ranges without source to the drives they stop (see
        the module doc); nothing is derived.  Clears the assembly of the
        previous flattening."""
        self.__dict__["_assembled"] = None
        drives = {}
        for rec in self._cstrs.values():
            for kind in ("len", "ang"):
                if rec.get(kind, {}).get("kind") == "drive":
                    drives[rec["id"]] = rec[kind]["element"]
                    rec[kind]["element"].set_stops([])
        for rec, kind, lo, hi, stops in self._ranges:
            target = self._stopped_drive(rec, kind, drives, stops)
            quantity = _quantity(rec["link"], kind)
            target.set_stops(target.stops + [(quantity, lo, hi)])
        return {}

    def _stopped_drive(self, rec, kind, drives, stops):
        where = "%s: the range of %s" % (rec["link"].describe(), kind)
        if stops is not None:
            if stops not in drives:
                raise ModelDefinitionError("%s stops %r, which is no driven constraint (driven: "
                                           "%s)" % (where, stops, ", ".join(drives) or "none"))
            return drives[stops]
        if len(drives) != 1:
            raise ModelDefinitionError(
                "%s has no source; at its limit it stops the model's drive, but the model has "
                "%s. Name the drive to stop with stops='id', or give the range a source "
                "(between(lo, hi, source=...)). Free motion against a stop would need an "
                "impact, which the node front end does not model."
                % (where, "%d drives (%s)" % (len(drives), ", ".join(drives)) if drives
                   else "none"))
        return next(iter(drives.values()))


    # ------------------------------------------------------------ eq. 1 and 2
    def node_counts(self):
        """Schnabel and Gössner's structure counts: N nodes, N_base of them fixed, C1
        constraints fixing one of (len, ang), C2 fixing both, the degree of
        freedom ``F = 2 (N - N_base) - C1 - 2 C2`` (eq. 1) and the number of
        independent loops ``m = C1 + C2 - N + N_base`` (eq. 2).  A driven
        value is the input and no constraint ("driven constraints handled
        as Schnabel and Gössner's talk does": the needle-bar drive's crank A0A, len + driven
        ang, is one C1); nodes with ``counted=False`` and their constraints
        are left out (Schnabel and Gössner's "G nicht beachtet").  Returns a dict with
        N, N_base, C1, C2, F, m, ``driven`` (the driven values) and
        ``not_counted`` (node and constraint ids left out)."""
        counted = {k for k, n in self._nodes.items() if n.counted}
        out = {"N": len(counted), "N_base": sum(self._nodes[k].base for k in counted),
               "C1": 0, "C2": 0, "driven": [], "not_counted": sorted(set(self._nodes) - counted)}
        for rec in self._cstrs.values():
            ids = [rec[k] for k in ("n1", "n2", "n3") if k in rec]
            if not all(i in counted for i in ids):
                out["not_counted"].append(rec["id"])
                continue
            if rec["type"] == "n3":
                out["C1"] += 1
                continue
            held = 0
            for kind in ("len", "ang"):
                k = "drive" if rec[kind].get("drive") else rec[kind]["kind"]
                if k == "drive":
                    out["driven"].append("%s.%s" % (rec["id"], kind))
                held += k not in ("free", "drive")
            if held:
                out["C%d" % held] += 1
        out["F"] = 2 * (out["N"] - out["N_base"]) - out["C1"] - 2 * out["C2"]
        out["m"] = out["C1"] + out["C2"] - out["N"] + out["N_base"]
        return out

    # ------------------------------------------------------------ description
    def node_system(self, drives=True):
        """Plain description of the nodes and constraints with the current
        parameter values (SI units) for the position correction
        (:class:`~acausal2d.library.nodes.correction.PositionCorrection`) and
        the animation page's drag mode.  ``drives=False`` leaves the driven
        values free (dragging) and gives a JSON-serializable dict."""
        nodes = [{"id": k, "x": float(n.parameter_value("x0")), "y": float(n.parameter_value("y0")),
                  "m": float(n.parameter_value("m")), "base": n.base}
                 for k, n in self._nodes.items()]
        cstrs = []
        for rec in self._cstrs.values():
            c = {k: rec[k] for k in ("id", "type", "n1", "n2", "n3") if k in rec}
            if rec["type"] == "n3":
                c["value"] = float(rec["link"].parameter_value("value"))
            else:
                c["dir"] = rec["dir"]
                for kind in ("len", "ang"):
                    c[kind] = _spec_dict(rec[kind], drives)
            cstrs.append(c)
        return {"nodes": nodes, "constraints": cstrs, "itrmax": int(self.itrmax),
                "lentol": float(self.lentol) * self.length_unit}

    def drag_system(self):
        """What the animation page needs to drag this model's nodes:
        :meth:`node_system` without drives (the user drives by dragging)
        and ``signals``, the result signals that are node coordinates,
        constraint lengths or angles ({name: [node, 'x'|'y'] or ['length'|
        'angle', node1, node2]}), qualified with the model's path."""
        out = self.node_system(drives=False)
        pre = self.path + "." if self.path else ""
        sig = {}
        for nid in self._nodes:
            sig.update({pre + nid + ".x": [nid, "x"], pre + nid + ".y": [nid, "y"]})
        for port, nid in self._ports.items():
            sig.update({pre + port + ".x": [nid, "x"], pre + port + ".y": [nid, "y"]})
        for cid, rec in self._cstrs.items():
            if rec["type"] == "n2":
                sig[pre + cid + ".r"] = ["length", rec["n1"], rec["n2"]]
                sig[pre + cid + ".w"] = ["angle", rec["n1"], rec["n2"]]
        out["signals"] = sig
        return out

    # ------------------------------------------------------------ assembly
    def node_guesses(self, context, comp):
        """Start guesses of a node, link or included angle of this model
        from the node assembly (computed once per flattening)."""
        return {k: v for k, v in self.assembly_values().get(id(comp), {}).items()
                if comp.has_variable(k)}

    def assembly_values(self):
        """Start values of the nodes, links and included angles ({id(comp):
        {variable: value}}) from the node assembly; computed once per
        flattening (the cache is cleared by :meth:`derived_parameters`)."""
        if self.__dict__.get("_assembled") is None:
            self.__dict__["_assembled"] = self._assembly()
        return self._assembled

    def assemble(self):
        """The position correction of the given coordinates at t = 0 (talk
        eq. 3-16) with the model's lentol, but at most 1e-4 of the extent of
        the node coordinates (a start close enough for the DAE's Newton):
        a :class:`~acausal2d.library.nodes.correction.PositionCorrection`
        after ``correct()`` and its
        :class:`~acausal2d.library.nodes.correction.Correction`; raises
        :class:`NodeAssemblyError` if the mechanism cannot close."""
        system = self.node_system()
        xs = [n[k] for n in system["nodes"] for k in ("x", "y")]
        span = max(xs) - min(xs) if xs else 1.0
        solver = PositionCorrection(system, lentol=min(system["lentol"], 1e-4 * span or 1.0))
        report = solver.correct(0.0)
        if not report.converged:
            raise NodeAssemblyError(
                "%s: the node assembly (position correction, talk eq. 3-16) found no closed "
                "position in %d sweeps (lentol %g m); the last sweep was undone. The largest "
                "correction, %.4g m, is in constraint %r: the mechanism cannot close with these "
                "lengths and coordinates. Check the lengths, or give coordinates nearer a closed "
                "position." % (type(self).__name__, report.iterations, solver.lentol,
                               report.largest, report.worst), report)
        return solver, report

    def _assembly(self):
        solver, _ = self.assemble()
        out = {}
        for nid, node in self._nodes.items():
            x, y = solver.positions()[nid]
            out[id(node)] = {"x": x, "y": y}
        for rec in self._cstrs.values():
            out[id(rec["link"])] = _link_start(solver, rec)
        return out
