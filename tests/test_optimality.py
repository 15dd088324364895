"""KKT check (acausal2d.analysis.optimality) against problems whose optimum
and multipliers are known in closed form."""
import numpy as np
import pytest

from acausal2d.analysis.optimality import kkt_check


def test_bound_at_the_optimum_gives_its_multiplier():
    """min (x-2)^2 s.t. x <= 1: x* = 1, grad = -2, so nu_up = 2."""
    r = kkt_check([2 * (1.0 - 2.0)], [1.0], upper=1.0, objective=1.0)
    assert r.ok, r.message()
    assert r.active["upper"] == [0]
    assert r.multipliers["upper"][0] == pytest.approx(2.0, abs=1e-14)
    assert r.stationarity < 1e-15


def test_a_bound_on_the_wrong_side_is_not_a_minimum():
    """min x^2 s.t. x <= 1 at x = 1: the gradient +2 points into the
    feasible set; the multiplier would have to be -2, so the check fails."""
    r = kkt_check([2.0], [1.0], upper=1.0)
    assert not r.ok
    assert r.stationarity == pytest.approx(1.0)
    # bounded least squares (lsq_linear, tol 1e-10) keeps it at its bound 0
    assert 0.0 <= r.multipliers["upper"][0] <= 1e-10 * 2.0         # gradient 2


def test_equality_constraint_closed_form():
    """min x^2 + y^2 s.t. x + y = 1: (1/2, 1/2), lambda = -1."""
    x = np.array([0.5, 0.5])
    r = kkt_check(2 * x, x, eq_values=[x.sum() - 1], eq_jacobian=[[1.0, 1.0]],
                  hessian=2 * np.eye(2))
    assert r.ok, r.message()
    assert r.multipliers["eq"][0] == pytest.approx(-1.0, abs=1e-14)
    assert r.curvature == pytest.approx(2 * 1.0 / 1.0 * 0.5, rel=1e-12)   # H=2, xs=0.5, gscale=1
    off = np.array([0.6, 0.4])                     # feasible but not optimal
    assert not kkt_check(2 * off, off, eq_values=[0.0], eq_jacobian=[[1.0, 1.0]]).ok


def test_general_inequality_and_complementarity():
    """min (x-1)^2 + (y-2)^2 s.t. x + y <= 2: projection of (1,2) on the
    line gives (1/2, 3/2) with mu = 1; a point inside the set with a
    nonzero gradient fails stationarity, an infeasible one feasibility."""
    x = np.array([0.5, 1.5])
    grad = 2 * (x - [1.0, 2.0])
    r = kkt_check(grad, x, ineq_values=[x.sum() - 2], ineq_jacobian=[[1.0, 1.0]])
    assert r.ok, r.message()
    assert r.multipliers["ineq"][0] == pytest.approx(1.0, abs=1e-14)
    inside = np.array([0.4, 1.4])
    assert kkt_check(2 * (inside - [1, 2]), inside, ineq_values=[inside.sum() - 2],
                     ineq_jacobian=[[1.0, 1.0]]).stationarity > 0.5
    out = np.array([0.6, 1.6])
    bad = kkt_check(2 * (out - [1, 2]), out, ineq_values=[out.sum() - 2],
                    ineq_jacobian=[[1.0, 1.0]])
    assert not bad.ok and bad.feasibility == pytest.approx(0.2 / np.sqrt(2) / 1.6, rel=1e-12)


def test_measures_do_not_depend_on_units():
    """The same problem in other units of f and x gives the same measures:
    min k (x/s - 2)^2 s.t. x <= s, x* = s, for k, s over 12 decades."""
    base = None
    for k, s in [(1.0, 1.0), (1e6, 1e-3), (1e-6, 1e3), (3.0, 0.02)]:
        x = s * (1.0 + 1e-11)                       # slightly outside, by 1e-11 relative
        g = 2 * k * (x / s - 2) / s
        r = kkt_check([g], [x], upper=s, objective=k)
        assert r.ok
        meas = (r.stationarity, r.feasibility, r.complementarity)
        base = base or meas
        assert np.allclose(meas, base, rtol=1e-4, atol=1e-20)


def test_second_order_test_rejects_a_saddle():
    """min x^2 - y^2 at the origin is stationary but a saddle: the curvature
    measure is negative; with y fixed by an equality it is a minimum."""
    r = kkt_check([0.0, 0.0], [0.0, 0.0], hessian=np.diag([2.0, -2.0]), x_scale=1.0)
    assert not r.ok and r.curvature < 0
    fixed = kkt_check([0.0, 0.0], [0.0, 0.0], eq_values=[0.0], eq_jacobian=[[0.0, 1.0]],
                      hessian=np.diag([2.0, -2.0]), x_scale=1.0)
    assert fixed.ok and fixed.curvature > 0


def test_shapes_are_checked():
    with pytest.raises(ValueError, match="eq_jacobian"):
        kkt_check([1.0, 2.0], eq_jacobian=[[1.0, 2.0, 3.0]], eq_values=[0.0])
    with pytest.raises(ValueError, match="bounds need the point x"):
        kkt_check([1.0], upper=1.0)
