"""Simple pendulum (PlanarMechanics example; reference Pendulum.csv).

Fixed -> Revolute (phi(0)=0, w(0)=0) -> FixedTranslation r={1,0} ->
Body m=1, I=0.1.  The pendulum starts horizontal and falls under gravity.
"""
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class Pendulum(Component):
    """Pendulum of length 1 m with a 1 kg body, released horizontally."""
    experiment = {"stop_time": 3.0, "intervals": 500}
    outputs = ["body.phi", "revolute.w"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
