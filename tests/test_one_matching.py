"""One cardinality matching in the code base (issue 34):
:class:`acausal2d.compiler.matching.Matching` serves the balance check, the
initial conditions, Pantelides' index reduction, the runtime's block
triangular form and the native LU's pivot order.  (The weighted transversal
of the dummy-derivative choice in large blocks is a different problem - a
minimum-weight perfect matching as in MC64 - and uses scipy's.)"""
import pathlib
import re

import numpy as np
from scipy.sparse import eye, random as sparse_random
from scipy.sparse.csgraph import maximum_bipartite_matching, structural_rank

from acausal2d.runtime.ordering import matching

ROOT = pathlib.Path(__file__).resolve().parents[1]
SEARCH = re.compile(r"def _?augment\b|maximum_bipartite_matching")


def test_only_the_matching_module_searches_augmenting_paths():
    found = sorted(str(p.relative_to(ROOT)) for p in (ROOT / "acausal2d").rglob("*.py")
                   if "library" not in p.parts and SEARCH.search(p.read_text(encoding="utf-8")))
    assert found == ["acausal2d/compiler/matching.py"]


def test_pivot_matching_is_maximum_and_prefers_the_diagonal():
    for seed in range(60):
        rng = np.random.default_rng(seed)
        n = int(rng.integers(1, 40))
        A = sparse_random(n, n, density=rng.uniform(0.02, 0.3), random_state=seed)
        if seed % 2:
            A = A + eye(n)
        A = A.tocsc()
        A.eliminate_zeros()
        rows = matching(n, A.indptr, A.indices)
        matched = [(r, c) for c, r in enumerate(rows) if r >= 0]
        assert len(matched) == structural_rank(A)                      # maximum
        assert np.count_nonzero(maximum_bipartite_matching(A.tocsr(), perm_type="row") >= 0) \
            == len(matched)
        assert len({r for r, _ in matched}) == len(matched)            # a matching
        assert all(A[r, c] != 0 for r, c in matched)                   # on the pattern
        if seed % 2:
            assert rows == list(range(n))                              # the diagonal first
