"""First models: a slider-crank built from bodies and joints.

Modelica PlanarMechanics' way: joints (Revolute, Prismatic), rigid rods
(FixedTranslation) and bodies (Body) joined frame to frame.  A massless crank
(r = 0.1 m) is driven at a constant 10 rad/s; a massless connecting rod
(l = 0.3 m) pushes a 2 kg piston along a horizontal guide through the
crank's axis.  By hand: the piston position x = r cos(phi) +
sqrt(l^2 - r^2 sin(phi)^2), 0.2 .. 0.4 m, and the drive torque from the
power balance, T w = m a v.  The page "A planar mechanism from bodies and
joints" of the documentation builds this file step by step.
"""
import math

from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute

# -- step 1: the numbers
R = 0.1          # crank radius, m
L = 0.3          # connecting rod, m
M = 2.0          # piston mass, kg
W = 10.0         # crank speed, rad/s
# -- end step 1


class SliderCrank(Component):
    """Slider-crank of joints, rods and a piston body, driven at constant speed."""
    experiment = {"stop_time": 1.2566370614359172, "intervals": 600, "rtol": 1e-10}
    outputs = ["crankJoint.phi", "slider.s", "drive.flange.tau"]
    figures = [{"name": "first_planar_mechanism", "title": "slider-crank: piston and torque",
                "x": "crankJoint.phi", "signals": [["slider.s"], ["drive.flange.tau"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: the crank: a revolute joint in the ground with a 1D flange for the drive
        self.ground = Fixed()
        self.crankJoint = Revolute(use_flange=True, phi=start(0.0, fixed=True))
        self.crank = FixedTranslation(r=(R, 0.0))
        self.connect(self.ground.frame, self.crankJoint.frame_a)
        self.connect(self.crankJoint.frame_b, self.crank.frame_a)
        # -- step 3: the rod, joined to the crank pin and to the piston by revolute joints
        self.pin = Revolute()
        self.rod = FixedTranslation(r=(L, 0.0))
        self.wristPin = Revolute()
        self.connect(self.crank.frame_b, self.pin.frame_a)
        self.connect(self.pin.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.wristPin.frame_a)
        # -- step 4: the piston: a body on a prismatic joint along x through the crank's axis
        self.piston = Body(m=M, I=0.01)
        self.slider = Prismatic(r=(1.0, 0.0), s=start(R + L), guide=(0.15, 0.45))
        self.guideFrame = Fixed()
        self.connect(self.wristPin.frame_b, self.piston.frame_a)
        self.connect(self.guideFrame.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.piston.frame_a)
        # -- step 5: the drive: a speed source on the crank joint's flange
        self.speed = signals.Constant(k=W)
        self.drive = rotational.Speed(phi=start(0.0, fixed=True))
        self.connect(self.speed.y, self.drive.w_in)
        self.connect(self.drive.flange, self.crankJoint.flange_a)
        # -- end step 5


def piston(phi):
    """Piston position x, dx/dphi and d2x/dphi2 at the crank angle ``phi`` (closed form)."""
    s, c = math.sin(phi), math.cos(phi)
    root = math.sqrt(L * L - R * R * s * s)
    x = R * c + root
    dx = -R * s - R * R * s * c / root
    ddx = -R * c - R * R * (c * c - s * s) / root - R ** 4 * s * s * c * c / root ** 3
    return x, dx, ddx


def hand_check(phi=math.pi / 3):
    """By hand at the crank angle ``phi``: {quantity: value}.  The drive's
    power T w goes into the piston's kinetic energy: T w = m a v, with
    v = x' w and a = x'' w^2 at constant speed, so T = m x'' x' w^2."""
    x, dx, ddx = piston(phi)
    return {"piston x": x, "piston v": dx * W, "drive torque": M * ddx * dx * W * W,
            "stroke": 2 * R}


def measure(res, phi=math.pi / 3):
    """The same quantities from a result of :class:`SliderCrank`, at its
    output point nearest to the crank angle ``phi`` (with 600 intervals over
    two turns, pi/3 is the 50th)."""
    import numpy as np
    k = int(np.argmin(np.abs(res["crankJoint.phi"] - phi)))
    at = lambda name: float(res[name][k])  # noqa: E731
    return {"piston x": at("slider.s"), "piston v": at("slider.v"),
            "drive torque": -at("drive.flange.tau"),
            "stroke": float(res["slider.s"].max() - res["slider.s"].min())}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(SliderCrank()))
    for name, value in hand_check().items():
        print("%-12s simulated %12.6g   by hand %12.6g" % (name, simulated[name], value))
