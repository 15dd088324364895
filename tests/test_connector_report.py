"""One connector report for every domain: ``check`` lists every unconnected
connector by what happens to it, flags an element that passes power from
a connected side to a loose one, ``simulate`` names them in one line and
warns, and a failed state selection names the loose connectors first.
The user models are those of tests/data/user_models, written as a new user
would from the docs."""
import os
import subprocess
import sys

import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError
from acausal2d.compiler.connectors import connector_report
from acausal2d.library import hydraulics, rotational, signals

HERE = os.path.dirname(os.path.abspath(__file__))
CLUTCH = os.path.join(HERE, "data", "user_models", "clutch_drive.py")
SLIDER = os.path.join(HERE, "data", "user_models", "slider_crank.py")


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "acausal2d", *args], capture_output=True,
                          text=True, timeout=600)


def test_seen2_check_names_the_loose_gear_and_crank_flanges():
    report = acausal2d.check(acausal2d.load_model(SLIDER, "SliderCrankLoose"))
    assert report.connectors.free == ["gear.flange_b", "crankJoint.flange_a"]
    assert report.connectors.held == ["crankJoint.support"]
    assert list(report.grounded) == ["gear.support"]
    assert [s[0] for s in report.connectors.suspects] == ["gear", "crankJoint"]
    text = " ".join(str(report).split())
    assert ("likely mistake: gear passes power between gear.flange_a and gear.flange_b, but "
            "gear.flange_b is connected to nothing") in text
    assert "crankJoint.flange_a is connected to nothing" in text


def test_seen2_the_wired_slider_crank_has_no_likely_mistake():
    report = acausal2d.check(acausal2d.load_model(SLIDER, "SliderCrank"))
    assert report.connectors.free == [] and report.connectors.suspects == []
    assert "likely mistake" not in str(report)


def test_seen2_simulate_warns_about_the_loose_flanges(tmp_path):
    proc = _cli("simulate", SLIDER, "--model", "SliderCrankLoose", "--out",
                str(tmp_path / "out"), "--native", "off", "--stop-time", "0.05")
    assert proc.returncode == 0, proc.stderr
    assert "  unconnected: 1 held by their element (crankJoint.support); 2 free " \
        "(gear.flange_b, crankJoint.flange_a)" in proc.stdout
    assert "warning: gear passes power between gear.flange_a and gear.flange_b, but " \
        "gear.flange_b is connected to nothing" in proc.stderr


def test_seen3_the_failed_state_selection_names_the_loose_flanges_first():
    with pytest.raises(acausal2d.Acausal2dError) as err:
        acausal2d.check(acausal2d.load_model(CLUTCH, "ClutchDriveLoose"))
    text = str(err.value)
    assert text.startswith("Likely cause: gear.flange_b, clutch.flange_a are connected to "
                           "nothing")
    assert text.index("clutch.flange_a") < text.index("State selection failed")
    assert "State selection failed" in str(err.value.__cause__)       # the original, chained


def test_seen3_simulate_names_the_loose_flanges(tmp_path):
    proc = _cli("simulate", CLUTCH, "--model", "ClutchDriveLoose", "--out",
                str(tmp_path / "out"), "--native", "off")
    assert proc.returncode == 2
    assert "error: Likely cause: gear.flange_b, clutch.flange_a are connected to nothing" \
        in proc.stderr


def test_seen4_the_clutch_drive_has_two_position_states():
    """motor.phi (its speed motor.w a state, w == der(phi)) and
    clutch.phi_rel (der(phi_rel) a state): two position states."""
    report = acausal2d.check(acausal2d.load_model(CLUTCH, "ClutchDrive"))
    assert report.states == ["motor.phi", "motor.w", "clutch.phi_rel", "clutch.w_rel"]
    assert report.structural_dof == 2
    assert "degree of freedom: 2 structural (position states)" in str(report)


def test_a_first_order_angle_is_no_position_state():
    """An angle integrated from a speed input (rotational.Speed) has one
    state and no velocity state: 0 position states."""
    class Driven(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.speed = rotational.Speed()
            self.w = signals.Constant(k=2.0)
            self.connect(self.w.y, self.speed.w_in)

    report = acausal2d.check(Driven())
    assert report.states == ["speed.phi"] and report.structural_dof == 0
    assert report.connectors.free == ["speed.flange"]


class _PumpLine(Component):
    """A pump on a volume; ``port_b`` of the pump is left closed."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.drive = rotational.Speed()
        self.w = signals.Constant(k=100.0)
        self.pump = hydraulics.Pump(Vg=1e-5)
        self.tank = hydraulics.PressureSource(p=1e5)
        self.connect(self.w.y, self.drive.w_in)
        self.connect(self.drive.flange, self.pump.flange)
        self.connect(self.tank.port, self.pump.port_a)


def test_a_hydraulic_port_left_open_is_closed_and_flagged():
    model = _PumpLine()
    report = connector_report(model)
    assert report.closed == ["pump.port_b"]
    assert list(report.grounded) == ["pump.support"]
    assert report.suspects == [("pump", ["pump.port_a", "pump.flange"], ["pump.port_b"])]


def test_an_unconnected_signal_input_is_an_error_naming_it():
    class Unfed(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.motor = rotational.Torque()
            self.rotor = rotational.Inertia(J=1.0)
            self.connect(self.motor.flange, self.rotor.flange_a)

    assert connector_report(Unfed()).inputs == ["motor.tau_in"]
    with pytest.raises(ModelDefinitionError, match="motor.tau_in must be connected"):
        acausal2d.check(Unfed())
