"""Events with Modelica semantics.

Between events every relation keeps its value ``d`` (0 or 1).  At an event
the relations that crossed flip; then the *event iteration* re-initializes
the unknowns (states held) and re-evaluates all relations until they agree
with the restarted state.  A relation whose crossing function is (near)
zero there takes the value it is about to have: the sign of the function's
time derivative under the relation values being tried.  If no set of
relation values agrees with its own motion - friction ``sign(v)`` at v = 0
pushes v up with one value and down with the other - the motion is in a
sliding mode (sticking), which the element must model itself (as
``rotational.Clutch`` does with its modes): the run stops with an
error naming the relation, its component, the time and what to change (the
component's own advice where it gives one,
:meth:`~acausal2d.language.dsl.Component.sliding_mode_advice`).  A relation
whose two values give the same motion (``max(fn, 0)`` while ``fn`` stays
0) takes the value of its crossing function instead.  Many events in a vanishing time
interval (chattering) stop the run the same way.  A re-initialization that
makes a position with a velocity jump (a prescribed motion that steps)
needs an impulse and is an error naming the components.
"""
import numpy as np

from ..errors import SimulationError
from .newton import NoConvergence, solve_consistent

MAX_ITERATIONS = 20       # event iterations at one instant
CHATTER_EVENTS = 50       # this many events ...
CHATTER_SPAN = 1e-8       # ... within this fraction of the run's time span: chattering
JUMP_TOL = 1e-4           # relative change of a position with a velocity that is a jump
NEAR_ZERO = 1e-6          # a crossing function this small may be at its zero
LATCH_BAND = 1e-9         # a latch's crossing function this close to 0 keeps the value
STORM_EVENTS = 500        # this many events ...
STORM_SPAN = 1e-3         # ... within this fraction of the run's time span: an event storm
ZENO_EVENTS = 12          # this many event intervals, each shrinking ...
ZENO_RATIO = 0.9          # ... to at most this fraction of the one before,
ZENO_SPAN = 1e-6          # the last below this fraction of the span: Zeno


class EventError(SimulationError):
    """An event the motion cannot pass (sliding mode, chattering, impulse)."""


def relation_owner(system, k):
    """The component whose equation holds relation k (None: a connection)."""
    rel = system.relations[k]
    return system.owner_of_equation_flat(rel.equation) if rel.equation >= 0 else None


def relation_text(system, k):
    """``'text' in Component 'path'`` of relation k."""
    owner = relation_owner(system, k)
    where = " in %s" % owner.describe() if owner is not None else ""
    return "'%s'%s" % (system.relations[k].text, where)


def sliding_mode_advice(system, relations):
    """What to change about the relations ``relations`` that have no
    consistent value or chatter: each owner's own advice
    (:meth:`~acausal2d.language.dsl.Component.sliding_mode_advice`), else
    the general one."""
    owners = {id(o): o for o in (relation_owner(system, k) for k in relations) if o is not None}
    advice = [a for a in (o.sliding_mode_advice() for o in owners.values()) if a]
    generic = ("Model sticking in the element with modes held by latches (as rotational.Clutch "
               "does with Modelica's PartialFriction modes), give a switching a hysteresis the "
               "run can resolve, or smooth the relation.")
    return " ".join(advice) if len(advice) == len(owners) and advice else generic


def values_from(system, g):
    """Relation values (0/1) for crossing values ``g``."""
    return np.array([r.value(x) for r, x in zip(system.relations, g)])


def node_rates(ev, t, z, d, solve=True):
    """Time derivatives of all node values at a consistent point: der(x) is
    the value of the derivative node where one exists; the others follow
    from d/dt E(t, z) = 0 (least squares; left 0 unless ``solve``)."""
    A = ev.system.structure.var_to_diff.to_diff
    A = np.asarray(A)
    zdot = np.zeros_like(z)
    known = A >= 0
    zdot[known] = z[A[known]]
    unknown = np.nonzero(~known)[0]
    if len(unknown) and solve:
        h = 1e-7 * max(1.0, abs(t))
        Et = (ev.residual(t + h, z, d) - ev.residual(t, z, d)) / h
        J = ev.jacobian(t, z, d, dense=True)
        rhs = -(Et + J[:, known] @ zdot[known])
        zdot[unknown] = equilibrated_lstsq(J[:, unknown], rhs)
    return zdot


