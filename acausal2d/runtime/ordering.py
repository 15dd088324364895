"""The pivot order of the native sparse LU (``native_lu.c``): a maximum
matching of rows to columns of the iteration matrix's pattern (each column's
preferred pivot row, so a zero-free "diagonal") and a minimum degree order
of the symmetric graph of the matched pattern (A + A^T with each row taken
as the column it is matched to), as KLU does with its maximum transversal
and AMD.  Pure Python on the pattern (no scipy: it is not imported on a
native run); computed once per formulation.
"""
import heapq

import numpy as np

from ..compiler.matching import Matching


def matching(n, colind, row):
    """The row matched to each column (a maximum matching; -1 where the
    pattern is structurally singular), the diagonal preferred: each column
    lists its own row first (:class:`~acausal2d.compiler.matching.Matching`,
    the code base's one matching)."""
    candidates = []
    for c in range(n):
        rows = [int(r) for r in row[colind[c]:colind[c + 1]]]
        candidates.append([c] + [r for r in rows if r != c] if c in rows else rows)
    return list(Matching(candidates, n).match_all().col_of)


def minimum_degree(adjacency):
    """An elimination order of a symmetric graph (list of neighbour sets,
    consumed): at each step the node of least degree in the graph where the
    eliminated nodes' neighbours are joined (smallest index on ties)."""
    heap = [(len(a), j) for j, a in enumerate(adjacency)]
    heapq.heapify(heap)
    done = [False] * len(adjacency)
    order = []
    while heap:
        degree, v = heapq.heappop(heap)
        if done[v] or degree != len(adjacency[v]):
            continue
        done[v] = True
        order.append(v)
        nb = adjacency[v]
        for u in nb:
            a = adjacency[u]
            a.discard(v)
            a |= nb
            a.discard(u)
            heapq.heappush(heap, (len(a), u))
        adjacency[v] = set()
    return order


def lu_order(n, colind, row):
    """(column order, preferred pivot row of each column) as C int arrays
    for ``native_lu.c``, from a CCS pattern of an n x n matrix."""
    colind, row = [int(c) for c in colind], [int(r) for r in row[:colind[n]]]
    prefer = matching(n, colind, row)
    free_rows = iter(sorted(set(range(n)) - set(prefer)))
    node = [-1] * n                       # row -> the column (node) it is matched to
    for c in range(n):
        if prefer[c] < 0:                 # structurally singular: any free row
            prefer[c] = next(free_rows)
        node[prefer[c]] = c
    adjacency = [set() for _ in range(n)]
    for c in range(n):
        for r in row[colind[c]:colind[c + 1]]:
            if node[r] != c:
                adjacency[c].add(node[r])
                adjacency[node[r]].add(c)
    order = minimum_degree(adjacency)
    return np.asarray(order, dtype=np.intc), np.asarray(prefer, dtype=np.intc)
