"""Friction with Modelica's PartialFriction modes (the default law of the
friction elements), hard stops, event robustness and nominals, against
closed forms.

Tolerances: IDA at RTOL (states tested at 0.03 RTOL).  A locked element
holds ``w_rel`` at its value of the locking event, which IDA locates to
about 100 unit roundoffs of the time (1e-13 s here) while ``|a_rel|`` is
at most some 10 rad/s2: |w_rel| <= 1e-12, the bound 1e-9 has room.  An
event time is off by the time its crossing function needs to move by RTOL
of its scale (``RTOL * scale / rate``, ten times room).  Speeds between
events: 100 RTOL of their scale (the global error)."""
import math
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.runtime.events import EventError
from acausal2d.library import blocks, signals
from acausal2d.library import rotational as rot
from acausal2d.library import translational as tr

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "benchmarks"))
from event_models import DRIVE, Bouncing, RampedDrive, Switching  # noqa: E402

RTOL = 1e-8
LOCKED = 1e-9


def is_code(values, code):
    """A mode output (an integer code solved from the 0/1 latch values)
    equals ``code`` everywhere, to rounding."""
    return float(np.max(np.abs(np.asarray(values, dtype=float) - code))) <= 1e-9


class Pair(Component):
    """Inertia a (at wa, driven by ``torque(t)`` if given) -- clutch --
    inertia b (at rest)."""

    def __init__(self, clutch, wa=0.0, ja=1.0, jb=3.0, torque=None, **kw):
        super().__init__(**kw)
        self.a = rot.Inertia(J=ja, phi=start(0.0, fixed=True), w=start(wa, fixed=True))
        self.b = rot.Inertia(J=jb, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = clutch
        self.eng = signals.Constant(k=1.0)
        self.connect(self.eng.y, self.clutch.f_normalized)
        self.connect(self.a.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.b.flange_a)
        if torque is not None:
            self.sig = signals.TimeFunction(torque)
            self.src = rot.Torque()
            self.connect(self.sig.y, self.src.tau_in)
            self.connect(self.src.flange, self.a.flange_a)


def test_clutch_locks_exactly_at_the_coulomb_time():
    """a at 10 rad/s, b at rest, tau0 = mu cgeo fn = 10 N m: w_rel = -10 +
    tau0 t / J_eff until t_lock = J_eff 10 / tau0 (J_eff = 3/4), then
    locked for good with |w_rel| <= 1e-9 (the stick zone crept at 7e-4)
    and both at the momentum's speed 2.5 rad/s."""
    ja, jb, tau0 = 1.0, 3.0, 10.0
    j_eff = ja * jb / (ja + jb)
    t_lock = j_eff * 10.0 / tau0
    res = acausal2d.simulate(Pair(rot.Clutch(mu=0.5, fn_max=20.0), wa=10.0), stop_time=1.0,
                             rtol=RTOL, output_times=np.linspace(0.0, 1.0, 201))
    assert len(res.events) == 1
    assert res.events[0][0] == pytest.approx(t_lock, abs=10 * RTOL * 10.0 / (tau0 / j_eff))
    slip = res.time < t_lock - 1e-3
    assert np.max(np.abs(res["clutch.w_rel"][slip] - (-10.0 + tau0 / j_eff * res.time[slip]))) \
        <= 100 * RTOL * 10
    late = res.time > t_lock + 1e-6
    assert np.max(np.abs(res["clutch.w_rel"][late])) <= LOCKED
    assert np.max(np.abs(res["b.w"][late] - 2.5)) <= 100 * RTOL * 10
    assert is_code(res["clutch.mode"][slip], -1.0) and is_code(res["clutch.mode"][late], 0.0)
    assert is_code(res["clutch.locked"][late], 1.0)


@pytest.mark.parametrize("peak", (1.0, 1.5))
def test_clutch_unlocks_at_peak_times_the_sliding_torque(peak):
    """Locked pair at rest, torque K t on a: the clutch passes K t JB / (JA
    + JB) and breaks away when that reaches peak tau0: t_u = peak tau0 (JA
    + JB) / (JB K) exactly (the stick zone was late by its lag); then b
    accelerates at tau0 / JB.  Stuck before: w_rel exactly held."""
    K, ja, jb, tau0 = 100.0, 1.0, 3.0, 10.0
    t_u = peak * tau0 * (ja + jb) / (jb * K)
    res = acausal2d.simulate(Pair(rot.Clutch(mu=0.5, fn_max=20.0, peak=peak),
                                  torque=lambda t: K * t),
                             stop_time=0.4, rtol=RTOL, output_times=np.linspace(0.0, 0.4, 201))
    assert res.events[0][0] == pytest.approx(t_u, abs=10 * RTOL * peak * tau0 / (K * jb / 4))
    stuck = res.time < t_u
    assert np.max(np.abs(res["clutch.w_rel"][stuck])) <= LOCKED
    assert np.max(np.abs(-res["clutch.tau"][stuck] - K * res.time[stuck] * jb / (ja + jb))) \
        <= 100 * RTOL * peak * tau0
    late = res.time > t_u
    want = 0.5 * K * t_u ** 2 / (ja + jb) + tau0 / jb * (res.time[late] - t_u)
    assert np.max(np.abs(res["b.w"][late] - want)) <= 100 * RTOL * float(np.max(want))
    assert is_code(res.final("clutch.mode"), -1.0)      # w_rel = w_b - w_a < 0: backward


class Braked(Component):
    """Inertia J = 2 under the constant torque T, braked (f_normalized = 1,
    capacity peak mu0 cgeo fn_max = 1.25 * 0.4 * 0.5 * 100 = 25 N m)."""

    def __init__(self, T, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=T)
        self.inertia = rot.Inertia(J=2.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rot.Brake(mu_pos=[[0.0, 0.4]], cgeo=0.5, fn_max=100.0, peak=1.25)
        self.one = signals.Constant(k=1.0)
        self.connect(self.one.y, self.brake.f_normalized)
        self.connect(self.src.flange, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.brake.flange_a)


@pytest.mark.parametrize("share", (0.99, 1.01))
def test_brake_holds_below_its_capacity_and_slips_above(share):
    """0.99 of the capacity: held, w = 0 exactly, tau = T; 1.01: slips from
    the start against the sliding torque 20 N m: w = (T - 20) t / J."""
    cap = 25.0
    res = acausal2d.simulate(Braked(share * cap), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 51))
    if share < 1:
        assert np.max(np.abs(res["inertia.w"])) <= LOCKED
        assert np.max(np.abs(res["brake.tau"] - share * cap)) <= 100 * RTOL * cap
        assert is_code(res["brake.mode"], 0.0)
    else:
        want = (share * cap - 20.0) * res.time / 2.0
        assert np.max(np.abs(res["inertia.w"] - want)) <= 100 * RTOL * 1.0
        assert is_code(res.final("brake.mode"), 1.0)


class Freewheel(Component):
    """OneWayClutch from the ground (flange_a) to an inertia pulled
    backward by the torque T (engaged by ``engage``)."""

    def __init__(self, T, engage, **kw):
        super().__init__(**kw)
        self.fix = rot.Fixed()
        self.owc = rot.OneWayClutch(fn_max=100.0)
        self.a = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.src = rot.ConstantTorque(tau_constant=T)
        self.f = signals.Constant(k=engage)
        self.connect(self.f.y, self.owc.f_normalized)
        self.connect(self.fix.flange, self.owc.flange_a)
        self.connect(self.owc.flange_b, self.a.flange_a)
        self.connect(self.src.flange, self.a.flange_b)


@pytest.mark.parametrize("engage", (1.0, 0.0))
def test_one_way_clutch_pulled_backward_stays_locked(engage):
    """Pulled backward by 500 N m (far beyond the clutch's 50 N m), engaged
    or open: the freewheel holds, w_rel = 0, tau = -500 N m (the stick zone
    crept backward by w_s |tau| / tau_lock)."""
    res = acausal2d.simulate(Freewheel(-500.0, engage), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 51))
    assert np.max(np.abs(res["owc.w_rel"])) <= LOCKED
    assert np.max(np.abs(res["owc.tau"] + 500.0)) <= 100 * RTOL * 500.0
    assert is_code(res["owc.locked"], 1.0)


