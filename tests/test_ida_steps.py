"""The Python path's call of IDA output time by output time
(acausal2d.runtime.ida._solve, scikit-sundae's init_step/step): the same
IDA calls as scikit-sundae's solve, so the same steps, events and values;
and a pause that ends the call at an output time, after which the run goes
on to the same answer.  The checkpoints of a run that looks for its library
(background.Tiering.pause) use it, so that looking does not restart IDA."""
import os
import sys
import time

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import background, ida, tiers
from tiers_support import agree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "models"))
from compressor import Compressor  # noqa: E402
from pendulum import Pendulum  # noqa: E402

SAME = 1e-12
"""The two ways make the same IDA calls in the same order, so their values
agree to the last bits; a different step anywhere would show at the
integration tolerance (1e-8 here), four orders above this bound."""


def _by_solve(solver, prob, tspan, y0, yp0, pause):
    """scikit-sundae's own solve, as the Python path called it before."""
    assert pause is None
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


def test_a_pause_ends_the_call_at_an_output_time_and_the_run_goes_on(monkeypatch):
    ref = _run(Pendulum(), 2.0, monkeypatch)
    real, ends = ida._solve, []

    def solve(solver, prob, tspan, y0, yp0, pause):   # each call ends a third of its way
        stop_at = tspan[1 + len(tspan) // 3]

        def third(t):
            if t >= stop_at:
                ends.append(t)
                return True
            return False
        return real(solver, prob, tspan, y0, yp0, third)
    res = _run(Pendulum(), 2.0, monkeypatch, solve)
    assert len(ends) >= 2 and res.stats["segments"] == len(ends) + 1
    assert res.time.shape == ref.time.shape
    assert np.max(np.abs(res.time - ref.time)) <= 1e-12 * 2.0
    for t in ends:                                     # ended at output times
        assert np.min(np.abs(ref.time - t)) <= 1e-12 * 2.0
    agree(res, ref, ("revolute.phi", "revolute.w"), 1e-8)


def _held_worker(tmp_path, monkeypatch):
    """A hold file of this process, held as :func:`background.launch` does
    with ``held=True``; a compile expected to take 1 s."""
    monkeypatch.setattr(background, "_holds", {})
    job = str(tmp_path / "job")
    background._holds[job + background.HOLD] = os.open(job + background.HOLD,
                                                       os.O_CREAT | os.O_RDWR, 0o600)
    assert background.hold()
    monkeypatch.setattr(background.Tiering, "active", lambda self: True)
    monkeypatch.setattr(background, "expected_left", lambda: 1.0)
    tiering = background.Tiering()
    tiering.waiting = True
    tiering.held(100.0)
    tiering.begin(0.0, 100.0, 8.0)
    return tiering


def test_a_worker_held_from_its_launch_goes_on_where_its_compile_fits(tmp_path, monkeypatch):
    tiering = _held_worker(tmp_path, monkeypatch)
    assert tiering.pause(1.0, 7.0, 100.5, lambda: False) is False   # before the checkpoint
    assert background._holds
    # at the first checkpoint (t = 2 of 8): 6 s of simulated time left at 0.5 s per
    # second, a rest of 3 s against a compile of 1 s: the worker goes on, no wait yet
    assert tiering.pause(2.0, 6.0, 101.0, lambda: False) is False
    assert not background._holds and not tiering.decided and tiering.waiting
    assert tiering.next_check == pytest.approx(4.0)


def test_a_worker_held_from_its_launch_stays_held_where_the_run_ends_first(tmp_path,
                                                                          monkeypatch):
    tiering = _held_worker(tmp_path, monkeypatch)
    monkeypatch.setattr(background, "expected_left", lambda: 10.0)
    assert tiering.pause(2.0, 6.0, 100.5, lambda: False) is False  # rest 1.5 s < 10 s
    assert background._holds and tiering.gave_up and not tiering.waiting
    assert tiering.pause(4.0, 4.0, 101.0, lambda: True) is False   # no more checks
    assert "waits for the run's end" in tiering.notes[-1]


def test_a_worker_held_from_its_launch_goes_on_without_a_decision_in_time(tmp_path,
                                                                         monkeypatch):
    tiering = _held_worker(tmp_path, monkeypatch)
    tiering.held(time.perf_counter() - 0.5 * background.FIRST_HOLD)
    tiering.tick()                                      # within FIRST_HOLD: still held
    assert background._holds
    tiering.held(time.perf_counter() - 1.01 * background.FIRST_HOLD)
    tiering.tick()
    assert not background._holds and tiering.held_until is None
    assert tiering.notes[-1].startswith("no decision within %g s" % background.FIRST_HOLD)


def test_a_checkpoint_where_the_library_is_there_ends_the_call(tmp_path, monkeypatch):
    tiering = _held_worker(tmp_path, monkeypatch)
    assert tiering.pause(2.0, 6.0, 101.0, lambda: True) is True
    assert not tiering.decided                          # taken up, nothing to decide
