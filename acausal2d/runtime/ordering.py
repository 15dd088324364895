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


def _augment(col, rows_of, row_match, col_match, seen):
    """Look for an augmenting path from the unmatched column ``col``
    (depth first, without recursion); True where one was found and applied."""
    stack = [(col, iter(rows_of[col]))]
    path = []
    while stack:
        c, rows = stack[-1]
        for r in rows:
            if r in seen:
                continue
            seen.add(r)
            if row_match[r] < 0:
                path.append((c, r))
                for cc, rr in path:
                    row_match[rr], col_match[cc] = cc, rr
                return True
            path.append((c, r))
            stack.append((row_match[r], iter(rows_of[row_match[r]])))
            break
        else:
            stack.pop()
            if path:
                path.pop()
    return False


def matching(n, colind, row):
    """The row matched to each column (a maximum matching; -1 where the
    pattern is structurally singular), cheap assignments first."""
    rows_of = [row[colind[c]:colind[c + 1]] for c in range(n)]
    row_match, col_match = [-1] * n, [-1] * n
    for c in range(n):                         # the diagonal, then any free row
        free = [r for r in rows_of[c] if row_match[r] < 0]
        if free:
            r = c if c in free else free[0]
            row_match[r], col_match[c] = c, r
    for c in range(n):
        if col_match[c] < 0:
            _augment(c, rows_of, row_match, col_match, set())
    return col_match


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
