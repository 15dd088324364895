"""Flattening: from a component tree to one list of scalar equations.

Creates the symbols of every component, collects their equations, builds
the connection sets (potentials equal, flows sum to zero, Ebert (2015), eq. 4.1) and
closes unconnected connectors (flows zero, or fixed to ground for connectors
declared with ``ground=``).
"""
import casadi as ca
import numpy as np

from ..errors import Acausal2dError, ModelDefinitionError
from ..language.context import ModelContext
from ..language.symbols import as_sx
from ..language.unionfind import UnionFind


class Equation:
    """One scalar residual equation ``expr == 0`` and where it comes from.
    ``text`` shows it as written (formatted on first use)."""

    __slots__ = ("expr", "origin", "_text", "_sides", "owner")

    def __init__(self, expr, origin, text=None, sides=None, owner=None):
        self.expr = expr
        self.origin = origin
        self.owner = owner          # the Component that wrote it (None: connections)
        self._text = text
        self._sides = sides

    @property
    def text(self):
        if self._text is None:
            if self._sides is not None:
                self._text = "%s == %s" % (_fmt(self._sides[0]), _fmt(self._sides[1]))
            else:
                self._text = "%s == 0" % _fmt(self.expr)
        return self._text

    def with_expr(self, expr):
        """A copy of the equation with residual ``expr`` (same origin)."""
        eq = Equation(expr, self.origin, self._text, self._sides, self.owner)
        if eq._text is None and self._sides is None:
            eq._text = self.text
        return eq

    def describe(self):
        """'origin: text' for messages."""
        return "%s: %s" % (self.origin, self.text)

    def __repr__(self):
        return "Equation(%s)" % self.describe()


class FlatModel:
    """Result of flattening: variables, parameters and equations."""

    def __init__(self, model, variables, parameters, equations):
        self.model = model
        self.variables = variables        # list of VarInfo
        self.parameters = parameters      # list of (name, symbol, value, decl)
        self.equations = equations        # list of Equation


def _residuals(item, origin, out, counter, owner=None):
    if isinstance(item, (list, tuple)):
        for sub in item:
            _residuals(sub, origin, out, counter, owner)
        return
    if isinstance(item, (bool, np.bool_)):
        raise ModelDefinitionError(
            "%s equation %d is the Python value %r; write equations between symbolic "
            "expressions (a == b)" % (origin, counter[0] + 1, item))
    if isinstance(item, ca.SX):
        e = item
    else:
        try:
            e = ca.SX(item)
        except Exception:
            raise ModelDefinitionError("%s equation %d is not an expression: %r"
                                       % (origin, counter[0] + 1, item)) from None
    for el in ([e] if e.is_scalar() else [e[k] for k in range(e.numel())]):
        counter[0] += 1
        if el.n_dep() == 2 and el.op() == ca.OP_EQ:
            lhs, rhs = el.dep(0), el.dep(1)
            res, sides = lhs - rhs, (lhs, rhs)
        else:
            res, sides = el, None
        eq = Equation(res, "%s equation %d" % (origin, counter[0]), sides=sides, owner=owner)
        if res.is_constant():
            raise ModelDefinitionError(
                "%s equation %d (%s) contains no unknowns" % (origin, counter[0], eq.text))
        out.append(eq)


def _fmt(e):
    s = str(e)
    return s if len(s) < 160 else s[:157] + "..."


def resolve_outers(model):
    """Give every :class:`~acausal2d.language.dsl.Outer` declaration of the
    model's components an instance: where the model holds none, one with
    default parameters is added to ``model`` (named like the declaration,
    e.g. ``world``)."""
    for comp in list(model.components()):
        for outer in comp.outers():
            if outer.find(comp) is not None:
                continue
            if comp is model and not model._children:
                continue
            name = outer.name
            while name in model._children or name in model.__dict__:
                name += "_"
            setattr(model, name, outer.cls())


def flatten(model, table):
    """Flatten ``model`` (a Component instance) into a :class:`FlatModel`
    whose symbols are created in ``table`` (a
    :class:`~acausal2d.language.symbols.SymbolTable`)."""
    resolve_outers(model)
    comps = list(model.components())
    context = ModelContext(model)
    for comp in comps:
        comp._set_derived(_hook(comp, "derived_parameters", context))
    params, variables = [], []
    with table.active():
        for comp in comps:
            comp._bind(table, params, variables)
        context.parameters = params
        for comp in comps:
            comp._apply_guesses(_hook(comp, "guesses", context))
        equations = []
        for comp in comps:
            items = _hook(comp, "equations")
            _residuals(items if items is not None else [], comp.describe(), equations, [0],
                       comp)
    equations.extend(_connection_equations(model, comps))
    return FlatModel(model, variables, params, equations)


