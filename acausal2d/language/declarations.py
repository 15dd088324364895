"""Declarations of the modelling language: :class:`Parameter` (SI units,
value rules), :class:`Variable` (start, fixed, nominal, state priority),
:func:`start` (per-instance attributes), :class:`VarInfo` (a flattened
unknown), and the generated documentation tables of a component class.
"""
import inspect
import math
import os
import sys
import numbers

import numpy as np

from ..errors import ModelDefinitionError
from .connector_doc import LazyDoc

STATE_SELECT = ("never", "avoid", "default", "prefer", "always")


def _fmt_value(v):
    arr = np.atleast_1d(np.asarray(v, dtype=float))
    return "%g" % arr[0] if arr.size == 1 else "(%s)" % ", ".join("%g" % x for x in arr)


class Parameter:
    """A parameter declared on a component class.

    ``default`` is a number or a tuple of numbers (a vector parameter);
    ``unit`` is the SI unit and ``doc`` a one-line description.  The value
    rules ``min``/``max`` (inclusive bounds), ``positive`` (> 0) and
    ``nonzero`` (a vector of nonzero length, a scalar other than 0) are
    checked wherever a value is set.  Inside ``equations()`` the attribute
    is a CasADi symbol; elsewhere (e.g. in ``__init__``) it is the numeric
    value.
    """

    def __init__(self, default: float | tuple[float, ...], unit: str = "", doc: str = "",
                 min: float | None = None, max: float | None = None, positive: bool = False,
                 nonzero: bool = False) -> None:
        self.default = default
        self.unit = unit
        self.doc = doc
        self.min, self.max, self.positive = min, max, bool(positive)
        self.nonzero = bool(nonzero)
        self.name: str | None = None

    def __set_name__(self, owner, name):
        self.name = name

    def __repr__(self):
        return "Parameter(%s%s%s%s)" % (
            _fmt_value(self.default), ", %r" % self.unit if self.unit else "",
            ", %r" % self.doc if self.doc else "", ", " + self.rule if self.rule else "")

    @property
    def size(self):
        """Number of scalars of the parameter (2 for a planar vector)."""
        return int(np.size(self.default))

    @property
    def rule(self):
        """The value rule as text ('> 0', '>= 0', '0 <= value <= 1') or ''."""
        parts = []
        if self.positive:
            parts.append("> 0")
        if self.min is not None and not (self.positive and self.min <= 0):
            parts.append(">= %g" % self.min)
        if self.max is not None:
            parts.append("<= %g" % self.max)
        if self.nonzero:
            parts.append("nonzero length" if self.size > 1 else "!= 0")
        return " and ".join(parts)

    def validated(self, value: object, where: str) -> float | tuple[float, ...]:
        """``value`` as float (scalar) or tuple of floats; raises
        :class:`ModelDefinitionError` naming ``where`` (component and
        parameter) if it has the wrong type or size, is not finite or breaks
        the declared rule."""
        desc = "%s: parameter %s" % (where, self.name)
        arr = self._numbers(value, desc)
        if not np.all(np.isfinite(arr)):
            raise ModelDefinitionError("%s = %r is not finite; give a finite number" % (desc, value))
        if not all(self._obeys(x) for x in arr) or (self.nonzero and not np.any(arr != 0)):
            raise ModelDefinitionError("%s = %s breaks its rule %s (%s%s)" % (
                desc, _fmt_value(arr), self.rule, self.doc or "value",
                ", " + self.unit if self.unit else ""))
        return float(arr[0]) if self.size == 1 else tuple(float(x) for x in arr)

    def _numbers(self, value, desc):
        """``value`` as a flat float array of the declared size; strings,
        booleans and None are refused alone, in a list or in a numpy array
        (of strings, booleans or objects) alike."""
        if _not_a_number(value):
            raise ModelDefinitionError("%s = %r is not a number%s" % (
                desc, value, " (give %d numbers)" % self.size if self.size > 1 else ""))
        try:
            arr = np.asarray(value, dtype=float).ravel()
        except (TypeError, ValueError):
            raise ModelDefinitionError("%s = %r is not a number" % (desc, value)) from None
        if arr.size != self.size:
            raise ModelDefinitionError("%s takes %d value%s, got %r" % (
                desc, self.size, "s" if self.size > 1 else "", value))
        return arr

    def _obeys(self, x):
        return not ((self.positive and not x > 0) or (self.min is not None and x < self.min)
                    or (self.max is not None and x > self.max))

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        sym = obj._param_syms.get(self.name)
        if sym is not None:
            return sym
        return obj.parameter_value(self.name)


def _not_a_number(value):
    """True for a string, a boolean, None, a complex number, or a list,
    tuple or numpy array holding any of them (a numpy array of booleans,
    strings or objects is judged by its elements, not converted)."""
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "iuf":
            return False
        if value.dtype.kind != "O":
            return True                            # bool, str, bytes, complex, datetime ...
        return any(_not_a_number(v) for v in value.ravel())
    if isinstance(value, (list, tuple)):
        return any(_not_a_number(v) for v in value)
    return value is None or isinstance(value, (str, bytes, bool, np.bool_, complex,
                                               np.complexfloating))


def _creation_site():
    """``file:line`` of the user code creating a component: the first
    caller outside the package and its library (the name of the component
    is not known while it is being constructed)."""
    frame = sys._getframe(1)
    while frame is not None:
        module = frame.f_globals.get("__name__", "")
        if module != "acausal2d" and not module.startswith("acausal2d."):
            return "%s:%d" % (os.path.basename(frame.f_code.co_filename), frame.f_lineno)
        frame = frame.f_back
    return "?"


