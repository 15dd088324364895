"""Output rows through the block lower-triangular (BLT) form of dE/dz_free:
the analysis (:mod:`acausal2d.runtime.blt`) on hand-made patterns - the
permuted pattern is block lower triangular, its blocks are the strongly
connected components, a structurally singular pattern is reported - the
layout handed to C (:mod:`acausal2d.runtime.blt_layout`: each nonzero in
its diagonal block or below it, none for a singular Jacobian), and the C
projector (``native_project.c``) on real runs: every row it returns
as converged satisfies every equation to 1e-12 of the equation's scale."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime.blt import blt
from acausal2d.runtime import blt_layout, native, projection

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "models"))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "benchmarks"))
from bench_core import PendulumChain  # noqa: E402
from compressor import Compressor  # noqa: E402
from conftest import assert_copied


def _dense(pattern, n):
    A = np.zeros((n, n), dtype=bool)
    for i, cols in enumerate(pattern):
        A[i, cols] = True
    return A


def _check_blt(pattern, n):
    """The BLT of a pattern: permutations, block lower triangular, each
    block's rows a strongly connected set; returns its block sizes."""
    form = blt(pattern, n)
    assert sorted(form.rows) == list(range(n)) and sorted(form.cols) == list(range(n))
    A = _dense(pattern, n)[np.ix_(form.rows, form.cols)]
    assert A.diagonal().all()                    # the matching on the diagonal
    for a, b in zip(form.starts, form.starts[1:]):
        assert not A[a:b, b:].any()              # nothing right of a block
        reach = A[a:b, a:b] | np.eye(b - a, dtype=bool)
        for _ in range(b - a):                   # transitive closure in the block
            reach = reach | ((reach.astype(int) @ reach.astype(int)) > 0)
        assert reach.all()                       # one strongly connected component
    return form.sizes


def test_a_triangular_pattern_gives_blocks_of_one_in_solving_order():
    # x2 from row 0, then x0 from row 1 (uses x2), then x1 from row 2
    pattern = [[2], [0, 2], [0, 1, 2]]
    form = blt(pattern, 3)
    assert form.sizes == [1, 1, 1]
    assert form.rows == [0, 1, 2] and form.cols == [2, 0, 1]
    assert _check_blt(pattern, 3) == [1, 1, 1]


def test_a_loop_is_one_block_after_what_it_needs_and_before_what_needs_it():
    # rows 1, 3 couple x1, x3 (a loop); row 0 gives x0 alone; row 2 needs all
    pattern = [[0], [1, 3, 0], [2, 1], [3, 1]]
    form = blt(pattern, 4)
    assert form.sizes == [1, 2, 1]
    assert form.rows[0] == 0 and sorted(form.rows[1:3]) == [1, 3] and form.rows[3] == 2
    assert _check_blt(pattern, 4) == [1, 2, 1]


def test_random_patterns_are_block_lower_triangular_with_strong_blocks():
    rng = np.random.default_rng(7)
    for n in (5, 12, 30):
        for _ in range(20):
            A = rng.random((n, n)) < 2.0 / n
            A[np.arange(n), rng.permutation(n)] = True         # structurally regular
            pattern = [list(np.nonzero(r)[0]) for r in A]
            assert sum(_check_blt(pattern, n)) == n


def test_a_structurally_singular_pattern_has_no_blt():
    # rows 0 and 1 both only hold x0: no perfect matching
    assert blt([[0], [0], [1, 2], [2, 3]], 4) is None
    assert blt([[0, 1], [0, 1], [0, 1]], 3) is None


def test_a_long_chain_needs_no_recursion():
    n = 20000                      # row i holds x_i and x_(i+1): one block of n
    pattern = [[i, (i + 1) % n] for i in range(n)]
    assert blt(pattern, n).sizes == [n]


def _stored_rows(cm, **settings):
    """(projector, T, Z, d) of each batch of output rows of a run."""
    saved = []
    project = projection.Projector.project

    def keep(self, T, Z, d, overwrite=False):
        saved.append((self, np.array(T), np.array(Z), np.array(d)))
        return project(self, T, Z, d, overwrite)
    projection.Projector.project = keep
    try:
        cm.simulate(**settings)
    finally:
        projection.Projector.project = project
    return saved


def _worst(proj, T, Z, d):
    """max over rows and equations of |E_i| / scale_i (independent of the C code)."""
    s = proj.system
    rows, cols = s.jacobian_pattern
    worst = 0.0
    for t, z in zip(T, Z):
        E = np.array(s.residual_fn(t, z, proj.p, d)).ravel()
        J = np.array(s.jacobian_fn(t, z, proj.p, d).nonzeros())
        scale = np.zeros(len(E))
        np.add.at(scale, rows, np.abs(J) * (s.nominal + np.abs(z))[cols])
        worst = max(worst, float(np.max(np.abs(E) / np.maximum(scale, 1e-300))))
    return worst