def test_one_way_clutch_open_overruns_forward_after_its_small_breakaway():
    """Open (f_normalized = 0) and pushed forward by 1 N m: the disengaged
    clutch breaks away at once (Modelica's tau0_max_low = 1e-4 mu0 cgeo
    fn_max = 5e-3 N m) and runs free: w = t."""
    res = acausal2d.simulate(Freewheel(1.0, 0.0), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 51))
    assert np.max(np.abs(res["a.w"] - res.time)) <= 100 * RTOL
    assert is_code(res.final("owc.mode"), 2.0)


class Stop(Component):
    """MassWithStopAndFriction (Coulomb 5 N, smax = 1 m) pushed by 10 N
    towards the stop until t = 1 s, then by -10 N."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.mass = tr.MassWithStopAndFriction(m=1.0, F_prop=0.0, F_Coulomb=5.0,
                                               F_Stribeck=0.0, smax=1.0, smin=-5.0,
                                               s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.step = blocks.Step(height=-20.0, offset=10.0, startTime=1.0)
        self.force = tr.Force()
        self.connect(self.step.y, self.force.f_in)
        self.connect(self.force.flange, self.mass.flange_b)


def test_mass_stays_at_its_hard_stop_and_leaves_when_the_force_reverses():
    """a = (10 - 5)/1 from rest: s = 2.5 t^2 reaches the stop s = 1 at t_s
    = sqrt(0.4) (the run went on; it used to end there); there v = 0 and s
    = 1 until t = 1, where -10 N exceeds the 5.005 N breakaway: s = 1 - 2.5
    (t - 1)^2."""
    t_s = math.sqrt(0.4)
    res = acausal2d.simulate(Stop(), stop_time=1.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.5, 151))
    stops = [(t, txt) for t, txt in res.events if "hard stop smax" in txt]
    assert stops[0][0] == pytest.approx(t_s, abs=10 * RTOL * 1.0 / 3.0)
    assert "reinit(mass.v)" in stops[0][1]
    t = res.time
    before, held, after = t < t_s, (t > t_s + 1e-6) & (t < 1.0), t > 1.0
    assert np.max(np.abs(res["mass.s"][before] - 2.5 * t[before] ** 2)) <= 100 * RTOL
    assert np.max(np.abs(res["mass.v"][held])) <= LOCKED
    assert np.max(np.abs(res["mass.s"][held] - 1.0)) <= LOCKED
    assert is_code(res["mass.stopped"][held], 1.0)
    assert np.max(np.abs(res["mass.s"][after] - (1.0 - 2.5 * (t[after] - 1.0) ** 2))) \
        <= 100 * RTOL * 1.0
    assert is_code(res["mass.stopped"][after], 0.0)


class SharedRamp(Component):
    """J1 (at 10 rad/s, a sine torque) -- clutch -- J2 -- brake; one Ramp
    engages the clutch and, through Feedback (1 - ramp), releases the brake."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sine = signals.Sine(amplitude=10.0, f=5.0)
        self.torque = rot.Torque()
        self.J1 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(10.0, fixed=True))
        self.clutch = rot.Clutch(fn_max=20.0, peak=1.1)
        self.J2 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rot.Brake(fn_max=20.0, peak=1.1)
        self.ramp = signals.Ramp(duration=0.1, startTime=0.5)
        self.one = signals.Constant(k=1.0)
        self.feedback = blocks.Feedback()
        self.connect(self.sine.y, self.torque.tau_in)
        self.connect(self.torque.flange, self.J1.flange_a)
        self.connect(self.J1.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.J2.flange_a)
        self.connect(self.J2.flange_b, self.brake.flange_a)
        self.connect(self.ramp.y, self.clutch.f_normalized)
        self.connect(self.one.y, self.feedback.u1)
        self.connect(self.ramp.y, self.feedback.u2)
        self.connect(self.feedback.y, self.brake.f_normalized)


