"""The values a constraint of a :class:`~acausal2d.library.nodes.NodeModel`
can be given (talk: const, ref, drive, range; cstr.js and mec2 spellings):
:func:`speed`, :func:`drive`, :func:`mec2_drive`, :func:`ref`,
:func:`delta`, :func:`between`, :func:`at_least`, :func:`at_most`, and the
source laws and solver descriptions the node model builds from them.
"""
from typing import Optional
import math
import numbers

from acausal2d.errors import InitializationError, ModelDefinitionError

from .drives import mec2_law


class NodeAssemblyError(InitializationError):
    """The node assembly (talk eq. 3-16 on the given coordinates) found no
    consistent position: the mechanism cannot close.  ``correction`` is the
    :class:`~acausal2d.library.nodes.correction.Correction` (iterations,
    undone)."""

    def __init__(self, message, correction=None):
        super().__init__(message)
        self.correction = correction


# ---------------------------------------------------------------- value specs
class _Spec:
    """A constraint value other than free/const/number."""
    kind: Optional[str] = None

    def __repr__(self):
        return "%s(%s)" % (type(self).__name__, ", ".join(
            "%s=%r" % kv for kv in sorted(vars(self).items())))


class _Drive(_Spec):
    kind = "drive"

    def __init__(self, law, params, label, **extra):
        self.law, self.params, self.label = law, dict(params), label
        self.extra = extra


def speed(om, start=None):
    """Drive at constant speed from the value the coordinates give (or
    ``start``): ``z(t) = z0 + om t`` - Schnabel and Gössner's drives, which add a fixed
    increment each tick.  om in rad/s (angles) or coordinate units per
    second (lengths)."""
    return _Drive(lambda t, get: get("z0") + get("om") * t, {"om": om}, "speed", start=start)


def drive(func):
    """Drive by a function of time: ``func(t)`` returns the value (rad, or
    coordinate units for lengths) as a CasADi expression of the time
    symbol, like cstr.js's getter drives (``get ang() {...}``)."""
    return _Drive(lambda t, get: func(t), {}, "function")


def mec2_drive(func="linear", Dz=None, Dt=1.0, t0=0.0, repeat=None, bounce=False, args=None,
               start=None):
    """A mec2 drive (mec.drive.js): ``z(t) = z0 + Dz f(q)``, ``q = clamp((t -
    t0)/Dt_total, 0, 1)``, see :mod:`acausal2d.library.nodes.drives`.  Dz
    defaults to 2 pi (angles) or 100 coordinate units (lengths) as in
    mec2."""
    return _Drive(None, {"Dz": Dz, "Dt": Dt, "t0": t0}, "mec2", func=func, repeat=repeat,
                  bounce=bounce, args=args, start=start)


class _Ref(_Spec):
    kind = "ref"

    def __init__(self, cid, ratio, offset, of, passive, relative, drive=None):
        self.cid, self.ratio, self.offset, self.of = cid, ratio, offset, of
        self.passive, self.relative, self.drive = passive, relative, drive


def ref(cid, ratio=1.0, offset=0.0, of=None, passive=False, relative=False, drive=None):
    """Coupled to the value ``of`` ('ang' or 'len'; default: the same kind)
    of constraint ``cid``: ``q = ratio q_ref + offset`` (cstr.js
    ``ang.from(id, offset)``, ``len.from(id, scl)``); with
    ``relative=True`` as in mec2, ``q = q0 + ratio (q_ref - q_ref0)`` with
    the values q0, q_ref0 the coordinates give (a length coupled to an
    angle: ``r = r0 + ratio r_ref (w_ref - w_ref0)``; an angle coupled to a
    length: ``w = w0 + ratio (r_ref - r_ref0) / r``).  ``passive=True``
    (mec2): no force back into the referenced value.  ``drive`` (a
    :func:`mec2_drive`, started from 0) adds a prescribed motion to the
    coupled value (mec2's drive with ``ref``: ``w = w0 + (w_ref - w_ref0) +
    z(t)``)."""
    if drive is not None and not isinstance(drive, _Drive):
        raise ModelDefinitionError("ref(..., drive=) takes a drive such as mec2_drive(), "
                                   "not %r" % (drive,))
    return _Ref(cid, float(ratio), float(offset), of, bool(passive), bool(relative), drive)


class _Delta(_Spec):
    kind = "delta"

    def __init__(self, frm, to, scl):
        self.frm, self.to, self.scl = frm, to, float(scl)


