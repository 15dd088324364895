"""Figures drawn by a forked child (acausal2d.visual.figure_process): the same
files as drawn in-process, errors handed back, nothing left running, and the
simulate command's own process never imports matplotlib."""
import os
import subprocess
import sys
import time

import numpy as np
import pytest

from acausal2d.errors import Acausal2dError
from acausal2d.visual import plotting
from acausal2d.visual.figure_process import FigureProcess
from conftest import assert_copied

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this platform")
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _plan(k):
    t = np.linspace(0.0, 2.0, 201)
    return {"x": t, "xlabel": "time [s]", "title": "Test %d" % k,
            "axes": [("q [m]", [("a.q", np.sin(3 * t + k)), ("b.q", np.cos(t))]),
                     ("F [N]", [("a.F", t ** 2)])]}


def _started():
    drawer = FigureProcess.start()
    if drawer is None:
        pytest.skip("threads are running in this test process: figures are drawn in-process")
    return drawer


def test_child_writes_the_files_the_process_itself_writes(tmp_path):
    import matplotlib.image as mpimg
    jobs = [(str(tmp_path / ("child%d.png" % k)), _plan(k)) for k in range(2)]
    mine = [(str(tmp_path / ("here%d.png" % k)), _plan(k)) for k in range(2)]
    drawer = _started()
    try:
        drawer.submit(jobs)
        paths = drawer.collect()
    finally:
        drawer.close()
    assert paths == [p for p, _ in jobs]
    for (a, _), b in zip(jobs, plotting.draw_jobs(mine)):
        pa, pb = mpimg.imread(a), mpimg.imread(b)
        assert pa.shape == pb.shape
        assert_copied(pa, pb)                  # the same drawing, deterministic


def test_a_drawing_error_is_raised_in_the_caller(tmp_path):
    drawer = _started()
    try:
        plan = _plan(0)
        plan["axes"][1][1][0] = ("a.F", np.zeros(7))          # 7 values for 201 times
        drawer.submit([(str(tmp_path / "x.png"), plan)])
        with pytest.raises(Acausal2dError, match="drawing the figures failed: ValueError: x and "
                                                 "y must have same first dimension"):
            drawer.collect()
    finally:
        drawer.close()


class _SlowImport:
    """A finder that makes importing matplotlib's Agg backend take 5 s (the
    child is a fork of this process, so it inherits the finder)."""

    def find_spec(self, name, path=None, target=None):
        if name == "matplotlib.backends.backend_agg":
            time.sleep(5.0)
        return None


def test_an_unused_child_is_interrupted_not_waited_for():
    agg = sys.modules.pop("matplotlib.backends.backend_agg", None)   # the child imports it
    sys.meta_path.insert(0, _SlowImport())
    try:
        drawer = _started()
    finally:
        del sys.meta_path[0]
        if agg is not None:
            sys.modules["matplotlib.backends.backend_agg"] = agg
    time.sleep(0.05)                                # the child is importing now
    t = time.perf_counter()
    drawer.close()                                  # SIGINT: its import is cut short
    assert time.perf_counter() - t < 2.0            # (waiting would take the 5 s)
    with pytest.raises(ChildProcessError):
        os.waitpid(drawer.pid, os.WNOHANG)          # reaped: no zombie left


def test_a_child_closed_at_once_never_runs_the_callers_code(tmp_path):
    marker = tmp_path / "after_start"
    for _ in range(20):                             # close right after the fork, repeatedly
        drawer = _started()
        drawer.close()
        with open(marker, "a") as fh:               # only this process may get here
            fh.write("%d\n" % os.getpid())
    assert set(marker.read_text().split()) == {str(os.getpid())}


def test_simulate_command_draws_without_importing_matplotlib(tmp_path):
    code = ("import sys; from acausal2d.cli import main; "
            "rc = main(['simulate', %r, '--out', %r]); "
            "print('MPL', 'matplotlib' in sys.modules); sys.exit(rc)"
            % (os.path.join(ROOT, "models", "pendulum.py"), str(tmp_path)))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert "MPL False" in proc.stdout
    for name in ("body.phi.png", "revolute.w.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
