"""The package layout (issue: library/ that reads like the seed): every import
the README and the models write resolves, each VDI element has its own
module citing its Anhang B section, no module is longer than 600 lines, and
no two modules of the package import each other (directly or in a circle).
"""
import ast
import importlib
import pathlib
import re

import networkx as nx
import pytest

import acausal2d

ROOT = pathlib.Path(__file__).resolve().parents[1]

def _import_statements(source):
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0 \
                and node.module.startswith("acausal2d"):
            yield node.module, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("acausal2d"):
                    yield a.name, []


def _readme_code(path="README.md"):
    text = (ROOT / path).read_text(encoding="utf-8")
    return "\n".join(re.findall(r"```python\n(.*?)```", text, re.S))


def _sources_users_copy():
    yield "README.md", _readme_code()
    for path in sorted((ROOT / "docs").rglob("*.md")):      # the documentation site's pages
        rel = str(path.relative_to(ROOT))
        if not rel.startswith(("docs/_build", "docs/gallery", "docs/api")):
            yield rel, _readme_code(rel)
    for path in sorted((ROOT / "models").glob("*.py")):
        yield path.name, path.read_text(encoding="utf-8")


@pytest.mark.parametrize("where,source", list(_sources_users_copy()), ids=lambda v: v
                         if isinstance(v, str) and len(v) < 60 else "")
def test_every_import_the_readme_and_models_write_resolves(where, source):
    for module, names in _import_statements(source):
        mod = importlib.import_module(module)
        for name in names:
            assert hasattr(mod, name) or importlib.util.find_spec(module + "." + name), \
                "%s: from %s import %s" % (where, module, name)


ELEMENTS = {"dan": "B.1", "san": "B.2", "fgp": "B.3", "ddd": "B.4", "dds": "B.5", "dsd": "B.6",
            "ssd": "B.7", "sds": "B.8"}


@pytest.mark.parametrize("module,section", sorted(ELEMENTS.items()))
def test_each_vdi_element_has_its_module_citing_anhang_b(module, section):
    mod = importlib.import_module("acausal2d.library.linkage." + module)
    assert "Anhang %s" % section in mod.__doc__
    cls = getattr(mod, module.upper())
    assert cls.__module__ == mod.__name__
    assert getattr(acausal2d.library.linkage, module.upper()) is cls


def _package_files():
    for folder in ("acausal2d", "library"):
        yield from sorted((ROOT / folder).rglob("*.py"))


def test_no_module_longer_than_600_lines():
    long = {str(p.relative_to(ROOT)): n for p in _package_files()
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert not long


def _module_name(path):
    rel = path.relative_to(ROOT).with_suffix("")
    parts = list(rel.parts)
    if parts[0] == "library":
        parts = ["acausal2d", "library"] + parts[1:]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _imports_of(path, name):
    """Package modules imported anywhere in the file (functions included)."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            base = package
            for _ in range(max(node.level - 1, 0)):
                base = base.rpartition(".")[0]
            mod = (base + "." + node.module if node.module else base) if node.level \
                else (node.module or "")
            yield mod
            for a in node.names:
                yield mod + "." + a.name
        elif isinstance(node, ast.Import):
            for a in node.names:
                yield a.name


def test_no_import_circles_between_modules():
    files = {_module_name(p): p for p in _package_files()}
    graph = nx.DiGraph()
    for name, path in files.items():
        for target in _imports_of(path, name):
            if target in files and target != name and not name.startswith(target + "."):
                if not target.startswith(name + "."):
                    graph.add_edge(name, target)
    cycles = [c for c in nx.simple_cycles(graph)
              if not any(n.rsplit(".", 1)[0] in c or n in ("acausal2d",) for n in c)]
    assert not cycles, cycles
