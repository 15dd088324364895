"""Plots through the real entry point and the Python API: units in every
axis label (read back from SVG files and Figure objects), overlay groups on
one axes with a legend, any signal as x axis, the model name in the title,
model-declared figures (the belt drive over its drive angle) and studies
(the pulley block's efficiency sweep over mu)."""
import csv
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from conftest import load_model_class, assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")


def run(*args):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=600)


def svg_texts(path):
    """The texts of an SVG written by matplotlib (each text element carries
    its string in a comment)."""
    return re.findall(r"<!-- (.*?) -->", path.read_text())


def test_cli_plots_carry_units_and_model_name(tmp_path):
    proc = run("simulate", os.path.join(MODELS, "pendulum.py"), "--stop-time", "1",
               "--plot", "revolute.phi,body.phi;revolute.w;body.frame_a.fx,body.frame_a.fy",
               "--format", "svg", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    angles = svg_texts(tmp_path / "revolute.phi_body.phi.svg")
    assert "phi [rad]" in angles and "time [s]" in angles and "Pendulum" in angles
    assert "revolute.phi" in angles and "body.phi" in angles        # the legend
    assert "revolute.w [rad/s]" in svg_texts(tmp_path / "revolute.w.svg")
    forces = svg_texts(tmp_path / "body.frame_a.fx_body.frame_a.fy.svg")
    assert "[N]" in forces
    assert "3 plots" in proc.stdout


def test_overlay_is_one_axes_with_n_lines_and_a_legend():
    cm = acausal2d.compile_model(load_model_class("pulley_block.py", "PulleyBlock")())
    res = cm.simulate(stop_time=1.0, output_times=np.linspace(0, 1, 101))
    names = ["rope%d.F" % k for k in range(1, 6)]
    fig = res.plot(names, title="rope forces")
    assert len(fig.axes) == 1
    ax = fig.axes[0]
    assert [ln.get_label() for ln in ax.get_lines()] == names
    assert [t.get_text() for t in ax.get_legend().get_texts()] == names
    assert ax.get_ylabel() == "F [N]" and ax.get_xlabel() == "time [s]"
    assert fig._suptitle.get_text() == "PulleyBlock: rope forces"
    assert_copied(ax.get_lines()[2].get_ydata(), res["rope3.F"])
    # signals of another unit get their own axes below, sharing x
    fig2 = res.plot(["rope1.F", "load.y"])
    assert [a.get_ylabel() for a in fig2.axes] == ["rope1.F [N]", "load.y [m]"]


def test_x_axis_signal_unwrapped_in_degrees(tmp_path, compiled_model):
    proc = run("simulate", os.path.join(MODELS, "piston_engine.py"), "--x", "revoluteDrive.phi",
               "--plot", "revoluteDrive.w", "--format", "svg", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    texts = svg_texts(tmp_path / "revoluteDrive.w.svg")
    assert "revoluteDrive.phi [deg]" in texts and "revoluteDrive.w [rad/s]" in texts
    res = compiled_model("piston_engine.py", "PistonEngine").simulate(stop_time=10.0)
    fig = res.plot(["revoluteDrive.w"], x="revoluteDrive.phi")
    x = fig.axes[0].get_lines()[0].get_xdata()
    np.testing.assert_allclose(x, np.degrees(res["revoluteDrive.phi"]), rtol=0, atol=1e-9)
    assert x[-1] == pytest.approx(np.degrees(-16.8149394961727), abs=0.2)   # 2.7 turns
    bad = run("simulate", os.path.join(MODELS, "piston_engine.py"), "--x", "crank.nope",
              "--out", str(tmp_path))
    assert bad.returncode == 2 and "--x: no signal 'crank.nope'" in bad.stderr


def test_belt_drive_figures_over_the_drive_angle(tmp_path):
    proc = run("simulate", os.path.join(MODELS, "noncircular_belt_drive.py"), "--format", "svg",
               "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert "2 plots" in proc.stdout
    ratio = svg_texts(tmp_path / "ratio.svg")
    spans = svg_texts(tmp_path / "span_forces.svg")
    assert "small.phi_rel [deg]" in ratio and "small.phi_rel [deg]" in spans
    assert "upper.F" in spans and "lower.F" in spans and "F [N]" in spans
    assert "NonCircularBeltDrive: transmission ratio over the drive angle (Bild 7.27)" in ratio
    # the x axis runs over two turns of the small pulley (360 deg/s for 2 s)
    with open(tmp_path / "result.csv") as fh:
        rows = list(csv.reader(fh))
    k = rows[0].index("small.phi_rel")
    assert np.degrees(float(rows[-1][k])) == pytest.approx(720.0, abs=1e-6)


def test_pulley_block_mu_study_from_the_cli(tmp_path):
    """``acausal2d study`` runs the model's efficiency sweep on a local Dask
    cluster; the efficiencies follow the quasi-static closed form."""
    quasi_static_forces = load_model_class("pulley_block.py", "quasi_static_forces")
    proc = run("study", os.path.join(MODELS, "pulley_block.py"), "efficiency", "--workers", "2",
               "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "pulley_block_efficiency.png").read_bytes()[:4] == b"\x89PNG"
    with open(tmp_path / "pulley_block_efficiency.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 11 and {r["status"] for r in rows} == {"ok"}
    for r in rows:
        mu = float(r["U1.mu,L2.mu,U3.mu,L4.mu"])
        T = quasi_static_forces(mu)
        assert float(r["efficiency"]) == pytest.approx(100 * 9.81 / (4 * T[0]), rel=2e-3)
        assert float(r["utilisation"]) == pytest.approx(T[4] / T[0], rel=2e-3)
    listed = run("study", os.path.join(MODELS, "pulley_block.py"), "--list")
    assert listed.returncode == 0 and listed.stdout.startswith("efficiency")
    bad = run("study", os.path.join(MODELS, "pulley_block.py"), "nope", "--out", str(tmp_path))
    assert bad.returncode == 2 and "has no study 'nope'; its studies: efficiency" in bad.stderr
