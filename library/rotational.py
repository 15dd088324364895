"""1D rotational mechanics (Modelica.Mechanics.Rotational conventions):
flange.phi is the absolute angle, flange.tau the torque acting on the
element from the connected part."""
import numbers
import warnings

import casadi as ca

from acausal2d import (Component, der, Parameter, RealInput, RealOutput, RotationalFlange,
                       Variable, time)
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.relative_states import relative_states
from acausal2d.library.friction1d import (_Modes, check_law, interpolate, partial_friction,
                                          table_rows, zone_law)


class Fixed(Component):
    """Flange fixed at angle phi0."""
    phi0 = Parameter(0.0, "rad", "fixed angle")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.flange.phi == self.phi0]


class Inertia(Component):
    """Rotational inertia J between two rigidly coupled flanges
    (Modelica Standard Library 4.0, Modelica.Mechanics.Rotational.Components.Inertia)::

        phi = flange_a.phi = flange_b.phi,  w = der(phi),  a = der(w)
        J * a = flange_a.tau + flange_b.tau

    ``a`` may be given a start value (``a=start(0, fixed=True)``: start in
    equilibrium)."""
    J = Parameter(1.0, "kg.m2", "moment of inertia", min=0.0)
    phi = Variable(unit="rad", doc="absolute angle")
    w = Variable(unit="rad/s", doc="angular velocity")
    a = Variable(unit="rad/s2", doc="angular acceleration")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()

    def equations(self):
        return [self.flange_a.phi == self.phi, self.flange_b.phi == self.phi,
                self.w == der(self.phi), self.a == der(self.w),
                self.J * self.a == self.flange_a.tau + self.flange_b.tau]


class _Compliant(Component):
    phi_rel = Variable(unit="rad", doc="relative angle flange_b - flange_a")
    tau = Variable(unit="N.m", doc="torque transmitted (acting on flange_b)")

    power_sides = (("flange_a",), ("flange_b",))

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


class _RelativeStates(_Compliant):
    """Modelica's PartialCompliantWithRelativeStates: ``phi_rel`` and
    ``w_rel`` are preferred states, ``phi_rel`` with the nominal
    ``phi_nominal = 1e-4`` rad (a small relative angle is integrated to
    its own scale, not as the difference of two large absolute ones)."""
    phi_rel = Variable(unit="rad", state_select="prefer", nominal=1e-4,
                       doc="relative angle flange_b - flange_a")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="relative angular velocity")

    def __init__(self, phi_nominal=None, stateSelect=None, **kw):
        super().__init__(**kw)
        relative_states(self, "phi_rel", "w_rel", phi_nominal, stateSelect)


class Damper(_RelativeStates):
    """Linear rotational damper (Modelica.Mechanics.Rotational.Components.
    Damper): ``tau = d w_rel``, ``w_rel = der(phi_rel)``."""
    d = Parameter(1.0, "N.m.s/rad", "damping constant", min=0.0)

    def equations(self):
        return self._common() + [self.w_rel == der(self.phi_rel), self.tau == self.d * self.w_rel]


class SpringDamper(_RelativeStates):
    """Linear torsion spring and damper in parallel
    (Modelica.Mechanics.Rotational.Components.SpringDamper):
    ``tau = c (phi_rel - phi_rel0) + d w_rel``, ``w_rel = der(phi_rel)``;
    ``tau`` acts on flange_b (``-tau`` on flange_a, Ebert (2015), eq. 4.1 at the
    flanges).  ``loss_power = d w_rel^2`` is the power dissipated."""
    c = Parameter(1.0, "N.m/rad", "spring constant", min=0.0)
    d = Parameter(1.0, "N.m.s/rad", "damping constant", min=0.0)
    phi_rel0 = Parameter(0.0, "rad", "unstretched relative angle")
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

    power_sides = (("flange",), ("phi",))

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

    power_sides = (("flange",), ("w",))

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.w = RealOutput()

    def equations(self):
        return [self.w.u == der(self.flange.phi), self.flange.tau == 0]


