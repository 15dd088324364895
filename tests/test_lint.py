"""The code passes the project's linter and type checker (issue 34): ruff
with the rules of pyproject.toml ([tool.ruff]) over the package and the
library, and mypy as [tool.mypy] configures it."""
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_ruff_passes_on_the_package_and_the_library():
    exe = shutil.which("ruff", path=str(pathlib.Path(sys.executable).parent)) or shutil.which("ruff")
    assert exe, "ruff is in the test extra: pip install -e '.[test]'"
    proc = subprocess.run([exe, "check", "acausal2d", "library"], cwd=ROOT, capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr


def test_mypy_passes_on_the_package():
    proc = subprocess.run([sys.executable, "-m", "mypy"], cwd=ROOT, capture_output=True,
                          text=True, timeout=900)
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-2000:]
    assert "Success: no issues found" in proc.stdout


STRICT_FLAGS = ("disallow_untyped_defs", "disallow_incomplete_defs", "disallow_untyped_calls",
                "disallow_any_generics", "check_untyped_defs", "warn_return_any")
PUBLIC_MODULES = ("acausal2d", "acausal2d.options", "acausal2d.arguments", "acausal2d.progress",
                  "acausal2d.threads", "acausal2d.compiled", "acausal2d.result")


def test_the_public_modules_are_type_checked_strictly():
    """pyproject.toml's [[tool.mypy.overrides]] holds mypy's strict flags for
    the public modules (test_mypy_passes_on_the_package runs them)."""
    import tomllib
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    overrides = config["tool"]["mypy"]["overrides"]
    strict = [o for o in overrides if all(o.get(flag) is True for flag in STRICT_FLAGS)]
    covered = {m for o in strict for m in ([o["module"]] if isinstance(o["module"], str)
                                           else o["module"])}
    assert set(PUBLIC_MODULES) <= covered, covered


def test_the_public_functions_and_run_options_are_fully_annotated():
    """Every function of acausal2d.__all__ written in acausal2d (casadi's
    symbolic functions are casadi's) and RunOptions' fields and methods
    carry annotations on every parameter and their return."""
    import dataclasses
    import inspect
    import acausal2d
    functions = [getattr(acausal2d, n) for n in acausal2d.__all__]
    functions = [f for f in functions if inspect.isfunction(f)
                 and f.__module__.startswith("acausal2d")]
    functions += [f for _, f in inspect.getmembers(acausal2d.RunOptions, inspect.isfunction)
                  if not f.__name__.startswith("__") or f.__name__ == "__post_init__"]
    assert len(functions) >= 15
    bare = []
    for f in functions:
        sig = inspect.signature(f)
        names = [p.name for p in sig.parameters.values() if p.name not in ("self", "cls")
                 and p.annotation is inspect.Parameter.empty]
        if names or sig.return_annotation is inspect.Signature.empty:
            bare.append("%s.%s: %s" % (f.__module__, f.__qualname__, names or "return"))
    assert not bare, bare
    assert all(f.type is not None for f in dataclasses.fields(acausal2d.RunOptions))


def test_compiled_model_and_result_are_fully_annotated():
    """Every method and property of CompiledModel and Result (theirs, not
    object's) carries annotations on every parameter and its return, and
    their modules' functions too (mypy strict checks the same statically)."""
    import inspect
    from acausal2d import compiled, result
    members = []
    for cls in (compiled.CompiledModel, result.Result):
        for name, value in vars(cls).items():
            if isinstance(value, property):
                members.append(value.fget)
            elif inspect.isfunction(value):
                members.append(value)
    members += [f for module in (compiled, result) for f in vars(module).values()
                if inspect.isfunction(f) and f.__module__ == module.__name__]
    assert len(members) >= 40
    bare = []
    for f in members:
        sig = inspect.signature(f)
        names = [p.name for p in sig.parameters.values() if p.name not in ("self", "cls")
                 and p.annotation is inspect.Parameter.empty]
        if names or sig.return_annotation is inspect.Signature.empty:
            bare.append("%s: %s" % (f.__qualname__, names or "return"))
    assert not bare, bare
