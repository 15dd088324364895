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
import contextlib
import difflib
import numbers
from collections.abc import Callable, Iterator

import numpy as np

from ..errors import ModelDefinitionError
from .declarations import (STATE_SELECT, Parameter, Variable, VarInfo, start,  # noqa: F401
                           _check_nominal, _check_state_select, _creation_site,
                           _declarations, _join, add_declarations, declaration_doc)
from .connectors import Connector
from .connector_doc import LazyDoc, connector_rows


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


def _deprecated(conn):
    """Whether a connector is kept only for old models (its ``doc`` starts
    with "deprecated"): never suggested for a misspelt name."""
    return conn is not None and str(getattr(conn, "doc", "")).lower().startswith("deprecated")


def _unknown_attribute(comp, name):
    """The message of an unknown attribute: the names the component has,
    by kind, and the closest one."""
    d = comp.__dict__
    groups = [("connectors", list(d["_connectors"])), ("sub-components", list(d["_children"])),
              ("parameters", list(d["_param_values"])), ("variables", list(d["_var_decls"]))]
    names = [n for _, group in groups for n in group]
    optional = {n: cond for n, _, _, cond in connector_rows(type(comp))
                if cond and n not in d["_connectors"]}
    current = [n for n in names if not _deprecated(d["_connectors"].get(n))]
    close = difflib.get_close_matches(name, current, n=1)
    text = "%s has no attribute %r" % (comp.describe(), name)
    if name in optional:
        text += " (the connector exists with %s)" % optional[name]
    elif close:
        text += "; did you mean %r?" % close[0]
    return text + ". It has " + "; ".join("%s %s" % (kind, ", ".join(group))
                                          for kind, group in groups if group) + "."


_reads: list = []       # the open compile_reads() lists (innermost last)

_DISPLAY: dict = {}
"""{format: draw(component) -> text}: how a notebook displays a component
(:func:`register_display`)."""


def register_display(fmt: str, draw) -> None:
    """Let a notebook display a component as ``fmt`` (``"svg"``) with
    ``draw(component)``.  The package root registers the diagram, so that
    the language imports nothing of the layers above it
    (tests/test_layering.py)."""
    _DISPLAY[fmt] = draw


