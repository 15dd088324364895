"""1D friction elements with stiction (Modelica Standard Library 4.0,
Modelica.Mechanics.Rotational.Components.BearingFriction, Brake,
OneWayClutch), and the friction laws they share with
:class:`acausal2d.library.rotational.Clutch` and the translational elements
of :mod:`acausal2d.library.friction_translational`.

By default (``law="modes"``) they compute Modelica's PartialFriction: the
modes Forward, Stuck, Backward and Free of its state machine are held by
latches (:func:`mode_latches`, :func:`partial_friction`); stuck, the
relative acceleration is 0 and any torque up to ``tau0_max = peak * tau0``
passes; sliding, the characteristic ``tau(w)`` (a table ``[w, tau]`` or
``[w, mu]``) acts.

``law="zone"`` keeps one DAE without modes: a stick zone ``|w| < w_s``
(Ebert 2015, ch. 8.2's discClutch) with the same thresholds::

    x = w / w_s,  sat = min(max(x, -1), 1),  e = (x - sat) * sat   (= |x| - 1 outside, 0 inside)
    tau = sat * (tau0_max + (tau_slide(|w|) - tau0_max) * (1 - exp(-e^2)))

Inside the zone the element is a stiff viscous coupling ``tau0_max / w_s``:
stuck (creep ``|w| <= w_s``) as long as the torque it has to pass stays
below ``tau0_max``; leaving the zone (an event) the torque falls from the
breakaway value ``tau0_max`` to the sliding characteristic within a few
``w_s`` of speed; entering it is locking.  Lock and unlock times match
Modelica's to about ``J_eff w_s / tau0`` (the lag of the zone).

``w_small`` (Modelica: a speed beyond which a velocity jump by ``reinit``
starts sliding at once) is accepted so that models transcribe one to one;
it changes nothing."""
import casadi as ca

from acausal2d import (Component, der, Parameter, RealInput, RotationalFlange,
                       Variable)
from acausal2d.language.symbols import define_latch, latch
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.relative_states import relative_states


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


def zone_torque(w, w_s, tau0_max, tau_slide):
    """(torque, sat) of the stick-zone law for the relative speed ``w``:
    the stick zone of width ``w_s`` up to ``tau0_max``, outside it
    ``sign(w) tau_slide(|w|)`` (``tau_slide``: a function of the speed
    magnitude), joined continuously (module docstring); ``sat`` is
    ``w / w_s`` clipped to [-1, 1].  ``exp(-e^2)`` stays bounded where a
    held relation value makes ``e`` negative (between a crossing and its
    event), which ``exp(-e)`` would overflow."""
    x = w / w_s
    sat = ca.fmin(ca.fmax(x, -1.0), 1.0)
    e = (x - sat) * sat
    return sat * (tau0_max + (tau_slide(w * sat) - tau0_max) * (1 - ca.exp(-e * e))), sat


def friction_law(w, w_s, tau0_max, tau_slide):
    """The friction torque of :func:`zone_torque`."""
    return zone_torque(w, w_s, tau0_max, tau_slide)[0]


LAWS = ("modes", "zone")


def check_law(comp, law):
    """``law`` if it is one of :data:`LAWS`, else an error naming the component."""
    if law not in LAWS:
        raise ModelDefinitionError("%s: law must be 'modes' (Modelica's PartialFriction) or "
                                   "'zone' (a stick zone of width w_s), not %r"
                                   % (type(comp).__name__, law))
    return law


def _named(comp, name):
    return "%s.%s" % (comp.path, name) if comp.path else name


