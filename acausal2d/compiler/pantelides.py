"""Pantelides' algorithm: find which equations must be differentiated.

A pass over the :class:`~acausal2d.compiler.structure.Structure`: matching
uses only the highest derivative nodes; whenever an equation cannot be
matched, the equations and variables of the failed augmenting-path search
are differentiated (Pantelides 1988).  The differentiated equations are then
built symbolically (chain rule over the derivative symbols), so library code
never writes velocity or acceleration equations.
"""
from dataclasses import replace

import casadi as ca

from ..errors import StructuralError
from ..language.symbols import time
from .matching import Matching
from .structure import DiffMap, NodeBuilder


class _Work:
    """Mutable working copy of the graph while the algorithm runs.  The
    matching is the code base's one :class:`~acausal2d.compiler.matching.Matching`
    over the equations and the highest derivative nodes (its candidate
    lists are renewed where a node gets a derivative)."""

    def __init__(self, s):
        self.nodes = NodeBuilder.of(s)
        self.eq_vars = [list(v) for v in s.eq_vars]
        self.eq_origin, self.eq_level = list(s.eq_origin), list(s.eq_level)
        self.B = list(s.eq_to_diff.to_diff)
        self.match = Matching([], len(self.nodes.sym))
        self.match.row_of[:len(s.matching)] = list(s.matching)
        self.eqs_of = [[] for _ in self.nodes.sym]        # node -> equations it appears in
        for i, vs in enumerate(self.eq_vars):
            for j in vs:
                self.eqs_of[j].append(i)
            self._append_row(i)
        for j, i in enumerate(self.match.row_of):
            if i >= 0:
                self.match.col_of[i] = j
        self.colV, self.colE = set(), set()

    @property
    def A(self):
        return self.nodes.to_diff

    @property
    def assign(self):
        """Node -> the equation matched to it (-1: none)."""
        return self.match.row_of

    def _append_row(self, i):
        self.match.rows.append(self.highest(i))
        self.match.col_of.append(-1)
        self.match._look.append(0)

    def grow_assign(self):
        more = len(self.nodes.sym) - len(self.match.row_of)
        self.match.row_of.extend([-1] * more)
        self.eqs_of.extend([] for _ in range(more))

    def highest(self, i):
        return [j for j in self.eq_vars[i] if self.A[j] < 0]

    def renew_candidates(self, first_new_node):
        """Candidate lists of the equations holding a node that got its
        derivative since nodes numbered from ``first_new_node`` were made."""
        changed = set()
        for k in range(first_new_node, len(self.nodes.sym)):
            j = self.nodes.base[k]
            while self.A[j] != k:
                j = self.A[j]
            changed.update(self.eqs_of[j])
        for i in changed:
            self.match.rows[i] = self.highest(i)
            self.match._look[i] = 0

    def colour_search(self, i0):
        """Augmenting path from equation i0; colours the nodes (colV) and
        equations (colE) the search visited."""
        seen = set()
        found = self.match.augment(i0, seen)
        self.colV = seen
        self.colE = {i0} | {self.assign[j] for j in seen}
        return found

    def set_assign(self, j, i):
        """Match node ``j`` to equation ``i``."""
        self.match.row_of[j] = i
        if i >= 0:
            self.match.col_of[i] = j

    def differentiate(self, l):
        inc = set()
        for j in self.eq_vars[l]:
            inc.add(j)
            inc.add(self.nodes.derivative(j))
        n = len(self.eq_vars)
        self.eq_vars.append(sorted(inc))
        self.eq_origin.append(self.eq_origin[l])
        self.eq_level.append(self.eq_level[l] + 1)
        self.B.append(-1)
        self.B[l] = n
        self.grow_assign()
        for j in self.eq_vars[n]:
            self.eqs_of[j].append(n)
        self._append_row(n)


