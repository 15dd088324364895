"""Tiered execution (issue 30, acausal2d.runtime.tiers): a run whose
structure has no library starts on the Python path while a background
worker compiles it; a library that appears during a run is taken up; two
processes compiling one structure at once publish one library; a failed
background compile is said once and the run stays on the Python path; and
the answer does not depend on the tier (per model, to the integration
tolerance, with the same events)."""
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import background, cbuild, cstore, native, tiers
from tiers_support import NEEDS_NATIVE, WAIT, fresh_cache
from tiers_support import agree as _agree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "models"))
from piston_engine import PistonEngine  # noqa: E402
from pendulum import Pendulum  # noqa: E402

pytestmark = NEEDS_NATIVE


@pytest.fixture
def auto(tmp_path, monkeypatch):
    """Mode auto with an empty cache of its own and this process's queue."""
    folder = fresh_cache(tmp_path, monkeypatch)
    monkeypatch.setattr(tiers, "FOREGROUND_BELOW", 0.0)   # no library is small enough to wait
    yield folder
    background.wait(lambda: False, WAIT)


def _run(model, stop_time=0.5, rtol=1e-8):
    cm = acausal2d.compile_model(model)
    res = cm.simulate(stop_time=stop_time, rtol=rtol, intervals=200)
    form = next(iter(cm.system._formulations.values()))
    return res, form


def _libraries(folder):
    return sorted(f for f in os.listdir(folder) if f.startswith("a2d_model") and f.endswith(".so"))


