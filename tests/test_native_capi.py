"""The driver on CasADi's C API (acausal2d.runtime.capi): IDA's native loop and
the C projector evaluating a formulation's own CasADi functions through
``casadi_c_eval_id`` of the wheel's libcasadi, built once per machine with no
library linked.  Over the piston engine's run it reaches the stop time with
the rows of the per-model compiled library to the integration tolerance; a
new structure runs on it from its first run (mode auto, the library compiled
after the run), also where no compiler is on PATH (the driver installed with
the package); its projector's rows satisfy every equation; mode off never
uses it; and benchmarks/bench_capi.py prints its table (small mode), whose
ratios are the quotients of its times."""
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import background, capi, drivers, native, projection, tiers
from acausal2d.runtime.simulation import Simulation
from tiers_support import NEEDS_NATIVE, WAIT, agree, fresh_cache, native_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [os.path.join(ROOT, "models")]
from piston_engine import PistonEngine  # noqa: E402
from pendulum import Pendulum  # noqa: E402

pytestmark = NEEDS_NATIVE
RTOL = 1e-8
NAMES = ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s")


def test_the_c_api_driver_gives_the_rows_of_the_compiled_library(tmp_path, monkeypatch):
    monkeypatch.setenv("ACAUSAL2D_CACHE_DIR", str(tmp_path))
    monkeypatch.setenv(tiers.ENV, "now")
    cm = acausal2d.compile_model(PistonEngine())
    opts = cm.run_options(stop_time=1.0, intervals=200, rtol=RTOL)
    sim = Simulation(cm.system, cm.parameter_values(None), opts.times(), opts.rtol, opts.atol)
    sim.run()
    form, prob = sim._solver()[:2]
    atol = np.broadcast_to(sim.rtol * sim.system.nominal, (form.n,)).copy()
    y0, yp0 = form.y_from(sim.out[0][1])
    runs = []
    for make in (native.native_ida, capi.capi_ida):
        drv = make(prob, sim.rtol, atol)
        assert drv is not None, make.__name__
        flag, T, Y = drv.run(sim.times, y0, yp0)[:3]
        assert flag >= 0 and T[-1] >= sim.times[-1] * (1 - 1e-12)
        runs.append((T, Y))
    (T1, Y1), (T2, Y2) = runs
    assert T1.shape == T2.shape and np.max(np.abs(T1 - T2)) <= 1e-12 * T1[-1]
    scale = 1.0 + np.max(np.abs(Y1), axis=0)
    assert np.all(np.max(np.abs(Y1 - Y2), axis=0) <= 1e3 * RTOL * scale)


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The package's driver objects and C API driver as ``setup.py`` builds them."""
    folder = str(tmp_path_factory.mktemp("prebuilt"))
    built = drivers.install(folder, log=lambda text: None)
    assert os.path.basename(built[-1]) == drivers.capi_file()
    return folder


def _run(model, **options):
    return acausal2d.compile_model(model).simulate(stop_time=0.5, rtol=RTOL, intervals=200,
                                                   **options)


@pytest.mark.parametrize("compiler", [True, False], ids=["compiler", "no-compiler"])
def test_a_new_structure_runs_on_the_c_api_driver_from_its_first_run(
        compiler, installed, tmp_path, monkeypatch):
    """Mode auto, empty cache, the driver installed with the package: the
    first run is native (no compile during it: with no compiler on PATH,
    none could run), its rows projected in C; the worker after it compiles
    the structure's library only where a compiler is found."""
    cache = fresh_cache(tmp_path, monkeypatch)
    monkeypatch.setenv(drivers.ENV, "1")
    monkeypatch.setattr(drivers, "PREBUILT", installed)
    monkeypatch.setattr(capi, "_loaded", {})
    if not compiler:
        monkeypatch.setenv("PATH", str(tmp_path / "empty"))
        monkeypatch.delenv("CC", raising=False)
    projected = []
    real = projection.Projector.project
    monkeypatch.setattr(projection.Projector, "project", lambda self, *a, **kw: projected.append(
        self.native) or real(self, *a, **kw))
    calls = native_runs(monkeypatch)
    res = _run(PistonEngine())
    lib = capi.driver()
    assert lib is not None and calls and all(c is lib for c in calls)
    assert projected and all(p is not None for p in projected)
    assert not [f for f in os.listdir(cache) if f.endswith(".so")]     # nothing compiled
    assert background.wait(WAIT)
    assert bool([f for f in os.listdir(cache) if f.startswith("a2d_model")]) == compiler
    monkeypatch.setenv(tiers.ENV, "off")
    del calls[:]
    ref = _run(PistonEngine())
    assert calls == []                                       # off: the Python path only
    assert res.stats["steps"] == ref.stats["steps"]          # the same IDA, the same dense LU
    agree(res, ref, NAMES, RTOL)


def test_the_c_api_projector_satisfies_every_equation(installed, tmp_path, monkeypatch):
    """The rows the C API driver's projector returns solve E(t, z) = 0 to
    the projector's tolerance (projection.RES_TOL of each equation's scale)."""
    fresh_cache(tmp_path, monkeypatch)
    monkeypatch.setenv(drivers.ENV, "1")
    monkeypatch.setattr(drivers, "PREBUILT", installed)
    monkeypatch.setattr(capi, "_loaded", {})
    cm = acausal2d.compile_model(Pendulum())
    opts = cm.run_options(stop_time=1.0, intervals=50, rtol=1e-6)
    sim = Simulation(cm.system, cm.parameter_values(None), opts.times(), opts.rtol, opts.atol)
    sim.run()
    form = sim._solver()[0]
    proj = projection.Projector(cm.system, form, sim.p)
    assert proj.native is not None and capi.driver() is not None
    T = np.asarray(sim.times, float)
    Z = np.array([row for _, row in sim.out], dtype=float)[:len(T)]
    Z[:, proj.free] *= 1.0 + 1e-6                         # moved off the solution
    out = proj.project(T, Z, sim.d)
    E = np.array([np.asarray(cm.system.residual_fn(t, z, sim.p, sim.d)).ravel()
                  for t, z in zip(T, out)])
    J = [np.abs(np.asarray(cm.system.jacobian_fn(t, z, sim.p, sim.d))) for t, z in zip(T, out)]
    size = cm.system.nominal + np.abs(out)
    scale = np.array([j @ s for j, s in zip(J, size)])
    assert np.all(np.abs(E) <= 10 * projection.RES_TOL * scale)


def test_bench_capi_small_prints_its_table():
    out = subprocess.run([sys.executable, os.path.join(ROOT, "benchmarks", "bench_capi.py"),
                          "--small"], capture_output=True, text=True, timeout=900, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    lines = out.stdout.splitlines()
    assert lines[1].split() == ["model", "compiled", "C", "API", "ratio"]
    rows = {" ".join(line.split()[:-3]): line.split()[-3:] for line in lines[2:]}
    assert set(rows) == {"piston engine", "chain of 20 links", "belt drive"}
    for name, (a, b, ratio) in rows.items():
        a, b, ratio = float(a), float(b), float(ratio)
        h = 0.5e-5        # the times are printed to 1e-5 s, the ratio to 0.01 (one pair)
        assert a > 0 and b > 0, name
        assert (b - h) / (a + h) - 0.005 <= ratio <= (b + h) / (a - h) + 0.005, name
