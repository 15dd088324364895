"""The modelling language: components, parameters, variables, equations.

A component is a Python class::

    class Spring(Component):
        '''Linear rotational spring.'''
        c = Parameter(1.0, "N.m/rad", "spring constant", positive=True)
        phi_rel = Variable(unit="rad", doc="relative angle")

        def __init__(self, **kw):
            super().__init__(**kw)
            self.flange_a = RotationalFlange()
            self.flange_b = RotationalFlange()

        def equations(self):
            return [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                    self.flange_b.tau == self.c * self.phi_rel,
                    self.flange_a.tau == -self.flange_b.tau]

Parameters are declared on the class and set by keyword (``Spring(c=10)``);
inside ``equations()`` they are symbolic, so a new value never needs a
recompilation.  Variables may be declared on the class or assigned in
``__init__``; their start values and attributes are changed per instance with
:func:`start` (``Revolute(phi=start(0, fixed=True))``).  Models are components
that hold other components as attributes and wire their connectors with
:meth:`Component.connect`.  A component that uses a model-wide component
(the gravity field of the planar library) declares it with :class:`Outer`.

Hooks a component may define, called once per flattening in this order:
:meth:`~Component.derived_parameters` (numeric values of parameters computed
from the whole model), :meth:`~Component.guesses` (start guesses),
:meth:`~Component.equations`.  After a simulation, :meth:`~Component.shapes`
and :meth:`~Component.topology` describe drawing and structure.
"""
import inspect
import math
import os
import sys
import numbers

import numpy as np

from ..errors import ModelDefinitionError

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

    def __init__(self, default, unit="", doc="", min=None, max=None, positive=False,
                 nonzero=False):
        self.default = default
        self.unit = unit
        self.doc = doc
        self.min, self.max, self.positive = min, max, bool(positive)
        self.nonzero = bool(nonzero)
        self.name = None

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

    def validated(self, value, where):
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
        """``value`` as a flat float array of the declared size."""
        if isinstance(value, (str, bytes, bool)) or value is None:
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


class Outer:
    """A model-wide component this component uses (Modelica's inner/outer):
    ``world = Outer(PlanarWorld)`` on a class makes ``self.world`` the
    nearest instance of ``PlanarWorld`` among the children of the
    component's ancestors (the model it is part of, then that model's
    parent, ...).  If the model holds none, flattening adds one with
    default parameters to the outermost model."""

    def __init__(self, cls):
        self.cls = cls
        self.name = None

    def __set_name__(self, owner, name):
        self.name = name

    def __repr__(self):
        return "Outer(%s)" % self.cls.__name__

    def find(self, comp):
        """The instance ``comp`` uses, or None if the model holds none."""
        node = comp._parent
        while node is not None:
            for child in node._children.values():
                if isinstance(child, self.cls):
                    return child
            node = node._parent
        return None

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        found = self.find(obj)
        if found is None:
            raise ModelDefinitionError(
                "%s uses a %s, but its model holds none; it is added when the model is "
                "compiled" % (obj.describe(), self.cls.__name__))
        return found


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
    own = vars(cls).get("__doc__")
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


def _join(path, name):
    return name if not path else path + "." + name


