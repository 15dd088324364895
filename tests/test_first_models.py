"""The "First models" pages of the documentation (docs/first-models/): every
file models/first_*.py runs with its own experiment and its result agrees
with the closed form its page works out by hand.  The closed forms are
written out again here, independently of the files' own ``hand_check``
(which the pages print), and both are compared."""
import glob
import importlib.util
import math
import os

import numpy as np
import pytest

import acausal2d

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
G = 9.81


def _module(stem):
    path = os.path.join(ROOT, "models", stem + ".py")
    spec = importlib.util.spec_from_file_location(stem, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _run(module, name):
    model = getattr(module, name)()
    return acausal2d.simulate(model, options=acausal2d.RunOptions(**model.experiment))


def _agree(simulated, by_hand, bounds):
    """Every quantity of ``by_hand`` within its relative bound of ``simulated``."""
    for name, value in by_hand.items():
        assert simulated[name] == pytest.approx(value, rel=bounds[name]), name


def test_every_first_model_has_a_test_and_a_page():
    stems = sorted(os.path.basename(p)[:-3] for p in glob.glob(os.path.join(ROOT, "models",
                                                                            "first_*.py")))
    assert stems == sorted(CASES)
    pages = " ".join(open(p, encoding="utf-8").read()
                     for p in glob.glob(os.path.join(ROOT, "docs", "first-models", "*.md")))
    for stem in stems:
        assert "models/%s.py" % stem in pages, stem


def belt_drive():
    m = _module("first_belt_drive")
    w2 = 20.0 * 0.05 / 0.10                        # slip-free: r1 w1 = r2 w2
    dF = 0.05 * w2 / 0.10                          # load torque / r2
    by_hand = {"driven.w_rel": w2, "tight.F": 200 + dF / 2, "slack.F": 200 - dF / 2,
               "driver torque": dF * 0.05}
    res = _run(m, "BeltDrive")
    simulated = {"driven.w_rel": res.final("driven.w_rel"), "tight.F": res.final("tight.F"),
                 "slack.F": res.final("slack.F"),
                 "driver torque": res.final("driver.ctrR2.tau")}
    # the run's rtol is 1e-8; 1.5 s after the run-up the belt's vibration (about
    # 700 rad/s, damped by d/c = 2.5e-4 s) has decayed far below it: bound 1e3 rtol
    return m, by_hand, simulated, dict.fromkeys(by_hand, 1e-5)


def rope_drive():
    m = _module("first_rope_drive")
    fall = 21.0 * G / 2
    eps = fall / 1e6
    by_hand = {"fall1.F": fall, "fall2.F": fall, "drum torque": fall * 0.1,
               "lift speed": 2.0 * 0.1 * (1 + eps) / 2}
    res = _run(m, "RopeDrive")
    simulated = {"fall1.F": res.final("fall1.F"), "fall2.F": res.final("fall2.F"),
                 "drum torque": res.final("drum.ctrR2.tau"), "lift speed": res.final("load.vy")}
    # rtol 1e-8 and a steady lift for 1.5 s; the strain term (1e-4) is 100 times the bound
    return m, by_hand, simulated, dict.fromkeys(by_hand, 1e-6)


def drive_train():
    m = _module("first_drive_train")
    Tc, Tb, J = 0.3 * 0.1 * 200, 0.4 * 0.1 * 1000, 0.02 + 0.8 / 16
    w_close = 2.0 * 0.5 / 0.02
    t_slip = w_close / (16 * Tc / 0.8 + (Tc - 2.0) / 0.02)
    w_lock = 16 * Tc / 0.8 * t_slip
    w_brake = w_lock + 2.0 / J * (2.0 - 0.5 - t_slip)
    decel = (Tb / 4 - 2.0) / J
    E_kin, W_braking = J * w_brake ** 2 / 2, 2.0 * w_brake ** 2 / (2 * decel)
    E_clutch = Tc * w_close * t_slip / 2
    by_hand = {"rotor.w at close": w_close, "slip time": t_slip, "rotor.w at lock": w_lock,
               "clutch loss": E_clutch, "rotor.w at brake": w_brake,
               "stop time": 2.0 + w_brake / decel, "brake loss": E_kin + W_braking,
               "motor work": E_clutch + E_kin + W_braking}
    simulated = m.measure(_run(m, "DriveTrain"))
    # the friction laws stick within a zone of w_s (1e-3 rad/s clutch, 1e-4 brake): the lock
    # lags by about J w_s / T, 1e-5 of the slip time; the times are read on the 5 ms output
    # grid (the lock and stop are events, so they are output points); the losses are
    # trapezoidal sums over that grid of piecewise linear powers.  After the lock the
    # clutch's stick zone shifts the speeds by up to w_s = 1e-3 rad/s, 2e-5 of the 57 rad/s
    # at the brake (and so the motor's angle and work): bound 5 times that
    bounds = {"rotor.w at close": 1e-7, "slip time": 1e-3, "rotor.w at lock": 1e-3,
              "clutch loss": 1e-3, "rotor.w at brake": 1e-4, "stop time": 1e-3,
              "brake loss": 1e-3, "motor work": 1e-4}
    return m, by_hand, simulated, bounds


def hydraulic_circuit():
    m = _module("first_hydraulic_circuit")
    D_p, D_m = 20e-6 / (2 * math.pi), 50e-6 / (2 * math.pi)
    q = 0.95 * D_p * 150.0
    dp_m, dp_v = 100.0 / (0.9 * D_m), q / 2.2689e-10
    by_hand = {"pump flow": q, "shaft.w": 0.95 * q / D_m, "motor.dp": -dp_m, "valve.dp": dp_v,
               "line.p": dp_m + dp_v, "pump torque": D_p * (dp_m + dp_v) / 0.9}
    assert by_hand["line.p"] < 250e5                   # the relief valve stays closed
    simulated = m.measure(_run(m, "HydraulicCircuit"))
    # steady after 3 s (the oil-spring mode decays within 1.5 s to below rtol 1e-8); the
    # efficiencies' blend tanh(P / 1 W) is 1 to 1e-9 at these kW
    return m, by_hand, simulated, dict.fromkeys(by_hand, 1e-6)


def linkage():
    m = _module("first_linkage")
    d, far, near = 0.4, 0.45, 0.25
    lo = math.pi - math.acos((d * d + 0.09 - far * far) / (2 * d * 0.3))
    hi = math.pi - math.acos((d * d + 0.09 - near * near) / (2 * d * 0.3))
    by_hand = {"rocker max": hi, "rocker min": lo, "swing": hi - lo}
    res = _run(m, "FourBar")
    # the whole curve against the loop closure solved by hand (circle intersection)
    phi = res["crank.phiL"]
    ax, ay = 0.1 * np.cos(phi), 0.1 * np.sin(phi)
    dx, dy = 0.4 - ax, -ay
    dist = np.hypot(dx, dy)
    at_b0 = np.arccos((dist ** 2 + 0.09 - 0.35 ** 2) / (2 * dist * 0.3))
    rocker = np.arctan2(-dy, -dx) - at_b0            # B above the line B0 -> A
    wrapped = np.angle(np.exp(1j * (res["dyad.phiL2"] - rocker)))
    assert np.max(np.abs(wrapped)) < 1e-7            # rtol 1e-10 positions
    simulated = m.measure(res)
    # the extremes fall between output points (1000 per turn): the angle there is
    # off by at most phi'' h^2 / 8 with |phi''| < 1 per rad^2 and h = 2 pi / 1000: 5e-6 rad
    bound = 5e-6 / 0.69
    return m, by_hand, simulated, dict.fromkeys(by_hand, bound)


def planar_mechanism():
    m = _module("first_planar_mechanism")
    res = _run(m, "SliderCrank")
    phi = res["crankJoint.phi"]
    s, c = np.sin(phi), np.cos(phi)
    root = np.sqrt(0.09 - 0.01 * s * s)
    x = 0.1 * c + root
    assert np.max(np.abs(res["slider.s"] - x)) < 1e-8
    k = int(np.argmin(np.abs(phi - math.pi / 3)))
    dx = -0.1 * s - 0.01 * s * c / root
    ddx = -0.1 * c - 0.01 * (c * c - s * s) / root - 1e-4 * s * s * c * c / root ** 3
    by_hand = {"piston x": x[k], "piston v": dx[k] * 10, "drive torque": 2.0 * ddx[k] * dx[k] * 100,
               "stroke": 0.2}
    simulated = m.measure(res)
    assert abs(phi[k] - math.pi / 3) < 1e-9         # the 50th output point: no interpolation
    return m, by_hand, simulated, {"piston x": 1e-7, "piston v": 1e-6, "drive torque": 1e-5,
                                   "stroke": 1e-6}


CASES = {"first_belt_drive": belt_drive, "first_rope_drive": rope_drive,
         "first_drive_train": drive_train, "first_hydraulic_circuit": hydraulic_circuit,
         "first_linkage": linkage, "first_planar_mechanism": planar_mechanism}


@pytest.mark.parametrize("stem", sorted(CASES))
def test_first_model_hand_check(stem, monkeypatch):
    monkeypatch.setenv("ACAUSAL2D_NATIVE", "0")
    module, by_hand, simulated, bounds = CASES[stem]()
    _agree(simulated, by_hand, bounds)
    # the file's own hand check (printed on its page) is the same closed form
    hand = module.hand_check()
    assert set(hand) == set(by_hand)
    for name, value in by_hand.items():
        assert hand[name] == pytest.approx(value, rel=1e-12, abs=1e-15), name
