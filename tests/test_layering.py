"""The layering is a contract (issue 34): imports point one way,
language <- compiler <- runtime <- analysis/visual/io <- library <- fmu/cli
(models and tests on top).  Read from the source, function-local imports
included (a local import hides a loop, it does not remove it)."""
import ast
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[1]
RANK = {"language": 0, "compiler": 1, "runtime": 2, "analysis": 3, "visual": 3, "io": 3,
        "library": 4, "fmu": 5, "explore": 5, "cli": 5}


def _module_name(path):
    if path.is_relative_to(ROOT / "library"):
        parts = ("acausal2d", "library") + path.relative_to(ROOT / "library").with_suffix("").parts
    else:
        parts = ("acausal2d",) + path.relative_to(ROOT / "acausal2d").with_suffix("").parts
    return ".".join(p for p in parts if p != "__init__"), path.name == "__init__.py"


def _targets(node, module, is_package):
    if isinstance(node, ast.Import):
        return [a.name for a in node.names]
    if node.level:
        base = module.split(".")[:len(module.split(".")) - node.level + is_package]
        return [".".join(base + ([node.module] if node.module else []))]
    return [node.module]


def _layer(module):
    parts = module.split(".")
    return parts[1] if len(parts) > 1 and parts[0] == "acausal2d" and parts[1] in RANK else None


def imports_against_the_order():
    """(file, importing layer, imported layer) of every import that points up."""
    paths = [p for p in (ROOT / "acausal2d").rglob("*.py") if "library" not in
             p.relative_to(ROOT / "acausal2d").parts[:1]] + list((ROOT / "library").rglob("*.py"))
    found = []
    for path in sorted(paths):
        module, is_package = _module_name(path)
        here = _layer(module)
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if here is None or not isinstance(node, (ast.Import, ast.ImportFrom)):
                continue
            for target in _targets(node, module, is_package):
                there = _layer(target)
                if there is not None and RANK[there] > RANK[here]:
                    found.append((str(path.relative_to(ROOT)), here, there))
    return sorted(set(found))


def test_language_never_imports_the_library_and_the_library_never_the_cli():
    bad = [f for f in imports_against_the_order()
           if (f[1] == "language" and f[2] == "library") or (f[1] == "library" and f[2] == "cli")]
    assert bad == []


def test_every_import_points_down_the_layers():
    assert imports_against_the_order() == []


def test_the_reader_sees_an_upward_import(tmp_path):
    module, _ = _module_name(ROOT / "acausal2d" / "language" / "dsl.py")
    tree = ast.parse("def f():\n    from ..library.planar import Body\n")
    node = [n for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)][0]
    assert _targets(node, module, False) == ["acausal2d.library.planar"]


def test_the_result_imports_no_analysis():
    """A Result is data: the analyses are functions that take one
    (acausal2d.analysis.poles: transfer, ratio, turn_slide, poles)."""
    path = ROOT / "acausal2d" / "result.py"
    module, is_package = _module_name(path)
    targets = [t for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
               if isinstance(node, (ast.Import, ast.ImportFrom))
               for t in _targets(node, module, is_package)]
    assert targets and not [t for t in targets if t.startswith("acausal2d.analysis")]


def test_the_mec2_reader_is_wired_in_by_the_package_root():
    """io reads mec2 files without importing the library: the package root
    registers the library's reader."""
    from acausal2d.io import loader
    kind, read = loader.READERS[".json"]
    assert kind == "mec2" and read.__module__ == "acausal2d"
