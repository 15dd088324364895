"""Symbols of one compilation: what each CasADi symbol stands for, and time
derivatives.

Every symbol the compiler creates for a model is registered in the
:class:`SymbolTable` of that compilation with its kind (variable, parameter,
discrete relation value, time).  Variables carry a chain of derivative
symbols ``x, der(x), der(der(x)), ...`` created on demand, so that ``der()``
in a model and the symbolic differentiation done by index reduction share
the same symbols.  A table lives as long as the compiled model that owns it;
nothing is registered process-wide except the one ``time`` symbol.

``der()`` and :func:`time_derivative` in component equations use the table
of the flattening in progress (:meth:`SymbolTable.active`).
"""
from contextlib import contextmanager
from typing import Any

import casadi as ca

from ..errors import ModelDefinitionError

VAR, PARAM, DISCRETE, TIME = "var", "param", "discrete", "time"

time = ca.SX.sym("time")
"""The simulation time symbol; use it in equations of time-dependent sources."""

_active: list = []  # stack of tables of flattenings in progress


def as_sx(expr):
    """``expr`` as a CasADi SX: itself if it is one already (``SX(sx)``
    costs ~60 us of SWIG overload resolution per call, which adds up to
    seconds in a large model), else converted (numbers, DM)."""
    return expr if isinstance(expr, ca.SX) else ca.SX(expr)


def key(s):
    """Hashable identity of a scalar CasADi symbol."""
    return s.element_hash()


class SymbolTable:
    """The symbols of one compilation (see module docstring)."""

    def __init__(self):
        self._kind = {}     # element hash -> kind
        self._sym = {}      # element hash -> SX (keeps it alive: hashes stay unique)
        self._base = {}     # element hash -> (base symbol, derivative level), variables
        self._der = {}      # element hash -> derivative symbol
        self.latches = {}   # element hash -> [symbol, g, g_start, text] of a latch
        self._register(time, TIME)

    def __len__(self):
        return len(self._sym)

    def _register(self, s, kind):
        h = key(s)
        self._kind[h] = kind
        self._sym[h] = s
        return s

    @contextmanager
    def active(self):
        """Make this the table ``der()`` uses while the block runs."""
        _active.append(self)
        try:
            yield self
        finally:
            _active.pop()

    def new_variable(self, name):
        """Create and register a scalar unknown named ``name``."""
        s = self._register(ca.SX.sym(name), VAR)
        self._base[key(s)] = (s, 0)
        return s

    def new_parameter(self, name, size=1):
        """Create and register a parameter symbol (a column of ``size``)."""
        s = ca.SX.sym(name, size)
        for i in range(size):
            self._register(s[i], PARAM)
        return s

    def new_discrete(self, name):
        """Create and register the value (0 or 1) of a relation between events."""
        return self._register(ca.SX.sym(name), DISCRETE)

    def new_latch(self, name):
        """Create and register a latch: a discrete value (0 or 1) whose
        crossing function :meth:`define_latch` gives (see :func:`latch`)."""
        s = self.new_discrete(name)
        self.latches[key(s)] = [s, None, None, name]
        return s

    def define_latch(self, sym, g, g_start, text):
        """Give the latch ``sym`` its crossing function ``g`` (which may use
        the latch values, its own among them), the crossing function
        ``g_start`` that decides its value at the start, and its text."""
        entry = self.latches.get(key(sym))
        if entry is None:
            raise ModelDefinitionError("define_latch: %r is no latch of this model" % sym)
        entry[1:] = [as_sx(g), as_sx(g if g_start is None else g_start), text]

    def latch_list(self):
        """(symbol, g, g_start, text) of every latch, in creation order;
        a latch without crossing function is an error."""
        out = []
        for sym, g, g_start, text in self.latches.values():
            if g is None:
                raise ModelDefinitionError("the latch %s has no crossing function: give it one "
                                           "with define_latch" % text)
            out.append((sym, g, g_start, text))
        return out

    def kind(self, s):
        """Kind of a registered scalar symbol, or None."""
        return self._kind.get(key(s))

    def base_and_level(self, s):
        """(base variable, derivative order) of a variable symbol."""
        return self._base[key(s)]

    def has_derivative(self, s):
        """True if the derivative symbol of ``s`` has been created."""
        return key(s) in self._der

    def derivative_symbol(self, s):
        """The symbol of der(s) for a variable symbol ``s``, created on first use."""
        h = key(s)
        d = self._der.get(h)
        if d is None:
            base, level = self._base[h]
            name = base.name()
            for _ in range(level + 1):
                name = "der(%s)" % name
            d = self._register(ca.SX.sym(name), VAR)
            self._base[key(d)] = (base, level + 1)
            self._der[h] = d
        return d

    def time_derivative(self, expr):
        """Total time derivative of a CasADi expression: variables map to
        their derivative symbols, parameters and discrete relation values
        are constant, ``time`` has derivative one."""
        expr = as_sx(expr)
        src, dst = [], []
        for s in ca.symvar(expr):
            k = self._kind.get(key(s))
            if k == VAR:
                src.append(s)
                dst.append(self.derivative_symbol(s))
            elif k == TIME:
                src.append(s)
                dst.append(ca.SX(1))
            elif k is None:
                raise ModelDefinitionError(
                    "der() of an expression with the symbol %r, which is no variable, "
                    "parameter or time of this model" % s.name())
        if not src:
            return ca.SX.zeros(expr.shape)
        return ca.jtimes(expr, ca.vertcat(*src), ca.vertcat(*dst))

    def der(self, expr):
        """``der(x)``: the derivative symbol of a variable, or the chain rule
        applied to an expression."""
        expr = as_sx(expr)
        if expr.is_scalar() and expr.is_symbolic() and self.kind(expr) == VAR:
            return self.derivative_symbol(expr)
        return self.time_derivative(expr)


def active_table():
    """The table of the flattening in progress."""
    if not _active:
        raise ModelDefinitionError(
            "der() and time_derivative() can only be used inside a component's equations()")
    return _active[-1]


def latch(name: str) -> Any:
    """A latch of the flattening in progress: a discrete value (0 or 1)
    that holds between events, like a relation, but whose crossing function
    (:func:`define_latch`) may depend on the latch values themselves - its
    own among them.  Its value is 1 where its crossing function is > 0;
    since that function can change with the value, a latch keeps its value
    until the function *for that value* crosses zero: hysteresis, the
    memory of a Modelica ``pre()`` state machine (PartialFriction's modes
    Forward/Stuck/Backward).  The event iteration settles all latches and
    relations together (:mod:`acausal2d.runtime.events`)."""
    return active_table().new_latch(name)


def define_latch(sym: Any, g: Any, text: str, g_start: Any = None) -> None:
    """Give the latch ``sym`` (from :func:`latch`) the crossing function
    ``g`` (an expression of unknowns, parameters, time, relations and
    latches), the text that names it in messages, and ``g_start``: the
    crossing function that decides its value at the start (default ``g``
    with every latch and relation 0)."""
    active_table().define_latch(sym, g, g_start, text)


def der(expr: Any) -> Any:
    """Time derivative ``der(x)`` for use in component equations: ``der`` of a
    variable gives its derivative symbol; ``der`` of an expression applies
    the chain rule."""
    return active_table().der(expr)


def time_derivative(expr: Any) -> Any:
    """Total time derivative of an expression in component equations (the
    chain rule over all variables and ``time``)."""
    return active_table().time_derivative(expr)
