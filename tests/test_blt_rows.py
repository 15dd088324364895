"""The block lower-triangular (BLT) form of a sparsity pattern
(:mod:`acausal2d.compiler.blt`) on hand-made patterns: the permuted
pattern is block lower triangular, its blocks are the strongly connected
components, a structurally singular pattern is reported."""
import numpy as np

from acausal2d.compiler.blt import blt


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
