"""IdealGear and IdealPlanetary (Modelica.Mechanics.Rotational.Components)
against closed forms: the speed of an inertia driven through the gear by a
constant torque (the load's inertia reflected by the ratio squared), the
power balance of a lossless gear, Willis' equation with the carrier moving
and the torque ratios of the planetary.

Tolerances: IDA runs at RTOL; the speeds are linear in time (BDF is exact
there up to the error control), so they are compared to 100 RTOL of their
range (the global error over some hundred steps).  The power balance and the
torque ratios are equations of the gear solved by Newton to its tolerance
(far below RTOL of the power scale), given RTOL of that scale."""
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import rotational as rot
from acausal2d.library import signals

RTOL = 1e-8
T_END = 1.0


def _times():
    return np.linspace(0.0, T_END, 51)


class GearTrain(Component):
    """Torque T on inertia J1 -- IdealGear(ratio) -- inertia J2; the gear's
    support on a housing inertia Jh when ``housing`` (else grounded)."""

    def __init__(self, ratio=5.0, T=2.0, J1=0.1, J2=3.0, housing=None, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=T)
        self.in_ = rot.Inertia(J=J1, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.gear = rot.IdealGear(ratio=ratio)
        self.out = rot.Inertia(J=J2, phi=start(0.0, fixed=True))
        self.connect(self.src.flange, self.in_.flange_a)
        self.connect(self.in_.flange_b, self.gear.flange_a)
        self.connect(self.gear.flange_b, self.out.flange_a)
        if housing is not None:
            self.house = rot.Inertia(J=housing, phi=start(0.0, fixed=True),
                                     w=start(0.0, fixed=True))
            self.connect(self.gear.support, self.house.flange_a)


def test_ideal_gear_reflects_the_load_by_the_ratio_squared():
    """w_a = T t / (J1 + J2 / ratio^2), w_b = w_a / ratio; the torque at
    flange_b is ratio times the torque at flange_a (opposite sign as a
    flow), so the power in equals the power out."""
    ratio, T, J1, J2 = 5.0, 2.0, 0.1, 3.0
    res = acausal2d.simulate(GearTrain(ratio, T, J1, J2), stop_time=T_END, rtol=RTOL,
                             output_times=_times())
    t = res.time
    w_a = T * t / (J1 + J2 / ratio ** 2)
    scale = float(np.max(w_a))
    assert np.max(np.abs(res["in_.w"] - w_a)) <= 100 * RTOL * scale
    assert np.max(np.abs(res["out.w"] - w_a / ratio)) <= 100 * RTOL * scale
    tau_a, tau_b = res["gear.flange_a.tau"], res["gear.flange_b.tau"]
    assert np.max(np.abs(tau_b + ratio * tau_a)) <= RTOL * T * ratio
    p_in, p_out = tau_a * res["in_.w"], -tau_b * res["out.w"]
    assert np.max(np.abs(p_in - p_out)) <= RTOL * T * scale
    # the grounded support takes the reaction -(tau_a + tau_b) = (ratio - 1) tau_a
    assert np.max(np.abs(res["gear.support.tau"] + tau_a + tau_b)) <= RTOL * T * ratio
    assert np.max(np.abs(res["gear.support.phi"])) <= 1e-12


def test_ideal_gear_on_a_free_housing_keeps_the_angular_momentum():
    """The support on a free housing: nothing is grounded, so the angular
    momentum J1 w1 + J2 w2 + Jh wh grows as T t; the relative angles obey
    phi_a - phi_h = ratio (phi_b - phi_h); the three flange powers sum to
    zero."""
    ratio, T, J1, J2, Jh = -3.0, 2.0, 0.1, 3.0, 0.7
    res = acausal2d.simulate(GearTrain(ratio, T, J1, J2, housing=Jh), stop_time=T_END,
                             rtol=RTOL, output_times=_times())
    t = res.time
    L = J1 * res["in_.w"] + J2 * res["out.w"] + Jh * res["house.w"]
    scale = float(np.max(np.abs(res["in_.w"])))
    assert np.max(np.abs(L - T * t)) <= 100 * RTOL * T * T_END
    rel = (res["in_.phi"] - res["house.phi"]) - ratio * (res["out.phi"] - res["house.phi"])
    assert np.max(np.abs(rel)) <= 100 * RTOL * scale * T_END
    assert np.max(np.abs(res["gear.phi_a"] - (res["in_.phi"] - res["house.phi"]))) \
        <= 100 * RTOL * scale * T_END
    power = res["gear.flange_a.tau"] * res["in_.w"] + res["gear.flange_b.tau"] * res["out.w"] \
        + res["gear.support.tau"] * res["house.w"]
    assert np.max(np.abs(power)) <= 10 * RTOL * T * scale
    assert float(np.max(np.abs(res["house.w"]))) > 0.1 * scale     # the housing does turn


class Planetary(Component):
    """Torque T on the sun (inertia Js); the ring fixed; the carrier drives
    the load inertia Jc."""

    def __init__(self, ratio=100 / 50, T=1.0, Js=0.01, Jc=2.0, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=T)
        self.sun = rot.Inertia(J=Js, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.gear = rot.IdealPlanetary(ratio=ratio)
        self.ring = rot.Fixed()
        self.load = rot.Inertia(J=Jc)
        self.connect(self.src.flange, self.sun.flange_a)
        self.connect(self.sun.flange_b, self.gear.sun)
        self.connect(self.ring.flange, self.gear.ring)
        self.connect(self.gear.carrier, self.load.flange_a)


def test_planetary_with_the_ring_held_reduces_by_one_plus_ratio():
    """Ring fixed: w_carrier = w_sun / (1 + ratio); the carrier's inertia
    is seen from the sun divided by (1 + ratio)^2, so w_sun = T t / (Js +
    Jc / (1 + ratio)^2); the ring takes ratio times the sun's torque."""
    r, T, Js, Jc = 100 / 50, 1.0, 0.01, 2.0
    res = acausal2d.simulate(Planetary(r, T, Js, Jc), stop_time=T_END, rtol=RTOL,
                             output_times=_times())
    w_s = T * res.time / (Js + Jc / (1 + r) ** 2)
    scale = float(np.max(w_s))
    assert np.max(np.abs(res["sun.w"] - w_s)) <= 100 * RTOL * scale
    assert np.max(np.abs(res["load.w"] - w_s / (1 + r))) <= 100 * RTOL * scale
    tau_s = res["gear.sun.tau"]
    assert np.max(np.abs(res["gear.ring.tau"] - r * tau_s)) <= RTOL * T * r
    assert np.max(np.abs(res["gear.carrier.tau"] + (1 + r) * tau_s)) <= RTOL * T * (1 + r)


class Willis(Component):
    """Sun and ring driven by prescribed angles (sun a t, ring b t^2), the
    carrier carries the inertia Jc."""

    def __init__(self, ratio, a, b, Jc, **kw):
        super().__init__(**kw)
        self.sun_angle = signals.TimeFunction(lambda t: a * t)
        self.ring_angle = signals.TimeFunction(lambda t: b * t ** 2)
        self.sun = rot.Position()
        self.ring = rot.Position()
        self.gear = rot.IdealPlanetary(ratio=ratio)
        self.carrier = rot.Inertia(J=Jc)
        self.connect(self.sun_angle.y, self.sun.phi_in)
        self.connect(self.ring_angle.y, self.ring.phi_in)
        self.connect(self.sun.flange, self.gear.sun)
        self.connect(self.ring.flange, self.gear.ring)
        self.connect(self.gear.carrier, self.carrier.flange_a)


def test_willis_equation_with_the_carrier_moving():
    """(1 + ratio) phi_carrier = phi_sun + ratio phi_ring with both sun and
    ring turning: the carrier's angle (a t + ratio b t^2) / (1 + ratio),
    its acceleration 2 ratio b / (1 + ratio) needs the torque Jc times it,
    which the sun supplies as 1/(1 + ratio) and the ring as ratio/(1 + ratio)."""
    r, a, b, Jc = 3.0, 2.0, 1.5, 0.4
    res = acausal2d.simulate(Willis(r, a, b, Jc), stop_time=T_END, rtol=RTOL,
                             output_times=_times())
    t = res.time
    phi_c = (a * t + r * b * t ** 2) / (1 + r)
    assert np.max(np.abs(res["carrier.phi"] - phi_c)) <= 100 * RTOL * float(np.max(phi_c))
    assert np.max(np.abs(res["carrier.w"] - (a + 2 * r * b * t) / (1 + r))) \
        <= 100 * RTOL * (a + 2 * r * b)
    tau_c = Jc * 2 * r * b / (1 + r)          # torque accelerating the carrier's inertia
    assert np.max(np.abs(res["gear.carrier.tau"] + tau_c)) <= 100 * RTOL * tau_c
    assert np.max(np.abs(res["gear.sun.tau"] - tau_c / (1 + r))) <= 100 * RTOL * tau_c
    assert np.max(np.abs(res["gear.ring.tau"] - r * tau_c / (1 + r))) <= 100 * RTOL * tau_c


@pytest.mark.parametrize("cls, name, value", [(rot.IdealGear, "ratio", 0.0),
                                               (rot.IdealPlanetary, "ratio", 0.0),
                                               (rot.IdealPlanetary, "ratio", -2.0)])
def test_bad_ratio_is_refused_naming_the_parameter(cls, name, value):
    with pytest.raises(ModelDefinitionError) as err:
        cls(**{name: value})
    assert cls.__name__ in str(err.value) and "parameter %s" % name in str(err.value)
