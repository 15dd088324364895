"""The modelling language: components, parameters, variables, equations.

A component is a Python class::

    class Spring(Component):
        '''Linear rotational spring.'''
        c = Parameter(1.0, "N.m/rad", "spring constant")
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
:meth:`Component.connect`.  Symbols are created when the model is flattened;
``equations()`` is only called then.
"""
import numbers

import numpy as np

from . import symbols
from ..errors import ModelDefinitionError

STATE_SELECT = ("never", "avoid", "default", "prefer", "always")


class Parameter:
    """A parameter declared on a component class.

    ``default`` is a number or a tuple of numbers (a vector parameter);
    ``unit`` is the SI unit and ``doc`` a one-line description.  Inside
    ``equations()`` the attribute is a CasADi symbol; elsewhere (e.g. in
    ``__init__``) it is the numeric value.
    """

    def __init__(self, default, unit="", doc=""):
        self.default = default
        self.unit = unit
        self.doc = doc
        self.name = None

    def __set_name__(self, owner, name):
        self.name = name

    @property
    def size(self):
        return int(np.size(self.default))

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        sym = obj._param_syms.get(self.name)
        if sym is not None:
            return sym
        return obj._param_values[self.name]


class Variable:
    """An unknown of a component.

    start: start value (a guess unless ``fixed``); fixed: hold the start
    value at initialization; nominal: magnitude used for scaling and
    tolerances; state_select: one of ``never, avoid, default, prefer,
    always`` (Modelica's StateSelect) to guide state selection.
    """

    def __init__(self, start=0.0, fixed=False, nominal=1.0, state_select="default",
                 unit="", doc=""):
        if state_select not in STATE_SELECT:
            raise ModelDefinitionError("state_select must be one of %s, not %r"
                                       % (", ".join(STATE_SELECT), state_select))
        self.start = start
        self.fixed = fixed
        self.nominal = nominal
        self.state_select = state_select
        self.unit = unit
        self.doc = doc
        self.name = None

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, obj, objtype=None):
        if obj is None:
            return self
        return obj._var_symbol(self.name)

    def copy(self):
        v = Variable(self.start, self.fixed, self.nominal, self.state_select, self.unit, self.doc)
        v.name = self.name
        return v


class start:
    """Per-instance change of a variable's attributes, given as a keyword
    argument named like the variable: ``Revolute(phi=start(0.5, fixed=True))``.
    Attributes left as None keep the component's default."""

    def __init__(self, value=None, fixed=None, state_select=None, nominal=None):
        if state_select is not None and state_select not in STATE_SELECT:
            raise ModelDefinitionError("state_select must be one of %s, not %r"
                                       % (", ".join(STATE_SELECT), state_select))
        self.value = value
        self.fixed = fixed
        self.state_select = state_select
        self.nominal = nominal

    def apply(self, var):
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


def _join(path, name):
    return name if not path else path + "." + name


