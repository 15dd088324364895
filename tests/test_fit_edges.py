"""Issue 29, Seen 6: fit statistics at their edges, against the closed form
x(t) = c/a + (1 - c/a) exp(-a t) of x' = -a x + c, x(0) = 1, fitted by
scipy.optimize.curve_fit.  Fewer measured values than parameters + 1 is
an error; an estimate held by its bound is reported as such (no interval,
not a regular optimum, exit 3); the comparison tube comes from the noise
of the data, not from the fit's residual; an option or a parameter given
twice is an error."""
import json
import textwrap

import numpy as np
import pytest
from scipy.optimize import curve_fit
from scipy.stats import t as student

import acausal2d
from acausal2d import Component, Parameter, Variable, der
from acausal2d.analysis.fit import KKT_TOL, fit
from acausal2d.analysis.fit_report import COMPARE_TUBE, data_noise
from conftest import assert_copied
from acausal2d.cli import main

RTOL = 1e-10
"""The runs' tolerance here: the finite-difference Jacobian (step 1e-3
relative) is then exact to about RTOL / 1e-3 = 1e-7 relative."""

WIDTH_RTOL = 1e-3
"""Our standard errors against curve_fit's: the estimates agree to
KKT_TOL = 1e-2 standard errors (polished towards 1e-3), which changes s^2
only to second order and J by about 1e-2 std / a relative (< 1e-4 here);
the Jacobian is exact to 1e-7; 1e-3 leaves a margin of 10."""

MODEL = '''
from acausal2d import Component, Parameter, Variable, der


class Decay(Component):
    a = Parameter(1.0, "1/s", "rate")
    c = Parameter(0.0, "m/s", "inflow")
    x = Variable(start=1.0, fixed=True, unit="m")

    def equations(self):
        return [der(self.x) == -self.a * self.x + self.c]
'''


class Decay(Component):
    """x' = -a x + c, x(0) = 1."""
    a = Parameter(1.0, "1/s", "rate")
    c = Parameter(0.0, "m/s", "inflow")
    x = Variable(start=1.0, fixed=True, unit="m")

    def equations(self):
        return [der(self.x) == -self.a * self.x + self.c]


def closed(t, a, c=0.0):
    return c / a + (1.0 - c / a) * np.exp(-a * t)


def data(n, sigma=0.005, seed=3, a=1.5, c=0.0, offset=0.0, t1=3.0):
    t = np.linspace(0.05, t1, n)
    y = closed(t, a, c) + offset + np.random.default_rng(seed).normal(0.0, sigma, t.size)
    return t, {"x": y}


@pytest.fixture(scope="module")
def decay():
    return acausal2d.compile_model(Decay())


def reference(t, y, a0=1.0):
    """curve_fit on the closed form with c = 0: (estimate, std, half-width of the 95 % CI)."""
    p, cov = curve_fit(lambda tt, a: closed(tt, a), t, y, p0=[a0])
    std = float(np.sqrt(cov[0, 0]))
    return p[0], std, student.ppf(0.975, t.size - 1) * std


def test_seen6_one_point_for_one_parameter_is_an_error(decay):
    t, cols = data(1)
    with pytest.raises(acausal2d.Acausal2dError,
                       match=r"1 measured value for 1 free parameter \(a\).*at least 2"):
        fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0)})
    t, cols = data(2)
    with pytest.raises(acausal2d.Acausal2dError, match=r"2 measured values for 2 free "
                       r"parameters \(a, c\).*at least 3"):
        fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0), "c": (0.0, -1, 1)})


@pytest.mark.parametrize("n", [2, 30])
def test_seen6_interval_widths_match_curve_fit_on_the_closed_form(decay, n):
    t, cols = data(n)
    fr = fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0)}, fixed={"c": 0.0}, rtol=RTOL)
    assert fr.success, fr.message
    a, std, half = reference(t, cols["x"])
    assert fr.dof == n - 1
    assert fr.std[0] == pytest.approx(std, rel=WIDTH_RTOL)
    assert (fr.ci95[0][1] - fr.ci95[0][0]) / 2 == pytest.approx(half, rel=WIDTH_RTOL)
    assert abs(fr.estimate[0] - a) <= KKT_TOL * std


