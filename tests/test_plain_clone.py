"""A clone of the repository alone - no ``../shared`` beside it - runs the
README's workflow commands (simulate, then compare against the reference
shipped in tests/data/references) and the reference tests, with nothing
skipped.  The clone is a copy of the repository's files (tracked and new,
not ignored) in a temporary folder that has no ``shared`` sibling."""
import os
import re
import shlex
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def repository_files():
    out = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout
    return [f for f in out.splitlines() if os.path.isfile(os.path.join(ROOT, f))]


def make_clone(base):
    repo = base / "repo"
    for rel in repository_files():
        dest = repo / rel
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(os.path.join(ROOT, rel), dest)
    assert not (base / "shared").exists()
    return repo


WORKFLOW_PAGE = os.path.join(ROOT, "docs", "user-guide", "workflow.md")
"""The user guide's "Simulate, check and compare" page (the README's
"Workflow" section until issue 31)."""


def readme_commands():
    """The ``$ acausal2d simulate|compare ...`` lines of the workflow block
    (the first code block of :data:`WORKFLOW_PAGE`; every other command of
    the README and the user guide runs in tests/test_readme_commands.py)."""
    with open(WORKFLOW_PAGE, encoding="utf-8") as fh:
        text = fh.read()
    block = text.split("```", 2)[1]
    return [shlex.split(m) for m in re.findall(r"^\$ (acausal2d (?:simulate|compare) .*)$",
                                               block, re.M)]


def test_readme_workflow_and_reference_tests_in_a_plain_clone(tmp_path):
    repo = make_clone(tmp_path)
    env = dict(os.environ, PATH=os.path.dirname(sys.executable) + os.pathsep
               + os.environ.get("PATH", ""))
    commands = readme_commands()
    assert [c[1] for c in commands] == ["simulate", "compare"], commands
    assert commands[1][3] == "tests/data/references/PistonEngine.csv"
    for cmd in commands:
        exe = os.path.join(os.path.dirname(sys.executable), cmd[0])
        proc = subprocess.run([exe] + cmd[1:], cwd=repo, env=env, capture_output=True,
                              text=True, timeout=300)
        assert proc.returncode == 0, (cmd, proc.stdout, proc.stderr)
    assert "2 of 2 signals passed" in proc.stdout
    tests = subprocess.run(
        [sys.executable, "-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider",
         "tests/test_references.py", "tests/test_cli.py::test_compare_passes_against_shared_reference"],
        cwd=repo, env=env, capture_output=True, text=True, timeout=600)
    assert tests.returncode == 0, tests.stdout + tests.stderr
    summary = tests.stdout.strip().splitlines()[-1]
    assert re.match(r"8 passed in ", summary), summary
    assert "skipped" not in tests.stdout
