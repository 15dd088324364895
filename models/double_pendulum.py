"""Double pendulum (PlanarMechanics example; reference DoublePendulum.csv).

Fixed -> revolute (phi(0)=0, w(0)=0) -> FixedTranslation r={1,0} -> Body
m=1, I=0.1 at its end; the same end frame -> revolute1 (phi(0)=0, w(0)=0)
-> FixedTranslation r={0.4,0} -> Body m=0.2, I=0.01.
"""
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class DoublePendulum(Component):
    """Two pendulum links released from rest; ``phi0``, ``phi1``: start
    angles (rad) of the two joints (the reference starts both at 0, both
    links horizontal)."""
    experiment = {"stop_time": 10.0, "intervals": 1000}
    outputs = ["revolute.phi", "revolute1.phi"]

    def __init__(self, phi0=0.0, phi1=0.0, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(phi0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.revolute1 = Revolute(phi=start(phi1, fixed=True), w=start(0.0, fixed=True))
        self.rod1 = FixedTranslation(r=(0.4, 0.0))
        self.body1 = Body(m=0.2, I=0.01)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)
        self.connect(self.rod.frame_b, self.revolute1.frame_a)
        self.connect(self.revolute1.frame_b, self.rod1.frame_a)
        self.connect(self.rod1.frame_b, self.body1.frame_a)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
