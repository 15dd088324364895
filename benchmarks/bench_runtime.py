"""Runtime start-up and event costs.  Prints a table.

    python benchmarks/bench_runtime.py [repeats]
    python benchmarks/bench_runtime.py --small     (1 repeat, for the test suite)

- piston engine, first compile + simulate in a fresh process (10 s, rtol
  1e-8, 5000 output points): a new Python process runs ``import acausal2d``
  (numpy, CasADi), then times one compile_model + simulate, which counts the
  imports of the compiler and runtime modules the run needs; the bytecode
  cache of those modules is written by an untimed process first (as on an
  installed package; this machine's shell sets PYTHONDONTWRITEBYTECODE);
- the same warm (compile + simulate again in one process);
- the whole process ``acausal2d simulate models/pendulum.py --out DIR``
  (CSV, plots, animation);
- the compressor (Ebert (2015), ch. 8.2, 14 s): simulate time, number of events and
  the time spent per event (re-initialization, event iteration).
Each figure is the median of ``repeats`` runs (default 5; the spread between
runs on this shared 2-core machine is large).  The processes started run with the bytecode
cache allowed (an installed package has it).
"""
import os
import resource
import statistics
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
import acausal2d
from piston_engine import PistonEngine
t = time.perf_counter()
cm = acausal2d.compile_model(PistonEngine())
cm.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
print(time.perf_counter() - t)
"""


def _with_bytecode():
    """This process's environment without PYTHONDONTWRITEBYTECODE."""
    return {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}


def first_run(runs):
    """Seconds of the first compile + simulate in a fresh process: the
    median of ``runs`` processes, after one that writes the bytecode."""
    env = _with_bytecode()

    def one():
        out = subprocess.run([sys.executable, "-c", _FIRST % MODELS], capture_output=True,
                             text=True, check=True, env=env)
        return float(out.stdout.strip().splitlines()[-1])
    one()
    return statistics.median(one() for _ in range(runs))


def warm_run(runs):
    """Seconds of compile + simulate once everything ran before (median of
    ``runs`` after one run)."""
    sys.path.insert(0, MODELS)
    import acausal2d
    from piston_engine import PistonEngine
    times = []
    for _ in range(runs + 1):
        t = time.perf_counter()
        cm = acausal2d.compile_model(PistonEngine())
        cm.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
        times.append(time.perf_counter() - t)
    return statistics.median(times[1:])


def pendulum_cli():
    """(wall s, CPU s) of the whole process ``acausal2d simulate
    models/pendulum.py`` (CSV, figures, animation)."""
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    cmd = [exe] if os.path.exists(exe) else [sys.executable, "-m", "acausal2d"]
    with tempfile.TemporaryDirectory() as out:
        c, t = _children_cpu(), time.perf_counter()
        subprocess.run(cmd + ["simulate", os.path.join(MODELS, "pendulum.py"), "--out", out],
                       capture_output=True, check=True, env=_with_bytecode())
        return time.perf_counter() - t, _children_cpu() - c


def _children_cpu():
    use = resource.getrusage(resource.RUSAGE_CHILDREN)
    return use.ru_utime + use.ru_stime


def compressor(runs):
    """(simulate s, events, event handling s) of the compressor run: the
    median of ``runs`` (wall time of ``simulate``)."""
    sys.path.insert(0, MODELS)
    import acausal2d
    from compressor import Compressor
    cm = acausal2d.compile_model(Compressor())
    rows = []
    for _ in range(runs):
        st = cm.simulate().stats
        rows.append((st["wall_time"], st["events"] + st["time_events"], st["event_time"]))
    return sorted(rows)[len(rows) // 2]


def main(repeats):
    first = first_run(repeats)
    warm = warm_run(repeats)
    pendulum_cli()                                  # writes the bytecode of the CLI's modules
    cli = sorted(pendulum_cli() for _ in range(repeats))[repeats // 2]   # median wall, its CPU
    sim, n_events, t_events = compressor(repeats)
    rows = [("piston engine, first compile + simulate (fresh process, after import acausal2d)",
             "%.3f s" % first),
            ("piston engine, warm compile + simulate", "%.3f s" % warm),
            ("  first / warm", "%.2f" % (first / warm)),
            ("acausal2d simulate models/pendulum.py (whole process)", "%.3f s" % cli[0]),
            ("  the same, CPU (user + system)", "%.3f s" % cli[1]),
            ("compressor, simulate (%d events)" % n_events, "%.3f s" % sim),
            ("compressor, per event", "%.2f ms" % (1e3 * t_events / max(n_events, 1)))]
    width = max(len(r[0]) for r in rows)
    for name, value in rows:
        print("%-*s  %10s" % (width, name, value))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
