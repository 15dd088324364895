"""Friction with stiction (Modelica's PartialFriction through the stick zone
of friction1d): Clutch with peak and a mu_pos table, BearingFriction,
Brake, OneWayClutch, translational SupportFriction, against Coulomb closed
forms: lock and breakaway times, holding torque, locking direction.

Tolerances: IDA at RTOL.  An event time is off by the time its crossing
function needs to move by RTOL of its scale (``RTOL * w0 / rate``, ten
times room) plus the lag of the stick zone, ``J w_s / tau0`` (the closed
forms are for w_s -> 0; docs/guide/friction.md).  While stuck the speeds
differ by the creep (<= w_s); after a breakaway the torque falls from
peak tau0 to tau0 within some ten w_s of slip, which changes a speed by at
most (peak - 1) tau0 / J times that time: 50 J_eff w_s / J.  Speeds between
events: 100 RTOL of their scale (global error).

After a breakaway the friction falls from peak tau0 to tau0 while the slip
grows by a few w_s (the zone's continuous drop, where Modelica jumps at
once).  The slip grows from the torque excess, which starts at 0 and rises
at the rate r of the load; it passes w_s within about sqrt(2 J_rel w_s / r)
(J_rel: the inertia of the relative motion).  Over three such times the
extra friction (peak - 1) tau0 changes the speed of an inertia J by at most
:func:`breakaway_slack`."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import rotational as rot
from acausal2d.library import signals
from acausal2d.library import translational as tr

RTOL = 1e-8
W_S = 1e-6


def breakaway_slack(excess, J, J_rel, rate):
    """Largest speed change of the inertia J by the extra friction
    ``excess`` = (peak - 1) tau0 during the drop after a breakaway (module
    docstring)."""
    return excess / J * 3 * math.sqrt(2 * J_rel * W_S / rate)


class Pair(Component):
    """Inertia a (driven by ``torque(t)`` if given) -- clutch -- inertia b."""

    def __init__(self, clutch, wa=0.0, ja=1.0, jb=3.0, torque=None, engage=1.0, **kw):
        super().__init__(**kw)
        self.a = rot.Inertia(J=ja, phi=start(0.0, fixed=True), w=start(wa, fixed=True))
        self.b = rot.Inertia(J=jb, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = clutch
        self.eng = signals.Constant(k=engage)
        self.connect(self.eng.y, self.clutch.f_normalized)
        self.connect(self.a.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.b.flange_a)
        if torque is not None:
            self.sig = signals.TimeFunction(torque)
            self.src = rot.Torque()
            self.connect(self.sig.y, self.src.tau_in)
            self.connect(self.src.flange, self.a.flange_a)


def test_clutch_breaks_away_at_peak_times_the_sliding_torque():
    """Locked pair, torque K t on a: the clutch passes K t JB/(JA + JB) and
    slips when that reaches peak tau0 (tau0 = mu cgeo fn_max = 10 N m),
    later by the zone's lag; then b accelerates at tau0 / JB."""
    K, ja, jb, tau0, peak = 100.0, 1.0, 3.0, 10.0, 1.5
    j_eff = ja * jb / (ja + jb)
    t_u = peak * tau0 * (ja + jb) / (jb * K) + j_eff * W_S / (peak * tau0)
    clutch = rot.Clutch(mu=0.5, cgeo=1.0, fn_max=20.0, peak=peak, w_s=W_S, law="zone")
    res = acausal2d.simulate(Pair(clutch, torque=lambda t: K * t), stop_time=0.4, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.4, 201))
    assert len(res.events) == 1
    assert res.events[0][0] == pytest.approx(t_u, abs=10 * RTOL * peak * tau0 / (K * jb / 4))
    late = res.time > t_u + 1e-3
    w_u = 0.5 * K * t_u ** 2 / (ja + jb)
    want = w_u + tau0 / jb * (res.time[late] - t_u)
    slack = breakaway_slack((peak - 1) * tau0, jb, j_eff, K * jb / (ja + jb))
    assert np.max(np.abs(res["b.w"][late] - want)) <= slack + 100 * RTOL * 10


