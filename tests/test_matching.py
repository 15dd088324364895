"""The maximum matching of the balance check and the initial conditions
(passes with lookahead and a shared visited set) against networkx's
Hopcroft-Karp on random incidences, and on a long chain."""
import random

import networkx as nx
from networkx.algorithms import bipartite

from acausal2d.compiler.matching import Matching


def _size_hk(rows, n_cols):
    g = nx.Graph()
    tops = [("r", i) for i in range(len(rows))]
    g.add_nodes_from(tops)
    g.add_nodes_from(("c", j) for j in range(n_cols))
    g.add_edges_from((("r", i), ("c", j)) for i, r in enumerate(rows) for j in r)
    return len(bipartite.hopcroft_karp_matching(g, top_nodes=tops)) // 2


def _check(m, rows):
    for r, c in enumerate(m.col_of):
        if c >= 0:
            assert c in rows[r] and m.row_of[c] == r
    return sum(c >= 0 for c in m.col_of)


def test_random_incidences_reach_maximum_size():
    rng = random.Random(7)
    for _ in range(400):
        nr, nc = rng.randint(1, 40), rng.randint(1, 40)
        rows = [sorted(rng.sample(range(nc), rng.randint(0, min(nc, 4)))) for _ in range(nr)]
        assert _check(Matching(rows, nc).match_all(), rows) == _size_hk(rows, nc)


def test_add_row_keeps_matchable_rows_only():
    rng = random.Random(11)
    for _ in range(100):
        nc = rng.randint(2, 25)
        rows = [sorted(rng.sample(range(nc), rng.randint(1, min(nc, 3)))) for _ in range(nc // 2)]
        m = Matching(rows, nc).match_all()
        kept = list(rows)
        for _ in range(nc):
            new = sorted(rng.sample(range(nc), rng.randint(1, 2)))
            before = _size_hk(kept, nc)
            if m.add_row(new):
                kept.append(new)
                assert _size_hk(kept, nc) == before + 1
            else:
                assert _size_hk(kept + [new], nc) == before
            assert _check(m, kept) == _size_hk(kept, nc)


def test_chain_whose_greedy_start_is_wrong_everywhere():
    # row i has columns (i, i + 1), the last row only column 0: the greedy
    # start gives row i column i, so the last row's one augmenting path
    # shifts every other row to column i + 1
    n = 20000
    rows = [[i, i + 1] for i in range(n - 1)] + [[0]]
    m = Matching(rows, n).match_all()
    assert m.perfect and m.col_of[-1] == 0
    assert all(m.col_of[i] == i + 1 for i in range(n - 1))
