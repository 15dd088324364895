"""Events in the elements' own words ("Brake 'brake': stuck -> sliding
forward at t = 0.5050013 s"), never in CasADi syntax; the raw relations
only with ``--verbose``."""
import os
import subprocess
import sys

import pytest

import acausal2d
from acausal2d.runtime.event_words import check_words, generic_words, is_plain

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BRAKE = os.path.join(HERE, "data", "user_models", "brake_release.py")
CLUTCH = os.path.join(HERE, "data", "user_models", "clutch_drive.py")


def test_the_brake_breaks_away_in_words_at_the_closed_form_time():
    """Torque 5 N m against the capacity 10 f(t) N m, f = 1 - 100 (t - 0.5):
    breakaway at f = 0.5, t = 0.505 s, in Modelica's modes: stuck ->
    starting forward -> sliding forward.  The event is located to IDA's
    root tolerance; the bound 1e-6 s leaves room for the time grid's
    rounding (2e-6 of the time)."""
    res = acausal2d.simulate(acausal2d.load_model(BRAKE))
    texts = [w for _, w in res.event_texts]
    start = texts.index("Brake 'brake': stuck -> starting forward")
    assert texts[start + 1] == "Brake 'brake': starting forward -> sliding forward"
    assert abs(res.event_texts[start][0] - 0.505) <= 1e-6
    assert len(res.event_texts) == len(res.events)       # raw relations kept beside
    assert any("brake.startForward" in raw for _, raw in res.events)


@pytest.mark.parametrize("path,model", [
    (BRAKE, None), (CLUTCH, "ClutchDrive"),
    (os.path.join(ROOT, "models", "clutch_motor.py"), "ClutchMotorConstantLoad"),
    (os.path.join(ROOT, "models", "hydraulic_drum_drive.py"), None),
])
def test_no_event_text_contains_casadi_syntax(path, model):
    res = acausal2d.simulate(acausal2d.load_model(path, model), stop_time=1.0)
    assert res.event_texts, "the model has events"
    for _, text in res.event_texts:
        assert check_words(text), text
        assert "?" not in text and "@" not in text and "rel" not in text.split()


def test_the_clutch_drive_locks_in_words():
    res = acausal2d.simulate(acausal2d.load_model(CLUTCH, "ClutchDrive"))
    texts = [w for _, w in res.event_texts]
    assert "Clutch 'clutch': sliding backward -> stuck" in texts
    assert "Ramp 'close': condition 'time < (startTime+duration)' became false" in texts


def test_verbose_prints_the_relations_and_the_default_does_not(tmp_path):
    def run(*extra):
        return subprocess.run([sys.executable, "-m", "acausal2d", "simulate", BRAKE, "--out",
                               str(tmp_path / ("o%d" % len(extra))), "--native", "off",
                               *extra], capture_output=True, text=True, timeout=600)
    plain, verbose = run(), run("--verbose")
    assert plain.returncode == verbose.returncode == 0
    assert "  Brake 'brake': stuck -> starting forward at t = 0.505" in plain.stdout
    assert "relations:" not in plain.stdout and "brake.startForward" not in plain.stdout
    assert "      relations: sliding forward (brake.startForward/Forward)" in verbose.stdout


def test_plain_conditions_read_as_written_and_others_by_their_variables():
    assert is_plain("time < (startTime+duration)") and is_plain("delta <= 0")
    assert not is_plain("min(((rel3?(w/w_s):0)+((!rel3)?-1:0)), 1)")
    assert not is_plain("@1=sq(x), (@1+y)")
    assert not check_words("min(((rel3?(brake.w/brake.w_s):0)+((!rel3)?-1:0)), 1)")


class _System:
    """The two attributes generic_words reads, for one relation."""

    class _Rel:
        def __init__(self, text, g):
            self.text, self.g = text, g

    def __init__(self, text, g, names):
        self.relations, self.names = [self._Rel(text, g)], names


def test_generic_words_name_the_condition_or_its_variables():
    import casadi as ca
    w, w_s = ca.SX.sym("brake.w"), ca.SX.sym("brake.w_s")
    plain = _System("max(brake.fn, 0)", ca.SX.sym("brake.fn"), ("brake.fn",))
    assert generic_words(plain, 0, 1.0, "brake") == "condition 'fn > 0' became true"
    nested = _System("min(((rel0?(brake.w/brake.w_s):0)+((!rel0)?-1:0)), 1)", w / w_s,
                     ("brake.w",))
    assert generic_words(nested, 0, 0.0, "brake") == "its condition on w switched (now false)"
