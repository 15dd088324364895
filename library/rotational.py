"""1D rotational mechanics (Modelica.Mechanics.Rotational conventions):
flange.phi is the absolute angle, flange.tau the torque acting on the
element from the connected part."""
import casadi as ca

from acausal2d import (Component, der, Parameter, RealInput, RealOutput, RotationalFlange,
                       Variable)
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.friction1d import friction_law, interpolate, table_rows


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
    J = Parameter(1.0, "kg.m2", "moment of inertia", min=0.0)
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
    c = Parameter(1.0, "N.m/rad", "spring constant", positive=True)
    phi_rel0 = Parameter(0.0, "rad", "unstretched relative angle")

    def equations(self):
        return self._common() + [self.tau == self.c * (self.phi_rel - self.phi_rel0)]


class Damper(_Compliant):
    """Linear rotational damper tau = d der(phi_rel)."""
    d = Parameter(1.0, "N.m.s/rad", "damping constant", min=0.0)

    def equations(self):
        return self._common() + [self.tau == self.d * der(self.phi_rel)]


class SpringDamper(_Compliant):
    """Linear torsion spring and damper in parallel
    (Modelica.Mechanics.Rotational.Components.SpringDamper):
    ``tau = c (phi_rel - phi_rel0) + d w_rel``, ``w_rel = der(phi_rel)``;
    ``tau`` acts on flange_b (``-tau`` on flange_a, Ebert (2015), eq. 4.1 at the
    flanges).  ``loss_power = d w_rel^2`` is the power dissipated."""
    c = Parameter(1.0, "N.m/rad", "spring constant", min=0.0)
    d = Parameter(1.0, "N.m.s/rad", "damping constant", min=0.0)
    phi_rel0 = Parameter(0.0, "rad", "unstretched relative angle")
    w_rel = Variable(unit="rad/s", doc="relative angular velocity")
    loss_power = Variable(unit="W", doc="power dissipated by the damper")

    def equations(self):
        return self._common() + [
            self.w_rel == der(self.phi_rel),
            self.tau == self.c * (self.phi_rel - self.phi_rel0) + self.d * self.w_rel,
            self.loss_power == self.d * self.w_rel ** 2]


class AngleSensor(Component):
    """Absolute angle of the flange as the signal ``phi``
    (Modelica.Mechanics.Rotational.Sensors.AngleSensor); takes no torque,
    so a joint it measures stays free.  Ebert (2015), eq. 4.1 at the flange."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.phi = RealOutput()

    def equations(self):
        return [self.phi.u == self.flange.phi, self.flange.tau == 0]


class SpeedSensor(Component):
    """Absolute angular velocity of the flange as the signal ``w``
    (Modelica.Mechanics.Rotational.Sensors.SpeedSensor: ``w =
    der(flange.phi)``, ``0 = flange.tau``); takes no torque.  Feeds the
    measurement input ``u_m`` of a :class:`~acausal2d.library.controllers.LimPID`."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.w = RealOutput()

    def equations(self):
        return [self.w.u == der(self.flange.phi), self.flange.tau == 0]


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


