"""The product of compilation: a frozen index-reduced system.

:class:`System` holds the structural state after index reduction, the
alias-free equations (for messages), the relations, the aliases and the
generated CasADi functions the runtime evaluates: all equations of every
derivative order as functions of all variable nodes E(t, z, p, d) with their
sparse Jacobian (consistent initialization, state selection), the start
values, the crossing functions and, per dummy selection, the semi-explicit
index-1 formulation (cached: a new parameter value or a second run never
generates code again).  Parameters stay symbolic inputs of every function.
"""
from __future__ import annotations

from typing import Any

import casadi as ca
import numpy as np
from numpy.typing import NDArray

from ..errors import InitializationError, ModelDefinitionError

from ..language.dsl import STATE_SELECT
from ..language.symbols import as_sx, time
from .aliases import Alias, substitution
from .relations import exact_crossings
from .gc_pause import cyclic_gc_paused
from .index1 import Formulation
from .structure import Structure, column
from ..language.context import ModelContext
from ..language.dsl import Component
from ..language.declarations import Parameter, VarInfo

ParameterEntry = tuple[str, Any, float, Parameter]
"""(dotted name, CasADi symbol, value, declaration) of a scalar parameter."""


def _param_function(exprs, p, name):
    """Numeric evaluator of a list of numbers / parameter expressions."""
    e = ca.vertcat(*[ca.SX(x) for x in exprs]) if exprs else ca.SX(0, 1)
    return ca.Function(name, [p], [e])


