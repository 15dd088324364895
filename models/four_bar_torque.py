"""Four-bar crank-rocker (the DDDD(a) of models/four_link_mechanisms.py:
crank 0.1 m, coupler 0.35 m, rocker 0.3 m, ground pivot B0 = (0.4, 0))
driven by a torque from the signal input ``tau`` at its crank, with a
rotational damper (0.02 N m s/rad) at the crank bearing; gravity acts.

``tau`` is a top-level ``RealInput``: exported as an FMU (``acausal2d
export-fmu models/four_bar_torque.py --model FourBarTorque``) it becomes
the FMU's input.  ``FourBarTorqueConstant`` closes it with a constant
0.2 N m for a run of its own (``acausal2d simulate
models/four_bar_torque.py --model FourBarTorqueConstant``).
"""
from acausal2d import Component, RealInput, start
from acausal2d.library import rotational
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.signals import Constant


class FourBarTorque(Component):
    """Four-bar whose crank is driven by the input torque ``tau`` [N m]."""
    experiment = {"stop_time": 2.0, "intervals": 400, "rtol": 1e-8}
    outputs = ["crank.phiL", "dyad.phiL2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.tau = RealInput()
        self.crank = DAN(lL=0.1, mL=0.5, JL=1e-3, phiL=start(0.0, fixed=True),
                         omL=start(0.0, fixed=True))
        self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)
        self.drive = rotational.Torque()
        self.damper = rotational.Damper(d=0.02)
        self.bearing = rotational.Fixed()
        self.connect(self.tau, self.drive.tau_in)
        self.connect(self.drive.flange, self.crank.ctrR2)
        self.connect(self.damper.flange_a, self.bearing.flange)
        self.connect(self.damper.flange_b, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


class FourBarTorqueConstant(Component):
    """:class:`FourBarTorque` with its input held at 0.2 N m."""
    experiment = FourBarTorque.experiment
    outputs = ["bar.crank.phiL", "bar.dyad.phiL2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.bar = FourBarTorque()
        self.torque = Constant(k=0.2)
        self.connect(self.torque.y, self.bar.tau)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__, "FourBarTorqueConstant"))
