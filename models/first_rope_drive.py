"""First models: a rope drive with a drum and a free pulley.

A drum (radius 100 mm) winds up a rope that runs down to a free pulley
(radius 50 mm) carrying a 20 kg load and back up to an anchor: a two-fall
hoist.  The load and its pulley are guided vertically.  The drum's speed
runs up smoothly to 2 rad/s.  By hand: each fall carries half the weight,
(20 + 1) kg * 9.81 m/s^2 / 2 = 103.0 N, the drum holds 10.30 N m, and the
load rises at half the rope speed, 0.1 m/s (times 1 + 1.03e-4,
the strain of the falls).  The page "A rope drive" of the
documentation builds this file step by step.
"""
import math

import casadi as ca

from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.belt import Belt, Drum, Pulley, connect_band
from acausal2d.library.planar import Body, Fixed, Prismatic

# -- step 1: the numbers
G = 9.81             # gravity, m/s^2 (the default world's, -y)
R_DRUM = 0.10        # drum radius, m
R_PULLEY = 0.05      # free pulley radius, m
M_LOAD = 20.0        # load, kg
M_PULLEY = 1.0       # free pulley, kg
Y0 = -1.0            # start height of the free pulley's axis, m (drum axis at y = 0)
C_ROPE = 1.0e6       # rope stiffness per unit strain, N
D_ROPE = 5.0e3       # rope damping per unit strain, N s
W_DRUM = 2.0         # final drum speed, rad/s
T_RUN_UP = 0.5       # run-up time, s
# -- end step 1


def drum_speed(t):
    """Drum speed: a smooth run-up 0 -> W_DRUM over T_RUN_UP, then constant."""
    return ca.if_else(t < T_RUN_UP, 0.5 * W_DRUM * (1 - ca.cos(math.pi * t / T_RUN_UP)), W_DRUM)


class RopeDrive(Component):
    """Two-fall hoist: a drum, a rope over a free pulley carrying a guided
    load, the rope's other end anchored."""
    experiment = {"stop_time": 2.0, "intervals": 400, "rtol": 1e-8}
    outputs = ["load.y", "fall1.F", "fall2.F", "drum.ctrR2.tau"]
    figures = [{"name": "first_rope_drive", "title": "rope drive: lift and fall forces",
                "signals": [["load.y"], ["fall1.F", "fall2.F"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: the drum, its axis fixed in the ground; the rope leaves it on its right side
        self.drum = Drum(r=R_DRUM, x10=-R_PULLEY - R_DRUM, y10=0.0, w_i=-1, J=0.05)
        # -- step 3: the load on a vertical guide, the free pulley's housing on the load
        self.guide = Fixed()
        self.slider = Prismatic(r=(0.0, 1.0), s=start(Y0, fixed=True), v=start(0.0, fixed=True))
        self.load = Body(m=M_LOAD, I=0.1, x=start(0.0), y=start(Y0))
        self.pulley = Pulley(r=R_PULLEY, w_i=-1, m=M_PULLEY, J=1e-3)
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.load.frame_a)
        self.connect(self.load.frame_a, self.pulley.ctr2D1)
        # -- step 4: two falls of rope, pretensioned to hold the load at rest
        eps0 = (M_LOAD + M_PULLEY) * G / 2 / C_ROPE
        self.fall1 = Belt(c=C_ROPE, d=D_ROPE, eps=start(eps0, fixed=True))
        self.fall2 = Belt(c=C_ROPE, d=D_ROPE, eps=start(eps0, fixed=True))
        connect_band(self, self.fall1, 1, self.drum, 1)       # drum -> free pulley (left fall)
        connect_band(self, self.fall1, 2, self.pulley, 1)
        connect_band(self, self.fall2, 1, self.pulley, 2)     # free pulley -> anchor (right fall)
        self.anchor = Fixed(r=(R_PULLEY, 0.0))
        self.connect(self.fall2.ctr2D2, self.anchor.frame)
        # -- step 5: the drum's drive
        self.profile = signals.TimeFunction(drum_speed)
        self.motor = rotational.Speed(phi=start(0.0, fixed=True))
        self.connect(self.profile.y, self.motor.w_in)
        self.connect(self.motor.flange, self.drum.ctrR2)
        # -- end step 5


def hand_check():
    """The steady lift by hand: {quantity: value}."""
    fall = (M_LOAD + M_PULLEY) * G / 2          # each fall carries half the weight
    eps = fall / C_ROPE                          # strain of the falls
    # the drum takes in W r of unstretched rope per second, which is W r (1 + eps) in
    # the stretched falls; two falls share it: the load rises at half that speed
    return {"fall1.F": fall, "fall2.F": fall, "drum torque": fall * R_DRUM,
            "lift speed": W_DRUM * R_DRUM * (1 + eps) / 2}


def measure(res):
    """The same quantities at the end of a run of :class:`RopeDrive`."""
    return {"fall1.F": res.final("fall1.F"), "fall2.F": res.final("fall2.F"),
            "drum torque": res.final("drum.ctrR2.tau"), "lift speed": res.final("load.vy")}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(RopeDrive()))
    for name, value in hand_check().items():
        print("%-12s simulated %12.6g   by hand %12.6g" % (name, simulated[name], value))
