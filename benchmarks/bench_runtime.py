"""Runtime start-up and event costs.  Prints a table.

    python benchmarks/bench_runtime.py [repeats]
    python benchmarks/bench_runtime.py --small     (1 repeat, for the test suite)

- piston engine, first compile + simulate in a fresh process (10 s, rtol
  1e-8, 5000 output points), imports excluded: a new Python process imports
  acausal2d and its runtime (numpy, CasADi, scikit-sundae), then times one
  compile_model + simulate;
- the same warm (best of several in one process);
- the whole process ``acausal2d simulate models/pendulum.py --out DIR``
  (CSV, plots, animation);
- the compressor (seed ch. 8.2, 14 s): simulate time, number of events and
  the time spent per event (re-initialization, event iteration).
Each figure is the best of ``repeats`` runs (default 5); the spread between
runs on this 2-core machine is large, so the best is what the code costs.
"""
import os
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MODELS = os.path.join(ROOT, "models")

_FIRST = r"""
import sys, time
sys.path.insert(0, %r)
import acausal2d, acausal2d.compiled, acausal2d.runtime.simulation
from piston_engine import PistonEngine
t = time.perf_counter()
cm = acausal2d.compile_model(PistonEngine())
cm.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
print(time.perf_counter() - t)
"""


def first_run():
    """Seconds of the first compile + simulate in a fresh process."""
    out = subprocess.run([sys.executable, "-c", _FIRST % MODELS], capture_output=True,
                         text=True, check=True)
    return float(out.stdout.strip().splitlines()[-1])


def warm_run():
    """Seconds of compile + simulate once everything ran before."""
    sys.path.insert(0, MODELS)
    import acausal2d
    from piston_engine import PistonEngine
    best = float("inf")
    for _ in range(6):
        t = time.perf_counter()
        cm = acausal2d.compile_model(PistonEngine())
        cm.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
        best = min(best, time.perf_counter() - t)
    return best


def pendulum_cli():
    """(wall s, CPU s) of the whole process ``acausal2d simulate
    models/pendulum.py`` (CSV, figures, animation)."""
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    cmd = [exe] if os.path.exists(exe) else [sys.executable, "-m", "acausal2d"]
    with tempfile.TemporaryDirectory() as out:
        c, t = _children_cpu(), time.perf_counter()
        subprocess.run(cmd + ["simulate", os.path.join(MODELS, "pendulum.py"), "--out", out],
                       capture_output=True, check=True)
        return time.perf_counter() - t, _children_cpu() - c


def _children_cpu():
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def compressor(runs=3):
    """(simulate s, events, event handling s) of the compressor run."""
    sys.path.insert(0, MODELS)
    import acausal2d
    from compressor import Compressor
    cm = acausal2d.compile_model(Compressor())
    best = None
    for _ in range(runs):
        res = cm.simulate()
        st = res.stats
        row = (st["wall_time"], st["events"] + st["time_events"], st["event_time"])
        best = row if best is None or row[0] < best[0] else best
    return best


def main(repeats, compressor_runs=3):
    first = min(first_run() for _ in range(repeats))
    warm = warm_run()
    cli = min(pendulum_cli() for _ in range(repeats))        # the best wall time and its CPU
    sim, n_events, t_events = compressor(compressor_runs)
    rows = [("piston engine, first compile + simulate (fresh process, imports excluded)",
             "%.3f s" % first),
            ("piston engine, warm compile + simulate", "%.3f s" % warm),
            ("acausal2d simulate models/pendulum.py (whole process)", "%.3f s" % cli[0]),
            ("  the same, CPU (user + system)", "%.3f s" % cli[1]),
            ("compressor, simulate (%d events)" % n_events, "%.3f s" % sim),
            ("compressor, per event", "%.2f ms" % (1e3 * t_events / max(n_events, 1)))]
    width = max(len(r[0]) for r in rows)
    for name, value in rows:
        print("%-*s  %10s" % (width, name, value))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1, compressor_runs=1)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
