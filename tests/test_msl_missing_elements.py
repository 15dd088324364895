"""Modelica elements drive trains need (Blocks.Math.Product, Rotational
TorqueStep, QuadraticSpeedDependentTorque, IdealGearR2T, IdealRollingWheel,
Translational Mass.L and Brake) against closed forms.

Tolerances: IDA at RTOL; speeds and positions within 100 RTOL of their
scale (the global error)."""

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import blocks, signals
from acausal2d.library import rotational as rot
from acausal2d.library import translational as tr

RTOL = 1e-8
T = np.linspace(0.0, 1.0, 101)


class Driven(Component):
    """Inertia J from rest driven by ``source`` (a torque element with a
    ``flange``)."""

    def __init__(self, source, J=2.0, w0=0.0, **kw):
        super().__init__(**kw)
        self.src = source
        self.inertia = rot.Inertia(J=J, phi=start(0.0, fixed=True), w=start(w0, fixed=True))
        self.connect(self.src.flange, self.inertia.flange_a)


def test_torque_step_accelerates_by_offset_then_step():
    """tau = 1 N m, 1 + 4 N m from 0.5 s, J = 2: w = t/2, then 0.25 +
    2.5 (t - 0.5); tau is the accelerating torque (= -flange.tau)."""
    res = acausal2d.simulate(Driven(rot.TorqueStep(stepTorque=4.0, offsetTorque=1.0,
                                                   startTime=0.5)),
                             stop_time=1.0, rtol=RTOL, output_times=T)
    t = res.time
    want = np.where(t < 0.5, t / 2, 0.25 + 2.5 * (t - 0.5))
    assert np.max(np.abs(res["inertia.w"] - want)) <= 100 * RTOL * 1.5
    assert res.final("src.tau") == pytest.approx(5.0, abs=100 * RTOL * 5)


@pytest.mark.parametrize("direction", (True, False))
def test_quadratic_speed_dependent_load_brakes_as_the_closed_form(direction):
    """tau_nominal = -1 N m at w_nominal = 1 rad/s, J = 2, from w0 = 2: J w'
    = -w^2 (both directions the same for w > 0): w = w0 / (1 + w0 t / J)."""
    src = rot.QuadraticSpeedDependentTorque(tau_nominal=-1.0, w_nominal=1.0,
                                            TorqueDirection=direction)
    res = acausal2d.simulate(Driven(src, w0=2.0), stop_time=1.0, rtol=RTOL, output_times=T)
    want = 2.0 / (1.0 + 2.0 * T / 2.0)
    assert np.max(np.abs(res["inertia.w"] - want)) <= 100 * RTOL * 2.0


def test_quadratic_load_against_the_motion_backward():
    """TorqueDirection=False from w0 = -2: J w' = +w^2: w = -2 / (1 + t)."""
    src = rot.QuadraticSpeedDependentTorque(tau_nominal=-1.0, w_nominal=1.0,
                                            TorqueDirection=False)
    res = acausal2d.simulate(Driven(src, w0=-2.0), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["inertia.w"] + 2.0 / (1.0 + T))) <= 100 * RTOL * 2.0


class ProductDrive(Component):
    """Product of t and 3 as the torque on an inertia J = 2."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.t = signals.TimeFunction(lambda t: t)
        self.k = signals.Constant(k=3.0)
        self.prod = blocks.Product()
        self.src = rot.Torque()
        self.inertia = rot.Inertia(J=2.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.connect(self.t.y, self.prod.u1)
        self.connect(self.k.y, self.prod.u2)
        self.connect(self.prod.y, self.src.tau_in)
        self.connect(self.src.flange, self.inertia.flange_a)


def test_product_multiplies_its_inputs():
    """J w' = 3 t: w = 0.75 t^2."""
    res = acausal2d.simulate(ProductDrive(), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["inertia.w"] - 0.75 * T ** 2)) <= 100 * RTOL


