"""1D friction elements with stiction (Modelica.Mechanics.Rotational.
Components.BearingFriction, Brake, OneWayClutch and Modelica.Mechanics.
Translational.Components.SupportFriction, MSL 4.0), and the friction law
they share with :class:`acausal2d.library.rotational.Clutch`.

Modelica's PartialFriction switches between the modes Forward, Stuck,
Backward and Free by a state machine: stuck while the torque needed to
keep the relative speed at 0 stays below ``tau0_max = peak * tau0``, then
sliding with the characteristic ``tau(w)`` (a table ``[w, tau]`` or
``[w, mu]``).  acausal2d keeps one DAE for the whole run, so sticking is a
stick zone ``|w| < w_s`` (Ebert 2015, ch. 8.2's discClutch, see
docs/guide/friction.md) with the same thresholds::

    x = w / w_s,  sat = min(max(x, -1), 1),  e = (x - sat) * sat   (= |x| - 1 outside, 0 inside)
    tau = sat * (tau0_max + (tau_slide(|w|) - tau0_max) * (1 - exp(-e^2)))

Inside the zone the element is a stiff viscous coupling ``tau0_max / w_s``:
stuck (creep ``|w| <= w_s``) as long as the torque it has to pass stays
below ``tau0_max``; leaving the zone (an event) the torque falls from the
breakaway value ``tau0_max`` to the sliding characteristic within a few
``w_s`` of speed, i.e. at once on the time scale of the motion; entering it
is locking.  Lock and unlock times match Modelica's to about ``J_eff w_s /
tau0`` (the lag of the zone).  With ``peak = 1`` and a constant
characteristic the law is the clutch's Karnopp saturation ``tau0 sat``.

``w_small`` (Modelica: a speed beyond which a velocity jump by ``reinit``
starts sliding at once) is accepted so that models transcribe one to one;
speeds in acausal2d never jump, so it changes nothing."""
import casadi as ca

from acausal2d import (Component, der, Parameter, RealInput, RotationalFlange,
                       TranslationalFlange, Variable)
from acausal2d.errors import ModelDefinitionError


def _pairs(comp, name, table):
    """Rows of ``table`` as float pairs (a single row may be given flat)."""
    try:
        if len(table) and isinstance(table[0], (int, float)):
            table = [table]
        if any(len(row) != 2 for row in table):
            raise ValueError(table)
        return [(float(x), float(y)) for x, y in table]
    except (TypeError, ValueError):
        raise ModelDefinitionError("%s: %s must be a table of rows [x, y] (Modelica's %s[:, 2]), "
                                   "not %r" % (type(comp).__name__, name, name, table)) from None


def table_rows(comp, name, table, default):
    """``table`` (rows ``[x, y]``, x strictly increasing, starting at x <=
    0, values >= 0: a positive sliding characteristic) as a tuple of float
    pairs; ``default`` if None.  Errors name the component and the
    argument."""
    rows = _pairs(comp, name, default if table is None else table)
    xs = [r[0] for r in rows]
    if not rows or any(b <= a for a, b in zip(xs, xs[1:])) or \
            not all(abs(v) < float("inf") for r in rows for v in r):
        raise ModelDefinitionError("%s: %s needs finite rows with strictly increasing first "
                                   "column, got %r" % (type(comp).__name__, name, table))
    if any(y < 0 for _, y in rows) or xs[0] > 0:
        raise ModelDefinitionError("%s: %s is the positive sliding characteristic: it must "
                                   "start at x <= 0 and have values >= 0, got %r"
                                   % (type(comp).__name__, name, table))
    return tuple(rows)


def interpolate(rows, v):
    """Linear interpolation in ``rows`` with linear extrapolation by the
    first/last two points (CombiTable1Ds' LinearSegments with
    Extrapolation.LastTwoPoints); a single row is a constant.  Each
    breakpoint is a relation (an event), the curve is continuous."""
    if len(rows) == 1:
        return rows[0][1]
    slopes = [(y1 - y0) / (x1 - x0) for (x0, y0), (x1, y1) in zip(rows, rows[1:])]
    out = rows[0][1] + slopes[0] * (v - rows[0][0])
    for k in range(1, len(slopes)):
        out = out + (slopes[k] - slopes[k - 1]) * ca.fmax(v - rows[k][0], 0)
    return out


