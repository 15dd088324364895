"""Signal blocks of Modelica.Blocks (Step, Ramp, Gain, Add, Feedback,
Integrator, PID, LimPID) against their laws and closed forms.

Tolerances: the algebraic blocks are equations solved by Newton far below
RTOL, compared to RTOL of the signal's scale.  The dynamic ones run IDA at
RTOL; their closed forms are compared to 100 RTOL of the signal's range (the
global error over some hundred steps).  Output times avoid the event
instants, where a sample may show either side."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component
from acausal2d.analysis.compare_inputs import modelica_counterpart
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import signals

RTOL = 1e-8


def away_from_events(res):
    """Mask of the result rows not at an event instant (where the result
    holds the values before and after it)."""
    ev = np.array([t for t, _ in res.events] or [np.inf])
    return np.min(np.abs(res.time[:, None] - ev[None, :]), axis=1) > 1e-9


class Chain(Component):
    """Step -> Gain -> Add.u1, Ramp -> Add.u2, Feedback(Add.y - Sine)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.step = signals.Step(height=2.0, offset=0.5, startTime=0.3)
        self.gain = signals.Gain(k=-3.0)
        self.ramp = signals.Ramp(height=4.0, duration=0.5, offset=-1.0, startTime=0.2)
        self.add = signals.Add(k1=2.0, k2=0.5)
        self.sine = signals.Sine(amplitude=1.5, f=2.0)
        self.fb = signals.Feedback()
        self.connect(self.step.y, self.gain.u)
        self.connect(self.gain.y, self.add.u1)
        self.connect(self.ramp.y, self.add.u2)
        self.connect(self.add.y, self.fb.u1)
        self.connect(self.sine.y, self.fb.u2)


def test_step_ramp_gain_add_feedback_laws():
    """Modelica's laws: Step offset + (t < startTime ? 0 : height); Ramp
    offset + height clip((t - startTime)/duration, 0, 1); Gain k u; Add
    k1 u1 + k2 u2; Feedback u1 - u2."""
    times = np.linspace(0.0, 1.0, 41) + 0.0123
    res = acausal2d.simulate(Chain(), rtol=RTOL, output_times=times)
    t = res.time
    step = 0.5 + np.where(t < 0.3, 0.0, 2.0)
    ramp = -1.0 + 4.0 * np.clip((t - 0.2) / 0.5, 0.0, 1.0)
    add = 2.0 * (-3.0 * step) + 0.5 * ramp
    fb = add - 1.5 * np.sin(2 * math.pi * 2.0 * t)
    for name, want in (("step.y.u", step), ("gain.y.u", -3.0 * step), ("ramp.y.u", ramp),
                       ("add.y.u", add), ("fb.y.u", fb)):
        ok = away_from_events(res)
        assert np.max(np.abs(res[name][ok] - want[ok])) <= RTOL * 20.0, name
    assert any(abs(tt - 0.3) <= 1e-9 for tt, _ in res.events)       # the step's time event


class Integrate(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.ramp = signals.Ramp(height=2.0, duration=1.0, startTime=0.0)
        self.integ = signals.Integrator(k=3.0, y_start=0.25)
        self.connect(self.ramp.y, self.integ.u)


def test_integrator_from_its_initial_state():
    """der(y) = k u from y_start: 0.25 + 3 t^2 for the ramp 2 t."""
    res = acausal2d.simulate(Integrate(), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 21))
    assert np.max(np.abs(res["integ.y_value"] - (0.25 + 3.0 * res.time ** 2))) <= 100 * RTOL * 3