class Hoist(Component):
    """Inertia J driven by the torque 1 N m, through a converter to a mass m."""

    def __init__(self, converter, J=0.5, m=4.0, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=1.0)
        self.inertia = rot.Inertia(J=J, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.conv = converter
        self.mass = tr.Mass(m=m)
        self.connect(self.src.flange, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.conv.flangeR)
        self.connect(self.conv.flangeT, self.mass.flange_a)


@pytest.mark.parametrize("make, ratio", [
    (lambda: rot.IdealGearR2T(ratio=5.0), 5.0),
    (lambda: rot.IdealRollingWheel(radius=0.25), 4.0)])
def test_rotation_to_translation_converters_by_energy(make, ratio):
    """phi = ratio s: 1 N m = (J + m / ratio^2) phi'' (the energy balance of
    the lossless converter); the mass follows s = phi / ratio."""
    J, m = 0.5, 4.0
    acc = 1.0 / (J + m / ratio ** 2)
    res = acausal2d.simulate(Hoist(make(), J=J, m=m), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["inertia.w"] - acc * T)) <= 100 * RTOL * acc
    assert np.max(np.abs(res["mass.v"] - acc * T / ratio)) <= 100 * RTOL * acc
    power = res["inertia.w"] * 1.0
    kinetic = 0.5 * J * res["inertia.w"] ** 2 + 0.5 * m * res["mass.v"] ** 2
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(T))])
    assert np.max(np.abs(kinetic - work)) <= 1e-6 * float(np.max(kinetic))   # trapezoid of a line