class Clutch(Component):
    """Friction clutch (Modelica.Mechanics.Rotational.Components.Clutch;
    the dissertation's disc clutch, ch. 8.2 "discClutch1") between ``flange_a`` and
    ``flange_b``, engaged by the signal input ``f_normalized`` (0 = open,
    1 = fully closed)::

        phi_rel = flange_b.phi - flange_a.phi,  w_rel = der(phi_rel),  a_rel = der(w_rel)
        flange_b.tau = tau,  flange_a.tau = -tau
        fn = fn_max * f_normalized,  free = fn <= 0
        tau0 = mu0 * cgeo * fn,  tau0_max = peak * tau0
        tau = cgeo * fn * mu(w_rel) sliding forward, -cgeo * fn * mu(-w_rel) backward,
              stuck (tau from the balance) while |tau| <= tau0_max

    The sliding friction coefficient is the constant ``mu`` or, as in
    Modelica, the table ``mu_pos`` (rows ``[w_rel, mu]``, linear, extrapolated
    by the last two points; give one of the two); ``mu0`` is its value at
    ``w_rel = 0``.  The defaults are Modelica's (``mu_pos = [0, 0.5]``,
    ``cgeo = 1``, ``fn_max``'s start value 1).  ``cgeo`` is the effective friction radius times the
    number of friction faces.  The torque capacity used is ``T_max = mu0 *
    cgeo * max(fn, 0)``: as in Modelica (``free = fn <= 0``) a negative
    ``f_normalized`` (a control signal overshooting below "open") transmits
    no torque and never drives the slip apart; ``fn`` crossing 0 is an
    event.  As in Modelica's ``PartialCompliantWithRelativeStates`` the
    relative angle and speed are preferred states: the creep ``w_rel`` (down
    to 1e-9 rad/s) is then integrated itself instead of being the
    difference of two flange speeds, whose rounding would be all of it.

    Sticking is a stick zone ``|w_rel| < w_s`` (the law of
    :func:`acausal2d.library.friction1d.friction_law`): a stiff viscous
    coupling ``peak T_max / w_s`` inside, the sliding characteristic outside,
    joined continuously; entering and leaving the zone are events.  With
    ``peak = 1`` and a constant ``mu`` this is the Karnopp saturation
    ``tau = T_max sat(w_rel / w_s)``: Coulomb while slipping, "stuck"
    (both flanges at one speed up to the creep ``w_s tau / T_max``) until
    the torque to transmit exceeds ``peak T_max`` (an event).  The time from
    engagement to sticking matches the Coulomb closed form ``J_eff w_rel0 /
    T_max`` up to about ``J_eff w_s / T_max`` (``J_eff = J_a J_b/(J_a +
    J_b)``); a small ``w_s`` makes the model stiff but not slower for IDA.
    ``w_small`` is Modelica's reinit threshold, accepted for transcription
    (speeds never jump here, so it has no effect).  A clutch with
    ``f_normalized = 0`` transmits nothing.

    Outputs: ``phi_rel``, ``w_rel``, ``a_rel``, ``tau``, ``fn``, ``T_max``; the
    friction power dissipated in the clutch is ``tau * w_rel`` (>= 0).
    """
    mu = Parameter(0.5, "1", "friction coefficient (constant; or give the table mu_pos)",
                   min=0.0)
    peak = Parameter(1.0, "1", "peak of the friction at w_rel = 0: tau0_max = peak tau0",
                     min=1.0)
    fn_max = Parameter(1.0, "N", "normal force at f_normalized = 1", min=0.0)
    cgeo = Parameter(1.0, "m", "effective friction radius x number of friction faces", positive=True)
    w_s = Parameter(1e-3, "rad/s", "width of the regularisation zone (creep speed)", positive=True)
    w_small = Parameter(1e10, "rad/s", "Modelica's reinit threshold (no effect here)",
                        positive=True)
    phi_rel = Variable(unit="rad", state_select="prefer",
                       doc="relative angle flange_b - flange_a")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="relative angular velocity")
    a_rel = Variable(unit="rad/s2", doc="relative angular acceleration der(w_rel)")
    tau = Variable(unit="N.m", doc="friction torque acting on flange_b")
    fn = Variable(unit="N", doc="normal force fn_max f_normalized (free for fn <= 0)")
    T_max = Variable(unit="N.m", doc="sliding torque at w_rel = 0: mu0 cgeo max(fn, 0)")

    def __init__(self, mu_pos=None, **kw):
        super().__init__(**kw)
        if mu_pos is not None and "mu" in kw:
            raise ModelDefinitionError("%s: give mu (a constant) or mu_pos (a table), not both"
                                       % self.describe())
        self.mu_pos = None if mu_pos is None else table_rows(self, "mu_pos", mu_pos, None)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.f_normalized = RealInput()

    def sliding_mode_advice(self):
        """The clutch models sticking itself: a sliding mode or chattering
        of its zone relations means the zone is too narrow to resolve."""
        return ("%s models sticking itself with its stick zone |w_rel| < w_s: a zone this "
                "narrow cannot be resolved at the speeds of the run. Give it a larger w_s "
                "(the lock time changes by about J_eff w_s / T_max only), or make its "
                "f_normalized input continuous." % self.describe())

    def _slide(self, v):
        """Sliding torque at the speed magnitude v: T_max for a constant mu,
        cgeo max(fn, 0) mu_pos(v) for a table."""
        if self.mu_pos is None:
            return self.T_max
        return interpolate(self.mu_pos, v) * self.cgeo * ca.fmax(self.fn, 0.0)

    def equations(self):
        mu0 = self.mu if self.mu_pos is None else interpolate(self.mu_pos, 0.0)
        return [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                self.w_rel == der(self.phi_rel), self.a_rel == der(self.w_rel),
                self.fn == self.fn_max * self.f_normalized.u,
                self.T_max == mu0 * self.cgeo * ca.fmax(self.fn, 0.0),
                self.tau == friction_law(self.w_rel, self.w_s, self.peak * self.T_max, self._slide),
                self.flange_b.tau == self.tau, self.flange_a.tau == -self.tau]