def mode_latches(comp, w, sa, free, tau0, tau0_max, block=(None, None)):
    """The latches of Modelica's PartialFriction state machine for the
    relative speed ``w`` and the path parameter ``sa``: ``(fw, wp, bw, wn)``
    = sliding forward (startForward or Forward), forward with ``w`` > 0
    reached (Forward), and the same backward.  ``free``: the relation (0/1)
    of an inactive element; ``block``: relations (0/1) that forbid sliding
    forward/backward (the hard stops of MassWithStopAndFriction), or None.

    Crossing functions (a latch is 1 where its function is > 0; the
    function depends on the latch values, which gives the hysteresis of
    Modelica's ``pre(mode)``)::

        fw = 1:  free: w;  Forward (wp): w;  startForward: sa - tau0
        fw = 0:  free: w;  backward: -1;     stuck: sa - tau0_max
        wp:      fw: w;    else -1
        (bw, wn mirrored: -w, -sa - tau0, -sa - tau0_max)

    A blocked direction has -1.  At the start (Modelica's ``initial() and
    w > 0``) fw and wp are ``w > 0``, bw and wn ``w < 0``.  While stuck no
    crossing function is near zero by rounding: the speed, held constant
    there, is watched by none of them."""
    fw, wp, bw, wn = (latch(_named(comp, n)) for n in
                      ("sliding_forward", "forward", "sliding_backward", "backward"))

    def side(mine, reached, other, sgn):
        g_on = ca.if_else(free, sgn * w, ca.if_else(reached, sgn * w, sgn * sa - tau0))
        g_off = ca.if_else(free, sgn * w, ca.if_else(other, -1.0, sgn * sa - tau0_max))
        return ca.if_else(mine, g_on, g_off)
    gs = [side(fw, wp, bw, 1.0), ca.if_else(fw, w, -1.0),
          side(bw, wn, fw, -1.0), ca.if_else(bw, -w, -1.0)]
    for k, stop in ((0, block[0]), (2, block[1])):
        if stop is not None:
            gs[k] = ca.if_else(stop, -1.0, gs[k])
    texts = ("sliding forward (%s)" % _named(comp, "startForward/Forward"),
             "forward speed reached (%s)" % _named(comp, "mode = Forward"),
             "sliding backward (%s)" % _named(comp, "startBackward/Backward"),
             "backward speed reached (%s)" % _named(comp, "mode = Backward"))
    for sym, g, sgn, text in zip((fw, wp, bw, wn), gs, (1, 1, -1, -1), texts):
        define_latch(sym, g, text, g_start=sgn * w)
    return fw, wp, bw, wn


def partial_friction(comp, w, a, sa, free, tau0, tau0_max, slide, block=(None, None)):
    """Modelica's PartialFriction (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Interfaces.PartialFriction) for the
    relative speed ``w``, its acceleration ``a`` and the path parameter
    ``sa`` (an unknown of the element); returns ``(tau, equations,
    latches)``: the friction torque (force) as an expression, the latches
    of :func:`mode_latches` and the equations of ``a`` and of the mode outputs
    ``mode``, ``locked``, ``startForward``, ``startBackward`` (variables
    of ``comp``)::

        locked = not free and not (Forward or startForward or Backward or startBackward)
        a = if locked then 0 else if free then sa else if forward then sa - tau0_max
            else sa + tau0_max
        tau = if locked then sa else if free then 0 else if forward then slide(w)
              else -slide(-w)
        mode = 2 free, 1 Forward, -1 Backward, 0 stuck (locked or starting)

    ``slide(v)``: the sliding torque for the forward speed ``v >= 0``.
    While locked ``a`` is 0: ``w`` keeps the value of the locking event
    (0 up to its location), any torque up to ``tau0_max`` passes; it slides
    when ``sa`` leaves [-tau0_max, tau0_max].  Latches: :func:`mode_latches`."""
    fw, wp, bw, wn = mode_latches(comp, w, sa, free, tau0, tau0_max, block)
    moving = ca.if_else(fw, 1.0, bw)
    locked = (1 - free) * (1 - moving)
    tau = ca.if_else(locked, sa, ca.if_else(free, 0.0, ca.if_else(fw, slide(w), -slide(-w))))
    acc = ca.if_else(locked, 0.0, ca.if_else(free, sa, ca.if_else(fw, sa - tau0_max,
                                                                   sa + tau0_max)))
    mode = ca.if_else(free, 2.0, fw * wp - bw * wn)
    return tau, [a == acc, comp.mode == mode, comp.locked == locked,
                 comp.startForward == (1 - free) * fw * (1 - wp),
                 comp.startBackward == (1 - free) * bw * (1 - wn)], (fw, wp, bw, wn)


