"""Qualitative decisions of the runtime do not flip on rounding.

Instead of a second machine (another CPU, another OpenBLAS kernel), every
decision the runtime takes - a singular position passed or a limit
position, the branch kept at a bifurcation, an event or none, a mode
switch (a clutch locking), which state set is integrated - is exercised on
its model with the inputs perturbed by a few ulps and by 1e-12 relative: a
parameter, a start value, rtol and the output grid.  Each run must give the
same outcome, and its numbers must agree with the closed form (or with the
unperturbed run) within the method's bound, which a perturbation of 1e-12
moves by far less than the bound.

Each model is compiled once per module (the perturbed parameters and start
values need no recompilation)."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational as rot
from acausal2d.library import signals
from conftest import load_model_class, same_time
from test_dynamic_state_selection import CartesianPendulum
from test_singular_positions import Parallelogram, _branches


def ulps(x, n):
    """x moved by n units in the last place (n < 0: downwards)."""
    x = float(x)
    for _ in range(abs(n)):
        x = float(np.nextafter(x, math.inf if n > 0 else -math.inf))
    return x


PERTURBATIONS = {
    "+3ulp": lambda x: ulps(x, 3),
    "-3ulp": lambda x: ulps(x, -3),
    "+1e-12": lambda x: x * (1.0 + 1e-12),
    "-1e-12": lambda x: x * (1.0 - 1e-12),
}
KNOBS = ("param", "start", "rtol", "grid")
FAST = ("+3ulp", "-1e-12")      # in the fast tier; the other two directions are slow
CASES = [pytest.param(knob, how, marks=() if how in FAST else pytest.mark.slow)
         for knob in KNOBS for how in PERTURBATIONS]


def nudge(knob, how, params, rtol, times, start_params=(), start_values=None):
    """The run settings with one of them perturbed (``knob``) by ``how``:
    every parameter of ``params`` except the start ones, the start values
    (``start_values``: {unknown: start value}, or the parameters named in
    ``start_params`` that are a drive's start angle), rtol, or every output
    time after the first."""
    f = PERTURBATIONS[how]
    start_values, times = dict(start_values or {}), np.array(times, float)
    if knob == "param":
        params = {k: (v if k in start_params else f(v)) for k, v in params.items()}
    elif knob == "start":
        params = {k: (f(v) if k in start_params else v) for k, v in params.items()}
        start_values = {k: f(v) for k, v in start_values.items()}
    elif knob == "rtol":
        rtol = f(rtol)
    else:
        times[1:] = [f(t) for t in times[1:]]
    return dict(params=params, start=start_values or None, rtol=rtol, output_times=times)


# ------------------------------------------------ singular position passed; branch kept
PAR_RTOL = 1e-10
PAR_TIMES = np.linspace(0.0, 2.0, 401)


@pytest.fixture(scope="module", params=[1, -1], ids=["K=1", "K=-1"])
def parallelogram(request):
    return request.param, acausal2d.compile_model(Parallelogram(request.param))


@pytest.mark.parametrize("knob,how", CASES)
def test_parallelogram_passes_its_change_points_on_its_branch(parallelogram, knob, how):
    """The driven parallelogram (crank = rocker = 0.1 m, coupler = ground =
    0.4 m) at rtol 1e-10, the run that stopped at a 'limit position' under
    two of OpenBLAS's kernels: perturbed, it still passes all four change
    points at the closed-form times (crank angle k pi) and keeps the branch
    chosen at t = 0 (K = 1 the parallelogram, K = -1 the other).  The crank
    alone lengthened or shortened by 1e-12 makes a mechanism 1e-13 m from
    the change-point one (no longer exactly one: a crank-rocker or a
    rocker-rocker whose two branches no longer meet), a thousand times below
    what rtol 1e-10 resolves: the run follows the motion's direction
    through it as for the exact one."""
    K, cm = parallelogram
    run = nudge(knob, how, {"crank.lL": 0.1, "preset.phi0": 0.3}, PAR_RTOL,
                PAR_TIMES, start_params=("preset.phi0",))
    res = cm.simulate(stop_time=None, **run)
    assert res.stopped is None and same_time(res.time[-1], run["output_times"][-1])
    assert np.all(np.isin(run["output_times"], res.time))
    passed = [s for s in res.singularities if s["kind"] == "singular position passed"]
    phi0 = run["params"]["preset.phi0"]
    expected = [(k * math.pi - phi0) / (2 * math.pi) for k in (1, 2, 3, 4)]
    assert [s["time"] for s in passed] == pytest.approx(expected, abs=1e-6)
    assert not [s for s in res.singularities if s["kind"] == "limit position"]
    phi = res["crank.phiL"]
    P = np.column_stack([res["dyad.xP"], res["dyad.yP"]])
    branch = 0 if K == 1 else 1
    err = [np.linalg.norm(P[k] - _branches(p)[branch]) for k, p in enumerate(phi)]
    assert max(err) < 1e-8                   # the bound of the unperturbed run's test
    turn = res["dyad.phiL2"][-1] - res["dyad.phiL2"][0]
    assert turn == pytest.approx(4 * math.pi if K == 1 else -4 * math.pi, abs=1e-8)


# ------------------------------------------------ limit position
LIMIT_RTOL = 1e-8
LIMIT_TIMES = np.linspace(0.0, 1.0, 201)


@pytest.fixture(scope="module")
def limit_four_bar():
    return acausal2d.compile_model(load_model_class("four_link_mechanisms.py", "DDDD")())


@pytest.mark.parametrize("knob,how", CASES)
def test_four_bar_stops_at_its_limit_position(limit_four_bar, knob, how):
    """DDDD with a 0.3 m crank (coupler 0.35, rocker 0.3, ground 0.4)
    driven at one turn per second from 0.1 rad cannot turn round: perturbed, it still
    stops at the limit position, where coupler and rocker stretch out
    (|P1 - B0| = 0.65), within 1e-4 s as the unperturbed run's test."""
    run = nudge(knob, how, {"crank.lL": 0.3, "preset.phi0": 0.1}, LIMIT_RTOL, LIMIT_TIMES,
                start_params=("preset.phi0",))
    res = limit_four_bar.simulate(stop_time=None, **run)
    lL, phi0 = run["params"]["crank.lL"], run["params"]["preset.phi0"]
    t_lim = (math.acos((lL ** 2 + 0.16 - 0.65 ** 2) / (2 * lL * 0.4)) - phi0) / (2 * math.pi)
    assert res.stopped is not None and "limit position" in res.stopped
    assert res.singularities[-1]["kind"] == "limit position"
    assert res.time[-1] == pytest.approx(t_lim, abs=1e-4)


# ------------------------------------------------ event and mode switch: a clutch locks
CL_RTOL = 1e-8
JA = JB = 1.0
CAP, W0 = 10.0, 10.0
CL_TIMES = np.linspace(0.0, 1.0, 101)


class ClutchPair(Component):
    """Inertia a at W0 -- a closed clutch of capacity CAP (mu = cgeo = 1,
    fn_max = CAP) -- inertia b at rest; ``engage`` the clutch's normalized
    normal force."""

    def __init__(self, engage=1.0, **kw):
        super().__init__(**kw)
        self.a = rot.Inertia(J=JA, phi=start(0.0, fixed=True), w=start(W0, fixed=True))
        self.b = rot.Inertia(J=JB, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = rot.Clutch(mu=1.0, fn_max=CAP, cgeo=1.0)
        self.eng = signals.Constant(k=engage)
        self.connect(self.eng.y, self.clutch.f_normalized)
        self.connect(self.a.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.b.flange_a)


@pytest.fixture(scope="module")
def clutch():
    return acausal2d.compile_model(ClutchPair())


@pytest.fixture(scope="module")
def free_clutch():
    return acausal2d.compile_model(ClutchPair(engage=-0.5))


@pytest.mark.parametrize("knob,how", CASES)
def test_clutch_locks_once_at_the_closed_form(clutch, knob, how):
    """Coulomb slip at the capacity until the slip speed reaches 0 at
    t = J_eff w0 / CAP (Modelica's PartialFriction modes, the clutch's
    default); then one event, the clutch stuck (one speed, the momentum's,
    w_rel held at 0) for the rest of the run.  Event time within
    10 rtol w0 / rate (the time the slip needs to move by rtol of its
    speed, with ten times room); speeds within 10 rtol w0."""
    run = nudge(knob, how, {"clutch.fn_max": CAP}, CL_RTOL, CL_TIMES, start_values={"a.w": W0})
    res = clutch.simulate(stop_time=None, **run)
    cap, w0, rtol = run["params"]["clutch.fn_max"], run["start"]["a.w"], run["rtol"]
    j_eff = JA * JB / (JA + JB)
    t_lock = j_eff * w0 / cap
    assert res.stopped is None
    assert len(res.events) == 1
    assert res.events[0][0] == pytest.approx(t_lock, abs=10 * rtol * w0 / (cap / j_eff))
    w_end = JA * w0 / (JA + JB)
    late = res.time > t_lock + 1e-3
    assert np.max(np.abs(res["a.w"][late] - w_end)) <= 10 * rtol * w0
    assert np.max(np.abs(res["b.w"][late] - w_end)) <= 10 * rtol * w0
    assert np.max(np.abs(res["clutch.w_rel"][late])) <= 10 * rtol * w0


@pytest.mark.parametrize("knob,how", CASES)
def test_free_clutch_has_no_event(free_clutch, knob, how):
    """Normal force -0.5 CAP: the clutch is free, no event, no torque; the
    speeds stay at w0 and 0 within rtol w0."""
    run = nudge(knob, how, {"clutch.fn_max": CAP}, CL_RTOL, CL_TIMES, start_values={"a.w": W0})
    res = free_clutch.simulate(stop_time=None, **run)
    w0, rtol = run["start"]["a.w"], run["rtol"]
    assert res.stopped is None and res.events == []
    assert np.max(np.abs(res["clutch.tau"])) <= 1e-12 * CAP
    assert np.max(np.abs(res["a.w"] - w0)) <= rtol * w0
    assert np.max(np.abs(res["b.w"])) <= rtol * w0


# ------------------------------------------------ which state set
SS_RTOL = 1e-10
SS_TIMES = np.linspace(0.0, 2.0, 201)


@pytest.fixture(scope="module")
def pendulum():
    cm = acausal2d.compile_model(CartesianPendulum())
    base = cm.simulate(rtol=SS_RTOL, output_times=SS_TIMES)
    return cm, base


@pytest.mark.parametrize("knob,how", CASES)
def test_cartesian_pendulum_reselects_the_same_states(pendulum, knob, how):
    """The pendulum x^2 + y^2 = L^2 re-selects its states (x or y) as it
    swings: perturbed, the same number of re-selections at the same times
    (within 1e-3 s: the |det| threshold is crossed at a slope of order 1 per
    second of the swing), the same states at the end, and the motion within
    1e-4 m of the unperturbed run (the accuracy of this form at rtol 1e-10,
    see test_dynamic_state_selection)."""
    cm, base = pendulum
    run = nudge(knob, how, {"L": 1.0}, SS_RTOL, SS_TIMES, start_values={"x": 1.0})
    res = cm.simulate(stop_time=None, **run)
    assert res.stopped is None
    assert res.stats["reselections"] == base.stats["reselections"] >= 2
    times = [t for t, text in res.events if text == "state re-selection"]
    base_times = [t for t, text in base.events if text == "state re-selection"]
    assert times == pytest.approx(base_times, abs=1e-3)
    assert res.states == base.states
    for name in ("x", "y"):
        ours = np.interp(base.time, res.time, res[name])
        assert np.max(np.abs(ours - base[name])) < 1e-4
