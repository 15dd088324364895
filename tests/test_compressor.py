"""Compressor of seed ch. 8.2 (models/compressor.py): belt drive with
tensioner, clutch closing at 2 s and opening at 10 s, Kloss motor, crank
drive and pneumatic cylinder.

One simulation (0..16 s, output every 5 ms plus 0.1 ms windows around
8.5 s and in the last 0.6 s before the clutch opens) feeds all checks:

- periodic steady state: the states at consecutive passes of bottom dead
  centre agree to 1e-5 (relative) and did not drift over the last second and
  a half; the span forces over the crank angle of consecutive revolutions
  agree within 1 % of their range.  The 1 % allows for the linear
  interpolation of the output samples onto a common crank-angle grid: the
  span-1 force rises by ~400 N within ~20 ms around the discharge, so a
  0.1 ms grid gives interpolation differences of about 1 N (0.3 %); the
  states themselves repeat to the integration tolerance (rtol 1e-6);
- energy: over a steady revolution the belt's work on the driven pulley
  equals the indicated work of the cylinder plus the crank-shaft bearing
  friction (1e-4 relative: kinetic energy returns in the periodic state, the
  only error is the trapezoidal rule on the 0.1 ms grid); the motor delivers
  more than the belt passes on, the difference (belt and tensioner damping,
  clutch creep) being below 1 %;
- the indicated work is within 0..5 % above the ideal single-stage
  adiabatic compressor with clearance (valve throttling losses);
- delivered mass per revolution equals the intake mass;
- start-up: the clutch slips with its capacity, then sticks; the span forces
  show a start-up peak above the steady-state peak; no span goes slack;
- run-out: after the clutch opens the compressor comes to rest.
"""
import math

import numpy as np
import pytest

from conftest import load_model_class


@pytest.fixture(scope="module")
def run():
    Compressor = load_model_class("compressor.py", "Compressor")
    import sys
    mod = sys.modules["models_compressor"]
    from acausal2d import compile_model
    cm = compile_model(Compressor())
    ot = np.unique(np.concatenate([np.linspace(0.0, 16.0, 3201),
                                   np.linspace(8.4, 8.8, 4001),
                                   np.linspace(9.4, 10.0, 6001)]))
    res = cm.simulate(stop_time=16.0, output_times=ot, rtol=1e-6)
    return mod, res


def test_periodic_steady_state(run):
    mod, res = run
    revs = mod.revolutions(res, 9.4, 10.0)
    assert len(revs) >= 4
    early = mod.revolutions(res, 8.4, 8.8)
    assert len(early) >= 2
    # states at bottom dead centre (1e-5: the crossing time is interpolated
    # linearly between output samples 0.1 ms apart, while the intake still
    # fills the cylinder there)
    for name in ("crank.w", "motor.w", "lever.phi", "cyl.p", "cyl.m"):
        vals = np.array([res.at(name, t) for t in revs + early])
        assert np.max(np.abs(vals - vals[0])) < 1e-5 * abs(vals[0]), name
    # span forces over the crank angle of consecutive revolutions
    for k in (1, 2, 3):
        name = "span%d.F" % k
        curves = [mod.over_crank_angle(res, name, revs[j], revs[j + 1])
                  for j in range(len(revs) - 1)]
        rng = curves[0].max() - curves[0].min()
        assert rng > 50.0                     # the crank load modulates every span
        for a, b in zip(curves[:-1], curves[1:]):
            assert np.max(np.abs(a - b)) < 0.01 * rng, name
        # and the revolution of ~8.5 s already looks the same
        c_early = mod.over_crank_angle(res, name, early[0], early[1])
        assert np.max(np.abs(c_early - curves[-1])) < 0.01 * rng, name


def test_energy_balance_over_a_revolution(run):
    mod, res = run
    revs = mod.revolutions(res, 9.4, 10.0)
    for j in range(len(revs) - 1):
        w = mod.cycle_work(res, revs[j], revs[j + 1])
        assert abs(w["W_belt"] - w["W_ind"] - w["W_fric"]) < 1e-4 * w["W_belt"]
        loss = w["W_motor"] - w["W_belt"]
        assert 0.0 < loss < 0.01 * w["W_motor"]
        assert w["W_fric"] > 0.0


def test_indicated_work_and_delivery_vs_ideal_compressor(run):
    mod, res = run
    revs = mod.revolutions(res, 9.4, 10.0)
    w = mod.cycle_work(res, revs[0], revs[1])
    # ideal single-stage adiabatic compressor with clearance
    kappa, p1, p2 = 1.4, 1e5, 8e5
    A = math.pi * mod.BORE ** 2 / 4
    V_s = A * 2 * mod.RC
    eps = A * mod.H_DEAD / V_s
    lam = 1 - eps * ((p2 / p1) ** (1 / kappa) - 1)          # volumetric efficiency
    W_ideal = kappa / (kappa - 1) * p1 * lam * V_s * ((p2 / p1) ** ((kappa - 1) / kappa) - 1)
    assert 1.0 < w["W_ind"] / W_ideal < 1.05
    # mass delivered per revolution equals the intake, near the ideal one
    t = res.time
    sel = (t >= revs[0]) & (t <= revs[1])
    tt = t[sel]

    def integ(y):
        return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(tt)))
    m_out = integ(res["cyl.mdot_out"][sel])
    m_in = integ(res["cyl.mdot_in"][sel])
    assert abs(m_out - m_in) < 2e-3 * m_in
    m_ideal = p1 * lam * V_s / (287.0 * 293.15)
    assert 0.9 < m_out / m_ideal < 1.0


def test_start_up_clutch_and_span_peaks(run):
    mod, res = run
    t = res.time
    before = t < 2.0 - 1e-9
    # clutch open: belt drive at rest with the pretension in every span
    for k in (1, 2, 3):
        assert np.max(np.abs(res["span%d.F" % k][before] - mod.F0)) < 1e-6
    assert res.at("motor.w", 1.9) == pytest.approx(157.07963267948966, rel=1e-6)
    # the clutch slips with its full capacity right after closing
    T_cap = 0.3 * 1500.0 * 0.11
    slip = (t > 2.05) & (t < 2.06)
    assert np.max(np.abs(np.abs(res["clutch.tau"][slip]) - T_cap)) < 1e-9
    # ... and sticks in the steady state
    steady = (t > 9.4) & (t < 10.0)
    assert np.max(np.abs(res["clutch.w_rel"][steady])) < 0.01
    # start-up peak above the steady-state peak of the tight span
    assert res["span1.F"][(t > 2.0) & (t < 2.3)].max() > 1.4 * res["span1.F"][steady].max()
    # no span goes slack
    for k in (1, 2, 3):
        assert res["span%d.F" % k].min() > 100.0


def test_run_out_after_opening(run):
    mod, res = run
    t = res.time
    # the motor runs idle, the compressor comes to rest
    assert res.final("motor.w") == pytest.approx(157.07963267948966, rel=1e-5)
    assert np.max(np.abs(res["crank.w"][t > 15.5])) < 0.5
    assert np.max(np.abs(res["clutch.tau"][t > 10.05])) < 1e-12
