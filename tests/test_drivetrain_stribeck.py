"""MassWithStopAndFriction (Modelica.Mechanics.Translational.Components,
Stribeck friction) against an independent solver: SciPy's solve_ivp
(rtol 1e-12) on Modelica's sliding law m v' = F - (F_prop v + F_Coulomb +
F_Stribeck exp(-fexp v)) for v > 0, with the lock at v = 0 and the
breakaway at F = 1.001 (F_Coulomb + F_Stribeck); and its hard stop, which
ends the run with an error naming the element.

Tolerances as in test_drivetrain_friction: speeds 100 RTOL of their scale
plus the stick zone's creep v_s; the lock and breakaway times the time the
speed (force) needs to move by 10 RTOL of its scale plus the zone's lag
m v_s / f0.  After the breakaway the friction falls from 1.001 f0 to the
sliding law within some v_s (the zone's continuous drop):
breakaway_slack of that excess."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import SimulationError
from acausal2d.library import signals
from acausal2d.library import translational as tr

RTOL = 1e-8
V_S = 1e-6
M, F_PROP, F_C, F_S, FEXP = 1.0, 1.0, 5.0, 10.0, 2.0
F0 = F_C + F_S


def _friction(v):
    return F_PROP * v + F_C + F_S * math.exp(-FEXP * v)


class Slider(Component):
    """MassWithStopAndFriction at v0, pushed by ``force(t)`` if given."""

    def __init__(self, v0=0.0, force=None, smax=25.0, s0=0.0, stribeck=True, **kw):
        super().__init__(**kw)
        coeff = dict(F_prop=F_PROP, F_Coulomb=F_C, F_Stribeck=F_S) if stribeck else \
            dict(F_prop=0.0, F_Coulomb=0.0, F_Stribeck=0.0)
        self.mass = tr.MassWithStopAndFriction(m=M, fexp=FEXP, L=0.2, smax=smax, v_s=V_S, law="zone",
                                               s=start(s0, fixed=True), v=start(v0, fixed=True),
                                               **coeff)
        if force is not None:
            self.sig = signals.TimeFunction(force)
            self.src = tr.Force()
            self.connect(self.sig.y, self.src.f_in)
            self.connect(self.src.flange, self.mass.flange_a)


def test_stribeck_mass_slides_to_a_stop_as_scipy():
    """v0 = 2 m/s, no force: decelerates by the Stribeck law and locks where
    SciPy's v reaches 0; then stays."""
    ref = solve_ivp(lambda t, y: [-_friction(y[0]) / M], (0.0, 1.0), [2.0], rtol=1e-12,
                    atol=1e-14, dense_output=True, events=lambda t, y: y[0])
    t_lock = float(ref.t_events[0][0])
    res = acausal2d.simulate(Slider(v0=2.0), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0.0, 1.0, 201))
    slide = res.time < t_lock - 1e-3
    want = ref.sol(res.time[slide])[0]
    assert np.max(np.abs(res["mass.v"][slide] - want)) <= 100 * RTOL * 2.0 + V_S
    lock = [t for t, txt in res.events if "mass.v" in txt]
    assert lock and lock[0] == pytest.approx(t_lock, abs=10 * RTOL * 2.0 / (F0 / M)
                                             + M * V_S / F0)
    assert np.max(np.abs(res["mass.v"][res.time > t_lock + 1e-3])) <= V_S


def test_stribeck_mass_breaks_away_at_f0_max_then_follows_scipy():
    """Force K t from rest: stuck until K t = 1.001 f0, then SciPy's
    m v' = K t - friction(v) from v = 0."""
    K = 50.0
    t_b = 1.001 * F0 / K
    ref = solve_ivp(lambda t, y: [(K * t - _friction(y[0])) / M], (t_b, 0.6), [0.0],
                    rtol=1e-12, atol=1e-14, dense_output=True)
    res = acausal2d.simulate(Slider(force=lambda t: K * t), stop_time=0.6, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.6, 121))
    assert res.events[0][0] == pytest.approx(t_b + M * V_S / (1.001 * F0),
                                             abs=10 * RTOL * F0 / K)
    assert np.max(np.abs(res["mass.v"][res.time < t_b - 1e-3])) <= V_S
    late = res.time > t_b + 1e-3
    want = ref.sol(res.time[late])[0]
    slack = 0.001 * F0 / M * 3 * math.sqrt(2 * M * V_S / K)
    assert np.max(np.abs(res["mass.v"][late] - want)) \
        <= slack + 100 * RTOL * float(np.max(want)) + V_S


def test_reaching_a_hard_stop_ends_the_run_naming_the_element():
    """Frictionless at 1 m/s from s = 0 towards smax = 0.6 with L = 0.2: the
    end s + L/2 reaches the stop at t = 0.5 s; the impact is not modelled,
    so the run stops there with the element's message."""
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(Slider(v0=1.0, smax=0.6, stribeck=False), stop_time=1.0, rtol=RTOL)
    msg = str(err.value)
    assert "MassWithStopAndFriction 'mass'" in msg and "smax" in msg
    assert "0.5" in msg