def equilibrated_lstsq(A, b):
    """Least-squares solution of A x = b after scaling each column, then
    each row, to a largest magnitude of 1.  A stiff element's gain (a
    clutch's ``T_max / w_s`` = 1e7 next to the 1s of ``w = der(phi)``)
    spreads the singular values of the unscaled matrix beyond the cut-off
    ``rcond`` although every unknown is well determined; the truncated
    solve then returns ~0 for the rate behind the gain (1e-8 instead of
    2e7) and the event iteration decides on its sign.  Scaling the columns
    makes the solution independent of the units of the unknowns."""
    col = np.max(np.abs(A), axis=0, initial=0.0)
    col[~(col > 0.0) | ~np.isfinite(col)] = 1.0
    As = A / col
    row = np.max(np.abs(As), axis=1, initial=0.0)
    row[~(row > 0.0) | ~np.isfinite(row)] = 1.0
    with np.errstate(all="ignore"):
        y = np.linalg.lstsq(As / row[:, None], b / row, rcond=1e-12)[0]
    return y / col


def near_zero(g):
    """Mask of the crossing values that may be at their zero."""
    return np.abs(g) <= NEAR_ZERO * (1.0 + np.abs(g))


def crossing_rates(ev, t, z, d):
    """(g, dg/dt) of all relations at a consistent point.  The rates of the
    nodes without derivative take a least-squares solve, done only when a
    relation near zero depends on them (so dg/dt is only meant for those)."""
    g = ev.crossings(t, z, d)
    near = near_zero(g)
    zdot = node_rates(ev, t, z, d, solve=bool(np.any(near & ev.system.relation_needs_rates)))
    h = 1e-7 * max(1.0, abs(t)) / max(1.0, float(np.max(np.abs(zdot))) if zdot.size else 1.0)
    g2 = ev.crossings(t + h, z + h * zdot, d)
    return g, (g2 - g) / h


def resolved_values(system, g, gdot, d, t, pinned=()):
    """Relation values that agree with the motion: from g where it is clearly
    nonzero, from the sign of dg/dt where g is (near) zero, else kept.  A
    crossing value is clearly nonzero when it is not :func:`near_zero` (a
    stiff relation's large rate, a clutch's 2e10/s at w_s = 1e-9, must not
    make a far-off value look close) or would not reach zero within 1e-9 of
    the time.  The relations ``pinned`` take the value of g alone, and so
    does a relation of time alone (its g is exact) that stays at its zero
    (the brake's ``fn <= 0`` when ``1 - ramp`` has reached 0 and stays).
    A latch within :data:`LATCH_BAND` (or its rate times 1e-9 of the time)
    of its zero keeps its value: its crossing function for the new value
    starts at zero by design (a friction element's ``-a`` after the
    breakaway), and only its crossing, which IDA reports (the latch is
    flipped before the iteration), or a clear sign changes it."""
    tau = 1e-9 * max(1.0, abs(t))
    out = np.array(d, dtype=float)
    near = near_zero(g)
    for k, rel in enumerate(system.relations):
        if rel.g_start is not None and k not in pinned:      # a latch
            if abs(g[k]) > max(LATCH_BAND, abs(gdot[k]) * tau):
                out[k] = rel.value(g[k])
            continue
        if k in pinned or not near[k] or \
                abs(g[k]) > abs(gdot[k]) * tau + 1e-13 * max(1.0, abs(g[k])) or \
                (rel.time_only and abs(gdot[k]) <= 1e-12):
            out[k] = rel.value(g[k])
        elif abs(gdot[k]) > 1e-12:
            out[k] = 1.0 if gdot[k] > 0 else 0.0
    return out


