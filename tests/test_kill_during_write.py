"""A ``simulate`` killed while it writes a large result never leaves a
``result.csv`` that looks complete: the file is written to a temporary name
in the run's temporary sibling folder and moved in when the run is whole,
the previous run's files are removed when a run starts, and the temporary
folder of a killed run is removed by the next run (SIGINT: by the run
itself, which exits 130)."""
import glob
import os
import signal
import subprocess
import sys
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
PENDULUM = os.path.join(HERE, os.pardir, "models", "pendulum.py")
INTERVALS = 60000          # a 39 MB result.csv: about 2 s of writing


def _simulate(out, intervals):
    return subprocess.Popen([sys.executable, "-m", "acausal2d", "simulate", PENDULUM,
                             "--intervals", str(intervals), "--out", str(out)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _temporary_csv(out):
    """The CSV being written: in the run's temporary sibling folder
    (acausal2d.io.output.OutputFolder), or a killed older run's in ``out``."""
    out = str(out)
    parts = os.path.join(os.path.dirname(out), "." + os.path.basename(out) + ".*.part")
    return glob.glob(os.path.join(out, ".result.*.tmp.csv")) + \
        glob.glob(os.path.join(parts, ".result.*.tmp.csv"))


def _kill_while_writing(out, sig, delay):
    """Start a run, wait until its CSV is being written, send ``sig`` after
    ``delay`` seconds; returns (exit code, stderr)."""
    proc = _simulate(out, INTERVALS)
    deadline = time.monotonic() + 60.0
    while not _temporary_csv(out):
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "the run never started writing its CSV"
        time.sleep(0.005)
    time.sleep(delay)
    proc.send_signal(sig)
    _, err = proc.communicate(timeout=60)
    return proc.returncode, err


def _rows(path):
    with open(path) as fh:
        return sum(1 for _ in fh) - 1


@pytest.mark.parametrize("sig, delay", [(signal.SIGKILL, 0.0), (signal.SIGKILL, 0.8),
                                        (signal.SIGINT, 0.0), (signal.SIGINT, 0.8)])
def test_a_killed_run_leaves_no_result_that_looks_complete(sig, delay, tmp_path):
    out = tmp_path / "out"
    first = _simulate(out, 20)
    assert first.wait(timeout=60) == 0 and _rows(out / "result.csv") == 21
    code, err = _kill_while_writing(out, sig, delay)
    if code == 0:                           # the signal came after the rename: a whole file
        assert _rows(out / "result.csv") == INTERVALS + 1
        return
    assert code == (-signal.SIGKILL if sig == signal.SIGKILL else 130), err
    # neither the killed run's half file nor the previous run's 21 rows under the name
    assert not (out / "result.csv").exists()
    if sig == signal.SIGINT:
        assert "Traceback" not in err and "interrupted" in err
        assert not _temporary_csv(out)     # the run cleaned up after itself
    third = _simulate(out, 20)
    assert third.wait(timeout=60) == 0 and _rows(out / "result.csv") == 21
    assert not _temporary_csv(out)         # a SIGKILL's leftover is gone too
