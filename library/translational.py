"""1D translational mechanics (Modelica.Mechanics.Translational conventions):
flange.s is the absolute position, flange.f the force acting on the element
from the connected part."""

from acausal2d import (Component, der, Parameter, RealInput, RealOutput, TranslationalFlange,
                       Variable)
from acausal2d.library.relative_states import relative_states


class Fixed(Component):
    """Flange fixed at position s0."""
    s0 = Parameter(0.0, "m", "fixed position")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()

    def equations(self):
        return [self.flange.s == self.s0]


class Mass(Component):
    """Sliding mass with inertia (Modelica Standard Library 4.0,
    Modelica.Mechanics.Translational.Components.Mass)::

        flange_a.s = s - L/2,  flange_b.s = s + L/2,  v = der(s)
        m der(v) = flange_a.f + flange_b.f

    ``s`` is the position of the centre, ``L`` the length (distance of the
    flanges, default 0)."""
    m = Parameter(1.0, "kg", "mass", min=0.0)
    L = Parameter(0.0, "m", "length of the mass (distance of the flanges)", min=0.0)
    s = Variable(unit="m", doc="position of the centre")
    v = Variable(unit="m/s", doc="velocity")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()

    def equations(self):
        return [self.flange_a.s == self.s - self.L / 2, self.flange_b.s == self.s + self.L / 2,
                self.v == der(self.s),
                self.m * der(self.v) == self.flange_a.f + self.flange_b.f]


class _Compliant(Component):
    s_rel = Variable(unit="m", doc="relative position flange_b - flange_a")
    f = Variable(unit="N", doc="force transmitted (acting on flange_b)")

    power_sides = (("flange_a",), ("flange_b",))

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()

    def _common(self):
        return [self.s_rel == self.flange_b.s - self.flange_a.s,
                self.flange_b.f == self.f, self.flange_a.f == -self.f]


class Spring(_Compliant):
    """Linear spring f = c (s_rel - s_rel0)."""
    c = Parameter(1.0, "N/m", "spring constant", positive=True)
    s_rel0 = Parameter(0.0, "m", "unstretched length")

    def equations(self):
        return self._common() + [self.f == self.c * (self.s_rel - self.s_rel0)]


class _RelativeStates(_Compliant):
    """Modelica's PartialCompliantWithRelativeStates (Modelica Standard
    Library 4.0, Modelica.Mechanics.Translational.Interfaces): ``s_rel``
    and ``v_rel`` are preferred states (``stateSelect = prefer``),
    ``s_rel`` with the nominal ``s_nominal = 1e-4`` m (a small relative
    displacement is integrated to its own scale, not as the difference of
    two large absolute positions)::

        s_rel = flange_b.s - flange_a.s,  v_rel = der(s_rel)
        flange_b.f = f,  flange_a.f = -f"""
    s_rel = Variable(unit="m", state_select="prefer", nominal=1e-4,
                     doc="relative position flange_b - flange_a")
    v_rel = Variable(unit="m/s", state_select="prefer", doc="relative velocity")

    def __init__(self, s_nominal=None, stateSelect=None, **kw):
        super().__init__(**kw)
        relative_states(self, "s_rel", "v_rel", s_nominal, stateSelect, "s_nominal")


class Damper(_RelativeStates):
    """Linear damper (Modelica Standard Library 4.0,
    Modelica.Mechanics.Translational.Components.Damper): ``f = d v_rel``
    with ``v_rel = der(s_rel)``; relative states as
    :class:`_RelativeStates`."""
    d = Parameter(1.0, "N.s/m", "damping constant", min=0.0)

    def equations(self):
        return self._common() + [self.v_rel == der(self.s_rel), self.f == self.d * self.v_rel]


