"""One RunOptions (issue 34): the settings of a run are checked in one
place, give one error naming the option with the same text from the API and
the command line, have their defaults in one place, and an API call that
gets both ``options=`` and a keyword says so."""
import dataclasses
import os
import pathlib
import re

import pytest

import acausal2d
from acausal2d import RunOptions
from acausal2d.cli import main
from acausal2d.options import DEFAULTS, RunOptionError
from conftest import MODELS, ROOT, assert_copied, same_time

PENDULUM = os.path.join(MODELS, "pendulum.py")

BAD = [("stop_time", "soon", "--stop-time"), ("stop_time", float("inf"), "--stop-time"),
       ("stop_time", -1.0, "--stop-time"), ("rtol", 0.0, "--rtol"), ("rtol", 0.5, "--rtol"),
       ("rtol", "tight", "--rtol"), ("atol", 0.0, "--atol"), ("intervals", 0, "--intervals"),
       ("intervals", 2.5, "--intervals"), ("max_steps", 0, "--max-steps"),
       ("max_wall_time", -1.0, "--max-wall-time")]


def _error(**kw):
    with pytest.raises(RunOptionError) as exc:
        RunOptions(**kw)
    return exc.value


@pytest.mark.parametrize("name,value,flag", BAD, ids=["%s=%s" % b[:2] for b in BAD])
def test_a_bad_value_is_one_error_naming_the_option_in_api_and_cli(name, value, flag, tmp_path,
                                                                   capfd):
    err = _error(**{name: value})
    assert err.option == name and str(err).startswith(name + " ")
    # the API's functions raise the same error, before anything is compiled or run
    with pytest.raises(RunOptionError) as api:
        acausal2d.simulate(PENDULUM, **{name: value})
    assert str(api.value) == str(err)
    # the command line: exit 2 and the same text after the flag, nothing written
    text = "nan" if value != value else str(value)
    out = tmp_path / "out"
    assert main(["simulate", PENDULUM, flag, text, "--out", str(out)]) == 2
    stderr = capfd.readouterr().err
    assert stderr.strip() == "error: %s: %s" % (flag, err), stderr
    assert not (out / "result.csv").exists()


@pytest.mark.parametrize("command", [
    ["sweep", PENDULUM, "--vary", "body.m=1,2", "--scheduler", "serial"],
    ["optimize", PENDULUM, "--vary", "body.m=1:0.5:2", "--objective", "final(revolute.phi)"],
    ["fit", PENDULUM, "--data", os.path.join(ROOT, "tests", "data", "nothing.csv"), "--free",
     "body.m=1"],
])
def test_every_command_declares_rtol_once_with_the_same_check(command, tmp_path, capfd):
    assert main(command + ["--rtol", "0.5", "--out", str(tmp_path / "out")]) == 2
    assert "--rtol: %s" % _error(rtol=0.5) in capfd.readouterr().err


def test_a_flag_given_twice_is_a_usage_error(tmp_path, capfd):
    assert main(["simulate", PENDULUM, "--rtol", "1e-6", "--rtol", "1e-7",
                 "--out", str(tmp_path)]) == 2
    assert "--rtol is given twice" in capfd.readouterr().err


def test_options_and_a_keyword_together_name_both():
    with pytest.raises(RunOptionError, match=r"options and the keyword rtol .* simulate"):
        acausal2d.simulate(PENDULUM, options=RunOptions(), rtol=1e-6)
    with pytest.raises(RunOptionError, match=r"options and the keyword stop_time .* sweep"):
        acausal2d.sweep(PENDULUM, vary={"body.m": [1, 2]}, options=RunOptions(), stop_time=1.0)
    with pytest.raises(RunOptionError, match="options of simulate must be a RunOptions"):
        acausal2d.simulate(PENDULUM, options={"rtol": 1e-6})
    with pytest.raises(RunOptionError, match=r"stop_time \(2 s\) differs from the last"):
        RunOptions(stop_time=2.0, output_times=[0.0, 1.0])
    with pytest.raises(RunOptionError, match=r"intervals \(4\) differs from the 1 intervals"):
        RunOptions(intervals=4, output_times=[0.0, 1.0])
    assert_copied(RunOptions(stop_time=1.0, intervals=1, output_times=[0.0, 1.0]).resolved({}).end, 1.0)