def _check_state_select(value, where):
    if value not in STATE_SELECT:
        raise ModelDefinitionError("%sstate_select must be one of %s, not %r"
                                   % (where, ", ".join(STATE_SELECT), value))


def _check_nominal(value, where):
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or \
            not math.isfinite(value) or not value > 0:
        raise ModelDefinitionError("%snominal must be a positive finite number, not %r"
                                   % (where, value))


class Variable:
    """An unknown of a component.

    start: start value (a guess unless ``fixed``); fixed: hold the start
    value at initialization; nominal: magnitude used for scaling and
    tolerances (> 0); state_select: one of ``never, avoid, default, prefer,
    always`` (Modelica's StateSelect) to guide state selection.
    """

    def __init__(self, start=0.0, fixed=False, nominal=1.0, state_select="default",
                 unit="", doc=""):
        _check_state_select(state_select, "")
        _check_nominal(nominal, "")
        self.start = start
        self.fixed = fixed
        self.nominal = nominal
        self.state_select = state_select
        self.unit = unit
        self.doc = doc
        self.name = None

    def __set_name__(self, owner, name):
        self.name = name

    def __repr__(self):
        return "Variable(unit=%r%s)" % (self.unit, ", doc=%r" % self.doc if self.doc else "")

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        return obj._var_symbol(self.name)

    def copy(self):
        """An independent copy (each component instance owns its declarations)."""
        v = Variable(self.start, self.fixed, self.nominal, self.state_select, self.unit, self.doc)
        v.name = self.name
        return v


class start:
    """Per-instance change of a variable's attributes, given as a keyword
    argument named like the variable: ``Revolute(phi=start(0.5, fixed=True))``.
    Attributes left as None keep the component's default."""

    def __init__(self, value=None, fixed=None, state_select=None, nominal=None):
        if state_select is not None:
            _check_state_select(state_select, "start(): ")
        if nominal is not None:
            _check_nominal(nominal, "start(): ")
        if value is not None and not isinstance(value, bool) and isinstance(value, numbers.Real) \
                and not math.isfinite(value):
            raise ModelDefinitionError("start(): the start value must be finite, not %r" % value)
        self.value = value
        self.fixed = fixed
        self.state_select = state_select
        self.nominal = nominal

    def apply(self, var):
        """Write the given attributes into the declaration ``var``."""
        if self.value is not None:
            var.start = self.value
        if self.fixed is not None:
            var.fixed = self.fixed
        if self.state_select is not None:
            var.state_select = self.state_select
        if self.nominal is not None:
            var.nominal = self.nominal


class VarInfo:
    """A flattened scalar unknown: full dotted name, CasADi symbol and
    attributes (start, fixed, nominal, state_select, unit, doc)."""

    __slots__ = ("name", "sym", "start", "fixed", "nominal", "state_select", "unit", "doc",
                 "owner")

    def __init__(self, name, sym, decl, owner):
        self.name = name
        self.sym = sym
        self.start = decl.start
        self.fixed = decl.fixed
        self.nominal = decl.nominal
        self.state_select = decl.state_select
        self.unit = decl.unit
        self.doc = decl.doc
        self.owner = owner

    def __repr__(self):
        return "VarInfo(%s)" % self.name


def _declarations(cls, kind):
    """{name: declaration} of the ``kind`` attributes of ``cls`` and its
    bases (the most derived declaration of a name wins), in declaration
    order, base classes first."""
    found = {}
    for klass in reversed(cls.__mro__):
        for name, attr in vars(klass).items():
            if isinstance(attr, kind):
                found[name] = attr
    return found


def _doc_table(rows, indent="    "):
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]) - 1)]
    return "\n".join((indent + "  ".join(c.ljust(w) for c, w in zip(r, widths))
                      + "  " + r[-1]).rstrip() for r in rows)


def declaration_doc(cls):
    """The docstring of component class ``cls`` (as written, or its base
    class's) followed by tables of its parameters (name, default, unit,
    rule, description) and class-level variables (name, unit, description),
    inherited ones included; set as ``cls.__doc__`` for every subclass so
    that ``help(Body)`` shows them."""
    own = vars(cls).get("_written_doc", vars(cls).get("__doc__"))
    text = inspect.cleandoc(own) if own else ""
    marker = "\n\nParameters (default, unit, rule, description):\n"
    params = _declarations(cls, Parameter)
    if params:
        rows = [(n, _fmt_value(p.default), p.unit or "-", p.rule or "-", p.doc)
                for n, p in params.items()]
        text += marker + _doc_table(rows)
    variables = _declarations(cls, Variable)
    if variables:
        rows = [(n, v.unit or "-", v.doc) for n, v in variables.items()]
        text += "\n\nVariables (unit, description):\n" + _doc_table(rows)
    return text.lstrip("\n") or None


def add_declarations(cls, declarations):
    """Declare the :class:`Parameter` and :class:`Variable` objects of the
    dict ``declarations`` (name -> declaration) on the component class
    ``cls`` after its creation, as if written in its body, and renew its
    documented tables (for declarations that several classes share, e.g.
    the mass data of a body)."""
    for name, decl in declarations.items():
        decl.__set_name__(cls, name)
        setattr(cls, name, decl)
    cls.__doc__ = LazyDoc(declaration_doc)
    return cls


def _join(path, name):
    return name if not path else path + "." + name
