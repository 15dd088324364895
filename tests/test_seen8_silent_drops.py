"""Issue 29, Seen 8: small silent drops become errors naming the thing --
a --poles label given twice, --transfer over a drive coordinate that does
not move, numpy arrays of strings, booleans or objects as parameter
values ('1' and True were refused, their arrays accepted), and the
linearize/modes "no equilibrium" error on stderr."""
import os

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis.poles import transfer
from acausal2d.cli import main
from acausal2d.library import translational
from acausal2d.visual.scene import parse_links
from test_modes_cli import TORQUE_PENDULUM

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MSD = os.path.join(ROOT, "tests", "data", "mass_spring_damper.py")


def test_seen8_a_poles_label_given_twice_is_an_error(tmp_path, capsys):
    assert parse_links("1=ground,2=A0A") == {"1": "ground", "2": "A0A"}
    with pytest.raises(acausal2d.Acausal2dError, match="label 2 is given twice"):
        parse_links("1=ground,2=A0A,2=crank.frame_b")
    code = main(["simulate", MSD, "--poles", "1=ground,1=wall", "--out", str(tmp_path)])
    assert code == 2 and "label 1 is given twice" in capsys.readouterr().err


def test_seen8_transfer_over_a_drive_that_does_not_move_is_an_error(tmp_path, capsys):
    cm = acausal2d.compile_model(acausal2d.load_model(MSD))
    res = cm.simulate(stop_time=0.1, intervals=20)
    with pytest.raises(acausal2d.Acausal2dError, match="wall.flange.s stays at 0"):
        transfer(res, "mass.s", "wall.flange.s", (0, 1))
    # over a moving coordinate: q' = v_q / v_p, here mass.v over mass.s is 1 where v != 0
    curves = transfer(res, "mass.s", "mass.s", (1,))
    moving = np.abs(res["mass.v"]) > 0
    assert np.allclose(curves[1][moving], 1.0, rtol=1e-12, atol=0)
    code = main(["simulate", MSD, "--plot", "mass.s", "--x", "wall.flange.s", "--transfer",
                 "0,1", "--stop-time", "0.1", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2 and "stays at 0" in err and "--x" in err
    assert not list(tmp_path.glob("transfer_*"))


@pytest.mark.parametrize("value", [
    np.array(["1"]), np.array([True]), np.array(["1.0"], dtype=object),
    np.array([None], dtype=object), np.array([1 + 0j]), [True], (1.0, "2")])
def test_seen8_arrays_of_strings_booleans_or_objects_are_refused(value):
    with pytest.raises(acausal2d.Acausal2dError, match="parameter m = .* is not a number"):
        translational.Mass(m=value)
    cm = acausal2d.compile_model(acausal2d.load_model(MSD))
    with pytest.raises(acausal2d.Acausal2dError, match="parameter m = .* is not a number"):
        cm.simulate(params={"mass.m": value}, stop_time=0.01)


@pytest.mark.parametrize("value", [np.array([2.0]), np.array(2.0), np.float32(2.0),
                                   np.array([2.0], dtype=object), [2]])
def test_seen8_numeric_arrays_stay_accepted(value):
    assert translational.Mass(m=value).parameter_value("m") == pytest.approx(2.0)


@pytest.mark.parametrize("command", ["linearize", "modes"])
def test_seen8_no_equilibrium_goes_to_stderr(tmp_path, capsys, command):
    path = tmp_path / "torque_pendulum.py"
    path.write_text(TORQUE_PENDULUM)
    code = main([command, str(path), "--equilibrium", "--out", str(tmp_path / "o")])
    cap = capsys.readouterr()
    assert code == 3
    assert "error: " in cap.err and "has no equilibrium" in cap.err
    assert "no equilibrium" not in cap.out
