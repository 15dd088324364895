"""Events with Modelica semantics (acausal2d/runtime/events.py): relations
never go out of step with the state.  A relation with no consistent value
(Coulomb friction at zero speed, x' = -sign(x) at x = 0) stops the run with
an error naming the relation and its component; a prescribed motion that
jumps is reported as needing an impulse; time events fall on their exact
times; relations that are at zero when the motion restarts take the value
their derivative gives."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import (Component, Parameter, SimulationError, TranslationalFlange, Variable, der,
                       if_else, start)
from acausal2d.library import rotational, signals
from acausal2d.library.translational import Mass
from conftest import same_time, assert_copied


class Friction(Component):
    """Coulomb friction force F sign(v) on a translational flange."""
    F = Parameter(5.0, "N", "friction force", min=0.0)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()

    def equations(self):
        return [self.flange.f == self.F * acausal2d.sign(der(self.flange.s))]


class CoulombBlock(Component):
    """1 kg block sliding at 1 m/s against 5 N of Coulomb friction."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.mass = Mass(m=1.0, s=start(0.0, fixed=True), v=start(1.0, fixed=True))
        self.friction = Friction()
        self.connect(self.mass.flange_a, self.friction.flange)


class SignODE(Component):
    """x' = -sign(x)."""
    x = Variable(start=0.1, fixed=True)

    def equations(self):
        return [der(self.x) == -acausal2d.sign(self.x)]


def test_coulomb_block_decelerates_then_stops_with_a_sliding_mode_error():
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(CoulombBlock(), stop_time=1.0, rtol=1e-8)
    exc = err.value
    assert exc.time == pytest.approx(0.2, abs=1e-6)
    msg = str(exc)
    assert "sign(der(friction.flange.s))" in msg and "Friction 'friction'" in msg
    assert "sliding mode" in msg
    # up to the stop: v = 1 - 5 t, never speeding up again
    res = exc.result
    assert res is not None and res.time[-1] == pytest.approx(0.2, abs=1e-6)
    v = res["mass.v"]
    assert np.max(np.abs(v - (1.0 - 5.0 * res.time))) < 1e-7
    assert np.all(np.diff(v) <= 1e-12)


def test_sign_ode_reaches_zero_at_one_tenth_then_stops_within_two_seconds():
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(SignODE(), stop_time=1.0, rtol=1e-8)
    # stops instead of chattering at x = 0, bounded in work, not in wall time
    # (a timed bound fails on a loaded machine): x = 0.1 - t is linear, so
    # IDA's error estimate vanishes and each step at most doubles from the
    # first (>= 1e-9 s at rtol 1e-8): log2(0.1 / 1e-9) = 27 steps to the
    # switch, and a few to locate it; 100 leaves room (measured: 30)
    assert err.value.result.stats["steps"] <= 100
    assert err.value.time == pytest.approx(0.1, abs=1e-6)
    assert "'sign(x)'" in str(err.value)
    res = err.value.result
    assert np.max(np.abs(res["x"] - (0.1 - res.time))) < 1e-9


def test_sign_ode_started_at_zero_is_an_error_at_the_start():
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(SignODE(x=start(0.0, fixed=True)), stop_time=1.0)
    assert same_time(err.value.time, 0.0)
    assert "'sign(x)'" in str(err.value)


class PositionStep(Component):
    """A Position source whose angle steps by 1 rad at t = 0.5 s, on an inertia."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.inertia = rotational.Inertia(J=1.0)
        self.position = rotational.Position()
        self.step = signals.TimeFunction(lambda t: if_else(t < 0.5, 0.0, 1.0))
        self.connect(self.step.y, self.position.phi_in)
        self.connect(self.position.flange, self.inertia.flange_a)


def test_prescribed_position_step_is_an_error_naming_the_source():
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(PositionStep(), stop_time=1.0)
    msg = str(err.value)
    assert err.value.time == pytest.approx(0.5, abs=1e-12)
    assert "jumps" in msg and "impulse" in msg
    assert "Position 'position'" in msg and "TimeFunction 'step'" in msg


class RampOnInertia(Component):
    """Position source following a ramp 0 -> 1 rad over [0.2, 0.7] s: a
    continuous motion with kinks (time events, no error)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.inertia = rotational.Inertia(J=2.0)
        self.position = rotational.Position()
        self.ramp = signals.Ramp(height=1.0, duration=0.5, start_time=0.2)
        self.connect(self.ramp.y, self.position.phi_in)
        self.connect(self.position.flange, self.inertia.flange_a)