def _reduce(w, starts, max_differentiations):
    """Pantelides' main loop from each equation in ``starts``: match it to a
    highest derivative, or differentiate the equations and variables of
    the failed search and go on with its derivative.  Returns the equation
    that would need too many differentiations, or None."""
    for k in starts:
        i = k
        while True:
            w.colV.clear()
            w.colE.clear()
            w.grow_assign()
            if w.colour_search(i):
                break
            if w.eq_level[i] >= max_differentiations:
                return i
            first_new = len(w.nodes.sym)
            for j in list(w.colV):
                w.nodes.derivative(j)
            w.grow_assign()
            for l in sorted(w.colE):
                w.differentiate(l)
            w.renew_candidates(first_new)
            for j in w.colV:
                w.set_assign(w.A[j], w.B[w.assign[j]])
            i = w.B[i]
    return None


def _finish(s, w, describe_equation, stuck, max_differentiations, **fields):
    """The structure after the reduction held by ``w`` (expressions of the
    new equations built symbolically)."""
    if stuck is not None:
        raise StructuralError(
            "Index reduction does not terminate: equation '%s' would be differentiated "
            "more than %d times. The model is structurally singular (a constraint "
            "repeats another one or an unknown is missing)."
            % (describe_equation(w.eq_origin[stuck]), max_differentiations))
    w.grow_assign()
    exprs = _differentiate_symbolically(w, list(s.eq_expr))
    return replace(s, eq_expr=tuple(exprs), eq_origin=tuple(w.eq_origin),
                   eq_level=tuple(w.eq_level), eq_vars=tuple(tuple(v) for v in w.eq_vars),
                   eq_to_diff=DiffMap(tuple(w.B)), var_sym=tuple(w.nodes.sym),
                   var_base=tuple(w.nodes.base), var_level=tuple(w.nodes.level),
                   var_to_diff=DiffMap(tuple(w.nodes.to_diff)), matching=tuple(w.assign),
                   _var_index=dict(w.nodes.index), **fields)


def pantelides(s, describe_equation, max_differentiations=None):
    """Index reduction of the structure ``s`` (before any differentiation);
    returns the structure with the differentiated equations, their
    expressions, the derivative maps and the matching.
    ``describe_equation(origin)`` names an equation in errors."""
    if max_differentiations is None:
        max_differentiations = s.n_original + 3
    w = _Work(s)
    stuck = _reduce(w, range(s.n_original), max_differentiations)
    return _finish(s, w, describe_equation, stuck, max_differentiations)


def differentiate_further(s, equations, describe_equation, **fields):
    """The reduced structure ``s`` with ``equations`` differentiated once
    more and the reduction continued until every equation is matched to a
    highest derivative again (a variable that must become a state may need
    derivatives Pantelides' minimal reduction did not create).  ``fields``
    are further structure fields to set."""
    max_differentiations = s.n_original + 3
    w = _Work(s)
    first_new = len(w.nodes.sym)
    for i in equations:
        w.differentiate(i)
    w.grow_assign()
    w.renew_candidates(first_new)
    for j in range(len(w.assign)):          # matches of variables that are no longer highest
        if w.A[j] >= 0:
            w.assign[j] = -1
    matched = set(w.assign)
    tops = [c for c in range(len(w.eq_vars)) if w.B[c] < 0 and c not in matched]
    stuck = _reduce(w, tops, max_differentiations)
    return _finish(s, w, describe_equation, stuck, max_differentiations, **fields)


def _differentiate_symbolically(w, exprs):
    """Expressions of all differentiated equations, one derivative order at
    a time, with a single forward-mode derivative per order."""
    exprs = exprs + [None] * (len(w.eq_vars) - len(exprs))
    parent = {d: i for i, d in enumerate(w.B) if d >= 0}
    sym, A = w.nodes.sym, w.nodes.to_diff
    level = 1
    while True:
        todo = [i for i in range(len(exprs)) if exprs[i] is None and w.eq_level[i] == level]
        if not todo:
            return exprs
        nodes = sorted({j for i in todo for j in w.eq_vars[parent[i]]})
        V = ca.vertcat(time, *[sym[j] for j in nodes])
        Vdot = ca.vertcat(1, *[sym[A[j]] for j in nodes])
        F = ca.vertcat(*[exprs[parent[i]] for i in todo])
        for i, e in zip(todo, ca.vertsplit(ca.jtimes(F, V, Vdot))):
            exprs[i] = e
        level += 1