@contextlib.contextmanager
def compile_reads():
    """Collect the (component, parameter name) pairs whose numeric value is
    read (:meth:`Component.parameter_value`) inside the block: the
    compiler's reads, after which a changed value would change nothing
    (a pulley's ``m`` decides whether it has mass)."""
    found: list = []
    _reads.append(found)
    try:
        yield found
    finally:
        _reads.remove(found)


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
        cls._written_doc = vars(cls).get("__doc__")
        cls.__doc__ = LazyDoc(declaration_doc)

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
        (:meth:`derived_parameters`), else the declared default.  A value
        read while a model is compiled (:func:`compile_reads`) makes the
        parameter structural: the compiled model depends on it beyond its
        symbol."""
        if _reads:
            _reads[-1].append((self, name))
        return self._value(name)

    def _value(self, name):
        """:meth:`parameter_value` not counted as a compiler's read (the
        value the parameter's symbol starts with)."""
        if name in self._given:
            return self._param_values[name]
        if name in self._derived:
            return self._derived[name]
        if name not in self._param_values:
            self.parameter_declaration(name)        # raises with the list
        return self._param_values[name]

    def check_parameters(self, value: Callable[[str], float | tuple[float, ...]]) -> None:
        """Rules between parameters of this component (``uMax >= uMin``),
        checked on the values ``value(name)`` gives: by the constructor on
        its own values and again on the final values of a run whatever way
        they came (``--set``, ``params=``, a sweep, a fit, the live page).
        Raises :class:`ModelDefinitionError` naming the component and the
        parameters; the base class has none."""

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
        raise AttributeError(_unknown_attribute(self, name))

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
        (kinds in :mod:`acausal2d.visual.animation`) whose signal names are
        relative to the component, e.g. ``{"type": "joint", "x": "frame_a.x",
        "y": "frame_a.y"}``.  Default: nothing."""
        return []

    def assertions(self):
        """Hook: conditions that end the run with an error, as a list of
        ``(name, message)``: ``name`` is a 0/1 variable of this component
        set by a relation in its equations (e.g. ``lifted == if_else(Fn <
        0, 1, 0)``); when it is 1 at the start or after an event, the run
        stops with a :class:`~acausal2d.errors.SimulationError` giving the
        time, this component and ``message`` (what to change).  Default:
        none."""
        return []

    def reinits(self):
        """Hook: Modelica's ``when c then reinit(x, value); end when``, as a
        list of ``(condition, variable, value)``: ``condition`` names a 0/1
        variable of this component set by a relation or latch in its
        equations; at an event where it becomes 1 (it was 0 just before),
        the state ``variable`` of this component is set to ``value`` (a
        number, or the name of a variable of this component, taken at the
        event) and the other unknowns are re-solved.  ``variable`` must be
        a state (declare it ``state_select="always"``).  Default: none."""
        return []

    def start_checks(self, context):
        """Hook: checks of the consistent initial state, made once at t0
        after initialization (by ``simulate``, ``check``, linearization and
        FMU export), as a list of functions ``check(value)``: ``value(comp,
        name)`` is the value of variable ``name`` (relative to ``comp``, e.g.
        ``"ctrK1.x"``) of component ``comp`` at t0, and ``check`` returns
        None or the text of the error (what is wrong and what to change),
        which stops the run with an
        :class:`~acausal2d.errors.InitializationError` naming this
        component.  ``context`` is the
        :class:`~acausal2d.language.context.ModelContext` (partners of a
        port).  Unlike :meth:`assertions` it adds no relation to the model.
        Default: none."""
        return []

    def sliding_mode_advice(self):
        """Hook: what to change when a relation in this component's
        equations has no consistent value at an event (a sliding mode) or
        chatters.  The runtime's error names the relation, this component
        and the time and ends with this text; ``None`` (the default) gives
        the general advice (model sticking in the element, as
        ``rotational.Clutch`` does, or smooth the relation), which an
        element that models sticking itself should replace."""
        return None

    def describe_mode(self, value):
        """Hook: the element's operating mode in words ("stuck", "sliding
        forward", "free") at a point of the run; ``value(name)`` is the value
        of its variable or parameter ``name`` (relative to the element, e.g.
        ``"w_rel"``, ``"w_s"``).  An event that switches relations of its
        equations reads ``Clutch 'clutch': sliding forward -> stuck at t =
        0.7 s`` (:mod:`acausal2d.runtime.event_words`, which reads the mode
        just before and after the event).  Default: None, the event names
        the condition that switched."""
        return None

    power_sides: tuple = ()
    """Connector names (tuples, one per side) between which the element
    passes power: a gear's ``(("flange_a",), ("flange_b",))``, a joint
    with a drive flange ``(("frame_a", "frame_b"), ("flange_a",))``, a
    sensor's ``(("flange",), ("w",))``.  With one side connected and
    another left unconnected (free, not grounded) the element passes
    nothing, which :func:`acausal2d.check` reports as a likely mistake.
    Names of connectors the instance does not have are skipped, and a side
    of signal outputs only is never loose.  Default: none."""

    held_connectors: tuple = ()
    """Names of connectors the element's own equations hold in place while
    nothing is connected to them (a joint's drive ``support``, fixed at 0
    inside the joint): the connector report lists them as held, not free.
    Default: none."""

    def topology(self):
        """Planar topology for the degree-of-freedom count (Ebert 2015, eq. 2.1):
        a list of ``("ground", [frames])``, ``("rigid", [frames])`` (frames
        of one link), ``("joint", frame_a, frame_b, f)`` (a joint with f
        degrees of freedom), ``("band", link, frame, band_port)`` (a band
        span's end: a band joint with the f its wheel declares by
        ``("contact", band_port, f)`` -- 1 rolling, 2 sliding -- or a pin
        with f = 1 where no wheel is connected), ``("coupling", k)`` (k
        constraints coupling band joints wrapped on one contour, Bild 2.1 b),
        ``("identical", k)`` (identical freedoms f_id) and ``("passive",
        k)`` (passive constraints s).  Default: nothing."""
        return []

    def _repr_svg_(self):
        """The component's diagram as a notebook shows it (drawn by
        :mod:`acausal2d.visual.diagram`, which the package root registers
        with :func:`register_display`); None (the notebook's text display)
        where none is registered."""
        draw = _DISPLAY.get("svg")
        return draw(self) if draw is not None else None

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

    def describe(self) -> str:
        """'ClassName 'path'' for messages."""
        return "%s '%s'" % (type(self).__name__, self.path or "<model>")

    def components(self) -> "Iterator[Component]":
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
            vals = np.atleast_1d(np.asarray(self._value(name), dtype=float))
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


def modelica_aliases():
    """The Modelica array-name aliases the component classes defined so far
    declare (class attribute ``modelica_names``, e.g. the planar Body's
    ``r[1]`` -> ``x``): {Modelica name: [our names]}.  ``compare`` matches
    reference columns such as ``body.r[1]`` by it; a library's aliases count
    once the library is imported (``acausal2d.compare`` and the command
    line import the planar library)."""
    table, todo, seen = {}, list(Component.__subclasses__()), set()
    while todo:
        cls = todo.pop(0)
        if cls in seen:
            continue
        seen.add(cls)
        todo.extend(cls.__subclasses__())
        for key, ours in (vars(cls).get("modelica_names") or {}).items():
            if ours not in table.setdefault(key, []):
                table[key].append(ours)
    return table
