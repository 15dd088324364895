"""Model files under any name, errors of the user's code, ambiguous files,
and the run settings (experiment, stop time, intervals) checked with
messages instead of tracebacks."""
import textwrap

import numpy as np
import pytest

import acausal2d
from acausal2d import Acausal2dError, ModelDefinitionError
from conftest import same_time

PENDULUM = textwrap.dedent('''
    from acausal2d import Component, start
    from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute

    class Pendulum(Component):
        experiment = {"stop_time": 0.5}

        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed()
            self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
            self.rod = FixedTranslation(r=(1.0, 0.0))
            self.body = Body(m=1.0, I=0.1)
            self.connect(self.fixed.frame, self.revolute.frame_a)
            self.connect(self.revolute.frame_b, self.rod.frame_a)
            self.connect(self.rod.frame_b, self.body.frame_a)
''')


@pytest.mark.parametrize("filename", ["pendulum.txt", "pendulum", "my model.py"])
def test_model_files_under_any_name(tmp_path, filename):
    path = tmp_path / filename
    path.write_text(PENDULUM)
    res = acausal2d.simulate(acausal2d.load_model(str(path)))
    assert same_time(res.time[-1], 0.5) and res["revolute.phi"][-1] < 0


@pytest.mark.parametrize("source,message", [
    ("import sys\nsys.exit(3)\n", "calls sys.exit(3)"),
    ("def f(:\n", "is not valid Python (line 1"),
    ("raise RuntimeError('boom')\n", "RuntimeError: boom"),
    ("x = 1\n", "defines no model"),
    (PENDULUM + "\nclass Longer(Pendulum):\n    experiment = {'stop_time': 2.0}\n",
     "defines several models (Longer, Pendulum); choose one with --model"),
])
def test_bad_model_files_are_errors_naming_the_file(tmp_path, source, message):
    path = tmp_path / "model.py"
    path.write_text(source)
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.load_model(str(path))
    assert message in str(err.value) and str(path) in str(err.value)


def test_a_named_model_of_several_is_loaded(tmp_path):
    path = tmp_path / "model.py"
    path.write_text(PENDULUM + "\nclass Longer(Pendulum):\n    experiment = {'stop_time': 2.0}\n")
    assert type(acausal2d.load_model(str(path), "Longer")).__name__ == "Longer"


def _pendulum(experiment=None):
    from conftest import load_model_class
    cls = load_model_class("pendulum.py", "Pendulum")
    if experiment is None:
        return cls()
    return type("Pendulum", (cls,), {"experiment": experiment})()


@pytest.mark.parametrize("experiment,message", [
    ({"stop_time": "long"}, "experiment['stop_time'] must be a number, got 'long'"),
    ({"stop_time": float("nan")}, "experiment['stop_time'] must be finite"),
    ({"stoptime": 2.0}, "experiment has unknown settings 'stoptime'"),
    ([("stop_time", 2.0)], "experiment must be a dict"),
])
def test_experiment_settings_are_checked(experiment, message):
    with pytest.raises(Acausal2dError, match=message.replace("[", r"\[").replace("]", r"\]")):
        acausal2d.simulate(_pendulum(experiment))


@pytest.mark.parametrize("settings,message", [
    (dict(stop_time=float("inf")), "stop_time must be finite"),
    (dict(stop_time=-1.0), "must be larger than start_time"),
    (dict(intervals=2e9), r"2000000000 output intervals of \d+ signals would take [0-9.e+]+ GB"),
    (dict(intervals=0), "intervals must be a whole number of at least 1, got 0"),
    (dict(intervals=2.5), "intervals must be a whole number of at least 1, got 2.5"),
    (dict(rtol=10.0), r"rtol must be between 0 and 0.1 \(a relative tolerance"),
    (dict(output_times=[0.0, float("nan")]), "output_times must be at least two finite"),
])
def test_run_settings_are_checked_before_the_run(settings, message):
    with pytest.raises(Acausal2dError, match=message):
        acausal2d.simulate(_pendulum(), **settings)
