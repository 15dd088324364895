"""The driver on CasADi's C API (no per-model compiler) against the
per-model compiled library, on benchmarks/bench_floor.py's models: CPU
seconds of IDA alone over the run's span (the native driver with the
formulation's default linear solver, no output rows), medians of
alternating pairs, and the ratio C API / compiled.

    python benchmarks/bench_capi.py            (5 pairs)
    python benchmarks/bench_capi.py --small    (a tenth of each run, 1 pair: the suite)
"""
import os
import statistics
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import bench_floor  # noqa: E402
from acausal2d.runtime import capi, native, tiers  # noqa: E402


def _ida(sim, make):
    """(driver, y0, yp0) of the run's formulation made by ``make``."""
    form, prob = sim._solver()[:2]
    atol = np.broadcast_to(sim.rtol * sim.system.nominal, (form.n,)).copy()
    y0, yp0 = form.y_from(sim.out[0][1])
    return make(prob, sim.rtol, atol), y0, yp0


def _time(drv, sim, y0, yp0):
    t0 = time.process_time()
    flag = drv.run(sim.times, y0, yp0)[0]
    return time.process_time() - t0 if flag >= 0 else float("nan")


def main(argv):
    os.environ[tiers.ENV] = "now"          # the compiled library: compile first
    small = "--small" in argv
    pairs = 1 if small else 5
    print("IDA alone, CPU s, medians of %d alternating pairs" % pairs)
    print("%-20s %10s %10s %8s" % ("model", "compiled", "C API", "ratio"))
    for name, make, stop, rtol in bench_floor.CASES:
        stop = stop / 10 if small else stop
        cm = bench_floor.acausal2d.compile_model(make())
        sim = bench_floor.the_run(cm, stop, rtol, 200 if small else 5000)
        compiled = _ida(sim, native.native_ida)
        capi_ = _ida(sim, capi.capi_ida)
        if compiled[0] is None or capi_[0] is None:
            print("%-20s  not measured (no native driver here)" % name)
            continue
        a, b = [], []
        for _ in range(pairs + 1):         # the first pair warms up
            a.append(_time(*compiled[:1], sim, *compiled[1:]))
            b.append(_time(*capi_[:1], sim, *capi_[1:]))
        ratios = [y / x for x, y in zip(a[1:], b[1:])]
        print("%-20s %10.5f %10.5f %8.2f" % (name, statistics.median(a[1:]),
                                             statistics.median(b[1:]), statistics.median(ratios)))


if __name__ == "__main__":
    main(sys.argv[1:])
