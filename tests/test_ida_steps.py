"""The Python path's call of IDA output time by output time
(acausal2d.runtime.ida._solve, scikit-sundae's init_step/step): the same
IDA calls as scikit-sundae's solve, so the same steps, events and values."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import ida, tiers

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "models"))
from compressor import Compressor  # noqa: E402
from pendulum import Pendulum  # noqa: E402

SAME = 1e-12
"""The two ways make the same IDA calls in the same order, so their values
agree to the last bits; a different step anywhere would show at the
integration tolerance (1e-8 here), four orders above this bound."""


def _by_solve(solver, prob, tspan, y0, yp0):
    """scikit-sundae's own solve, as the Python path called it before."""
    sol = solver.solve(tspan, y0, yp0)
    return np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp), sol


def _run(model, stop, monkeypatch, solve=None):
    monkeypatch.setenv(tiers.ENV, "off")
    if solve is not None:
        monkeypatch.setattr(ida, "_solve", solve)
    res = acausal2d.compile_model(model).simulate(stop_time=stop, rtol=1e-8, intervals=200)
    monkeypatch.undo()
    return res


@pytest.mark.parametrize("model,stop,names", [
    (Pendulum, 2.0, ("revolute.phi", "revolute.w")),
    (Compressor, 0.5, ("cyl.p",)),        # the valves' terminal events in the first cycles
], ids=["pendulum", "compressor"])
def test_output_by_output_takes_the_steps_of_solve(model, stop, names, monkeypatch):
    ref = _run(model(), stop, monkeypatch, _by_solve)
    res = _run(model(), stop, monkeypatch)
    assert res.stats["steps"] == ref.stats["steps"]
    assert res.stats["segments"] == ref.stats["segments"]
    assert len(res.events) == len(ref.events)
    assert np.max(np.abs(np.array([e[0] for e in res.events]) -
                         np.array([e[0] for e in ref.events])), initial=0.0) <= SAME
    assert res.time.shape == ref.time.shape
    for name in names:
        assert np.max(np.abs(res[name] - ref[name])) <= SAME * (1.0 + np.max(np.abs(ref[name])))
