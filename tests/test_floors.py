"""Issue 35, Seen 2: the dependency floors work.  pyproject.toml allowed
Python 3.10 and scikit-sundae 1.1, with which `acausal2d simulate` of the
event-heavy examples died with SIGSEGV.  The floors are raised (Python
3.11, scikit-sundae 1.2) and CI checks them: .ci/floors installs exactly the
lower bounds (tests/data/floors.txt as pip constraints) on the lowest
Python in a second fresh environment and runs those examples.  Checked
here: the constraints file pins every lower bound of pyproject.toml at that
version and nothing else, .ci/floors runs on the requires-python floor and
runs the examples, and .ci/run starts it before the README's test command
(beside it) and fails on its result."""
import pathlib
import re
import tomllib

from packaging.requirements import Requirement
from packaging.version import Version

ROOT = pathlib.Path(__file__).resolve().parents[1]
EXAMPLES = ("compressor", "pulley_block", "cable_crane")


def lower_bounds():
    """{name: Version} of each '>=' bound in pyproject.toml's dependencies
    and its test extra, with {extra: name} of the extras they pull in."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    bounds, extras = {}, {}
    texts = project["dependencies"] + project["optional-dependencies"]["test"]
    for text in list(texts):          # the test extra's own extras (acausal2d[explore])
        req = Requirement(text)
        if req.name == project["name"]:
            texts.remove(text)
            texts += [t for extra in req.extras for t in project["optional-dependencies"][extra]]
    for text in texts:
        req = Requirement(text)
        low = [Version(s.version) for s in req.specifier if s.operator == ">="]
        assert len(low) == 1, "%s: one '>=' lower bound expected" % text
        bounds[req.name] = low[0]
        extras.update({extra: req.name for extra in req.extras})
    return bounds, extras, project["requires-python"]


def pins():
    """{name: Version} of tests/data/floors.txt's 'name==version' lines."""
    out = {}
    for line in (ROOT / "tests" / "data" / "floors.txt").read_text(encoding="utf-8").splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            req = Requirement(line)
            (spec,) = req.specifier
            assert spec.operator == "==", line
            out[req.name] = Version(spec.version)
    return out


def test_seen_2_floors_pin_every_lower_bound():
    bounds, extras, _ = lower_bounds()
    pinned = pins()
    for name, version in bounds.items():
        assert pinned.get(name) == version, "floors.txt: %s==%s expected" % (name, version)
    # an extra (dask[distributed]) is pinned with the package that names it
    for extra, owner in extras.items():
        assert pinned.get(extra) == bounds[owner], extra
    assert set(pinned) == set(bounds) | set(extras)


def test_seen_2_scikit_sundae_floor_is_above_the_crashing_releases():
    bounds, _, python = lower_bounds()
    assert bounds["scikit-sundae"] >= Version("1.2")          # 1.1.0 .. 1.1.3 segfault
    assert python == ">=3.11"                                 # scikit-sundae 1.2 needs 3.11


def test_seen_2_ci_floors_step_uses_the_lowest_python_and_runs_the_examples():
    _, _, python = lower_bounds()
    script = (ROOT / ".ci" / "floors").read_text(encoding="utf-8")
    floor = re.search(r"^FLOOR_PYTHON=python(\S+)", script, re.M).group(1)
    assert Version(floor) == Version(python.removeprefix(">="))
    assert "-c tests/data/floors.txt" in script
    ran = re.findall(r"^(?:ACAUSAL2D_NATIVE=0 )?run (\w+)$", script, re.M)
    assert set(ran) == set(EXAMPLES) and "ACAUSAL2D_NATIVE=0 run" in script
    for name in EXAMPLES:
        assert (ROOT / "models" / (name + ".py")).is_file()


def test_seen_2_ci_run_calls_the_floors_step_before_the_test_command():
    lines = (ROOT / ".ci" / "run").read_text(encoding="utf-8").rstrip("\n").splitlines()
    calls = [k for k, line in enumerate(lines) if "bash .ci/floors" in line]
    assert len(calls) == 1 and calls[0] < len(lines) - 1
    assert not lines[calls[0]].lstrip().startswith("#")
