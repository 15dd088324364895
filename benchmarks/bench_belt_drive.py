"""Wall time of the non-circular toothed belt drive (Ebert (2015), ch. 7.3.2): 2 s
simulated (720 deg of drive angle), compilation and pulley design included.
Prints a table.

    python benchmarks/bench_belt_drive.py [repeats]     (default 5)
    python benchmarks/bench_belt_drive.py --small       (1 repeat, for the test suite)

synthesis = the pulley-pair synthesis computed (models/noncircular_belt_drive.py,
            ``synthesise``: Gauss-Newton on the collocated contact conditions)
design    = ``design()`` as a model construction gets it: the synthesis read
            from acausal2d's disk cache (keyed by its inputs and the model
            file) and the two contours built
compile   = model construction and compile_model (flatten, aliases, balance, Pantelides)
simulate  = CompiledModel.simulate with the model's experiment (rtol 1e-8,
            721 output points): initialization, state selection, generation
            of the index-1 functions and the IDA run
native    = whether the C of the model (its residual, Jacobian and event
            functions, compiled once per model structure by the native
            runtime) was already in the disk cache (``$ACAUSAL2D_CACHE_DIR``,
            else ~/.cache/acausal2d/cbuild) at the first run: "warm" or
            "cold" (the first run then includes the C compiler)
cold      = (full mode only) one run in a fresh process with empty caches
            (native libraries and pulley design): what the very first run
            on a machine costs, C compiler included (CPU of the process and
            of its children, the compiler)
Ebert (2015) reports 4.2 s in SimulationX on a 3 GHz CPU for compile + simulate
(with given contours).  The table shows the first run in this process and the
median of ``repeats`` runs; the target is design + compile + simulate
<= 0.14 s (30x faster than the dissertation's SimulationX run).
"""
import math
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "models"))

import acausal2d  # noqa: E402
import noncircular_belt_drive as nbd  # noqa: E402
from _cache import cold_run, native_libraries, print_cold, state  # noqa: E402

SEED_TIME = 4.2
TARGET = SEED_TIME / 30


def one_run():
    """(synthesis, design, compile, simulate, CPU of design + compile +
    simulate) seconds and the result."""
    t0 = time.perf_counter()
    nbd.synthesise()
    t1 = time.perf_counter()
    nbd.design()                              # fills the disk cache if it is empty
    t2, c2 = time.perf_counter(), time.process_time()
    des = nbd.design.__wrapped__()            # what a fresh process does
    t3 = time.perf_counter()
    cm = acausal2d.compile_model(nbd.NonCircularBeltDrive(des))
    t4 = time.perf_counter()
    res = cm.simulate()
    t5 = time.perf_counter()
    return (t1 - t0, t3 - t2, t4 - t3, t5 - t4, time.process_time() - c2), res


def main(repeats=5, cold=True):
    rows, res = [], None
    libs = native_libraries()
    for _ in range(max(repeats, 1)):
        times, res = one_run()
        rows.append(times)
        if len(rows) == 1:
            warm = state(libs)
    first = rows[0]
    med = [statistics.median(r[k] for r in rows) for k in range(5)]
    dev = max(abs(r / rd - 1.0) for r, rd in zip(res["ratio"], res["ratio_design"]))
    print("Non-circular toothed belt drive, 2 s simulated (%d output points, rtol %g), %d runs"
          % (len(res.time), nbd.NonCircularBeltDrive.experiment["rtol"], len(rows)))
    print("%-40s %10s %10s" % ("step", "first [s]", "median [s]"))
    labels = ("synthesis of the pulley pair (computed)", "design (from the disk cache)",
              "build + compile_model", "simulate")
    for k, label in enumerate(labels):
        print("%-40s %10.3f %10.3f" % (label, first[k], med[k]))
    tot_first, tot_med = sum(first[1:4]), sum(med[1:4])
    print("%-40s %10.3f %10.3f" % ("design + compile + simulate", tot_first, tot_med))
    print("%-40s %10.3f %10.3f" % ("design + compile + simulate, CPU", first[4], med[4]))
    print("%-40s %10.3f %10.3f" % ("target (SimulationX / 30)", TARGET, TARGET))
    print("%-40s %10.3f" % ("Ebert (2015): SimulationX, 3 GHz", SEED_TIME))
    print("%-40s %9.1fx %9.1fx" % ("speed-up vs SimulationX, incl. design", SEED_TIME / tot_first,
                                   SEED_TIME / tot_med))
    print("native C libraries in the disk cache at the first run: %s" % warm)
    if cold:
        print_cold(*cold_run(__file__, "--one"))
    print("IDA: %d residual evaluations, %d Jacobians; max |ratio/designed - 1| = %.2e; "
          "large pulley turned %.6f rev" % (res.stats["nfev"], res.stats["njev"], dev,
                                            res["large.phi"][-1] / (2 * math.pi)))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1, cold=False)
    elif sys.argv[1:] == ["--one"]:
        nbd.design()
        acausal2d.compile_model(nbd.NonCircularBeltDrive(nbd.design())).simulate()
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
