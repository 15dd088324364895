"""Numbers that go wrong become the project's errors naming the element,
equation and values (no numpy/LAPACK/CasADi traceback or chatter), and a
model with nothing left to integrate is simply evaluated."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import (Component, InitializationError, ModelDefinitionError, Parameter,
                       SimulationError, Variable, der)
from acausal2d.library.planar import Body, Fixed, Prismatic
from conftest import same_time


class Welded(Component):
    """A body welded to the ground: every unknown is determined."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed(r=(0.5, 0.25))
        self.body = Body(m=2.0)
        self.connect(self.fixed.frame, self.body.frame_a)


class Reciprocal(Component):
    """x = 1/p: determined by the parameter alone."""
    p = Parameter(4.0, "", "divisor", positive=True)
    x = Variable()

    def equations(self):
        return [self.x == 1 / self.p]


def test_fully_determined_models_are_evaluated():
    res = acausal2d.simulate(Welded(), stop_time=1.0, intervals=4)
    assert len(res.time) == 5 and same_time(res.time[-1], 1.0)
    # values fixed by the parameters, evaluated in a few operations: exact up
    # to their rounding (4 ulps)
    assert np.max(np.abs(res["body.x"] - 0.5)) <= 4 * np.spacing(0.5)
    assert np.max(np.abs(res["body.y"] - 0.25)) <= 4 * np.spacing(0.25)
    # the ground carries the weight
    assert np.all(res["body.frame_a.fy"] == pytest.approx(2.0 * 9.81))
    res = acausal2d.simulate(Reciprocal(), stop_time=1.0, params={"p": 8.0})
    assert np.max(np.abs(res["x"] - 0.125)) <= 4 * np.spacing(0.125)
    res = acausal2d.simulate(_lone_fixed(), stop_time=0.5)
    assert np.max(np.abs(res["fixed.frame.phi"])) <= 4 * np.spacing(1.0)


