"""Wall time of runs whose events could storm: each must end in seconds.

    python benchmarks/bench_events.py [repeats]     (default 5)
    python benchmarks/bench_events.py --small       (1 repeat, for the test suite)

- drive train, shared ramp: a constant torque on J1 -- Clutch -- J2 --
  Brake; one Ramp closes the clutch and, through Feedback (1 - ramp), opens
  the brake; 1 s at rtol 1e-8 (the brake's normal force 1 - ramp is solved
  as +-1e-32 where it is 0; Modelica Standard Library 4.0 semantics of
  PartialFriction).  Target: a few seconds (a run that once took minutes);
- Zeno ball: a ball bouncing with restitution 0.5, whose bounces
  accumulate at 1.3546 s; the run must stop there with an error.  Target:
  10 s;
- relay storm: a two-point switch with a hysteresis of 1e-7 (an event
  every 2e-7 s); the run must stop with an event-storm error.  Target: 10 s.
Each figure is compile + simulate, the median of ``repeats`` runs in this
process (the first run of a model pays for the compiler's imports).
"""
import statistics
import sys
import time

import casadi as ca

import acausal2d
from acausal2d import Component, Parameter, Variable, der, start
from acausal2d.language.symbols import define_latch, latch
from acausal2d.library import blocks, signals
from acausal2d.library import rotational as rot
from acausal2d.runtime.events import EventError


class RampedDrive(Component):
    """J1 (driven by 10 N m) -- clutch -- J2 -- brake; one Ramp for both."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.src = rot.ConstantTorque(tau_constant=10.0)
        self.J1 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = rot.Clutch(fn_max=30.0, peak=1.1)
        self.J2 = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.brake = rot.Brake(fn_max=30.0, peak=1.1)
        self.ramp = signals.Ramp(duration=0.5, startTime=0.2)
        self.one = signals.Constant(k=1.0)
        self.feedback = blocks.Feedback()
        for a, b in ((self.src.flange, self.J1.flange_a), (self.J1.flange_b, self.clutch.flange_a),
                     (self.clutch.flange_b, self.J2.flange_a),
                     (self.J2.flange_b, self.brake.flange_a),
                     (self.ramp.y, self.clutch.f_normalized), (self.one.y, self.feedback.u1),
                     (self.ramp.y, self.feedback.u2),
                     (self.feedback.y, self.brake.f_normalized)):
            self.connect(a, b)


class Ball(Component):
    """A ball bouncing with restitution e: a contact latch and a reinit."""
    e = Parameter(0.5, "1", "restitution")
    h = Variable(unit="m", state_select="always", start=1.0, fixed=True)
    v = Variable(unit="m/s", state_select="always", start=0.0, fixed=True)
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


class Relay(Component):
    """x' = 1 while on, -1 while off; off at x = band, on at x = -band."""
    band = Parameter(1e-7, "1", "half width of the hysteresis")
    x = Variable(unit="1", state_select="always", start=0.0, fixed=True)
    on = Variable(unit="1")

    def equations(self):
        h = latch("relay.on")
        define_latch(h, ca.if_else(h, self.band - self.x, -self.band - self.x), "heater on",
                     g_start=-self.x)
        return [der(self.x) == 2 * h - 1, self.on == h]


def _wrapped(cls, name):
    class Model(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            setattr(self, name, cls())
    return Model


CASES = (("drive train, shared ramp (1 s)", RampedDrive, 1.0, None, 5.0),
         ("Zeno ball (stops at 1.35 s)", _wrapped(Ball, "ball"), 3.0, "Zeno", 10.0),
         ("relay storm (stops at 1e-4 s)", _wrapped(Relay, "relay"), 1.0, "event storm", 10.0))


def one(make, stop, error):
    """(seconds, events or the error's time) of compile + simulate."""
    t = time.perf_counter()
    try:
        res = acausal2d.compile_model(make()).simulate(stop_time=stop, rtol=1e-8)
        outcome = "%d events" % len(res.events)
        assert error is None, "the run should have stopped with an error"
    except EventError as err:
        assert error is not None and error in str(err), str(err)
        outcome = "stopped at t=%.4g" % err.time
    return time.perf_counter() - t, outcome


def main(repeats=5):
    print("Runs whose events could storm: compile + simulate, median of %d" % repeats)
    print("%-32s %10s %10s  %s" % ("model", "median [s]", "target [s]", "outcome"))
    for label, make, stop, error, target in CASES:
        runs = [one(make, stop, error) for _ in range(repeats)]
        med = statistics.median(r[0] for r in runs)
        print("%-32s %10.2f %10.2f  %s%s" % (label, med, target, runs[-1][1],
                                            "" if med <= target else "  OVER TARGET"))


if __name__ == "__main__":
    if sys.argv[1:] == ["--small"]:
        main(1)
    else:
        main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
