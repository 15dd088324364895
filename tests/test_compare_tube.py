"""compare cannot false-fail a converged result and still catches real
deviations: our curve is evaluated at the reference times with a cubic
interpolant (Hermite where the derivative is in the result), and the
csv-compare tube with a time tolerance accepts a step shifted by less than
the tolerance.  The reference is the subsampled Dymola file shipped in
tests/data/references."""
import csv
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis.compare import compare, read_csv
from conftest import same_time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DP_REF = os.path.join(ROOT, "tests", "data", "references", "DoublePendulum.csv")
SIGNALS = ["revolute.phi", "revolute.w", "revolute1.phi", "revolute1.w"]


def run(*args):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def dp_result(tmp_path_factory):
    out = tmp_path_factory.mktemp("dp")
    proc = run("simulate", os.path.join(ROOT, "models", "double_pendulum.py"), "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    assert "1001 output points" in proc.stdout          # the default grid, 10 ms
    return out / "result.csv"


def test_double_pendulum_default_grid_passes_to_6_5_s(dp_result):
    proc = run("compare", str(dp_result), DP_REF, "--until", "6.5")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "4 of 4 signals passed" in proc.stdout


def test_interpolant_has_the_integrator_s_accuracy(dp_result):
    """The default grid (10 ms) interpolated onto the reference times agrees
    with the same run written directly at those times (IDA's own output) to
    5e-5, an order below the run's error at its tolerance; linear
    interpolation is off by 8e-3 there (the old false failure)."""
    t_ref, _ = read_csv(DP_REF)
    cls = acausal2d.load_model(os.path.join(ROOT, "models", "double_pendulum.py"))
    cm = acausal2d.compile_model(cls)
    grid = np.linspace(0.0, 10.0, 1001)
    direct = cm.simulate(output_times=np.union1d(grid, t_ref))
    t_ours, ours = read_csv(dp_result)
    cmp = compare(str(dp_result), (direct.time, {n: direct[n] for n in SIGNALS}),
                  signals=SIGNALS, abs_tol=5e-5)
    assert cmp.passed, cmp.table()
    linear = np.interp(direct.time, t_ours, ours["revolute1.w"])
    assert np.max(np.abs(linear - direct["revolute1.w"])) > 5e-3


def test_perturbed_result_fails(dp_result, tmp_path):
    t, cols = read_csv(dp_result)
    bad = tmp_path / "perturbed.csv"
    with open(bad, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["time"] + SIGNALS)
        for k in range(t.size):
            w.writerow(["%r" % float(t[k])] + ["%r" % float(cols[n][k] + 3e-3) for n in SIGNALS])
    proc = run("compare", str(bad), DP_REF, "--until", "6.5")
    assert proc.returncode == 1
    lines = {ln.split()[0]: ln for ln in proc.stdout.splitlines() if ln.strip()}
    for name in SIGNALS:
        assert "FAIL" in lines[name], proc.stdout
    assert "0 of 4 signals passed" in proc.stdout


def _step_files(tmp_path, shift):
    """Reference: a step from 0 to 1 at t = 0.5 (duplicated event rows, 1 ms
    grid); ours: the same step at 0.5 + shift on a 10 ms grid."""
    tr = np.linspace(0.0, 1.0, 1001)
    ref_t = np.sort(np.r_[tr, 0.5])
    ref_y = (ref_t > 0.5).astype(float)
    ref_y[np.flatnonzero(same_time(ref_t, 0.5))[-1]] = 1.0             # right limit row
    to = np.linspace(0.0, 1.0, 101)
    te = 0.5 + shift
    our_t = np.sort(np.r_[to, te, te])
    our_y = (our_t > te).astype(float)
    our_y[np.flatnonzero(our_t == te)[-1]] = 1.0
    return (our_t, {"y": our_y}), (ref_t, {"y": ref_y})


@pytest.mark.parametrize("shift", [3e-3, -3e-3])
def test_time_tolerance_tube_on_a_shifted_step(tmp_path, shift):
    ours, ref = _step_files(tmp_path, shift)
    assert compare(ours, ref, time_tol=5e-3).passed                  # inside the tube
    strict = compare(ours, ref, time_tol=1e-3)
    assert not strict.passed and strict.rows[0].max_deviation == pytest.approx(1.0)
    assert not compare(ours, ref).passed                             # no time tolerance
    # a shifted step does not hide a wrong level
    off = (ours[0], {"y": ours[1]["y"] + 0.01})
    row = compare(off, ref, time_tol=5e-3).rows[0]
    assert not row.passed and row.max_deviation == pytest.approx(0.01, abs=1e-12)


def test_time_tolerance_from_the_cli(tmp_path):
    (ot, oc), (rt, rc) = _step_files(tmp_path, 3e-3)
    for path, t, y, quoted in ((tmp_path / "ours.csv", ot, oc["y"], False),
                               (tmp_path / "ref.csv", rt, rc["y"], True)):
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh, quoting=csv.QUOTE_NONNUMERIC if quoted else csv.QUOTE_MINIMAL)
            w.writerow(["Time" if quoted else "time", "y"])
            w.writerows(zip(t.tolist(), y.tolist()))
    ok = run("compare", str(tmp_path / "ours.csv"), str(tmp_path / "ref.csv"), "--time-tol",
             "0.005", "--out", str(tmp_path / "plots"))
    assert ok.returncode == 0, ok.stdout + ok.stderr
    assert "tube with time tolerance 0.005 s" in ok.stdout
    assert (tmp_path / "plots" / "y.png").exists()
    assert run("compare", str(tmp_path / "ours.csv"), str(tmp_path / "ref.csv")).returncode == 1
    bad = run("compare", str(tmp_path / "ours.csv"), str(tmp_path / "ref.csv"), "--time-tol",
              "-1")
    assert bad.returncode == 2 and "--time-tol" in bad.stderr and "Traceback" not in bad.stderr


def test_hermite_uses_the_derivative_column():
    """With der(x) in our result the interpolant matches value and slope at
    every output point: sin(5 t) on a coarse 50 ms grid is met to the
    Hermite error bound h^4/384 max|x''''| (1.0e-5) at 7 ms reference points."""
    t = np.linspace(0.0, 2.0, 41)
    tr = np.linspace(0.0, 2.0, 287)
    ours = (t, {"x": np.sin(5 * t), "der(x)": 5 * np.cos(5 * t)})
    bound = 0.05 ** 4 / 384 * 5 ** 4
    row = compare(ours, (tr, {"x": np.sin(5 * tr)}), abs_tol=bound).rows[0]
    assert row.passed and row.max_deviation > 0.5 * bound      # the bound is sharp here
    wrong = (t, {"x": np.sin(5 * t), "der(x)": np.zeros_like(t)})
    assert not compare(wrong, (tr, {"x": np.sin(5 * tr)}), abs_tol=bound).passed
