"""Issue 18, Seen 2: CI runs what a user on a fresh machine runs -- the
README's test command (the last line of .ci/run is that command, checked
here against README.md) inside a new virtual environment in a temporary
folder."""
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


def readme_commands():
    """Indented command lines of the README's Quick start section."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    section = text.split("## Quick start", 1)[1].split("\n## ", 1)[0]
    return [line[4:] for line in section.splitlines()
            if line.startswith("    ") and not line.startswith("     ")]


def ci_command():
    """The command line .ci/run runs (its last line)."""
    return (ROOT / ".ci" / "run").read_text(encoding="utf-8").rstrip("\n").splitlines()[-1]


def test_seen_2_ci_command_is_the_readme_test_command():
    out = ci_command()
    assert out == readme_commands()[1]
    assert "python -m pytest" in out and "chromium" in out


@pytest.mark.skipif(shutil.which("python3.11") is None, reason="needs python3.11 for the venv")
def test_seen_2_ci_runs_in_a_fresh_environment(tmp_path):
    """.ci/run with its command replaced by one that prints the
    interpreter's prefix: it is a new venv in a temporary folder, not the
    Python that runs the tests, and the folder is gone afterwards."""
    (tmp_path / ".ci").mkdir()
    text = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    probe = "python -c \"import sys; print('PREFIX', sys.prefix, sys.base_prefix != sys.prefix)\""
    script = tmp_path / ".ci" / "run"
    assert "python -m sphinx" not in text    # the site is built by the suite (test_site_build.py)
    script.write_text(text.replace(ci_command(), probe), encoding="utf-8")
    script.chmod(0o755)
    env = dict(os.environ, ACAUSAL2D_CI_FLOORS="0")     # the floors step: tests/test_floors.py
    run = subprocess.run([str(script)], capture_output=True, text=True, timeout=300, env=env)
    assert run.returncode == 0, run.stderr
    line = [s for s in run.stdout.splitlines() if s.startswith("PREFIX")][0]
    _, prefix, in_venv = line.split()
    assert in_venv == "True" and pathlib.Path(prefix).name == "venv"
    assert pathlib.Path(prefix).resolve() != pathlib.Path(sys.prefix).resolve()
    assert not pathlib.Path(prefix).exists()                 # removed on exit
