"""Issue 29, Seen 7: optimisation from an infeasible start.  A peak
constraint ``max(mass.s) <= 0.102`` on the step response of a
mass-spring-damper (tests/data/mass_spring_damper.py) stays one constraint
for SLSQP, so the search recovers from starts on either side of it and
reaches the analytic optimum d* = 33.0800; checked by the KKT conditions
against the closed form, not by the optimiser's flag.  Missing bounds and
objectives that are not numbers are errors naming the parameter or the
objective."""
import json
import math
import os

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis.optimize import optimize
from acausal2d.cli import main

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MSD = os.path.join(ROOT, "tests", "data", "mass_spring_damper.py")
M, C, F = 1.0, 450.0, 45.0               # the model's mass, spring rate and force
S_END = F / C                             # 0.1 m
PEAK = 0.102                              # the constraint: 2 % overshoot
INTERVALS, STOP, RTOL = 2000, 1.0, 1e-9
OBJECTIVE = "integral((mass.s - %r) ** 2)" % S_END
CONSTRAINT = "max(mass.s) <= %r" % PEAK
W_N = math.sqrt(C / M)


def zeta_of(d):
    return d / (2.0 * math.sqrt(C * M))


def peak(d):
    """Continuous peak of the step response: S_END (1 + exp(-pi zeta / sqrt(1 - zeta^2)));
    S_END (approached from below) without overshoot, zeta >= 1."""
    z = zeta_of(d)
    if z >= 1.0:
        return S_END
    return S_END * (1.0 + math.exp(-math.pi * z / math.sqrt(1.0 - z * z)))


def ise(d):
    """int_0^inf (s - S_END)^2 dt = S_END^2 (1 + 4 zeta^2) / (4 zeta omega_n)."""
    z = zeta_of(d)
    return S_END ** 2 * (1.0 + 4.0 * z * z) / (4.0 * z * W_N)


def d_star():
    """peak(d*) = PEAK: zeta* = a / sqrt(1 + a^2), a = -ln(0.02) / pi."""
    a = -math.log(PEAK / S_END - 1.0) / math.pi
    return 2.0 * math.sqrt(C * M) * a / math.sqrt(1.0 + a * a)


def d_tolerance(d):
    """How far the optimum of the sampled problem may lie from d*: the
    output grid h samples the peak up to |s''| h^2 / 8 below it (s'' =
    -S_END omega_n^2 OS at the peak), the integrator adds up to 100 rtol
    of the peak (IDA's global error over the run, not its local rtol); both
    divided by |d peak / d d| (central difference of the closed form)."""
    h = STOP / INTERVALS
    grid = S_END * W_N ** 2 * (peak(d) / S_END - 1.0) * h * h / 8.0
    slope = abs(peak(d * (1 + 1e-6)) - peak(d * (1 - 1e-6))) / (2e-6 * d)
    return (grid + 100.0 * RTOL * PEAK) / slope


@pytest.fixture(scope="module")
def msd():
    return acausal2d.compile_model(acausal2d.load_model(MSD))


def test_closed_form_of_the_reference():
    assert d_star() == pytest.approx(33.0800, abs=5e-5)   # the analytic optimum (4 decimals)
    assert peak(d_star()) == pytest.approx(PEAK, rel=1e-12)


@pytest.mark.parametrize("d0", [10.0, 25.0, 50.0])
def test_seen7_peak_constraint_recovers_from_either_side_to_the_analytic_optimum(msd, d0):
    opt = optimize(msd, {"spring.d": (d0, 1.0, 100.0)}, OBJECTIVE, constraints=[CONSTRAINT],
                   intervals=INTERVALS, rtol=RTOL)
    assert (peak(d0) > PEAK) == (d0 < d_star())    # 10 and 25 start infeasible, 50 feasible
    d = opt.optimum[0]
    assert abs(d - d_star()) <= d_tolerance(d_star()), (d, opt.message)
    # first-order optimality, not SLSQP's flag: the KKT check of the sampled problem ...
    kkt = opt.kkt
    assert opt.success and kkt.ok, opt.message
    assert max(kkt.stationarity, kkt.feasibility, kkt.complementarity) <= kkt.tol
    con = opt.constraints[0]
    assert con["active"] and con["value"] == pytest.approx(PEAK, abs=100 * RTOL * PEAK)
    # ... and its multiplier against the closed form: mu = ISE'(d) / -peak'(d) in the
    # scaled units of the problem (objective / f0, constraint / g_scale); the sampled
    # peak's gradient differs from the continuous one by O(omega_d h) = 0.7 %
    e = 1e-5 * d
    mu = ((ise(d + e) - ise(d - e)) / (peak(d - e) - peak(d + e))
          * opt.problem.g_scale[0] / opt.problem.f0)
    assert con["multiplier"] == pytest.approx(mu, rel=0.02)
    # the objective is the closed-form ISE (trapezoidal rule at h: (omega h)^2 / 12 relative)
    assert opt.objective == pytest.approx(ise(d), rel=1e-4)


