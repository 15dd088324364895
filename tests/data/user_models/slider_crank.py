"""A geared slider-crank written from the docs: AsyncMotor -> IdealGear(3)
-> Revolute(use_flange=True) crank; rod; piston on a Prismatic with a
translational damper.  ``SliderCrankLoose`` forgets ``connect(gear.flange_b,
crankJoint.flange_a)``."""
from acausal2d import Component
from acausal2d.library import planar, rotational, translational


class SliderCrank(Component):
    """Geared slider-crank with a damped piston."""
    experiment = {"stop_time": 0.5, "intervals": 100}
    outputs = ["crankJoint.phi", "piston.s"]
    wire_gear_to_crank = True

    def __init__(self, **kw):
        super().__init__(**kw)
        self.motor = rotational.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2)
        self.gear = rotational.IdealGear(ratio=3.0)
        self.ground = planar.Fixed()
        self.crankJoint = planar.Revolute(use_flange=True)
        self.crank = planar.BodyShape(r=(0.1, 0.0), m=1.0, I=0.002)
        self.pin = planar.Revolute()
        self.rod = planar.BodyShape(r=(0.3, 0.0), m=0.5, I=0.004)
        self.wrist = planar.Revolute()
        self.slide = planar.Fixed(r=(0.4, 0.0))
        self.piston = planar.Prismatic(r=(-1.0, 0.0), use_flange=True)
        self.damper = translational.Damper(d=20.0)
        self.connect(self.motor.flange, self.gear.flange_a)
        if self.wire_gear_to_crank:
            self.connect(self.gear.flange_b, self.crankJoint.flange_a)
        self.connect(self.ground.frame, self.crankJoint.frame_a)
        self.connect(self.crankJoint.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.pin.frame_a)
        self.connect(self.pin.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.wrist.frame_a)
        self.connect(self.slide.frame, self.piston.frame_a)
        self.connect(self.piston.frame_b, self.wrist.frame_b)
        self.connect(self.piston.flange_a, self.damper.flange_b)
        self.connect(self.piston.support, self.damper.flange_a)


class SliderCrankLoose(SliderCrank):
    """The slider-crank without connect(gear.flange_b, crankJoint.flange_a)."""
    wire_gear_to_crank = False
