"""The fast tier's lists name what exists: every module of SLOW_MODULES
and every test of SLOW_TESTS (tests/conftest.py) is there, so that a
renamed test does not silently fall into the fast tier, and the fuzz
sample takes the same cases on every run, at least one of each class."""
import ast
import os

import conftest
import fuzz_cases

HERE = os.path.dirname(os.path.abspath(__file__))


def _test_functions(module):
    with open(os.path.join(HERE, module), encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    return {node.name for node in ast.walk(tree)
            if isinstance(node, ast.FunctionDef) and node.name.startswith("test")}


def test_slow_modules_exist():
    missing = [m for m in conftest.SLOW_MODULES if not os.path.exists(os.path.join(HERE, m))]
    assert missing == []


def test_first_modules_exist():
    missing = [m for m in conftest.FIRST if not os.path.exists(os.path.join(HERE, m))]
    assert missing == []


def test_slow_tests_exist():
    missing = [(m, name) for m, names in conftest.SLOW_TESTS.items()
               for name in names if name not in _test_functions(m)]
    assert missing == []


def test_fast_cases_name_parametrized_tests_that_exist():
    missing = [(m, name) for m, names in conftest.FAST_CASES.items()
               for name in names if name not in _test_functions(m)]
    assert missing == []


def test_fuzz_sample_is_fixed_and_covers_every_class():
    cases = fuzz_cases.all_cases()
    first = [p.id for p in conftest.fuzz_sample(cases)]
    assert first == [p.id for p in conftest.fuzz_sample(cases)]
    assert {c["category"] for c in cases if c["id"] in first} == {c["category"] for c in cases}
    fast = [p for p in conftest.fuzz_sample(cases) if not p.marks]
    assert len(fast) == len({c["category"] for c in cases})
    if not conftest.FUZZ_ALL:
        assert len(first) < 0.3 * len(cases)


class _Item:
    def __init__(self, module, k):
        self.fspath = os.path.join(HERE, module)
        self.k = k


def test_the_longest_modules_lead_each_worker_s_first_chunk():
    items = [_Item("test_a.py", k) for k in range(300)] + \
        [_Item(m, k) for m in conftest.FIRST for k in range(2)] + \
        [_Item("test_z.py", k) for k in range(300)]
    out = conftest.first_for_each_worker(items, 2)
    assert sorted(map(id, out)) == sorted(map(id, items))          # a reordering
    chunk = len(items) // 2 // 4                                  # xdist's first chunk
    for k, start in enumerate((0, chunk)):
        heads = [os.path.basename(str(i.fspath)) for i in out[start:start + 2 * len(
            conftest.FIRST[k::2])]]
        assert heads == [m for m in conftest.FIRST[k::2] for _ in range(2)]
    assert conftest.first_for_each_worker(items, 1) is items
