"""1D rotational mechanics (Modelica.Mechanics.Rotational conventions):
flange.phi is the absolute angle, flange.tau the torque acting on the
element from the connected part."""
from acausal2d.connectors import RealInput, RotationalFlange
from acausal2d.dsl import Component, Parameter, Variable
from acausal2d.symbols import der


class Fixed(Component):
    """Flange fixed at angle phi0."""
    phi0 = Parameter(0.0, "rad", "fixed angle")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.flange.phi == self.phi0]


class Inertia(Component):
    """Rotational inertia J between two rigidly coupled flanges; w = der(phi)."""
    J = Parameter(1.0, "kg.m2", "moment of inertia")
    phi = Variable(unit="rad", doc="absolute angle")
    w = Variable(unit="rad/s", doc="angular velocity")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()

    def equations(self):
        return [self.flange_a.phi == self.phi, self.flange_b.phi == self.phi,
                self.w == der(self.phi),
                self.J * der(self.w) == self.flange_a.tau + self.flange_b.tau]


class _Compliant(Component):
    phi_rel = Variable(unit="rad", doc="relative angle flange_b - flange_a")
    tau = Variable(unit="N.m", doc="torque transmitted (acting on flange_b)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()

    def _common(self):
        return [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                self.flange_b.tau == self.tau, self.flange_a.tau == -self.tau]


class Spring(_Compliant):
    """Linear torsion spring tau = c (phi_rel - phi_rel0)."""
    c = Parameter(1.0, "N.m/rad", "spring constant")
    phi_rel0 = Parameter(0.0, "rad", "unstretched relative angle")

    def equations(self):
        return self._common() + [self.tau == self.c * (self.phi_rel - self.phi_rel0)]


class Damper(_Compliant):
    """Linear rotational damper tau = d der(phi_rel)."""
    d = Parameter(1.0, "N.m.s/rad", "damping constant")

    def equations(self):
        return self._common() + [self.tau == self.d * der(self.phi_rel)]


class Torque(Component):
    """Torque from the signal tau_in acting on the flange (reaction on the
    fixed support)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.tau_in = RealInput()

    def equations(self):
        return [self.flange.tau == -self.tau_in.u]


class ConstantTorque(Component):
    """Constant torque tau acting on the flange."""
    tau = Parameter(0.0, "N.m", "torque")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.flange.tau == -self.tau]


class Speed(Component):
    """Drives the flange at the angular velocity w_in (rad/s); the angle is
    integrated from its start value (``phi=start(...)``)."""
    phi = Variable(unit="rad", doc="flange angle", fixed=True)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.w_in = RealInput()

    def equations(self):
        return [self.flange.phi == self.phi, der(self.phi) == self.w_in.u]


class Position(Component):
    """Drives the flange angle to the signal phi_in (rad); velocity and
    acceleration follow by index reduction."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.phi_in = RealInput()

    def equations(self):
        return [self.flange.phi == self.phi_in.u]