class Pulsed(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.p = signals.Pulse(amplitude=2.0, width=30.0, period=0.4, offset=0.5,
                               startTime=0.3, nperiod=3)
        self.i = signals.Integrator()
        self.connect(self.p.y, self.i.u)


def test_pulse_law_and_its_integral():
    """Modelica's Pulse: offset + amplitude on [0.3 + 0.4 k, 0.42 + 0.4 k)
    for k = 0, 1, 2; its integral over 2 s is 0.5 * 2 + 3 * 2 * 0.12."""
    res = acausal2d.simulate(Pulsed(), rtol=RTOL,
                             output_times=np.linspace(0.0, 2.0, 201) + 0.001)
    t = res.time
    k = np.floor((t - 0.3) / 0.4)
    on = (t >= 0.3) & (k < 3) & (t - 0.3 - 0.4 * k < 0.12)
    ok = away_from_events(res)
    assert np.max(np.abs(res["p.y.u"][ok] - (0.5 + 2.0 * on[ok]))) <= RTOL
    # the run starts at the first output time 0.001 and lasts 2 s
    assert res.final("i.y_value") == pytest.approx(0.5 * 2.0 + 3 * 2.0 * 0.12, abs=100 * RTOL)
    edges = sorted(0.3 + 0.4 * k + d for k in range(3) for d in (0.0, 0.12))
    got = [tt for tt, _ in res.events if 0.25 < tt < 1.3]
    assert np.max(np.abs(np.array(got) - edges)) <= 1e-9


class OpenPID(Component):
    """A unit step at T0 into a PID."""
    T0 = 0.105

    def __init__(self, k=2.0, Ti=0.5, Td=0.1, Nd=10.0, **kw):
        super().__init__(**kw)
        self.u = signals.Step(height=1.0, startTime=self.T0)
        self.pid = signals.PID(k=k, Ti=Ti, Td=Td, Nd=Nd)
        self.connect(self.u.y, self.pid.u)


@pytest.mark.parametrize("Td", (0.1, 0.0))
def test_pid_step_response_is_the_closed_form(Td):
    """From InitialState (I.y = D.x = 0): y = k (1 + (t - T0)/Ti + Nd
    exp(-(t - T0) Nd / Td)) after the step, 0 before it; Td = 0 is
    Modelica's zero-gain derivative: a PI controller."""
    k, Ti, Nd = 2.0, 0.5, 10.0
    res = acausal2d.simulate(OpenPID(k, Ti, Td, Nd), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 101))
    t = res.time
    s = t - OpenPID.T0
    d = Nd * np.exp(-np.maximum(s, 0) * Nd / Td) if Td > 0 else 0.0
    want = np.where(s < 0, 0.0, k * (1 + s / Ti + d))
    scale = k * (1 + Nd)
    ok = away_from_events(res)
    assert np.max(np.abs(res["pid.y.u"][ok] - want[ok])) <= 100 * RTOL * scale
    assert np.max(np.abs(res["pid.I_y"][ok] - np.maximum(s, 0)[ok] / Ti)) <= 100 * RTOL * scale
    # compare finds Modelica's result names of the controller
    names = res.names
    assert [modelica_counterpart(n, names) for n in ("pid.y", "pid.I.y", "pid.D.x", "u.y")] \
        == ["pid.y.u", "pid.I_y", "pid.D_x", "u.y.u"]


class HeldPID(Component):
    """PID or LimPID (u_s = u_m = 0) with input 0 from the start."""

    def __init__(self, limited, pid, **kw):
        super().__init__(**kw)
        self.zero = signals.Constant(k=0.0)
        if limited:
            self.pid = signals.LimPID(yMax=5.0, **pid)
            self.connect(self.zero.y, self.pid.u_s)
            self.connect(self.zero.y, self.pid.u_m)
        else:
            self.pid = signals.PID(**pid)
            self.connect(self.zero.y, self.pid.u)


@pytest.mark.parametrize("limited", (False, True))
@pytest.mark.parametrize("init, y0", [("InitialOutput", 1.5), ("InitialState", 0.75),
                                      ("NoInit", 0.75)])
def test_controller_init_types_hold_their_start(limited, init, y0):
    """Input 0: InitialOutput holds y (LimPID: gainPID.y) = y_start = 1.5
    (I.y = y_start / k, D steady); InitialState and NoInit keep xi_start =
    0.375, so y = k xi_start = 0.75; the output stays for the whole run.
    (SteadyState with the input held at 0 leaves I.y undetermined, the
    singular case Modelica's PID documentation warns of.)"""
    pid = dict(k=2.0, initType=init, y_start=1.5, xi_start=0.375)
    res = acausal2d.simulate(HeldPID(limited, pid=pid), stop_time=0.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.5, 11))
    assert np.max(np.abs(res["pid.y.u"] - y0)) <= 100 * RTOL * 2.0


