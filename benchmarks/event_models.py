"""The models whose events could storm, shared by benchmarks/bench_events.py
(their wall times) and tests/test_friction_modes.py (their answers): the
drive train of one Ramp closing a clutch and opening a brake, the bouncing
ball (Zeno) and the two-point switch of a tiny hysteresis (an event storm)."""
import casadi as ca

from acausal2d import Component, Parameter, Variable, der, start
from acausal2d.language.symbols import define_latch, latch
from acausal2d.library import blocks, signals
from acausal2d.library import rotational as rot


class RampedDrive(Component):
    """Modelica-like drive train: a constant torque T on J1 -- clutch -- J2
    -- brake to the ground.  One Ramp (0 -> 1 from t0 over D) closes the
    clutch and, through Feedback (1 - ramp), opens the brake; ``shared=False``
    feeds Feedback from a second, identical Ramp instead."""

    def __init__(self, shared=True, D=0.5, law="modes", **kw):
        super().__init__(**kw)
        zone = {} if law == "modes" else {"law": law, "w_s": 1e-3}
        self.src = rot.ConstantTorque(tau_constant=DRIVE["T"])
        self.J1 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = rot.Clutch(fn_max=DRIVE["fn_max"], peak=DRIVE["peak"], **zone)
        self.J2 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rot.Brake(fn_max=DRIVE["fn_max"], peak=DRIVE["peak"], **zone)
        self.ramp = signals.Ramp(duration=D, startTime=DRIVE["t0"])
        self.one = signals.Constant(k=1.0)
        self.feedback = blocks.Feedback()
        self.connect(self.src.flange, self.J1.flange_a)
        self.connect(self.J1.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.J2.flange_a)
        self.connect(self.J2.flange_b, self.brake.flange_a)
        self.connect(self.ramp.y, self.clutch.f_normalized)
        self.connect(self.one.y, self.feedback.u1)
        if shared:
            self.connect(self.ramp.y, self.feedback.u2)
        else:
            self.ramp2 = signals.Ramp(duration=D, startTime=DRIVE["t0"])
            self.connect(self.ramp2.y, self.feedback.u2)
        self.connect(self.feedback.y, self.brake.f_normalized)


DRIVE = {"T": 10.0, "fn_max": 30.0, "peak": 1.1, "t0": 0.2}


class Ball(Component):
    """A ball bouncing on the ground with restitution e (Zeno: the bounces
    accumulate at t* = t1 (1 + e) / (1 - e)); a latch and a reinit."""
    e = Parameter(0.5, "1", "restitution")
    h = Variable(unit="m", state_select="always")
    v = Variable(unit="m/s", state_select="always")
    contact = Variable(unit="1")
    v_after = Variable(unit="m/s")

    def equations(self):
        c = latch("ball.contact")
        define_latch(c, ca.if_else(c, -self.v, -self.h), "ground contact", g_start=-self.h)
        return [self.v == der(self.h), der(self.v) == -9.81, self.contact == c,
                self.v_after == -self.e * self.v]

    def reinits(self):
        """The bounce: v := -e v."""
        return [("contact", "v", "v_after")]


class Bouncing(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.ball = Ball(h=start(1.0, fixed=True), v=start(0.0, fixed=True))


class Relay(Component):
    """A two-point switch with the hysteresis +-band: x' = 1 while on, -1
    while off; it switches off at x = band, on at x = -band."""
    band = Parameter(1e-7, "1", "half width of the hysteresis")
    x = Variable(unit="1", state_select="always")
    on = Variable(unit="1")

    def equations(self):
        h = latch("relay.on")
        define_latch(h, ca.if_else(h, self.band - self.x, -self.band - self.x), "heater on",
                     g_start=-self.x)
        return [der(self.x) == 2 * h - 1, self.on == h]


class Switching(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.relay = Relay(x=start(0.0, fixed=True))
