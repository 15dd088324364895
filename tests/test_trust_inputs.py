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
    assert np.array_equal(a["revolute.phi"], b["revolute.phi"])


@pytest.mark.parametrize("call, name", [
    (lambda: acausal2d.simulate(5), "model"),
    (lambda: acausal2d.compile_model("models/pendulum.py"), "load_model"),
    (lambda: acausal2d.compile_model(acausal2d.Component), "instantiate"),
    (lambda: acausal2d.compile_model(None), "model"),
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
