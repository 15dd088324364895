"""Speed-up of a parameter study on Dask over the same runs done serially.
Prints a table.

    python benchmarks/bench_sweep.py [points] [workers]

The study is the pulley block's efficiency sweep (models/pulley_block.py):
the four pulleys' bearing friction mu from 0 to 0.5 in ``points`` steps
(default 40), each run 3 s at rtol 1e-8 with 31 output points.

serial        = compile once, then every point in this process
dask (cold)   = a new LocalCluster of ``workers`` single-threaded processes
                (default: one per core): starting it, each worker importing
                acausal2d and compiling the model once, all points
dask (warm)   = the same points again on that cluster (models compiled)
The speed-up is serial time / dask time.  On a machine whose cores are
busy with other work the speed-up drops accordingly.
"""
import os
import sys
import time

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "models"))

import acausal2d  # noqa: E402
from acausal2d.analysis.sweep import cluster  # noqa: E402
import pulley_block as pb  # noqa: E402

MODEL = os.path.join(ROOT, "models", "pulley_block.py")


def run(points, **options):
    """The efficiency sweep over ``points`` values of mu; returns (table, s)."""
    t0 = time.perf_counter()
    table = acausal2d.sweep(options.pop("model", MODEL), vary={pb.MU_TIED: "0:0.5:%d" % points},
                            metrics=pb.efficiency_metrics, stop_time=3.0, intervals=30,
                            rtol=1e-8, progress=False, model_name="PulleyBlock", **options)
    assert not table.failed, table.failed[0]["error"]
    return table, time.perf_counter() - t0


def main(points=40, workers=None):
    workers = workers or os.cpu_count()
    t0 = time.perf_counter()
    compiled = acausal2d.compile_model(pb.PulleyBlock())
    serial, _ = run(points, model=compiled)
    t_serial = time.perf_counter() - t0
    t1 = time.perf_counter()
    with cluster(workers=workers) as client:
        cold, _ = run(points, client=client)
        t_cold = time.perf_counter() - t1
        warm, t_warm = run(points, client=client)
    for table in (cold, warm):
        for a, b in zip(serial.rows, table.rows):
            assert abs(a["efficiency"] - b["efficiency"]) <= 1e-12
    print("pulley block efficiency sweep, %d points, %d cores, %d workers"
          % (points, os.cpu_count(), workers))
    print("%-28s %10s %10s" % ("mode", "wall s", "speed-up"))
    print("%-28s %10.2f %10s" % ("serial (compile + runs)", t_serial, "1.00"))
    print("%-28s %10.2f %10.2f" % ("dask, cold (cluster start)", t_cold, t_serial / t_cold))
    print("%-28s %10.2f %10.2f" % ("dask, warm cluster", t_warm, t_serial / t_warm))


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:3]))