def test_a_run_before_the_library_exists_takes_the_python_path(auto, capfd, monkeypatch):
    res, form = _run(PistonEngine())
    err = capfd.readouterr().err
    assert err.count("compiling native code for PistonEngine in the background") == 1
    assert background.wait(lambda: False, WAIT) is False and not background.pending()
    assert len(_libraries(auto)) == 1                      # published by the worker
    again, form2 = _run(PistonEngine())                   # a later run finds it
    assert native.library(form2) is not None
    assert "in the background" not in capfd.readouterr().err
    monkeypatch.setenv(tiers.ENV, "off")
    ref, _ = _run(PistonEngine())
    _agree(res, ref, ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"), 1e-8)
    _agree(again, ref, ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"), 1e-8)


def test_a_library_that_appears_during_a_run_is_taken_up(auto, monkeypatch):
    def wait_for_it(self, t, t_left, now, ready):      # as if the run were long
        self.decided = True
        background.release()                            # held since its launch: it goes on
        assert background.wait(ready, WAIT)
        self.notes.append("waited")
    monkeypatch.setattr(background.Tiering, "decide", wait_for_it)
    res, form = _run(Pendulum(), stop_time=3.0)
    assert any(n.startswith("native loop from t=") for n in res.native_notes), res.native_notes
    t_switch = float([n for n in res.native_notes if n.startswith("native")][0].split("t=")[1]
                     .split()[0])
    first = 3.0 / background.CHUNKS                        # the first checkpoint: its output time
    assert first - 1e-9 <= t_switch <= first + 3.0 / 200 + 1e-9, t_switch
    monkeypatch.setenv(tiers.ENV, "off")
    ref, _ = _run(Pendulum(), stop_time=3.0)
    _agree(res, ref, ("revolute.phi", "revolute.w"), 1e-8)


def test_two_processes_compiling_one_structure_publish_one_library(tmp_path):
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=str(tmp_path / "cache"))
    model = os.path.join(ROOT, "models", "pendulum.py")
    procs = [subprocess.Popen([sys.executable, "-m", "acausal2d", "simulate", model, "--native",
                               "now", "--out", str(tmp_path / ("out%d" % k))], env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for k in range(2)]
    results = [p.communicate(timeout=WAIT) for p in procs]
    assert [p.returncode for p in procs] == [0, 0], results
    assert all("Traceback" not in err for _, err in results)
    assert len(_libraries(tmp_path / "cache")) == 1
    assert not [f for f in os.listdir(tmp_path / "cache") if f.startswith(cstore.BUILD_PREFIX)]
    a, b = (np.loadtxt(tmp_path / ("out%d" % k) / "result.csv", delimiter=",", skiprows=1)
            for k in range(2))
    assert a.shape == b.shape
    assert np.max(np.abs(a - b)) <= 1e3 * 1e-6 * (1.0 + np.max(np.abs(b)))


def test_a_failed_background_compile_is_said_once_and_stays_on_python(auto, capfd,
                                                                     monkeypatch):
    monkeypatch.setenv("CC", "/bin/false")
    res, form = _run(PistonEngine())
    background.wait(lambda: False, WAIT)
    marker = [f for f in os.listdir(auto) if f.endswith(".failed")]
    assert marker, os.listdir(auto)
    assert "failed (exit 1)" in (auto / marker[0]).read_text()
    capfd.readouterr()
    monkeypatch.setattr(cstore, "_said", set())          # as in a new process
    for _ in range(2):
        again, form2 = _run(PistonEngine())
        assert native.library(form2) is None and not background.pending()
    err = capfd.readouterr().err
    assert err.count("compile of native code for PistonEngine failed") == 1, err
    assert "/bin/false" in err
    assert "in the background" not in err
    monkeypatch.setenv(tiers.ENV, "off")
    ref, _ = _run(PistonEngine())
    _agree(again, ref, ("revoluteDrive.phi", "prismatic.s"), 1e-8)


def test_a_small_library_is_compiled_first_and_a_failure_said_once(auto, capfd, monkeypatch):
    monkeypatch.setattr(tiers, "FOREGROUND_BELOW", 1e9)   # every library is small
    res, form = _run(Pendulum())
    assert native.library(form) is not None                # in this run, not in the background
    assert any(n.startswith("compile first: a2d_model is small") for n in res.native_notes)
    err = capfd.readouterr().err
    assert "before the run" not in err
    monkeypatch.setenv(cbuild.CACHE_ENV, str(auto) + "-2")
    monkeypatch.setenv("CC", "/bin/false")
    said = []
    for _ in range(3):              # the first fails (and may say so), each failure said once
        again, form2 = _run(Pendulum())
        background.wait(lambda: False, WAIT)               # the maps' library (not small)
        assert native.library(form2) is None
        said.append([line for line in capfd.readouterr().err.splitlines()
                     if "compile of native code for Pendulum failed" in line])
    lines = said[0] + said[1] + said[2]
    assert lines and len(set(lines)) == len(lines) and not said[2], said
    assert any(f.endswith(".failed") for f in os.listdir(str(auto) + "-2"))
    monkeypatch.setenv(tiers.ENV, "off")
    ref, _ = _run(Pendulum())
    _agree(res, ref, ("revolute.phi", "revolute.w"), 1e-8)
    _agree(again, ref, ("revolute.phi", "revolute.w"), 1e-8)


SEPARATED = 0.01     # s: events further apart than this are compared one by one
MODELS = [("pendulum.py", "Pendulum", ("revolute.phi", "revolute.w"), 2.0),
          ("piston_engine.py", "PistonEngine", ("revoluteDrive.phi", "prismatic.s"), 1.0),
          ("compressor.py", "Compressor", ("cyl.p",), 4.0)]
"""The compressor runs 4 s of its 16 s (the start-up, the valves' events of
the first cycles and the steady belt drive): its whole run on the Python path
at rtol 1e-7 took minutes of the suite, and the tiers share every equation
of the rest of it."""


@pytest.mark.parametrize("filename,cls,names,stop", MODELS, ids=[m[1] for m in MODELS])
def test_the_answer_does_not_depend_on_the_tier(filename, cls, names, stop, model_class,
                                                monkeypatch, tmp_path):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    runs = {}
    for mode in ("now", "off"):
        monkeypatch.setenv(tiers.ENV, mode)
        cm = acausal2d.compile_model(model_class(filename, cls)())
        runs[mode] = cm.simulate(stop_time=stop, rtol=1e-7)
    fast, slow = runs["now"], runs["off"]
    rtol, t = 1e-7, slow.time
    te = np.array([e[0] for e in slow.events])
    apart = len(te) < 2 or np.min(np.diff(te)) > SEPARATED
    if apart:                                          # events well separated: the same ones
        assert len(fast.events) == len(slow.events)
        assert np.max(np.abs(np.array([e[0] for e in fast.events]) - te), initial=0.0) <= \
            1e3 * rtol * max(1.0, t[-1])
    far = np.ones(len(t), dtype=bool)                  # rows away from any event
    for tk in te:
        far &= np.abs(t - tk) > SEPARATED
    for name in names:
        a = np.interp(t[far], fast.time, fast[name])
        scale = np.max(np.abs(slow[name])) + 1.0
        assert np.max(np.abs(a - slow[name][far])) <= 1e3 * rtol * scale, name