class MultiSensor(Component):
    """Power, torque and angular velocity between two flanges
    (Modelica Standard Library 4.0, Modelica.Mechanics.Rotational.Sensors.MultiSensor)::

        flange_a.phi = flange_b.phi,  w = der(flange_a.phi)
        tau = flange_a.tau,  0 = flange_a.tau + flange_b.tau
        power = tau * w

    The signals ``power``, ``w``, ``tau`` are outputs; the sensor is a
    rigid connection (``tau`` is the torque passed from flange_a to
    flange_b)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.power = RealOutput()
        self.w = RealOutput()
        self.tau = RealOutput()

    def equations(self):
        return [self.flange_a.phi == self.flange_b.phi, self.w.u == der(self.flange_a.phi),
                self.tau.u == self.flange_a.tau, 0 == self.flange_a.tau + self.flange_b.tau,
                self.power.u == self.tau.u * self.w.u]


class Torque(Component):
    """Torque from the signal tau_in acting on the flange
    (Modelica Standard Library 4.0, Modelica.Mechanics.Rotational.Sources.Torque)::

        flange.tau = -tau,  support.tau = -flange.tau

    ``support`` is Modelica's optional support: left unconnected it is fixed
    to ground (``useSupport = false``); connect it to a housing to take the
    reaction torque there."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.support = RotationalFlange(ground={"phi": 0.0},
                                        doc="housing (fixed at 0 if unconnected)")
        self.tau_in = RealInput()

    def equations(self):
        return [self.flange.tau == -self.tau_in.u, self.support.tau == -self.flange.tau]


