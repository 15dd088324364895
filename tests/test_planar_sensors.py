"""Every planar sensor against a hand computation on a known motion, and
the force sources against closed forms.

The known motion: two revolute joints driven through their 1D flanges by
prescribed angles a1(t) = 0.4 + 0.7 t + 0.2 sin(3 t) and a2(t) = -0.3 +
1.1 t + 0.1 t^2; a rod c1 = (0.8, 0.3) from the first joint to the elbow P
(frame angle a1), a rod c2 = (0.5, -0.2) from the second joint to Q (frame
angle b = a1 + a2), and a body (m, I) at Q behind CutForce, CutTorque and
Power.  In complex notation (x + i y) every quantity is closed form:
r_Q = e^{i a1} c1 + e^{i b} c2, v_Q = i a1' e^{i a1} c1 + i b' e^{i b} c2, ...
"""
import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import rotational, signals
from acausal2d.library.planar import Body, Fixed, FixedRotation, FixedTranslation, Revolute
from acausal2d.library.planar.forces import RelativeForce, WorldForce, WorldTorque
from acausal2d.library.planar.sensors import (AbsoluteAcceleration, AbsolutePosition,
                                              AbsoluteVelocity, CutForce, CutTorque, Distance,
                                              Power, RelativeAcceleration, RelativePosition,
                                              RelativeVelocity)

G = 9.81
C1, C2 = 0.8 + 0.3j, 0.5 - 0.2j
MASS, INERTIA, ALPHA = 2.0, 0.3, 0.5
ABSOLUTE = ("world", "frame_a", "frame_resolve")
RELATIVE = ("world", "frame_a", "frame_b", "frame_resolve")


