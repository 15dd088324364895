"""Five PlanarMechanics examples, built as the reference README describes
them (references SpringDemo.csv, SpringDamperDemo.csv, PendulumExcited.csv,
InvertedCraneCrab.csv, MeasureDemo.csv; Dymola, PlanarMechanics
2.0.0-alpha).  Run one with ``acausal2d simulate models/planar_examples.py
--model SpringDemo``.  The output grid of each experiment is the
reference's (5000 intervals).
"""
from acausal2d import Component, start
from acausal2d.library import rotational, signals, translational
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute
from acausal2d.library.planar.forces import Damper, Spring, SpringDamper, WorldForce
from acausal2d.library.planar.sensors import (AbsoluteAcceleration, AbsolutePosition,
                                              AbsoluteVelocity, CutForce, RelativeAcceleration,
                                              RelativePosition, RelativeVelocity)


class SpringDemo(Component):
    """A body on a vertical prismatic joint at A = (1, 0), held by a
    world-axis Spring (c_y = 10 N/m, s_rely0 = -0.5 m; c_x = 1 N/m idle)
    and a line Damper (d = 1 N s/m) in parallel, all from A to the body:
    ``0.5 s'' = -10 (s + 0.5) - s' - 0.5*9.81``, equilibrium s = -0.9905 m.
    The body passes through A (zero spring and damper length) at 0.137 s."""
    experiment = {"stop_time": 5.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["prismatic.s", "prismatic.v"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.fixedTranslation = FixedTranslation(r=(1.0, 0.0))
        self.prismatic = Prismatic(r=(0.0, 1.0), state_select="default",
                                   s=start(0.2, fixed=True), v=start(0.0, fixed=True),
                                   guide=(-1.6, 0.3))
        self.spring1 = Spring(c_x=1.0, c_y=10.0, s_relx0=0.0, s_rely0=-0.5, c_phi=1e5,
                              phi_rel0=0.0)
        self.damper = Damper(d=1.0)
        self.body = Body(m=0.5, I=0.1)
        self.connect(self.fixed.frame, self.fixedTranslation.frame_a)
        for element in (self.prismatic, self.spring1, self.damper):
            self.connect(self.fixedTranslation.frame_b, element.frame_a)
            self.connect(element.frame_b, self.body.frame_a)


class SpringDamperDemo(Component):
    """A free body (no joint) on a world-axis SpringDamper (c = 5 N/m,
    d = 1 N s/m per axis, no rotational part) from A = (-1, 0), released
    at rest at (1, 1): two separate damped oscillators with the
    equilibrium (-1, -0.981)."""
    experiment = {"stop_time": 5.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["body.x", "body.y", "body.vx", "body.vy"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.fixedTranslation = FixedTranslation(r=(-1.0, 0.0))
        self.springDamper = SpringDamper(c_x=5.0, c_y=5.0, d_x=1.0, d_y=1.0, c_phi=0.0,
                                         d_phi=0.0, s_relx0=0.0, s_rely0=0.0, phi_rel0=0.0)
        zero = start(0.0, fixed=True)
        self.body = Body(m=0.5, I=0.1, x=start(1.0, fixed=True), y=start(1.0, fixed=True),
                         vx=zero, vy=start(0.0, fixed=True), phi=start(0.0, fixed=True),
                         w=start(0.0, fixed=True))
        self.connect(self.fixed.frame, self.fixedTranslation.frame_a)
        self.connect(self.fixedTranslation.frame_b, self.springDamper.frame_a)
        self.connect(self.springDamper.frame_b, self.body.frame_a)


class PendulumExcited(Component):
    """The Pendulum with a WorldForce on its body, resolved in the body's
    frame: from t = 1.8 s it pushes with -5 sin(2 pi (t - 1.8)) N along the
    body's y axis (perpendicular to the rod).  A CutForce sensor between
    rod and body measures the rod force in the rod's axes."""
    experiment = {"stop_time": 3.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["revolute.phi", "revolute.w"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(state_select="always", phi=start(0.0, fixed=True),
                                 w=start(0.0, fixed=True))
        self.fixedTranslation = FixedTranslation(r=(1.0, 0.0))
        self.cutForce = CutForce(resolve_in_frame="frame_a")
        self.body = Body(m=1.0, I=0.1)
        self.worldForce = WorldForce(resolve_in_frame="frame_b")
        self.sine1 = signals.Sine(amplitude=0.0, f=1.0, start_time=1.8)
        self.sine2 = signals.Sine(amplitude=-5.0, f=1.0, start_time=1.8)
        self.const = signals.Constant(k=0.0)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.fixedTranslation.frame_a)
        self.connect(self.fixedTranslation.frame_b, self.cutForce.frame_a)
        self.connect(self.cutForce.frame_b, self.body.frame_a)
        self.connect(self.worldForce.frame_b, self.body.frame_a)
        self.connect(self.sine1.y, self.worldForce.force_x)
        self.connect(self.sine2.y, self.worldForce.force_y)
        self.connect(self.const.y, self.worldForce.torque)


class InvertedCraneCrab(Component):
    """An inverse model: the pendulum angle on the crane crab is prescribed
    (a ramp from -0.5 rad to 0 over 0.5 s, filtered by a first-order lag
    T = 0.1 s with a steady-state start) and the cart force F is solved
    for through InverseBlockConstraints.  The pendulum rod points up at
    phi = 0; the cart's prismatic joint and the pendulum's revolute joint
    use their 1D flanges (force source and angle sensor)."""
    experiment = {"stop_time": 3.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["body.phi", "prismatic.s", "prismatic.v", "force.f_in.u"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.prismatic = Prismatic(r=(1.0, 0.0), use_flange=True, state_select="default",
                                   s=start(0.0, fixed=True), v=start(0.0, fixed=True),
                                   guide=(-1.0, 7.0))
        self.body1 = Body(m=1.0, I=0.1)
        self.revolute = Revolute(use_flange=True, state_select="default")
        self.fixedTranslation = FixedTranslation(r=(0.0, 1.0))
        self.body = Body(m=0.5, I=0.1)
        self.force = translational.Force()
        self.angleSensor = rotational.AngleSensor()
        self.ramp = signals.Ramp(offset=-0.5, height=0.5, duration=0.5, start_time=0.0)
        self.firstOrder = signals.FirstOrder(k=1.0, T=0.1, init="steady_state")
        self.inverseBlockConstraints = signals.InverseBlockConstraints()
        self.connect(self.fixed.frame, self.prismatic.frame_a)
        self.connect(self.prismatic.frame_b, self.body1.frame_a)
        self.connect(self.prismatic.frame_b, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.fixedTranslation.frame_a)
        self.connect(self.fixedTranslation.frame_b, self.body.frame_a)
        self.connect(self.force.flange, self.prismatic.flange_a)
        self.connect(self.revolute.flange_a, self.angleSensor.flange)
        self.connect(self.ramp.y, self.firstOrder.u)
        self.connect(self.angleSensor.phi, self.inverseBlockConstraints.u1)
        self.connect(self.firstOrder.y, self.inverseBlockConstraints.u2)
        self.connect(self.inverseBlockConstraints.y1, self.force.f_in)


class MeasureDemo(Component):
    """A double pendulum (arms 1 m and 0.4 m, both released horizontally
    at rest) with six sensors on the outer body's frame: absolute position
    (world), velocity (frame_a) and acceleration (world); relative
    position (world), velocity (frame_b) and acceleration (frame_b) from
    the elbow P.  The sensors exert no force: the motion is that of the
    plain double pendulum."""
    experiment = {"stop_time": 10.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["body1.phi", "body1.w", "revolute2.phi", "revolute2.w"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute1 = Revolute(state_select="default", phi=start(0.0, fixed=True),
                                  w=start(0.0, fixed=True))
        self.fixedTranslation = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.revolute2 = Revolute(state_select="default", phi=start(0.0, fixed=True),
                                  w=start(0.0, fixed=True))
        self.fixedTranslation1 = FixedTranslation(r=(0.4, 0.0))
        self.body1 = Body(m=0.4, I=0.02)
        self.absolutePosition = AbsolutePosition(resolve_in_frame="world")
        self.absoluteVelocity = AbsoluteVelocity(resolve_in_frame="frame_a")
        self.absoluteAcceleration = AbsoluteAcceleration(resolve_in_frame="world")
        self.relativePosition = RelativePosition(resolve_in_frame="world")
        self.relativeVelocity = RelativeVelocity(resolve_in_frame="frame_b")
        self.relativeAcceleration = RelativeAcceleration(resolve_in_frame="frame_b")
        self.connect(self.fixed.frame, self.revolute1.frame_a)
        self.connect(self.revolute1.frame_b, self.fixedTranslation.frame_a)
        self.connect(self.fixedTranslation.frame_b, self.body.frame_a)
        self.connect(self.fixedTranslation.frame_b, self.revolute2.frame_a)
        self.connect(self.revolute2.frame_b, self.fixedTranslation1.frame_a)
        self.connect(self.fixedTranslation1.frame_b, self.body1.frame_a)
        for sensor in (self.absolutePosition, self.absoluteVelocity, self.absoluteAcceleration):
            self.connect(sensor.frame_a, self.body1.frame_a)
        for sensor in (self.relativePosition, self.relativeVelocity, self.relativeAcceleration):
            self.connect(self.fixedTranslation.frame_b, sensor.frame_a)
            self.connect(sensor.frame_b, self.body1.frame_a)


if __name__ == "__main__":
    from acausal2d import simulate
    for cls in (SpringDemo, SpringDamperDemo, PendulumExcited, InvertedCraneCrab, MeasureDemo):
        res = simulate(cls())
        print("%s: %s" % (cls.__name__, ", ".join(
            "%s(end) = %.9g" % (n, res.final(n)) for n in cls.outputs)))
