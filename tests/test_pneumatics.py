"""Pneumatic cylinder chamber (library/pneumatics.py): adiabatic and
polytropic compression of a fixed gas mass (p V^n = const), energy of a gas
spring, discharge valve opening at the closed-form volume, mass balance."""
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import translational as tr
from acausal2d.library.pneumatics import GasCylinder
from conftest import assert_copied

A = 5e-3          # piston area [m2]
GAP0 = 0.1        # initial gap piston -> head [m]
M = 2.0           # piston mass [kg]


class GasSpring(Component):
    """A 2 kg piston thrown towards the cylinder head with v0; the chamber
    (gap 0.1 m, 0.5 l, air at 1 bar) stops and throws it back."""

    def __init__(self, v0=20.0, n=1.4, discharge=False, intake=False, p_out=3e5, **kw):
        super().__init__(**kw)
        self.head = tr.Fixed(s0=GAP0)
        self.piston = tr.Mass(m=M, s=start(0.0, fixed=True), v=start(v0, fixed=True))
        self.cyl = GasCylinder(A=A, n=n, p_out=p_out, G_out=1e-6,
                               discharge=discharge, intake=intake)
        self.connect(self.piston.flange_b, self.cyl.flange_a)
        self.connect(self.cyl.flange_b, self.head.flange)


@pytest.mark.parametrize("n", [1.4, 1.2])
def test_closed_chamber_follows_p_V_n(n):
    res = acausal2d.simulate(GasSpring(n=n), stop_time=0.05, rtol=1e-9,
                             output_times=np.linspace(0.0, 0.05, 501))
    p, V = res["cyl.p"], res["cyl.V"]
    inv = p * V ** n
    assert np.max(np.abs(inv / inv[0] - 1.0)) < 1e-6
    assert p.max() > 3e5                      # a real compression took place
    assert np.max(np.abs(res["cyl.m"] / res["cyl.m"][0] - 1.0)) < 1e-12
    # ideal gas: m = p V / (R T) at t0 with T = 293.15 K
    assert res["cyl.m"][0] == pytest.approx(1e5 * A * GAP0 / (287.0 * 293.15), rel=1e-10)


def test_adiabatic_gas_spring_conserves_energy():
    res = acausal2d.simulate(GasSpring(n=1.4), stop_time=0.05, rtol=1e-10,
                             output_times=np.linspace(0.0, 0.05, 501))
    p, V, v = res["cyl.p"], res["cyl.V"], res["piston.v"]
    # kinetic + internal energy of the gas + potential of the ambient pressure
    E = 0.5 * M * v ** 2 + p * V / 0.4 + 1e5 * V
    assert np.max(np.abs(E / E[0] - 1.0)) < 1e-6
    # the piston is thrown back (elastic gas spring): at the start volume
    # again it has its start speed, reversed
    assert v.min() < -0.98 * v[0]


def test_discharge_valve_opens_at_closed_form_volume():
    p_out = 3e5
    res = acausal2d.simulate(GasSpring(v0=6.0, discharge=True, p_out=p_out), stop_time=0.03,
                             rtol=1e-9, output_times=np.linspace(0.0, 0.03, 301))
    opens = [t for t, txt in res.events if "cyl.p" in txt]
    assert len(opens) >= 2                    # opens and closes again
    t_open = opens[0]
    V_open = res.at("cyl.V", t_open)
    V0 = A * GAP0
    assert V_open == pytest.approx(V0 * (1e5 / p_out) ** (1 / 1.4), rel=1e-6)
    # valve flow only while p > p_out, and the mass balance holds
    p, mdot, m = res["cyl.p"], res["cyl.mdot_out"], res["cyl.m"]
    assert_copied(mdot[p < p_out * (1 - 1e-9)], 0.0)        # the closed-valve branch
    assert np.all(mdot >= -1e-9 * mdot.max())   # round-off at the closing event
    t = res.time
    delivered = np.concatenate([[0.0], np.cumsum(0.5 * (mdot[1:] + mdot[:-1]) * np.diff(t))])
    assert np.max(np.abs(m[0] - m - delivered)) < 2e-3 * (m[0] - m[-1])
    assert m[-1] < 0.9 * m[0]
    # after the valve has closed again the remaining gas expands adiabatically
    after = t > opens[1] + 1e-9
    inv = p[after] * res["cyl.V"][after] ** 1.4
    assert np.max(np.abs(inv / inv[0] - 1.0)) < 1e-6
