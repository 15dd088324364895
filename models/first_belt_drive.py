"""First models: an open belt drive with two pulleys and two spans.

A driving pulley (radius 50 mm) turns a driven pulley (radius 100 mm) 0.4 m
away through a closed elastic belt with a pretension of 200 N.  The driving
pulley's speed runs up smoothly to 20 rad/s; a viscous load of 0.05 N m s on
the driven pulley takes the power.  By hand: the slip-free speed ratio
r1/r2 = 0.5, the driven speed 10 rad/s, the load torque 0.5 N m and the span
forces 200 +- 2.5 N (tight and slack span).  The page "A belt drive" of the
documentation builds this file step by step.
"""
import math

import casadi as ca

from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.belt import Belt, Pulley, connect_band

# -- step 1: the numbers
R1 = 0.05          # driving pulley radius, m
R2 = 0.10          # driven pulley radius, m
DISTANCE = 0.40    # centre distance, m (driven pulley at (0.4, 0))
C_BELT = 2.0e5     # belt stiffness per unit strain, N (spring rate of a span: C_BELT / length)
D_BELT = 50.0      # belt damping per unit strain, N s
F0 = 200.0         # pretension of both spans at t = 0, N
W1 = 20.0          # final speed of the driving pulley, rad/s
T_RUN_UP = 0.5     # run-up time, s
D_LOAD = 0.05      # viscous load on the driven pulley, N m s/rad
J2 = 2e-3          # inertia of the driven pulley, kg m^2
# -- end step 1


def speed_profile(t):
    """Speed of the driving pulley: a smooth run-up 0 -> W1 over T_RUN_UP, then constant."""
    ramp = 0.5 * W1 * (1 - ca.cos(math.pi * t / T_RUN_UP))
    return ca.if_else(t < T_RUN_UP, ramp, W1)


class BeltDrive(Component):
    """Open belt drive: two pulleys, two elastic spans with 200 N pretension,
    a speed-driven pulley and a viscous load on the other."""
    experiment = {"stop_time": 2.0, "intervals": 400, "rtol": 1e-8}
    outputs = ["driver.w_rel", "driven.w_rel", "tight.F", "slack.F"]
    figures = [{"name": "first_belt_drive", "title": "belt drive: speeds and span forces",
                "signals": [["driver.w_rel", "driven.w_rel"], ["tight.F", "slack.F"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: two pulleys, their axes fixed in the ground (ctr2D1 left unconnected)
        self.driver = Pulley(r=R1, x10=0.0, y10=0.0, w_i=-1, J=1e-3)
        self.driven = Pulley(r=R2, x10=DISTANCE, y10=0.0, w_i=-1, J=J2)
        # -- step 3: two spans, each from the contact K2 of one pulley to the contact K1 of the next
        eps0 = F0 / C_BELT                           # pretension as a start strain
        self.slack = Belt(c=C_BELT, d=D_BELT, eps=start(eps0, fixed=True))
        self.tight = Belt(c=C_BELT, d=D_BELT, eps=start(eps0, fixed=True))
        connect_band(self, self.slack, 1, self.driver, 2)     # lower span: driver -> driven
        connect_band(self, self.slack, 2, self.driven, 1)
        connect_band(self, self.tight, 1, self.driven, 2)     # upper span: driven -> driver
        connect_band(self, self.tight, 2, self.driver, 1)
        # -- step 4: drive and load on the pulleys' flanges ctrR2
        self.profile = signals.TimeFunction(speed_profile)
        self.motor = rotational.Speed(phi=start(0.0, fixed=True))
        self.connect(self.profile.y, self.motor.w_in)
        self.connect(self.motor.flange, self.driver.ctrR2)
        self.load = rotational.Damper(d=D_LOAD)
        self.ground = rotational.Fixed()
        self.connect(self.driven.ctrR2, self.load.flange_a)
        self.connect(self.load.flange_b, self.ground.flange)
        # -- end step 4


def hand_check():
    """The steady state by hand: {quantity: value}."""
    w2 = W1 * R1 / R2                  # slip-free ratio: equal belt speed on both pulleys
    torque = D_LOAD * w2               # load torque on the driven pulley
    dF = torque / R2                   # tight minus slack span force
    return {"driven.w_rel": w2, "tight.F": F0 + dF / 2, "slack.F": F0 - dF / 2,
            "driver torque": dF * R1}


def measure(res):
    """The same quantities at the end of a run of :class:`BeltDrive`."""
    return {"driven.w_rel": res.final("driven.w_rel"), "tight.F": res.final("tight.F"),
            "slack.F": res.final("slack.F"),
            "driver torque": res.final("driver.ctrR2.tau")}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(BeltDrive()))
    for name, value in hand_check().items():
        print("%-14s simulated %12.6g   by hand %12.6g" % (name, simulated[name], value))