def delta(frm, to, scl):
    """Angle between two constraints' angles (cstr.js ``ang.delta``):
    ``w = w_from + scl (w_to - w_from)`` (the angle bisector with 1/2)."""
    return _Delta(frm, to, scl)


class _Range(_Spec):
    kind = "range"

    def __init__(self, lo, hi, source, stops):
        self.lo, self.hi, self.source, self.stops = lo, hi, source, stops


def between(lo, hi, source=None, stops=None):
    """Unilateral range ``lo <= value <= hi`` (cstr.js ``range``); see the
    module doc for ranges with and without a ``source``; ``stops`` names
    the driven constraint a range without source stops (default: the
    model's only drive)."""
    return _Range(lo, hi, source, stops)


def at_least(lo, source=None, stops=None):
    """Unilateral ``value >= lo`` (cstr.js ``min``); see :func:`between`."""
    return _Range(lo, None, source, stops)


def at_most(hi, source=None, stops=None):
    """Unilateral ``value <= hi`` (cstr.js ``max``); see :func:`between`."""
    return _Range(None, hi, source, stops)


# ---------------------------------------------------------------- the model
def _is_number(v):
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _linear_source(q, get):
    return get("ratio") * q[0] + get("offset")


def _relative_source(q, get):
    return get("base") + get("ratio") * (q[0] - get("ref0"))


def _delta_source(q, get):
    return q[0] + get("ratio") * (q[1] - q[0])


def _ang_from_len_source(q, get):
    return get("base") + get("ratio") * (q[0] - get("ref0")) / q[1]


def _len_from_ang_source(q, get):
    return get("base") + get("ratio") * q[1] * (q[0] - get("ref0"))


def _mec2_law(func, repeat, bounce, join):
    return lambda t, get: mec2_law(t, get("z0"), get("Dz"), get("t0"), get("Dt"), func,
                                   repeat, bounce, join)


def _scaled(law, scale):
    return lambda t, get: scale * law(t, get)


def _quantity(link, kind):
    return lambda: link.r if kind == "len" else link.w


def _spec_dict(value, drives):
    """The solver's description of one constraint value (see
    :meth:`NodeModel.node_system`)."""
    k, elem = value["kind"], value.get("element")
    if k == "free":
        out = {"kind": "free"}
    elif k == "hold":
        out = {"kind": "value", "value": float(elem.parameter_value("value"))}
    elif k == "drive":
        out = {"kind": "drive"}
        if drives:
            out["at"] = elem.numeric_law()
    elif k == "range":
        out = {"kind": "range"}
    elif k == "delta":
        out = {"kind": "delta", "from": value["refs"][0], "to": value["refs"][1],
               "scl": float(elem.parameter_value("ratio"))}
    else:
        out = _ref_dict(value, elem)
        if value.get("drive") and drives:
            out["plus"] = elem.numeric_drive()
        elif value.get("drive"):
            out = {"kind": "drive"}
    for bound in ("lo", "hi"):
        if value.get(bound) is not None:
            out[bound] = float(value[bound])
    return out


def _ref_dict(value, elem):
    pv = elem.parameter_value
    if value["kind"] == "ref":
        ratio = float(pv("ratio"))
        if elem.source is _relative_source:
            offset = float(pv("base")) - ratio * float(pv("ref0"))
        else:
            offset = float(pv("offset"))
        return {"kind": "ref", "ref": value["ref"], "of": value["of"], "ratio": ratio,
                "offset": offset}
    return {"kind": value["kind"], "ref": value["ref"], "ratio": float(pv("ratio")),
            "base": float(pv("base")), "ref0": float(pv("ref0"))}


def _link_start(solver, rec):
    """Start values of a link's (or included angle's) unknowns after the
    assembly: held angles at their targets, lengths as signed projections
    (so that the polar form holds exactly)."""
    c = solver.by_id[rec["id"]]
    if rec["type"] == "n3":
        (x12, y12), (x13, y13) = solver.vector(c), solver.vector(c, "n1", "n3")
        w12 = math.atan2(y12, x12)
        w13 = w12 + c["value"]
        return {"r12": math.hypot(x12, y12), "w12": w12, "w13": w13,
                "r13": x13 * math.cos(w13) + y13 * math.sin(w13)}
    w = solver.target(c, "ang")
    if w is None:
        w = solver.angle(rec["id"])
    dx, dy = solver.vector(c)
    x1, y1 = solver.positions()[rec["n1"]]
    return {"w": w, "r": dx * math.cos(w) + dy * math.sin(w), "x1": x1, "y1": y1}