def _hook(comp, name, *args):
    """Call a component hook; errors other than the project's name it."""
    try:
        return getattr(comp, name)(*args)
    except Acausal2dError:
        raise
    except Exception as exc:
        raise ModelDefinitionError("%s: %s() failed: %s: %s"
                                   % (comp.describe(), name, type(exc).__name__, exc)) from None


def _is_descendant(comp, ancestor):
    node = comp
    while node is not None:
        if node is ancestor:
            return True
        node = node._parent
    return False


def _connection_sets(comps):
    """The connection sets: lists of (connector, side) where side is
    'inside' (a sub-component's connector) or 'outside' (the connecting
    component's own connector)."""
    sets, members = UnionFind(), {}
    for scope in comps:
        for a, b in scope._connections:
            keys = []
            for c in (a, b):
                if c.owner is None:
                    raise ModelDefinitionError("connect(): connector %s is not attached to a "
                                               "component" % c.describe())
                if not _is_descendant(c.owner, scope):
                    raise ModelDefinitionError(
                        "%s connects %s, which is not part of it" % (scope.describe(), c.path))
                side = "outside" if c.owner is scope else "inside"
                members[(id(c), side)] = (c, side)
                keys.append((id(c), side))
            sets.union(keys[0], keys[1])
    groups = {}
    for k in members:
        groups.setdefault(sets.find(k), []).append(members[k])
    return [sorted(g, key=lambda e: e[0].path) for g in groups.values()]


def _check_set(elems, names):
    """Band ports one-to-one; signal sets with exactly one source."""
    kind = type(elems[0][0])
    if kind.one_to_one and len(elems) > 2:
        raise ModelDefinitionError(
            "band connectors may be connected one-to-one only, but %s are joined: "
            "use a separate band element between them" % names)
    if kind.signal is not None:
        sources = [c for c, side in elems if (c.signal == "output") == (side == "inside")]
        if len(sources) != 1:
            raise ModelDefinitionError(
                "signal connection {%s} must have exactly one source (an output), has %d"
                % (names, len(sources)))


def _set_equations(elems):
    """Potentials equal, flows summing to zero (Ebert 2015, eq. 4.1) for one set."""
    conns = [c for c, _ in elems]
    names = ", ".join(c.path for c in conns)
    _check_set(elems, names)
    origin = "connect(%s)" % names
    first, eqs = conns[0], []
    for c in conns[1:]:
        for pot in type(first).potentials:
            eqs.append(_conn_eq(getattr(c, pot) - getattr(first, pot), origin,
                                "%s.%s == %s.%s" % (c.path, pot, first.path, pot)))
    for flow in type(first).flows:
        total, terms = 0, []
        for c, side in elems:
            f = getattr(c, flow)
            total = total + (f if side == "inside" else -f)
            terms.append(("" if side == "inside" else "-") + "%s.%s" % (c.path, flow))
        eqs.append(_conn_eq(total, origin, " + ".join(terms) + " == 0"))
    return eqs


GROUNDED = " (unconnected, fixed to ground)"
"""Origin suffix of the equations that fix an unconnected ``ground=``
connector (Ebert 2015, Tabelle 4.1: a triangle port left open is fixed to ground)."""


def grounded_ports(equations):
    """The connectors fixed to ground because nothing is connected to them,
    from the flattened ``equations``: ``{path: [potentials fixed]}`` in
    model order, e.g. ``{"dyad.ctr2D1": ["x", "y", "phi"]}``."""
    ports = {}
    for eq in equations:
        if eq.origin.endswith(GROUNDED):
            path = eq.origin[:-len(GROUNDED)]
            ports.setdefault(path, []).append(eq.text.split(" == ")[0][len(path) + 1:])
    return ports


def _unconnected_equations(comp, conn):
    """An unconnected connector: fixed to ground (``ground=``), an error
    (``required=True``), or zero flows."""
    if conn.ground is not None:
        ground = conn.ground(comp) if callable(conn.ground) else conn.ground
        return [_conn_eq(getattr(conn, pot) - value, conn.path + GROUNDED,
                         "%s.%s == %s" % (conn.path, pot, value)) for pot, value in ground.items()]
    if conn.required:
        raise ModelDefinitionError("connector %s must be connected (it is required by %s)"
                                   % (conn.path, comp.describe()))
    return [_conn_eq(getattr(conn, flow), "%s (unconnected)" % conn.path,
                     "%s.%s == 0" % (conn.path, flow)) for flow in type(conn).flows]


def _connection_equations(model, comps):
    """Equations of all connection sets and of the unconnected connectors."""
    eqs, connected_inside = [], set()
    for elems in _connection_sets(comps):
        connected_inside.update(id(c) for c, side in elems if side == "inside")
        eqs.extend(_set_equations(elems))
    for comp in comps:
        for conn in comp._connectors.values():
            if id(conn) not in connected_inside and comp is not model:
                eqs.extend(_unconnected_equations(comp, conn))
    return eqs


def _conn_eq(expr, origin, text):
    return Equation(as_sx(expr), origin, text)
