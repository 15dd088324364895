"""Parts, 1D elements and signal blocks of issue 14 against closed forms:
BodyShape (compound pendulum), FixedRotation, the 2D Spring (world-axis,
inert c_phi) and Damper (line damper through zero length), the 1D
SpringDampers and sensors, Sine/Ramp with start times, FirstOrder and
InverseBlockConstraints; units on every new parameter; the drawings."""
import math

import casadi as ca
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import planar, rotational, signals, translational
from acausal2d.library.planar import forces as planar_forces
from acausal2d.library.planar import (Body, BodyShape, Fixed, FixedRotation, FixedTranslation,
                                      Prismatic, Revolute)
from acausal2d.library.planar.forces import Damper, Spring
from acausal2d.visual.animation import validate_scene
from acausal2d.visual.scene import build_scene
from conftest import load_model_class, assert_copied

G = 9.81


# --------------------------------------------------------------------------
# BodyShape and FixedRotation

class CompoundPendulum(Component):
    """Revolute -> FixedRotation(alpha) -> BodyShape (r, r_CM, m, I about
    the centre of mass), released from phi0."""

    def __init__(self, alpha=0.4, phi0=0.3, shape="box", **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(phi0, fixed=True), w=start(0.0, fixed=True))
        self.turn = FixedRotation(alpha=alpha)
        self.link = BodyShape(r=(1.2, 0.0), r_CM=(0.5, 0.1), m=2.0, I=0.2, shape=shape)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.turn.frame_a)
        self.connect(self.turn.frame_b, self.link.frame_a)