class Windup(Component):
    """Set point 1 from t = 0, -1 from T2; measurement 0; LimPID as PI
    with wp = 0 (the output is the integrator's state while unlimited)."""
    T2 = 2.0

    def __init__(self, **kw):
        super().__init__(**kw)
        self.up = signals.Step(height=1.0, startTime=0.0)
        self.down = signals.Step(height=-2.0, startTime=self.T2)
        self.sp = signals.Add()
        self.meas = signals.Constant(k=0.0)
        self.pid = signals.LimPID(controllerType="PI", k=1.0, Ti=1.0, wp=0.0, Ni=0.9, yMax=0.5)
        self.connect(self.up.y, self.sp.u1)
        self.connect(self.down.y, self.sp.u2)
        self.connect(self.sp.y, self.pid.u_s)
        self.connect(self.meas.y, self.pid.u_m)


def _windup_closed_form(t, y_max=0.5, ni=0.9, ti=1.0, t2=2.0):
    """Integrator state of Windup: t/Ti up to yMax (t1 = Ti yMax); limited,
    the tracking term pulls it to yMax + Ni e (time constant Ni Ti); after
    the set point falls at t2 it decays towards yMax - Ni and the output
    leaves the limit at t3, then falls as -(t - t3)/Ti."""
    t1 = ti * y_max
    hi = y_max + ni
    i2 = hi + (y_max - hi) * math.exp(-(t2 - t1) / (ni * ti))
    lo = y_max - ni
    t3 = t2 + ni * ti * math.log((i2 - lo) / (y_max - lo))
    i = np.where(t < t1, t / ti,
                 np.where(t < t2, hi + (y_max - hi) * np.exp(-(t - t1) / (ni * ti)),
                          np.where(t < t3, lo + (i2 - lo) * np.exp(-(t - t2) / (ni * ti)),
                                   y_max - (t - t3) / ti)))
    return i, np.clip(i, -y_max, y_max), t3


def test_limpid_clips_and_its_anti_windup_recovers():
    """The limiter holds y at yMax; the integrator winds up only to yMax +
    Ni e and leaves the limit Ni Ti ln(...) after the set point reverses
    (0.53 s here, against 1.5 s for a plain integrator)."""
    res = acausal2d.simulate(Windup(), stop_time=3.3, rtol=RTOL,
                             output_times=np.linspace(0.0, 3.3, 151))
    i, y, t3 = _windup_closed_form(res.time)
    ok = away_from_events(res)
    assert np.max(np.abs(res["pid.I_y"][ok] - i[ok])) <= 100 * RTOL * 1.4
    assert np.max(np.abs(res["pid.y.u"][ok] - y[ok])) <= 100 * RTOL * 1.4
    assert np.max(res["pid.y.u"]) <= 0.5 + RTOL
    leave = [tt for tt, txt in res.events if tt > 2.0 + 1e-6]
    assert leave and leave[0] == pytest.approx(t3, abs=1e3 * RTOL)


@pytest.mark.parametrize("cls, kw, words", [
    (signals.PID, {"Ti": 0.0}, ("PID", "parameter Ti")),
    (signals.PID, {"Ti": -1.0}, ("PID", "parameter Ti")),
    (signals.LimPID, {"Ti": 0.0}, ("LimPID", "parameter Ti")),
    (signals.LimPID, {"yMax": 1.0, "yMin": 2.0}, ("LimPID", "yMax", "yMin")),
    (signals.LimPID, {"Td": -1.0}, ("LimPID", "parameter Td")),
    (signals.LimPID, {"initType": "InitialOutput", "y_start": 2.0}, ("LimPID", "y_start")),
    (signals.LimPID, {"controllerType": "PIDD"}, ("LimPID", "controllerType")),
    (signals.PID, {"initType": "Steady"}, ("PID", "initType")),
    (signals.Limiter, {"uMax": -1.0, "uMin": 0.0}, ("Limiter", "uMax", "uMin")),
    (signals.Pulse, {"width": 100.0}, ("Pulse", "width")),
    (signals.Pulse, {"period": 0.0}, ("Pulse", "period")),
    (signals.Pulse, {"nperiod": 0}, ("Pulse", "nperiod")),
])
def test_bad_block_parameters_are_refused_naming_them(cls, kw, words):
    with pytest.raises(ModelDefinitionError) as err:
        cls(**kw)
    assert all(w in str(err.value) for w in words), str(err.value)
