"""The native engine's rules (acausal2d.runtime.tiers): a run whose
structure has a library in the cache uses it; one that has none runs on the
driver on CasADi's C API (acausal2d.runtime.capi; nothing of the structure
is compiled or waited for during it, its IDA takes the steps of the Python
path) and a detached worker compiles the library after the run, where a
later run finds it.  The engine is a field
of the run's options; two processes compiling one structure at once publish
one library; a failed background compile is said once and the run stays on
the Python path; and the answer does not depend on the engine (per model,
to the integration tolerance, with the same events)."""
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.options import RunOptionError
from acausal2d.runtime import background, capi, cbuild, cstore, native, notices, tiers
from tiers_support import NEEDS_NATIVE, WAIT, fresh_cache, native_runs
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
    yield folder
    assert background.wait(WAIT)


def _run(model, stop_time=0.5, rtol=1e-8, **options):
    cm = acausal2d.compile_model(model)
    res = cm.simulate(stop_time=stop_time, rtol=rtol, intervals=200, **options)
    form = next(iter(cm.system._formulations.values()))
    return res, form


def _libraries(folder):
    return sorted(f for f in os.listdir(folder) if f.startswith("a2d_model") and f.endswith(".so"))


def test_a_run_before_the_library_exists_runs_on_the_c_api_driver(auto, capfd, monkeypatch):
    workers = []             # workers of this process at each step of the run
    drivers_run = native_runs(monkeypatch)

    def progress(t, t_end):
        workers.append(len(background._workers))
    res, form = _run(PistonEngine(), progress=progress)
    assert drivers_run and all(lib is capi.driver() for lib in drivers_run)
    assert len(workers) > 2 and max(workers[:-1]) == 0     # none during the run (the last
    #                                                        call: after it, at its end)
    err = capfd.readouterr().err
    assert err.count("compiling native code for PistonEngine in the background") == 1
    assert len(background._workers) == 1                   # launched after it
    assert background.wait(WAIT) and not background.pending()
    assert len(_libraries(auto)) == 1                      # published by the worker
    again, form2 = _run(PistonEngine())                   # a later run finds it
    assert native.library(form2) is not None
    assert "in the background" not in capfd.readouterr().err
    ref, _ = _run(PistonEngine(), native="off")
    # the first run's IDA on the C API: the steps of the Python path (the same dense LU)
    assert res.stats["steps"] == ref.stats["steps"]
    assert res.stats["segments"] == ref.stats["segments"]
    _agree(res, ref, ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"), 1e-8)
    _agree(again, ref, ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"), 1e-8)


def test_the_engine_is_chosen_per_run(auto, monkeypatch):
    """``native`` of the run's options over ``$ACAUSAL2D_NATIVE`` (auto
    here), run by run in one process: ``now`` compiles first and runs
    natively, ``off`` then runs on the Python path with the library there."""
    calls = native_runs(monkeypatch)
    fast, form = _run(Pendulum(), native="now")
    assert calls and native.library(form, "now") is not None
    assert fast.stats["native_compile_time"] > 0.0
    del calls[:]
    slow, form2 = _run(Pendulum(), native="off")
    assert calls == [] and native.library(form2, "off") is None
    _agree(fast, slow, ("revolute.phi", "revolute.w"), 1e-8)
    with pytest.raises(RunOptionError, match="native"):
        acausal2d.RunOptions(native="sometimes")


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
    assert background.wait(WAIT)
    marker = [f for f in os.listdir(auto) if f.endswith(".failed")]
    assert marker, os.listdir(auto)
    assert "failed (exit 1)" in (auto / marker[0]).read_text()
    capfd.readouterr()
    monkeypatch.setattr(notices, "_said", set())          # as in a new process
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


def test_a_compile_first_that_fails_keeps_the_python_path(auto, capfd, monkeypatch):
    monkeypatch.setenv("CC", "/bin/false")
    res, form = _run(Pendulum(), native="now")
    assert native.library(form, "now") is None
    assert "Traceback" not in capfd.readouterr().err
    ref, _ = _run(Pendulum(), native="off")
    _agree(res, ref, ("revolute.phi", "revolute.w"), 1e-8)


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
