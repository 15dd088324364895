"""The nine four-link mechanisms of seed Bild 2.2 (models/four_link_mechanisms.py):
each completes one full crank revolution (or its full slider stroke) at
constant speed and its output position matches the closed-form VDI 2729
solution to 1e-8 over the run."""
import math

import numpy as np
import pytest

import acausal2d
from vdi2729_reference import e, line_intersection, n, vdi_ddd, vdi_dds, vdi_dsd, wrap

TOL = 1e-8


def simulate(cls):
    model = cls()
    # rtol 1e-10 so the algebraic positions are exact to ~1e-11
    times = np.linspace(0.0, 1.0, 201)
    return acausal2d.simulate(model, stop_time=1.0, rtol=1e-10, output_times=times)


def crank_pin(phi):
    return 0.1 * e(phi)


def check_crank(res):
    phi = res["crank.phiL"]
    assert abs(phi[-1] - phi[0] - 2 * math.pi) < 1e-12          # one full revolution
    assert np.max(np.abs(phi - 2 * math.pi * res.time)) < 1e-12
    return phi


def check_slider(res, s0, stroke):
    xG = res["slider.xG"]
    assert abs(xG[0] - s0) < 1e-12 and abs(xG[-1] - (s0 + stroke)) < 1e-12   # full stroke
    return xG


def test_dddd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DDDD"))
    phi = check_crank(res)
    B0 = np.array([0.4, 0.0])
    err = [wrap(res["dyad.phiL2"][k] - math.atan2(*(vdi_ddd(crank_pin(p), B0, 0.35, 0.3, 1)
                                                  - B0)[::-1]))
           for k, p in enumerate(phi)]
    assert np.max(np.abs(err)) < TOL
    # the rocker oscillates (crank-rocker): the output stays continuous
    assert np.max(np.abs(np.diff(res["dyad.phiL2"]))) < 0.1


def test_ddds(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DDDS"))
    phi = check_crank(res)
    ref = [vdi_dds(crank_pin(p), np.array([0.0, -0.02]), 0.0, 0.35, 0.02, 1)[1] for p in phi]
    assert np.max(np.abs(res["dyad.xG"] - ref)) < TOL


def test_sddd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "SDDD"))
    xG = check_slider(res, 0.0, 0.2)
    B0 = np.array([0.1, 0.25])
    ref = [math.atan2(*(vdi_ddd(np.array([x, 0.0]), B0, 0.25, 0.15, -1) - B0)[::-1]) for x in xG]
    assert np.max(np.abs(wrap(res["dyad.phiL2"] - ref))) < TOL


def test_ddsd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DDSD"))
    phi = check_crank(res)
    ref = [vdi_dsd(np.array([-0.25, 0.0]), crank_pin(p), 0.02) for p in phi]
    assert np.max(np.abs(wrap(res["dyad.phiU"] - [r[0] for r in ref]))) < TOL
    assert np.max(np.abs(res["dyad.xG"] - [r[1] for r in ref])) < TOL


def test_dsdd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DSDD"))
    phi = check_crank(res)
    B0 = np.array([0.3, 0.1])
    err = []
    for k, p in enumerate(phi):
        P, _ = vdi_dds(B0, crank_pin(p), p, 0.4, 0.0, 1)
        err.append(wrap(res["dyad.phiL"][k] - math.atan2(*(B0 - P)[::-1])))
    assert np.max(np.abs(err)) < TOL
    # the output link turns fully once with the crank
    assert abs(res["dyad.phiL"][-1] - res["dyad.phiL"][0] - 2 * math.pi) < 1e-9


def test_sdds(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "SDDS"))
    xG = check_slider(res, -0.2, 0.4)
    ref = [vdi_dds(np.array([x, 0.0]), np.zeros(2), math.pi / 2, 0.3, 0.0, 1)[1] for x in xG]
    assert np.max(np.abs(res["dyad.xG"] - ref)) < TOL
    assert np.max(np.abs(res["dyad.xG"] - np.sqrt(0.09 - xG ** 2))) < TOL


def _ssd_travels(P1, a1, v1, P2, v2, phiv):
    a2 = a1 + phiv
    xG1, t = line_intersection(P1 + v1 * n(a1), e(a1), P2 - v2 * n(a2), e(a2))
    return xG1, -t


def test_ssdd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "SSDD"))
    phi = check_crank(res)
    ref = np.array([_ssd_travels(np.array([-0.3, 0.0]), 0.0, 0.05, crank_pin(p), 0.0,
                                 math.pi / 2) for p in phi])
    assert np.max(np.abs(res["dyad.xG1"] - ref[:, 0])) < TOL
    assert np.max(np.abs(res["dyad.xG1"] - (0.3 + 0.1 * np.cos(phi)))) < TOL   # Scotch yoke


def test_dssd(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DSSD"))
    phi = check_crank(res)
    ref = np.array([_ssd_travels(crank_pin(p), p, 0.0, np.array([0.05, 0.02]), 0.0,
                                 math.pi / 2) for p in phi])
    assert np.max(np.abs(res["dyad.xG1"] - ref[:, 0])) < TOL
    assert np.max(np.abs(res["dyad.xG2"] - ref[:, 1])) < TOL
    assert np.max(np.abs(res["dyad.phiS2"] - phi - math.pi / 2)) < TOL


def test_dsds(model_class):
    res = simulate(model_class("four_link_mechanisms.py", "DSDS"))
    xG = check_slider(res, -0.2, 0.4)
    ref = [vdi_dsd(np.array([0.0, 0.15]), np.array([x, 0.0]), 0.0)[0] for x in xG]
    assert np.max(np.abs(wrap(res["dyad.phiU"] - ref))) < TOL


@pytest.mark.parametrize("name", ["DDDD", "DDSD"])
def test_gravity_changes_only_forces(model_class, name):
    """Kinematic drive: gravity changes the drive torque, not the motion."""
    cm = acausal2d.compile_model(model_class("four_link_mechanisms.py", name)())
    a = cm.simulate(stop_time=0.5, rtol=1e-8, intervals=50)
    b = cm.simulate(stop_time=0.5, rtol=1e-8, intervals=50,
                    params={"world.g": (0.0, 0.0)})
    out = "dyad.phiL2" if name == "DDDD" else "dyad.phiU"
    assert np.max(np.abs(a[out] - b[out])) < 1e-8
    assert np.max(np.abs(a["preset.tau"] - b["preset.tau"])) > 1e-3