class EventIteration:
    """Settles the relation values at an instant (see module docstring);
    ``held`` are the nodes kept at their values (the states)."""

    def __init__(self, system, ev, describe_failure):
        self.system, self.ev = system, ev
        self.describe_failure = describe_failure
        self.reinit = None       # the Reinits of the last settle

    def settle(self, t, z, d, held):
        """(z, d) consistent with each other at time t, starting from the
        relation values ``d``.  When the values go round in a cycle, the
        relations of the cycle that leave the motion unchanged (:meth:`idle`)
        take the value of their crossing function; if there are none, the
        motion is in a sliding mode (an error).  The components' reinits
        (:class:`Reinits`) whose condition comes on set their states."""
        seen = [np.array(d, dtype=float)]
        pinned = set()
        reinit = self.reinit = Reinits(self.system, self.ev.p, z)
        for _ in range(MAX_ITERATIONS):
            z = self.consistent(t, z, d, held)
            z_new = reinit.apply(t, z, held)
            if z_new is not None:
                z = self.consistent(t, z_new, d, held)
            if not len(d):
                return z, d
            g, gdot = crossing_rates(self.ev, t, z, d)
            d_new = resolved_values(self.system, g, gdot, d, t, pinned)
            if not np.array_equal(d_new, d) and any(np.array_equal(d_new, s) for s in seen):
                idle = self.idle(t, z, d, d_new)
                if not idle:
                    self.sliding_mode(t, seen + [d_new])
                pinned.update(idle)
                d_new = resolved_values(self.system, g, gdot, d, t, pinned)
            if np.array_equal(d_new, d):
                return z, d
            seen.append(d_new)
            d = d_new
        self.sliding_mode(t, seen)

    def idle(self, t, z, d, d_new):
        """The relations that differ between ``d`` and ``d_new`` and leave
        the motion at (t, z) unchanged: z stays consistent and the rates of
        all nodes stay the same (to 1e-9 of the largest) with the value
        flipped.  ``max(fn, 0)`` of a clutch while ``fn`` stays 0 is one:
        the rate of ``fn`` is 0 up to rounding, and its sign must not decide
        (nor stop the run as a sliding mode)."""
        rates = node_rates(self.ev, t, z, d)
        scale = float(np.max(np.abs(rates), initial=0.0))
        out = []
        for k in np.nonzero(np.asarray(d) != np.asarray(d_new))[0]:
            other = np.array(d, dtype=float)
            other[k] = 1.0 - other[k]
            if np.max(np.abs(self.ev.residual(t, z, other)), initial=0.0) > 1e-10:
                continue
            if np.max(np.abs(node_rates(self.ev, t, z, other) - rates), initial=0.0) \
                    <= 1e-9 * scale:
                out.append(int(k))
        return out

    def consistent(self, t, z, d, held):
        try:
            return solve_consistent(self.ev, t, z, d, held, z[held])
        except NoConvergence as exc:
            raise self.describe_failure(t, exc) from None

    def sliding_mode(self, t, tried):
        flipping = sorted({k for a in tried for b in tried for k in np.nonzero(a != b)[0]})
        names = ", ".join(relation_text(self.system, k) for k in flipping)
        raise EventError(
            "At t=%.6g the relation %s has no consistent value: with either value the motion "
            "drives it to the other (a sliding mode, e.g. Coulomb friction at zero speed, "
            "where the part should stick). %s"
            % (t, names, sliding_mode_advice(self.system, flipping)), time=t)


class Reinits:
    """The components' ``reinits()`` at one event (Modelica's ``when c then
    reinit(x, v)``): each whose condition was off at the entry point and
    is on at a consistent point of the event iteration sets its state once."""

    def __init__(self, system, p, z_entry):
        self.system, self.p = system, p
        self.before = [system.value(cond, z_entry, p) > 0.5 for _, cond, _, _ in system.reinits]
        self.done = set()

    def texts(self):
        """``reinit(variable)`` of each reinit done."""
        return ["reinit(%s)" % self.system.reinits[k][2] for k in sorted(self.done)]

    def apply(self, t, z, held):
        """New node values with the due reinits applied, or None if none is due."""
        out = None
        for k, (comp, cond, var, value) in enumerate(self.system.reinits):
            if k in self.done or self.before[k] or self.system.value(cond, z, self.p) <= 0.5:
                continue
            self.done.add(k)
            out = np.array(z if out is None else out, dtype=float)
            v = value if isinstance(value, float) else self.system.value(value, out, self.p)
            j, sign, offset = self._node(var)
            if j not in set(held):
                raise EventError("At t=%.6g %s re-initializes %s, which is no state here; "
                                 "connect it so that %s stays a state (e.g. through a spring, "
                                 "not rigidly to another mass)" % (t, comp.describe(), var, var),
                                 time=t, variable=var)
            out[j] = (v - offset) / sign
        return out

    def _node(self, name):
        """(node, sign, offset) with ``name = sign * z[node] + offset``."""
        s = self.system
        if name in s.node_names:
            return s.node_names.index(name), 1.0, 0.0
        k = s.alias_names.index(name)
        offset = float(s.alias_offset_fn(self.p).full().ravel()[k])
        return int(s.alias_node[k]), float(s.alias_sign[k]), offset