def test_options_are_frozen_and_replace_checks_again():
    opts = RunOptions(stop_time=2.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.rtol = 1e-3
    with pytest.raises(RunOptionError, match="rtol must be between"):
        opts.replace(rtol=1.0)
    assert_copied(opts.replace(rtol=1e-3).stop_time, 2.0)


def test_defaults_come_from_the_experiment_then_from_defaults():
    bare = RunOptions().resolved({})
    assert (bare.stop_time, bare.rtol, bare.intervals, bare.max_steps) == (
        DEFAULTS["stop_time"], DEFAULTS["rtol"], DEFAULTS["intervals"], DEFAULTS["max_steps"])
    model = RunOptions().resolved({"stop_time": 3.0, "rtol": 1e-8})
    assert_copied((model.stop_time, model.rtol, model.intervals), (3.0, 1e-8, DEFAULTS["intervals"]))
    given = RunOptions(stop_time=0.5).resolved({"stop_time": 3.0})
    assert_copied(given.stop_time, 0.5)


def test_a_run_with_options_is_the_run_with_keywords():
    cm = acausal2d.compile_model(PENDULUM)
    a = cm.simulate(options=RunOptions(stop_time=0.4, intervals=8, rtol=1e-8))
    b = cm.simulate(stop_time=0.4, intervals=8, rtol=1e-8)
    assert len(a.time) == len(b.time) == 9 and same_time(a.time[-1], 0.4)
    # the same run twice: the same steps, so agreement far inside the tolerance
    assert abs(a.final("revolute.phi") - b.final("revolute.phi")) <= 1e-8 * (
        1.0 + abs(b.final("revolute.phi")))


def test_the_fmu_default_experiment_comes_from_the_options():
    from acausal2d.fmu.description import model_description
    from acausal2d.fmu.export import export_data
    model = acausal2d.load_model(PENDULUM)
    data = export_data(model, options=RunOptions(stop_time=2.5, rtol=1e-7))
    xml = model_description(data, "me")
    assert '<DefaultExperiment startTime="0" stopTime="2.5" tolerance="1e-07"/>' in xml
    own = model_description(export_data(model), "me")
    exp = RunOptions().resolved(getattr(model, "experiment", None))
    assert 'stopTime="%r" tolerance="%r"' % (exp.stop_time, exp.rtol) in own


# the defaults live in acausal2d/options.py only: no other copy in the package
COPIES = [
    (r"""\.get\(\s*["'](stop_time|rtol|intervals)["']\s*,\s*[0-9]""",
     "an experiment default read with .get(key, number)"),
    (r"\bMAX_STEPS\b", "a step budget constant"),
    (r"""max[_-]steps["']?\s*[=:,]\s*[0-9]""", "the step budget's value"),
    (r"max_num_steps\s*=\s*[0-9]", "IDA's steps per output as a literal"),
    (r"""add_argument\(\s*["']--(stop-time|rtol|atol|intervals|max-steps|max-wall-time)["']""",
     "a run option declared outside cli/args.py"),
]


def test_the_defaults_and_declarations_have_no_other_copy():
    package = pathlib.Path(ROOT) / "acausal2d"
    found = []
    for path in package.rglob("*.py"):
        if path.name == "options.py":
            continue
        text = path.read_text(encoding="utf-8")
        for pattern, what in COPIES:
            for m in re.finditer(pattern, text):
                if path.name == "explore.py" and "max-wall-time" in m.group(0):
                    continue          # the explorer's per-request budget (not a run's option)
                found.append("%s:%d: %s" % (path.relative_to(ROOT),
                                            text[:m.start()].count("\n") + 1, what))
    assert not found, "\n".join(found)
