"""Function-local imports only where an import is optional or costly
(issue 34).  A local import hides a dependency from the reader, so each one
must have one of these reasons:

- optional: inside ``try: ... except ImportError`` (an extra that may be
  missing, e.g. pandas);
- import cost of a third-party package: :data:`COSTLY` (measured with
  ``python -X importtime``; none of them is loaded by ``import acausal2d``);
- import cost of our own modules at the start: the importing module is
  loaded by ``import acausal2d`` or ``acausal2d --help`` and the imported
  one is not (the start stays as light as docs/speed.md measures it);
- a site of :data:`SITES`, with its reason.

Measured when the rule was made (issue 34): 259 of 978 imports were
function-local before, 123 of 963 after (the rest moved to module level;
``import acausal2d`` loads the same 237 modules, the CLI's start one more,
the light io.loader)."""
import ast
import json
import pathlib
import subprocess
import sys

from test_layering import ROOT, _module_name, _targets

COSTLY = {
    "scipy": "0.1-0.3 s; the runtime needs it only for sparse systems and fits",
    "matplotlib": "0.4 s; figures only",
    "sksundae": "imports scipy.optimize; the Python IDA path only",
    "dask": "0.5 s with distributed; sweeps only",
    "distributed": "as dask",
    "cloudpickle": "sweep workers only",
    "networkx": "0.1 s; structural diagnostics only",
    "ezdxf": "0.2 s; DXF export only",
    "starlette": "the explore extra (optional) and its import cost",
    "uvicorn": "the explore extra (optional) and its import cost",
    "webbrowser": "explore only: opens the page",
    "tqdm": "0.1 s; a progress bar only where standard error is a terminal",
    "threadpoolctl": "0.03 s (and 34 ms for its controller); made once per process at the first run",
    "subprocess": "7-8 ms (with signal, selectors, locale); only where a compiler or a worker runs",
    "concurrent": "2-7 ms (and logging); the background worker's process only",
    "logging": "5-16 ms; only when a notice is said",
}
"""Third-party (and stdlib) packages imported inside functions: name -> reason."""

SITES = {
    ("acausal2d/runtime/ida.py", "acausal2d.runtime.sundae"): "imports scikit-sundae (COSTLY)",
    ("acausal2d/runtime/sundials_ext.py", "acausal2d.runtime.sundae"):
        "imports scikit-sundae (COSTLY)",
    ("acausal2d/runtime/newton.py", "acausal2d.runtime.stacked"): "imports scipy.sparse",
    ("acausal2d/analysis/fit.py", "acausal2d.analysis.optimality"): "imports scipy.optimize",
    ("library/linkage/base.py", "acausal2d.library"):
        "the module defines a function 'translational' and planar imports linkage",
    ("acausal2d/__init__.py", "acausal2d.analysis.compare"):
        "compare only: it loads io.files (tempfile, hashlib, json, shutil), 20-28 ms of "
        "``import acausal2d`` (the command line loads it for its compare command)",
    ("acausal2d/compiled.py", "acausal2d.analysis.modes"):
        "linearize and modes only (with the equilibrium, 6-14 ms of a first run's imports)",
    ("acausal2d/compiled.py", "acausal2d.analysis.equilibrium"): "the equilibrium only (as above)",
    ("acausal2d/result.py", "acausal2d.io.files"):
        "a CSV written only (io.files loads tempfile, hashlib, json, shutil: 10-24 ms)",
    ("acausal2d/compiled.py", "acausal2d.visual.diagram"):
        "the diagram's layout loads networkx (COSTLY): only when a diagram is drawn",
    ("acausal2d/explore/runner.py", "acausal2d.visual.diagram"):
        "the diagram's layout loads networkx (COSTLY): once per explored model",
    **{("acausal2d/result.py", "acausal2d." + m): "a result's figures, animation and MAT file "
       "only: a run that draws nothing does not load the visual layer (its import took 0.03-0.1 "
       "s of the first run of a process)" for m in ("visual.plotting", "visual.scene",
                                                   "visual.animation", "visual.notebook",
                                                   "io.dymola_mat")},
    ("library/belt/placement.py", "acausal2d.library"):
        "the linkage imports planar, which imports the belts: a module-level import is a cycle",
}
"""(file, imported module) -> reason, for the sites no rule above covers."""


def local_imports():
    """[(file, line, importing module, imported module, optional)] of every
    import inside a function in acausal2d/ and library/."""
    paths = [p for p in (ROOT / "acausal2d").rglob("*.py") if "library" not in
             p.relative_to(ROOT / "acausal2d").parts[:1]] + list((ROOT / "library").rglob("*.py"))
    found = []
    for path in sorted(paths):
        module, is_package = _module_name(path)
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for fn in ast.walk(tree):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                found += _in_function(fn, path, module, is_package)
    return sorted(set(found))


def _in_function(fn, path, module, is_package):
    optional = {id(n) for t in ast.walk(fn) if isinstance(t, ast.Try) and any(
        h.type is None or "ImportError" in ast.unparse(h.type) for h in t.handlers)
        for n in ast.walk(t)}
    return [(str(path.relative_to(ROOT)), node.lineno, module, target, id(node) in optional)
            for node in ast.walk(fn) if isinstance(node, (ast.Import, ast.ImportFrom))
            for target in _targets(node, module, is_package)]


def started_modules():
    """The modules loaded by ``import acausal2d`` and ``acausal2d --help``."""
    code = ("import contextlib, io, json, sys\nsys.argv = ['acausal2d', '--help']\n"
            "import acausal2d, acausal2d.cli\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    try:\n        acausal2d.cli.main()\n    except SystemExit:\n        pass\n"
            "print(json.dumps(sorted(sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout
    return set(json.loads(out.strip().splitlines()[-1]))


def _reason(site, started):
    path, _, module, target, optional = site
    top = target.split(".")[0]
    if optional:
        return "optional"
    if top != "acausal2d":
        return COSTLY.get(top)
    if module in started and target not in started:
        return "start cost"
    return SITES.get((path, target)) or SITES.get((path, ".".join(target.split(".")[:2])))


def test_every_function_local_import_has_a_reason():
    started = started_modules()
    unexplained = [s[:4] for s in local_imports() if _reason(s, started) is None]
    assert unexplained == []


def test_the_rule_sees_a_local_import():
    module, _ = _module_name(ROOT / "acausal2d" / "analysis" / "check.py")
    tree = ast.parse("def f():\n    import json\n    try:\n        import pandas\n"
                     "    except ImportError:\n        pass\n")
    sites = _in_function(tree.body[0], ROOT / "acausal2d" / "analysis" / "check.py",
                         module, False)
    assert [(s[3], s[4]) for s in sites] == [("json", False), ("pandas", True)]
    assert _reason(sites[0], set()) is None and _reason(sites[1], set()) == "optional"


def test_the_allow_lists_name_no_site_that_is_gone():
    sites = {(s[0], ".".join(s[3].split(".")[:n])) for s in local_imports() for n in (2, 3)}
    assert [key for key in SITES if key not in sites] == []
