"""Wall time of a calibration and a design optimisation through the DAE,
serial vs on a local Dask cluster.  Prints a table.

    python benchmarks/bench_fit.py [--small] [--workers N]

fit       = the pulley block's bearing friction (the four pulleys' mu tied)
            from models/pulley_block_measured.csv (rope1.F, rope5.F, t = 1..5 s),
            start mu = 0.1 (acausal2d.fit)
optimize  = the cabinet door (models/cabinet_door.py): spring rate and the
            spring's attachment point B0 minimising the peak residual torque
            max(abs(drive.tau)) over the travel, 100 output intervals, from
            the ch. 6 design (acausal2d.optimize)
serial    = every run in this process (the model compiled once)
dask      = the runs of each finite-difference Jacobian in parallel on a
            LocalCluster of N single-threaded workers (default: one per
            core; cluster start and the workers' compilation included)

--small runs short versions (t = 1..1.5 s; spring rate only, 20 intervals, 2
iterations) for the test suite.  Both modes must give the same numbers:
the table's last column is the largest difference of the results.
"""
import argparse
import os
import sys
import time

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
MODELS = os.path.join(ROOT, "models")
sys.path.insert(0, ROOT)

import acausal2d  # noqa: E402

MU = "U1.mu,L2.mu,U3.mu,L4.mu"


def fit_case(small, **options):
    """The pulley-block fit; returns (estimates, model runs)."""
    fr = acausal2d.fit(os.path.join(MODELS, "pulley_block.py"),
                       os.path.join(MODELS, "pulley_block_measured.csv"),
                       free={MU: (0.1, 0.0, 0.6)}, t_range=(1.0, 1.5) if small else None,
                       **options)
    assert fr.success, fr.message
    return fr.estimate, fr.evaluations


def optimize_case(small, **options):
    """The cabinet-door optimisation; returns (optimum, model runs)."""
    vary = {"spring.k": (938.0, 500.0, 1500.0)}
    if not small:
        vary.update({"B0.r[0]": (-0.296, -0.316, -0.276), "B0.r[1]": (0.0, -0.02, 0.02)})
    opt = acausal2d.optimize(os.path.join(MODELS, "cabinet_door.py"), vary,
                             "max(abs(drive.tau))", intervals=20 if small else 100,
                             max_iterations=2 if small else 60, **options)
    assert small or opt.success, opt.message
    return opt.optimum, opt.evaluations


def timed(func, *args, **kwargs):
    t0 = time.perf_counter()
    out = func(*args, **kwargs)
    return out, time.perf_counter() - t0


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--small", action="store_true")
    p.add_argument("--workers", type=int, default=os.cpu_count())
    args = p.parse_args(argv)
    print("fit and optimisation through the DAE, %s mode, %d cores, %d Dask workers"
          % ("small" if args.small else "full", os.cpu_count(), args.workers))
    print("%-10s %6s %12s %12s %9s %12s" % ("case", "runs", "serial s", "dask s", "speed-up",
                                           "max |diff|"))
    for name, case in (("fit", fit_case), ("optimize", optimize_case)):
        (x_s, runs), t_s = timed(case, args.small)
        (x_d, _), t_d = timed(case, args.small, scheduler="local", workers=args.workers)
        print("%-10s %6d %12.2f %12.2f %9.2f %12.3g" % (name, runs, t_s, t_d, t_s / t_d,
                                                        float(np.max(np.abs(x_s - x_d)))))


if __name__ == "__main__":
    main()