def friction_law(w, w_s, tau0_max, tau_slide):
    """Friction torque for the relative speed ``w``: the stick zone of
    width ``w_s`` up to ``tau0_max``, outside it ``sign(w) tau_slide(|w|)``
    (``tau_slide``: a function of the speed magnitude), joined continuously
    (module docstring).  ``exp(-e^2)`` stays bounded where a held relation
    value makes ``e`` negative (between a crossing and its event), which
    ``exp(-e)`` would overflow."""
    x = w / w_s
    sat = ca.fmin(ca.fmax(x, -1.0), 1.0)
    e = (x - sat) * sat
    return sat * (tau0_max + (tau_slide(w * sat) - tau0_max) * (1 - ca.exp(-e * e)))


class _Friction(Component):
    """Parameters every friction element has: peak, w_s, w_small."""
    peak = Parameter(1.0, "1", "peak of the friction at w = 0: tau0_max = peak * tau0", min=1.0)
    w_small = Parameter(1e10, "rad/s", "Modelica's reinit threshold (no effect, see module)",
                        positive=True)

    ZONE = "w_s"

    def sliding_mode_advice(self):
        """Sticking is modelled by the stick zone (w_s, or v_s for the
        translational elements)."""
        return ("%s models sticking itself with its stick zone of width %s: a zone this narrow "
                "cannot be resolved at the speeds of the run. Give it a larger %s, or make "
                "its inputs continuous." % (self.describe(), self.ZONE, self.ZONE))


