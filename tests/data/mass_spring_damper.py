"""Step response of a mass-spring-damper (issue 29, Seen 7): a constant
force F = 45 N pushes the mass m = 1 kg, at rest at s = 0 on the
unstretched spring c = 450 N/m, through the damper d; s -> F/c = 0.1 m.

With omega_n = sqrt(c/m) and zeta = d / (2 sqrt(c m)) the response is the
standard second-order step: s(t) = 0.1 (1 - exp(-zeta omega_n t) (cos
omega_d t + zeta/sqrt(1-zeta^2) sin omega_d t)), its peak 0.1 (1 +
exp(-pi zeta / sqrt(1 - zeta^2))) at t_p = pi / omega_d and its integral
squared error int (s - 0.1)^2 dt = 0.01 (1 + 4 zeta^2) / (4 zeta omega_n)
(tests/test_optimize_edges.py, tests/fuzz_cases_fitopt.py)."""
from acausal2d import Component, start
from acausal2d.library import signals, translational


class MassSpringDamper(Component):
    experiment = {"stop_time": 1.0, "intervals": 500}
    outputs = ["mass.s"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.wall = translational.Fixed()
        self.spring = translational.SpringDamper(c=450.0, d=10.0)
        self.mass = translational.Mass(m=1.0, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.force = translational.Force()
        self.load = signals.Constant(k=45.0)
        self.connect(self.wall.flange, self.spring.flange_a)
        self.connect(self.spring.flange_b, self.mass.flange_a)
        self.connect(self.force.flange, self.mass.flange_b)
        self.connect(self.load.y, self.force.f_in)
