"""Clutch and asynchronous motor (library/rotational.py): a clutch between
two inertias slips with the Coulomb torque, sticks at the common speed given
by the conservation of angular momentum, transmits a torque below its
capacity while sticking and slips when the capacity is exceeded; the Kloss
motor runs up to its no-load speed and carries a load at the closed-form
slip."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational as rot
from acausal2d.library import signals
from conftest import assert_copied

JA, JB = 0.1, 0.3
T_MAX = 0.3 * 1000.0 * 0.1          # mu * fn_max * cgeo
W_S = 1e-4


class TwoInertias(Component):
    """Inertia a (J 0.1, speed w0, external torque T_ext) -- clutch (capacity
    30 N m, engaged by the signal ``engage(t)``) -- inertia b (J 0.3, at
    rest)."""

    def __init__(self, T_ext=0.0, w0=10.0, engage=None, **kw):
        super().__init__(**kw)
        self.a = rot.Inertia(J=JA, phi=start(0.0, fixed=True), w=start(w0, fixed=True))
        self.b = rot.Inertia(J=JB, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = rot.Clutch(mu=0.3, fn_max=1000.0, cgeo=0.1, w_s=W_S, law="zone",
                                 w_rel=start(-w0))
        if engage is None:
            self.eng = signals.Constant(k=1.0)
        else:
            self.eng = signals.TimeFunction(engage)
        self.src = rot.ConstantTorque(tau_constant=T_ext)
        self.connect(self.eng.y, self.clutch.f_normalized)
        self.connect(self.a.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.b.flange_a)
        self.connect(self.src.flange, self.a.flange_a)


def test_clutch_slip_time_and_common_speed():
    w0 = 10.0
    res = acausal2d.simulate(TwoInertias(w0=w0), stop_time=0.1, rtol=1e-8,
                             output_times=np.linspace(0.0, 0.1, 201))
    J_eff = JA * JB / (JA + JB)
    t_slip = J_eff * w0 / T_MAX                       # Coulomb: 0.025 s
    w_end = JA * w0 / (JA + JB)                       # momentum: 2.5 rad/s
    stick = [t for t, txt in res.events if "clutch.w_rel" in txt]
    assert len(stick) == 1
    # the event is where |w_rel| = w_s, a time J_eff w_s / T_max before t_slip
    assert stick[0] == pytest.approx(t_slip - J_eff * W_S / T_MAX, abs=1e-9)
    # Coulomb torque while slipping, exact linear speeds
    slip = res.time < stick[0] - 1e-9
    assert np.max(np.abs(res["clutch.tau"][slip] + T_MAX)) < 1e-9
    tt = res.time[slip]
    assert np.max(np.abs(res["b.w"][slip] - T_MAX / JB * tt)) < 1e-7
    assert np.max(np.abs(res["a.w"][slip] - (w0 - T_MAX / JA * tt))) < 1e-7
    # common final speed from the conservation of angular momentum
    late = res.time > t_slip + 0.01
    assert np.max(np.abs(res["a.w"][late] - w_end)) < 1e-6
    assert np.max(np.abs(res["b.w"][late] - w_end)) < 1e-6
    mom = JA * res["a.w"] + JB * res["b.w"]
    assert np.max(np.abs(mom - JA * w0)) < 1e-7


def test_clutch_sticks_below_capacity():
    # 10 N m on a: the clutch has to pass 10 * JB/(JA+JB) = 7.5 N m < 30 N m
    T_ext = 10.0
    res = acausal2d.simulate(TwoInertias(T_ext=T_ext, w0=0.0), stop_time=0.5, rtol=1e-8,
                             output_times=np.linspace(0.0, 0.5, 101))
    assert res.events == []
    acc = T_ext / (JA + JB)
    assert np.max(np.abs(res["b.w"] - acc * res.time)) < 1e-5
    # transmitted torque and the creep speed of the regularisation
    k = res.time > 0.05
    assert np.max(np.abs(res["clutch.tau"][k] + T_ext * JB / (JA + JB))) < 1e-4
    assert np.max(np.abs(res["clutch.w_rel"])) < W_S


def test_clutch_slips_above_capacity():
    # 50 N m on a would need 37.5 N m through the clutch: it slips at 30 N m
    T_ext = 50.0
    res = acausal2d.simulate(TwoInertias(T_ext=T_ext, w0=0.0), stop_time=0.2, rtol=1e-8,
                             output_times=np.linspace(0.0, 0.2, 101))
    k = res.time > 0.01
    t = res.time[k]
    assert np.max(np.abs(res["clutch.tau"][k] + T_MAX)) < 1e-9
    w_a0 = res.at("a.w", 0.01) - (T_ext - T_MAX) / JA * 0.01
    assert np.max(np.abs(res["a.w"][k] - (w_a0 + (T_ext - T_MAX) / JA * t))) < 1e-4
    assert np.max(np.abs(np.diff(res["b.w"][k]) / np.diff(t) - T_MAX / JB)) < 1e-4


def test_clutch_open_transmits_nothing_then_engages():
    # the clutch closes with a linear ramp from t = 0.05 s to 0.06 s
    def engage(t):
        return acausal2d.if_else(t < 0.05, 0.0, acausal2d.if_else(t < 0.06, (t - 0.05) / 0.01, 1.0))
    res = acausal2d.simulate(TwoInertias(w0=10.0, engage=engage), stop_time=0.15,
                             rtol=1e-8, output_times=np.linspace(0.0, 0.15, 301))
    before = res.time < 0.05
    assert_copied(res["clutch.tau"][before], 0.0)    # engage is the constant 0 there
    assert np.max(np.abs(res["a.w"][before] - 10.0)) < 1e-12
    assert res.final("a.w") == pytest.approx(2.5, abs=1e-6)
    assert res.final("b.w") == pytest.approx(2.5, abs=1e-6)


class MotorLoad(Component):
    """Kloss motor started at rest against a constant load torque."""

    def __init__(self, T_load=0.0, **kw):
        super().__init__(**kw)
        self.motor = rot.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2)
        self.load = rot.ConstantTorque(tau_constant=-T_load)
        self.connect(self.motor.flange, self.load.flange)


@pytest.mark.parametrize("T_load", [0.0, 15.0])
def test_motor_runs_up_to_kloss_slip(T_load):
    res = acausal2d.simulate(MotorLoad(T_load=T_load), stop_time=1.0, rtol=1e-8,
                             output_times=np.linspace(0.0, 1.0, 201))
    # starting torque 2 T_k s_k / (1 + s_k^2) minus the load
    assert res["motor.T_el"][0] == pytest.approx(2 * 40 * 0.2 / 1.04, rel=1e-10)
    # steady state: T_el(s) = T_load on the stable branch s < s_k
    q = T_load / 40.0
    s_ss = 0.2 * (1 - math.sqrt(1 - q * q)) / q if q > 0 else 0.0
    assert res.final("motor.s") == pytest.approx(s_ss, abs=1e-6)
    assert res.final("motor.w") == pytest.approx(157.07963267948966 * (1 - s_ss), rel=1e-6)
    assert res.final("motor.P_mech") == pytest.approx(T_load * res.final("motor.w"), abs=1e-3)