def test_seen6_estimate_held_by_its_bound_has_no_interval(decay):
    # data in the wrong unit (mm for m): x = exp(-a t) <= 1 comes closest to 1000 x at a = 0
    t, cols = data(30)
    fr = fit(decay, (t, {"x": 1000.0 * cols["x"]}), free={"a": (1.0, 0.0, 5.0)},
             fixed={"c": 0.0})
    assert fr.at_bound == {"a": "lower"}
    assert_copied(fr.estimate[0], 0.0)          # put on its bound
    assert np.isnan(fr.std[0]) and np.all(np.isnan(fr.ci95[0]))
    assert not fr.success and "bounds hold a at its lower bound 0" in fr.message and "KKT point" in fr.message
    report = fr.report()
    assert "at bound" in report and "NOT a regular optimum" in report
    doc = fr.to_dict()
    assert doc["at_bound"] == {"a": "lower"} and doc["parameters"]["a"]["std"] is None
    assert not fr.compare().passed           # 1000x the data lies far outside its noise


def test_seen6_other_intervals_are_those_with_the_held_estimate_fixed(decay):
    # the data's inflow c = -0.2 lies below the bound 0: c is held there, and a's interval
    # is curve_fit's of exp(-a t) (c fixed at 0) with m - 1 degrees of freedom
    t, cols = data(40, a=1.5, c=-0.2)
    fr = fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0), "c": (0.1, 0.0, 1.0)}, rtol=RTOL)
    assert fr.at_bound == {"c": "lower"}
    assert_copied(fr.estimate[1], 0.0)          # put on its bound
    a, std, half = reference(t, cols["x"])
    assert fr.std[0] == pytest.approx(std, rel=WIDTH_RTOL)
    assert (fr.ci95[0][1] - fr.ci95[0][0]) / 2 == pytest.approx(half, rel=WIDTH_RTOL)
    assert np.isnan(fr.std[1]) and np.isnan(fr.correlation[0, 1])


def test_seen6_noise_estimate_of_the_data():
    # 2000 points of a smooth curve plus N(0, 0.01^2): the median estimator's standard
    # error is about sqrt(1.36 / n) = 2.6 % (times ~1.5 for the neighbours' correlation);
    # 15 % is about four of them
    t = np.linspace(0.0, 2.0, 2000)
    for seed in (1, 2):
        y = np.sin(3 * t) + np.random.default_rng(seed).normal(0.0, 0.01, t.size)
        assert data_noise(t, y) == pytest.approx(0.01, rel=0.15)
    uneven = np.sort(np.random.default_rng(5).uniform(0.0, 2.0, 2000))
    y = np.sin(3 * uneven) + np.random.default_rng(6).normal(0.0, 0.01, uneven.size)
    assert data_noise(uneven, y) == pytest.approx(0.01, rel=0.15)
    assert data_noise(t, 2 * t + 1) == pytest.approx(0.0, abs=1e-12)   # a line: no noise
    assert np.isnan(data_noise(t[:2], t[:2]))


def test_seen6_compare_tube_comes_from_the_data_not_the_fit(decay):
    # a model error (the data's offset 0.05, the model decays to 0) the fit cannot remove:
    # residuals ~0.05 against noise 0.005; a tube of 4 residual std would pass, the
    # data's noise fails it unless the user's tolerance covers the model error
    t, cols = data(60, offset=0.05)
    fr = fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0)}, fixed={"c": 0.0})
    assert fr.success, fr.message
    assert fr.noise["x"] == pytest.approx(0.005, rel=0.5)
    assert fr.tolerance("x") == pytest.approx(COMPARE_TUBE * fr.noise["x"])
    cmp = fr.compare()
    assert not cmp.passed and cmp.rows[0].max_deviation > 2 * fr.tolerance("x")
    assert COMPARE_TUBE * fr.residual_std > cmp.rows[0].max_deviation    # the old tube passed
    loose = fit(decay, (t, cols), free={"a": (1.0, 0.1, 5.0)}, fixed={"c": 0.0}, abs_tol=0.1)
    assert loose.tolerance("x") == pytest.approx(COMPARE_TUBE * loose.noise["x"] + 0.1)
    assert loose.compare().passed
    good = fit(decay, data(60), free={"a": (1.0, 0.1, 5.0)}, fixed={"c": 0.0})
    assert good.compare().passed                                          # noise only