class KnownMotion(Component):
    """The driven two-joint arm of the module docstring with all sensors;
    frame_resolve of every sensor that has one is the elbow frame turned by
    ALPHA (a FixedRotation), so it moves and differs from frame_a and
    frame_b."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.joint1 = Revolute(use_flange=True)
        self.rod1 = FixedTranslation(r=(C1.real, C1.imag))
        self.joint2 = Revolute(use_flange=True)
        self.rod2 = FixedTranslation(r=(C2.real, C2.imag))
        self.cutForce = CutForce()
        self.cutTorque = CutTorque()
        self.power = Power()
        self.body = Body(m=MASS, I=INERTIA)
        self.turned = FixedRotation(alpha=ALPHA)
        self.distance = Distance()
        self._drive(self.joint1, "drive1", lambda t: 0.4 + 0.7 * t + 0.2 * ca.sin(3 * t))
        self._drive(self.joint2, "drive2", lambda t: -0.3 + 1.1 * t + 0.1 * t ** 2)
        chain = [self.fixed.frame, self.joint1, self.rod1, self.joint2, self.rod2,
                 self.cutForce, self.cutTorque, self.power]
        self.connect(chain[0], chain[1].frame_a)
        for a, b in zip(chain[1:], chain[2:]):
            self.connect(a.frame_b, b.frame_a)
        self.connect(self.power.frame_b, self.body.frame_a)
        self.connect(self.rod1.frame_b, self.turned.frame_a)
        self.connect(self.fixed.frame, self.distance.frame_a)
        self.connect(self.distance.frame_b, self.body.frame_a)
        self._sensors()

    def _drive(self, joint, name, func):
        source = signals.TimeFunction(func=func)
        position = rotational.Position()
        setattr(self, name + "_signal", source)
        setattr(self, name, position)
        self.connect(source.y, position.phi_in)
        self.connect(position.flange, joint.flange_a)

    def _sensors(self):
        for cls in (AbsolutePosition, AbsoluteVelocity, AbsoluteAcceleration):
            for frame in ABSOLUTE:
                sensor = cls(resolve_in_frame=frame)
                setattr(self, "%s_%s" % (cls.__name__, frame), sensor)
                self.connect(sensor.frame_a, self.body.frame_a)
                if frame == "frame_resolve":
                    self.connect(sensor.frame_resolve, self.turned.frame_b)
        for cls in (RelativePosition, RelativeVelocity, RelativeAcceleration):
            for frame in RELATIVE:
                sensor = cls(resolve_in_frame=frame)
                setattr(self, "%s_%s" % (cls.__name__, frame), sensor)
                self.connect(self.rod1.frame_b, sensor.frame_a)
                self.connect(sensor.frame_b, self.body.frame_a)
                if frame == "frame_resolve":
                    self.connect(sensor.frame_resolve, self.turned.frame_b)



def _angles(t):
    """a1, a2 and their first and second derivatives (hand)."""
    a1 = (0.4 + 0.7 * t + 0.2 * np.sin(3 * t), 0.7 + 0.6 * np.cos(3 * t), -1.8 * np.sin(3 * t))
    a2 = (-0.3 + 1.1 * t + 0.1 * t ** 2, 1.1 + 0.2 * t, 0.2 + 0.0 * t)
    return a1, a2


def _hand(t):
    """Expected outputs {result name: values} of all sensors."""
    (a1, da1, dda1), (a2, da2, dda2) = _angles(t)
    b, db, ddb = a1 + a2, da1 + da2, dda1 + dda2
    e1, eb = np.exp(1j * a1), np.exp(1j * b)
    r = e1 * C1 + eb * C2
    v = 1j * da1 * e1 * C1 + 1j * db * eb * C2
    a = (1j * dda1 - da1 ** 2) * e1 * C1 + (1j * ddb - db ** 2) * eb * C2
    psi_abs = {"world": 0 * t, "frame_a": b, "frame_resolve": a1 + ALPHA}
    psi_rel = {"world": (0 * t, 0 * t), "frame_a": (a1, da1), "frame_b": (b, db),
               "frame_resolve": (a1 + ALPHA, da1)}
    out = {}

    def put(name, z, third):
        out[name + "_x.u"], out[name + "_y.u"] = z.real, z.imag
        out[name.rsplit(".", 1)[0] + "." + third[0] + ".u"] = third[1]

    for f, psi in psi_abs.items():
        turn = np.exp(-1j * psi)
        put("AbsolutePosition_%s.r" % f, r * turn, ("phi", b - psi))
        put("AbsoluteVelocity_%s.v" % f, v * turn, ("w", db))
        put("AbsoluteAcceleration_%s.a" % f, a * turn, ("z", ddb))
    for f, (psi, dpsi) in psi_rel.items():
        rot = np.exp(1j * (b - psi))
        put("RelativePosition_%s.r_rel" % f, rot * C2, ("phi_rel", a2))
        put("RelativeVelocity_%s.v_rel" % f, 1j * da2 * rot * C2, ("w_rel", da2))
        put("RelativeAcceleration_%s.a_rel" % f, (1j * dda2 - da2 * (db - dpsi)) * rot * C2,
            ("z_rel", dda2))
    force = MASS * a - MASS * (-G * 1j)             # from the rod on the body, world
    put("cutForce.f", force * np.exp(-1j * b), ("f_x", (force * np.exp(-1j * b)).real))
    out["cutTorque.torque.u"] = INERTIA * ddb
    out["power.power.u"] = (np.conj(force) * v).real + INERTIA * ddb * db
    out["distance.distance.u"] = np.abs(r)
    return out


@pytest.fixture(scope="module")
def known_motion():
    return acausal2d.simulate(KnownMotion(), stop_time=2.0, rtol=1e-10,
                              output_times=np.linspace(0.0, 2.0, 81))


def test_every_sensor_matches_the_hand_computation(known_motion):
    """All 21 kinematic sensor outputs (three absolute sensors in three
    resolve frames, three relative ones in four), the cut force, cut
    torque, power and distance equal their closed forms to 1e-8.  The cut
    force being m a - m g shows that the 24 kinematic sensors on the body
    frame put no force on it."""
    res = known_motion
    expected = _hand(res.time)
    assert len(expected) == 3 * 3 * 3 + 3 * 4 * 3 + 2 + 3
    for name, value in expected.items():
        dev = np.max(np.abs(res[name] - value))
        assert dev < 1e-8, "%s: deviation %.3g" % (name, dev)


def test_sensor_options_are_checked():
    with pytest.raises(ModelDefinitionError, match="resolve_in_frame must be one of"):
        AbsolutePosition(resolve_in_frame="frame_b")
    with pytest.raises(ModelDefinitionError, match="resolve_in_frame must be one of"):
        RelativeForce(resolve_in_frame="body")

    class Unresolved(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed()
            self.sensor = AbsolutePosition(resolve_in_frame="frame_resolve")
            self.connect(self.fixed.frame, self.sensor.frame_a)

    with pytest.raises(ModelDefinitionError, match="frame_resolve must be connected"):
        acausal2d.compile_model(Unresolved())


# --------------------------------------------------------------------------
# sources

class FreeBodies(Component):
    """Two free bodies: A (m 2, I 0.4) with a WorldForce and a WorldTorque,
    B (m 0.5, I 0.1) pulled from A by a RelativeForce resolved in
    ``resolve``; A starts turned by 0.6 rad."""

    def __init__(self, world_resolve="world", resolve="frame_a", **kw):
        super().__init__(**kw)
        fixed = dict(fixed=True)
        self.a = Body(m=2.0, I=0.4, x=start(0.0, **fixed), y=start(0.0, **fixed),
                      phi=start(0.6, **fixed), vx=start(0.0, **fixed), vy=start(0.0, **fixed),
                      w=start(0.0, **fixed))
        self.b = Body(m=0.5, I=0.1, x=start(1.0, **fixed), y=start(0.0, **fixed),
                      phi=start(0.0, **fixed), vx=start(0.0, **fixed), vy=start(0.0, **fixed),
                      w=start(0.0, **fixed))
        self.force = WorldForce(resolve_in_frame=world_resolve)
        self.torque = WorldTorque()
        self.pull = RelativeForce(resolve_in_frame=resolve)
        k = {"fx": 3.0, "fy": 4.0, "t": 0.0, "tt": 0.8, "rx": 1.5, "ry": -0.5, "rt": 0.0}
        for name, value in k.items():
            setattr(self, "c_" + name, signals.Constant(k=value))
        self.connect(self.c_fx.y, self.force.force_x)
        self.connect(self.c_fy.y, self.force.force_y)
        self.connect(self.c_t.y, self.force.torque)
        self.connect(self.c_tt.y, self.torque.torque)
        self.connect(self.c_rx.y, self.pull.force_x)
        self.connect(self.c_ry.y, self.pull.force_y)
        self.connect(self.c_rt.y, self.pull.torque)
        self.connect(self.force.frame_b, self.a.frame_a)
        self.connect(self.torque.frame_b, self.a.frame_a)
        self.connect(self.pull.frame_a, self.a.frame_a)
        self.connect(self.pull.frame_b, self.b.frame_a)


def test_world_force_torque_and_relative_force_closed_form():
    """A turns at the constant rate 0.8/0.4 rad/s^2 (WorldTorque); the
    RelativeForce, resolved in A's turning frame, pulls B with R(phi_A)
    (1.5, -0.5) and A with the opposite; the world force (3, 4) N acts on A.
    Accelerations checked against the closed forms to 1e-9."""
    res = acausal2d.simulate(FreeBodies(), stop_time=1.0, rtol=1e-10,
                             output_times=np.linspace(0.0, 1.0, 41))
    t = res.time
    phi_a = 0.6 + 0.5 * 2.0 * t ** 2
    assert np.max(np.abs(res["a.phi"] - phi_a)) < 1e-9
    pull = np.exp(1j * phi_a) * (1.5 - 0.5j)
    acc_b = pull / 0.5 - G * 1j
    acc_a = ((3 + 4j) - pull) / 2.0 - G * 1j
    for body, acc in (("a", acc_a), ("b", acc_b)):
        assert np.max(np.abs(res["der(der(%s.x))" % body] - acc.real)) < 1e-9
        assert np.max(np.abs(res["der(der(%s.y))" % body] - acc.imag)) < 1e-9
    assert np.max(np.abs(res["b.phi"])) <= 1e-10       # atol: rtol 1e-10 x nominal 1 rad
    assert np.max(np.abs(res["pull.fx"] - pull.real)) < 1e-9


def test_world_force_resolved_in_the_body_frame_turns_with_it():
    """resolve_in_frame='frame_b': the signals (3, 4) are along A's own
    axes, so the world force is R(phi_A) (3, 4)."""
    res = acausal2d.simulate(FreeBodies(world_resolve="frame_b", resolve="world"),
                             stop_time=1.0, rtol=1e-10, output_times=np.linspace(0.0, 1.0, 41))
    phi_a = 0.6 + res.time ** 2
    world = np.exp(1j * phi_a) * (3 + 4j)
    assert np.max(np.abs(res["force.fx"] - world.real)) < 1e-9
    assert np.max(np.abs(res["force.fy"] - world.imag)) < 1e-9
    acc_b = (1.5 - 0.5j) / 0.5 - G * 1j
    assert np.max(np.abs(res["der(der(b.x))"] - acc_b.real)) < 1e-9
