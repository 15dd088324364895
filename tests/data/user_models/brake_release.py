"""A flywheel driven by a constant torque of 5 N m, held by a brake whose
normal force is released by a ramp from 1 to 0 over [0.5, 0.51] s: the brake
(capacity mu cgeo fn_max f = 10 f N m) breaks away at f = 0.5, t = 0.505 s."""
from acausal2d import Component, start
from acausal2d.library import rotational, signals


class BrakeDemo(Component):
    """A flywheel driven by a constant torque against a brake released at 0.5 s."""
    experiment = {"stop_time": 1.0, "intervals": 100}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.torque = rotational.ConstantTorque(tau_constant=5.0)
        self.wheel = rotational.Inertia(J=0.1, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rotational.Brake(mu_pos=[[0.0, 0.5]], cgeo=0.1, fn_max=200.0)
        self.press = signals.Ramp(height=-1.0, duration=0.01, offset=1.0, startTime=0.5)
        self.connect(self.torque.flange, self.wheel.flange_a)
        self.connect(self.wheel.flange_b, self.brake.flange_a)
        self.connect(self.press.y, self.brake.f_normalized)
