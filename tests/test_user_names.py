"""Names as the user writes them: a signal by its connector (``close.y``,
not ``close.y.u``), a state by the variable that equals it
(``clutch.w_rel``, not ``der(clutch.phi_rel)``), a did-you-mean for a
misspelt ``--set`` name, never a deprecated name suggested, and a help
text for every command-line option."""
import argparse
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, RotationalFlange
from acausal2d.cli import build_parser

HERE = os.path.dirname(os.path.abspath(__file__))
CLUTCH = os.path.join(HERE, "data", "user_models", "clutch_drive.py")


@pytest.fixture(scope="module")
def clutch_run():
    return acausal2d.simulate(acausal2d.load_model(CLUTCH, "ClutchDrive"), stop_time=0.4)


def test_a_signal_is_read_by_its_connector_name(clutch_run):
    res = clutch_run
    assert "close.y" in res and "close.y.u" in res
    np.testing.assert_allclose(res["close.y"], res["close.y.u"], rtol=0, atol=1e-15)  # one column
    ramp = np.clip((res.time - 0.3) / 0.05, 0.0, 1.0)          # Ramp(1, 0.05, startTime=0.3)
    assert np.max(np.abs(res["close.y"] - ramp)) <= 1e-12


def test_the_states_are_named_by_the_variables_the_user_declared(clutch_run):
    assert clutch_run.states == ["motor.phi", "motor.w", "clutch.phi_rel", "clutch.w_rel"]


def test_simulate_plots_a_signal_by_its_connector_name(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", CLUTCH, "--model",
                           "ClutchDrive", "--plot", "close.y,clutch.w_rel", "--stop-time", "0.1",
                           "--native", "off", "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert "states: motor.phi, motor.w, clutch.phi_rel, clutch.w_rel" in proc.stdout


def test_a_misspelt_set_name_gets_a_did_you_mean(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", CLUTCH, "--model",
                           "ClutchDrive", "--set", "clutch.fnmax=3", "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 2
    assert "error: unknown parameter 'clutch.fnmax'; did you mean clutch.fn_max" in proc.stderr


def test_a_deprecated_connector_is_never_suggested():
    class Wheel(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.ctrR = RotationalFlange(doc="deprecated: the former flange")
            self.ctrR2 = RotationalFlange(doc="the flange")

    with pytest.raises(AttributeError) as err:
        Wheel().ctrRR
    assert "did you mean 'ctrR2'?" in str(err.value)


def _options(parser, prefix):
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _options(sub, prefix + [name])
        elif not isinstance(action, argparse._HelpAction):
            yield " ".join(prefix), action


def test_every_command_line_option_has_a_help_text():
    missing = ["%s %s" % (cmd, "/".join(a.option_strings) or a.dest)
               for cmd, a in _options(build_parser(), ["acausal2d"]) if not (a.help or "").strip()]
    assert missing == []