@pytest.mark.parametrize("model, settings, largest", [
    (lambda: PendulumChain(20), dict(stop_time=2.0, rtol=1e-6, intervals=500), 158),
    (Compressor, dict(stop_time=0.2), 25)], ids=["chain of 20 links", "compressor"])
def test_the_c_projector_solves_every_row_to_1e_12(model, settings, largest):
    cm = acausal2d.compile_model(model())
    saved = _stored_rows(cm, **settings)
    assert saved and all(proj.native is not None for proj, *_ in saved)
    proj = saved[0][0]
    ints = blt_layout.layout(proj.system, proj.free)
    nb = ints[0]
    assert max(np.diff(ints[1:nb + 2])) == largest          # the largest diagonal block
    n_rows = 0
    for proj, T, Z, d in saved:
        out, ok = proj.native(T, Z, proj.p, d, projection.RES_TOL, proj.native_iterations,
                              proj.native_slow)
        assert ok.all()
        assert_copied(out[:, ~np.isin(np.arange(Z.shape[1]), proj.free)],   # held columns
                      Z[:, ~np.isin(np.arange(Z.shape[1]), proj.free)])
        assert _worst(proj, T, out, d) <= 1e-12
        given = Z.copy()                   # the run's way: IDA's rows solved where they are
        inplace, ok = proj.native(T, given, proj.p, d, projection.RES_TOL,
                                  proj.native_iterations, proj.native_slow, True)
        assert inplace is given and ok.all()
        assert_copied(inplace, out)                    # the same deterministic call
        n_rows += len(T)
    assert n_rows >= 100
    assert native.row_projector(proj.system, proj.free) is not None


class _System:
    """What :func:`blt_layout.layout` reads of a system: sizes and the
    sparsity of dE/dz (a CasADi function of a given pattern)."""

    def __init__(self, A):
        import casadi as ca
        self.structure = type("S", (), {"n_eq": A.shape[0], "n_var": A.shape[1]})()
        rows, cols = np.nonzero(A)
        sp = ca.Sparsity.triplet(A.shape[0], A.shape[1], rows.tolist(), cols.tolist())
        self.jacobian_fn = ca.Function("dEdz", [], [ca.DM(sp, 1.0)])


def test_the_layout_puts_each_nonzero_in_its_block_or_below():
    rng = np.random.default_rng(3)
    n, n_var = 40, 46
    A = rng.random((n, n_var)) < 0.06
    free = np.sort(rng.permutation(n_var)[:n])
    A[np.arange(n), free[rng.permutation(n)]] = True       # structurally regular
    ints = blt_layout._layout(_System(A), free)
    nb = int(ints[0])
    start, q = ints[1:nb + 2], nb + 2
    rperm, pvar, q = ints[q:q + n], ints[q + n:q + 2 * n], q + 2 * n
    rows, cols = (np.asarray(a) for a in _System(A).jacobian_fn.sparsity_out(0).get_triplet())
    slot, q = ints[q:q + len(rows)], q + len(rows)
    aptr, q = ints[q:q + n + 1], q + n + 1
    ai, q = ints[q:q + aptr[-1]], q + aptr[-1]
    bptr, q = ints[q:q + n + 1], q + n + 1
    brow = ints[q:q + bptr[-1]]
    assert sorted(rperm) == list(range(n)) and sorted(pvar) == sorted(free)
    pos_row, pos_col = np.argsort(rperm), {v: k for k, v in enumerate(pvar)}
    block = np.repeat(np.arange(nb), np.diff(start))
    for k, (r, c) in enumerate(zip(rows, cols)):
        if c not in pos_col:
            assert slot[k] == -1                    # a state's column
            continue
        i, j = pos_row[r], pos_col[c]
        assert block[i] >= block[j]                 # block lower triangular
        if block[i] == block[j]:
            assert aptr[j] <= slot[k] < aptr[j + 1] and ai[slot[k]] == i - start[block[j]]
        else:
            q = -2 - slot[k]
            assert bptr[j] <= q < bptr[j + 1] and brow[q] == i
    assert aptr[-1] + bptr[-1] == np.isin(cols, free).sum()


def test_a_structurally_singular_jacobian_gets_no_layout():
    A = np.eye(4, dtype=bool)
    A[2] = A[1]                                     # rows 1 and 2 hold column 1 only
    assert blt_layout._layout(_System(A), np.arange(4)) is None
