"""docs/guide/when-your-model-does-not-run.md shows each message next to
the mistake that causes it: the messages it prints are the ones the code
gives for those mistakes (compared with the whitespace folded)."""
import os
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
DATA = os.path.join(HERE, "data", "user_models")
PAGE = os.path.join(ROOT, "docs", "guide", "when-your-model-does-not-run.md")


def _fold(text):
    return " ".join(text.split())


def _cli(*args, cwd=DATA):
    return subprocess.run([sys.executable, "-m", "acausal2d", *args], capture_output=True,
                          text=True, timeout=600, cwd=cwd)


@pytest.fixture(scope="module")
def page():
    with open(PAGE, encoding="utf-8") as fh:
        return _fold(fh.read())


def test_the_loose_slider_crank_report_is_on_the_page(page):
    out = _cli("check", "slider_crank.py", "--model", "SliderCrankLoose").stdout
    block = out[out.index("  grounded ports:"):out.index("  degree of freedom")]
    assert _fold(block) in page


def test_the_clutch_drive_failure_is_on_the_page(page):
    err = _cli("check", "clutch_drive.py", "--model", "ClutchDriveLoose").stderr
    assert _fold(err.split("State selection failed")[0]) in page


def test_the_set_suggestion_and_the_event_words_are_on_the_page(page, tmp_path):
    err = _cli("simulate", "clutch_drive.py", "--model", "ClutchDrive", "--set",
               "clutch.fnmax=1000", "--out", str(tmp_path / "a")).stderr
    assert _fold(err) in page
    out = _cli("simulate", "brake_release.py", "--native", "off", "--out",
               str(tmp_path / "b")).stdout.splitlines()
    for line in ("  Ramp 'press': condition 'time < startTime' became false at t = 0.5 s",
                 "  no animation: BrakeDemo has no planar geometry to draw (its elements "
                 "declare no shapes, as in a drive train or a hydraulic circuit)"):
        assert line in out and _fold(line) in page
    # the breakaway at 0.505 s: the digits the page shows, not the last ones
    start = "  Brake 'brake': stuck -> starting forward at t = 0.505"
    assert any(line.startswith(start) for line in out) and _fold(start) in page
