"""Issue 18, Seen 5-8: public API arguments of the wrong type name the
argument; a fixed start value the equations contradict is an error naming
both values; a stop time that cannot advance the clock is an error; every
failure removes the previous run's outputs."""
import os

import numpy as np
import pytest

import acausal2d
from acausal2d import Acausal2dError
from acausal2d.cli import main
from conftest import assert_copied

HERE = os.path.dirname(os.path.abspath(__file__))
PENDULUM = os.path.join(HERE, os.pardir, "models", "pendulum.py")
NOISE = ("Traceback", "ValueError", "TypeError", "AttributeError")


@pytest.fixture(scope="module")
def compiled():
    return acausal2d.compile_model(acausal2d.load_model(PENDULUM))


@pytest.mark.parametrize("kw, name", [
    ({"rtol": "tight"}, "rtol"), ({"atol": [1e-6, 1e-6]}, "atol"), ({"atol": "x"}, "atol"),
    ({"atol": [[1e-6]]}, "atol"), ({"output_times": "0,1"}, "output_times"),
    ({"output_times": {"a": 1}}, "output_times"), ({"stop_time": "1"}, "stop_time"),
    ({"intervals": "10"}, "intervals"), ({"progress": 5}, "progress"),
    ({"params": [1]}, "params"), ({"start_time": "0"}, "start_time"),
    ({"max_steps": "5"}, "max_steps"), ({"foo": 1}, "foo"),
])
def test_seen_5_simulate_arguments_name_themselves(compiled, kw, name):
    with pytest.raises(Acausal2dError, match=name) as exc:
        acausal2d.simulate(compiled, **kw)
    assert not any(n in str(exc.value) for n in NOISE)


def test_seen_5_atol_one_per_unknown_is_accepted(compiled):
    """A vector atol with one entry per unknown runs and matches the scalar."""
    n = len(compiled.system.node_names)
    a = acausal2d.simulate(compiled, stop_time=0.5, atol=np.full(n, 1e-9))
    b = acausal2d.simulate(compiled, stop_time=0.5, atol=1e-9)
    assert_copied(a["revolute.phi"], b["revolute.phi"])


@pytest.mark.parametrize("call, name", [
    (lambda: acausal2d.simulate(5), "model"),
    (lambda: acausal2d.compile_model("no/such/model.py"), "no/such/model.py"),
    (lambda: acausal2d.compile_model(acausal2d.Component), "nothing to simulate"),
    (lambda: acausal2d.compile_model(None), "model"),
    (lambda: acausal2d.check(5), "check: model must be a model file's path, a Component "
                                 "subclass, an instance or a CompiledModel, not int"),
    (lambda: acausal2d.load_model(5), "path"),
    (lambda: acausal2d.load_model(PENDULUM, 5), "name"),
    (lambda: acausal2d.sweep(PENDULUM, vary=[1, 2]), "vary"),
    (lambda: acausal2d.sweep(PENDULUM, vary={"bob.m": [object()]}), "vary"),
    (lambda: acausal2d.sweep(PENDULUM, points=5), "points"),
    (lambda: acausal2d.sweep(PENDULUM, points=[5]), "points"),
    (lambda: acausal2d.sweep(PENDULUM, vary={"bob.m": [1]}, stop_time="x"), "stop_time"),
    (lambda: acausal2d.sweep(PENDULUM, vary={"bob.m": [1]}, workers="x"), "workers"),
    (lambda: acausal2d.sweep(PENDULUM, vary={"bob.m": [1]}, params=[1]), "params"),
])
def test_seen_5_api_arguments_of_the_wrong_type(call, name):
    with pytest.raises(Acausal2dError, match=name) as exc:
        call()
    assert not any(n in str(exc.value) for n in NOISE)


