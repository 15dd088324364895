"""acausal2d's warm simulate against the floor of IDA: CasADi's own IDAS on
the same index-1 system.  Prints a table.

    python benchmarks/bench_floor.py [--small] [repeats]

For each model, acausal2d simulates it (warm: compiled, run once before);
then the run's own formulation (the index-1 system of the state selection
the run used, :mod:`acausal2d.compiler.index1`: states x with
x' = y[der(x)], every equation as an algebraic equation) is handed to
``casadi.integrator(..., 'idas')`` with the same tolerances (the run's
rtol and the smallest of its absolute tolerances; algebraic unknowns left
out of the error test as in acausal2d) and the same output grid, without
events.  Both are timed in CPU seconds of this process (single-threaded
both; on a machine shared with other jobs wall times scatter by 2-3x),
alternating, ``repeats`` pairs (default 5): the table gives the medians of
each and the median of the pairs' ratios.  A second table gives the
native IDA alone with each linear solver it can use (the choice of
:mod:`acausal2d.runtime.native`: SUNDIALS' dense LU, LAPACK's, SuperLU_MT,
the driver's own sparse LU).

Models: the piston engine (10 s, rtol 1e-8), a chain of 20 pendulum links
(2 s, rtol 1e-6), the non-circular belt drive (2 s, rtol 1e-8; it has no
events), each with 5000 output points.  ``--small`` runs short versions
(a test runs it so that the table cannot rot).
"""
import os
import statistics
import sys
import time

import casadi as ca
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "models"))
sys.path.insert(0, HERE)

import acausal2d  # noqa: E402
from acausal2d.runtime import native, tiers  # noqa: E402
from acausal2d.runtime.simulation import Simulation  # noqa: E402

HEADER = ("model", "acausal2d [s]", "IDAS [s]", "ratio", "steps a2d", "steps IDAS")


def _piston():
    from piston_engine import PistonEngine
    return PistonEngine()


def _chain():
    from bench_core import PendulumChain
    return PendulumChain(20)


def _belt():
    import noncircular_belt_drive as nbd
    return nbd.NonCircularBeltDrive(nbd.design())


CASES = [("piston engine", _piston, 10.0, 1e-8), ("chain of 20 links", _chain, 2.0, 1e-6),
         ("belt drive", _belt, 2.0, 1e-8)]


def acausal2d_run(cm, stop, rtol, n_out):
    """(seconds, steps) of one warm ``simulate``."""
    t0 = time.process_time()
    res = cm.simulate(stop_time=stop, rtol=rtol, intervals=n_out)
    return time.process_time() - t0, int(res.stats["steps"])


def the_run(cm, stop, rtol, n_out):
    """The :class:`Simulation` of the same run (its selection, tolerances)."""
    opts = cm.run_options(stop_time=stop, intervals=n_out, rtol=rtol)
    times, rtol_, atol_ = opts.times(), opts.rtol, opts.atol
    sim = Simulation(cm.system, cm.parameter_values(None), times, rtol_, atol_)
    sim.run()
    return sim


def floor_integrator(sim):
    """(casadi IDAS integrator, x0, z0) on the run's index-1 system."""
    form = sim.system.formulation(sim.selection)
    n = form.n
    alg = np.nonzero(~form.differential)[0]
    x, z = ca.SX.sym("x", len(form.states)), ca.SX.sym("z", len(alg))
    nom = np.asarray(sim.system.nominal, float)     # unknowns scaled by their nominal:
    y = ca.SX.zeros(n)                               # abstol rtol = acausal2d's rtol * nominal
    y[list(form.states)] = x * nom[form.states]
    y[list(alg)] = z * nom[alg]
    t = ca.SX.sym("t")
    F = form.res_fn(t, y, ca.SX.zeros(n), sim.p, sim.d)
    n_eq = n - len(form.states)
    ode = y[list(form.state_deriv)] / nom[form.states]
    dae = {"t": t, "x": x, "z": z, "ode": ode, "alg": F[:n_eq]}
    opts = {"abstol": float(sim.rtol), "reltol": float(sim.rtol), "suppress_algebraic": True,
            "max_num_steps": 1000000, "calc_ic": False}
    grid = np.asarray(sim.times, float)
    fn = ca.integrator("floor", "idas", dae, float(grid[0]), grid[1:], opts)
    y0, _ = form.y_from(sim.out[0][1])
    return fn, y0[form.states] / nom[form.states], y0[alg] / nom[alg]


