"""Issue 31: every subcommand's ``--help`` ends with one example, and every
example works: run in order (the compare example reads what the simulate
example wrote) in a plain clone of the repository."""
import os
import shlex
import signal
import subprocess
import sys
import time

import pytest

from acausal2d.cli import build_parser
from acausal2d.cli.examples import EXAMPLES
from test_plain_clone import make_clone


def subcommands():
    parser = build_parser()
    sub = next(a for a in parser._actions if hasattr(a, "choices") and a.choices)
    return sorted(sub.choices)


def test_every_subcommand_help_ends_with_its_example():
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    assert set(subcommands()) == set(EXAMPLES)
    for name in subcommands():
        proc = subprocess.run([exe, name, "--help"], capture_output=True, text=True, timeout=120)
        assert proc.returncode == 0, proc.stderr
        lines = proc.stdout.rstrip("\n").splitlines()
        assert lines[-2:] == ["example:", "  " + EXAMPLES[name]], (name, lines[-3:])
        assert shlex.split(EXAMPLES[name])[:2] == ["acausal2d", name]


SERVERS = {"explore"}
"""Commands that serve until interrupted: run until they print their address."""


def _serve_then_interrupt(argv, cwd, limit=300.0):
    """Start a server command, wait for its ``http://`` line, send Ctrl-C:
    (exit code, what it said)."""
    proc = subprocess.Popen(argv, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    said, t0 = [], time.monotonic()
    try:
        for line in proc.stdout:
            said.append(line)
            if "http://" in line or time.monotonic() - t0 > limit:
                break
        proc.send_signal(signal.SIGINT)
        rest, _ = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return proc.returncode, "".join(said) + (rest or "")


@pytest.mark.slow
def test_every_help_example_runs_in_a_plain_clone(tmp_path):
    repo = make_clone(tmp_path)
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    for name, command in EXAMPLES.items():
        if name in SERVERS:
            code, said = _serve_then_interrupt([exe] + shlex.split(command)[1:], repo)
        else:
            proc = subprocess.run([exe] + shlex.split(command)[1:], cwd=repo,
                                  capture_output=True, text=True, timeout=900)
            code, said = proc.returncode, proc.stdout + proc.stderr
        assert code == 0 and "Traceback" not in said, (command, said)
    assert (repo / "out" / "pendulum" / "result.mat").exists()
    assert (repo / "out" / "Pendulum.fmu").exists()
