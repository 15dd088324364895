"""Signal fuzz of the output transaction (issue 35): ``acausal2d simulate``
processes write into one ``--out``; SIGINT arrives at a random point of the
output phase (after the run's temporary folder received its first file;
a random fraction, up to 1.2, of the phase's length measured in the
same test) of one of them, and a second run may start into the same folder meanwhile.

Whatever the timing: nothing crashes (no traceback, no death by the
signal; exit codes 0, 2 with the lock's message, or 130), nothing wrong is
reported as success (exit 0 only with the complete, listed files), nothing
partial remains (the folder holds either one run's complete files with
their manifest or nothing of any run, and no temporary folder or lock), and
no file of the earlier run survives a failing run.  (An interrupt that
comes after the files were moved in, while the summary is printed, exits
130 with the run's complete files in place.)"""
import csv
import glob
import json
import os
import signal
import subprocess
import sys
import time

import pytest

from acausal2d.io.files import MANIFEST
from acausal2d.io.output import LOCK_SUFFIX, PART_SUFFIX
from fuzz_cases_tx import signal_plans

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir)
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
INTERVALS = 1000          # half a MB of CSV and animation
EXPECTED = {"result.csv", "animation.html", "diagram.svg", "body.phi.png", "revolute.w.png"}


def _start(out):
    return subprocess.Popen([sys.executable, "-m", "acausal2d", "simulate", PENDULUM,
                             "--intervals", str(INTERVALS), "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _parts(out):
    return glob.glob(os.path.join(os.path.dirname(out), "." + os.path.basename(out) + ".*"
                                  + PART_SUFFIX))


def _wait_for_output_phase(proc, out, timeout=120.0):
    """Until a temporary folder of ``out`` holds a file (or the run ended)."""
    deadline = time.monotonic() + timeout
    while proc.poll() is None and time.monotonic() < deadline:
        if any(os.listdir(p) for p in _parts(out) if os.path.isdir(p)):
            return
        time.sleep(0.002)


def _state(out):
    """'complete' (one run's files, all listed and whole) or 'empty'."""
    names = set(os.listdir(out))
    leftovers = [n for n in os.listdir(os.path.dirname(out))
                 if n.startswith("." + os.path.basename(out) + ".")]
    assert not leftovers, leftovers
    if not names:
        return "empty"
    with open(os.path.join(out, MANIFEST), encoding="utf-8") as fh:
        listed = set(json.load(fh)["files"])
    assert names == listed | {MANIFEST} and listed == EXPECTED, names
    with open(os.path.join(out, "result.csv"), newline="") as fh:
        rows = list(csv.reader(fh))
    assert len(rows) == INTERVALS + 2 and all(len(r) == len(rows[0]) for r in rows)
    assert abs(float(rows[-1][0]) - 3.0) < 1e-9          # the pendulum's stop time, whole
    return "complete"


def _outcome(proc):
    out, err = proc.communicate(timeout=300)
    assert "Traceback" not in err and "Exception ignored" not in err, err
    code = proc.returncode
    assert code in (0, 2, 130), (code, err)
    if code == 2:
        assert "is being written by process" in err, err
    if code == 130:
        assert err.strip().endswith("interrupted"), err
    return code


@pytest.mark.parametrize("plan", signal_plans(), ids=lambda p: "sigint-at-%g%s" % (
    p[0], "-second+%gs" % p[2] if p[1] else ""))
def test_sigint_and_a_second_run_never_leave_partial_or_stale_files(plan, tmp_path):
    fraction, second, second_delay = plan
    out = str(tmp_path / "out")
    first = _start(out)
    _wait_for_output_phase(first, out)
    began = time.monotonic()
    assert _outcome(first) == 0 and _state(out) == "complete"
    phase = time.monotonic() - began        # this machine's output phase, measured
    proc = _start(out)
    other = None
    if second:
        time.sleep(second_delay)
        other = _start(out)
    _wait_for_output_phase(proc, out)
    time.sleep(fraction * phase)
    if proc.poll() is None:
        proc.send_signal(signal.SIGINT)
    codes = [_outcome(proc)] + ([_outcome(other)] if other is not None else [])
    state = _state(out)                     # 'complete' or 'empty', never partial
    if 0 in codes:                          # success only with the whole run in place
        assert state == "complete", (codes, state)
    assert not os.path.exists(os.path.join(os.path.dirname(out),
                                           "." + os.path.basename(out) + LOCK_SUFFIX))