class _SupportFriction(_Friction):
    """Two rigidly coupled flanges and the support (Modelica's
    PartialElementaryTwoFlangesAndSupport2): the friction acts between the
    shaft and the support (grounded at 0 if unconnected)."""
    phi = Variable(unit="rad", doc="angle of the flanges relative to the support")
    w = Variable(unit="rad/s", doc="angular velocity relative to the support")
    a = Variable(unit="rad/s2", doc="angular acceleration relative to the support")
    tau = Variable(unit="N.m", doc="friction torque (flange_a.tau + flange_b.tau)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.support = RotationalFlange(ground={"phi": 0.0}, doc="housing (fixed if unconnected)")

    def _kinematics(self, tau):
        return [self.phi == self.flange_a.phi - self.support.phi,
                self.flange_b.phi == self.flange_a.phi,
                self.w == der(self.phi), self.a == der(self.w),
                0 == self.flange_a.tau + self.flange_b.tau - self.tau,
                self.support.tau == -self.flange_a.tau - self.flange_b.tau,
                self.tau == tau]


class BearingFriction(_SupportFriction):
    """Coulomb friction in a bearing (Modelica.Mechanics.Rotational.
    Components.BearingFriction)::

        phi = flange_a.phi - support.phi,  flange_b.phi = flange_a.phi
        w = der(phi),  a = der(w)
        0 = flange_a.tau + flange_b.tau - tau
        tau0 = tau_pos(w = 0),  tau0_max = peak * tau0
        tau = tau_pos(w) forward, -tau_pos(-w) backward, stuck below tau0_max

    ``tau_pos``: rows ``[w, tau]`` of the positive sliding characteristic
    (default ``[[0, 1]]``, a constant torque of 1 N m).  Sticking by the
    stick zone ``w_s`` (module docstring).  ``tau`` is the torque the
    flanges pass into the friction (it has the sign of ``w``)."""
    w_s = Parameter(1e-4, "rad/s", "width of the stick zone (creep speed)", positive=True)

    def __init__(self, tau_pos=None, **kw):
        super().__init__(**kw)
        self.tau_pos = table_rows(self, "tau_pos", tau_pos, [(0.0, 1.0)])

    def equations(self):
        tau0 = interpolate(self.tau_pos, 0.0)
        return self._kinematics(friction_law(self.w, self.w_s, self.peak * tau0,
                                             lambda v: interpolate(self.tau_pos, v)))


class Brake(_SupportFriction):
    """Brake based on Coulomb friction (Modelica.Mechanics.Rotational.
    Components.Brake)::

        phi = flange_a.phi - support.phi,  flange_b.phi = flange_a.phi
        w = der(phi),  a = der(w)
        0 = flange_a.tau + flange_b.tau - tau
        fn = fn_max * f_normalized,  free = fn <= 0
        tau0 = mu0 * cgeo * fn,  mu0 = mu_pos(w = 0),  tau0_max = peak * tau0
        tau = cgeo * fn * mu_pos(w) forward (-mu_pos(-w) backward), stuck below tau0_max

    ``mu_pos``: rows ``[w, mu]`` (default ``[[0, 0.5]]``).  The brake holds
    the shaft (creep ``|w| <= w_s``) while the torque on it stays below
    ``peak * mu0 * cgeo * fn``; a normal force ``fn <= 0`` leaves it free."""
    cgeo = Parameter(1.0, "m", "geometry constant (effective radius x friction faces)", min=0.0)
    fn_max = Parameter(1.0, "N", "maximum normal force", min=0.0)
    w_s = Parameter(1e-4, "rad/s", "width of the stick zone (creep speed)", positive=True)
    fn = Variable(unit="N", doc="normal force fn_max f_normalized")
    tau0_max = Variable(unit="N.m", doc="breakaway torque peak mu0 cgeo max(fn, 0)")

    def __init__(self, mu_pos=None, **kw):
        super().__init__(**kw)
        self.mu_pos = table_rows(self, "mu_pos", mu_pos, [(0.0, 0.5)])
        self.f_normalized = RealInput(doc="normalized normal force (0..1)")

    def equations(self):
        fn_pos = ca.fmax(self.fn, 0.0)
        mu0 = interpolate(self.mu_pos, 0.0)
        slide = lambda v: self.cgeo * fn_pos * interpolate(self.mu_pos, v)  # noqa: E731
        return self._kinematics(friction_law(self.w, self.w_s, self.tau0_max, slide)) + [
            self.fn == self.fn_max * self.f_normalized.u,
            self.tau0_max == self.peak * mu0 * self.cgeo * fn_pos]


class OneWayClutch(_Friction):
    """Parallel connection of a freewheel and a clutch (Modelica.Mechanics.
    Rotational.Components.OneWayClutch)::

        phi_rel = flange_b.phi - flange_a.phi,  w_rel = der(phi_rel),  a_rel = der(w_rel)
        flange_b.tau = tau,  flange_a.tau = -tau
        fn = if f_normalized <= 0 then 0 else fn_max * f_normalized
        tau0 = mu0 * cgeo * fn,  tau0_max = peak * tau0
        stuck = locked or w_rel <= 0
        tau = cgeo * fn * mu_pos(w_rel) while w_rel > 0 (sliding forward)

    The freewheel locks the backward direction: ``w_rel = flange_b.w -
    flange_a.w`` never becomes negative (Modelica: start with ``w_rel >=
    0``); forward, flange_b overruns flange_a against the clutch's friction
    (none when open), and from rest it starts sliding forward once the
    torque exceeds ``tau0_max``.  Regularised (module docstring): forward
    the stick zone ``w_s`` of the clutch; backward a stiff viscous lock
    ``tau = tau_lock w_rel / w_s`` with ``tau_lock = peak mu0 cgeo fn_max``,
    whatever the normal force (so ``fn_max * cgeo * mu0`` must be > 0): the
    backward creep ``-w_rel`` stays below ``w_s |tau| / tau_lock``."""
    cgeo = Parameter(1.0, "m", "geometry constant (effective radius x friction faces)", min=0.0)
    fn_max = Parameter(1.0, "N", "maximum normal force", positive=True)
    w_s = Parameter(1e-4, "rad/s", "width of the stick zones (creep speed)", positive=True)
    phi_rel = Variable(unit="rad", state_select="prefer", doc="relative angle flange_b - flange_a")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="relative angular velocity")
    a_rel = Variable(unit="rad/s2", doc="relative angular acceleration")
    tau = Variable(unit="N.m", doc="torque acting on flange_b")
    fn = Variable(unit="N", doc="normal force (0 if f_normalized <= 0)")

    def __init__(self, mu_pos=None, **kw):
        super().__init__(**kw)
        self.mu_pos = table_rows(self, "mu_pos", mu_pos, [(0.0, 0.5)])
        if not interpolate(self.mu_pos, 0.0) * self.parameter_value("cgeo") > 0:
            raise ModelDefinitionError(
                "%s: the freewheel's lock torque peak mu0 cgeo fn_max is 0 (mu_pos at w = 0 is "
                "%g, cgeo = %g); give mu_pos(0) > 0 and cgeo > 0" % (
                    self.describe(), interpolate(self.mu_pos, 0.0),
                    self.parameter_value("cgeo")))
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.f_normalized = RealInput(doc="normalized normal force (0..1)")

    def equations(self):
        mu0 = interpolate(self.mu_pos, 0.0)
        slide = lambda v: self.cgeo * self.fn * interpolate(self.mu_pos, v)  # noqa: E731
        forward = friction_law(ca.fmax(self.w_rel, 0.0), self.w_s,
                               self.peak * mu0 * self.cgeo * self.fn, slide)
        lock = self.peak * mu0 * self.cgeo * self.fn_max / self.w_s * ca.fmin(self.w_rel, 0.0)
        return [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                self.w_rel == der(self.phi_rel), self.a_rel == der(self.w_rel),
                self.fn == self.fn_max * ca.fmax(self.f_normalized.u, 0.0),
                self.tau == forward + lock,
                self.flange_b.tau == self.tau, self.flange_a.tau == -self.tau]