def test_body_shape_compound_pendulum():
    """I_O phi'' = -m g (R(phi + alpha) r_CM)_x with I_O = I + m |r_CM|^2
    (DOP853 to 1e-8); frame_b sits at R(phi + alpha) r; the link's own
    variables are its centre of mass."""
    alpha, m, inertia, rc = 0.4, 2.0, 0.2, 0.5 + 0.1j
    times = np.linspace(0.0, 3.0, 301)
    res = acausal2d.simulate(CompoundPendulum(alpha), output_times=times, rtol=1e-11)
    i_o = inertia + m * abs(rc) ** 2

    def rhs(t, x):
        return [x[1], -m * G * (np.exp(1j * (x[0] + alpha)) * rc).real / i_o]

    sol = solve_ivp(rhs, (0, 3), [0.3, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
                    t_eval=times)
    assert np.max(np.abs(res["revolute.phi"] - sol.y[0])) < 1e-8
    turn = np.exp(1j * (res["revolute.phi"] + alpha))
    end = turn * 1.2
    assert np.max(np.abs(res["link.frame_b.x"] - end.real)) < 1e-10
    assert np.max(np.abs(res["link.frame_b.y"] - end.imag)) < 1e-10
    assert np.max(np.abs(res["link.x"] - (turn * rc).real)) < 1e-10
    assert np.max(np.abs(res["link.phi"] - res["revolute.phi"] - alpha)) < 1e-10


def test_body_shape_forces_at_frame_b():
    """A BodyShape carrying a Body at frame_b equals the same mass data
    written with two FixedTranslations and two Bodies (the centre-of-mass
    moment balance with a load at frame_b)."""
    class Carrying(CompoundPendulum):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.tip = Body(m=0.7, I=0.05)
            self.connect(self.link.frame_b, self.tip.frame_a)

    class Plain(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed()
            self.revolute = Revolute(phi=start(0.3, fixed=True), w=start(0.0, fixed=True))
            self.turn = FixedRotation(alpha=0.4)
            self.to_cm = FixedTranslation(r=(0.5, 0.1))
            self.cm = Body(m=2.0, I=0.2)
            self.to_tip = FixedTranslation(r=(1.2, 0.0))
            self.tip = Body(m=0.7, I=0.05)
            self.connect(self.fixed.frame, self.revolute.frame_a)
            self.connect(self.revolute.frame_b, self.turn.frame_a)
            for rod, body in ((self.to_cm, self.cm), (self.to_tip, self.tip)):
                self.connect(self.turn.frame_b, rod.frame_a)
                self.connect(rod.frame_b, body.frame_a)

    times = np.linspace(0.0, 3.0, 61)
    a = acausal2d.simulate(Carrying(), output_times=times, rtol=1e-11)
    b = acausal2d.simulate(Plain(), output_times=times, rtol=1e-11)
    assert np.max(np.abs(a["revolute.phi"] - b["revolute.phi"])) < 1e-8
    assert np.max(np.abs(a["revolute.w"] - b["revolute.w"])) < 1e-8


def test_body_shape_shape_option_checked():
    with pytest.raises(ModelDefinitionError, match="shape must be one of rod, box"):
        BodyShape(shape="sphere")


class DrivenJoints(Component):
    """No gravity: a body on a revolute joint (I about the pivot 0.5) driven
    by a 1D torque source on its flange, and a body on a prismatic joint
    (m 2, axis (3, 4)) pushed by a 1D force source on its flange."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.world = planar.PlanarWorld(g=(0.0, 0.0))
        self.fixed = Fixed(phi=0.3)
        self.revolute = Revolute(use_flange=True, phi=start(0.0, fixed=True),
                                 w=start(0.0, fixed=True))
        self.wheel = Body(m=1.0, I=0.5)
        self.torque = rotational.Torque()
        self.tau = signals.Constant(k=1.5)
        self.prismatic = Prismatic(use_flange=True, r=(3.0, 4.0), s=start(0.0, fixed=True),
                                   v=start(0.0, fixed=True))
        self.slider = Body(m=2.0, I=0.1)
        self.force = translational.Force()
        self.f = signals.Constant(k=4.0)
        for joint, body in ((self.revolute, self.wheel), (self.prismatic, self.slider)):
            self.connect(self.fixed.frame, joint.frame_a)
            self.connect(joint.frame_b, body.frame_a)
        self.connect(self.tau.y, self.torque.tau_in)
        self.connect(self.torque.flange, self.revolute.flange_a)
        self.connect(self.f.y, self.force.f_in)
        self.connect(self.force.flange, self.prismatic.flange_a)


def test_joint_flanges_drive_the_joint_coordinates():
    """A 1D source pushing a joint's flange positively drives phi (s)
    positively: phi'' = 1.5/0.5, s'' = 4/2 along the axis turned by the
    fixed frame's 0.3 rad; the supports are grounded inside the joints."""
    times = np.linspace(0.0, 1.0, 11)
    res = acausal2d.simulate(DrivenJoints(), output_times=times, rtol=1e-10)
    assert np.max(np.abs(res["revolute.phi"] - 1.5 * times ** 2)) < 1e-8
    assert np.max(np.abs(res["prismatic.s"] - 1.0 * times ** 2)) < 1e-8
    axis = np.exp(0.3j) * (0.6 + 0.8j)
    assert np.max(np.abs(res["slider.x"] - axis.real * times ** 2)) < 1e-8
    assert np.max(np.abs(res["slider.y"] - axis.imag * times ** 2)) < 1e-8
    assert np.max(np.abs(res["wheel.phi"] - 0.3 - 1.5 * times ** 2)) < 1e-8


# --------------------------------------------------------------------------
# the 2D Spring and Damper

class SpringOnSlider(Component):
    """A body on a prismatic joint along r, held by a Spring (and optionally
    a Damper) from the fixed origin."""

    def __init__(self, axis=(1.0, 1.0), damper=False, c_phi=0.0, **kw):
        super().__init__(**kw)
        self.world = planar.PlanarWorld(g=(0.0, 0.0))
        self.fixed = Fixed()
        self.prismatic = Prismatic(r=axis, s=start(1.0, fixed=True), v=start(0.0, fixed=True))
        self.spring = Spring(c_x=4.0, c_y=1.0, s_relx0=0.0, s_rely0=0.0, c_phi=c_phi,
                             phi_rel0=1.0)
        self.body = Body(m=1.0, I=0.1)
        parts = [self.prismatic, self.spring]
        if damper:
            self.damper = Damper(d=0.5)
            parts.append(self.damper)
        for part in parts:
            self.connect(self.fixed.frame, part.frame_a)
            self.connect(part.frame_b, self.body.frame_a)


def test_spring_is_two_world_axis_springs_and_c_phi_is_inert():
    """On a 45 degree slider the axis springs act separately: the force
    along the axis is -(c_x + c_y)/2 s, so s'' = -2.5 s (no gravity);
    c_phi = 1e5 and phi_rel0 = 1 change nothing, both frame torques stay 0."""
    times = np.linspace(0.0, 4.0, 81)
    soft = acausal2d.simulate(SpringOnSlider(c_phi=0.0), output_times=times, rtol=1e-11)
    stiff = acausal2d.simulate(SpringOnSlider(c_phi=1e5), output_times=times, rtol=1e-11)
    assert np.max(np.abs(soft["prismatic.s"] - np.cos(math.sqrt(2.5) * times))) < 1e-8
    # c_phi multiplies phi_rel, which is 0 by the joint (the slider does not
    # turn): both runs do the same arithmetic
    assert_copied(stiff["prismatic.s"], soft["prismatic.s"])
    assert_copied(stiff["spring.frame_b.t"], 0.0)
    s = soft["prismatic.s"] / math.sqrt(2)
    energy = 0.5 * 4.0 * s ** 2 + 0.5 * 1.0 * s ** 2
    assert np.max(np.abs(soft["spring.energy"] - energy)) < 1e-10
    assert_copied(soft["spring.phi_rel"], 0.0)


def test_line_damper_passes_through_zero_length():
    """With the Damper the axial motion is s'' = -2.5 s - 0.5 s' (the line
    of the damper is the slider axis, on either side of the origin: the
    body passes the fixed frame, where the damper has zero length); closed
    form to 1e-7 and the loss power d v^2."""
    times = np.linspace(0.0, 6.0, 601)
    res = acausal2d.simulate(SpringOnSlider(damper=True), output_times=times, rtol=1e-11)
    wd = math.sqrt(2.5 - 0.0625)
    expected = np.exp(-0.25 * times) * (np.cos(wd * times) + 0.25 / wd * np.sin(wd * times))
    assert np.min(res["prismatic.s"]) < 0 < np.max(res["prismatic.s"])
    assert np.max(np.abs(res["prismatic.s"] - expected)) < 1e-7
    v = res["prismatic.v"]
    assert np.max(np.abs(res["damper.loss_power"] - 0.5 * v ** 2)) < 1e-7
    assert np.max(np.abs(np.abs(res["damper.v"]) - np.abs(v))) < 1e-7


# --------------------------------------------------------------------------
# 1D elements

class OneD(Component):
    """A translational and a rotational oscillator on 1D SpringDampers,
    with position and angle sensors."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ground = translational.Fixed()
        self.sd = translational.SpringDamper(c=4.0, d=0.4, s_rel0=0.5)
        self.mass = translational.Mass(m=1.0, s=start(1.5, fixed=True), v=start(0.0, fixed=True))
        self.pos = translational.PositionSensor()
        self.rground = rotational.Fixed()
        self.rsd = rotational.SpringDamper(c=8.0, d=0.8)
        self.inertia = rotational.Inertia(J=2.0, phi=start(1.0, fixed=True),
                                          w=start(0.0, fixed=True))
        self.angle = rotational.AngleSensor()
        self.connect(self.ground.flange, self.sd.flange_a)
        self.connect(self.sd.flange_b, self.mass.flange_a)
        self.connect(self.mass.flange_b, self.pos.flange)
        self.connect(self.rground.flange, self.rsd.flange_a)
        self.connect(self.rsd.flange_b, self.inertia.flange_a)
        self.connect(self.inertia.flange_b, self.angle.flange)


def test_one_dimensional_spring_dampers_and_sensors():
    """x'' = -4 x - 0.4 x' for both (x = s - 0.5 resp. phi): closed form to
    1e-8; the sensors read the flange without loading it."""
    times = np.linspace(0.0, 5.0, 101)
    res = acausal2d.simulate(OneD(), output_times=times, rtol=1e-11)
    wd = math.sqrt(4.0 - 0.04)
    x = np.exp(-0.2 * times) * (np.cos(wd * times) + 0.2 / wd * np.sin(wd * times))
    assert np.max(np.abs(res["mass.s"] - 0.5 - x)) < 1e-8
    assert np.max(np.abs(res["inertia.phi"] - x)) < 1e-8
    assert_copied(res["pos.s.u"], res["mass.s"])                    # sensors: aliases
    assert_copied(res["angle.phi.u"], res["inertia.phi"])
    assert np.max(np.abs(res["sd.loss_power"] - 0.4 * res["mass.v"] ** 2)) < 1e-10


# --------------------------------------------------------------------------
# signals

class SignalBench(Component):
    """Sine and Ramp with start times, a FirstOrder (steady-state start)
    fed by the ramp."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sine = signals.Sine(amplitude=2.0, f=0.5, phase=0.3, offset=1.0, start_time=0.7)
        self.ramp = signals.Ramp(height=3.0, duration=1.0, offset=-1.0, start_time=0.5)
        self.lag = signals.FirstOrder(k=2.0, T=0.4)
        self.connect(self.ramp.y, self.lag.u)


def test_sine_ramp_and_first_order():
    """Sine: offset before its start time, the shifted wave after; Ramp:
    offset, linear rise, offset + height; FirstOrder: starts in steady
    state y = k u(0) and follows the closed-form response to the ramp
    (to 1e-8)."""
    times = np.linspace(0.0, 3.0, 301)
    res = acausal2d.simulate(SignalBench(), output_times=times, rtol=1e-11)
    t = res.time
    sine = np.where(t < 0.7, 1.0, 1.0 + 2.0 * np.sin(2 * np.pi * 0.5 * (t - 0.7) + 0.3))
    left = np.append(np.diff(t) == 0, False)                  # left limits at events
    assert np.max(np.abs(res["sine.y.u"] - sine)[~left]) < 1e-9
    ramp = -1.0 + 3.0 * np.clip(t - 0.5, 0.0, 1.0)
    assert np.max(np.abs(res["ramp.y.u"] - ramp)) < 1e-10
    k, T = 2.0, 0.4

    def response(tt):          # y for a unit-slope ramp starting at 0, y(0) = 0
        return k * (tt - T * (1 - np.exp(-tt / T)))

    y = -2.0 + 3.0 * (response(np.clip(t - 0.5, 0, None)) - response(np.clip(t - 1.5, 0, None)))
    assert res["lag.y_value"][0] == pytest.approx(-2.0, abs=1e-12)
    assert np.max(np.abs(res["lag.y_value"] - y)) < 1e-8
    assert sorted({round(e, 9) for e, _ in res.events}) == pytest.approx([0.5, 0.7, 1.5], abs=1e-9)


class InverseLag(Component):
    """A FirstOrder run backwards: its output is prescribed to sin(t) by
    InverseBlockConstraints, its input is solved for."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.target = signals.TimeFunction(func=ca.sin)
        self.lag = signals.FirstOrder(k=2.0, T=0.4, init="free")
        self.inverse = signals.InverseBlockConstraints()
        self.connect(self.lag.y, self.inverse.u1)
        self.connect(self.target.y, self.inverse.u2)
        self.connect(self.inverse.y1, self.lag.u)


def test_inverse_block_constraints_invert_a_first_order_lag():
    """u = (T y' + y)/k for y = sin(t): the inverse of the lag (1e-9)."""
    times = np.linspace(0.0, 2.0, 41)
    res = acausal2d.simulate(InverseLag(), output_times=times, rtol=1e-10)
    t = res.time
    assert np.max(np.abs(res["lag.y_value"] - np.sin(t))) < 1e-10
    assert np.max(np.abs(res["inverse.y1.u"] - (0.4 * np.cos(t) + np.sin(t)) / 2.0)) < 1e-9
    assert_copied(res["inverse.y2.u"], res["inverse.y1.u"])


def test_first_order_init_options():
    with pytest.raises(ModelDefinitionError, match="init must be one of"):
        signals.FirstOrder(init="steady")

    class Start(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.c = signals.Constant(k=1.0)
            self.lag = signals.FirstOrder(k=1.0, T=0.5, init="initial_output", y_start=3.0)
            self.connect(self.c.y, self.lag.u)

    res = acausal2d.simulate(Start(), stop_time=1.0, rtol=1e-10,
                             output_times=np.linspace(0, 1, 11))
    assert np.max(np.abs(res["lag.y_value"] - (1.0 + 2.0 * np.exp(-res.time / 0.5)))) < 1e-8


# --------------------------------------------------------------------------
# units and drawings

NEW_ELEMENTS = [planar.FixedRotation, planar.BodyShape, planar.IdealRolling,
                planar_forces.Spring, planar_forces.Damper, planar_forces.SpringDamper,
                planar_forces.LineSpringDamper,
                translational.SpringDamper, rotational.SpringDamper, signals.FirstOrder,
                signals.Sine, signals.Ramp]


@pytest.mark.parametrize("cls", NEW_ELEMENTS, ids=[c.__name__ for c in NEW_ELEMENTS])
def test_every_new_parameter_has_a_unit_and_a_description(cls):
    """Units are declared ('' only for the dimensionless signal values and
    gains), and listed with the value rules."""
    dimensionless = {"k", "amplitude", "offset", "height", "y_start"}
    for klass in cls.__mro__:
        for name, decl in vars(klass).items():
            if isinstance(decl, acausal2d.Parameter):
                assert decl.doc, (cls.__name__, name)
                assert decl.unit or name in dimensionless, (cls.__name__, name)


@pytest.mark.parametrize("name", ["SpringDemo", "SpringDamperDemo", "PendulumExcited",
                                  "InvertedCraneCrab", "MeasureDemo"])
def test_reference_models_draw_every_element(name):
    """Each model's scene is valid and every planar element of it draws
    something: springs as zigzags, dampers as pots, sensors as marks,
    forces as arrows."""
    model = load_model_class("planar_examples.py", name)()
    res = acausal2d.simulate(model, stop_time=0.5, intervals=10)
    scene = build_scene(res)
    validate_scene(scene)
    drawn = {s_name for shape in scene["shapes"] for s_name in _owners(shape)}
    planar_elements = [c for c in model.components() if c is not model
                       and type(c).__module__.split(".")[-1].startswith("planar")
                       and not isinstance(c, planar.PlanarWorld)]
    for comp in planar_elements:
        assert comp.path in drawn, comp.describe()
    kinds = {s["type"] for s in scene["shapes"]}
    expected = {"SpringDemo": {"spring", "damper"}, "SpringDamperDemo": {"spring", "damper"},
                "PendulumExcited": {"arrow", "torque", "sensor"},
                "InvertedCraneCrab": {"arrow", "torque"}, "MeasureDemo": {"sensor"}}[name]
    assert expected <= kinds


def _owners(shape):
    """Component paths a shape's signals belong to."""
    names = []
    for value in shape.values():
        items = value if isinstance(value, list) else [value]
        for item in items:
            for v in (item if isinstance(item, list) else [item]):
                if isinstance(v, str) and "." in v:
                    names.append(v.split(".")[0])
    return names