class _PartialTorque(Component):
    """A torque source on ``flange`` with Modelica's optional ``support``
    (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Interfaces.PartialTorque)::

        phi = flange.phi - phi_support,  w = der(phi)
        tau = -flange.tau,  support.tau = -flange.tau

    ``support`` left unconnected is fixed to ground (``useSupport = false``,
    ``phi_support = 0``); connected to a housing (``useSupport = true``) it
    takes the reaction torque there.  ``tau`` accelerates the flange (a
    negative one is a load).  Subclasses give :meth:`torque_law`."""
    phi = Variable(unit="rad", doc="angle of flange with respect to support (= flange.phi - "
                   "support.phi)")
    w = Variable(unit="rad/s", doc="angular velocity of flange with respect to support "
                 "(= der(phi))")
    tau = Variable(unit="N.m", doc="accelerating torque acting at the flange (= -flange.tau)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()
        self.support = RotationalFlange(ground={"phi": 0.0},
                                        doc="housing (fixed at 0 if unconnected)")

    def torque_law(self):
        """The right-hand side of ``tau = ...``."""
        raise NotImplementedError

    def equations(self):
        return [self.phi == self.flange.phi - self.support.phi, self.w == der(self.phi),
                self.tau == -self.flange.tau, self.support.tau == -self.flange.tau,
                self.tau == self.torque_law()]


class ConstantTorque(_PartialTorque):
    """Constant torque, not dependent on speed (Modelica Standard Library
    4.0, Modelica.Mechanics.Rotational.Sources.ConstantTorque; the
    support as :class:`_PartialTorque`'s)::

        phi = flange.phi - phi_support,  w = der(phi)
        tau = -flange.tau,  tau = tau_constant

    ``tau`` is the variable, as in Modelica; ``tau=`` with a number is the
    former name of ``tau_constant`` (DeprecationWarning)."""
    tau_constant = Parameter(0.0, "N.m", "constant torque (< 0: a load in the positive "
                             "direction of rotation)")

    def __init__(self, **kw):
        former = kw.get("tau")
        if isinstance(former, numbers.Real) and not isinstance(former, bool):
            if "tau_constant" in kw:
                raise ModelDefinitionError("ConstantTorque: give tau_constant only (tau is the "
                                           "former name of the constant torque)")
            warnings.warn("ConstantTorque(tau=...) is the former name of Modelica's "
                          "tau_constant: write ConstantTorque(tau_constant=...); tau is the "
                          "torque variable", DeprecationWarning, stacklevel=2)
            kw["tau_constant"] = kw.pop("tau")
        super().__init__(**kw)

    def torque_law(self):
        return self.tau_constant


class TorqueStep(_PartialTorque):
    """Constant torque with a step (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Sources.TorqueStep; the support as
    :class:`_PartialTorque`'s)::

        phi = flange.phi - phi_support,  w = der(phi),  tau = -flange.tau
        tau = offsetTorque + (if time < startTime then 0 else stepTorque)

    The step is a time event."""
    stepTorque = Parameter(1.0, "N.m", "height of the torque step (< 0: a load)")
    offsetTorque = Parameter(0.0, "N.m", "offset of the torque")
    startTime = Parameter(0.0, "s", "torque = offsetTorque for time < startTime")

    def torque_law(self):
        return self.offsetTorque + ca.if_else(time < self.startTime, 0.0, self.stepTorque)


class QuadraticSpeedDependentTorque(_PartialTorque):
    """Torque quadratic in the speed (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Sources.QuadraticSpeedDependentTorque;
    the support as :class:`_PartialTorque`'s)::

        phi = flange.phi - phi_support,  w = der(phi),  tau = -flange.tau
        tau = tau_nominal (w / w_nominal)^2                        TorqueDirection
        tau = tau_nominal (if w >= 0 then 1 else -1) (w / w_nominal)^2   otherwise

    ``tau_nominal < 0`` is a load (a fan); with ``TorqueDirection=False``
    it opposes the motion in both directions (``w |w|``: continuous with
    its first derivative, no event).  ``w`` is the speed relative to the
    support."""
    tau_nominal = Parameter(1.0, "N.m", "nominal torque (< 0: a load in the positive direction)")
    w_nominal = Parameter(1.0, "rad/s", "nominal speed", positive=True)

    def __init__(self, TorqueDirection=True, **kw):
        super().__init__(**kw)
        self.TorqueDirection = bool(TorqueDirection)

    def torque_law(self):
        x = self.w / self.w_nominal
        return self.tau_nominal * (x * x if self.TorqueDirection else x * ca.fabs(x))


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


class Clutch(_Modes):
    """Friction clutch (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Components.Clutch; the disc clutch
    "discClutch1" of Ebert (2015), ch. 8.2) between ``flange_a`` and
    ``flange_b``, engaged by the signal input ``f_normalized`` (0 = open,
    1 = fully closed)::

        phi_rel = flange_b.phi - flange_a.phi,  w_rel = der(phi_rel),  a_rel = der(w_rel)
        flange_b.tau = tau,  flange_a.tau = -tau
        fn = fn_max * f_normalized,  free = fn <= 0
        tau0 = mu0 * cgeo * fn,  tau0_max = peak * tau0
        tau = if locked then sa else if free then 0 else
              cgeo * fn * (if forward then mu_pos(w_rel) else -mu_pos(-w_rel))
        a_rel = if locked then 0 else if free then sa else
                if forward then sa - tau0_max else sa + tau0_max

    with the modes of Modelica's PartialFriction
    (:func:`~acausal2d.library.friction1d.partial_friction`): stuck
    (``locked``: ``a_rel = 0``, so ``w_rel`` stays at its value of the
    locking event, 0 to the event's location, while any torque up to
    ``tau0_max`` passes), sliding forward/backward, free; it breaks away
    when the torque needed to stay locked leaves ``[-tau0_max,
    tau0_max]``.  Outputs ``mode`` (-1 backward, 0 stuck, 1 forward, 2
    free), ``locked``, ``startForward``, ``startBackward``, ``sa``.

    The sliding friction coefficient is the constant ``mu`` or, as in
    Modelica, the table ``mu_pos`` (rows ``[w_rel, mu]``, linear, extrapolated
    by the last two points; give one of the two); ``mu0`` is its value at
    ``w_rel = 0``.  The defaults are Modelica's (``mu_pos = [0, 0.5]``,
    ``cgeo = 1``, ``fn_max``'s start value 1).  ``T_max = mu0 cgeo fn``
    (0 when free) is the sliding torque at ``w_rel = 0``.  As in
    Modelica's ``PartialCompliantWithRelativeStates`` the relative angle and
    speed are preferred states with ``phi_rel``'s nominal ``phi_nominal =
    1e-4``.

    ``law="zone"`` keeps the former stick zone ``|w_rel| < w_s``
    (:func:`~acausal2d.library.friction1d.friction_law`, one DAE without
    modes: ``tau = T_max sat(w_rel / w_s)`` for ``peak = 1`` and a constant
    ``mu``; it creeps at up to ``w_s`` while "stuck"); its mode outputs are
    then 0 inside the zone and the sign of ``w_rel`` outside.  ``w_small``
    is Modelica's reinit threshold, accepted for transcription (speeds
    never jump here, so it has no effect).
    """
    mu = Parameter(0.5, "1", "friction coefficient (constant; or give the table mu_pos)",
                   min=0.0)
    peak = Parameter(1.0, "1", "peak of the friction at w_rel = 0: tau0_max = peak tau0",
                     min=1.0)
    fn_max = Parameter(1.0, "N", "normal force at f_normalized = 1", min=0.0)
    cgeo = Parameter(1.0, "m", "effective friction radius x number of friction faces", positive=True)
    w_s = Parameter(1e-3, "rad/s", "width of the stick zone of law='zone'", positive=True)
    w_small = Parameter(1e10, "rad/s", "Modelica's reinit threshold (no effect here)",
                        positive=True)
    phi_rel = Variable(unit="rad", state_select="prefer", nominal=1e-4,
                       doc="relative angle flange_b - flange_a")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="relative angular velocity")
    a_rel = Variable(unit="rad/s2", doc="relative angular acceleration der(w_rel)")
    tau = Variable(unit="N.m", doc="friction torque acting on flange_b")
    fn = Variable(unit="N", doc="normal force fn_max f_normalized (free for fn <= 0)")
    T_max = Variable(unit="N.m", doc="sliding torque at w_rel = 0: mu0 cgeo fn, 0 when free")

    power_sides = (("flange_a",), ("flange_b",))

    def __init__(self, mu_pos=None, law="modes", phi_nominal=None, stateSelect=None, **kw):
        super().__init__(**kw)
        relative_states(self, "phi_rel", "w_rel", phi_nominal, stateSelect)
        if mu_pos is not None and "mu" in kw:
            raise ModelDefinitionError("%s: give mu (a constant) or mu_pos (a table), not both"
                                       % self.describe())
        self.law = check_law(self, law)
        self.refuse_zone_width()
        self.mu_pos = None if mu_pos is None else table_rows(self, "mu_pos", mu_pos, None)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.f_normalized = RealInput()

    def sliding_mode_advice(self):
        """What to change when the clutch's relations chatter."""
        if self.law == "modes":
            return ("%s switches its modes without progress; make its f_normalized input "
                    "continuous, or look for a relation elsewhere that moves it back and forth."
                    % self.describe())
        return ("%s models sticking itself with its stick zone |w_rel| < w_s: a zone this "
                "narrow cannot be resolved at the speeds of the run. Give it a larger w_s "
                "(the lock time changes by about J_eff w_s / T_max only), leave law='zone' "
                "(Modelica's modes), or make its f_normalized input continuous."
                % self.describe())

    def _mu(self, v):
        return self.mu if self.mu_pos is None else interpolate(self.mu_pos, v)

    def equations(self):
        free = self.fn <= 0
        mu0 = self._mu(0.0)
        common = [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                  self.w_rel == der(self.phi_rel), self.a_rel == der(self.w_rel),
                  self.fn == self.fn_max * self.f_normalized.u,
                  self.T_max == ca.if_else(free, 0.0, mu0 * self.cgeo * self.fn),
                  self.flange_b.tau == self.tau, self.flange_a.tau == -self.tau]
        if self.law == "zone":
            fn_pos = ca.fmax(self.fn, 0.0)
            common[4] = self.T_max == mu0 * self.cgeo * fn_pos

            def slide(v):
                return self.T_max if self.mu_pos is None else \
                    interpolate(self.mu_pos, v) * self.cgeo * fn_pos
            return common + zone_law(self, self.tau, self.w_rel, self.w_s,
                                     self.peak * self.T_max, slide)
        tau0 = mu0 * self.cgeo * self.fn
        tau, eqs, _ = partial_friction(self, self.w_rel, self.a_rel, self.sa, free, tau0,
                                    self.peak * tau0,
                                    lambda v: self.cgeo * self.fn * self._mu(v))
        return common + eqs + [self.tau == tau]


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
from acausal2d.library.gears import (IdealGear, IdealGearR2T, IdealPlanetary,  # noqa: E402,F401
                                     IdealRollingWheel)
from acausal2d.library.friction1d import BearingFriction, Brake, OneWayClutch  # noqa: E402,F401
