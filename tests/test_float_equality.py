"""Issue 35, Seen 1: no test asserts exact equality of computed floats.

A computed float carries the rounding of the machine, library and
operation order that made it (an LU pivot order, a BLAS kernel, a summation
order), so a test comparing it with ``==`` passes on one machine and fails
on another; a bound has to be derived from the method (rtol, atol, KKT
scale, event tolerance, round-off of the operation) instead.  This test
reads every test module's syntax tree and flags

* ``==`` / ``!=`` with a float literal operand (``x == 0.0``, ``t[-1] ==
  2.0``, ``np.all(a == 1.5)``, also ``-1.0`` and literal arithmetic such as
  ``3.0 * 4.0 - 1``, a list ``[0.1, 0.2]``) anywhere in test code but model equations (an
  ``equations`` method builds equations with ``==``, it compares nothing);
* ``==`` / ``!=`` in an ``assert`` whose operand is a float-valued call:
  ``float(...)``, ``np.max`` / ``min`` / ``ptp`` / ``sum`` / ``mean`` /
  ``norm``, a result's ``final`` / ``at``;
* ``np.array_equal``, ``np.array_equiv`` and ``np.testing.assert_equal`` /
  ``assert_array_equal`` (exact equality of arrays).

Integers and counts (``len(x) == 3``, ``a.sum() == 2``, ``max(ints) == k``)
pass.  A comparison that is exact by design goes through
``conftest.assert_copied`` (numbers passed through without arithmetic, a
deterministic call repeated, a constant selected by a branch), times
through ``conftest.same_time``.  ALLOWED lists the few remaining exact
comparisons that are not of computed floats, each with the reason."""
import ast
import pathlib

TESTS = pathlib.Path(__file__).resolve().parent

FLOAT_CALLS = {"float", "max", "min", "amax", "amin", "ptp", "mean", "norm", "final", "at"}
ARRAY_EQUAL = {"array_equal", "array_equiv", "assert_equal", "assert_array_equal"}

# (file, text of the flagged line stripped) -> why the comparison is exact
ALLOWED = {
    ("conftest.py", "np.testing.assert_array_equal(actual, expected)"):
        "assert_copied: numbers passed through without arithmetic (its docstring)",
    ("fuzz_cases.py", "codes=(0,) if given == 2.0 else (2,)))"):
        "an input the case drew from its own list [1.0, 2.0, -3.5, 0.0], not a result",
    ("fuzz_cases.py", '"nan-middle": (_csv(["time", "a"], [[x, "nan" if x == 0.5 else 0] '
                      'for x in t]), (2,))}'):
        "builds an input file: the row of t = i * 0.1 that is exactly 0.5 (i = 5)",
}


def _float_literal(node):
    """True for a float constant, arithmetic of constants containing one, or
    a list or tuple display with such an element."""
    if isinstance(node, ast.Constant):
        return isinstance(node.value, float)
    if isinstance(node, ast.UnaryOp):
        return _float_literal(node.operand)
    if isinstance(node, (ast.List, ast.Tuple)):               # [0.1, 0.2] == values
        return any(_float_literal(n) for n in node.elts)
    if isinstance(node, ast.BinOp):
        consts = all(isinstance(n, (ast.Constant, ast.UnaryOp, ast.BinOp))
                     for n in (node.left, node.right))
        return consts and (_float_literal(node.left) or _float_literal(node.right))
    return False


def _call_name(node):
    """The called name of a call node (``np.max(...)`` -> "max"), else None;
    builtin max/min of Python numbers (counts) are not float calls."""
    if isinstance(node, ast.Call):
        f = node.func
        if isinstance(f, ast.Attribute):
            return f.attr
        return f.id if getattr(f, "id", None) == "float" else "builtin"
    return None


class _Finder(ast.NodeVisitor):
    """Collects the line numbers of exact float comparisons in one module."""

    def __init__(self):
        self.lines, self._in_assert = set(), 0

    def visit_FunctionDef(self, node):
        if node.name != "equations":                  # model equations compare nothing
            self.generic_visit(node)

    def visit_Assert(self, node):
        self._in_assert += 1
        self.generic_visit(node)
        self._in_assert -= 1

    def visit_Compare(self, node):
        if any(isinstance(op, (ast.Eq, ast.NotEq)) for op in node.ops):
            operands = [node.left] + node.comparators
            if any(_call_name(n) == "approx" for n in operands):
                pass                                  # pytest.approx: a tolerance is given
            elif any(_float_literal(n) for n in operands) or (
                    self._in_assert and any(_call_name(n) in FLOAT_CALLS for n in operands)):
                self.lines.add(node.lineno)
        self.generic_visit(node)

    def visit_Call(self, node):
        if _call_name(node) in ARRAY_EQUAL:
            self.lines.add(node.lineno)
        self.generic_visit(node)


def exact_float_comparisons(path):
    """[(line number, stripped line)] of the flagged comparisons in ``path``."""
    text = path.read_text(encoding="utf-8")
    finder = _Finder()
    finder.visit(ast.parse(text, str(path)))
    lines = text.splitlines()
    return [(k, lines[k - 1].strip()) for k in sorted(finder.lines)]


def test_seen_1_finder_catches_the_patterns(tmp_path):
    src = tmp_path / "test_sample.py"
    src.write_text("import numpy as np\n"
                   "def test_a(fit, res, a, b):\n"
                   "    assert fit.kkt.feasibility == 0.0\n"
                   "    assert res.time[-1] == 1.5\n"
                   "    assert np.all(res['x'] == -1.0)\n"
                   "    assert lib.poly(2.0) == 3.0 * 4.0 - 4.0\n"
                   "    assert np.max(np.abs(a - b)) == 0\n"
                   "    assert float(a) != b\n"
                   "    assert np.array_equal(a, b)\n"
                   "    np.testing.assert_array_equal(a, b)\n"
                   "    k = np.nonzero(res.time == 0.5)[0]\n"
                   "    assert list(res.time) == [0.0, 0.5]\n"
                   "    assert len(a) == 3 and a.shape == (2, 2) and abs(a - b) < 1e-9\n"
                   "    assert max(a) == 3 and a.sum() == 2 and x == pytest.approx(0.5)\n"
                   "class M:\n"
                   "    def equations(self):\n"
                   "        return [der(self.x) == 1.0]\n", encoding="utf-8")
    assert [k for k, _ in exact_float_comparisons(src)] == list(range(3, 13))


def test_seen_1_no_test_asserts_exact_equality_of_computed_floats():
    found = {(p.name, text): k for p in sorted(TESTS.glob("*.py"))
             for k, text in exact_float_comparisons(p)}
    flagged = sorted("%s:%d: %s" % (name, k, text)
                     for (name, text), k in found.items() if (name, text) not in ALLOWED)
    assert not flagged, ("exact equality of computed floats; bound the difference by the "
                         "method's tolerance instead:\n" + "\n".join(flagged))
    stale = sorted(set(ALLOWED) - set(found))
    assert not stale, "ALLOWED entries no longer found: %s" % stale
