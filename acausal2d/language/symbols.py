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


def der(expr: Any) -> Any:
    """Time derivative ``der(x)`` for use in component equations: ``der`` of a
    variable gives its derivative symbol; ``der`` of an expression applies
    the chain rule."""
    return active_table().der(expr)


def time_derivative(expr: Any) -> Any:
    """Total time derivative of an expression in component equations (the
    chain rule over all variables and ``time``)."""
    return active_table().time_derivative(expr)