class Component:
    """Base class of every component and model.

    Subclasses declare :class:`Parameter` and :class:`Variable` attributes on
    the class, create connectors and sub-components in ``__init__`` (after
    calling ``super().__init__(**kw)``), wire them with :meth:`connect` and
    return their equations from :meth:`equations`.  Keyword arguments set
    parameter values or, with :func:`start` (or a number), variable
    attributes.
    """

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        cls.__doc__ = declaration_doc(cls)

    def __init__(self, **kwargs):
        d = self.__dict__
        d.update(_name=None, _parent=None, _children={}, _connectors={}, _var_decls={},
                 _var_syms={}, _param_syms={}, _param_values={}, _given=set(), _derived={},
                 _connections=[], _overrides={}, _var_infos={})
        for cls in reversed(type(self).__mro__):
            for name, attr in vars(cls).items():
                if isinstance(attr, Parameter):
                    d["_param_values"][name] = attr.default
                elif isinstance(attr, Variable):
                    d["_var_decls"][name] = attr.copy()
        for name, value in kwargs.items():
            if name in d["_param_values"]:
                decl = self.parameter_declaration(name)
                try:
                    d["_param_values"][name] = decl.validated(value, type(self).__name__)
                except ModelDefinitionError:     # the same error, saying where (walks the stack)
                    decl.validated(value, "%s created at %s" % (type(self).__name__,
                                                                 _creation_site()))
                    raise
                d["_given"].add(name)
            else:
                d["_overrides"][name] = value

    # ----------------------------------------------------------- declarations
    def parameter_declaration(self, name):
        """The :class:`Parameter` declared on the class as ``name``."""
        for cls in type(self).__mro__:
            attr = vars(cls).get(name)
            if isinstance(attr, Parameter):
                return attr
        raise ModelDefinitionError("%s has no parameter %r; parameters: %s" % (
            type(self).__name__, name, ", ".join(sorted(self._param_values)) or "none"))

    def parameter_value(self, name):
        """Numeric value of the parameter ``name`` (float or tuple): given by
        keyword, else derived for the current flattening
        (:meth:`derived_parameters`), else the declared default."""
        if name in self._given:
            return self._param_values[name]
        if name in self._derived:
            return self._derived[name]
        if name not in self._param_values:
            self.parameter_declaration(name)        # raises with the list
        return self._param_values[name]

    def is_given(self, name):
        """True if the model set the parameter or variable ``name`` of this
        component by keyword (a parameter value, ``start(...)`` or a number)."""
        return name in self._given or name in self._overrides

    def start_value(self, name):
        """Numeric start value of the variable ``name``: the value given with
        :func:`start` (or a number) when the component was created, else the
        declaration's default (0.0 when that is not a number)."""
        ov = self._overrides.get(name)
        if isinstance(ov, start) and ov.value is not None:
            value = ov.value
        elif isinstance(ov, numbers.Real):
            value = ov
        else:
            decl = self._var_decls.get(name)
            value = decl.start if decl is not None else 0.0
        try:
            return float(value)
        except (TypeError, ValueError, RuntimeError):
            return 0.0

    def variable_names(self):
        """Names of the variables this component declares (not its
        connectors')."""
        return list(self._var_decls)

    def has_variable(self, name):
        """True if ``name`` is a variable of this component or, written
        ``"connector.x"``, of one of its connectors."""
        if name in self._var_decls:
            return True
        conn, _, var = name.partition(".")
        c = self._connectors.get(conn)
        return c is not None and var in type(c).potentials + type(c).flows

    def variable(self, name):
        """This instance's declaration (:class:`Variable`) of ``name``; an
        element's ``__init__`` may change its defaults (e.g. ``state_select``)
        before the model's :func:`start` arguments apply."""
        decl = self._var_decls.get(name)
        if decl is None:
            raise ModelDefinitionError("%s has no variable %r" % (type(self).__name__, name))
        return decl

    def __setattr__(self, name, value):
        from .connectors import Connector
        if isinstance(value, Component):
            self._add_child(name, value)
        elif isinstance(value, Connector):
            value._attach(self, name)
            self._connectors[name] = value
        elif isinstance(value, Variable):
            decl = value.copy()
            decl.name = name
            self._var_decls[name] = decl
        elif (isinstance(value, (list, tuple)) and value
              and all(isinstance(v, Component) for v in value)):
            for i, child in enumerate(value):
                self._add_child("%s[%d]" % (name, i), child)
            object.__setattr__(self, name, value)
        elif name in self._param_values:
            raise ModelDefinitionError(
                "%s: set parameter %r as a keyword argument, not by assignment"
                % (type(self).__name__, name))
        else:
            object.__setattr__(self, name, value)

    def _add_child(self, name, child):
        if child._parent is not None:
            raise ModelDefinitionError("component %r is already part of a model as %r"
                                       % (name, child._name))
        child.__dict__["_name"] = name
        child.__dict__["_parent"] = self
        self._children[name] = child

    def __getattr__(self, name):
        d = self.__dict__
        if name.startswith("__") or "_var_decls" not in d:
            raise AttributeError(name)
        if name in d["_var_decls"]:
            return self._var_symbol(name)
        if name in d["_connectors"]:
            return d["_connectors"][name]
        if name in d["_children"]:
            return d["_children"][name]
        raise AttributeError("%s has no attribute %r" % (type(self).__name__, name))

    def _var_symbol(self, name):
        sym = self._var_syms.get(name)
        if sym is None:
            raise ModelDefinitionError(
                "%s.%s is a symbolic variable; it can only be used inside equations()"
                % (type(self).__name__, name))
        return sym

    def add_variable(self, name, **attributes):
        """Declare a variable named ``name`` from ``__init__`` (same keywords
        as :class:`Variable`); for variables whose number depends on
        structural options."""
        setattr(self, name, Variable(**attributes))

    # ----------------------------------------------------------- structure
    def connect(self, a, b):
        """Connect two connectors of this model's sub-components (or of the
        model itself).  Potentials become equal, flows sum to zero."""
        from .connectors import Connector
        for c in (a, b):
            if not isinstance(c, Connector):
                raise ModelDefinitionError("connect() takes connectors, got %r" % (c,))
        if type(a).kind != type(b).kind:
            raise ModelDefinitionError(
                "cannot connect %s (%s) with %s (%s): connector kinds differ"
                % (a.describe(), type(a).kind, b.describe(), type(b).kind))
        if a is b:
            raise ModelDefinitionError("connect(%s, %s) connects a connector with itself"
                                       % (a.describe(), a.describe()))
        self._connections.append((a, b))

    # ----------------------------------------------------------- hooks
    def derived_parameters(self, context):
        """Hook: numeric values of this component's parameters that follow
        from the whole model (e.g. the whole turns of a belt's wrap angle
        from the layout), as ``{name: value}``.  Called once per flattening
        before any symbol exists; ``context`` is the
        :class:`~acausal2d.language.context.ModelContext`.  Values the model
        gave by keyword are never replaced.  Default: none."""
        return {}

    def guesses(self, context):
        """Hook: start guesses for this component's variables, as ``{name:
        value}`` with names relative to the component (``"phi"``,
        ``"frame_a.x"``) and values numbers or parameter expressions (e.g.
        an assembly from the parameters, a branch chosen by a parameter K).
        Called once per flattening after the symbols exist and before
        :meth:`equations`; a start value the model gave with :func:`start`
        wins.  Default: none."""
        return {}

    def equations(self):
        """Return this component's equations: CasADi expressions written as
        ``lhs == rhs`` (or residuals that must vanish), possibly nested in
        lists.  Components without own equations return an empty list."""
        return []

    def shapes(self):
        """How the component is drawn in the animation: a list of shape dicts
        (kinds in :mod:`acausal2d.tools.animation`) whose signal names are
        relative to the component, e.g. ``{"type": "joint", "x": "frame_a.x",
        "y": "frame_a.y"}``.  Default: nothing."""
        return []

    def topology(self):
        """Planar topology for the degree-of-freedom count (seed eq. 2.1):
        a list of ``("ground", [frames])``, ``("rigid", [frames])`` (frames
        of one link) and ``("joint", frame_a, frame_b, f)`` (a joint with f
        degrees of freedom).  Default: nothing."""
        return []

    # ----------------------------------------------------------- tree
    @property
    def path(self):
        """Dotted instance name inside the model ('' for the model itself)."""
        if self._parent is None:
            return ""
        return _join(self._parent.path, self._name)

    @property
    def root(self):
        """The outermost model this component is part of (itself if none)."""
        comp = self
        while comp._parent is not None:
            comp = comp._parent
        return comp

    def describe(self):
        """'ClassName 'path'' for messages."""
        return "%s '%s'" % (type(self).__name__, self.path or "<model>")

    def components(self):
        """This component and all sub-components, depth first."""
        yield self
        for child in self._children.values():
            yield from child.components()

    def outers(self):
        """The :class:`Outer` declarations of this component's class."""
        seen = {}
        for cls in reversed(type(self).__mro__):
            for name, attr in vars(cls).items():
                if isinstance(attr, Outer):
                    seen[name] = attr
        return list(seen.values())

    # ----------------------------------------------------------- flattening
    def _apply_overrides(self):
        for name, decl in self._var_decls.items():
            ov = self._overrides.get(name)
            if ov is None:
                continue
            if isinstance(ov, start):
                ov.apply(decl)
            elif isinstance(ov, numbers.Real) and not isinstance(ov, bool):
                decl.start = float(ov)
            else:
                raise ModelDefinitionError(
                    "%s: variable %r takes start(...) or a number, got %r"
                    % (self.describe(), name, ov))
        unknown = set(self._overrides) - set(self._var_decls)
        if unknown:
            valid = sorted(set(self._param_values) | set(self._var_decls))
            raise ModelDefinitionError(
                "%s has no parameter or variable %s; valid names: %s"
                % (self.describe(), ", ".join(repr(u) for u in sorted(unknown)),
                   ", ".join(valid)))
        for name, decl in self._var_decls.items():
            where = "%s: variable %s: " % (self.describe(), name)
            _check_state_select(decl.state_select, where)
            _check_nominal(decl.nominal, where)

    def _set_derived(self, values):
        """Store the values of :meth:`derived_parameters` (validated)."""
        self._derived.clear()
        for name, value in (values or {}).items():
            decl = self.parameter_declaration(name)
            if name not in self._given:
                self._derived[name] = decl.validated(value, self.describe())

    def _bind(self, table, params_out, vars_out):
        """Create the symbols of this component (full dotted names)."""
        self._apply_overrides()
        path = self.path
        for name in self._param_values:
            decl = self.parameter_declaration(name)
            sym = table.new_parameter(_join(path, name), decl.size)
            self._param_syms[name] = sym if decl.size > 1 else sym[0]
            vals = np.atleast_1d(np.asarray(self.parameter_value(name), dtype=float))
            for i in range(decl.size):
                pname = _join(path, name) + ("[%d]" % i if decl.size > 1 else "")
                params_out.append((pname, sym[i], float(vals[i]), decl))
        self._var_infos.clear()
        for name, decl in self._var_decls.items():
            sym = table.new_variable(_join(path, name))
            self._var_syms[name] = sym
            self._var_infos[name] = VarInfo(_join(path, name), sym, decl, self)
            vars_out.append(self._var_infos[name])
        for cname, conn in self._connectors.items():
            n0 = len(vars_out)
            conn._bind(table, vars_out)
            for info in vars_out[n0:]:
                self._var_infos[cname + "." + info.name.rsplit(".", 1)[1]] = info

    def _apply_guesses(self, values):
        """Start guesses from :meth:`guesses`; the model's own start wins."""
        for name, value in (values or {}).items():
            info = self._var_infos.get(name)
            if info is None:
                raise ModelDefinitionError("%s: guesses() names %r, which is no variable of it"
                                           % (self.describe(), name))
            if not self._has_start_value(name):
                info.start = value

    def _has_start_value(self, name):
        ov = self._overrides.get(name)
        return isinstance(ov, start) and ov.value is not None or \
            isinstance(ov, numbers.Real) and not isinstance(ov, bool)