class AsyncMotor(Component):
    """Asynchronous (induction) motor with the static torque-speed
    characteristic of Kloss and the rotor inertia ``J``.

    Slip ``s = (w_sync - w)/w_sync`` with the synchronous speed ``w_sync``
    (= 2 pi f / number of pole pairs); air-gap torque (Kloss)::

        T_el = 2 T_k / (s/s_k + s_k/s) = 2 T_k s s_k / (s^2 + s_k^2)

    with the breakdown torque ``T_k`` at the breakdown slip ``s_k`` (the
    second form has no singularity at s = 0).  The rotor:
    ``J der(w) = T_el + flange.tau`` (``flange.tau``: torque of the load on
    the rotor).  The stator is fixed in the ground.  The electrical
    transients are neglected (static characteristic), which is the usual
    simplification for drive-train simulations.  Starting torque
    ``T_el(s=1) = 2 T_k s_k/(1 + s_k^2)``.

    Outputs: ``phi``, ``w``, ``s``, ``T_el``, ``P_mech = T_el * w`` (air-gap
    power minus rotor copper losses = mechanical power of the rotor).
    Start at rest by default (``w=start(0, fixed=True)``), or give
    ``w=start(w_sync, fixed=True)`` for a motor running idle at t0.
    """
    J = Parameter(0.01, "kg.m2", "rotor inertia", min=0.0)
    w_sync = Parameter(157.07963267948966, "rad/s", "synchronous speed (default 50 Hz, 2 pole pairs)", positive=True)
    T_k = Parameter(40.0, "N.m", "breakdown torque", positive=True)
    s_k = Parameter(0.2, "1", "breakdown slip", positive=True)
    phi = Variable(unit="rad", fixed=True, doc="rotor angle")
    w = Variable(unit="rad/s", fixed=True, doc="rotor angular velocity")
    s = Variable(unit="1", doc="slip")
    T_el = Variable(unit="N.m", doc="air-gap torque (Kloss)")
    P_mech = Variable(unit="W", doc="mechanical power T_el * w")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.flange.phi == self.phi, self.w == der(self.phi),
                self.s == (self.w_sync - self.w) / self.w_sync,
                self.T_el == 2 * self.T_k * self.s * self.s_k / (self.s ** 2 + self.s_k ** 2),
                self.J * der(self.w) == self.T_el + self.flange.tau,
                self.P_mech == self.T_el * self.w]


# Modelica.Mechanics.Rotational.Components' gears, where Modelica users look for them
from acausal2d.library.gears import IdealGear, IdealPlanetary  # noqa: E402,F401
from acausal2d.library.friction1d import BearingFriction, Brake, OneWayClutch  # noqa: E402,F401