class Component:
    """Base class of every component and model.

    Subclasses declare :class:`Parameter` and :class:`Variable` attributes on
    the class, create connectors and sub-components in ``__init__`` (after
    calling ``super().__init__(**kw)``), wire them with :meth:`connect` and
    return their equations from :meth:`equations`.  Keyword arguments set
    parameter values or, with :func:`start`, variable attributes.
    """

    def __init__(self, **kwargs):
        d = self.__dict__
        d["_name"] = None
        d["_parent"] = None
        d["_path"] = None
        d["_children"] = {}
        d["_connectors"] = {}
        d["_var_decls"] = {}
        d["_var_syms"] = {}
        d["_param_syms"] = {}
        d["_param_values"] = {}
        d["_connections"] = []
        d["_overrides"] = {}
        d["_var_infos"] = {}
        for cls in reversed(type(self).__mro__):
            for name, attr in vars(cls).items():
                if isinstance(attr, Parameter):
                    d["_param_values"][name] = attr.default
                elif isinstance(attr, Variable):
                    d["_var_decls"][name] = attr.copy()
        for name, value in kwargs.items():
            if name in d["_param_values"]:
                decl = self._param_decl(name)
                if np.size(value) != decl.size:
                    raise ModelDefinitionError(
                        "%s: parameter %r takes %d value(s), got %r"
                        % (type(self).__name__, name, decl.size, value))
                d["_param_values"][name] = value
            else:
                d["_overrides"][name] = value

    # ----------------------------------------------------------- declarations
    def _param_decl(self, name):
        for cls in type(self).__mro__:
            attr = vars(cls).get(name)
            if isinstance(attr, Parameter):
                return attr
        raise KeyError(name)

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

    def before_flatten(self):
        """Hook called once per flattening for every component, before any
        symbol exists: the place to compute parameter values or start values
        from the whole model's numeric data (e.g. a belt layout).  Default:
        nothing."""

    def on_flatten(self):
        """Hook called once per flattening, after all symbols of the model
        exist and before any ``equations()`` is called (e.g. to reset caches
        built from symbols).  Default: nothing."""

    def set_start(self, name, value):
        """Set the start value (a guess: number or parameter expression) of
        the variable ``name`` of this component or of one of its connectors
        (``"frame_a.x"``), unless the model gave one with :func:`start`.
        Meant for ``before_flatten()``, ``on_flatten()`` or ``equations()``
        of elements that compute assembly guesses, such as branch choices
        from a parameter K."""
        ov = self._overrides.get(name)
        if isinstance(ov, start) and ov.value is not None or isinstance(ov, numbers.Real):
            return
        info = self._var_infos.get(name) or self._var_decls.get(name)
        if info is None:
            raise ModelDefinitionError("%s has no variable %r" % (self.describe(), name))
        info.start = value

    def equations(self):
        """Return this component's equations: CasADi expressions written as
        ``lhs == rhs`` (or residuals that must vanish), possibly nested in
        lists.  Components without own equations return an empty list."""
        return []

    def shapes(self):
        """How the component is drawn in the animation: a list of shape dicts
        (kinds in :mod:`acausal2d.tools.animation`) whose signal names are relative
        to the component, e.g. ``{"type": "joint", "x": "frame_a.x", "y":
        "frame_a.y"}``.  Default: nothing."""
        return []

    def topology(self):
        """Planar topology for the degree-of-freedom count (seed eq. 2.1):
        a list of ``("ground", [frames])``, ``("rigid", [frames])`` (frames
        of one link) and ``("joint", frame_a, frame_b, f)`` (a joint with f
        degrees of freedom).  Default: nothing."""
        return []

    @property
    def path(self):
        """Dotted instance name inside the model ('' for the model itself)."""
        if self._parent is None:
            return ""
        return _join(self._parent.path, self._name)

    def describe(self):
        """'ClassName 'path'' for messages."""
        return "%s '%s'" % (type(self).__name__, self.path or "<model>")

    def components(self):
        """This component and all sub-components, depth first."""
        yield self
        for child in self._children.values():
            yield from child.components()

    def world(self):
        """The nearest PlanarWorld among this component's ancestors' children,
        or None."""
        from acausal2d.library.planar import PlanarWorld
        node = self._parent
        while node is not None:
            for child in node._children.values():
                if isinstance(child, PlanarWorld):
                    return child
            node = node._parent
        return None

    # ----------------------------------------------------------- binding
    def _bind(self, params_out, vars_out):
        """Create the symbols of this component (full dotted names)."""
        path = self.path
        for name, decl in list(self._var_decls.items()):
            ov = self._overrides.get(name)
            if ov is not None:
                if isinstance(ov, start):
                    ov.apply(decl)
                elif isinstance(ov, numbers.Real):
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
        for name, value in self._param_values.items():
            decl = self._param_decl(name)
            sym = symbols.new_parameter(_join(path, name), decl.size)
            self._param_syms[name] = sym if decl.size > 1 else sym[0]
            vals = np.atleast_1d(np.asarray(value, dtype=float))
            for i in range(decl.size):
                pname = _join(path, name) + ("[%d]" % i if decl.size > 1 else "")
                params_out.append((pname, sym[i], float(vals[i]), decl))
        self._var_infos.clear()
        for name, decl in self._var_decls.items():
            sym = symbols.new_variable(_join(path, name))
            self._var_syms[name] = sym
            self._var_infos[name] = VarInfo(_join(path, name), sym, decl, self)
            vars_out.append(self._var_infos[name])
        for cname, conn in self._connectors.items():
            n0 = len(vars_out)
            conn._bind(vars_out)
            for info in vars_out[n0:]:
                self._var_infos[cname + "." + info.name.rsplit(".", 1)[1]] = info