def test_shared_ramp_makes_no_round_off_events():
    """The clutch's and the brake's normal forces are explicit functions of
    time (ramp and 1 - ramp, the latter solved as +-1e-32 where it is 0):
    their relations fn <= 0 switch at the ramp's time events only, 0.5 s
    (the clutch engages) and 0.6 s (the brake is free) (main
    97e483c had round-off events of max(brake.fn, 0) at 6e-8 s and after
    the ramp, and a variant of this model 13,407 of them in 1.6 ms).  After
    0.6 s the brake is free (mode 2)."""
    res = acausal2d.simulate(SharedRamp(), stop_time=1.0, rtol=1e-6)
    fn_events = [t for t, txt in res.events if ".fn" in txt]
    assert fn_events == [pytest.approx(0.5, abs=1e-12), pytest.approx(0.6, abs=1e-12)]
    assert len(res.events) <= 6
    assert is_code(res.final("brake.mode"), 2.0)


def test_zeno_ball_ends_with_an_error_naming_element_and_relation():
    """The bounces accumulate at t* = sqrt(2/g) 3 = 1.3546 s; the run stops
    there (it went on through the ground) naming the ball and its relation
    (its wall time: benchmarks/bench_events.py)."""
    with pytest.raises(EventError) as err:
        acausal2d.simulate(Bouncing(), stop_time=3.0, rtol=RTOL)
    msg = str(err.value)
    assert "Zeno" in msg and "ground contact" in msg and "Ball 'ball'" in msg
    assert err.value.time == pytest.approx(3 * math.sqrt(2 / 9.81), rel=1e-3)


