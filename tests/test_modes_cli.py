"""``acausal2d linearize`` and ``acausal2d modes`` (issue 21): the files
they write, their numbers against closed forms, and the exit codes of a
model without equilibrium (3), a kinematically driven model and a bad
option (2)."""
import csv
import json
import math
import os

import numpy as np

from acausal2d import cli
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")

TORQUE_PENDULUM = '''
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute
from acausal2d.library.rotational import ConstantTorque


class TorquePendulum(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True),
                                 use_flange=True)
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.drive = ConstantTorque(tau_constant=15.0)      # more than m g d = 9.81 N.m
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)
        self.connect(self.drive.flange, self.revolute.flange_a)
'''


def test_modes_command_writes_table_json_and_page(tmp_path, capsys):
    out = str(tmp_path / "modes")
    code = cli.main(["modes", os.path.join(MODELS, "pendulum.py"), "--equilibrium", "--out", out])
    text = capsys.readouterr().out
    assert code == 0, text
    data = json.load(open(os.path.join(out, "modes.json")))
    (mode,) = data["modes"]
    # body m = 1 at d = 1 with I = 0.1: omega = sqrt(m g d / (I + m d^2))
    assert abs(mode["frequency_hz"] / (math.sqrt(9.81 / 1.1) / (2 * math.pi)) - 1) < 1e-9
    assert data["rigid_body_modes"] == 0 and "revolute.phi" in mode["shape"]
    assert os.path.getsize(os.path.join(out, "modes.html")) > 10000
    assert "static equilibrium" in text and "0.475" in text


def test_linearize_command_writes_json_and_csv(tmp_path, capsys):
    out = str(tmp_path / "lin")
    code = cli.main(["linearize", os.path.join(MODELS, "pendulum.py"), "--equilibrium",
                     "--set", "body.m=2", "--outputs", "body.x", "--out", out])
    assert code == 0, capsys.readouterr()
    data = json.load(open(os.path.join(out, "linear.json")))
    assert data["states"] == ["revolute.phi", "der(revolute.phi)"]
    # m = 2, d = 1, I = 0.1: der(w) = -m g d / (I + m d^2) phi at the bottom
    assert np.allclose(data["A"], [[0, 1], [-2 * 9.81 / 2.1, 0]], rtol=1e-12, atol=1e-12)
    assert np.allclose(data["C"], [[1.0, 0.0]], rtol=1e-12, atol=1e-12)
    assert data["units"]["revolute.phi"] == "rad"
    assert data["point"]["kind"] == "equilibrium"
    rows = list(csv.reader(open(os.path.join(out, "A.csv"))))
    assert rows[0] == ["", "revolute.phi", "der(revolute.phi)"]
    assert_copied(float(rows[2][1]), data["A"][1][0])     # CSV and JSON, 17 digits


def test_no_equilibrium_exits_3_and_bad_options_2(tmp_path, capsys):
    path = tmp_path / "torque_pendulum.py"
    path.write_text(TORQUE_PENDULUM)
    code = cli.main(["modes", str(path), "--equilibrium", "--out", str(tmp_path / "o")])
    assert code == 3
    assert "TorquePendulum has no equilibrium" in capsys.readouterr().err   # issue 29, Seen 8
    code = cli.main(["modes", str(path), "--start", "revolute.phi=1", "--out",
                     str(tmp_path / "o")])
    assert code == 2 and "add --equilibrium" in capsys.readouterr().err
    code = cli.main(["modes", os.path.join(MODELS, "four_link_mechanisms.py"), "--model",
                     "DDDD", "--at", "0.1", "--out", str(tmp_path / "o")])
    assert code == 2 and "kinematically driven" in capsys.readouterr().err


def test_modes_campbell_of_the_four_bar_follows_its_reduced_inertia(tmp_path, capsys):
    import sys
    sys.path.insert(0, MODELS)
    import four_bar_modes as fb
    out = str(tmp_path / "campbell")
    code = cli.main(["modes", os.path.join(MODELS, "four_bar_modes.py"), "--equilibrium",
                     "--vary", "hold.phi0=0.5:4.5:3", "--count", "1", "--out", out])
    assert code == 0, capsys.readouterr()
    rows = list(csv.DictReader(open(os.path.join(out, "campbell.csv"))))
    assert [r["status"] for r in rows] == ["ok"] * 3
    for r in rows:
        phi = float(r["hold.phi0"])
        expected = math.sqrt(fb.C_SHAFT / fb.reduced_inertia(phi)) / (2 * math.pi)
        assert abs(float(r["f1"]) / expected - 1) < 1e-9
    assert os.path.getsize(os.path.join(out, "campbell.png")) > 5000


def test_at_with_equilibrium_and_a_bad_time(tmp_path, capsys):
    code = cli.main(["modes", os.path.join(MODELS, "pendulum.py"), "--equilibrium", "--at",
                     "0.5", "--out", str(tmp_path / "o")])
    assert code == 0 and "static equilibrium" in capsys.readouterr().out
    code = cli.main(["linearize", os.path.join(MODELS, "pendulum.py"), "--at", "-1", "--out",
                     str(tmp_path / "o")])
    assert code == 2 and "--at must be a time >= 0" in capsys.readouterr().err


FORCED_MASS = os.path.join(ROOT, "tests", "data", "forced_mass.py")


def test_linearize_with_a_top_level_input(tmp_path, capsys):
    out = str(tmp_path / "lin")
    code = cli.main(["linearize", FORCED_MASS, "--equilibrium", "--set", "u_source.k=20",
                     "--inputs", "u", "--out", out])
    assert code == 0, capsys.readouterr()
    data = json.load(open(os.path.join(out, "linear.json")))
    j = data["states"].index("mass.v")
    assert data["inputs"] == ["u"] and abs(data["B"][j][0] - 0.25) < 1e-12
    assert abs(data["point"]["values"]["mass.s"] - 0.2) < 1e-12      # u / c
    assert data["outputs"] == ["mass.s"]
    assert_copied(data["D"], [[0.0]])             # a structural zero of the Jacobian