def test_seen6_a_parameter_given_twice_is_an_error(decay):
    t, cols = data(30)
    with pytest.raises(acausal2d.Acausal2dError, match="a is given twice"):
        fit(decay, (t, cols), free=["a=1:0.1:5", "a=2:0.1:5"])
    with pytest.raises(acausal2d.Acausal2dError, match="a is given twice"):
        fit(decay, (t, cols), free={"a,c": 1.0, "a": 2.0})
    with pytest.raises(acausal2d.Acausal2dError, match="a: also given as a fixed value"):
        fit(decay, (t, cols), free={"a": 1.0}, fixed={"a": 2.0})


@pytest.fixture
def files(tmp_path):
    model = tmp_path / "decay.py"
    model.write_text(textwrap.dedent(MODEL))
    t, cols = data(30)
    csv = tmp_path / "measured.csv"
    mm = tmp_path / "measured_mm.csv"
    for path, factor in ((csv, 1.0), (mm, 1000.0)):
        path.write_text("time,x\n" + "".join("%.17g,%.17g\n" % (a, factor * b)
                                             for a, b in zip(t, cols["x"])))
    return str(model), str(csv), str(mm), str(tmp_path / "out")


@pytest.mark.parametrize("extra, message", [
    (["--free", "a=2:0.1:5"], "a is given twice"),
    (["--data", "other.csv"], "--data is given twice"),
    (["--set", "c=0", "--set", "c=1"], "--set c is given twice"),
    (["--map", "x=x", "--map", "x=x"], "--map x is given twice"),
    (["--weights", "x=1,x=2"], "--weights x is given twice"),
    (["--set", "a=1"], "also given as a fixed value"),
])
def test_seen6_cli_option_given_twice_exits_2(files, capsys, extra, message):
    model, csv, _, out = files
    code = main(["fit", model, "--data", csv, "--free", "a=1:0.1:5", "--out", out] + extra)
    err = capsys.readouterr().err
    assert code == 2 and message in err and "Traceback" not in err


def test_seen6_cli_exit_codes_of_a_bound_and_of_the_tube(files, capsys):
    model, csv, mm, out = files
    assert main(["fit", model, "--data", csv, "--free", "a=1:0.1:5", "--out", out]) == 0
    assert "PASS" in capsys.readouterr().out
    code = main(["fit", model, "--data", mm, "--free", "a=1:0:5", "--out", out])
    cap = capsys.readouterr()
    assert code == 3 and "not a regular optimum" in cap.err and "bounds hold a" in cap.err
    assert "at bound" in cap.out and "FAIL" in cap.out
    assert json.loads(open(out + "/fit.json").read())["at_bound"] == {"a": "lower"}
    # a converged fit outside the data's tube (the data's offset 0.05): exit 1, the
    # compare's code; the user's tolerance for that model error lets it pass
    shifted = out + "_offset.csv"
    t, cols = data(30, offset=0.05)
    with open(shifted, "w") as fh:
        fh.write("time,x\n" + "".join("%.17g,%.17g\n" % p for p in zip(t, cols["x"])))
    assert main(["fit", model, "--data", shifted, "--free", "a=1:0.1:5", "--out", out]) == 1
    cap = capsys.readouterr()
    assert "FAIL" in cap.out and "outside the tube of the measured noise" in cap.err
    assert main(["fit", model, "--data", shifted, "--free", "a=1:0.1:5", "--abs-tol", "0.1",
                 "--out", out]) == 0