class Housing(Component):
    """A housing (inertia 1) on a SpringDamper to the ground, driven by
    the torque 1e-6 sin(t): its speed is a 1e-6 rad/s signal, the spring
    damper's w_rel (nominal 1e-4) an alias of it."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sig = signals.Sine(amplitude=1e-6, f=1 / (2 * math.pi))
        self.src = rot.Torque()
        self.housing = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.sd = rot.SpringDamper(c=1.0, d=0.5, w_rel=start(0.0, nominal=1e-4))
        self.fix = rot.Fixed()
        self.connect(self.sig.y, self.src.tau_in)
        self.connect(self.src.flange, self.housing.flange_a)
        self.connect(self.housing.flange_b, self.sd.flange_b)
        self.connect(self.fix.flange, self.sd.flange_a)


def test_small_relative_speed_meets_rtol_on_its_nominal_scale():
    """phi'' + 0.5 phi' + phi = 1e-6 sin t from rest, against scipy's
    solution at rtol 1e-12: w_rel (1e-6 rad/s) within 100 RTOL of its
    nominal scale 1e-4 (it was computed with an absolute tolerance of about
    1e-6 before: the alias set kept the largest nominal)."""
    from scipy.integrate import solve_ivp
    T = np.linspace(0.0, 10.0, 101)
    ref = solve_ivp(lambda t, y: [y[1], 1e-6 * math.sin(t) - 0.5 * y[1] - y[0]], (0.0, 10.0),
                    [0.0, 0.0], t_eval=T, rtol=1e-12, atol=1e-20)
    res = acausal2d.simulate(Housing(), stop_time=10.0, rtol=1e-6, output_times=T)
    assert np.max(np.abs(res["sd.w_rel"] - ref.y[1])) <= 100 * 1e-6 * 1e-4


def test_zone_width_without_the_zone_law_is_refused():
    """w_s means the stick zone: without law='zone' it is an error naming it
    and what to do (Clutch, Brake, BearingFriction, OneWayClutch alike)."""
    for element in (rot.Clutch, rot.Brake, rot.BearingFriction, rot.OneWayClutch):
        with pytest.raises(ModelDefinitionError, match="w_s.*drop w_s or give law='zone'"):
            element(w_s=1e-3)
        assert element(w_s=1e-3, law="zone").law == "zone"
    # and in a run's parameters (--set, params=, a sweep), where it would change nothing
    cm = acausal2d.compile_model(Pair(rot.Clutch(mu=0.5, fn_max=20.0), wa=10.0))
    with pytest.raises(ModelDefinitionError, match="w_s.*leave w_s out of the run's param"):
        cm.simulate(stop_time=0.1, params={"clutch.w_s": 1e-2})
    zone = acausal2d.compile_model(Pair(rot.Clutch(mu=0.5, fn_max=20.0, law="zone"), wa=10.0))
    assert zone.simulate(stop_time=0.1, params={"clutch.w_s": 1e-2}).time[-1] == \
        pytest.approx(0.1, abs=1e-12)
    with pytest.raises(ModelDefinitionError, match="law"):
        rot.Brake(law="smooth")


def ramped_drive_closed_form(t, D):
    """(w1, w2, switching times) of :class:`RampedDrive` (J1 = J2 = 1, mu
    0.5, cgeo 1: k = mu cgeo fn_max = 15 N m, s = (t - t0)/D clipped).
    The clutch slides (w_rel < 0 from t = 0: J1 runs ahead) and passes k s
    to J2; the brake (capacity peak k (1 - s)) holds J2 until k s = peak k
    (1 - s): tb = t0 + D peak / (1 + peak); then J2' = k s - k (1 - s);
    after t0 + D the brake is free, J1' = T - k, J2' = k, until the speeds
    meet at tl; then both at T / 2 (the clutch passes T / 2 < peak k)."""
    T, k, peak, t0 = DRIVE["T"], 0.5 * DRIVE["fn_max"], DRIVE["peak"], DRIVE["t0"]
    tb, te = t0 + D * peak / (1 + peak), t0 + D

    def w1_ramp(t):
        return T * t - k * np.clip(t - t0, 0.0, None) ** 2 / (2 * D)

    def w2_ramp(t):
        return k * (((t - t0) ** 2 - (tb - t0) ** 2) / D - (t - tb)) if t > tb else 0.0

    w1e, w2e = w1_ramp(te), w2_ramp(te)
    tl = te + (w1e - w2e) / (k - (T - k))
    wl = w2e + k * (tl - te)
    w1 = np.where(t <= te, w1_ramp(np.minimum(t, te)), w1e + (T - k) * (t - te))
    w2 = np.where(t <= te, [w2_ramp(x) for x in np.minimum(t, te)], w2e + k * (t - te))
    locked = t >= tl
    w1[locked] = w2[locked] = wl + T / 2 * (t[locked] - tl)
    return w1, w2, (0.0, t0, tb, te, tl)


@pytest.mark.parametrize("ulps", (0, 3, -3))
def test_shared_ramp_clutch_and_brake_run_a_second_as_the_closed_form(ulps):
    """The drive train of a shared Ramp closing the clutch and, through
    Feedback (1 - ramp), opening the brake runs its second to the end (main
    97e483c: an event storm of max(fn, 0) on the +-1e-30 round-off of 1 -
    ramp, 13,407 events in 1.6 ms).  Against the closed form: speeds within
    100 RTOL of their scale, the brake's breakaway and the clutch's lock at
    their times.  No storm can hold this: the closed form has 5 switching
    points (t = 0, t0, tb, t0 + D, tl), each at most two events (a
    breakaway's start and its sliding mode, Modelica's startForward ->
    Forward); IDA's steps per segment (a polynomial piece restarted at
    order 1) at most 60 beside the output grid's.  The ramp's duration moved
    by a few ulps changes nothing."""
    D = 0.5 * (1 + ulps * np.finfo(float).eps)
    grid = np.linspace(0.0, 1.0, 101)
    res = acausal2d.simulate(RampedDrive(D=D), stop_time=1.0, rtol=RTOL, output_times=grid)
    w1, w2, switching = ramped_drive_closed_form(res.time, D)
    assert len(res.events) <= 2 * len(switching)
    assert res.stats["steps"] <= 60 * (len(res.events) + 1) + len(grid)
    assert np.max(np.abs(res["J1.w"] - w1)) <= 100 * RTOL * 10.0
    assert np.max(np.abs(res["J2.w"] - w2)) <= 100 * RTOL * 10.0
    tb, tl = switching[2], switching[4]
    brake = [t for t, txt in res.events if "brake.startForward" in txt]
    assert brake[0] == pytest.approx(tb, abs=10 * RTOL * 15.0 / (2 * 15.0 / D))
    lock = [t for t, txt in res.events if "clutch" in txt and t > switching[3]]
    assert lock[0] == pytest.approx(tl, abs=10 * RTOL * 10.0 / 20.0)
    t = res.time
    before, after = t < tl - 1e-6, t > tl + 1e-6
    assert is_code(res["clutch.mode"][t < 0.2], 2.0) and is_code(res["clutch.mode"][after], 0.0)
    assert is_code(res["clutch.mode"][(t > 0.2 + 1e-6) & before], -1.0)
    assert is_code(res["brake.mode"][t < tb - 1e-6], 0.0)
    assert is_code(res["brake.mode"][t > switching[3] + 1e-6], 2.0)
    assert np.max(np.abs(res["clutch.w_rel"][after])) <= LOCKED
    # Modelica's startForward: 1 only while the brake starts to slide (at tb)
    starting = t[res["brake.startForward"] > 0.5]
    assert len(starting) and np.max(np.abs(starting - tb)) <= 1e-9
    assert is_code(res["brake.locked"][t < tb - 1e-6], 1.0)
    assert is_code(res["brake.startBackward"], 0.0)


@pytest.mark.parametrize("law", ("modes", "zone"))
def test_shared_ramp_agrees_with_two_separate_ramps(law):
    """The same drive with two separate identical Ramp blocks (which ran
    in 0.4 s on main 97e483c) gives the same motion, within the global
    error of both runs (100 RTOL of the speeds' scale), with the same
    events; also with the stick-zone law, whose relation max(clutch.fn, 0)
    stormed there (at most two events per switching point of the closed
    form)."""
    grid = np.linspace(0.0, 1.0, 101)
    shared = acausal2d.simulate(RampedDrive(law=law), stop_time=1.0, rtol=RTOL,
                                output_times=grid)
    apart = acausal2d.simulate(RampedDrive(shared=False, law=law), stop_time=1.0, rtol=RTOL,
                               output_times=grid)
    assert len(shared.events) <= 2 * 5
    # torques too under the modes; in the zone a torque is its stiff
    # coupling tau0_max / w_s times a speed's error: the speeds stand for it
    names = ("J1.w", "J2.w") + (("clutch.tau", "brake.tau") if law == "modes" else ())
    for name in names:
        assert np.max(np.abs(shared[name] - apart[name])) <= 2 * 100 * RTOL * 15.0, name
    assert len(shared.events) == len(apart.events)
    # an event time within the speeds' bound over the slowest crossing rate,
    # J2's k (2 s_b - 1) as the brake leaves its zone (exact locks: 10 RTOL)
    rate = 15.0 * (2 * DRIVE["peak"] / (1 + DRIVE["peak"]) - 1)
    tol = 10 * RTOL if law == "modes" else 2 * 100 * RTOL * 15.0 / rate
    assert np.max(np.abs(np.array([t for t, _ in shared.events])
                         - np.array([t for t, _ in apart.events]))) <= tol


def test_event_storm_ends_with_an_error_naming_element_and_relation():
    """A hysteresis of 1e-7 switches every 2e-7 s: events without progress
    on the run's scale of 1 s, none of them closer than the chattering
    bound, none shrinking (no Zeno).  The storm watch (500 events within
    1e-3 of the span) stops it at its 500th event, t = band + 499 (2 band)
    (to the event location, RTOL of the crossing's scale), naming the
    relation and its element."""
    from acausal2d.runtime.events import STORM_EVENTS
    band = 1e-7
    with pytest.raises(EventError) as err:
        acausal2d.simulate(Switching(), stop_time=1.0, rtol=RTOL)
    msg = str(err.value)
    assert "event storm" in msg and "'heater on' in Relay 'relay'" in msg
    assert "%d events" % STORM_EVENTS in msg
    want = band + (STORM_EVENTS - 1) * 2 * band
    assert err.value.time == pytest.approx(want, abs=STORM_EVENTS * 10 * RTOL * band)