class SupportFriction(Component):
    """Coulomb friction between a flange and its support (Modelica.Mechanics.
    Translational.Components.SupportFriction)::

        s = flange_a.s - support.s,  flange_b.s = flange_a.s
        v = der(s),  a = der(v)
        0 = flange_a.f + flange_b.f - f
        f0 = f_pos(v = 0),  f0_max = peak * f0
        f = f_pos(v) forward, -f_pos(-v) backward, stuck below f0_max

    ``f_pos``: rows ``[v, f]`` (default ``[[0, 1]]``).  Sticking by the
    stick zone ``|v| < v_s`` (module docstring); ``v_small`` is accepted
    and has no effect (no velocity jumps)."""
    peak = Parameter(1.0, "1", "peak of the friction at v = 0: f0_max = peak * f0", min=1.0)
    v_s = Parameter(1e-4, "m/s", "width of the stick zone (creep speed)", positive=True)
    v_small = Parameter(1e-3, "m/s", "Modelica's reinit threshold (no effect)", positive=True)
    s = Variable(unit="m", doc="position of the flanges relative to the support")
    v = Variable(unit="m/s", doc="velocity relative to the support")
    a = Variable(unit="m/s2", doc="acceleration relative to the support")
    f = Variable(unit="N", doc="friction force (flange_a.f + flange_b.f)")
    ZONE = "v_s"
    sliding_mode_advice = _Friction.sliding_mode_advice

    def __init__(self, f_pos=None, **kw):
        super().__init__(**kw)
        self.f_pos = table_rows(self, "f_pos", f_pos, [(0.0, 1.0)])
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()
        self.support = TranslationalFlange(ground={"s": 0.0}, doc="support (fixed if unconnected)")

    def equations(self):
        f0 = interpolate(self.f_pos, 0.0)
        f = friction_law(self.v, self.v_s, self.peak * f0, lambda v: interpolate(self.f_pos, v))
        return [self.s == self.flange_a.s - self.support.s, self.flange_b.s == self.flange_a.s,
                self.v == der(self.s), self.a == der(self.v),
                0 == self.flange_a.f + self.flange_b.f - self.f,
                self.support.f == -self.flange_a.f - self.flange_b.f, self.f == f]