class Long(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.fix = tr.Fixed(s0=1.0)
        self.mass = tr.Mass(m=1.0, L=0.4)
        self.connect(self.fix.flange, self.mass.flange_a)


def test_mass_length_puts_the_centre_half_way():
    """flange_a at 1 m and L = 0.4: the centre s at 1.2 m."""
    res = acausal2d.simulate(Long(), stop_time=0.1, rtol=RTOL)
    assert res.final("mass.s") == pytest.approx(1.2, abs=1e-12)


class BrakedMass(Component):
    """Mass 2 kg pushed by the force F, braked (capacity peak mu0 cgeo
    fn_max = 1.2 * 0.5 * 1 * 10 = 6 N, sliding 5 N)."""

    def __init__(self, F, **kw):
        super().__init__(**kw)
        self.force = tr.Force()
        self.f = signals.Constant(k=F)
        self.mass = tr.Mass(m=2.0, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.brake = tr.Brake(fn_max=10.0, peak=1.2)
        self.one = signals.Constant(k=1.0)
        self.connect(self.f.y, self.force.f_in)
        self.connect(self.force.flange, self.mass.flange_a)
        self.connect(self.mass.flange_b, self.brake.flange_a)
        self.connect(self.one.y, self.brake.f_normalized)


@pytest.mark.parametrize("share", (0.99, 1.01))
def test_translational_brake_holds_below_capacity_slips_above(share):
    """0.99 of 6 N: held (v = 0 to the locking's rounding); 1.01: slides
    against 5 N: v = (F - 5) t / 2."""
    F = share * 6.0
    res = acausal2d.simulate(BrakedMass(F), stop_time=1.0, rtol=RTOL, output_times=T)
    if share < 1:
        assert np.max(np.abs(res["mass.v"])) <= 1e-9
        assert np.max(np.abs(res["brake.f"] - F)) <= 100 * RTOL * F
    else:
        assert np.max(np.abs(res["mass.v"] - (F - 5.0) * res.time / 2.0)) <= 100 * RTOL


class Measured(Component):
    """Torque 1 N m -- MultiSensor -- inertia J = 2 from rest."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=1.0)
        self.sensor = rot.MultiSensor()
        self.inertia = rot.Inertia(J=2.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.connect(self.src.flange, self.sensor.flange_a)
        self.connect(self.sensor.flange_b, self.inertia.flange_a)


def test_multisensor_measures_torque_speed_and_power():
    """w = t / 2, the torque passed 1 N m, power = tau w = t / 2 (the
    kinetic energy J w^2 / 2 = t^2 / 4 grows at that rate)."""
    res = acausal2d.simulate(Measured(), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["sensor.w.u"] - T / 2)) <= 100 * RTOL
    assert np.max(np.abs(res["sensor.tau.u"] - 1.0)) <= 100 * RTOL
    assert np.max(np.abs(res["sensor.power.u"] - T / 2)) <= 100 * RTOL


class Reaction(Component):
    """A torque source between a shaft (J1 = 1) and its housing (J2 = 3),
    the housing free: the source's support connected to it (``useSupport =
    true``), the shaft at w1 = w0."""

    def __init__(self, src, w0=0.0, **kw):
        super().__init__(**kw)
        self.src = src
        self.shaft = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(w0, fixed=True))
        self.housing = rot.Inertia(J=3.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.connect(self.src.flange, self.shaft.flange_a)
        self.connect(self.src.support, self.housing.flange_a)


@pytest.mark.parametrize("make", (lambda: rot.ConstantTorque(tau_constant=1.0),
                                  lambda: rot.TorqueStep(stepTorque=0.75, offsetTorque=0.25,
                                                         startTime=0.0)),
                         ids=("ConstantTorque", "TorqueStep"))
def test_torque_support_takes_the_reaction(make):
    """The reaction -1 N m turns the housing: w1 = t, w2 = -t / 3, the
    angular momentum J1 w1 + J2 w2 stays 0; the source's w is the speed
    relative to its support, 4 t / 3, its tau the constant."""
    res = acausal2d.simulate(Reaction(make()), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["shaft.w"] - T)) <= 100 * RTOL
    assert np.max(np.abs(res["housing.w"] + T / 3)) <= 100 * RTOL
    assert np.max(np.abs(res["src.w"] - 4 * T / 3)) <= 100 * RTOL * 4 / 3
    assert np.max(np.abs(res["src.tau"] - 1.0)) <= 100 * RTOL


def test_quadratic_load_on_a_housing_brakes_the_relative_speed():
    """QuadraticSpeedDependentTorque (tau_nominal = -1, TorqueDirection=
    False) between a shaft (J1 = 1, w0 = 2) and a free housing (J2 = 3):
    its w is w1 - w2, w' = -(1/J1 + 1/J2) w |w|: w = w0 / (1 + 4/3 w0 t);
    the momentum J1 w1 + J2 w2 = 2 stays; tau = -w^2."""
    src = rot.QuadraticSpeedDependentTorque(tau_nominal=-1.0, TorqueDirection=False)
    res = acausal2d.simulate(Reaction(src, w0=2.0), stop_time=1.0, rtol=RTOL, output_times=T)
    w = 2.0 / (1.0 + 4.0 / 3.0 * 2.0 * T)
    assert np.max(np.abs(res["src.w"] - w)) <= 100 * RTOL * 2.0
    w1, w2 = res["shaft.w"], res["housing.w"]
    assert np.max(np.abs(w1 + 3 * w2 - 2.0)) <= 100 * RTOL * 2.0
    assert np.max(np.abs(res["src.tau"] + w * w)) <= 100 * RTOL * 4.0


def test_constant_torque_former_tau_warns_and_means_tau_constant():
    """ConstantTorque(tau=...) names the new parameter in a
    DeprecationWarning and drives as tau_constant: w = tau t / J."""
    with pytest.warns(DeprecationWarning, match="tau_constant"):
        src = rot.ConstantTorque(tau=4.0)
    res = acausal2d.simulate(Driven(src), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["inertia.w"] - 2.0 * T)) <= 100 * RTOL * 2.0
    with pytest.raises(ModelDefinitionError, match="tau_constant only"):
        rot.ConstantTorque(tau=4.0, tau_constant=4.0)


class Equilibrium(Component):
    """Inertia on a torsion spring (c = 4) under 2 N m, started with
    a(fixed=True) = 0 and w = 0: the start is the equilibrium phi = 0.5."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=2.0)
        self.inertia = rot.Inertia(J=1.0, a=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.spring = rot.Spring(c=4.0)
        self.fix = rot.Fixed()
        self.connect(self.src.flange, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.spring.flange_b)
        self.connect(self.spring.flange_a, self.fix.flange)


def test_inertia_acceleration_fixed_at_the_start_gives_the_equilibrium():
    """a = 0 and w = 0 at the start: c phi = 2, phi = 0.5, and it stays."""
    res = acausal2d.simulate(Equilibrium(), stop_time=1.0, rtol=RTOL, output_times=T)
    assert np.max(np.abs(res["inertia.phi"] - 0.5)) <= 100 * RTOL
    assert np.max(np.abs(res["inertia.a"])) <= 100 * RTOL * 2.0


class PointToPoint(Component):
    """KinematicPTP's acceleration integrated twice: qd, then q."""

    def __init__(self, ptp, **kw):
        super().__init__(**kw)
        self.ptp = ptp
        self.qd = blocks.Integrator()
        self.q = blocks.Integrator()
        self.connect(self.ptp.y, self.qd.u)
        self.connect(self.qd.y, self.q.u)


def ptp_closed_form(t, deltaq, a, ta, tv, te):
    """(q, qd) of a rest-to-rest motion by deltaq: path acceleration a up to
    ta, constant path speed a ta up to tv, -a up to te (path s from 0 to 1)."""
    sd = np.where(t < ta, a * t, np.where(t < tv, a * ta, np.where(t < te, a * (ta - (t - tv)),
                                                                     0.0)))
    s_tv = a * ta ** 2 / 2 + a * ta * (tv - ta)
    s = np.where(t < ta, a * t ** 2 / 2, np.where(
        t < tv, a * ta ** 2 / 2 + a * ta * (t - ta),
        np.where(t < te, s_tv + a * ta * (t - tv) - a * (t - tv) ** 2 / 2, 1.0)))
    return deltaq * s, deltaq * sd


@pytest.mark.parametrize("deltaq,qd_max,qdd_max,ta,tv,te", (
    (1.0, 10.0, 1.0, 1.0, 1.0, 2.0),              # no phase of constant speed: Ta2 = 10 >= Ta1
    (-2.0, 0.5, 1.0, 0.5, 4.0, 4.5)))             # Ta2 = 0.5 < Ta1 = sqrt(2): speed -qd_max
def test_kinematic_ptp_moves_rest_to_rest_by_deltaq(deltaq, qd_max, qdd_max, ta, tv, te):
    """KinematicPTP's acceleration, integrated, moves q by deltaq from rest
    to rest in Te (times from its equations by hand: sdd_max = qdd_max /
    |deltaq|, the speed never above qd_max), starting at startTime = 0.3;
    its switches are time events at 0.3 + Ta2 (or Ta1), Tv, Te."""
    t0 = 0.3
    ptp = signals.KinematicPTP(deltaq=deltaq, qd_max=qd_max, qdd_max=qdd_max, startTime=t0)
    grid = np.linspace(0.0, 5.0, 101)
    res = acausal2d.simulate(PointToPoint(ptp), stop_time=5.0, rtol=RTOL, output_times=grid)
    tau = np.maximum(res.time - t0, 0.0)
    q, qd = ptp_closed_form(tau, deltaq, qdd_max / abs(deltaq), ta, tv, te)
    scale = abs(deltaq)
    assert np.max(np.abs(res["q.y_value"] - q)) <= 100 * RTOL * scale
    assert np.max(np.abs(res["qd.y_value"] - qd)) <= 100 * RTOL * scale
    assert np.max(np.abs(res["qd.y_value"])) <= qd_max * (1 + 100 * RTOL)
    assert res.final("q.y_value") == pytest.approx(deltaq, abs=100 * RTOL * scale)
    times = [t for t, _ in res.events]
    for switch in (t0, t0 + ta, t0 + tv, t0 + te):
        assert min(abs(t - switch) for t in times) <= 1e-12


class Mount(Component):
    """A mass (m = 1) on a translational SpringDamper to the ground (c = 1,
    d = 0.5), pushed by 1e-6 sin(t) N: a micrometre-scale relative motion."""

    def __init__(self, sd=None, **kw):
        super().__init__(**kw)
        self.sig = signals.Sine(amplitude=1e-6, f=1 / (2 * np.pi))
        self.force = tr.Force()
        self.mass = tr.Mass(m=1.0)
        self.sd = tr.SpringDamper(c=1.0, d=0.5, s_rel=start(0.0, fixed=True),
                                  v_rel=start(0.0, fixed=True), **(sd or {}))
        self.fix = tr.Fixed()
        self.connect(self.sig.y, self.force.f_in)
        self.connect(self.force.flange, self.mass.flange_a)
        self.connect(self.mass.flange_b, self.sd.flange_b)
        self.connect(self.fix.flange, self.sd.flange_a)


def test_translational_relative_states_with_msl_nominal():
    """Translational SpringDamper as Modelica's
    PartialCompliantWithRelativeStates: s_rel is a state (stateSelect =
    prefer; v_rel is the mass's speed), s_rel with s_nominal = 1e-4 m, so the 1e-6 m
    motion s'' + 0.5 s' + s = 1e-6 sin t meets rtol on that scale:
    within 100 rtol x 1e-4 of scipy's solution at rtol 1e-12 (with a
    nominal of 1 the absolute tolerance would be 1e-6, the signal's size)."""
    from scipy.integrate import solve_ivp
    grid = np.linspace(0.0, 10.0, 101)
    ref = solve_ivp(lambda t, y: [y[1], 1e-6 * np.sin(t) - 0.5 * y[1] - y[0]], (0.0, 10.0),
                    [0.0, 0.0], t_eval=grid, rtol=1e-12, atol=1e-20)
    cm = acausal2d.compile_model(Mount())
    res = cm.simulate(stop_time=10.0, rtol=1e-6, output_times=grid)
    assert "sd.s_rel" in res.states and len(res.states) == 2     # v_rel: an alias of mass.v
    assert np.max(np.abs(res["sd.s_rel"] - ref.y[0])) <= 100 * 1e-6 * 1e-4
    assert np.max(np.abs(res["sd.v_rel"] - ref.y[1])) <= 100 * 1e-6 * 1e-4


class Damped(Component):
    """Inertia J = 2 at w0 = 3 on a rotational Damper (d = 4) to the ground."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.inertia = rot.Inertia(J=2.0, phi=start(0.0, fixed=True), w=start(3.0, fixed=True))
        self.damper = rot.Damper(d=4.0)
        self.fix = rot.Fixed()
        self.connect(self.fix.flange, self.damper.flange_a)
        self.connect(self.damper.flange_b, self.inertia.flange_a)


def test_damper_w_rel_and_its_relative_angle():
    """Modelica's Damper (PartialCompliantWithRelativeStates): w_rel =
    der(phi_rel), tau = d w_rel; J w' = -d w: w_rel = 3 exp(-2 t), phi_rel
    = 1.5 (1 - exp(-2 t)), the torque on the inertia -d w_rel."""
    res = acausal2d.simulate(Damped(), stop_time=1.0, rtol=RTOL, output_times=T)
    w = 3.0 * np.exp(-2.0 * T)
    assert np.max(np.abs(res["damper.w_rel"] - w)) <= 100 * RTOL * 3.0
    assert np.max(np.abs(res["damper.phi_rel"] - 1.5 * (1 - np.exp(-2.0 * T)))) <= 100 * RTOL
    assert np.max(np.abs(res["damper.tau"] - 4.0 * w)) <= 100 * RTOL * 12.0


def test_relative_state_keywords_as_modelica():
    """Modelica's stateSelect and phi_nominal / s_nominal of
    PartialCompliantWithRelativeStates: StateSelect.avoid leaves the
    mass's own s, v as the states (the run's motion unchanged: within 100
    rtol of the nominal scale of the default run); a nominal below
    Modelica.Constants.eps means 1; the clutches take them too; a wrong
    literal is an error naming the keyword."""
    grid = np.linspace(0.0, 10.0, 101)
    cm = acausal2d.compile_model(Mount(sd={"stateSelect": "StateSelect.avoid"}))
    avoid = cm.simulate(stop_time=10.0, rtol=1e-6, output_times=grid)
    assert "sd.s_rel" not in avoid.states and set(avoid.states) == {"mass.s", "mass.v"}
    default = acausal2d.simulate(Mount(), stop_time=10.0, rtol=1e-6, output_times=grid)
    assert np.max(np.abs(avoid["sd.s_rel"] - default["sd.s_rel"])) <= 100 * 1e-6 * 1e-4
    assert tr.SpringDamper(s_nominal=1e-3).variable("s_rel").nominal == pytest.approx(1e-3)
    assert rot.SpringDamper(phi_nominal=0.0).variable("phi_rel").nominal == pytest.approx(1.0)
    assert rot.Clutch(phi_nominal=1e-3).variable("phi_rel").nominal == pytest.approx(1e-3)
    assert rot.OneWayClutch(stateSelect="never").variable("w_rel").state_select == "never"
    with pytest.raises(ModelDefinitionError, match="stateSelect must be one of"):
        rot.Damper(stateSelect="StateSelect.sometimes")
    with pytest.raises(ModelDefinitionError, match="phi_nominal"):
        rot.Damper(phi_nominal=-1.0)
