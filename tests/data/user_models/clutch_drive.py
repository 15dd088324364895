"""A clutch drive written from the drive-train guide: an asynchronous motor
drives, through an IdealGear(2) and a disc clutch closed by a ramp, a load
inertia.  ``ClutchDriveLoose`` forgets ``connect(gear.flange_b,
clutch.flange_a)``, with the clutch's stick zone (law='zone', w_s = 0.01
rad/s); ``ClutchDriveLooseModes`` forgets it with Modelica's modes."""
from acausal2d import Component, start
from acausal2d.library import rotational, signals


class ClutchDrive(Component):
    """Motor -- gear -- clutch -- load."""
    experiment = {"stop_time": 1.0, "intervals": 200}
    outputs = ["motor.w", "load.w"]
    wire_gear_to_clutch = True
    clutch_law: dict = {}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.motor = rotational.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2)
        self.gear = rotational.IdealGear(ratio=2.0)
        self.clutch = rotational.Clutch(mu=0.3, fn_max=1500.0, cgeo=0.11, **self.clutch_law)
        self.close = signals.Ramp(height=1.0, duration=0.05, startTime=0.3)
        self.load = rotational.Inertia(J=0.05, phi=start(0.0, fixed=True),
                                       w=start(0.0, fixed=True))
        self.connect(self.motor.flange, self.gear.flange_a)
        if self.wire_gear_to_clutch:
            self.connect(self.gear.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.load.flange_a)
        self.connect(self.close.y, self.clutch.f_normalized)


class ClutchDriveLoose(ClutchDrive):
    """The clutch drive without connect(gear.flange_b, clutch.flange_a),
    the clutch with its stick zone."""
    wire_gear_to_clutch = False
    clutch_law = {"law": "zone", "w_s": 0.01}


class ClutchDriveLooseModes(ClutchDrive):
    """The clutch drive without connect(gear.flange_b, clutch.flange_a),
    the clutch with Modelica's modes."""
    wire_gear_to_clutch = False
