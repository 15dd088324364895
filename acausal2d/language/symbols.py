"""Symbol registry: what each CasADi symbol stands for, and time derivatives.

Every symbol acausal2d creates is registered here with its kind (variable,
parameter, discrete relation value, time).  Variables carry a chain of
derivative symbols ``x, der(x), der(der(x)), ...`` created on demand, so that
``der()`` in a model and the symbolic differentiation done by index reduction
share the same symbols.
"""
import casadi as ca

VAR, PARAM, DISCRETE, TIME = "var", "param", "discrete", "time"

_kind = {}      # element hash -> kind
_sym = {}       # element hash -> SX symbol (keeps it alive, so hashes stay unique)
_base = {}      # element hash -> (base symbol, derivative level) for variables
_der = {}       # element hash -> derivative symbol


def key(s):
    """Hashable identity of a scalar CasADi symbol."""
    return s.element_hash()


def _register(s, kind):
    h = key(s)
    _kind[h] = kind
    _sym[h] = s
    return s


time = _register(ca.SX.sym("time"), TIME)
"""The simulation time symbol; use it in equations of time-dependent sources."""


def new_variable(name):
    """Create and register a scalar unknown named ``name``."""
    s = _register(ca.SX.sym(name), VAR)
    _base[key(s)] = (s, 0)
    return s


def new_parameter(name, size=1):
    """Create and register a parameter symbol (a column of ``size`` scalars)."""
    s = ca.SX.sym(name, size)
    for i in range(size):
        _register(s[i], PARAM)
    return s


def new_discrete(name):
    """Create and register the value (0 or 1) of a relation between events."""
    return _register(ca.SX.sym(name), DISCRETE)


def kind(s):
    """Kind of a registered scalar symbol, or None."""
    return _kind.get(key(s))


def base_and_level(s):
    """(base variable, derivative order) of a variable symbol."""
    return _base[key(s)]


def has_derivative(s):
    """True if the derivative symbol of ``s`` has been created."""
    return key(s) in _der


def derivative_symbol(s):
    """The symbol of der(s) for a variable symbol ``s``, created on first use."""
    h = key(s)
    d = _der.get(h)
    if d is None:
        base, level = _base[h]
        name = base.name()
        for _ in range(level + 1):
            name = "der(%s)" % name
        d = _register(ca.SX.sym(name), VAR)
        _base[key(d)] = (base, level + 1)
        _der[h] = d
    return d


def time_derivative(expr):
    """Total time derivative of a CasADi expression.

    Variables map to their derivative symbols, parameters and discrete
    relation values are constant, and ``time`` has derivative one.
    """
    expr = ca.SX(expr)
    syms = ca.symvar(expr)
    if not syms:
        return ca.SX.zeros(expr.shape)
    src, dst = [], []
    for s in syms:
        k = _kind.get(key(s))
        if k == VAR:
            src.append(s)
            dst.append(derivative_symbol(s))
        elif k == TIME:
            src.append(s)
            dst.append(ca.SX(1))
        elif k is None:
            raise ValueError("der() of an expression with the unregistered symbol %r" % s.name())
    if not src:
        return ca.SX.zeros(expr.shape)
    return ca.jtimes(expr, ca.vertcat(*src), ca.vertcat(*dst))


def der(expr):
    """Time derivative ``der(x)`` for use in component equations.

    ``der`` of a variable gives its derivative symbol; ``der`` of an
    expression applies the chain rule.
    """
    expr = ca.SX(expr)
    if expr.is_scalar() and expr.is_symbolic() and _kind.get(key(expr)) == VAR:
        return derivative_symbol(expr)
    return time_derivative(expr)