class System:
    """A compiled model (see module docstring).

    Attributes used by the runtime and the tools: ``structure``,
    ``equations`` (alias-free), ``relations``, ``aliases``, ``parameters``
    (name, symbol, value, declaration), ``node_names``, ``node_info``
    (VarInfo of each node's variable), ``priority``, ``nominal``,
    ``residual_fn``/``jacobian_fn`` (E and dE/dz), ``crossing_fn``,
    ``start_fn``."""

    structure: Structure
    parameters: tuple[ParameterEntry, ...]
    param_index: dict[str, int]
    outputs: list[str]
    node_names: tuple[str, ...]
    node_info: tuple[VarInfo, ...]
    level0: NDArray[np.int_]
    aliases: tuple[Alias, ...]
    alias_names: tuple[str, ...]
    alias_der_names: tuple[str, ...]
    model_name: str
    """The model class's name (set by :class:`~acausal2d.compiled.CompiledModel`)."""

    def __init__(self, model, flat, equations, variables, aliases, relations, structure):
        self.model = model
        self.structure = s = structure
        self.table = s.table
        self.all_variables = tuple(flat.variables)
        self.n_flat_equations = len(flat.equations)
        self.equations = tuple(equations)
        self.flat_equations = tuple(flat.equations)
        self.variables = tuple(variables)
        self.aliases = tuple(aliases)
        self.parameters = tuple(flat.parameters)
        self.param_index = {name: k for k, (name, *_) in enumerate(self.parameters)}
        self.p = ca.vertcat(*[sym for _, sym, _, _ in self.parameters]) \
            if self.parameters else ca.SX(0, 1)
        self.relations = tuple(exact_crossings(self._crossings_in_nodes(relations),
                                               [eq.expr for eq in self.equations], self.table))
        self.d = ca.vertcat(*[r.sym for r in self.relations]) if self.relations else ca.SX(0, 1)
        self._nodes(variables)
        self._functions()
        self._alias_maps()
        self.outputs = declared_outputs(model)
        self.assertions = self._assertions(model)
        self.start_checks = self._start_checks(model)
        self.reinits = self._reinits(model)
        self._formulations = {}

    # ------------------------------------------------------------ setup
    def _crossings_in_nodes(self, relations):
        """Relations whose crossing functions use the remaining unknowns."""
        if not relations or not self.aliases:
            return relations
        src, dst = substitution(self.aliases, self.table)
        n = len(relations)
        gs = ca.substitute([r.g for r in relations] + [r.start_g for r in relations], src,
                           [as_sx(x) for x in dst])
        return [r.with_g(g, g0) for r, g, g0 in zip(relations, gs[:n], gs[n:])]

    def _nodes(self, variables):
        s = self.structure
        info = {v.sym.element_hash(): v for v in variables}
        self.node_info = tuple(info[s.var_sym[s.var_base[j]].element_hash()]
                               for j in range(s.n_var))
        self.node_names = tuple(sym.name() for sym in s.var_sym)
        self.priority = self._priorities()
        self.priority_names = tuple(v.state_select for v in self.node_info)
        self.nominal = np.array([float(v.nominal) for v in self.node_info])
        self.level0 = np.array([j for j in range(s.n_var) if s.var_level[j] == 0], dtype=int)
        self.fixed_nodes = tuple(int(j) for j in self.level0 if self.node_info[j].fixed)
        self.has_start = tuple(s.var_level[j] == 0 and not _is_zero(self.node_info[j].start)
                               for j in range(s.n_var))

    def _priorities(self):
        """State priority of each node: its variable's ``state_select``; the
        derivatives of a derivative that a state variable stands for (``w``
        in ``w == der(phi)``) one class lower, so that der(w) rather than
        der(der(phi)) stays a state derivative."""
        s = self.structure
        prio = [STATE_SELECT.index(v.state_select) for v in self.node_info]
        prefer = STATE_SELECT.index("prefer")
        for w, v in s.velocity_of:
            j = s.var_to_diff[v]
            while j >= 0:
                prio[j] = min(prio[j], prefer, prio[w] - 1)
                j = s.var_to_diff[j]
        return tuple(prio)

    def _functions(self):
        s = self.structure
        z = column(s.var_sym)
        E = column(s.eq_expr)
        args = [time, z, self.p, self.d]
        self.residual_fn = ca.Function("E", args, [E])
        self._dEdz = J = ca.jacobian(E, z)
        self.jacobian_fn = ca.Function("dEdz", args, [J])
        rows, cols = J.sparsity().get_triplet()
        self.jacobian_pattern = (np.array(rows, dtype=int), np.array(cols, dtype=int))
        self.start_fn = _param_function([self.node_info[j].start for j in self.level0], self.p,
                                        "start")
        self.crossings = ca.vertcat(*[r.g for r in self.relations]) if self.relations else None
        self.crossing_fn = ca.Function("g", args, [self.crossings]) \
            if self.crossings is not None else None
        self.start_crossing_fn = self.crossing_fn
        if any(r.g_start is not None for r in self.relations):
            self.start_crossing_fn = ca.Function(
                "g_start", args, [ca.vertcat(*[r.start_g for r in self.relations])])
        self.relation_needs_rates = self._relations_on_highest(z)
        self._split_relations()

    def _relations_on_highest(self, z):
        """For each relation: does its crossing function depend on a node
        without a derivative node (whose rate takes a linear solve)?"""
        if self.crossings is None:
            return np.zeros(0, dtype=bool)
        rows, cols = ca.jacobian_sparsity(self.crossings, z).get_triplet()
        A = self.structure.var_to_diff
        out = np.zeros(len(self.relations), dtype=bool)
        for r, c in zip(rows, cols):
            if A[c] < 0:
                out[r] = True
        return out

    def _split_relations(self):
        """Relations of time alone whose crossing function is affine in time
        are time events, scheduled exactly (``time_event_fn(t, p)`` gives
        their g and dg/dt); the others are state events located by IDA."""
        timed = []
        for k, r in enumerate(self.relations):
            if r.time_only and not ca.depends_on(r.g, self.d):
                rate = ca.jacobian(r.g, time)
                if not ca.depends_on(rate, time):
                    timed.append((k, r.g, rate))
        self.time_relations = tuple(k for k, *_ in timed)
        self.state_relations = tuple(k for k in range(len(self.relations))
                                     if k not in set(self.time_relations))
        self.state_crossings = ca.vertcat(*[self.relations[k].g for k in self.state_relations]) \
            if self.state_relations else None
        self.time_event_fn = ca.Function(
            "time_events", [time, self.p], [ca.vertcat(*[g for _, g, _ in timed]),
                                            ca.vertcat(*[r for *_, r in timed])]) \
            if timed else None

    def _alias_maps(self):
        """Eliminated variables as sign * node + offset(p), and their derivatives."""
        A = self.structure.var_to_diff
        index = self.structure.var_index
        self.alias_names = tuple(a.var.name for a in self.aliases)
        self.alias_node = np.array([-1 if a.rep is None else index[a.rep.sym.element_hash()]
                                    for a in self.aliases], dtype=int)
        self.alias_sign = np.array([float(a.sign) for a in self.aliases])
        self.alias_offset_fn = _param_function([a.offset for a in self.aliases], self.p,
                                               "alias_offsets")
        names, nodes, signs = [], [], []
        for a, j, sign in zip(self.aliases, self.alias_node, self.alias_sign):
            name = a.var.name
            while j >= 0 and A[j] >= 0:
                j = A[j]
                name = "der(%s)" % name
                names.append(name)
                nodes.append(j)
                signs.append(sign)
        self.alias_der_names = tuple(names)
        self.alias_der_node = np.array(nodes, dtype=int)
        self.alias_der_sign = np.array(signs)
        self._fixed_aliases()

    def _fixed_aliases(self):
        """Eliminated variables with a fixed start whose value the equations
        set: by parameters alone, or through a representative that is fixed
        too; (fixed value, value by the equations) as a function of p."""
        fixed = [a for a in self.aliases if a.var.fixed and (a.rep is None or a.rep.fixed)]
        self.fixed_alias_names = tuple(a.var.name for a in fixed)
        self.fixed_alias_fn = _param_function(
            [e for a in fixed for e in (a.var.start, a.offset if a.rep is None
                                        else a.sign * a.rep.start + a.offset)],
            self.p, "fixed_aliases")

    def _assertions(self, model):
        """(component, variable name, message) of the components'
        ``assertions()`` (see :meth:`~acausal2d.language.dsl.Component.assertions`)."""
        out = []
        for comp in model.components():
            for name, message in comp.assertions():
                full = "%s.%s" % (comp.path, name) if comp.path else name
                if full not in self.node_names and full not in self.alias_names:
                    raise ModelDefinitionError("%s: assertions() names '%s', which is not a "
                                               "variable of it" % (comp.describe(), name))
                out.append((comp, full, message))
        return tuple(out)

    def _reinits(self, model):
        """(component, condition, variable, value) of the components'
        ``reinits()`` (see :meth:`~acausal2d.language.dsl.Component.reinits`),
        with the names made full; ``value`` a number or a full name."""
        out = []
        for comp in model.components():
            if type(comp).reinits is Component.reinits:
                continue
            full = (lambda n: "%s.%s" % (comp.path, n) if comp.path else n)  # noqa: E731
            for cond, var, value in comp.reinits():
                names = [cond, var] + ([value] if isinstance(value, str) else [])
                for name in names:
                    if full(name) not in self.node_names and full(name) not in self.alias_names:
                        raise ModelDefinitionError("%s: reinits() names '%s', which is not a "
                                                   "variable of it" % (comp.describe(), name))
                out.append((comp, full(cond), full(var),
                            full(value) if isinstance(value, str) else float(value)))
        return tuple(out)

    def _start_checks(self, model):
        """(component, check) of the components' ``start_checks()`` (see
        :meth:`~acausal2d.language.dsl.Component.start_checks`)."""
        context, out = None, []
        for comp in model.components():
            if type(comp).start_checks is Component.start_checks:
                continue
            context = context or ModelContext(model)
            out += [(comp, check) for check in comp.start_checks(context)]
        return tuple(out)

    def value(self, name, z, p):
        """Value of the variable ``name`` (a node or an eliminated alias)
        at the node values ``z``."""
        if name in self.node_names:
            return float(z[self.node_names.index(name)])
        k = self.alias_names.index(name)
        v = float(self.alias_offset_fn(p).full().ravel()[k])
        j = self.alias_node[k]
        return v + (float(z[j]) * self.alias_sign[k] if j >= 0 else 0.0)

    # ------------------------------------------------------------ queries
    @property
    def names(self) -> tuple[str, ...]:
        """All time-varying columns of a result (nodes, aliases, derivatives)."""
        return self.node_names + self.alias_names + self.alias_der_names

    def describe_equation(self, i: int) -> str:
        """Text of index-reduced equation i with its origin and order."""
        s = self.structure
        lvl = s.eq_level[i]
        text = self.equations[s.eq_origin[i]].describe()
        return text + ("" if lvl == 0 else "  [differentiated %d times]" % lvl)

    def node_name(self, j):
        """Name of variable node j (``der(...)`` for derivative nodes)."""
        return self.node_names[j]

    def owner_of_equation(self, i):
        """Component that wrote index-reduced equation i (None: connections)."""
        return self.equations[self.structure.eq_origin[i]].owner

    def owner_of_equation_flat(self, k):
        """Component that wrote flattened equation k (None: connections)."""
        return self.flat_equations[k].owner

    def owners_of_node(self, j):
        """Components (described) whose equations or eliminated aliases
        contain the variable of node j."""
        s = self.structure
        base = s.var_base[j]
        names = []
        for i in range(s.n_original):
            if base in s.eq_vars[i] and self.equations[i].owner is not None:
                names.append(self.equations[i].owner.describe())
        rep = self.node_info[j]
        for a in self.aliases:
            if a.rep is not None and a.rep.name == rep.name and a.var.owner is not None:
                names.append(a.var.owner.describe())
        return list(dict.fromkeys(names))

    def formulation(self, selection):
        """The semi-explicit index-1 formulation of a dummy selection (cached)."""
        f = self._formulations.get(selection.dummies)
        if f is None:
            with cyclic_gc_paused():
                f = Formulation(self.structure, selection, self.p, self.d, self.state_crossings,
                                self._dEdz)
            self._formulations[selection.dummies] = f
        return f

    def check_fixed_values(self, p: NDArray[np.float64]) -> None:
        """Raise ModelDefinitionError if a variable fixed by parameters alone
        (an eliminated alias with no remaining unknown) is inf or NaN for the
        parameter values ``p``, naming it and the equations that fix it; and
        InitializationError if an eliminated variable's fixed start value
        differs from the value its equations give (over-determined
        initialization: the fixed value would be dropped)."""
        self._check_fixed_starts(p)
        offsets = self.alias_offset_fn(p).full().ravel()
        bad = [k for k in range(len(self.aliases))
               if self.alias_node[k] < 0 and not np.isfinite(offsets[k])]
        if not bad:
            return
        names = [self.aliases[k].var.name for k in bad[:6]]
        syms = [self.aliases[k].var.sym for k in bad[:6]]
        eqs = [eq.describe() for eq in self.flat_equations
               if any(ca.depends_on(eq.expr, sym) for sym in syms)][:6]
        raise ModelDefinitionError(
            "%s would be inf or NaN with these parameter values (a division by zero, the "
            "square root or logarithm of a negative number):\n%s\nChange the parameters of "
            "these equations." % (", ".join(names), "\n".join("  - " + e for e in eqs)))

    def _check_fixed_starts(self, p):
        if not self.fixed_alias_names:
            return
        v = self.fixed_alias_fn(p).full().ravel().reshape(-1, 2)
        for name, (given, by_eq) in zip(self.fixed_alias_names, v):
            if np.isfinite(by_eq) and abs(given - by_eq) > 1e-10 * max(1.0, abs(by_eq)):
                eqs = [eq.describe() for eq in self.flat_equations
                       if any(str(x) == name for x in ca.symvar(eq.expr))][:4]
                raise InitializationError(
                    "%s has the fixed start value %.10g, but the equations give %s = %.10g "
                    "(the initialization is over-determined):\n%s\nDrop fixed=True from %s "
                    "or change its start value to %.10g." % (
                        name, given, name, by_eq, "\n".join("  - " + e for e in eqs), name,
                        by_eq))

    def alias_columns(self, Z: NDArray[np.float64], p: NDArray[np.float64]) -> AliasColumns:
        """The columns of :meth:`alias_values` as an :class:`AliasColumns`:
        each is computed when it is first read (a run's Result reads few)."""
        return AliasColumns(self, np.asarray(Z, dtype=float),
                            self.alias_offset_fn(p).full().ravel())

    def alias_values(self, Z, p):
        """Values of the eliminated variables and their derivatives for node
        values Z (one point per row)."""
        offsets = self.alias_offset_fn(p).full().ravel()
        Z = np.asarray(Z, dtype=float)
        free = self.alias_node >= 0
        n_der = len(self.alias_der_node)
        if Z.shape[1] == 0 or len(Z) == 0:
            A = np.tile(offsets, (len(Z), 1))
            return np.hstack([A, np.zeros((len(Z), n_der))])
        # one gather, one product, one sum over all columns (a node column
        # stands in for the fixed aliases, which are then set to their offsets)
        node = np.concatenate([np.where(free, self.alias_node, 0), self.alias_der_node])
        sign = np.concatenate([np.where(free, self.alias_sign, 0.0), self.alias_der_sign])
        A = Z.take(node.astype(np.intp), axis=1)
        A *= sign
        A[:, :len(offsets)] += offsets
        A[:, np.nonzero(~free)[0]] = offsets[~free]
        return A