class _Modes(Component):
    """The mode outputs of Modelica's PartialFriction (MSL's names and codes)."""
    sa = Variable(unit="1", doc="path parameter: torque (force) while locked, else "
                                "acceleration + tau0_max")
    mode = Variable(unit="1", doc="-1 Backward, 0 Stuck (locked or starting), 1 Forward, 2 Free")
    locked = Variable(unit="1", doc="1 if the speed is 0 and not sliding")
    startForward = Variable(unit="1", doc="1 while starting to slide forward from rest")
    startBackward = Variable(unit="1", doc="1 while starting to slide backward from rest")

    MODE_WORDS = {-1: "sliding backward", 0: "stuck", 1: "sliding forward", 2: "free"}
    """The words of the mode codes, for events."""
    ZONE = "w_s"
    """The parameter of the stick zone's width (law='zone' only)."""

    def _zone_error(self, how):
        return ModelDefinitionError(
            "%s: %s is the width of the stick zone of law='zone'; with Modelica's modes (the "
            "default) it has no meaning: %s or give law='zone'" % (self.describe(), self.ZONE, how))

    def refuse_zone_width(self):
        """An error naming the stick zone's width if the model gives it
        to an element of Modelica's modes (it would change nothing)."""
        if self.law == "modes" and self.is_given(self.ZONE):
            raise self._zone_error("drop %s" % self.ZONE)

    def check_parameters(self, value):
        """Under Modelica's modes the stick zone's width keeps its default
        in every run (``--set``, ``params=``, a sweep): changed, it is an
        error naming it, as in the constructor."""
        zone = self.ZONE
        if getattr(self, "law", None) == "modes" and \
                value(zone) != self.parameter_declaration(zone).default:
            raise self._zone_error("leave %s out of the run's parameters" % zone)

    def describe_mode(self, value):
        """The mode output in words (stuck, sliding forward or backward,
        free; "starting forward" while starting from rest), for events."""
        code = int(round(value("mode")))
        if code == 0 and value("startForward") > 0.5:
            return "starting forward"
        if code == 0 and value("startBackward") > 0.5:
            return "starting backward"
        return self.MODE_WORDS.get(code)


def zone_law(comp, tau, w, w_s, tau0_max, tau_slide):
    """The equations of the stick-zone law (:func:`zone_torque`) for the
    torque variable ``tau`` and the mode outputs it gives: ``mode`` 0
    inside the zone ``|w| < w_s`` (``locked`` 1), the sign of ``w``
    outside (from the zone's own relations: no event of their own);
    ``sa`` the friction torque; never starting."""
    torque, sat = zone_torque(w, w_s, tau0_max, tau_slide)
    mode = ca.eq(sat, 1.0) - ca.eq(sat, -1.0)
    return [tau == torque, comp.mode == mode, comp.locked == 1 - mode * mode,
            comp.startForward == 0, comp.startBackward == 0, comp.sa == tau]


class _Friction(_Modes):
    """Parameters every friction element has: peak, w_small, the law and
    its stick zone w_s (law='zone' only)."""
    peak = Parameter(1.0, "1", "peak of the friction at w = 0: tau0_max = peak * tau0", min=1.0)

    def __init__(self, law="modes", **kw):
        super().__init__(**kw)
        self.law = check_law(self, law)
        self.refuse_zone_width()

    def sliding_mode_advice(self):
        """What to change when the element's relations chatter."""
        if self.law == "modes":
            return ("%s switches its modes without progress; make the inputs that drive it "
                    "continuous, or look for a relation elsewhere that moves it back and forth."
                    % self.describe())
        return ("%s models sticking itself with its stick zone of width %s: a zone this narrow "
                "cannot be resolved at the speeds of the run. Give it a larger %s, or leave "
                "law='zone' for Modelica's modes." % (self.describe(), self.ZONE, self.ZONE))

    def law_equations(self, w, a, free, tau0, slide):
        """The friction torque ``self.tau``'s equation and the mode
        outputs' for the relative speed ``w`` (acceleration ``a``), the
        relation ``free``, the sliding torque ``tau0`` at rest and
        ``slide(v)`` for ``v >= 0``, by the element's law."""
        tau0_max = self.peak * tau0
        if self.law == "zone":
            return zone_law(self, self.tau_name(), w, getattr(self, self.ZONE), tau0_max, slide)
        tau, eqs, _ = partial_friction(self, w, a, self.sa, free, tau0, tau0_max, slide)
        return eqs + [self.tau_name() == tau]

    def tau_name(self):
        """The friction torque (force) variable."""
        return self.tau


