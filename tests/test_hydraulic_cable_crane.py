"""The cable crane driven by the hydraulic drum drive of Ebert (2015), Bild
8.6 (models/hydraulic_cable_crane.py): one transfer cycle, checked by

* the energy balance of the whole system: diesel work = kinetic energy of
  diesel, motor rotors, drums, pulleys, carriage and hook + the potential
  energy of carriage and hook + the ropes' elastic energy c l_u eps^2 / 2
  + the oil's elastic energy + the losses of pump, motors, relief valve and
  leakage + the ropes' damping d l_u eps'^2 + the strain energy of the
  rope material running onto and off the wheels (material leaves a span at
  its strain eps and enters the next at that span's: (c eps^2/2 + d eps
  eps') l_u' per span; the spans of Ebert (2015), eq. 4.53-4.62, count
  the material on a wheel unstretched);
* the drums following their motion laws and the ropes staying taut;
* the study's table and plot.

Work and losses are integrated as states of the run (rtol 1e-7); the
balance is held to 100 rtol of the diesel's work at every output time, the
bound of the drum drive's own balance (tests/test_hydraulic_drum_drive.py)."""
import math
import sys

import casadi as ca
import numpy as np
import pytest
from conftest import load_model_class

import acausal2d
from acausal2d import der, Variable

Crane = load_model_class("hydraulic_cable_crane.py", "HydraulicCableCrane")
hc = sys.modules["models_hydraulic_cable_crane"]
cc = hc.crane

RTOL = 1e-7
SPANS = [n for names in cc.SECTIONS.values() for n in names]
PULLEYS = list(cc.MAST_PULLEYS) + list(cc.CARRIAGE_PULLEYS)


class MeteredCrane(Crane):
    """The hydraulic crane with its energy terms: ``E_in`` the diesel's
    work and ``E_loss`` all losses as states, ``E_store`` the stored energy
    (kinetic, potential, ropes, oil)."""
    E_in = Variable(start=0.0, fixed=True, unit="J", nominal=1e5, doc="diesel work")
    E_loss = Variable(start=0.0, fixed=True, unit="J", nominal=1e4, doc="losses")
    E_store = Variable(unit="J", nominal=1e5, doc="stored energy")

    def equations(self):
        return [der(self.E_in) == self.diesel_control.y_value * self.diesel.w,
                der(self.E_loss) == self._hydraulic_losses() + self._rope_losses(),
                self.E_store == self._kinetic() + self._potential() + self._elastic()]

    def _hydraulic_losses(self):
        return (self.pump.loss_power + self.hoist.motor.loss_power
                + self.haul.motor.loss_power + self.relief.loss_power
                + self.leakage.loss_power)

    def _rope_losses(self):
        out = 0
        for name in SPANS:
            s = getattr(self, name)
            e, de = s.eps, der(s.eps)
            out = out + s.d * de ** 2 * s.l_u + (s.c * e ** 2 / 2 + s.d * e * de) * der(s.l_u)
        return out

    def _kinetic(self):
        rot = [(self.diesel.J, self.diesel.w), (self.hoist.rotor.J, self.hoist.rotor.w),
               (self.haul.rotor.J, self.haul.rotor.w)]
        rot += [(getattr(self, d).J, der(getattr(self, d).phi)) for d in ("D1", "D2")]
        rot += [(getattr(self, p).J, der(getattr(self, p).phi)) for p in PULLEYS]
        car, hook = self.carriage, self.hook
        S = self._carriage_cog()
        return (sum(0.5 * J * w ** 2 for J, w in rot)
                + 0.5 * car.m * (der(S[0]) ** 2 + der(S[1]) ** 2) + 0.5 * car.J * der(car.phi) ** 2
                + 0.5 * hook.m * (der(hook.x) ** 2 + der(hook.y) ** 2))

    def _carriage_cog(self):
        car = self.carriage
        c, s = ca.cos(car.phi), ca.sin(car.phi)
        return (car.x + c * car.cog[0] - s * car.cog[1], car.y + s * car.cog[0] + c * car.cog[1])

    def _potential(self):
        S = self._carriage_cog()
        return cc.G * (self.carriage.m * S[1] + self.hook.m * self.hook.y)

    def _elastic(self):
        ropes = sum(getattr(self, n).c * getattr(self, n).l_u * getattr(self, n).eps ** 2 / 2
                    for n in SPANS)
        return ropes + self.line.E


@pytest.fixture(scope="module")
def cycle():
    return acausal2d.simulate(MeteredCrane(), stop_time=cc.T_STOP, rtol=RTOL,
                              output_times=np.linspace(0.0, cc.T_STOP, 301))


def test_energy_balance_of_the_whole_system_closes(cycle):
    res = cycle
    E_in = res["E_in"]
    gap = E_in - res["E_loss"] - (res["E_store"] - res["E_store"][0])
    assert res.final("E_in") > 1e5                     # the cycle does real work
    assert np.max(np.abs(gap)) < 100 * RTOL * np.max(np.abs(E_in))
    # the terms are not negligible: the hook is lifted 4 m and lowered again,
    # the transport runs the haul-back rope in; the losses are a real share
    assert res.final("E_loss") > 0.1 * res.final("E_in")


def test_drums_follow_their_motion_laws_and_the_ropes_stay_taut(cycle):
    """The speed loops integrate the angle error: at the end of the cycle
    (3 s at rest, ten time constants of the loops after the lowering) each
    drum stands at its law's end angle to 1e-3 of its stroke; the ropes
    never go slack."""
    res = cycle
    phi1, phi2 = cc.drum_angles(cc.drive_design()[2])
    for drum, law in (("D1", phi1), ("D2", phi2)):
        target = float(law(ca.DM(cc.T_STOP)))
        stroke = max(abs(float(law(ca.DM(t)))) for t in np.linspace(0, cc.T_STOP, 61))
        assert abs(res.final(drum + ".phi") - target) < 1e-3 * stroke, drum
    for name in SPANS:
        assert np.min(res[name + ".F"]) > 0.0, name


@pytest.mark.slow          # six runs of the lift (a study)
def test_study_writes_the_pressure_table_and_plot(tmp_path):
    """The declared study writes its table and plot; the largest load
    pressure falls with the ratio and never lies below the quasi-static
    holding pressure m g r / ((1 + i) D) (lifting needs more than holding),
    nor above the line's set pressure plus the pump loop's overshoot."""
    from acausal2d.analysis.study import run_studies
    model = Crane()
    files = run_studies(hc.__file__, model, ["pressure_vs_ratio"], out=str(tmp_path))
    names = sorted(p.split("/")[-1] for p in files)
    assert names == ["hydraulic_cable_crane_pressure.csv", "hydraulic_cable_crane_pressure.png"]
    rows = np.genfromtxt(tmp_path / "hydraulic_cable_crane_pressure.csv", delimiter=",",
                         names=True)
    assert list(rows["ratio"]) == list(hc.STUDY_RATIOS)
    assert np.all(np.diff(rows["p_load_max"]) < 0)
    assert np.all(rows["p_load_max"] > rows["p_holding"])
    assert np.all(rows["p_load_max"] < 1.01 * hc.drive.P_SET)
    hold = cc.M_HOOK * cc.G * cc.R_DRUM / ((1 + rows["ratio"]) * hc.MOTOR_VG / (2 * math.pi))
    assert np.allclose(rows["p_holding"], hold, rtol=1e-9)      # 10 digits written
