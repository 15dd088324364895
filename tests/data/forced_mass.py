"""A top-level input u pushes a mass on a spring: x' = v, v' = (u - c s) / m
(tests/test_modes.py and tests/test_modes_cli.py)."""
from acausal2d import Component, RealInput, start
from acausal2d.library import translational


class ForcedMass(Component):
    outputs = ["mass.s"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u = RealInput()
        self.wall = translational.Fixed()
        self.spring = translational.Spring(c=100.0)
        self.mass = translational.Mass(m=4.0, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.force = translational.Force()
        self.connect(self.wall.flange, self.spring.flange_a)
        self.connect(self.spring.flange_b, self.mass.flange_a)
        self.connect(self.force.flange, self.mass.flange_b)
        self.connect(self.u, self.force.f_in)