@pytest.mark.parametrize("stop", ["1e-300", "1e-320", "1e-10"])
def test_seen_7_stop_time_that_cannot_advance_the_clock(stop, tmp_path, capfd):
    """500 intervals below the run's time resolution (1e-12 s): an error,
    exit 2, no result."""
    out = tmp_path / "out"
    assert main(["simulate", PENDULUM, "--out", str(out), "--stop-time", stop]) == 2
    err = "".join(capfd.readouterr())
    assert "cannot advance the clock" in err and "Traceback" not in err
    assert not (out / "result.csv").exists()
    with pytest.raises(Acausal2dError, match="cannot advance the clock"):
        acausal2d.simulate(acausal2d.load_model(PENDULUM), stop_time=float(stop))


def test_seen_7_a_short_run_above_the_resolution_still_runs(compiled):
    res = acausal2d.simulate(compiled, stop_time=1e-6, intervals=10)
    assert len(res.time) == 11 and res.time[-1] == pytest.approx(1e-6, rel=1e-12)


# ------------------------------------------------ Seen 6: contradicted fixed starts
class _Constant(acausal2d.Component):
    """x = 2 by its equation; y follows x."""
    experiment = {"stop_time": 1.0, "intervals": 10}
    x = acausal2d.Variable()
    y = acausal2d.Variable()

    def equations(self):
        return [self.x == 2.0, acausal2d.der(self.y) == self.x - self.y]


class _Twice(acausal2d.Component):
    """x = 2 y with y a fixed state: x is determined by the equations."""
    experiment = {"stop_time": 1.0, "intervals": 10}
    x = acausal2d.Variable()
    y = acausal2d.Variable()

    def equations(self):
        return [self.x == 2 * self.y, acausal2d.der(self.y) == -self.y]


class _Shifted(acausal2d.Component):
    """x = y + 1: one alias set with two fixed members."""
    experiment = {"stop_time": 1.0, "intervals": 10}
    x = acausal2d.Variable()
    y = acausal2d.Variable()

    def equations(self):
        return [self.x == self.y + 1, acausal2d.der(self.y) == -self.y]


@pytest.mark.parametrize("make, name, given, by_eq", [
    (lambda: _Constant(x=acausal2d.start(1.0, fixed=True)), "x", "1", "2"),
    (lambda: _Twice(x=acausal2d.start(1.0, fixed=True), y=acausal2d.start(1.0, fixed=True)),
     "x", "1", "2"),
    (lambda: _Shifted(x=acausal2d.start(3.0, fixed=True), y=acausal2d.start(1.0, fixed=True)),
     "y", "1", "2"),
])
def test_seen_6_contradicted_fixed_start_names_variable_and_both_values(make, name, given,
                                                                        by_eq):
    with pytest.raises(acausal2d.InitializationError) as exc:
        acausal2d.simulate(make())
    msg = str(exc.value)
    assert "%s has the fixed start value %s" % (name, given) in msg
    assert "equations give %s = %s" % (name, by_eq) in msg


@pytest.mark.parametrize("make", [
    lambda: _Constant(x=acausal2d.start(2.0, fixed=True)),
    lambda: _Twice(x=acausal2d.start(2.0, fixed=True), y=acausal2d.start(1.0, fixed=True)),
    lambda: _Shifted(x=acausal2d.start(2.0, fixed=True), y=acausal2d.start(1.0, fixed=True)),
])
def test_seen_6_agreeing_fixed_start_is_accepted(make):
    res = acausal2d.simulate(make())
    assert res["x"][0] == pytest.approx(2.0, abs=1e-12)
    if "y" in res.names and not isinstance(make(), _Constant):
        assert res["y"][0] == pytest.approx(1.0, abs=1e-12)
        assert res["y"][-1] == pytest.approx(np.exp(-1.0), rel=1e-4)   # der(y) = -y


