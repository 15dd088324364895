"""The structural state that the compiler passes consume and return.

In the style of ModelingToolkit's ``SystemStructure``: the equations and the
variable nodes, the bipartite incidence graph between them, the derivative
maps ``var_to_diff`` (node of x -> node of der(x)) and ``eq_to_diff``
(equation -> its time derivative), the matching found by index reduction
and, once chosen, the dummy-derivative selection.  Every derivative order of
a variable is a node of its own.  All fields are immutable (tuples, frozen
dataclasses); a pass returns a new state with :func:`dataclasses.replace`.
"""
from dataclasses import dataclass, field
from typing import Optional

import casadi as ca

from .incidence import variable_incidence


def column(exprs):
    """A CasADi SX column of scalar expressions (0 x 1 when there is none:
    ``vertcat()`` of nothing is a numeric matrix, which CasADi cannot
    differentiate).  Only what is not an SX yet is converted: SWIG's
    overload resolution of ``SX(sx)`` costs ~50 us per element."""
    exprs = [e if isinstance(e, ca.SX) else ca.SX(e) for e in exprs]
    return ca.vertcat(*exprs) if exprs else ca.SX(0, 1)


@dataclass(frozen=True)
class DiffMap:
    """Links ``x -> der(x)`` between the nodes of one kind (variables or
    equations): ``to_diff[i]`` is the node of the derivative of i, or -1."""
    to_diff: tuple

    def __len__(self):
        return len(self.to_diff)

    def __getitem__(self, i):
        return self.to_diff[i]

    @property
    def from_diff(self):
        """{derivative node: node it is the derivative of}."""
        return {d: i for i, d in enumerate(self.to_diff) if d >= 0}

    def chain(self, i):
        """[i, der(i), der(der(i)), ...]."""
        out = [i]
        while self.to_diff[out[-1]] >= 0:
            out.append(self.to_diff[out[-1]])
        return out


@dataclass(frozen=True)
class Selection:
    """The dummy derivatives chosen for a point (see
    :mod:`~acausal2d.compiler.dummy_derivatives`): the set of dummy
    derivative nodes and the levels it was built from."""
    dummies: frozenset
    levels: tuple

    @property
    def dynamic(self):
        """True if some level offered a real choice (re-selection may help)."""
        return any(lv.dynamic for lv in self.levels)


@dataclass(frozen=True)
class Level:
    """One level of a selection: equations ``eqs``, candidate derivative
    nodes ``cands``, the chosen dummies and whether there was a choice."""
    eqs: tuple
    cands: tuple
    chosen: tuple
    dynamic: bool


@dataclass(frozen=True)
class Structure:
    """Equations x variable nodes of a model (see module docstring).

    eq_expr[i]: residual expression; eq_origin[i]: index of the flattened
    (alias-free) equation it comes from; eq_level[i]: how often it was
    differentiated; eq_vars[i]: incident variable nodes.  var_sym[j]: node
    symbol; var_base[j]: node of the level-0 variable; var_level[j]:
    derivative order.  matching[j]: equation matched to a highest
    derivative node (-1 if none).  velocity_of: pairs (node, derivative
    node) of variables that equal a derivative, such as a joint's ``w`` in
    ``w == der(phi)``, made states by the 'always' pass.
    """
    table: object
    eq_expr: tuple
    eq_origin: tuple
    eq_level: tuple
    eq_vars: tuple
    eq_to_diff: DiffMap
    var_sym: tuple
    var_base: tuple
    var_level: tuple
    var_to_diff: DiffMap
    matching: tuple = ()
    n_original: int = 0
    selection: Optional[Selection] = None
    velocity_of: tuple = ()
    _var_index: Optional[dict] = field(default=None, compare=False, repr=False)

    @property
    def n_eq(self):
        return len(self.eq_expr)

    @property
    def n_var(self):
        return len(self.var_sym)

    @property
    def var_index(self):
        """{symbol key: node}."""
        return self._var_index

    @staticmethod
    def table_key(sym):
        return sym.element_hash()

    def structural_index(self):
        """Largest number of differentiations of an equation."""
        return max(self.eq_level) if self.eq_level else 0

    def chains(self):
        """For each original equation the list [i, der(i), ...]."""
        return [self.eq_to_diff.chain(i) for i in range(self.n_original)]

    def state_nodes(self, selection=None):
        """Nodes integrated as states for ``selection``: those whose derivative
        node exists and is not a dummy derivative."""
        sel = selection or self.selection
        dummies = sel.dummies if sel is not None else frozenset()
        return [j for j in range(self.n_var)
                if self.var_to_diff[j] >= 0 and self.var_to_diff[j] not in dummies]


class NodeBuilder:
    """Creates variable nodes for symbols (every derivative order its own node)."""

    def __init__(self, table):
        self.table = table
        self.sym, self.base, self.level, self.to_diff = [], [], [], []
        self.index = {}

    @classmethod
    def of(cls, structure):
        """A builder continuing the nodes of ``structure``."""
        b = cls(structure.table)
        b.sym, b.base = list(structure.var_sym), list(structure.var_base)
        b.level, b.to_diff = list(structure.var_level), list(structure.var_to_diff.to_diff)
        b.index = dict(structure.var_index)
        return b

    def node(self, sym):
        k = sym.element_hash()
        j = self.index.get(k)
        if j is not None:
            return j
        base, level = self.table.base_and_level(sym)
        lower = None
        if level > 0:
            s = base
            for _ in range(level - 1):
                s = self.table.derivative_symbol(s)
            lower = self.node(s)
        j = len(self.sym)
        self.index[k] = j
        self.sym.append(sym)
        self.base.append(self.index[base.element_hash()] if level > 0 else j)
        self.level.append(level)
        self.to_diff.append(-1)
        if lower is not None:
            self.to_diff[lower] = j
        return j

    def derivative(self, j):
        """Node of der(node j), created if needed."""
        if self.to_diff[j] < 0:
            self.node(self.table.derivative_symbol(self.sym[j]))
        return self.to_diff[j]


def initial_structure(table, exprs, variables):
    """The structure of residuals ``exprs`` in the unknowns ``variables``
    (VarInfo), before index reduction: derivatives appearing in the
    equations are nodes linked to their variables."""
    nodes = NodeBuilder(table)
    for v in variables:
        nodes.node(v.sym)
    syms, inc = variable_incidence(exprs, table)
    col = [nodes.node(s) for s in syms]
    eq_vars = tuple(tuple(sorted({col[c] for c in inc.row(i)}))
                    for i in range(len(exprs)))
    n = len(exprs)
    return Structure(table=table, eq_expr=tuple(exprs), eq_origin=tuple(range(n)),
                     eq_level=(0,) * n, eq_vars=eq_vars, eq_to_diff=DiffMap((-1,) * n),
                     var_sym=tuple(nodes.sym), var_base=tuple(nodes.base),
                     var_level=tuple(nodes.level), var_to_diff=DiffMap(tuple(nodes.to_diff)),
                     matching=(-1,) * len(nodes.sym), n_original=n,
                     _var_index=dict(nodes.index))