class ChatterWatch:
    """Stops a run whose events make no progress: many events in a
    vanishing time interval (chattering), an event storm (:data:`STORM_EVENTS`
    within :data:`STORM_SPAN` of the run's time span: round-off or a
    switching that undoes itself), or a Zeno sequence (:data:`ZENO_EVENTS`
    intervals, each at most :data:`ZENO_RATIO` of the one before, the last
    below :data:`ZENO_SPAN` of the span: events that accumulate at a point,
    like a bouncing ball's, which the run can neither resolve nor pass)."""

    def __init__(self, system, span):
        self.system, self.span = system, span
        self.recent = []

    def record(self, t, relations):
        """Note an event at t of ``relations``; raise if the events make no progress."""
        self.recent.append((t, tuple(relations)))
        if len(self.recent) > STORM_EVENTS:
            self.recent.pop(0)
        kind = self._kind()
        if kind is not None:
            self._stop(t, *kind)

    def _kind(self):
        """(what, number of events) of the pattern found, or None."""
        times = [t for t, _ in self.recent]
        n = len(times)
        if n >= CHATTER_EVENTS and times[-1] - times[-CHATTER_EVENTS] <= CHATTER_SPAN * self.span:
            return "Chattering", CHATTER_EVENTS
        if n >= STORM_EVENTS and times[-1] - times[0] <= STORM_SPAN * self.span:
            return "An event storm", STORM_EVENTS
        if n > ZENO_EVENTS:
            gaps = np.diff(times[-ZENO_EVENTS - 1:])
            if gaps[-1] <= ZENO_SPAN * self.span and \
                    np.all(gaps[1:] <= ZENO_RATIO * gaps[:-1]):
                return "Zeno behaviour", ZENO_EVENTS + 1
        return None

    def _stop(self, t, what, n):
        window = self.recent[-n:]
        counts = {}
        for _, rels in window:
            for k in rels:
                counts[k] = counts.get(k, 0) + 1
        worst = sorted(counts, key=lambda k: -counts[k])[:3]
        raise EventError(
            "%s at t=%.6g: %d events within %.3g s, from the relation %s. The motion makes "
            "no progress at the switching point of the relation. %s"
            % (what, t, n, window[-1][0] - window[0][0],
               ", ".join(relation_text(self.system, k) for k in worst),
               sliding_mode_advice(self.system, worst)), time=t)


def check_assertions(system, p, t, z):
    """Raise an :class:`EventError` if a component's assertion variable
    (``Component.assertions()``) is 1 at the consistent point (t, z)."""
    for comp, name, message in system.assertions:
        if system.value(name, z, p) > 0.5:
            raise EventError("At t=%.9g in %s: %s" % (t, comp.describe(), message),
                             time=t, variable=name)


def position_nodes(s):
    """Mask of the variables that are positions of a motion: level 0 with a
    velocity and an acceleration among the nodes (an angle or a
    coordinate; its jump would need an infinite velocity)."""
    A = np.asarray(s.var_to_diff.to_diff)
    level = np.asarray(s.var_level)
    vel = np.where(A >= 0, A, 0)
    return (level == 0) & (A >= 0) & (A[vel] >= 0)


def check_jumps(system, t, z_before, z_after, changed):
    """Raise if a position jumps at an event (it would need an impulse);
    velocities may jump where a prescribed motion has a kink."""
    moved = np.abs(z_after - z_before) > JUMP_TOL * (system.nominal + np.abs(z_before))
    jumps = np.nonzero(moved & position_nodes(system.structure))[0]
    if not len(jumps):
        return
    j = int(jumps[0])
    owners = system.owners_of_node(j)
    cause = ", ".join(relation_text(system, k) for k in changed) or "an event"
    raise EventError(
        "At t=%.6g the prescribed motion jumps: %s would change from %.6g to %.6g in no time "
        "when %s switches, which needs an impulse. Make the prescribed position or angle "
        "continuous (a ramp or a smooth step) in %s." % (
            t, system.node_names[j], z_before[j], z_after[j], cause,
            ", ".join(owners)), time=t, variable=system.node_names[j])
