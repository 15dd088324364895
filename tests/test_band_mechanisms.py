"""Band mechanisms of seed Bild 2.6-2.9 (models/band_mechanisms.py): the
static balances of the massless links at every output point, computed from
the result's geometry (contact point, band direction, pivots):

- drum: drive torque = -(K - O) x (F u), u the band direction away from K;
- DB~DD: load torque = F h_B and the ratio omega_rocker / omega_drum =
  -tau_drive / T_load (power balance, no losses);
- DB~DS: the band's component along the guide = the slider load;
- nozzle and spring mechanisms: the band force from the band material
  wound off the cam (its arc length, numpy) and the positions."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d import cli

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import band_mechanisms as bm  # noqa: E402


def _run(cls):
    return acausal2d.simulate(cls(), stop_time=2.0, intervals=40, rtol=1e-10)


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def _drum_balance(res, ux, uy):
    K = res["drum.ctrK1.x"], res["drum.ctrK1.y"]
    expect = -_cross(K[0], K[1], res["band.F"] * ux, res["band.F"] * uy)
    assert np.max(np.abs(res["drive.tau"] - expect)) < 1e-8 * np.max(np.abs(expect))
    assert np.ptp(res["drive.tau"]) > 0.1 * np.max(np.abs(res["drive.tau"]))   # not constant


def test_dbdd_balance_and_ratio():
    res = _run(bm.DBDD)
    g = res["band.gamma"]                      # tip -> drum: u = -e on the drum side
    _drum_balance(res, -np.cos(g), -np.sin(g))
    tip = res["rocker.ctr2D2.x"] - 0.2, res["rocker.ctr2D2.y"] - 0.12
    h_B = _cross(tip[0], tip[1], np.cos(g), np.sin(g))
    assert np.max(np.abs(res["band.F"] * np.abs(h_B) - 2.0)) < 1e-8
    ratio = res["der(rocker.phiL)"] / res["der(drum.phi)"]
    assert np.max(np.abs(ratio + res["drive.tau"] / 2.0)) < 1e-7
    assert np.ptp(ratio) > 0.05                # a non-constant ratio


def test_dbdd_with_the_rocker_as_ground():
    """The neighbour of DB~DD by a change of the ground link: the band's
    moment about the moving drum pivot balances the 1 N m between crank and
    drum, and the power of the crank drive is the power of that torque."""
    res = _run(bm.DBDDInverted)
    g = res["band.gamma"]
    K = res["drum.ctrK1.x"], res["drum.ctrK1.y"]
    P = res["crank.ctr2D2.x"], res["crank.ctr2D2.y"]
    h_D = _cross(K[0] - P[0], K[1] - P[1], np.cos(g), np.sin(g))
    assert np.max(np.abs(res["band.F"] * np.abs(h_D) - 1.0)) < 1e-8
    power = res["drive.tau"] * bm.OM + 1.0 * res["drum.w_rel"]
    assert np.max(np.abs(power)) < 1e-7 * np.max(np.abs(res["drive.tau"]))
    assert np.ptp(res["drive.tau"]) > 1.0


def test_dbds_balance():
    res = _run(bm.DBDS)
    g = res["band.gamma"]
    _drum_balance(res, -np.cos(g), -np.sin(g))
    assert np.max(np.abs(res["band.F"] * np.abs(np.cos(g)) - 20.0)) < 1e-8


def test_sbds_cross_slider_balance():
    """SB~DS: the band's vertical component carries the 10 N slider load, and
    the carriage drive's power is the load's (massless, no losses)."""
    res = _run(bm.SBDS)
    g = res["band.gamma"]
    assert np.max(np.abs(res["band.F"] * np.abs(np.sin(g)) - 10.0)) < 1e-8
    power = res["drive.tau"] * 0.05 - 10.0 * res["der(slider.xG)"]
    assert np.max(np.abs(power)) < 1e-8 * np.max(np.abs(res["drive.tau"]))
    assert np.ptp(res["drive.tau"]) > 1.0           # a non-constant ratio
    # the plate does not turn: drum.phi stays within the integrator's atol
    # (rtol 1e-10 x nominal 1 rad)
    assert np.max(np.abs(res["drum.phi"])) <= 1e-10


def _wound_off(res):
    """Band material paid out by the cam since t = 0 (w = +1: ctrB1.L = s)."""
    C = bm.SupportContour(bm.RC, a=(bm.E,), b=(0.0,))
    k = res["drum.kappa1"]
    return C.s(k) - C.s(k[0])


def test_nozzle_mechanism_band_force():
    res = _run(bm.Nozzle3)
    g1 = res["band.gamma1"]
    _drum_balance(res, np.cos(g1), np.sin(g1))
    N, A = bm.Nozzle3.NOZZLE, bm.Nozzle3.ANCHOR
    K = res["drum.ctrK1.x"], res["drum.ctrK1.y"]
    length = np.hypot(N[0] - K[0], N[1] - K[1]) + np.hypot(A[0] - N[0], A[1] - N[1])
    l_u = length[0] / 1.2 + _wound_off(res)                 # 20 % pre-strain at t = 0
    F = 500.0 * (length - l_u) / l_u
    assert np.max(np.abs(res["band.F"] - F)) < 1e-6 * np.max(F)


def test_spring_mechanism_band_force():
    res = _run(bm.Spring3)
    g = res["band.gamma"]
    _drum_balance(res, np.cos(g), np.sin(g))
    A = bm.Spring3.ANCHOR
    K = res["drum.ctrK1.x"], res["drum.ctrK1.y"]
    length = np.hypot(A[0] - K[0], A[1] - K[1])
    band = length[0] - 0.1 - 0.05 + _wound_off(res)         # band pieces: start 0.05 extension
    F = 400.0 * (length - band - 0.1)
    assert np.max(np.abs(res["band.F"] - F)) < 1e-8 * np.max(F)


@pytest.mark.parametrize("name", ["DBDD", "Spring3"])
def test_band_mechanism_from_the_cli_writes_figures(tmp_path, name):
    code = cli.main(["simulate", os.path.join(ROOT, "models", "band_mechanisms.py"),
                     "--model", name, "--out", str(tmp_path)])
    assert code == 0
    assert (tmp_path / "forces.png").exists() and (tmp_path / "drive_torque.png").exists()


def test_nozzle_slotted_crank_bild_3_1_f():
    """Bild 3.1 f: the rocker angle of the slotted crank is the closed form
    psi = atan2(R sin phi - y_B0, R cos phi - x_B0); the band pulls E towards
    the nozzle with the band force (frictionless nozzle: one force in both
    pieces); the massless linkage's power balance drive torque x omega + F
    u . v_E = 0 with v_E from the closed-form psi'; the drum obeys J psi'' =
    T - F r.  Bounds: rtol 1e-10 on O(0.1 m) and O(10 N) quantities."""
    C = bm.NozzleSlottedCrank
    res = acausal2d.simulate(C(), stop_time=1.0, intervals=50, rtol=1e-10)
    R, (bx, by), L = C.R_CRANK, C.B0, C.L_ROCKER
    phi, om = res["drive.phi"], 2 * np.pi
    X, Y = R * np.cos(phi) - bx, R * np.sin(phi) - by
    psi = np.arctan2(Y, X)
    assert np.max(np.abs(np.unwrap(res["rocker.phiU"]) - np.unwrap(psi))) < 1e-8
    dpsi = (X * R * np.cos(phi) * om + Y * R * np.sin(phi) * om) / (X ** 2 + Y ** 2)
    E = bx + L * np.cos(psi), by + L * np.sin(psi)
    d = C.NOZZLE[0] - E[0], C.NOZZLE[1] - E[1]
    u = d[0] / np.hypot(*d), d[1] / np.hypot(*d)
    F = res["band.F"]
    assert np.all(F > 0.5 * C.T_TAKE_UP / C.R_DRUM)
    pull = res["arm.frame_b.fx"] * u[0] + res["arm.frame_b.fy"] * u[1]
    assert np.max(np.abs(np.abs(pull) - F)) < 1e-7 * np.max(F)
    v_along = L * dpsi * (-np.sin(psi) * u[0] + np.cos(psi) * u[1])
    power = res["drive.tau"] * om + F * v_along
    assert np.max(np.abs(power)) < 1e-6 * np.max(np.abs(F * v_along))
    assert np.ptp(res["drive.tau"]) > 0.5                      # the band is pulled out and back
    drum = C.J_DRUM * res["der(der(drum.phi))"] - (C.T_TAKE_UP - F * C.R_DRUM)
    assert np.max(np.abs(drum)) < 1e-6 * C.T_TAKE_UP
