"""Step counts stay sane (issue: the runtime core): IDA integrates the
semi-explicit form with the states in its error test, so a mechanism driven
into its limit position, a parallelogram swinging through its change points
and the piston engine take few steps at every tolerance.  Counts, not
times; the margins are generous."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError, start
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute
from conftest import load_model_class, same_time
from test_singular_positions import Parallelogram, SwingingParallelogram


def test_four_bar_driven_into_its_limit_stops_there_in_few_steps():
    """DDDD with a 0.3 m crank (coupler 0.35, rocker 0.3, ground 0.4) cannot
    turn round: coupler and rocker stretch out when |P1 - B0| = 0.65, at
    cos(phi) = (0.3^2 + 0.4^2 - 0.65^2) / (2 0.3 0.4)."""
    model = load_model_class("four_link_mechanisms.py", "DDDD")()
    res = acausal2d.simulate(model, params={"crank.lL": 0.3}, stop_time=1.0, rtol=1e-8)
    t_lim = math.acos((0.09 + 0.16 - 0.65 ** 2) / 0.24) / (2 * math.pi)
    assert res.stopped is not None and "limit position" in res.stopped
    assert res.time[-1] == pytest.approx(t_lim, abs=1e-4)
    assert res.stats["steps"] <= 2000


def test_swinging_parallelogram_steps_grow_slowly_with_the_tolerance():
    cm = acausal2d.compile_model(SwingingParallelogram())
    steps = {}
    for rtol in (1e-7, 1e-9):
        res = cm.simulate(stop_time=2.0, rtol=rtol, intervals=400)
        assert res.stopped is None and same_time(res.time[-1], 2.0)
        steps[rtol] = res.stats["steps"]
    assert steps[1e-9] <= 3 * steps[1e-7]
    res = cm.simulate(stop_time=2.0, rtol=1e-10, intervals=400)
    assert res.stopped is None and same_time(res.time[-1], 2.0) and len(res.time) >= 401
    passed = [s for s in res.singularities if s["kind"] == "singular position passed"]
    assert len(passed) >= 7


@pytest.mark.parametrize("K", [1, -1])
def test_driven_parallelogram_at_tight_tolerance_keeps_the_final_row(K):
    """Stepping over the last change point before the end must not lose the
    output row at the stop time."""
    res = acausal2d.simulate(Parallelogram(K), stop_time=2.0, rtol=1e-10, intervals=400)
    assert same_time(res.time[-1], 2.0) and np.count_nonzero(same_time(res.time, 2.0)) >= 1
    assert np.all(np.isin(np.linspace(0.0, 2.0, 401), res.time))


def test_piston_engine_takes_no_more_steps_than_before_the_rebuild(compiled_model):
    """3975 steps at rtol 1e-8 over 10 s with 5000 output points before."""
    engine = compiled_model("piston_engine.py", "PistonEngine")
    res = engine.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
    assert res.stats["steps"] <= 3975


class PendulumOnCoupler(Component):
    """A pendulum hanging from the coupler point of a driven four-bar; its
    joint asks for state_select='always'."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.preset = Preset(om=2 * math.pi, phi0=0.5)
        self.crank = DAN(lL=0.1)
        self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)
        self.joint = Revolute(state_select="always", phi=start(-math.pi / 2, fixed=True),
                              w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(0.2, 0.0))
        self.bob = Body(m=0.5, I=0.001)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        self.connect(self.dyad.ctr2D3, self.joint.frame_a)
        self.connect(self.joint.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.bob.frame_a)


def test_always_makes_the_joint_angle_and_speed_states():
    res = acausal2d.simulate(PendulumOnCoupler(), stop_time=0.5, rtol=1e-8)
    assert "joint.phi" in res.states and "joint.w" in res.states
    # w is the derivative of the angle all along
    phi, w = res["joint.phi"], res["joint.w"]
    assert np.max(np.abs(np.gradient(phi, res.time) - w)[5:-5]) < 1e-3 * np.max(np.abs(w))


class AllJointsAlways(Component):
    """A four-bar of revolute joints, all asking for 'always': one degree of
    freedom cannot have four angle states."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ground_a, self.ground_d = Fixed(), Fixed(r=(1.0, 0.0))
        self.ja = Revolute(state_select="always", phi=start(1.2, fixed=True),
                           w=start(0.0, fixed=True))
        self.crank = FixedTranslation(r=(0.5, 0.0))
        self.jb = Revolute(state_select="always", phi=start(-1.0))
        self.coupler = FixedTranslation(r=(1.0, 0.0))
        self.jc = Revolute(state_select="always", phi=start(-1.5))
        self.rocker = FixedTranslation(r=(0.8, 0.0))
        self.jd = Revolute(state_select="always")
        self.mass = Body(m=1.0, I=0.1)
        self.connect(self.ground_a.frame, self.ja.frame_a)
        self.connect(self.ja.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.jb.frame_a)
        self.connect(self.jb.frame_b, self.coupler.frame_a)
        self.connect(self.coupler.frame_b, self.jc.frame_a)
        self.connect(self.jc.frame_b, self.rocker.frame_a)
        self.connect(self.rocker.frame_b, self.jd.frame_b)
        self.connect(self.ground_d.frame, self.jd.frame_a)
        self.connect(self.crank.frame_b, self.mass.frame_a)


def test_always_that_cannot_be_honoured_names_the_variable():
    with pytest.raises(ModelDefinitionError) as err:
        acausal2d.simulate(AllJointsAlways(), stop_time=0.1)
    msg = str(err.value)
    assert "state_select='always'" in msg
    assert any("j%s." % c in msg for c in "abcd")