class MassWithStopAndFriction(Component):
    """Sliding mass with Stribeck friction (Modelica.Mechanics.Translational.
    Components.MassWithStopAndFriction, MSL 4.0), friction part::

        flange_a.s = s - L/2,  flange_b.s = s + L/2,  v = der(s),  a = der(v)
        0 = flange_a.f + flange_b.f - f - m * der(v)
        f0 = F_Coulomb + F_Stribeck,  f0_max = 1.001 * f0
        f = F_prop * v + sign(v) * (F_Coulomb + F_Stribeck * exp(-fexp * |v|))  sliding,
            stuck (f from the balance) while |f| <= f0_max

    Sticking by the stick zone ``|v| < v_s`` (module docstring).  The hard
    stops at ``smin`` and ``smax`` (Modelica: ``s`` and ``v`` re-initialised
    at the stop, an impact) are not modelled: a run in which the mass's end
    reaches a stop (``s - L/2 <= smin`` or ``s + L/2 >= smax``) ends there
    with an error naming the element; the motion up to it is Modelica's.
    Start with ``s=start(..., fixed=True)``, ``v=start(..., fixed=True)``."""
    m = Parameter(1.0, "kg", "mass", min=0.0)
    L = Parameter(0.0, "m", "length of the mass (distance of the flanges)", min=0.0)
    F_prop = Parameter(1.0, "N.s/m", "velocity dependent friction", min=0.0)
    F_Coulomb = Parameter(5.0, "N", "constant friction: Coulomb force")
    F_Stribeck = Parameter(10.0, "N", "Stribeck effect")
    fexp = Parameter(2.0, "s/m", "exponential decay", min=0.0)
    smax = Parameter(25.0, "m", "right stop for (the right end of) the mass")
    smin = Parameter(-25.0, "m", "left stop for (the left end of) the mass")
    v_s = Parameter(1e-4, "m/s", "width of the stick zone (creep speed)", positive=True)
    v_small = Parameter(1e-3, "m/s", "Modelica's reinit threshold (no effect)", positive=True)
    s = Variable(unit="m", state_select="always", doc="position of the centre")
    v = Variable(unit="m/s", state_select="always", doc="velocity")
    a = Variable(unit="m/s2", doc="acceleration")
    f = Variable(unit="N", doc="friction force (against v)")
    stopped = Variable(unit="1", doc="1 when an end of the mass is at a stop")
    ZONE = "v_s"
    sliding_mode_advice = _Friction.sliding_mode_advice

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

    def assertions(self):
        """Reaching a hard stop ends the run (the impact is not modelled)."""
        return [("stopped", "reached a hard stop (s - L/2 <= smin or s + L/2 >= smax): the stops' "
                            "impact (Modelica's reinit of s and v) is not modelled; give smin/smax "
                            "outside the travel, or limit the travel by a spring or a force")]

    def equations(self):
        f0 = self.F_Coulomb + self.F_Stribeck
        slide = lambda v: self.F_prop * v + self.F_Coulomb \
            + self.F_Stribeck * ca.exp(-self.fexp * v)  # noqa: E731
        at_stop = ca.if_else(self.s - self.L / 2 <= self.smin, 1.0,
                             ca.if_else(self.s + self.L / 2 >= self.smax, 1.0, 0.0))
        return [self.flange_a.s == self.s - self.L / 2, self.flange_b.s == self.s + self.L / 2,
                self.v == der(self.s), self.a == der(self.v),
                0 == self.flange_a.f + self.flange_b.f - self.f - self.m * self.a,
                self.f == friction_law(self.v, self.v_s, 1.001 * f0, slide),
                self.stopped == at_stop]
