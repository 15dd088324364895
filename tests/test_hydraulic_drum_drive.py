"""The hydraulic drum drive of seed Bild 8.6 (models/hydraulic_drum_drive.py):
run-up of both drums from rest with the load hanging, checked by

* the energy balance of the whole run: diesel work = rope work (hoisting
  and hauling) + kinetic energy of all inertias + elastic energy of the oil
  + the losses of pump, motors, relief valve and leakage;
* the controllers reaching their set points: drum speeds, line pressure,
  diesel speed;
* at the steady end, each motor's displacement setting equal to the closed
  form alpha = F r / ((1 + ratio) eta_hm D p) (motoring) and the pump's to
  the flow the motors and the leakage draw.

Tolerances: the run is at RTOL = 1e-7 (atol = RTOL * nominal); the work
integrals are states, so the balance holds to the global error of the run,
given 100 RTOL of the diesel's work.  The set points are reached with the
slowest closed-loop decay of the drum speed loops (J s^2 + b k s + b k / Ti
with the torque gain b per alpha: time constants 0.25 s hoist, 0.27 s
haul), more than 10 time constants after the ramps end at 2.5 s and 3 s:
the remaining error is below 1e-4 of the ramp's tracking error; 1e-3 of
the set point leaves room for the pressure and diesel loops' coupling."""
import math
import sys

import numpy as np
import pytest
from conftest import load_model_class

import acausal2d
from acausal2d import der, Variable
from acausal2d.library.hydraulics import _TWO_PI

Drive = load_model_class("hydraulic_drum_drive.py", "HydraulicDrumDrive")
dd = sys.modules["models_hydraulic_drum_drive"]

RTOL = 1e-7
STOP = 6.0


class MeteredDrive(Drive):
    """The drum drive with its work integrals as states."""
    E_diesel = Variable(start=0.0, fixed=True, unit="J", nominal=1e5, doc="diesel work")
    E_rope = Variable(start=0.0, fixed=True, unit="J", nominal=1e5, doc="work on both ropes")
    E_loss = Variable(start=0.0, fixed=True, unit="J", nominal=1e4, doc="losses")

    def equations(self):
        rope = sum(s.rope.flange.tau * s.drum.w for s in (self.hoist, self.haul))
        loss = (self.pump.loss_power + self.hoist.motor.loss_power + self.haul.motor.loss_power
                + self.relief.loss_power + self.leakage.loss_power)
        return [der(self.E_diesel) == self.diesel_control.y_value * self.diesel.w,
                der(self.E_rope) == rope, der(self.E_loss) == loss]


@pytest.fixture(scope="module")
def res():
    return acausal2d.simulate(MeteredDrive(), stop_time=STOP, rtol=RTOL,
                              output_times=np.linspace(0.0, STOP, 121))


def _kinetic(res, i):
    model = MeteredDrive()
    E = 0.5 * model.diesel.J * res["diesel.w"][i] ** 2
    for s in ("hoist", "haul"):
        string = getattr(model, s)
        E += 0.5 * string.drum.J * res[s + ".drum.w"][i] ** 2
        E += 0.5 * string.rotor.J * res[s + ".rotor.w"][i] ** 2
    return E


def test_diesel_work_equals_rope_work_kinetic_energy_and_losses(res):
    d_kin = _kinetic(res, -1) - _kinetic(res, 0)
    d_oil = res["line.E"][-1] - res["line.E"][0]
    E_in = res.final("E_diesel")
    out = res.final("E_rope") + d_kin + d_oil + res.final("E_loss")
    assert E_in > 1e5                                   # the run does real work
    assert out == pytest.approx(E_in, rel=100 * RTOL)
    # the rope work is the hoisting and hauling work F r phi of the drums
    rope = sum(dd.DRUMS[s][1] * dd.R_DRUM * res.final(s + ".drum.phi") for s in dd.DRUMS)
    assert res.final("E_rope") == pytest.approx(rope, rel=100 * RTOL)


def test_controllers_reach_their_set_points(res):
    for s, (_, _, _, w_set, _) in dd.DRUMS.items():
        assert abs(res.final(s + ".drum.w") - w_set) <= 1e-3 * w_set
    assert abs(res.final("line.p") - dd.P_SET) <= 1e-3 * dd.P_SET
    assert abs(res.final("diesel.w") - dd.W_DIESEL) <= 1e-3 * dd.W_DIESEL
    assert np.max(res["relief.q"]) <= 1e-12        # the relief valve never opened
    # the measurements the controllers see: PressureSensor and SpeedSensor
    assert np.allclose(res["pressure.p.u"], res["line.p"], rtol=10 * RTOL, atol=0)
    assert np.allclose(res["hoist.speed.w.u"], res["hoist.drum.w"], rtol=10 * RTOL,
                       atol=10 * RTOL)


def test_steady_displacement_settings_follow_the_closed_forms(res):
    """Motor alpha = F r / ((1 + ratio) eta_hm Vg/(2 pi) p); pump alpha from
    the flows: eta_vp D_p w_p alpha_p = sum D_m w_m alpha_m / eta_vm + G p."""
    p = res.final("line.p")
    q = dd.G_LEAK * p
    for s, (vg, force, _, _, _) in dd.DRUMS.items():
        alpha = force * dd.R_DRUM / ((1 + dd.RATIO) * 0.92 * vg / _TWO_PI * p)
        assert res.final(s + ".control.y_value") == pytest.approx(alpha, rel=1e-3)
        q += res.final(s + ".control.y_value") * vg / _TWO_PI * res.final(s + ".rotor.w") / 0.97
    alpha_p = q / (dd.EV_PUMP * dd.VG_PUMP / _TWO_PI * res.final("pump.w"))
    assert res.final("pump_control.y_value") == pytest.approx(alpha_p, rel=1e-3)
    assert res.final("pump.w") == pytest.approx(res.final("diesel.w") / dd.GEAR, rel=10 * RTOL)
    assert math.isclose(res.final("hoist.motor.s"), -1.0, abs_tol=1e-6)
