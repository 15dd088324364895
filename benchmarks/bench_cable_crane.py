"""Wall time of one cable-crane transfer cycle (Ebert (2015), ch. 8.1:
140 s in SimulationX on a 3 GHz machine), compilation included.

    python benchmarks/bench_cable_crane.py [repeats]     (default 5)
    python benchmarks/bench_cable_crane.py --small       (1 cycle, for the test suite)

build = model construction (static solutions for the start state and the
drum drive design, prepare_belts), compile = compile_model (flattening,
index reduction, code generation), simulate = consistent initialization and
the IDA run over the 30 s cycle at the model's rtol (1e-7), 601 output
points.  The first row is the first cycle in this process; the last rows the
median and the best of all repeats (target: >= 300x faster than those 140 s).
The native C of the model is compiled once per model structure and cached
on disk; the table says whether it was there at the first cycle ("warm") and
(full mode) what one cycle costs in a fresh process with empty caches, C
compiler included ("cold").
"""
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "models"))

from acausal2d import compile_model  # noqa: E402
from cable_crane import CableCrane, T_STOP  # noqa: E402
from _cache import cold_run, native_libraries, print_cold, state  # noqa: E402

SEED_SECONDS = 140.0


def one_cycle():
    c0, t0 = time.process_time(), time.perf_counter()
    model = CableCrane()
    t1 = time.perf_counter()
    cm = compile_model(model)
    t2 = time.perf_counter()
    res = cm.simulate()
    t3 = time.perf_counter()
    cpu = time.process_time() - c0
    assert abs(res.time[-1] - T_STOP) < 1e-9
    return t1 - t0, t2 - t1, t3 - t2, cpu, cm.system.n_flat_equations, res


def main(repeats=5, cold=True):
    rows, libs = [], native_libraries()
    for _ in range(repeats):
        b, c, s, cpu, neq, res = one_cycle()
        rows.append((b, c, s, b + c + s, cpu))
        if len(rows) == 1:
            warm = state(libs)
    print("Cable crane, one transfer cycle of %.0f s (%d flat equations, %d events)"
          % (T_STOP, neq, len(res.events)))
    print("%-8s %8s %9s %9s %9s %10s %9s %10s" % ("run", "build", "compile", "simulate",
                                                  "total", "vs 140 s", "CPU", "vs 140 s"))
    med = tuple(statistics.median(r[k] for r in rows) for k in range(5))
    best = min(rows, key=lambda r: r[3])
    for label, r in [("#%d" % (k + 1), r) for k, r in enumerate(rows)] + [("median", med),
                                                                        ("best", best)]:
        print("%-8s %7.2fs %8.2fs %8.2fs %8.2fs %9.0fx %8.2fs %9.0fx"
              % (label, *r[:4], SEED_SECONDS / r[3], r[4], SEED_SECONDS / r[4]))
    print("native C libraries in the disk cache at the first cycle: %s" % warm)
    if cold:
        print_cold(*cold_run(__file__, "--one"), width=17)


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1, cold=False)
    elif sys.argv[1:] == ["--one"]:
        one_cycle()
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
