"""Compile and simulation times of the core: piston engine and chains of N
pendulum links.  Prints a table.

    python benchmarks/bench_core.py [N ...]
    python benchmarks/bench_core.py --small     (small sizes, for the test suite)

compile = flatten, aliases, balance, Pantelides (compile_model) plus the
consistent initialization, state selection and generation of the index-1
functions; simulate = the IDA run.  Columns: equations after flattening,
after alias elimination, and unknowns of the semi-explicit index-1 system
handed to IDA.  Each
figure is the best of a few runs (one for the large chains).

The second table compiles chains of about 10k, 20k and 50k flattened
equations (compile as above, no simulation) and prints the growth exponent
of the CPU time between the sizes (targets: 50k in <= 30 s, exponent
<= 1.2 between 10k and 50k).
"""
import math
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "models"))

import acausal2d  # noqa: E402
from acausal2d import Component, start  # noqa: E402
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute  # noqa: E402


class PendulumChain(Component):
    """N pendulum links (revolute + rod + body) hanging from a fixed point."""

    def __init__(self, n, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.joints = [Revolute(phi=start(-math.pi / 2 + (0.3 if i == 0 else 0.0), fixed=True),
                                w=start(0.0, fixed=True)) for i in range(n)]
        self.rods = [FixedTranslation(r=(1.0 / n, 0.0)) for _ in range(n)]
        self.bodies = [Body(m=1.0 / n, I=0.01 / n) for _ in range(n)]
        prev = self.fixed.frame
        for j, r, b in zip(self.joints, self.rods, self.bodies):
            self.connect(prev, j.frame_a)
            self.connect(j.frame_b, r.frame_a)
            self.connect(r.frame_b, b.frame_a)
            prev = r.frame_b


def measure(make, stop_time, rtol, intervals, repeat=3):
    best_c = best_s = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        cm = acausal2d.compile_model(make())
        cm.system.formulation(cm.initial_point().selection)
        t1 = time.perf_counter()
        res = cm.simulate(stop_time=stop_time, rtol=rtol, intervals=intervals)
        t2 = time.perf_counter()
        best_c = min(best_c, t1 - t0)
        best_s = min(best_s, t2 - t1)
    return cm, res, best_c, best_s


def compile_only(n):
    """(flattened equations, wall s, CPU s) of compiling a chain of n links:
    compile_model, the initial point with its state selection and the
    index-1 formulation of that selection."""
    model = PendulumChain(n)
    w0, c0 = time.perf_counter(), time.process_time()
    cm = acausal2d.compile_model(model)
    cm.system.formulation(cm.initial_point().selection)
    return cm.system.n_flat_equations, time.perf_counter() - w0, time.process_time() - c0


def links_for(n_flat):
    """Links of a chain with about ``n_flat`` flattened equations (38 per
    link plus 6)."""
    return max(1, round((n_flat - 6) / 38))


def _sizes(cm):
    """Equations after flattening, after alias elimination, unknowns of the
    semi-explicit index-1 system."""
    s = cm.system
    return s.n_flat_equations, len(s.equations), s.structure.n_var


def main(sizes, scale):
    from piston_engine import PistonEngine
    rows = []
    cm, res, c, s = measure(PistonEngine, 10.0, 1e-8, 5000)
    rows.append(("piston engine (10 s, rtol 1e-8, 5000 pts)", *_sizes(cm), c, s))
    for n in sizes:
        cm, res, c, s = measure(lambda: PendulumChain(n), 1.0, 1e-6, 100,
                                repeat=3 if n <= 20 else 1)
        rows.append(("chain of %d links (1 s, rtol 1e-6)" % n, *_sizes(cm), c, s))
    print("%-44s %8s %8s %9s %10s %10s %10s" % ("model", "flat", "aliased", "index-1",
                                                 "compile s", "simulate s", "total s"))
    for name, n_flat, n_eq, n_red, c, s in rows:
        print("%-44s %8d %8d %9d %10.3f %10.3f %10.3f" % (name, n_flat, n_eq, n_red, c, s, c + s))
    if scale:
        print_scale(scale)


def print_scale(targets):
    """Compile time of chains of about ``targets`` flattened equations and
    the growth exponent log(t2/t1)/log(n2/n1) between consecutive sizes and
    between the first and the last (CPU time: the machine is shared)."""
    print()
    print("%-30s %8s %10s %10s %12s" % ("compile only (chain)", "flat", "wall s", "CPU s",
                                        "exponent"))
    got = []
    for target in targets:
        n = links_for(target)
        got.append((n,) + compile_only(n))
        n_flat, wall, cpu = got[-1][1:]
        exp = "" if len(got) == 1 else "%.2f" % _exponent(got[-2], got[-1])
        print("%-30s %8d %10.2f %10.2f %12s" % ("%d links" % n, n_flat, wall, cpu, exp))
    if len(got) > 2:
        print("%-30s %8s %10s %10s %12.2f" % ("exponent first -> last", "", "", "",
                                              _exponent(got[0], got[-1])))


def _exponent(a, b):
    """Growth exponent of CPU time between two (links, flat, wall, cpu) rows."""
    return math.log(b[3] / a[3]) / math.log(b[1] / a[1])


if __name__ == "__main__":
    args = sys.argv[1:]
    if args == ["--small"]:
        main([5, 20], [800, 1600, 3200])
    else:
        main([int(a) for a in args] or [5, 20, 80, 200], [10000, 20000, 50000])
