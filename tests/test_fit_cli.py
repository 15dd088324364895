"""The fit and optimize commands: files, exit codes and messages; the
benchmark's small mode prints its table."""
import json
import os
import subprocess
import sys

import pytest

from acausal2d.cli import main
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RIG = os.path.join(ROOT, "models", "belt_span_rig.py")
RIG_DATA = os.path.join(ROOT, "models", "belt_span_rig_measured.csv")
FREE = ["--free", "span.c=1e5:1e4:1e6", "--free", "span.d=50:0:1000"]


def test_fit_writes_its_files_and_the_known_values_lie_in_the_intervals(tmp_path, capsys):
    code = main(["fit", RIG, "--data", RIG_DATA, "--out", str(tmp_path)] + FREE)
    out = capsys.readouterr().out
    assert code == 0, out
    doc = json.loads((tmp_path / "fit.json").read_text())
    assert set(doc) >= {"parameters", "cost", "cost_start", "success", "message", "evaluations"}
    assert doc["success"] and doc["cost"] < 1e-3 * doc["cost_start"]
    for name, true in (("span.c", 1.5e5), ("span.d", 150.0)):     # the CSV's known values
        p = doc["parameters"][name]
        assert p["ci95"][0] < true < p["ci95"][1]
        assert set(p) == {"estimate", "std", "ci95", "start"}
    assert (tmp_path / "fit.csv").exists() and (tmp_path / "fit.png").exists()
    assert (tmp_path / "compare" / "span.F.png").exists()
    assert "span.F" in out and "PASS" in out and "95% interval" in out


@pytest.mark.parametrize("args, message", [
    (["--free", "span.x=1"], "unknown parameter 'span.x'"),
    (["--free", "span.c"], "NAME=START"),
    (["--free", "span.c=5:10:20"], "must lie between"),
    (["--free", "span.c=1e5", "--signals", "rope.F"], "not in the reference: rope.F"),
    (["--free", "span.c=1e5", "--t-range", "7:8"], "contains none of the measured times"),
    (["--free", "span.c=1e5", "--weights", "span.F=x"], "--weights"),
])
def test_fit_bad_input_exits_2_naming_it(tmp_path, capsys, args, message):
    assert main(["fit", RIG, "--data", RIG_DATA, "--out", str(tmp_path)] + args) == 2
    assert message in capsys.readouterr().err


def test_fit_budget_exits_3(tmp_path, capsys):
    code = main(["fit", RIG, "--data", RIG_DATA, "--out", str(tmp_path), "--free",
                 "span.c=1e5:1e4:1e6", "--max-evaluations", "1"])
    assert code == 3
    assert "budget of 1 evaluations ran out" in capsys.readouterr().err
    assert json.loads((tmp_path / "fit.json").read_text())["success"] is False


def test_optimize_writes_the_optimum_and_its_active_bound(tmp_path, capsys):
    # the rms span force is smallest without damping: d at its lower bound 0
    code = main(["optimize", RIG, "--vary", "span.d=150:0:1000", "--objective", "rms(span.F)",
                 "--constraint", "max(span.F)<=800", "--intervals", "50", "--grid", "3",
                 "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 0, out
    doc = json.loads((tmp_path / "optimize.json").read_text())
    assert doc["optimum"]["span.d"] == pytest.approx(0.0, abs=1e-9)
    assert doc["active_bounds"] == ["span.d"] and doc["active_constraints"] == []
    assert doc["objective"] < doc["objective_start"]
    assert "(the optimum's)" in out
    assert (tmp_path / "optimize.png").exists() and (tmp_path / "grid.csv").exists()


def test_optimize_bad_objective_exits_2(tmp_path, capsys):
    assert main(["optimize", RIG, "--vary", "span.d=150:0:1000", "--objective",
                 "max(span.G)", "--out", str(tmp_path)]) == 2
    assert "no signal span.G" in capsys.readouterr().err


def test_benchmark_small_mode_prints_its_table():
    proc = subprocess.run([sys.executable, os.path.join(ROOT, "benchmarks", "bench_fit.py"),
                           "--small", "--workers", "1"], capture_output=True, text=True,
                          timeout=600, cwd=ROOT)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines[1].split() == ["case", "runs", "serial", "s", "dask", "s", "speed-up", "max",
                                "|diff|"]
    for line, case in zip(lines[2:4], ("fit", "optimize")):
        cells = line.split()
        assert cells[0] == case and int(cells[1]) > 0
        assert_copied(float(cells[-1]), 0.0)     # serial and Dask: the same computation
