"""FMU export: export time, FMPy's run of the exported Model Exchange
(CVode, rtol 1e-8) and Co-Simulation (1 ms communication step) FMUs against
acausal2d's own run (IDA, rtol 1e-8), and the largest deviation relative to
each output's range on the 1 ms grid.

    python benchmarks/bench_fmu.py [--small]

export = compile_model + C code generation + the C compiler (a cold build
cache: a fresh $ACAUSAL2D_CACHE_DIR); fmpy = FMPy's simulate_fmu of the FMU;
acausal2d = CompiledModel.simulate of the same model.  ``--small`` runs the
pendulum only (the test suite runs it so).
"""
import os
import sys
import tempfile
import time

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STEP = 1e-3

CASES = {   # model file, class, stop time, input values
    "pendulum": ("models/pendulum.py", None, 3.0, {}),
    "piston": ("models/piston_engine.py", None, 10.0, {}),
    "clutch": ("models/clutch_motor.py", "ClutchMotor", 1.5, {"load": -10.0}),
    "fourbar": ("models/four_bar_torque.py", "FourBarTorque", 2.0, {"tau": 0.2}),
    "double": ("models/double_pendulum.py", None, 3.0, {}),   # a choice, never singular
    "dynamic": ("models/piston_engine_dynamic.py", None, 3.0, {}),   # with fixed_states
}
FIXED_STATES = {"dynamic"}
"""Cases exported with ``fixed_states=True`` (dynamic state selection)."""


def export(case, kind, path):
    """Export the model of ``case`` to ``path``."""
    from acausal2d.fmu import export_fmu
    return export_fmu(load(case), kind, path, fixed_states=case in FIXED_STATES)


def load(case):
    """A fresh instance of the model of ``case``."""
    import acausal2d
    path, name, _, _ = CASES[case]
    return acausal2d.load_model(os.path.join(ROOT, path), name)


def reference(case, params=None):
    """(result, 1 ms grid, outputs) of acausal2d's own run of the model
    with its inputs bound (and set to the case's values)."""
    import acausal2d
    from acausal2d.fmu import bind_inputs
    model = load(case)
    model, names = bind_inputs(model)
    stop, inputs = CASES[case][2], CASES[case][3]
    p = {names[k]: v for k, v in inputs.items()}
    p.update(params or {})
    grid = np.linspace(0.0, stop, int(round(stop / STEP)) + 1)
    compiled = acausal2d.compile_model(model)
    return compiled.simulate(params=p, rtol=1e-8, output_times=grid), grid, compiled.outputs


def fmu_run(fmu, kind, case, start_values=None):
    """FMPy's run of an exported FMU (ME: CVode rtol 1e-8; CS: 1 ms steps)."""
    import fmpy
    stop, inputs = CASES[case][2], CASES[case][3]
    sv = dict(inputs, **(start_values or {}))
    if kind == "me":
        return fmpy.simulate_fmu(fmu, stop_time=stop, solver="CVode", relative_tolerance=1e-8,
                                 output_interval=STEP, start_values=sv)
    return fmpy.simulate_fmu(fmu, stop_time=stop, step_size=STEP, output_interval=STEP,
                             start_values=sv)


def on_grid(times, values, grid):
    """Values at the grid times (the last row at a time recorded twice at an event)."""
    return values[np.searchsorted(times, grid + 1e-12, side="right") - 1]


def max_relative_errors(res, grid, outputs, r):
    """{output: max |FMU - acausal2d| / range of acausal2d's curve} on the grid."""
    errs = {}
    for o in outputs:
        ref = on_grid(res.time, res[o], grid)
        got = on_grid(r["time"], r[o], grid)
        errs[o] = float(np.max(np.abs(got - ref)) / max(np.ptp(ref), 1e-12))
    return errs


def row(case, kind, folder):
    """One table row: model, kind, export s, fmpy s, acausal2d s, max deviation."""
    t0 = time.perf_counter()
    fmu = export(case, kind, os.path.join(folder, "%s_%s.fmu" % (case, kind)))
    t1 = time.perf_counter()
    r = fmu_run(fmu, kind, case)
    t2 = time.perf_counter()
    res, grid, outputs = reference(case)
    t3 = time.perf_counter()
    err = max(max_relative_errors(res, grid, outputs, r).values())
    return case, kind, t1 - t0, t2 - t1, t3 - t2, err


def main(small=False):
    cases = ["pendulum"] if small else list(CASES)
    print("%-9s %-4s %9s %9s %11s %13s" % ("model", "kind", "export s", "fmpy s", "acausal2d s",
                                           "max rel dev"))
    saved = os.environ.get("ACAUSAL2D_CACHE_DIR")
    with tempfile.TemporaryDirectory() as tmp:
        os.environ["ACAUSAL2D_CACHE_DIR"] = os.path.join(tmp, "cache")
        try:
            for case in cases:
                for kind in ("me", "cs"):
                    print("%-9s %-4s %9.2f %9.3f %11.3f %13.2e" % row(case, kind, tmp))
        finally:
            if saved is None:
                del os.environ["ACAUSAL2D_CACHE_DIR"]
            else:
                os.environ["ACAUSAL2D_CACHE_DIR"] = saved


if __name__ == "__main__":
    main("--small" in sys.argv[1:])