def _lone_fixed():
    class LoneFixed(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed()
    return LoneFixed()


def test_an_empty_model_is_an_error_naming_it():
    class Nothing(Component):
        pass
    with pytest.raises(ModelDefinitionError, match="Nothing '<model>' has no unknowns"):
        acausal2d.simulate(Nothing())
    with pytest.raises(ModelDefinitionError, match="nothing to simulate"):
        acausal2d.compile_model(Component())


class ZeroDirection(Component):
    """A prismatic joint whose direction r is the zero vector."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.slide = Prismatic(r=(0.0, 0.0))
        self.body = Body()
        self.connect(self.fixed.frame, self.slide.frame_a)
        self.connect(self.slide.frame_b, self.body.frame_a)


def test_zero_direction_is_refused_by_the_parameter_rule():
    with pytest.raises(ModelDefinitionError) as err:
        ZeroDirection()
    # the component's name is not known while it is built: the message says where it was made
    assert "Prismatic created at test_numeric_failures.py:" in str(err.value)
    assert "parameter r = (0, 0) breaks its rule nonzero length" in str(err.value)
    cm = acausal2d.compile_model(Welded())
    with pytest.raises(ModelDefinitionError, match="body: parameter m = -1 breaks its rule >= 0"):
        cm.simulate(params={"body.m": -1.0})


class Skewed(Component):
    """A rod whose end is fixed at 1/(p - 1): not finite for p = 1."""
    p = Parameter(2.0, "", "shape factor")
    x = Variable()

    def equations(self):
        return [self.x == 1 / (self.p - 1)]


def test_a_value_fixed_by_parameters_that_is_not_finite_is_named():
    cm = acausal2d.compile_model(Skewed())
    assert abs(cm.simulate(stop_time=0.1)["x"][0] - 1.0) <= 4 * np.spacing(1.0)
    with pytest.raises(ModelDefinitionError) as err:
        cm.simulate(stop_time=0.1, params={"p": 1.0})
    assert "x" in str(err.value) and "inf or NaN" in str(err.value)
    assert "Skewed '<model>' equation 1" in str(err.value)


class SqrtAtStart(Component):
    x = Variable(start=1.0, fixed=True)

    def equations(self):
        return [der(self.x) == acausal2d.sqrt(self.x - 2.0)]


class Overflow(Component):
    x = Variable(start=1.0, fixed=True)

    def equations(self):
        return [der(self.x) == acausal2d.exp(1000 * self.x)]


@pytest.mark.parametrize("model,text", [(SqrtAtStart, "sqrt((x-2))"),
                                        (Overflow, "exp((1000*x))")])
def test_non_finite_at_the_start_names_the_equation(model, text, capfd):
    with pytest.raises(InitializationError) as err:
        acausal2d.simulate(model(), stop_time=1.0)
    assert text in str(err.value) and "inf or NaN" in str(err.value)
    assert "DLASCL" not in "".join(capfd.readouterr())


class IntoSqrt(Component):
    """y = sqrt(1 - x) with x = t: not finite from t = 1 on."""
    x = Variable(start=0.0, fixed=True)
    y = Variable(start=1.0)

    def equations(self):
        return [der(self.x) == 1.0, self.y == acausal2d.sqrt(1.0 - self.x)]


def test_non_finite_during_the_run_names_the_equation_and_time(capfd):
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(IntoSqrt(), stop_time=2.0)
    assert err.value.time == pytest.approx(1.0, abs=1e-6)
    assert "y == sqrt((1-x))" in str(err.value)
    # up to there the result is the closed form
    res = err.value.result
    k = res.time < 0.999
    assert np.max(np.abs(res["y"][k] - np.sqrt(1.0 - res.time[k]))) < 1e-6
    assert "DLASCL" not in "".join(capfd.readouterr())
    assert math.isfinite(res["y"][-1])


class FourBar(Component):
    """Four revolute joints; the crank angle is given, the other joints have
    no start guesses; a rocker of 0.1 m cannot close the loop."""

    def __init__(self, rocker=0.8, **kw):
        super().__init__(**kw)
        from acausal2d import start
        from acausal2d.library.planar import FixedTranslation, Revolute
        self.ground_a, self.ground_d = Fixed(), Fixed(r=(1.0, 0.0))
        self.ja = Revolute(phi=start(1.2, fixed=True), w=start(0.0, fixed=True))
        self.crank = FixedTranslation(r=(0.5, 0.0))
        self.jb, self.jc, self.jd = Revolute(), Revolute(), Revolute()
        self.coupler = FixedTranslation(r=(1.0, 0.0))
        self.rocker = FixedTranslation(r=(rocker, 0.0))
        self.mass = Body(m=1.0, I=0.1)
        for a, b in ((self.ground_a.frame, self.ja.frame_a), (self.ja.frame_b, self.crank.frame_a),
                     (self.crank.frame_b, self.jb.frame_a), (self.jb.frame_b, self.coupler.frame_a),
                     (self.coupler.frame_b, self.jc.frame_a), (self.jc.frame_b, self.rocker.frame_a),
                     (self.rocker.frame_b, self.jd.frame_b), (self.ground_d.frame, self.jd.frame_a),
                     (self.crank.frame_b, self.mass.frame_a)):
            self.connect(a, b)


def test_a_loop_that_cannot_close_reports_its_position_equations():
    with pytest.raises(InitializationError) as err:
        acausal2d.simulate(FourBar(rocker=0.1), stop_time=0.1)
    msg = str(err.value)
    assert "the position equations do not close" in msg
    assert "FixedTranslation 'rocker' equation 1" in msg
    assert "Held at their start values: ja.phi, ja.w" in msg
    # acceleration-level and force residuals are not what is listed
    assert "der(der(" not in msg.split("Held at")[0]


def test_the_same_loop_with_a_closing_rocker_assembles_without_guesses():
    res = acausal2d.simulate(FourBar(rocker=0.8), stop_time=0.1)
    # the rocker end lies on the ground pivot: loop closed to 1e-10
    x = res["rocker.frame_b.x"] - 1.0
    y = res["rocker.frame_b.y"]
    assert np.max(np.hypot(x, y)) < 1e-10
