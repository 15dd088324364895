"""Crane crab (PlanarMechanics example; reference CraneCrab.csv).

Fixed -> Prismatic r={1,0} (s(0)=0, v(0)=0) whose frame_b carries Body1
(m=1, I=0.1).  A 1D translational damper d=10 N s/m acts between the
prismatic joint's support and its flange.  Body1's frame -> Revolute
(phi(0)=150 deg, w(0)=0) -> FixedTranslation r={0,-1} -> Body m=0.5, I=0.1.
"""
import math

from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute
from acausal2d.library.translational import Damper


class CraneCrab(Component):
    """A damped trolley carrying a swinging load."""
    experiment = {"stop_time": 10.0, "intervals": 1000}
    outputs = ["body.phi", "damper1D.s_rel", "damper1D.v_rel", "revolute.w"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.prismatic = Prismatic(r=(1.0, 0.0), use_flange=True,
                                   s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.damper1D = Damper(d=10.0)
        self.body1 = Body(m=1.0, I=0.1)
        self.revolute = Revolute(phi=start(math.radians(150.0), fixed=True),
                                 w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(0.0, -1.0))
        self.body = Body(m=0.5, I=0.1)
        self.connect(self.fixed.frame, self.prismatic.frame_a)
        self.connect(self.prismatic.support, self.damper1D.flange_a)
        self.connect(self.damper1D.flange_b, self.prismatic.flange_a)
        self.connect(self.prismatic.frame_b, self.body1.frame_a)
        self.connect(self.prismatic.frame_b, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