def test_seen7_vary_without_bounds_is_an_error_naming_the_parameter(msd, tmp_path, capsys):
    with pytest.raises(acausal2d.Acausal2dError, match="vary spring.d: give its bounds"):
        optimize(msd, {"spring.d": 25.0}, OBJECTIVE)
    code = main(["optimize", MSD, "--vary", "spring.d=25", "--objective", OBJECTIVE,
                 "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2 and "spring.d" in err and "START:LO:HI" in err and "Traceback" not in err


def test_seen7_nan_objective_is_an_error_naming_it(msd, tmp_path, capsys):
    nan = "mean(mass.s) / (final(mass.v) * 0)"          # 0/0 and x/0: not a number
    with pytest.raises(acausal2d.Acausal2dError, match=r"objective mean\(mass.s\).*not a number"):
        optimize(msd, {"spring.d": (25.0, 1.0, 100.0)}, nan, intervals=50)
    with pytest.raises(acausal2d.Acausal2dError, match=r"constraint final\(mass.s\)/0"):
        optimize(msd, {"spring.d": (25.0, 1.0, 100.0)}, OBJECTIVE, intervals=50,
                 constraints=["final(mass.s)/0 <= 1"])
    code = main(["optimize", MSD, "--vary", "spring.d=25:1:100", "--objective", nan,
                 "--intervals", "50", "--grid", "3", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 2 and "not a number" in err and "Traceback" not in err


def test_seen7_grid_where_every_run_fails_is_an_error_naming_the_objective(msd, tmp_path):
    from acausal2d.cli.optimize import _grid_check
    opt = optimize(msd, {"spring.d": (40.0, 1.0, 100.0)}, OBJECTIVE, intervals=50)

    class Args:
        grid, grid_span, out = 3, 0.01, str(tmp_path)
    opt.grid = lambda rel, points: (np.zeros((3, 1)), np.full(3, np.nan))   # every run failed
    with pytest.raises(acausal2d.Acausal2dError, match=r"--grid: the objective integral"):
        _grid_check(opt, Args, Args.out)


def test_seen7_a_parameter_or_option_given_twice_is_an_error(msd, tmp_path, capsys):
    with pytest.raises(acausal2d.Acausal2dError, match="spring.d is given twice"):
        optimize(msd, ["spring.d=25:1:100", "spring.d=30:1:100"], OBJECTIVE)
    with pytest.raises(acausal2d.Acausal2dError, match="also given as a fixed value"):
        optimize(msd, {"spring.d": (25.0, 1.0, 100.0)}, OBJECTIVE, fixed={"spring.d": 3.0})
    base = ["optimize", MSD, "--vary", "spring.d=25:1:100", "--objective", OBJECTIVE,
            "--out", str(tmp_path)]
    assert main(base + ["--vary", "spring.d=30:1:100"]) == 2
    assert "spring.d is given twice" in capsys.readouterr().err
    assert main(base + ["--objective", "final(mass.s)"]) == 2
    assert "--objective is given twice" in capsys.readouterr().err
    assert not (tmp_path / "optimize.json").exists()


def test_seen7_cli_reaches_the_optimum_from_an_infeasible_start(tmp_path, capsys):
    code = main(["optimize", MSD, "--vary", "spring.d=10:1:100", "--objective", OBJECTIVE,
                 "--constraint", CONSTRAINT, "--intervals", str(INTERVALS), "--rtol", str(RTOL),
                 "--out", str(tmp_path)])
    assert code == 0, capsys.readouterr()
    doc = json.loads((tmp_path / "optimize.json").read_text())
    assert abs(doc["optimum"]["spring.d"] - d_star()) <= d_tolerance(d_star())
    assert doc["active_constraints"] == [CONSTRAINT]