def test_clutch_with_a_mu_table_locks_at_the_closed_form():
    """mu_pos = [[0, 0.5], [10, 0.3]]: slipping from w_rel = -10 (a at 10,
    b at rest), J_eff dw/dt = c (0.5 + 0.02 w) with c = cgeo fn / J_eff:
    |w| = 25 - 15 exp(0.02 c t) reaches 0 at ln(5/3) / (0.02 c)."""
    ja, jb, fn = 1.0, 3.0, 20.0
    j_eff = ja * jb / (ja + jb)
    c = fn / j_eff
    t_lock = math.log(5.0 / 3.0) / (0.02 * c)
    clutch = rot.Clutch(mu_pos=[[0.0, 0.5], [10.0, 0.3]], cgeo=1.0, fn_max=fn, w_s=W_S, law="zone")
    res = acausal2d.simulate(Pair(clutch, wa=10.0), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 201))
    slip = res.time < t_lock - 1e-3
    w = 25.0 - 15.0 * np.exp(0.02 * c * res.time[slip])
    assert np.max(np.abs(-res["clutch.w_rel"][slip] - w)) <= 100 * RTOL * 10
    lock = [t for t, txt in res.events if "clutch.w_rel" in txt]
    assert lock and lock[0] == pytest.approx(t_lock, abs=10 * RTOL * 10 / (0.5 * c)
                                             + j_eff * W_S / (0.5 * fn))
    w_end = ja * 10.0 / (ja + jb)
    assert abs(res.final("b.w") - w_end) <= W_S + 100 * RTOL * 10


class Bearing(Component):
    """Inertia J on a BearingFriction (peak), driven by the torque K t."""

    def __init__(self, K, J, peak, tau_pos, **kw):
        super().__init__(**kw)
        self.sig = signals.TimeFunction(lambda t: K * t)
        self.src = rot.Torque()
        self.inertia = rot.Inertia(J=J, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.bearing = rot.BearingFriction(tau_pos=tau_pos, peak=peak, w_s=W_S, law="zone")
        self.connect(self.sig.y, self.src.tau_in)
        self.connect(self.src.flange, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.bearing.flange_a)


def test_bearing_friction_breakaway_and_sliding():
    """Stuck until K t = peak tau0 (t_b), then J dw/dt = K t - tau_pos(w)
    with tau_pos = 1 + 0.5 w: w = (K/(0.5)) ... solved in closed form of
    the linear ODE J w' + 0.5 w = K t - 1."""
    K, J, peak = 10.0, 2.0, 2.0
    t_b = peak * 1.0 / K + J * W_S / (peak * 1.0)
    res = acausal2d.simulate(Bearing(K, J, peak, [[0.0, 1.0], [2.0, 2.0]]), stop_time=1.0,
                             rtol=RTOL, output_times=np.linspace(0.0, 1.0, 201))
    assert res.events[0][0] == pytest.approx(t_b, abs=10 * RTOL * peak / K)
    stuck = res.time < t_b - 1e-3
    assert np.max(np.abs(res["inertia.w"][stuck])) <= W_S
    # J w' + b w = K t - 1 from w(t_b) = 0, b = 0.5: particular solution p + q t
    b = 0.5
    q = K / b
    p = (-1.0 - J * q) / b
    tt = res.time[res.time > t_b + 1e-3]
    w = p + q * tt - (p + q * t_b) * np.exp(-b * (tt - t_b) / J)
    assert np.max(np.abs(res["inertia.w"][res.time > t_b + 1e-3] - w)) \
        <= breakaway_slack(peak - 1.0, J, J, K) + 100 * RTOL * float(np.max(w))
    assert np.all(res["bearing.tau"][stuck] <= peak * 1.0 + 1e-9)


class Braked(Component):
    """Inertia J under the constant torque T, braked (f_normalized = 1)."""

    def __init__(self, T, J, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=T)
        self.inertia = rot.Inertia(J=J, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rot.Brake(mu_pos=[[0.0, 0.4]], cgeo=0.5, fn_max=100.0, peak=1.25, w_s=W_S, law="zone")
        self.one = signals.Constant(k=1.0)
        self.connect(self.one.y, self.brake.f_normalized)
        self.connect(self.src.flange, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.brake.flange_a)


@pytest.mark.parametrize("share", (0.9, 1.1))
def test_brake_holds_below_its_capacity_and_slips_above(share):
    """Holding torque peak mu cgeo fn_max = 25 N m: 0.9 of it is held (creep
    below w_s), 1.1 of it slips with J a = T - mu cgeo fn_max."""
    J, hold = 0.5, 1.25 * 0.4 * 0.5 * 100.0
    T = share * hold
    res = acausal2d.simulate(Braked(T, J), stop_time=0.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.5, 51))
    if share < 1:
        assert np.max(np.abs(res["inertia.w"])) <= W_S
        held = res.time > 0       # at t = 0 the creep, and so the torque, is still 0
        assert np.max(np.abs(res["brake.tau"][held] - T)) <= 100 * RTOL * hold
    else:
        t = res.time[res.time > 1e-3]
        want = (T - hold / 1.25) / J * t
        assert np.max(np.abs(res["inertia.w"][res.time > 1e-3] - want)) \
            <= 50 * W_S + 100 * RTOL * float(np.max(want))


def _one_way(engage):
    clutch = rot.OneWayClutch(mu_pos=[[0.0, 0.5]], cgeo=1.0, fn_max=100.0, w_s=W_S, law="zone")
    return Pair(clutch, torque=lambda t: 4.0 * acausal2d.if_else(t < 0.5, 1.0, -1.0),
                engage=engage)


def test_one_way_clutch_drives_forward_and_overruns_when_open():
    """Torque +4 on a for 0.5 s: the freewheel locks (a drives b), both at
    4 t / (JA + JB); then -4: open, b overruns at 0.5 rad/s, a slows at 4/JA."""
    res = acausal2d.simulate(_one_way(0.0), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 100))
    t = res.time
    first = t < 0.5
    assert np.max(np.abs(res["b.w"][first] - t[first])) <= W_S + 100 * RTOL
    assert np.max(np.abs(res["a.w"][first] - t[first])) <= W_S + 100 * RTOL
    assert np.max(np.abs(res["b.w"][~first] - 0.5)) <= W_S + 100 * RTOL
    assert np.max(np.abs(res["a.w"][~first] - (0.5 - 4.0 * (t[~first] - 0.5)))) \
        <= W_S + 100 * RTOL
    assert np.min(res["clutch.w_rel"]) >= -W_S


