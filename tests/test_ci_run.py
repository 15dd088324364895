"""Issue 18, Seen 2: CI runs what a user on a fresh machine runs -- the
README's test command, read from README.md, inside a new virtual
environment in a temporary folder."""
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


def test_seen_2_ci_command_is_the_readme_test_command():
    out = subprocess.run([str(ROOT / ".ci" / "run"), "--print-command"], capture_output=True,
                         text=True, check=True).stdout.strip()
    assert out == readme_commands()[1]
    assert "python -m pytest" in out and "chromium" in out


@pytest.mark.skipif(shutil.which("python3.11") is None, reason="needs python3.11 for the venv")
def test_seen_2_ci_runs_in_a_fresh_environment(tmp_path):
    """.ci/run copied next to a README whose test command prints the
    interpreter's prefix: it is a new venv in a temporary folder, not the
    Python that runs the tests, and the folder is gone afterwards."""
    (tmp_path / ".ci").mkdir()
    shutil.copy(ROOT / ".ci" / "run", tmp_path / ".ci" / "run")
    (tmp_path / "README.md").write_text(
        "# x\n\n## Quick start\n\n    echo first\n\n"
        "    python -c \"import sys; print('PREFIX', sys.prefix, sys.base_prefix != sys.prefix)\"\n"
        "\n## Next\n\n    echo not this\n", encoding="utf-8")
    run = subprocess.run([str(tmp_path / ".ci" / "run")], capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    line = [s for s in run.stdout.splitlines() if s.startswith("PREFIX")][0]
    _, prefix, in_venv = line.split()
    assert in_venv == "True" and pathlib.Path(prefix).name == "venv"
    assert pathlib.Path(prefix).resolve() != pathlib.Path(sys.prefix).resolve()
    assert not pathlib.Path(prefix).exists()                 # removed on exit