def floor_run(fn, x0, z0):
    """(seconds, steps) of one CasADi IDAS run."""
    t0 = time.process_time()
    fn(x0=x0, z0=z0)
    return time.process_time() - t0, int(fn.stats()["nsteps"])


def measure(make, stop, rtol, n_out, repeats):
    """One row of the table: the two runs alternate ``repeats`` times
    (after a warm-up of each; each pair in the other order than the last);
    their medians and the median of the pairs' ratios (the machine's speed
    drifts between runs, and a pair sees nearly the same machine)."""
    cm = acausal2d.compile_model(make())
    acausal2d_run(cm, stop, rtol, n_out)              # warm-up
    sim = the_run(cm, stop, rtol, n_out)
    fn, x0, z0 = floor_integrator(sim)
    floor_run(fn, x0, z0)
    runs, floors = [], []
    for k in range(repeats):            # in turn which of the pair runs first
        if k % 2:
            floors.append(floor_run(fn, x0, z0))
        runs.append(acausal2d_run(cm, stop, rtol, n_out))
        if not k % 2:
            floors.append(floor_run(fn, x0, z0))
    a = statistics.median(r[0] for r in runs)
    f = statistics.median(r[0] for r in floors)
    ratio = statistics.median(r[0] / q[0] for r, q in zip(runs, floors))
    return (a, f, ratio, runs[-1][1], floors[-1][1]), sim


def solver_times(sim, repeats):
    """{solver: CPU seconds} of the native IDA alone (no output rows) over
    the run's span with each linear solver of the driver."""
    form, prob = sim._solver()[:2]
    atol = np.broadcast_to(sim.rtol * sim.system.nominal, (form.n,)).copy()
    y0, yp0 = form.y_from(sim.out[0][1])
    out = {}
    for name in native.SOLVERS:
        drv = native.native_ida(prob, sim.rtol, atol, solver=name)
        if drv is None:
            return {}
        runs = []
        for _ in range(repeats + 1):
            t0 = time.process_time()
            flag = drv.run(sim.times, y0, yp0)[0]
            runs.append(time.process_time() - t0)
        out[name] = statistics.median(runs[1:]) if flag >= 0 else float("nan")
    return out


def main(argv):
    os.environ[tiers.ENV] = "now"    # warm means native: compile first (an empty cache's first run)
    small = "--small" in argv
    args = [a for a in argv if a != "--small"]
    repeats = int(args[0]) if args else (1 if small else 5)
    n_out = 200 if small else 5000
    print("Warm simulate vs CasADi IDAS on the same index-1 system (%d output points, "
          "%d alternating pairs: medians, ratio the median of the pairs')" % (n_out, repeats))
    print("%-20s %14s %10s %7s %10s %11s" % HEADER)
    solvers = []
    for name, make, stop, rtol in CASES:
        stop = stop / 10 if small else stop
        row, sim = measure(make, stop, rtol, n_out, repeats)
        print("%-20s %14.5f %10.5f %7.2f %10d %11d" % ((name,) + row))
        solvers.append((name, sim.system.formulation(sim.selection).n,
                        solver_times(sim, repeats)))
    print()
    print("IDA alone (native driver, no output rows) by linear solver [s]")
    print("%-20s %6s" % ("model", "n") + " %10s" * len(native.SOLVERS) % tuple(native.SOLVERS))
    for name, n, times in solvers:
        print("%-20s %6d" % (name, n) +
              " %10.5f" * len(native.SOLVERS) % tuple(times.get(s, np.nan) for s in native.SOLVERS))


if __name__ == "__main__":
    main(sys.argv[1:])
