"""Parameters change without recompiling; relations and time events;
integration failures are reported with time and variable."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, SimulationError, Variable, der, if_else, start, time
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute
from acausal2d.library.translational import Force, Mass


class SmallSwing(Component):
    """Physical pendulum hanging down, started 0.01 rad off the vertical."""
    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(-math.pi / 2 + 0.01, fixed=True),
                                 w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


def _period(res):
    phi = res["revolute.phi"] + math.pi / 2
    t = res.time
    ups = np.nonzero((phi[:-1] < 0) & (phi[1:] >= 0))[0]
    crossings = t[ups] - phi[ups] * (t[ups + 1] - t[ups]) / (phi[ups + 1] - phi[ups])
    return float(np.mean(np.diff(crossings)))


def test_parameter_change_does_not_recompile(monkeypatch):
    import acausal2d.compiler.pipeline as compiler
    calls = {"flatten": 0, "pantelides": 0}
    real_flatten, real_pant = compiler.flatten, compiler.pantelides

    def counting_flatten(*a, **k):
        calls["flatten"] += 1
        return real_flatten(*a, **k)

    def counting_pantelides(*a, **k):
        calls["pantelides"] += 1
        return real_pant(*a, **k)
    monkeypatch.setattr(compiler, "flatten", counting_flatten)
    monkeypatch.setattr(compiler, "pantelides", counting_pantelides)
    cm = acausal2d.compile_model(SmallSwing())
    periods = {}
    for length in (1.0, 2.0):
        res = cm.simulate(stop_time=12.0, rtol=1e-10, intervals=6000,
                          params={"rod.r": (length, 0.0)})
        periods[length] = _period(res)
        # small-angle period of a physical pendulum: 2 pi sqrt((m L^2 + I) / (m g L))
        expected = 2 * math.pi * math.sqrt((length ** 2 + 0.1) / (9.81 * length))
        assert periods[length] == pytest.approx(expected, rel=2e-5)
    assert calls == {"flatten": 1, "pantelides": 1}
    assert len(cm.system._formulations) == 1       # the same generated functions served both runs


def test_unknown_parameter_is_reported():
    cm = acausal2d.compile_model(SmallSwing())
    with pytest.raises(acausal2d.ModelDefinitionError, match="unknown parameter 'rod.length'"):
        cm.simulate(stop_time=0.1, params={"rod.length": 2.0})


class StepSource(Component):
    """Signal F0 from t = t_on, 0 before (a time event)."""
    F0 = acausal2d.Parameter(2.0, "N", "force after the step")
    t_on = acausal2d.Parameter(1.0, "s", "step time")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.y = acausal2d.RealOutput()

    def equations(self):
        return [self.y.u == if_else(time < self.t_on, 0.0, self.F0)]


class ForceStep(Component):
    """A free 1D mass pushed by a force step."""
    def __init__(self, **kw):
        super().__init__(**kw)
        self.mass = Mass(m=4.0, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.force = Force()
        self.step = StepSource()
        self.connect(self.step.y, self.force.f_in)
        self.connect(self.force.flange, self.mass.flange_a)


def test_time_event_closed_form():
    res = acausal2d.simulate(ForceStep(), stop_time=3.0, rtol=1e-10, intervals=30)
    assert len(res.events) == 1
    assert res.events[0][0] == pytest.approx(1.0, abs=1e-9)
    t = res.time
    expected = np.where(t < 1.0, 0.0, 0.5 * (2.0 / 4.0) * np.clip(t - 1.0, 0, None) ** 2)
    assert np.max(np.abs(res["mass.s"] - expected)) < 1e-8
    assert res.final("mass.v") == pytest.approx(0.5 * 2.0, abs=1e-9)


class Bouncer(Component):
    """A ball on a stiff contact spring that acts only while compressed
    (relation on the position): the ball leaves the spring with the speed it
    arrived (no damping), so it keeps bouncing to its release height."""
    x = Variable(start=1.0, fixed=True)
    v = Variable(start=0.0, fixed=True)

    def equations(self):
        k, m, g = 1e4, 1.0, 9.81
        return [self.v == der(self.x),
                m * der(self.v) == -m * g + if_else(self.x < 0, -k * self.x, 0.0)]


def test_relation_events_and_reinitialization():
    res = acausal2d.simulate(Bouncer(), stop_time=2.0, rtol=1e-10, intervals=2000)
    # free fall from 1 m reaches x=0 at t = sqrt(2/g)
    t_hit = math.sqrt(2 / 9.81)
    assert res.events[0][0] == pytest.approx(t_hit, abs=1e-7)
    # contact lasts half a period of the spring-mass oscillation around x = -g m/k
    assert len(res.events) >= 2
    # energy is conserved across the events: the ball returns to 1 m
    x = res["x"]
    after = res.time > res.events[1][0]
    assert np.max(x[after]) == pytest.approx(1.0, abs=1e-4)
    energy = 0.5 * res["v"] ** 2 + 9.81 * x + np.where(x < 0, 0.5 * 1e4 * x ** 2, 0.0)
    assert np.max(np.abs(energy - 9.81)) < 1e-5


class Runaway(Component):
    """x' = x^2 from x(0) = 1 blows up at t = 1."""
    x = Variable(start=1.0, fixed=True)

    def equations(self):
        return [der(self.x) == self.x ** 2]


def test_integration_failure_names_time_and_variable(capsys):
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(Runaway(), stop_time=2.0)
    assert 0.9 < err.value.time <= 1.0
    assert "Integration failed at t=" in str(err.value)
    assert err.value.variable == "x"
    # SUNDIALS' own message is in our error, not printed (scikit-sundae prints
    # it with Python's print: sys.stdout may be a notebook's stream)
    assert "mxstep steps taken before reaching tout" in str(err.value)
    out = capsys.readouterr()
    assert "IDA" not in out.out + out.err
