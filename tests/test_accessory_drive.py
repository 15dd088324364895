"""Bild 3.1 c of Ebert (2015): the accessory belt drive with a back-side
tensioner on a lever (models/accessory_drive.py), checked by

* the statics: at rest the lever stays where it starts (the spring's
  unstressed angle balances the belt's moment at F0); at the steady end
  each driven pulley's load torque is r (F_leave - F_arrive), the
  crankshaft's torque r (F5 - F1), and the lever's spring torque the
  moment of the two span forces at T about the pivot -- all from the run's
  span forces, angles and axis positions;
* the power balance of the whole run: crankshaft work = loads' work +
  dampers' losses + kinetic energy + the elastic energy of spring and belt
  + the belt's damping and creep (material running onto and off the
  pulleys at its span's strain; see tests/test_hydraulic_cable_crane.py);
* the back-side wrap: T lies outside the loop of the other axes, turns
  against them and is wrapped by less than a quarter turn.

Tolerances: rtol 1e-8 of the run.  Statics at the end, 0.9 s after the
ramp (the lever's and the spans' modes are damped within a few hundredths
of a second): bound 1e-6 of the torque scale (the largest span force times
the largest radius).  Energies: 100 rtol of the crankshaft's work."""
import math
import sys

import numpy as np
import pytest
from conftest import load_model_class

import acausal2d
from acausal2d import der, Variable

Drive = load_model_class("accessory_drive.py", "AccessoryDrive")
ad = sys.modules["models_accessory_drive"]

RTOL = 1e-8
SPANS = ["span%d" % k for k in range(1, len(ad.LOOP) + 1)]


class MeteredDrive(Drive):
    """The drive with its work and losses as states and the stored energy."""
    E_in = Variable(start=0.0, fixed=True, unit="J", nominal=1e2, doc="crankshaft work")
    E_loss = Variable(start=0.0, fixed=True, unit="J", nominal=1e2, doc="losses")
    E_store = Variable(unit="J", nominal=1.0, doc="stored energy")

    def equations(self):
        loads = sum(getattr(self, "load" + n).loss_power for n, p in ad.PULLEYS.items()
                    if p[4] is not None)
        belt = 0
        for name in SPANS:
            s = getattr(self, name)
            e, de = s.eps, der(s.eps)
            belt = belt + s.d * de ** 2 * s.l_u + (s.c * e ** 2 / 2 + s.d * e * de) * der(s.l_u)
        kin = sum(0.5 * getattr(self, n).J * der(getattr(self, n).phi) ** 2 for n in ad.PULLEYS)
        kin = kin + 0.5 * self.lever.JL * der(self.lever.phiL) ** 2
        t = self.tensioner
        elastic = 0.5 * t.c * (t.tau / t.c) ** 2 + sum(
            getattr(self, n).c * getattr(self, n).l_u * getattr(self, n).eps ** 2 / 2
            for n in SPANS)
        return [der(self.E_in) == self.C.ctrR2.tau * der(self.C.phi),
                der(self.E_loss) == loads + self.lever_damper.loss_power + belt,
                self.E_store == kin + elastic]


@pytest.fixture(scope="module")
def res():
    return acausal2d.simulate(MeteredDrive(), stop_time=ad.T_STOP, rtol=RTOL,
                              output_times=np.linspace(0.0, ad.T_STOP, 151))


def test_lever_rests_in_its_balance_before_the_drive_starts(res):
    rest = res.time <= ad.T_START
    assert rest.sum() >= 10
    phi0 = ad.lever_start()[1]
    assert np.max(np.abs(res["lever.phiL"][rest] - phi0)) < 1e3 * RTOL
    for name in SPANS:
        assert np.max(np.abs(res[name + ".F"][rest] - ad.F0)) < 1e3 * RTOL * ad.F0


def _span(res, k):
    """(force, unit vector of the span direction) of span k at the end."""
    g = res.final("span%d.gamma" % k)
    return res.final("span%d.F" % k), np.array([math.cos(g), math.sin(g)])


def test_steady_statics_of_pulleys_and_tensioner(res):
    scale = max(res.final(n + ".F") for n in SPANS) * max(p[1] for p in ad.PULLEYS.values())
    for k, name in enumerate(ad.LOOP):
        r, load = ad.PULLEYS[name][1], ad.PULLEYS[name][4]
        leave, arrive = _span(res, k + 1)[0], _span(res, k if k else len(ad.LOOP))[0]
        if load is not None:     # a driven pulley: load d w = r (F_leave - F_arrive)
            w = res.final(name + ".w_rel")
            assert abs(load * w - r * (leave - arrive)) < 1e-6 * scale, name
            assert load * w > 0.1 * scale / 100                 # a real load
    F1, e1 = _span(res, 1)
    F5, _ = _span(res, 5)
    assert abs(res.final("C.ctrR2.tau") - ad.PULLEYS["C"][1] * (F5 - F1)) < 1e-6 * scale
    # tensioner: span 1 pulls T back towards C, span 2 on towards K
    F2, e2 = _span(res, 2)
    R = F2 * e2 - F1 * e1
    arm = np.array([res.final("T.xP1") - ad.PIVOT[0], res.final("T.yP1") - ad.PIVOT[1]])
    moment = arm[0] * R[1] - arm[1] * R[0]
    spring = -ad.C_SPRING * (res.final("lever.phiL") - ad.spring_zero_angle())
    assert abs(spring + moment) < 1e-6 * scale
    assert abs(moment) > 1.0                                  # the spring works


def test_power_balance_of_the_whole_run(res):
    gap = res["E_in"] - res["E_loss"] - (res["E_store"] - res["E_store"][0])
    assert res.final("E_in") > 10.0
    assert np.max(np.abs(gap)) < 100 * RTOL * res.final("E_in")
    # the loads take most of the work
    loads = res.final("E_loss")
    assert 0.5 * res.final("E_in") < loads <= res.final("E_in")


def test_tensioner_runs_on_the_belts_back(res):
    axes = [ad.PULLEYS[n][0] for n in ad.LOOP if n != "T"]      # C, K, W, A: the loop
    T = (res["T.xP1"][0], res["T.yP1"][0])
    inside = all((b[0] - a[0]) * (T[1] - a[1]) - (b[1] - a[1]) * (T[0] - a[0]) > 0
                 for a, b in zip(axes, axes[1:] + axes[:1]))
    assert not inside
    assert res.final("T.w_rel") * res.final("C.w_rel") < 0      # turns against the others
    assert 0.0 < res.final("T.beta") < math.pi / 2
    assert all(res.final(n + ".beta") > math.pi / 2 for n in ("C", "K", "A"))