def test_time_events_fall_on_their_times_without_root_finding():
    res = acausal2d.simulate(RampOnInertia(), stop_time=1.0, intervals=7)
    times = [t for t, _ in res.events]
    assert len(times) == 2 and same_time(times[0], 0.2) and same_time(times[1], 0.7)   # scheduled
    assert res.stats["time_events"] == 2
    # the angle follows the ramp, the speed jumps between 0 and 2 rad/s
    assert res.at("inertia.phi", 0.45) == pytest.approx(0.5, abs=1e-12)
    w = res["inertia.w"]
    k = np.nonzero(same_time(res.time, 0.2))[0]
    assert_copied(w[k[0]], 0.0)
    assert w[k[-1]] == pytest.approx(2.0, abs=1e-12)



def test_time_relation_values_are_those_of_the_plain_call():
    """The time relations' g and dg/dt the run schedules its time events by
    (bound once per run) equal CasADi's plain call of ``time_event_fn``."""
    from acausal2d.runtime.simulation import Simulation
    cm = acausal2d.compile_model(RampOnInertia())
    opts = cm.run_options(stop_time=1.0)
    sim = Simulation(cm.system, cm.parameter_values(None), opts.times(), opts.rtol, opts.atol)
    assert len(cm.system.time_relations) == 2
    for t in (0.0, 0.2, 0.45, 0.7, 1.0):
        sim.t = t
        g, rate = sim._time_relation_values()
        want = [np.asarray(x).ravel() for x in cm.system.time_event_fn(t, sim.p)]
        for got, ref in zip((g, rate), want):       # the same function evaluated: a few ulps
            np.testing.assert_allclose(got, ref, rtol=4 * np.finfo(float).eps, atol=1e-15)


class Bouncer(Component):
    """A ball on a stiff contact spring (x < 0) under gravity, dropped from 1 m."""
    x = Variable(start=1.0, fixed=True)
    v = Variable(start=0.0, fixed=True)

    def equations(self):
        return [self.v == der(self.x),
                der(self.v) == -9.81 + if_else(self.x < 0, -1e4 * self.x, 0.0)]


def test_relation_at_zero_after_an_event_is_resolved_by_its_derivative():
    """The ball touches x = 0 with speed -sqrt(2 g): the relation x < 0 flips
    and the contact spring decelerates it; without resolving x = 0 by the
    sign of x' the relation would stay wrong and the ball fall through."""
    t_hit = math.sqrt(2 / 9.81)
    w = 100.0
    probe = t_hit + np.linspace(1e-3, 0.02, 5)
    times = np.concatenate([np.linspace(0.0, 1.2, 121), probe])
    res = acausal2d.simulate(Bouncer(), rtol=1e-9, output_times=np.unique(times))
    assert res.events[0][0] == pytest.approx(t_hit, abs=1e-8)
    # in contact: x = -g/w^2 (1 - cos w tau) + v0/w sin w tau (spring-mass about -g/k)
    v0 = -math.sqrt(2 * 9.81)
    for t in probe:
        tau = t - t_hit
        x = -9.81 / w ** 2 * (1 - math.cos(w * tau)) + v0 / w * math.sin(w * tau)
        assert res["x"][np.nonzero(res.time == t)[0][0]] == pytest.approx(x, abs=1e-8)
    assert np.min(res["x"]) > -0.05


def test_chatter_watch_stops_events_piling_up_in_a_vanishing_interval():
    """50 events of one relation within 1e-8 of the run's span stop the run
    with the relation named; the same 50 events spread out do not."""
    from acausal2d.runtime.events import CHATTER_EVENTS, ChatterWatch, EventError
    system = acausal2d.compile_model(SignODE()).system
    spread = ChatterWatch(system, span=1.0)
    for k in range(2 * CHATTER_EVENTS):
        spread.record(0.3 + 1e-3 * k, [0])
    piled = ChatterWatch(system, span=1.0)
    with pytest.raises(EventError) as err:
        for k in range(CHATTER_EVENTS):
            piled.record(0.3 + 1e-11 * k, [0])
    assert "Chattering at t=0.3" in str(err.value) and "'sign(x)'" in str(err.value)
    assert err.value.time == pytest.approx(0.3, abs=1e-9)
