"""Issue 18 (compare bullet): Body's accelerations ax, ay and angular
acceleration z (PlanarMechanics' a[1], a[2], z), Revolute's z, Prismatic's
a and IdealRolling's ax, z are signals of every run (Result and
result.csv), read exactly from the derivatives index reduction made (no new
equations), and compare maps the Modelica names a[1]/a[2] to them.

Expected values are closed forms (free fall, uniform rotation, the
pendulum's equation of motion, a body falling along a guide) or, for the
SpringDamperDemo reference, accelerations computed by Newton's law from
Dymola's positions and velocities -- never by the code under test."""
import csv
import importlib.util
import math
import os

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.analysis.compare_inputs import modelica_counterpart
from acausal2d.cli import main
from acausal2d.io.tables import read_csv
from acausal2d.library.planar import (Body, BodyShape, Fixed, FixedTranslation, IdealRolling,
                                      PlanarWorld, Prismatic, Revolute, modelica_names)

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, os.pardir, "models", "planar_examples.py")
ADD = os.path.join(HERE, "data", "references", "add_accelerations.py")
G = 9.81


class FreeFall(Component):
    """A free body and a free BodyShape thrown: ax = 0, ay = -g, z = 0."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.body = Body(m=2.0, I=0.3, x=start(0.0, fixed=True), y=start(0.0, fixed=True),
                         phi=start(0.0, fixed=True), vx=start(1.5, fixed=True),
                         vy=start(2.0, fixed=True), w=start(0.7, fixed=True))
        self.link = BodyShape(m=1.0, I=0.2, x=start(0.0, fixed=True), y=start(1.0, fixed=True),
                              phi=start(0.4, fixed=True), vx=start(-1.0, fixed=True),
                              vy=start(0.0, fixed=True), w=start(2.0, fixed=True))


class Spinner(Component):
    """Without gravity a body on a rod of length L turns at constant w."""
    L, W, GRAVITY = 0.8, 3.0, (0.0, 0.0)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.world = PlanarWorld(g=self.GRAVITY)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.3, fixed=True), w=start(self.W, fixed=True))
        self.rod = FixedTranslation(r=(self.L, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


class Pendulum(Spinner):
    """The Spinner under gravity (started turning at 3 rad/s)."""
    GRAVITY = (0.0, -G)


class Guide(Component):
    """A body falling along a vertical Prismatic guide: a = -g."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.prismatic = Prismatic(r=(0.0, 1.0), s=start(0.0, fixed=True),
                                   v=start(0.5, fixed=True))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.prismatic.frame_a)
        self.connect(self.prismatic.frame_b, self.body.frame_a)


def test_free_fall_accelerations_are_exact():
    res = acausal2d.simulate(FreeFall(), stop_time=1.0, intervals=20)
    assert np.max(np.abs(res["body.ax"])) <= 1e-12
    assert np.max(np.abs(res["body.ay"] + G)) <= 1e-12
    assert np.max(np.abs(res["body.z"])) <= 1e-12
    assert np.max(np.abs(res["link.ax"])) <= 1e-12
    assert np.max(np.abs(res["link.ay"] + G)) <= 1e-12
    assert np.max(np.abs(res["link.z"])) <= 1e-12
    assert res.unit("body.ax") == "m/s2" and res.unit("body.z") == "rad/s2"


def test_uniform_rotation_gives_centripetal_acceleration():
    """a = -w^2 r at every output point (r the body's position)."""
    res = acausal2d.simulate(Spinner(), stop_time=2.0, intervals=40, rtol=1e-10)
    w2 = Spinner.W ** 2
    phi = 0.3 + Spinner.W * res.time
    assert np.max(np.abs(res["body.ax"] + w2 * Spinner.L * np.cos(phi))) < 1e-10
    assert np.max(np.abs(res["body.ay"] + w2 * Spinner.L * np.sin(phi))) < 1e-10
    assert np.max(np.abs(res["revolute.z"])) < 1e-9
    assert np.max(np.abs(res["body.z"])) < 1e-9


def test_pendulum_angular_acceleration_follows_its_equation_of_motion():
    """(I + m L^2) z = -m g L cos(phi) at each output point; the body's
    acceleration is the rigid-rotation kinematics -L w^2 e_r + L z e_t."""
    res = acausal2d.simulate(Pendulum(), stop_time=2.0, intervals=50, rtol=1e-10)
    m, I, L = 1.0, 0.1, Spinner.L
    phi, w, z = res["revolute.phi"], res["revolute.w"], res["revolute.z"]
    assert np.max(np.abs(z + m * G * L * np.cos(phi) / (I + m * L * L))) < 1e-8
    ax = -L * w ** 2 * np.cos(phi) - L * z * np.sin(phi)
    ay = -L * w ** 2 * np.sin(phi) + L * z * np.cos(phi)
    assert np.max(np.abs(res["body.ax"] - ax)) < 1e-8
    assert np.max(np.abs(res["body.ay"] - ay)) < 1e-8
    assert np.max(np.abs(res["body.z"] - z)) < 1e-12


