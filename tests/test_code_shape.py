"""The code stays readable: no function of the package, the library or the
models is more complex than cyclomatic complexity 15 (radon's measure) or
longer than one screen (50 lines of code below its docstring)."""
import ast
import pathlib

import pytest
from radon.complexity import cc_visit

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ("acausal2d", "library", "models")
MAX_COMPLEXITY = 15
MAX_LINES = 50


def _sources():
    return sorted(p for folder in FOLDERS for p in (ROOT / folder).rglob("*.py"))


def _code_lines(node):
    """Lines from the ``def`` to the end, without the docstring."""
    body = node.body
    doc = isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
        and isinstance(body[0].value.value, str)
    skipped = (body[0].end_lineno - body[0].lineno + 1) if doc and len(body) > 1 else 0
    return node.end_lineno - node.lineno + 1 - skipped


def test_the_sources_are_found():
    names = {p.name for p in _sources()}
    assert {"simulation.py", "joints.py", "piston_engine.py"} <= names


@pytest.mark.parametrize("path", _sources(), ids=lambda p: str(p.relative_to(ROOT)))
def test_complexity_and_length(path):
    text = path.read_text(encoding="utf-8")
    too_complex = ["%s (line %d): %d" % (b.fullname, b.lineno, b.complexity)
                   for b in cc_visit(text) if b.complexity > MAX_COMPLEXITY]
    too_long = ["%s (line %d): %d lines" % (n.name, n.lineno, _code_lines(n))
                for n in ast.walk(ast.parse(text))
                if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))
                and _code_lines(n) > MAX_LINES]
    assert not too_complex, "cyclomatic complexity above %d: %s" % (MAX_COMPLEXITY, too_complex)
    assert not too_long, "functions longer than %d lines: %s" % (MAX_LINES, too_long)