def test_seen_6_cli_exit_code(tmp_path, capfd):
    path = tmp_path / "m.py"
    path.write_text(
        "from acausal2d import Component, Variable, der, start\n\n"
        "class M(Component):\n    experiment = {'stop_time': 1.0, 'intervals': 10}\n"
        "    x = Variable()\n    y = Variable()\n\n    def __init__(self, **kw):\n"
        "        super().__init__(x=start(1.0, fixed=True), **kw)\n\n"
        "    def equations(self):\n        return [self.x == 2.0, der(self.y) == self.x - self.y]\n",
        encoding="utf-8")
    assert main(["simulate", str(path), "--out", str(tmp_path / "o")]) == 2
    err = "".join(capfd.readouterr())
    assert "fixed start value 1" in err and "x = 2" in err and "Traceback" not in err


# ------------------------------------------------ Seen 8: stale outputs
STAGES = {
    "load": ("class Model(Component):\n    experiment = {'stop_time': 0.5, 'intervals': 10}\n"
             "    def __init__(self, **kw):\n        super().__init__(**kw)\n"
             "        self.b = Body(m=float('nan'))\n"),
    "compile": ("class Model(Component):\n    experiment = {'stop_time': 0.5, 'intervals': 10}\n"
                "    x = Variable()\n    y = Variable()\n"
                "    def equations(self):\n        return [self.x == 1]\n"),
    "init": ("class Model(Component):\n    experiment = {'stop_time': 0.5, 'intervals': 10}\n"
             "    x = Variable()\n    y = Variable()\n    def __init__(self, **kw):\n"
             "        super().__init__(x=start(1.0, fixed=True), **kw)\n"
             "    def equations(self):\n        return [self.x == 2.0, der(self.y) == -self.y]\n"),
    "run": ("class Model(Component):\n    experiment = {'stop_time': 2.0, 'intervals': 10}\n"
            "    x = Variable(start=1.0)\n    def __init__(self, **kw):\n"
            "        super().__init__(x=start(1.0, fixed=True), **kw)\n"
            "    def equations(self):\n        return [der(self.x) == self.x ** 2]\n"),
}


@pytest.mark.parametrize("stage", sorted(STAGES))
def test_seen_8_every_failure_removes_the_previous_outputs(stage, tmp_path, capfd):
    """A good run writes result.csv, plots, the page and the manifest; a
    failing run into the same folder (at load, compile, init or run time)
    exits 2 and leaves none of them."""
    out = tmp_path / "out"
    assert main(["simulate", PENDULUM, "--out", str(out)]) == 0
    before = set(os.listdir(out))
    assert {"result.csv", "animation.html"} <= before
    path = tmp_path / "bad.py"
    path.write_text("from acausal2d import Component, Variable, der, start\n"
                    "from acausal2d.library.planar import Body\n\n" + STAGES[stage],
                    encoding="utf-8")
    code = main(["simulate", str(path), "--out", str(out)])
    err = "".join(capfd.readouterr())
    assert code == 2 and "Traceback" not in err and "error" in err
    left = set(os.listdir(out))
    assert not left & before, left & before


@pytest.mark.parametrize("form", ["path", "class", "instance", "compiled"])
def test_every_public_function_takes_a_path_a_class_an_instance_or_a_compiled_model(form):
    """Issue 34: one way to give a model, the same result each way (the
    pendulum's angle after 0.5 s, compared across the four forms)."""
    from acausal2d.io.loader import load_model
    cls = type(load_model(PENDULUM))
    given = {"path": PENDULUM, "class": cls, "instance": cls(),
             "compiled": acausal2d.compile_model(cls())}[form]
    reference = acausal2d.simulate(cls(), stop_time=0.5, rtol=1e-8)
    res = acausal2d.simulate(given, stop_time=0.5, rtol=1e-8)
    # the same model and settings: the same steps, so agreement far inside rtol
    assert np.max(np.abs(res["revolute.phi"] - reference["revolute.phi"])) < 1e-10
    assert isinstance(acausal2d.compile_model(given), acausal2d.compiled.CompiledModel)
    assert "degree of freedom" in str(acausal2d.check(given))
    table = acausal2d.sweep(given, vary={"body.m": [1.0]}, stop_time=0.2, scheduler="serial",
                            progress=False)
    assert len(table.rows) == 1