class _SupportFriction(_Friction):
    """Two rigidly coupled flanges and the support (Modelica's
    PartialElementaryTwoFlangesAndSupport2): the friction acts between the
    shaft and the support (grounded at 0 if unconnected)."""
    w_small = Parameter(1e10, "rad/s", "Modelica's reinit threshold (no effect, see module)",
                        positive=True)
    w_s = Parameter(1e-4, "rad/s", "width of the stick zone of law='zone'", positive=True)
    phi = Variable(unit="rad", doc="angle of the flanges relative to the support")
    w = Variable(unit="rad/s", doc="angular velocity relative to the support")
    a = Variable(unit="rad/s2", doc="angular acceleration relative to the support")
    tau = Variable(unit="N.m", doc="friction torque (flange_a.tau + flange_b.tau)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.support = RotationalFlange(ground={"phi": 0.0}, doc="housing (fixed if unconnected)")

    def _kinematics(self):
        return [self.phi == self.flange_a.phi - self.support.phi,
                self.flange_b.phi == self.flange_a.phi,
                self.w == der(self.phi), self.a == der(self.w),
                0 == self.flange_a.tau + self.flange_b.tau - self.tau,
                self.support.tau == -self.flange_a.tau - self.flange_b.tau]


class BearingFriction(_SupportFriction):
    """Coulomb friction in a bearing (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Components.BearingFriction)::

        phi = flange_a.phi - support.phi,  flange_b.phi = flange_a.phi
        w = der(phi),  a = der(w)
        0 = flange_a.tau + flange_b.tau - tau
        tau0 = tau_pos(w = 0),  tau0_max = peak * tau0,  free = false
        tau = if locked then sa else if forward then tau_pos(w) else -tau_pos(-w)

    with the modes of Modelica's PartialFriction
    (:func:`partial_friction`: stuck with ``a = 0`` while ``|sa| <=
    tau0_max``).  ``tau_pos``: rows ``[w, tau]`` of the positive sliding
    characteristic (default ``[[0, 1]]``, a constant torque of 1 N m).
    ``tau`` is the torque the flanges pass into the friction (it has the
    sign of ``w``).  ``law="zone"``: the stick zone ``w_s`` instead (module
    docstring)."""

    def __init__(self, tau_pos=None, **kw):
        super().__init__(**kw)
        self.tau_pos = table_rows(self, "tau_pos", tau_pos, [(0.0, 1.0)])

    def equations(self):
        tau0 = interpolate(self.tau_pos, 0.0)
        return self._kinematics() + self.law_equations(
            self.w, self.a, 0.0, tau0, lambda v: interpolate(self.tau_pos, v))


class Brake(_SupportFriction):
    """Brake based on Coulomb friction (Modelica Standard Library 4.0,
    Modelica.Mechanics.Rotational.Components.Brake)::

        phi = flange_a.phi - support.phi,  flange_b.phi = flange_a.phi
        w = der(phi),  a = der(w)
        0 = flange_a.tau + flange_b.tau - tau
        fn = fn_max * f_normalized,  free = fn <= 0
        mu0 = mu_pos(w = 0),  tau0 = mu0 * cgeo * fn,  tau0_max = peak * tau0
        tau = if locked then sa else if free then 0 else
              cgeo * fn * (if forward then mu_pos(w) else -mu_pos(-w))

    with the modes of Modelica's PartialFriction (:func:`partial_friction`).
    ``mu_pos``: rows ``[w, mu]`` (default ``[[0, 0.5]]``).  The brake holds
    the shaft (``w`` stays 0) while the torque on it stays within
    ``tau0_max = peak * mu0 * cgeo * fn``; a normal force ``fn <= 0``
    leaves it free.  ``tau0_max`` is output (0 when free)."""
    cgeo = Parameter(1.0, "m", "geometry constant (effective radius x friction faces)", min=0.0)
    fn_max = Parameter(1.0, "N", "maximum normal force", min=0.0)
    fn = Variable(unit="N", doc="normal force fn_max f_normalized")
    tau0_max = Variable(unit="N.m", doc="breakaway torque peak mu0 cgeo fn (0 when free)")

    def __init__(self, mu_pos=None, **kw):
        super().__init__(**kw)
        self.mu_pos = table_rows(self, "mu_pos", mu_pos, [(0.0, 0.5)])
        self.f_normalized = RealInput(doc="normalized normal force (0..1)")

    def equations(self):
        free, breakaway, slide = brake_friction(self)
        return self._kinematics() + self.law_equations(self.w, self.a, free, breakaway, slide) + [
            self.fn == self.fn_max * self.f_normalized.u,
            self.tau0_max == self.peak * breakaway]


def brake_friction(brake):
    """What a brake (rotational or translational) hands to the friction law
    from its normal force ``fn``, ``cgeo`` and ``mu_pos`` table: (free: the
    relation ``fn <= 0``, the breakaway value mu0 cgeo fn (0 when free), the
    sliding value as a function of the relative speed cgeo fn mu_pos(v))."""
    free = brake.fn <= 0
    fn_pos = ca.if_else(free, 0.0, brake.fn)
    breakaway = interpolate(brake.mu_pos, 0.0) * brake.cgeo * fn_pos
    return free, breakaway, lambda v: brake.cgeo * fn_pos * interpolate(brake.mu_pos, v)


class OneWayClutch(_Modes):
    """Parallel connection of a freewheel and a clutch (Modelica Standard
    Library 4.0, Modelica.Mechanics.Rotational.Components.OneWayClutch)::

        phi_rel = flange_b.phi - flange_a.phi,  w_rel = der(phi_rel),  a_rel = der(w_rel)
        flange_b.tau = tau,  flange_a.tau = -tau
        free = f_normalized <= 0,  fn = if free then 0 else fn_max * f_normalized
        tau0 = mu0 * cgeo * fn
        tau0_max = if free then eps0 * mu0 * cgeo * fn_max else peak2 * tau0
        peak2 = max(peak, 1 + eps0),  eps0 = 1e-4
        startForward = pre(stuck) and (sa > tau0_max or pre(startForward) and sa > tau0)
                       or initial() and w_rel > 0
        locked = pre(stuck) and not startForward
        a_rel = if locked then 0 else sa - tau0
        tau = if locked then sa else if free then 0 else cgeo * fn * mu_pos(w_rel)
        stuck = locked or w_rel <= 0

    The freewheel locks the backward direction: ``w_rel = flange_b.w -
    flange_a.w`` never becomes negative (start with ``w_rel >= 0``); it
    stays locked (``a_rel = 0``) under any backward torque, and from rest
    starts sliding forward once the torque exceeds ``tau0_max`` (open: the
    small ``eps0 mu0 cgeo fn_max``).  Latches ``locked`` (1 while locked;
    off: ``w_rel`` reaching 0 once it was positive, else ``sa`` falling
    below ``tau0``; on: ``sa`` above ``tau0_max``) and ``forward``
    (``w_rel`` > 0 reached).  Outputs ``locked``, ``stuck``,
    ``startForward``, ``mode`` (0 stuck, 1 forward, 2 free and sliding).
    ``law="zone"``: the former regularisation (a stick zone ``w_s``
    forward, a stiff viscous lock ``tau = peak mu0 cgeo fn_max w_rel / w_s``
    backward, which creeps at ``w_s |tau| / (peak mu0 cgeo fn_max)``; its
    mode outputs are 0)."""
    peak = Parameter(1.0, "1", "peak of the friction at w = 0: tau0_max = peak * tau0", min=1.0)
    w_small = Parameter(1e10, "rad/s", "Modelica's reinit threshold (no effect here)",
                        positive=True)
    cgeo = Parameter(1.0, "m", "geometry constant (effective radius x friction faces)", min=0.0)
    fn_max = Parameter(1.0, "N", "maximum normal force", positive=True)
    w_s = Parameter(1e-4, "rad/s", "width of the stick zones of law='zone'", positive=True)
    phi_rel = Variable(unit="rad", state_select="prefer", nominal=1e-4,
                       doc="relative angle flange_b - flange_a")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="relative angular velocity")
    a_rel = Variable(unit="rad/s2", doc="relative angular acceleration")
    tau = Variable(unit="N.m", doc="torque acting on flange_b")
    fn = Variable(unit="N", doc="normal force (0 if f_normalized <= 0)")
    stuck = Variable(unit="1", doc="1 if w_rel = 0 (locked or starting forward)")
    EPS0 = 1e-4
    power_sides = (("flange_a",), ("flange_b",))

    def __init__(self, mu_pos=None, law="modes", phi_nominal=None, stateSelect=None, **kw):
        super().__init__(**kw)
        relative_states(self, "phi_rel", "w_rel", phi_nominal, stateSelect)
        self.law = check_law(self, law)
        self.refuse_zone_width()
        self.mu_pos = table_rows(self, "mu_pos", mu_pos, [(0.0, 0.5)])
        self.check_parameters(self.parameter_value)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()
        self.f_normalized = RealInput(doc="normalized normal force (0..1)")

    sliding_mode_advice = _Friction.sliding_mode_advice

    def check_parameters(self, value):
        """The lock torque peak mu0 cgeo fn_max > 0 (on the values
        ``value(name)`` gives): a freewheel without it never locks; the
        stick zone's width as :meth:`_Modes.check_parameters`."""
        super().check_parameters(value)
        if not interpolate(self.mu_pos, 0.0) * value("cgeo") > 0:
            raise ModelDefinitionError(
                "%s: the freewheel's lock torque peak mu0 cgeo fn_max is 0 (mu_pos at w = 0 is "
                "%g, cgeo = %g); give mu_pos(0) > 0 and cgeo > 0" % (
                    self.describe(), interpolate(self.mu_pos, 0.0), value("cgeo")))

    def equations(self):
        free = self.f_normalized.u <= 0
        mu0 = interpolate(self.mu_pos, 0.0)
        common = [self.phi_rel == self.flange_b.phi - self.flange_a.phi,
                  self.w_rel == der(self.phi_rel), self.a_rel == der(self.w_rel),
                  self.fn == ca.if_else(free, 0.0, self.fn_max * self.f_normalized.u),
                  self.flange_b.tau == self.tau, self.flange_a.tau == -self.tau]
        slide = lambda v: self.cgeo * self.fn * interpolate(self.mu_pos, v)  # noqa: E731
        if self.law == "zone":
            forward = friction_law(ca.fmax(self.w_rel, 0.0), self.w_s,
                                   self.peak * mu0 * self.cgeo * self.fn, slide)
            lock = self.peak * mu0 * self.cgeo * self.fn_max / self.w_s * \
                ca.fmin(self.w_rel, 0.0)
            return common + [self.mode == 0, self.locked == 0, self.stuck == 0,
                             self.startForward == 0, self.startBackward == 0,
                             self.sa == self.tau, self.tau == forward + lock]
        return common + self._modes(free, mu0, slide)

    def _modes(self, free, mu0, slide):
        """Modelica's OneWayClutch state machine (class docstring) by the
        latches ``locked`` and ``forward``."""
        tau0 = mu0 * self.cgeo * self.fn
        tau0_max = ca.if_else(free, self.EPS0 * mu0 * self.cgeo * self.fn_max,
                              ca.fmax(self.peak, 1 + self.EPS0) * tau0)
        lk, fw = latch(_named(self, "locked")), latch(_named(self, "forward"))
        w, sa = self.w_rel, self.sa
        define_latch(lk, ca.if_else(lk, tau0_max - sa, ca.if_else(fw, -w, tau0 - sa)),
                     "freewheel locked (%s)" % _named(self, "locked"), g_start=-w)
        define_latch(fw, ca.if_else(lk, -1.0, w), "forward speed reached (%s)"
                     % _named(self, "mode = Forward"), g_start=w)
        return [self.a_rel == ca.if_else(lk, 0.0, sa - tau0),
                self.tau == ca.if_else(lk, sa, ca.if_else(free, 0.0, slide(w))),
                self.locked == lk, self.startForward == (1 - lk) * (1 - fw),
                self.stuck == lk + (1 - lk) * (1 - fw), self.startBackward == 0,
                self.mode == ca.if_else(lk, 0.0, ca.if_else(free, 2.0, fw))]
