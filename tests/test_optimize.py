"""Design optimisation (acausal2d.optimize) and the metric expressions:
closed-form optima (an active bound, an active constraint) and the
four-bar's precision points.  The cabinet door's peak residual torque
against the ch. 6 least-squares design, with a grid around the optimum, is
checked on the documentation's own ``acausal2d optimize`` command
(tests/test_readme_commands.py), which runs it once in a plain clone."""
import math
import os

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, Parameter, Variable, der
from acausal2d.analysis.metrics import Expression, parse_constraint
from acausal2d.analysis.optimize import optimize
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_metric_expressions_against_numpy():
    t = np.linspace(0.0, 2.0, 201)
    v = {"a.x": np.sin(np.pi * t), "b.y": t ** 2}
    ev = lambda s: Expression(s).evaluate(t, v)         # noqa: E731
    assert ev("max(abs(a.x))") == pytest.approx(1.0)
    assert ev("min(a.x)") == pytest.approx(-1.0)
    assert_copied(ev("final(b.y)"), 4.0)                # the last sample
    assert ev("at(b.y, 0.5)") == pytest.approx(0.25, abs=1e-4)
    assert ev("integral(b.y)") == pytest.approx(8.0 / 3.0, rel=1e-4)
    assert ev("integral(b.y, 1, 2)") == pytest.approx(7.0 / 3.0, rel=1e-4)
    assert ev("rms(a.x)") == pytest.approx(math.sqrt(0.5), rel=1e-2)
    assert ev("mean(a.x * a.x) - 2 * max(time) ** 2") == pytest.approx(0.5 - 8.0, rel=1e-2)
    assert Expression("max(abs(a.x), 0, 0.25)").vector(t, v).size == 26
    expr, sense, limit = parse_constraint("max(b.y)<=3")
    assert expr.kind == "max"
    assert_copied((sense, limit), (1.0, 3.0))                  # parsed


@pytest.mark.parametrize("text, match", [
    ("max(abs(a.x)", "not valid"), ("foo(a.x)", "unknown function foo"),
    ("max(a.q)", "no signal a.q"), ("a.x", "time series, not a number"),
    ("__import__('os')", "unknown function __import__")])
def test_bad_expressions_are_named(text, match):
    t = np.linspace(0, 1, 5)
    with pytest.raises(acausal2d.Acausal2dError, match=match):
        Expression(text, known={"a.x"}).evaluate(t, {"a.x": t})


class Decay(Component):
    """x' = -a x, x(0) = 1: x(T) = exp(-a T)."""
    a = Parameter(1.0, "1/s", "rate")
    x = Variable(start=1.0, fixed=True, unit="m")

    def equations(self):
        return [der(self.x) == -self.a * self.x]


@pytest.fixture(scope="module")
def decay():
    cm = acausal2d.compile_model(Decay())
    cm.model.experiment = {"stop_time": 1.0, "intervals": 50}
    return cm


def test_optimum_on_a_bound(decay):
    opt = optimize(decay, {"a": (0.5, 0.2, 3.0)}, "final(x)")
    assert opt.success, opt.message
    assert opt.optimum[0] == pytest.approx(3.0)
    assert opt.active_bounds == ["a"]
    assert opt.objective == pytest.approx(math.exp(-3.0), rel=1e-6)


def test_optimum_on_a_constraint(decay):
    opt = optimize(decay, {"a": (0.5, 0.2, 3.0)}, "final(x)",
                   constraints=["final(x)>=%r" % math.exp(-2.4)])
    assert opt.success, opt.message
    assert opt.optimum[0] == pytest.approx(2.4, rel=1e-6)
    assert opt.constraints[0]["active"] and opt.constraints[0]["multiplier"] > 0
    assert not opt.active_bounds


def test_a_python_objective_and_a_peak_constraint(decay):
    # minimise (a - 2)^2 = (ln x(1) + 2)^2, a peak constraint that stays inactive (x <= 1)
    opt = optimize(decay, {"a": (0.5, 0.2, 3.0)},
                   lambda res: (-math.log(res.final("x")) - 2.0) ** 2,
                   constraints=["max(x) <= 1.5"])
    assert opt.success, opt.message
    assert opt.optimum[0] == pytest.approx(2.0, rel=1e-4)
    assert not opt.constraints[0]["active"]
    assert opt.constraints[0]["value"] == pytest.approx(1.0)


def test_four_bar_passes_its_precision_points():
    from acausal2d.analysis.fit import fit
    from acausal2d.io.tables import read_csv
    path = os.path.join(ROOT, "models", "four_bar_precision_points.csv")
    fr = fit(os.path.join(ROOT, "models", "four_bar_precision.py"), path,
             free={"crank.lL": (0.11, 0.05, 0.2), "dyad.lL1": (0.33, 0.2, 0.5),
                   "dyad.lL2": (0.32, 0.2, 0.5)})
    assert fr.success, fr.message
    # an independent run at the synthesised lengths through the points
    cm = acausal2d.compile_model(acausal2d.load_model(os.path.join(ROOT, "models",
                                                                   "four_bar_precision.py")))
    t, cols = read_csv(path)
    res = cm.simulate(params=dict(zip(fr.names, fr.estimate)), output_times=np.union1d(t, [1.0]))
    dist = np.hypot(np.interp(t, res.time, res["coupler.ctr2D2.x"]) - cols["coupler.ctr2D2.x"],
                    np.interp(t, res.time, res["coupler.ctr2D2.y"]) - cols["coupler.ctr2D2.y"])
    assert np.max(dist) < 1e-6
    assert np.allclose(fr.estimate, [0.10, 0.35, 0.30], atol=1e-6)   # the points' four-bar


class DecayBand(Component):
    """x' = -a x; no real z (the initialization fails) for lo < a < hi."""
    a = Parameter(1.0, "1/s", "rate")
    lo = Parameter(2.0, "1/s", "lower end of the failing band")
    hi = Parameter(2.3, "1/s", "upper end of the failing band")
    x = Variable(start=1.0, fixed=True, unit="m")
    z = Variable(start=1.0, unit="")

    def equations(self):
        c, h = (self.lo + self.hi) / 2, (self.hi - self.lo) / 2
        return [der(self.x) == -self.a * self.x, self.z ** 2 == (self.a - c) ** 2 - h ** 2]


def test_optimize_reports_a_failing_trial_point_and_goes_on():
    cm = acausal2d.compile_model(DecayBand())
    cm.model.experiment = {"stop_time": 1.0, "intervals": 20}
    # (x(1) - e^-1.5)^2 is smallest at a = 1.5; SLSQP's first step from a = 1 lands at
    # a = 2.89, inside the failing band 2.6 < a < 4
    opt = optimize(cm, {"a": (1.0, 0.1, 5.0)}, "(final(x) - %r) ** 2" % math.exp(-1.5),
                   fixed={"lo": 2.6, "hi": 4.0})
    assert opt.success, opt.message
    assert opt.optimum[0] == pytest.approx(1.5, abs=1e-4)
    assert opt.infeasible and 2.6 < opt.infeasible[0][0]["a"] < 4.0
    assert "Initialization" in opt.infeasible[0][1]
    assert "infeasible trial point a=" in opt.report()