def test_prismatic_guide_acceleration_is_minus_g():
    res = acausal2d.simulate(Guide(), stop_time=1.0, intervals=20)
    assert np.max(np.abs(res["prismatic.a"] + G)) <= 1e-12
    assert np.max(np.abs(res["body.ay"] + G)) <= 1e-12
    assert np.max(np.abs(res["body.ax"])) <= 1e-12


def test_rolling_wheel_accelerations_on_a_slope():
    """IdealRolling's ax = g sin(alpha) / (1 + I/(m R^2)) and z = -ax/R."""
    from test_planar_closed_forms import WheelOnSlope
    alpha, radius, m, inertia = 0.3, 0.3, 2.0, 0.05
    res = acausal2d.simulate(WheelOnSlope(alpha, radius, m, inertia), stop_time=1.0,
                             intervals=20, rtol=1e-10)
    acc = G * math.sin(alpha) / (1 + inertia / (m * radius ** 2))
    assert np.max(np.abs(res["rolling.ax"] - acc)) < 1e-9
    assert np.max(np.abs(res["rolling.z"] + acc / radius)) < 1e-9
    assert np.max(np.abs(res["body.ax"] - acc)) < 1e-9
    assert np.max(np.abs(res["body.ay"])) < 1e-9


def test_derived_signals_add_no_equations():
    """The DAE is the same: derived signals are columns, not unknowns."""
    cm = acausal2d.compile_model(Pendulum())
    assert not any(n.endswith((".ax", ".ay", ".z", ".a")) for n in cm.system.names)
    assert {"body.ax", "body.ay", "body.z", "revolute.z"} <= set(cm.names)


def test_seen_3_modelica_acceleration_names_are_declared():
    table = modelica_names()
    assert "ax" in table["a[1]"] and "ay" in table["a[2]"]
    assert BodyShape.modelica_names["body.a[1]"] == "ax"
    ours = {"crank.ax", "crank.phi", "body.ay", "revolute.z"}
    assert modelica_counterpart("crank.body.a[1]", ours) == "crank.ax"
    assert modelica_counterpart("crank.body.phi", ours) == "crank.phi"
    assert modelica_counterpart("body.a[2]", ours) == "body.ay"
    assert IdealRolling.derived_signals["z"][0] == "der(w)"


def _newton_reference(path):
    """SpringDamperDemo.csv plus body.a[1], body.a[2] from Newton's law on
    Dymola's own r and v (tests/data/references/add_accelerations.py, which
    uses nothing of acausal2d)."""
    spec = importlib.util.spec_from_file_location("add_accelerations", ADD)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.main(str(path))


def test_seen_3_spring_damper_demo_compares_accelerations(tmp_path, capfd):
    out = tmp_path / "sdd"
    assert main(["simulate", MODELS, "--model", "SpringDamperDemo", "--out", str(out)]) == 0
    result_csv = str(out / "result.csv")
    t, cols = read_csv(result_csv)
    for name in ("body.ax", "body.ay", "body.z"):
        assert name in cols
    # closed form x = -1 + e^-t (2 cos 3t + 2/3 sin 3t): x'' = -20 e^-t (cos 3t - 1/3 sin 3t)
    ax = -20 * np.exp(-t) * (np.cos(3 * t) - np.sin(3 * t) / 3)
    assert np.max(np.abs(cols["body.ax"] - ax)) < 1e-6
    ref = _newton_reference(tmp_path / "SpringDamperDemo_a.csv")
    capfd.readouterr()
    assert main(["compare", result_csv, ref]) == 0
    text = capfd.readouterr().out
    assert "8 of 8 signals passed" in text
    assert "body.a[1] -> body.ax" in text and "body.a[2] -> body.ay" in text
    cmp = acausal2d.compare(result_csv, ref)
    assert cmp.passed and not cmp.unmatched
    dev = {r.name: r.max_deviation for r in cmp.rows}
    assert dev["body.a[1]"] < 2e-3 and dev["body.a[2]"] < 2e-3
    # an acceleration off by 0.1 m/s^2 fails
    bad = tmp_path / "bad.csv"
    rows = list(csv.reader(open(ref, encoding="utf-8")))
    j = rows[0].index("body.a[1]")
    for row in rows[1:]:
        row[j] = repr(float(row[j]) + 0.1)
    with open(bad, "w", newline="", encoding="utf-8") as fh:
        csv.writer(fh).writerows(rows)
    assert not acausal2d.compare(result_csv, str(bad)).passed
    assert math.isfinite(dev["body.a[1]"])
