"""Every benchmark of issue 17 this branch owns runs in its small mode and
prints its table (so none can rot); the figures are not checked here (speed
targets live in the benchmark scripts, never in timed tests), only that the
table has its rows and that the numbers in it are positive and finite."""
import math
import os
import re
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMBER = re.compile(r"-?\d+\.\d+")


def _run(script, *args):
    out = subprocess.run([sys.executable, os.path.join(ROOT, "benchmarks", script), *args],
                         capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    return out.stdout


def _numbers(line):
    vals = [float(x) for x in NUMBER.findall(line)]
    assert vals and all(math.isfinite(v) and v >= 0 for v in vals), line
    return vals


def test_bench_peers_small():
    text = _run("bench_peers.py", "--small")
    rows = {line.split("  ")[0].strip(): line for line in text.splitlines()}
    for label in ("whole process [s] (median)", "warm compile + simulate [s] (median)",
                  "first compile + simulate in a process [s]", "acausal2d first / warm"):
        assert label in rows, text
        _numbers(rows[label])
    try:
        import rumoca  # noqa: F401
        assert "missing" not in text
        assert len(_numbers(rows["whole process [s] (median)"])) == 3    # both and the ratio
    except ImportError:
        assert "rumoca is missing" in text


def test_bench_core_small():
    text = _run("bench_core.py", "--small")
    assert "piston engine" in text and "chain of 20 links" in text
    scale = text.split("compile only (chain)")[1].splitlines()
    sizes = [line for line in scale if re.match(r"\d+ links ", line)]
    assert len(sizes) == 3
    for line in sizes:
        _numbers(line)
    assert "exponent first -> last" in text


@pytest.mark.parametrize("script,labels", [
    ("bench_belt_drive.py", ("synthesis of the pulley pair", "design (from the disk cache)",
                             "build + compile_model", "design + compile + simulate")),
    ("bench_cable_crane.py", ("#1", "median", "best")),
    ("bench_events.py", ("drive train, shared ramp", "Zeno ball", "relay storm")),
    ("bench_runtime.py", ("first compile + simulate", "warm compile + simulate",
                          "acausal2d simulate models/pendulum.py", "compressor, simulate")),
])
def test_small_modes_print_their_tables(script, labels):
    text = _run(script, "--small")
    for label in labels:
        line = next((s for s in text.splitlines() if label in s), None)
        assert line is not None, (label, text)
        _numbers(line)


def test_bench_cold_small():
    text = _run("bench_cold.py", "--small")
    row = next(s for s in text.splitlines() if s.startswith("chain of 3 links"))
    numbers = _numbers(row)     # Python, first (auto), ratio, no drivers, ratio, no compiler,
    assert len(numbers) == 12   # ratio, native in, alone, background, CPU, later
    assert numbers[2] == pytest.approx(numbers[1] / numbers[0], rel=0.01, abs=0.01)
    assert numbers[4] == pytest.approx(numbers[3] / numbers[0], rel=0.01, abs=0.01)
    assert numbers[6] == pytest.approx(numbers[5] / numbers[0], rel=0.01, abs=0.01)
    assert numbers[7] <= numbers[9]         # the libraries are published before the worker ends
    assert (numbers[7] > 0) == (numbers[8] > 0)    # a worker beside a run and alone, or none
    line = next(s for s in text.splitlines() if "piston_engine.py, whole process" in s)
    numbers = _numbers(line)    # empty, without the installed drivers, full; two ratios
    assert len(numbers) == 5
    assert numbers[3] == pytest.approx(numbers[0] / numbers[2], rel=0.01, abs=0.01)
    assert numbers[4] == pytest.approx(numbers[1] / numbers[2], rel=0.01, abs=0.01)
