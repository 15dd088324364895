"""Examples of Modelica.Mechanics.Rotational (MSL 4.0), transcribed one to
one with the library's Modelica names and defaults.

Modelica.Mechanics.Rotational.Examples.CoupledClutches:
transcribed with the library's Modelica names and defaults: four inertias
coupled by three clutches (peak 1.1, fn_max 20, Modelica's default
mu_pos = [0, 0.5] and cgeo = 1), J1 driven by a 5 Hz sine torque, the
clutches engaged by a sine (clutch1) and steps at T2 = 0.4 s, T3 = 0.9 s.

Without Modelica's result at hand the run is checked by the laws it must
obey whatever the friction does: the clutches' torques are internal, so
the angular momentum sum J_i w_i changes only by the drive's impulse,
10 + (1 - cos(10 pi t)) / pi (to 100 RTOL of its scale, the global error);
each clutch dissipates (tau w_rel >= 0, up to the creep torque of its
stick zone times w_s); clutch3 is open before T3 (no torque)."""
import math

import numpy as np

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational as rot
from acausal2d.library import signals

RTOL = 1e-8


class CoupledClutches(Component):
    """Modelica.Mechanics.Rotational.Examples.CoupledClutches."""

    def __init__(self, freqHz=0.2, T2=0.4, T3=0.9, **kw):
        super().__init__(**kw)
        self.J1 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(10.0, fixed=True))
        self.torque = rot.Torque()
        self.sin1 = signals.Sine(amplitude=10.0, f=5.0)
        self.step1 = signals.Step(startTime=T2)
        self.clutch1 = rot.Clutch(peak=1.1, fn_max=20.0)
        self.sin2 = signals.Sine(amplitude=1.0, f=freqHz, phase=math.pi / 2)
        self.J2 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch2 = rot.Clutch(peak=1.1, fn_max=20.0)
        self.J3 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch3 = rot.Clutch(peak=1.1, fn_max=20.0)
        self.J4 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.step2 = signals.Step(startTime=T3)
        self.connect(self.sin1.y, self.torque.tau_in)
        self.connect(self.torque.flange, self.J1.flange_a)
        self.connect(self.J1.flange_b, self.clutch1.flange_a)
        self.connect(self.clutch1.flange_b, self.J2.flange_a)
        self.connect(self.J2.flange_b, self.clutch2.flange_a)
        self.connect(self.clutch2.flange_b, self.J3.flange_a)
        self.connect(self.J3.flange_b, self.clutch3.flange_a)
        self.connect(self.clutch3.flange_b, self.J4.flange_a)
        self.connect(self.sin2.y, self.clutch1.f_normalized)
        self.connect(self.step1.y, self.clutch2.f_normalized)
        self.connect(self.step2.y, self.clutch3.f_normalized)


def test_coupled_clutches_keep_the_momentum_balance_and_dissipate():
    res = acausal2d.simulate(CoupledClutches(), stop_time=1.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.5, 301))
    t = res.time
    momentum = sum(res["J%d.w" % i] for i in range(1, 5))
    impulse = 10.0 + (1.0 - np.cos(10 * math.pi * t)) / math.pi
    assert np.max(np.abs(momentum - impulse)) <= 100 * RTOL * 10.0
    for k in (1, 2, 3):
        c = "clutch%d." % k
        creep = 1.1 * 0.5 * 20.0 * 1e-3          # peak tau0 times w_s
        assert np.min(res[c + "tau"] * res[c + "w_rel"]) >= -creep
    open3 = t < 0.9 - 1e-9
    assert np.max(np.abs(res["clutch3.tau"][open3])) <= 1e-12
    assert np.max(np.abs(res["J4.w"][open3])) <= 1e-12
    # the drive and clutch1 pass momentum down the chain: J4 turns after T3
    assert res.final("J4.w") > 0.5


class OneWayClutchExample(Component):
    """Modelica.Mechanics.Rotational.Examples.OneWayClutch."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.inertiaIn = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(-0.5, fixed=True))
        self.inertiaOut = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.oneWayClutch = rot.OneWayClutch(peak=25.0, fn_max=3.0)
        self.torque = rot.Torque()
        self.signalTorque = signals.Sine(amplitude=10.0, f=3.0)
        self.signalEngagement = signals.Pulse(amplitude=1.0, width=50.0, period=1.3,
                                              startTime=0.3)
        self.connect(self.torque.flange, self.inertiaIn.flange_a)
        self.connect(self.signalTorque.y, self.torque.tau_in)
        self.connect(self.inertiaIn.flange_b, self.oneWayClutch.flange_a)
        self.connect(self.oneWayClutch.flange_b, self.inertiaOut.flange_a)
        self.connect(self.signalEngagement.y, self.oneWayClutch.f_normalized)


def test_one_way_clutch_example_never_runs_backwards():
    """Modelica's OneWayClutch example (2 s): the momentum sum follows the
    drive's impulse -0.5 + 10 (1 - cos(6 pi t)) / (6 pi); the relative speed
    w_rel = inertiaOut.w - inertiaIn.w never falls below 0 by more than
    the freewheel's lock leaves: it locks (a_rel = 0) at the event where
    w_rel reaches 0, located to ~1e-13 s, with |a_rel| <= 20 rad/s2 here,
    so 1e-9 has ample room; the clutch dissipates where it is not locked
    (locked, Modelica's loss power is 0)."""
    res = acausal2d.simulate(OneWayClutchExample(), stop_time=2.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 2.0, 401))
    t = res.time
    momentum = res["inertiaIn.w"] + res["inertiaOut.w"]
    impulse = -0.5 + 10.0 * (1.0 - np.cos(6 * math.pi * t)) / (6 * math.pi)
    assert np.max(np.abs(momentum - impulse)) <= 100 * RTOL * 2.0
    tau = res["oneWayClutch.tau"]
    assert np.min(res["oneWayClutch.w_rel"]) >= -1e-9
    sliding = res["oneWayClutch.locked"] < 0.5
    assert np.min((tau * res["oneWayClutch.w_rel"])[sliding]) >= 0.0 - 1e-12
    # the engagement makes the output follow: both speeds meet while engaged
    engaged = (t > 0.35) & (t < 0.95)
    assert np.min(np.abs(res["oneWayClutch.w_rel"][engaged])) <= 1e-4
