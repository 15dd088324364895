"""Dummy-derivative choice in large blocks (issue 17, item 5): the sparse
transversal used above LARGE_BLOCK equations picks the same dummies as the
dense QR with column pivoting on a long pendulum chain, gives a regular
block, and respects the priority classes like the dense choice."""
import os
import sys

import numpy as np

import acausal2d
from acausal2d.compiler import dummy_derivatives as dd

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "benchmarks"))
from bench_core import PendulumChain  # noqa: E402


def test_chain_sparse_choice_equals_dense_choice(monkeypatch):
    cm = acausal2d.compile_model(PendulumChain(230))       # level blocks of 460 equations
    sparse = cm.initial_point().selection
    assert max(len(lv.eqs) for lv in sparse.levels) > dd.LARGE_BLOCK
    monkeypatch.setattr(dd, "LARGE_BLOCK", 10 ** 9)
    dense = cm.initial_point().selection
    assert sparse.dummies == dense.dummies
    assert [lv.dynamic for lv in sparse.levels] == [lv.dynamic for lv in dense.levels]


def test_random_blocks_regular_and_class_counts_as_dense():
    rng = np.random.default_rng(5)
    for _ in range(30):
        m = rng.integers(5, 40)
        n = m + rng.integers(1, 20)
        H = np.zeros((m, n))
        for i in range(m):                       # a banded regular part plus random entries
            H[i, i] = rng.uniform(0.5, 2.0)
            H[i, rng.integers(0, n, size=3)] = rng.normal(size=3)
        prio = list(rng.integers(1, 4, size=n))
        got = dd._pick_large(H, prio, m)
        ref = dd._pick(H, prio, m)
        assert got is not None and ref is not None
        sv = np.linalg.svd(H[:, got[0]], compute_uv=False)
        assert sv[-1] > 1e-9 * sv[0]
        assert list(np.bincount([prio[c] for c in got[0]], minlength=5)) == \
            list(np.bincount([prio[c] for c in ref[0]], minlength=5))
