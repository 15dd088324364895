"""benchmarks/bench_floor.py runs (small mode) and prints its table: one row
per model with both times, their ratio and both step counts."""
import os
import subprocess
import sys

from acausal2d.runtime import cbuild

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def test_bench_floor_small_prints_its_table():
    out = subprocess.run([sys.executable, os.path.join(ROOT, "benchmarks", "bench_floor.py"),
                          "--small"], capture_output=True, text=True, timeout=600, cwd=ROOT)
    assert out.returncode == 0, out.stderr[-2000:]
    lines = out.stdout.splitlines()
    assert lines[1].split()[:3] == ["model", "acausal2d", "[s]"]
    blank = lines.index("")
    rows = {}
    for line in lines[2:blank]:
        rest = line.split()
        rows[" ".join(rest[:-5])] = rest[-5:]
    assert set(rows) == {"piston engine", "chain of 20 links", "belt drive"}
    for name, (a, f, ratio, steps_a, steps_f) in rows.items():
        a, f, ratio = float(a), float(f), float(ratio)
        assert a > 0 and f > 0, name
        h = 0.5e-5        # the times are printed to 1e-5 s, the ratio to 0.01; one pair in
        #                   the small mode: the ratio is that pair's
        assert (a - h) / (f + h) - 0.005 <= ratio <= (a + h) / (f - h) + 0.005, name
        # the same system at the same tolerances: step counts within 25 % of each other
        assert abs(int(steps_a) - int(steps_f)) <= 0.25 * int(steps_f), name
    # second table: the native IDA alone with each linear solver
    assert lines[blank + 2].split() == ["model", "n", "dense", "lapack", "sparse", "sparse-lu"]
    solvers = {" ".join(line.split()[:-5]): line.split()[-5:] for line in lines[blank + 3:]}
    assert set(solvers) == set(rows)
    assert int(solvers["chain of 20 links"][0]) >= 100         # a sparse-size system
    for name, (n, *times) in solvers.items():
        if cbuild.find_compiler() is None:      # no native driver: no times
            break
        assert all(float(t) > 0 for t in times), name
