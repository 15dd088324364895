"""Block lower-triangular (BLT) form of a square sparsity pattern: a
perfect matching of rows to columns (:class:`~acausal2d.compiler.matching.Matching`)
and the strongly connected components of the graph it induces (Tarjan,
iterative), in the order in which they can be solved one after the other;
inside a component the rows go in minimum-degree order.

Row i matched to column c(i) depends on row j when it holds column c(j);
Tarjan's algorithm closes a component only after every component it
depends on, so its output order is the solving order: with rows and
columns permuted to it, every nonzero lies in a diagonal block or to the
left of it.  The runtime's output rows (:mod:`acausal2d.runtime.projection`)
factor the diagonal blocks one by one instead of the whole Jacobian.
The minimum-degree order (:func:`~acausal2d.runtime.ordering.minimum_degree`
of the component's graph made symmetric, which keeps the matched entries on
the diagonal, as :func:`~acausal2d.runtime.ordering.lu_order` does for
IDA's matrix) is for the fill of the block's LU: the block of 158 unknowns
of the chain of 20 pendulum links had 1166 entries in L and U besides the
diagonal in the rows' own order and 657 in this one (partial pivoting, a
row of a run).  Pure Python on lists (no
scipy or networkx: the native runtime path must not import them)."""
from ..compiler.matching import Matching
from .ordering import minimum_degree


class BLT:
    """Row order ``rows`` and column order ``cols`` (permuted position ->
    original index) and block boundaries ``starts`` (block b is positions
    ``starts[b]:starts[b + 1]``) of a square pattern."""

    def __init__(self, rows, cols, starts):
        self.rows, self.cols, self.starts = rows, cols, starts

    @property
    def sizes(self):
        """The size of each diagonal block, in solving order."""
        return [b - a for a, b in zip(self.starts, self.starts[1:])]


def _components(succ):
    """Strongly connected components of the graph ``succ[v]`` (list of
    successors of node v), each a list of nodes, every component after all
    the components it reaches (Tarjan's algorithm, with an explicit stack)."""
    n = len(succ)
    index, low, on = [-1] * n, [0] * n, [False] * n
    stack, out, count = [], [], 0
    for root in range(n):
        if index[root] >= 0:
            continue
        work = [(root, 0)]
        while work:
            v, k = work.pop()
            if k == 0:
                index[v] = low[v] = count
                count += 1
                stack.append(v)
                on[v] = True
            k = _descend(succ, v, k, work, index, low, on)
            if k is not None:
                continue
            if low[v] == index[v]:
                out.append(_pop_component(stack, on, v))
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
    return out


def _descend(succ, v, k, work, index, low, on):
    """Go on with node v from its k-th successor: push (v, next k) and the
    first unvisited successor and return its position, or None when v's
    successors are all seen (their lowlinks folded into v's)."""
    nxt = succ[v]
    while k < len(nxt):
        w = nxt[k]
        k += 1
        if index[w] < 0:
            work.append((v, k))
            work.append((w, 0))
            return k
        if on[w]:
            low[v] = min(low[v], index[w])
    return None


def _pop_component(stack, on, v):
    comp = []
    while True:
        w = stack.pop()
        on[w] = False
        comp.append(w)
        if w == v:
            return comp


def _ordered(comp, succ):
    """The rows of a component in minimum-degree order (module docstring)."""
    nodes = sorted(comp)
    if len(nodes) < 3:
        return nodes
    local = {v: k for k, v in enumerate(nodes)}
    adj = [set() for _ in nodes]
    for k, v in enumerate(nodes):
        for w in succ[v]:
            if w in local:
                adj[k].add(local[w])
                adj[local[w]].add(k)
    return [nodes[k] for k in minimum_degree(adj)]


def blt(pattern_rows, n):
    """The :class:`BLT` of the n x n pattern ``pattern_rows[i]`` = columns of
    row i, or None where it is structurally singular (no perfect matching)."""
    match = Matching(pattern_rows, n).match_all()
    if not match.perfect:
        return None
    row_of = match.row_of
    succ = [[row_of[c] for c in set(cols) if row_of[c] != i]
            for i, cols in enumerate(pattern_rows)]
    rows, starts = [], [0]
    for comp in _components(succ):
        rows.extend(_ordered(comp, succ))
        starts.append(len(rows))
    return BLT(rows, [match.col_of[i] for i in rows], starts)
