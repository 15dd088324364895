"""Signal sources (RealOutput ``y``)."""
import casadi as ca

from acausal2d import Component, Parameter, RealOutput, time


class _Source(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.y = RealOutput()


class Constant(_Source):
    """y = k."""
    k = Parameter(0.0, "", "output value")

    def equations(self):
        return [self.y.u == self.k]


class Sine(_Source):
    """y = offset + amplitude sin(2 pi f (t - start_time) + phase) after start_time."""
    amplitude = Parameter(1.0, "", "amplitude")
    f = Parameter(1.0, "Hz", "frequency")
    phase = Parameter(0.0, "rad", "phase")
    offset = Parameter(0.0, "", "offset")

    def equations(self):
        return [self.y.u == self.offset + self.amplitude
                * ca.sin(2 * ca.pi * self.f * time + self.phase)]


class Ramp(_Source):
    """Linear ramp from offset by height over [start_time, start_time + duration]."""
    height = Parameter(1.0, "", "height of the ramp")
    duration = Parameter(1.0, "s", "duration")
    offset = Parameter(0.0, "", "value before the ramp")
    start_time = Parameter(0.0, "s", "start of the ramp")

    def equations(self):
        tau = (time - self.start_time) / self.duration
        ramp = ca.if_else(time < self.start_time, 0,
                          ca.if_else(time < self.start_time + self.duration, tau, 1))
        return [self.y.u == self.offset + self.height * ramp]


class TimeFunction(_Source):
    """y = func(time) for a Python function building a CasADi expression of
    the time symbol (e.g. ``lambda t: 1.5 * t``).  Changing the function
    needs a recompilation; its numbers can be parameters of other components."""

    def __init__(self, func, **kw):
        super().__init__(**kw)
        self.func = func

    def equations(self):
        return [self.y.u == self.func(time)]