class SpringDamper(_RelativeStates):
    """Linear spring and damper in parallel (Modelica Standard Library 4.0,
    Modelica.Mechanics.Translational.Components.SpringDamper):
    ``f = c (s_rel - s_rel0) + d v_rel``, ``v_rel = der(s_rel)``; the force
    ``f`` acts on flange_b (``-f`` on flange_a, Ebert (2015), eq. 4.1 at the
    flanges).  ``loss_power = d v_rel^2`` is the power dissipated.
    Relative states as :class:`_RelativeStates`."""
    c = Parameter(1.0, "N/m", "spring constant", min=0.0)
    d = Parameter(1.0, "N.s/m", "damping constant", min=0.0)
    s_rel0 = Parameter(0.0, "m", "unstretched length")
    loss_power = Variable(unit="W", doc="power dissipated by the damper")

    def equations(self):
        return self._common() + [
            self.v_rel == der(self.s_rel),
            self.f == self.c * (self.s_rel - self.s_rel0) + self.d * self.v_rel,
            self.loss_power == self.d * self.v_rel ** 2]


class Force(Component):
    """Force from the signal f_in acting on the flange
    (Modelica.Mechanics.Translational.Sources.Force without support: the
    reaction goes to ground); a positive signal pushes the flange in its
    positive direction.  Ebert (2015), eq. 4.1 at the flange."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()
        self.f_in = RealInput()

    def equations(self):
        return [self.flange.f == -self.f_in.u]


class Position(Component):
    """Drives the flange position to the signal s_in (m); velocity and
    acceleration follow by index reduction (the translational counterpart of
    rotational.Position, e.g. a slider travel prescribed as a function of
    time)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()
        self.s_in = RealInput()

    def equations(self):
        return [self.flange.s == self.s_in.u]


class PositionSensor(Component):
    """Absolute position of the flange as the signal ``s``
    (Modelica.Mechanics.Translational.Sensors.PositionSensor); takes no
    force.  Ebert (2015), eq. 4.1 at the flange."""

    power_sides = (("flange",), ("s",))

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()
        self.s = RealOutput()

    def equations(self):
        return [self.s.u == self.flange.s, self.flange.f == 0]


# Modelica.Mechanics.Translational.Components' friction, where Modelica users look for it
from acausal2d.library.friction_translational import (  # noqa: E402,F401
    MassWithStopAndFriction, SupportFriction)
from acausal2d.library.friction1d import brake_friction, interpolate, table_rows  # noqa: E402,F401,E501


class Brake(SupportFriction):
    """Brake based on Coulomb friction (Modelica Standard Library 4.0,
    Modelica.Mechanics.Translational.Components.Brake)::

        s = flange_a.s - support.s,  flange_b.s = flange_a.s
        v = der(s),  a = der(v),  0 = flange_a.f + flange_b.f - f
        fn = fn_max * f_normalized,  free = fn <= 0
        mu0 = mu_pos(v = 0),  f0 = mu0 * cgeo * fn,  f0_max = peak * f0
        f = if locked then sa else if free then 0 else
            cgeo * fn * (if forward then mu_pos(v) else -mu_pos(-v))

    with the modes of Modelica's PartialFriction
    (:func:`~acausal2d.library.friction1d.partial_friction`): it holds the
    flanges (``v`` stays 0) while the force on them stays within
    ``f0_max``.  ``mu_pos``: rows ``[v, mu]`` (default ``[[0, 0.5]]``)."""
    cgeo = Parameter(1.0, "1", "geometry constant (friction distribution)", min=0.0)
    fn_max = Parameter(1.0, "N", "maximum normal force", min=0.0)
    fn = Variable(unit="N", doc="normal force fn_max f_normalized")

    def __init__(self, mu_pos=None, **kw):
        super().__init__(**kw)
        self.mu_pos = table_rows(self, "mu_pos", mu_pos, [(0.0, 0.5)])
        self.f_normalized = RealInput(doc="normalized normal force (0..1)")

    def equations(self):
        free, breakaway, slide = brake_friction(self)
        return [self.s == self.flange_a.s - self.support.s, self.flange_b.s == self.flange_a.s,
                self.v == der(self.s), self.a == der(self.v),
                0 == self.flange_a.f + self.flange_b.f - self.f,
                self.support.f == -self.flange_a.f - self.flange_b.f,
                self.fn == self.fn_max * self.f_normalized.u] + self.law_equations(
            self.v, self.a, free, breakaway, slide)
