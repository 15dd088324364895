"""Translational friction elements with stiction (Modelica Standard Library
4.0, Modelica.Mechanics.Translational.Components.SupportFriction and
MassWithStopAndFriction), on the modes and laws of :mod:`acausal2d.library.friction1d`
(Modelica's PartialFriction by default, ``law="zone"`` for the stick
zone)."""
import casadi as ca

from acausal2d import der, Parameter, TranslationalFlange, Variable
from acausal2d.language.symbols import define_latch, latch
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.friction1d import (_Friction, _named, interpolate, partial_friction,
                                          table_rows, zone_law)


class SupportFriction(_Friction):
    """Coulomb friction between a flange and its support (Modelica Standard
    Library 4.0, Modelica.Mechanics.Translational.Components.SupportFriction)::

        s = flange_a.s - support.s,  flange_b.s = flange_a.s
        v = der(s),  a = der(v)
        0 = flange_a.f + flange_b.f - f
        f0 = f_pos(v = 0),  f0_max = peak * f0,  free = false
        f = if locked then sa else if forward then f_pos(v) else -f_pos(-v)

    with the modes of Modelica's PartialFriction (:func:`partial_friction`).
    ``f_pos``: rows ``[v, f]`` (default ``[[0, 1]]``).  ``law="zone"``: the
    stick zone ``|v| < v_s`` instead; ``v_small`` is accepted and has no
    effect (no velocity jumps)."""
    peak = Parameter(1.0, "1", "peak of the friction at v = 0: f0_max = peak * f0", min=1.0)
    v_s = Parameter(1e-4, "m/s", "width of the stick zone of law='zone'", positive=True)
    v_small = Parameter(1e-3, "m/s", "Modelica's reinit threshold (no effect)", positive=True)
    s = Variable(unit="m", doc="position of the flanges relative to the support")
    v = Variable(unit="m/s", doc="velocity relative to the support")
    a = Variable(unit="m/s2", doc="acceleration relative to the support")
    f = Variable(unit="N", doc="friction force (flange_a.f + flange_b.f)")
    ZONE = "v_s"

    def __init__(self, f_pos=None, **kw):
        super().__init__(**kw)
        self.f_pos = table_rows(self, "f_pos", f_pos, [(0.0, 1.0)])
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()
        self.support = TranslationalFlange(ground={"s": 0.0}, doc="support (fixed if unconnected)")

    def tau_name(self):
        """The friction force."""
        return self.f

    def equations(self):
        f0 = interpolate(self.f_pos, 0.0)
        return [self.s == self.flange_a.s - self.support.s, self.flange_b.s == self.flange_a.s,
                self.v == der(self.s), self.a == der(self.v),
                0 == self.flange_a.f + self.flange_b.f - self.f,
                self.support.f == -self.flange_a.f - self.flange_b.f] + self.law_equations(
            self.v, self.a, 0.0, f0, lambda v: interpolate(self.f_pos, v))


