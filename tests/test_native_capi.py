"""The native driver built once with no model code (benchmarks/capi_driver.py): it
evaluates a formulation's serialized CasADi functions through CasADi's C
API (``casadi_c_eval_id`` of the wheel's libcasadi).  Over the piston
engine's run it reaches the stop time with the rows of the per-model
compiled library to the integration tolerance; and
benchmarks/bench_capi.py prints its table (small mode), whose ratios are
the quotients of its times."""
import os
import subprocess
import sys

import numpy as np

import acausal2d
from acausal2d.runtime import native, tiers
from acausal2d.runtime.simulation import Simulation
from tiers_support import NEEDS_NATIVE

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = [os.path.join(ROOT, "models"), os.path.join(ROOT, "benchmarks")]
from piston_engine import PistonEngine  # noqa: E402
import capi_driver  # noqa: E402

pytestmark = NEEDS_NATIVE
RTOL = 1e-8


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
    for make in (native.native_ida, capi_driver.capi_ida):
        drv = make(prob, sim.rtol, atol)
        assert drv is not None, make.__name__
        flag, T, Y = drv.run(sim.times, y0, yp0)[:3]
        assert flag >= 0 and T[-1] >= sim.times[-1] * (1 - 1e-12)
        runs.append((T, Y))
    (T1, Y1), (T2, Y2) = runs
    assert T1.shape == T2.shape and np.max(np.abs(T1 - T2)) <= 1e-12 * T1[-1]
    scale = 1.0 + np.max(np.abs(Y1), axis=0)
    assert np.all(np.max(np.abs(Y1 - Y2), axis=0) <= 1e3 * RTOL * scale)


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
