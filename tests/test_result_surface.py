"""What a Python user meets on a Result (issue 34): its repr, ``success``
and ``message`` (as scipy's and scikit-sundae's results have them), the
declared ``units``, a did-you-mean for a misspelt signal and ``to_pandas``
(pandas an optional extra).  The pendulum of models/pendulum.py (1 kg at
1 m, I = 0.1 kg m^2, released horizontally) checks the run's numbers by
its energy: 0.5 (I + m l^2) w^2 = m g l |sin(phi)|, to the run's tolerance."""
import sys

import numpy as np
import pytest

from acausal2d.errors import Acausal2dError
from conftest import assert_copied

RTOL = 1e-8
G = 9.81          # the planar world's gravity (PlanarMechanics' default g = {0, -9.81})


@pytest.fixture(scope="module")
def compiled(compiled_model):
    return compiled_model("pendulum.py", "Pendulum")


@pytest.fixture(scope="module")
def run(compiled):
    return compiled.simulate(stop_time=0.5, intervals=50, rtol=RTOL)


def test_a_finished_run_says_so_and_conserves_energy(run):
    assert run.success and run.message == "reached the stop time" and run.stopped is None
    kinetic = 0.5 * (0.1 + 1.0) * run["revolute.w"] ** 2
    potential_lost = G * np.abs(np.sin(run["revolute.phi"]))
    # the global error of a run at rtol stays within a few hundred rtol of the motion's scale
    assert np.max(np.abs(kinetic - potential_lost)) < 1e3 * RTOL * np.max(potential_lost)
    text = repr(run)
    assert text.startswith("<Result Pendulum: t 0..0.5 s, 51 points, %d signals, 0 events, "
                           % len(run.names)) and text.endswith("success: reached the stop time>")


def test_a_run_stopped_by_its_step_budget_says_why(compiled):
    # the budget is looked at between IDA calls: a long run with many output points
    res = compiled.simulate(stop_time=1e4, intervals=100000, rtol=RTOL, max_steps=200)
    assert not res.success and res.message == res.stopped
    assert "step budget of 200 steps" in res.message
    assert "stopped early: " + res.message in repr(res)
    assert res.time[-1] < 1e4


def test_units_come_from_the_declarations(run):
    units = run.units
    assert units["time"] == "s"
    assert units["revolute.phi"] == "rad" and units["revolute.w"] == "rad/s"
    assert units["body.m"] == "kg" and units["body.frame_a.x"] == "m"
    assert set(units) == {"time"} | set(run.names) | set(run.parameters)
    assert all(units[n] == run.unit(n) for n in units)


def test_a_misspelt_signal_gets_a_did_you_mean(run):
    with pytest.raises(Acausal2dError, match=r"no variable 'revolute\.phj' in the result; "
                                             r"did you mean revolute\.phi"):
        run["revolute.phj"]
    with pytest.raises(Acausal2dError, match=r"did you mean .*body\.m"):      # parameters too
        run["body.mm"]
    with pytest.raises(Acausal2dError) as err:
        run["nothing_like_it"]
    assert "did you mean" not in str(err.value)


def test_to_pandas_has_the_columns_and_units(run):
    pd = pytest.importorskip("pandas")
    frame = run.to_pandas(["revolute.phi", "revolute.w"])
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "time"
    assert_copied(frame.index.to_numpy(), run.time)
    assert_copied(frame["revolute.w"].to_numpy(), run["revolute.w"])
    assert frame.attrs["units"] == {"revolute.phi": "rad", "revolute.w": "rad/s"}
    assert list(run.to_pandas().columns) == run.names


def test_to_pandas_without_pandas_names_the_extra(run, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)      # import pandas raises ImportError
    with pytest.raises(Acausal2dError, match=r"pip install 'acausal2d\[pandas\]'"):
        run.to_pandas()