class MassWithStopAndFriction(_Friction):
    """Sliding mass with hard stops and Stribeck friction (Modelica Standard
    Library 4.0, Modelica.Mechanics.Translational.Components.MassWithStopAndFriction)::

        flange_a.s = s - L/2,  flange_b.s = s + L/2,  v = der(s),  a = der(v)
        0 = flange_a.f + flange_b.f - f - m * der(v)
        f0 = F_Coulomb + F_Stribeck,  f0_max = 1.001 * f0
        free = f0 <= 0 and F_prop <= 0 and smin + L/2 < s < smax - L/2
        f = if locked then sa else if free then 0 else
            F_prop * v + sign(v) * (F_Coulomb + F_Stribeck * exp(-fexp * |v|))
        stopped = if s <= smin + L/2 then -1 else if s >= smax - L/2 then +1 else 0
        when stopped <> 0 then reinit(s, stop position); reinit(v, 0); end when

    with the modes of Modelica's PartialFrictionWithStop
    (:func:`partial_friction`): starting or sliding towards a stop the mass
    is at is forbidden.  At a stop ``s`` and ``v`` are re-initialised (the
    impact, an event), the mass is locked there (``v = 0``, any force
    into the stop passes) and leaves it when the force pulls it away by
    more than ``f0_max``.  ``stopped`` comes from a latch per stop: on when
    the end reaches the stop, off when the mass starts sliding away from it.  Start with
    ``s=start(..., fixed=True)``, ``v=start(..., fixed=True)`` within the
    stops.  ``law="zone"``: the stick zone ``|v| < v_s`` and no stops (a
    run reaching a stop ends with an error)."""
    peak = Parameter(1.001, "1", "f0_max / f0 (Modelica's fixed 1.001)", min=1.0)
    m = Parameter(1.0, "kg", "mass", min=0.0)
    L = Parameter(0.0, "m", "length of the mass (distance of the flanges)", min=0.0)
    F_prop = Parameter(1.0, "N.s/m", "velocity dependent friction", min=0.0)
    F_Coulomb = Parameter(5.0, "N", "constant friction: Coulomb force")
    F_Stribeck = Parameter(10.0, "N", "Stribeck effect")
    fexp = Parameter(2.0, "s/m", "exponential decay", min=0.0)
    smax = Parameter(25.0, "m", "right stop for (the right end of) the mass")
    smin = Parameter(-25.0, "m", "left stop for (the left end of) the mass")
    v_s = Parameter(1e-4, "m/s", "width of the stick zone of law='zone'", positive=True)
    v_small = Parameter(1e-3, "m/s", "Modelica's reinit threshold (no effect)", positive=True)
    s = Variable(unit="m", state_select="always", doc="position of the centre")
    v = Variable(unit="m/s", state_select="always", doc="velocity")
    a = Variable(unit="m/s2", doc="acceleration")
    f = Variable(unit="N", doc="friction force (against v)")
    stopped = Variable(unit="1", doc="-1 at the stop smin, +1 at smax, 0 between")
    at_stop = Variable(unit="1", doc="1 while at a stop (|stopped|)")
    s_stop = Variable(unit="m", doc="the position at the stop reached")
    ZONE = "v_s"

    def __init__(self, **kw):
        super().__init__(**kw)
        if self.parameter_value("smax") - self.parameter_value("smin") <= self.parameter_value("L"):
            raise ModelDefinitionError("%s: the stops smin = %g, smax = %g leave no room for the "
                                       "length L = %g; give smax - smin > L" % (
                                           self.describe(), self.parameter_value("smin"),
                                           self.parameter_value("smax"),
                                           self.parameter_value("L")))
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()

    def tau_name(self):
        """The friction force."""
        return self.f

    def assertions(self):
        """law='zone' has no stops: reaching one ends the run."""
        if self.law == "modes":
            return []
        return [("at_stop", "reached a hard stop (s - L/2 <= smin or s + L/2 >= smax); "
                            "law='zone' does not model the stops: leave law='zone' (Modelica's "
                            "modes, which stop the mass there)")]

    def reinits(self):
        """At a stop: ``s`` to the stop, ``v`` to 0 (Modelica's reinit)."""
        return [("at_stop", "s", "s_stop"), ("at_stop", "v", 0.0)] if self.law == "modes" \
            else []

    def start_checks(self, context):
        """The mass starts within its stops."""
        def check(value):
            s, L = value(self, "s"), self.parameter_value("L")
            if s - L / 2 < self.parameter_value("smin") or \
                    s + L / 2 > self.parameter_value("smax"):
                return ("starts at s = %g with its ends outside the stops smin = %g, smax = %g "
                        "(L = %g); give a start value of s between smin + L/2 and smax - L/2"
                        % (s, self.parameter_value("smin"), self.parameter_value("smax"), L))
            return None
        return [check]

    def equations(self):
        f0 = self.F_Coulomb + self.F_Stribeck
        slide = lambda v: self.F_prop * v + self.F_Coulomb \
            + self.F_Stribeck * ca.exp(-self.fexp * v)  # noqa: E731
        right, left = self.smax - self.L / 2, self.smin + self.L / 2
        common = [self.flange_a.s == self.s - self.L / 2, self.flange_b.s == self.s + self.L / 2,
                  self.v == der(self.s), self.a == der(self.v),
                  0 == self.flange_a.f + self.flange_b.f - self.f - self.m * self.a]
        if self.law == "zone":
            at = ca.if_else(self.s <= left, -1.0, ca.if_else(self.s >= right, 1.0, 0.0))
            return common + zone_law(self, self.f, self.v, self.v_s, self.peak * f0, slide) + [
                self.stopped == at, self.at_stop == at * at, self.s_stop == self.s]
        hi, lo = latch(_named(self, "at_smax")), latch(_named(self, "at_smin"))
        free = (f0 <= 0) * (self.F_prop <= 0) * (1 - hi) * (1 - lo)
        f, eqs, (fw, _, bw, _) = partial_friction(self, self.v, self.a, self.sa, free, f0,
                                                  self.peak * f0, slide, block=(hi, lo))
        define_latch(hi, ca.if_else(hi, 0.5 - bw, self.s - right),
                     "hard stop smax reached (%s)" % _named(self, "stopped = 1"),
                     g_start=self.s - right)
        define_latch(lo, ca.if_else(lo, 0.5 - fw, left - self.s),
                     "hard stop smin reached (%s)" % _named(self, "stopped = -1"),
                     g_start=left - self.s)
        return common + eqs + [self.f == f, self.stopped == hi - lo,
                               self.at_stop == hi + lo,
                               self.s_stop == ca.if_else(hi, right, left)]