class AliasColumns:
    """The eliminated variables' and derivatives' values at node rows Z,
    column by column (the same operations as :meth:`System.alias_values`,
    so the same values)."""

    def __init__(self, system, Z, offsets):
        self.Z, self.offsets = Z, offsets
        s = system
        self.node = np.concatenate([s.alias_node, s.alias_der_node]).astype(int)
        self.sign = np.concatenate([s.alias_sign, s.alias_der_sign])
        self.n_alias = len(offsets)

    def __len__(self):
        return len(self.node)

    def column(self, k):
        """Values of column k over the rows of Z (a new array)."""
        if k >= self.n_alias:
            return self.Z[:, self.node[k]] * self.sign[k]
        if self.node[k] < 0:
            return np.full(len(self.Z), self.offsets[k])
        return self.Z[:, self.node[k]] * self.sign[k] + self.offsets[k]


def _is_zero(v):
    try:
        return float(v) == 0.0
    except (TypeError, RuntimeError):
        return False


def declared_outputs(model):
    """The model's ``outputs`` (signal names to plot), checked: a list or
    tuple of strings; None or missing means none."""
    outputs = getattr(model, "outputs", None)
    if outputs is None:
        return []
    if isinstance(outputs, str) or not isinstance(outputs, (list, tuple)) \
            or not all(isinstance(o, str) for o in outputs):
        raise ModelDefinitionError("%s: outputs must be a list of signal names like "
                                   "['body.phi', 'revolute.w'], got %r"
                                   % (type(model).__name__, outputs))
    return list(outputs)