def test_one_way_clutch_engaged_holds_both_ways_within_its_capacity():
    """Engaged (tau0_max = 50 N m > the 3 N m b needs): after the torque
    reverses the pair slows together at 4 / (JA + JB)."""
    res = acausal2d.simulate(_one_way(1.0), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 100))
    t = res.time
    want = np.where(t < 0.5, t, 0.5 - (t - 0.5))
    assert np.max(np.abs(res["b.w"] - want)) <= W_S + 100 * RTOL
    assert np.max(np.abs(res["clutch.w_rel"])) <= W_S


class Sliding(Component):
    """Mass m on a SupportFriction (f_pos = [[0, 2]], peak), pushed by K t."""

    def __init__(self, K, m, peak, **kw):
        super().__init__(**kw)
        self.sig = signals.TimeFunction(lambda t: K * t)
        self.src = tr.Force()
        self.mass = tr.Mass(m=m, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.friction = tr.SupportFriction(f_pos=[[0.0, 2.0]], peak=peak, v_s=W_S, law="zone")
        self.connect(self.sig.y, self.src.f_in)
        self.connect(self.src.flange, self.mass.flange_a)
        self.connect(self.mass.flange_b, self.friction.flange_a)


def test_support_friction_breaks_away_then_slides_at_coulomb():
    """Stuck until K t = peak f0 (t_b), then m v' = K t - f0:
    v = (K (t^2 - t_b^2) / 2 - f0 (t - t_b)) / m."""
    K, m, peak, f0 = 20.0, 0.5, 1.5, 2.0
    t_b = peak * f0 / K + m * W_S / (peak * f0)
    res = acausal2d.simulate(Sliding(K, m, peak), stop_time=0.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.5, 101))
    assert res.events[0][0] == pytest.approx(t_b, abs=10 * RTOL * peak * f0 / K)
    late = res.time > t_b + 1e-3
    tt = res.time[late]
    v = (0.5 * K * (tt ** 2 - t_b ** 2) - f0 * (tt - t_b)) / m
    assert np.max(np.abs(res["mass.v"][late] - v)) \
        <= breakaway_slack((peak - 1) * f0, m, m, K) + 100 * RTOL * float(np.max(v))


@pytest.mark.parametrize("make, words", [
    (lambda: rot.Brake(fn_max=-1.0), ("Brake", "parameter fn_max")),
    (lambda: rot.Clutch(peak=0.5), ("Clutch", "parameter peak")),
    (lambda: rot.BearingFriction(tau_pos=[[1.0, 1.0], [0.5, 2.0]]), ("BearingFriction", "tau_pos")),
    (lambda: rot.Brake(mu_pos="abc"), ("Brake", "mu_pos")),
    (lambda: rot.Clutch(mu=0.3, mu_pos=[[0, 0.3]]), ("Clutch", "mu_pos")),
    (lambda: rot.OneWayClutch(cgeo=0.0), ("OneWayClutch", "cgeo")),
    (lambda: tr.SupportFriction(f_pos=[[0.0, -1.0]]), ("SupportFriction", "f_pos")),
    (lambda: tr.MassWithStopAndFriction(L=60.0), ("MassWithStopAndFriction", "smax", "L")),
    (lambda: tr.MassWithStopAndFriction(fexp=-1.0), ("MassWithStopAndFriction", "fexp")),
])
def test_bad_friction_parameters_are_refused_naming_them(make, words):
    with pytest.raises(ModelDefinitionError) as err:
        make()
    assert all(w in str(err.value) for w in words), str(err.value)
