"""Clutch and motor: the drive of models/compressor.py without the belt.

An asynchronous motor (Kloss, T_k = 40 N m at s_k = 0.2, J = 0.01 kg m^2,
started at rest) drives, through a disc clutch (mu 0.3, fn_max 1500 N, cgeo
0.11 m: capacity 49.5 N m, creep speed w_s = 0.01 rad/s), a load inertia
(J = 0.05 kg m^2) that a load torque from the signal input ``load`` brakes.
The clutch closes with a ramp over [0.3, 0.35] s (the motor has run up idle
by then), slips until both sides turn at the same speed (the lock event),
and opens with a ramp over [1.0, 1.05] s: the transmitted torque exceeds the
falling capacity and the clutch slips again (the unlock event).

``load`` is a top-level ``RealInput`` (the FMU's input when exported with
``acausal2d export-fmu models/clutch_motor.py --model ClutchMotor``);
``ClutchMotorConstantLoad`` closes it with -10 N m for a run of its own
(``acausal2d simulate models/clutch_motor.py --model ClutchMotorConstantLoad``).
"""
from acausal2d import Component, RealInput, if_else, start
from acausal2d.library import rotational
from acausal2d.library.signals import Constant, TimeFunction


def clutch_signal(t):
    """f_normalized: 0 -> 1 over [0.3, 0.35] s, back to 0 over [1.0, 1.05] s."""
    closing = if_else(t < 0.3, 0.0, if_else(t < 0.35, (t - 0.3) / 0.05, 1.0))
    opening = if_else(t < 1.0, 1.0, if_else(t < 1.05, (1.05 - t) / 0.05, 0.0))
    return closing * opening


class ClutchMotor(Component):
    """Motor -- clutch -- load inertia with the load torque input ``load`` [N m]."""
    experiment = {"stop_time": 1.5, "intervals": 1500, "rtol": 1e-8}
    outputs = ["motor.w", "load_inertia.w", "clutch.tau", "clutch.w_rel"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.load = RealInput()
        self.motor = rotational.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2)
        self.clutch = rotational.Clutch(mu=0.3, fn_max=1500.0, cgeo=0.11, w_s=0.01, law="zone")
        self.engage = TimeFunction(clutch_signal)
        self.load_inertia = rotational.Inertia(J=0.05, phi=start(0.0, fixed=True),
                                               w=start(0.0, fixed=True))
        self.brake = rotational.Torque()
        self.connect(self.engage.y, self.clutch.f_normalized)
        self.connect(self.motor.flange, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.load_inertia.flange_a)
        self.connect(self.load_inertia.flange_b, self.brake.flange)
        self.connect(self.load, self.brake.tau_in)


class ClutchMotorConstantLoad(Component):
    """:class:`ClutchMotor` with the load torque held at -10 N m."""
    experiment = ClutchMotor.experiment
    outputs = ["drive.motor.w", "drive.load_inertia.w", "drive.clutch.tau"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.drive = ClutchMotor()
        self.torque = Constant(k=-10.0)
        self.connect(self.torque.y, self.drive.load)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__, "ClutchMotorConstantLoad"))
