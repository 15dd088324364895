"""The command line through its real entry point (subprocess)."""
import csv
import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# the subsampled Dymola reference shipped with the repository (tests/data/references)
SHARED_REF = os.path.join(ROOT, "tests", "data", "references", "PistonEngine.csv")


def run(*args):
    # the entry point installed with this interpreter (a virtualenv's bin/),
    # not another installation that happens to come first on PATH
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def engine_out(tmp_path_factory):
    out = tmp_path_factory.mktemp("engine")
    proc = run("simulate", os.path.join(ROOT, "models", "piston_engine.py"), "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    return out, proc


def test_simulate_writes_csv_plots_and_animation(engine_out):
    out, proc = engine_out
    assert "PistonEngine: simulated 10 s" in proc.stdout
    with open(out / "result.csv") as fh:
        rows = list(csv.reader(fh))
    assert rows[0][0] == "time"
    assert "revoluteDrive.phi" in rows[0]
    assert len(rows) == 5002                      # header + 5001 output points
    k = rows[0].index("revoluteDrive.phi")
    assert float(rows[-1][k]) == pytest.approx(-16.8149394961727, abs=2e-3)
    pngs = sorted(p.name for p in out.glob("*.png"))
    assert "revoluteDrive.phi.png" in pngs
    assert (out / "revoluteDrive.phi.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    html = (out / "animation.html").read_text()
    assert "<canvas" in html and "<script src" not in html


def test_summary_line_counts_steps_and_evaluations(engine_out):
    import re
    _, proc = engine_out
    m = re.search(r"(\d+) steps, (\d+) output points, (\d+) events, (\d+) state "
                  r"re-selections, (\d+) residual evaluations", proc.stdout)
    assert m, proc.stdout
    steps, points, events, _, nfev = (int(g) for g in m.groups())
    assert points == 5001 and events == 0
    # IDA takes many steps over 10 s of a spinning crank; each needs residuals
    assert 100 < steps < nfev
    assert "3 plots" in proc.stdout


@pytest.mark.parametrize("args,message", [
    (["--stop-time", "-1"], "stop_time (-1 s) must be larger than start_time (0 s)"),
    (["--stop-time", "0"], "stop_time (0 s) must be larger than start_time (0 s)"),
    (["--intervals", "0"], "intervals must be a whole number of at least 1, got 0"),
    (["--rtol", "0"], "rtol must be between 0 and 0.1 (a relative tolerance, e.g. 1e-6), got 0"),
], ids=["negative-stop", "zero-stop", "no-intervals", "zero-rtol"])
def test_bad_numbers_are_errors_with_exit_code_2(tmp_path, args, message):
    proc = run("simulate", os.path.join(ROOT, "models", "pendulum.py"),
               "--out", str(tmp_path / "o"), *args)
    assert proc.returncode == 2
    assert message in proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout


def test_out_on_an_existing_file_is_an_error_before_simulating(tmp_path):
    blocker = tmp_path / "taken"
    blocker.write_text("not a folder")
    proc = run("simulate", os.path.join(ROOT, "models", "pendulum.py"), "--out", str(blocker))
    assert proc.returncode == 2
    assert proc.stderr.startswith("error: ") and "taken" in proc.stderr
    assert "Traceback" not in proc.stderr and "simulated" not in proc.stdout


def test_trace_of_a_frame_and_of_a_signal_pair(tmp_path):
    """Coupler curves: the crank pin (a frame) and the dyad's point P (no
    frame of its own: its x, y signals) are traced in the animation."""
    import json
    import re
    proc = run("simulate", os.path.join(ROOT, "models", "four_link_mechanisms.py"),
               "--model", "DDDD", "--out", str(tmp_path), "--stop-time", "0.5",
               "--trace", "crank.ctr2D2, dyad.xP:dyad.yP")
    assert proc.returncode == 0, proc.stderr
    html = (tmp_path / "animation.html").read_text()
    data = json.loads(re.search(r'<script id="acausal2d-data" type="application/json">(.*?)'
                                r'</script>', html, re.S).group(1))
    traces = [(s["x"], s["y"]) for s in data["shapes"] if s["type"] == "trace"]
    assert ("crank.ctr2D2.x", "crank.ctr2D2.y") in traces
    assert ("dyad.xP", "dyad.yP") in traces
    # the traced point moves on the rocker's circle about B0 = (0.4, 0), radius 0.3
    x, y = (np.asarray(data["signals"][n], dtype=float) for n in ("dyad.xP", "dyad.yP"))
    np.testing.assert_allclose(np.hypot(x - 0.4, y), 0.3, atol=1e-6)


def test_unknown_trace_is_an_error_before_simulating(tmp_path):
    proc = run("simulate", os.path.join(ROOT, "models", "four_link_mechanisms.py"),
               "--model", "DDDD", "--out", str(tmp_path), "--trace", "dyad.P")
    assert proc.returncode == 2
    assert "cannot trace 'dyad.P'" in proc.stderr and "dyad.ctr2D3" in proc.stderr
    assert "simulated" not in proc.stdout and "Traceback" not in proc.stderr


def test_simulate_with_parameter_and_stop_time(tmp_path):
    proc = run("simulate", os.path.join(ROOT, "models", "pendulum.py"), "--out", str(tmp_path),
               "--stop-time", "0.5", "--set", "body.m=2", "--set", "rod.r=0.5,0")
    assert proc.returncode == 0, proc.stderr
    with open(tmp_path / "result.csv") as fh:
        rows = list(csv.reader(fh))
    assert float(rows[-1][0]) == pytest.approx(0.5)
    assert float(rows[1][rows[0].index("body.frame_a.x")]) == pytest.approx(0.5)


def test_check_explains_a_driven_mechanism_s_dof():
    proc = run("check", os.path.join(ROOT, "models", "four_link_mechanisms.py"), "--model", "DDDD")
    assert proc.returncode == 0, proc.stderr
    assert ("degree of freedom: 1 by Ebert (2015) eq. 2.1 (n = 4 links with ground, g = 4 joints), "
            "0 structural (position states)") in proc.stdout
    assert "(1 prescribed: drives that give the motion as a function of time" in proc.stdout


def test_check_prints_structure_and_both_dof_counts():
    proc = run("check", os.path.join(ROOT, "models", "piston_engine.py"))
    assert proc.returncode == 0, proc.stderr
    out = proc.stdout
    assert "states:            revoluteDrive.phi, revoluteDrive.w" in out
    assert "structural index:  3" in out
    assert "closed loops:      1" in out
    assert ("degree of freedom: 1 by Ebert (2015) eq. 2.1 (n = 4 links with ground, g = 4 joints), "
            "1 structural") in out


def test_compare_passes_against_shared_reference(engine_out, tmp_path):
    out, _ = engine_out
    proc = run("compare", str(out / "result.csv"), SHARED_REF, "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "revoluteDrive.phi" in proc.stdout and "PASS" in proc.stdout
    assert (tmp_path / "revoluteDrive.phi.png").exists()


def test_compare_fails_on_perturbed_signal(engine_out, tmp_path):
    out, _ = engine_out
    with open(out / "result.csv") as fh:
        rows = list(csv.reader(fh))
    k = rows[0].index("revoluteDrive.w")
    ref = tmp_path / "reference.csv"
    with open(ref, "w", newline="") as fh:
        w = csv.writer(fh, quoting=csv.QUOTE_NONNUMERIC)
        w.writerow(["Time", "revoluteDrive.phi", "revoluteDrive.w"])
        for i, row in enumerate(rows[1::10]):
            wv = float(row[k]) + (5e-3 if i == 200 else 0.0)
            w.writerow([float(row[0]), float(row[rows[0].index("revoluteDrive.phi")]), wv])
    proc = run("compare", str(out / "result.csv"), str(ref))
    assert proc.returncode == 1
    lines = {ln.split()[0]: ln for ln in proc.stdout.splitlines() if ln.strip()}
    assert "FAIL" in lines["revoluteDrive.w"]
    assert "PASS" in lines["revoluteDrive.phi"]
    assert "5.0000e-03" in lines["revoluteDrive.w"]


BROKEN_UNBALANCED = textwrap.dedent('''
    from acausal2d import Component, Variable, der

    class Broken(Component):
        x = Variable()
        y = Variable()

        def equations(self):
            return [der(self.x) == -self.x]
''')

BROKEN_UNCONNECTED = textwrap.dedent('''
    from acausal2d import Component, start
    from acausal2d.library.rotational import Inertia, Torque

    class Broken(Component):
        def __init__(self):
            super().__init__()
            self.inertia = Inertia(phi=start(0, fixed=True), w=start(0, fixed=True))
            self.torque = Torque()
            self.connect(self.torque.flange, self.inertia.flange_a)
''')


@pytest.mark.parametrize("source,message", [
    (BROKEN_UNBALANCED, "under-determined: 1 equations for 2 unknowns"),
    (BROKEN_UNCONNECTED, "connector torque.tau_in must be connected"),
], ids=["unbalanced", "unconnected"])
@pytest.mark.parametrize("command", ["simulate", "check"])
def test_broken_model_gives_error_and_exit_code_2(tmp_path, source, message, command):
    path = tmp_path / "broken.py"
    path.write_text(source)
    args = [command, str(path)] + (["--out", str(tmp_path / "o")] if command == "simulate" else [])
    proc = run(*args)
    assert proc.returncode == 2
    assert proc.stderr.startswith("error: ")
    assert message in proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout


def test_simulated_animation_draws_in_browser(engine_out, tmp_path):
    """The animation page written by `acausal2d simulate` for the piston
    engine, opened in headless Chromium at two frames: the mechanism is drawn
    (non-blank canvas with steel-blue links), scrubbing to another frame
    changes the picture, and the console stays silent.  Screenshots are kept
    in tests/artifacts/engine_frame*.png."""
    from test_animation import assert_canvas_drawn, assert_differ, screenshot_frames
    out, _ = engine_out
    first, later = screenshot_frames(out / "animation.html", (0, 150), tmp_path, "engine")
    assert_canvas_drawn(first, "frame 0")
    assert_canvas_drawn(later, "frame 150")
    assert_differ(first, later)
