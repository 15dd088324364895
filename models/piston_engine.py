"""Piston engine: a slider-crank without drive, started spinning
(PlanarMechanics example; reference PistonEngine.csv).

Fixed at the origin -> revoluteDrive (phi(0)=0, w(0)=-2.5 rad/s, always a
state) -> its frame_b carries bodyDrive (m=1, I=0.1) and the crank
FixedTranslation r={0.3,0} -> revoluteDisc -> massless rod FixedTranslation
r={0.8,0} -> revolutePiston -> frame carrying bodyPiston (m=3, I=0.1), which
is frame_a of a Prismatic r={1,0} whose frame_b is connected to a second
Fixed at the origin (so the piston's x equals -s).  At t=0 the mechanism is
at its dead centre with s=-1.1.  Gravity does no work; the energy
E = 0.5*0.1*w^2 + 0.5*3*xdot^2 = 0.3125 J is conserved.

The piston's travel in three frames: in the world it moves along x from
0.5 to 1.1 m (rod minus crank to rod plus crank); the prismatic joint's
coordinate ``prismatic.s`` is the position of its frame_a (the piston)
seen from frame_b (the origin) against the direction r = {1, 0}, so it
runs from -1.1 to -0.5 m (s = -x); the cylinder is drawn from x = 0.4 to
1.2 m (``guide``, given in s), and the summary of ``acausal2d simulate``
counts the travel along the guide from that drawn start, 0.1 to 0.7 m.
The stroke is 0.6 m in each.
"""
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute


class PistonEngine(Component):
    """Slider-crank with crank angle chosen as state (``state_select``
    'always' on the drive joint, 'prefer' on the others as in
    PlanarMechanics).  Pass ``state_select='default'`` to leave the choice of
    states entirely to the compiler."""
    experiment = {"stop_time": 10.0, "intervals": 5000, "rtol": 1e-8}
    outputs = ["revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"]

    def __init__(self, drive_state_select="always", state_select="prefer", **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revoluteDrive = Revolute(state_select=drive_state_select,
                                      phi=start(0.0, fixed=True), w=start(-2.5, fixed=True))
        self.bodyDrive = Body(m=1.0, I=0.1)
        self.crank = FixedTranslation(r=(0.3, 0.0))
        self.revoluteDisc = Revolute(state_select=state_select)
        self.rod = FixedTranslation(r=(0.8, 0.0))
        self.revolutePiston = Revolute(state_select=state_select)
        self.bodyPiston = Body(m=3.0, I=0.1)
        # guide: the cylinder drawn 0.1 m beyond the piston's travel, x = 0.4 ... 1.2 m
        # (given in s: frame_a = frame_b - s r, the piston's s = -1.1 ... -0.5)
        self.prismatic = Prismatic(r=(1.0, 0.0), state_select=state_select,
                                   s=start(-1.1), guide=(-0.4, -1.2))
        self.fixed1 = Fixed()
        self.connect(self.fixed.frame, self.revoluteDrive.frame_a)
        self.connect(self.revoluteDrive.frame_b, self.bodyDrive.frame_a)
        self.connect(self.revoluteDrive.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.revoluteDisc.frame_a)
        self.connect(self.revoluteDisc.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.revolutePiston.frame_a)
        self.connect(self.revolutePiston.frame_b, self.bodyPiston.frame_a)
        self.connect(self.revolutePiston.frame_b, self.prismatic.frame_a)
        self.connect(self.prismatic.frame_b, self.fixed1.frame)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
