"""Runs are bounded: a step budget (default 1,000,000) and an optional
wall-clock budget stop a run early, keeping the data so far and saying why;
long segments are split into IDA calls of bounded wall time so that the
budgets are looked at during them."""
import sys
import time

import numpy as np
import pytest

import acausal2d
from acausal2d import Acausal2dError
from conftest import load_model_class, same_time


def _pendulum():
    return load_model_class("pendulum.py", "Pendulum")()


def test_step_budget_stops_a_run_that_would_take_hours():
    wall = time.perf_counter()
    res = acausal2d.simulate(_pendulum(), stop_time=1e7, max_steps=20000)
    assert time.perf_counter() - wall < 20.0
    assert res.stopped is not None and "step budget of 20000 steps" in res.stopped
    assert 20000 <= res.stats["steps"] < 22000
    # the data so far is kept, ending with the point reached
    assert res.time[-1] > 0 and res.time[-1] < 1e7
    assert np.all(np.isfinite(res["revolute.phi"]))


def test_wall_clock_budget_stops_the_run():
    wall = time.perf_counter()
    res = acausal2d.simulate(_pendulum(), stop_time=1e6, max_wall_time=0.5)
    elapsed = time.perf_counter() - wall
    assert res.stopped is not None and "wall-clock budget of 0.5 s" in res.stopped
    assert elapsed < 5.0


def test_budgets_leave_normal_runs_alone_and_are_checked():
    res = acausal2d.simulate(_pendulum(), stop_time=3.0, max_wall_time=60.0)
    assert res.stopped is None and same_time(res.time[-1], 3.0)
    for bad in (0, -1, float("nan"), "many", True):
        with pytest.raises(Acausal2dError, match="max_steps must be "):
            acausal2d.simulate(_pendulum(), stop_time=1.0, max_steps=bad)
