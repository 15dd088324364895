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
``Clutch`` does with stick/slip): the run stops with an error naming the
relation, its component and the time.  Many events in a vanishing time
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


class EventError(SimulationError):
    """An event the motion cannot pass (sliding mode, chattering, impulse)."""


def relation_text(system, k):
    """``'text' in Component 'path'`` of relation k."""
    rel = system.relations[k]
    owner = system.owner_of_equation_flat(rel.equation) if rel.equation >= 0 else None
    where = " in %s" % owner.describe() if owner is not None else ""
    return "'%s'%s" % (rel.text, where)


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
        with np.errstate(all="ignore"):
            zdot[unknown] = np.linalg.lstsq(J[:, unknown], rhs, rcond=1e-12)[0]
    return zdot


def crossing_rates(ev, t, z, d):
    """(g, dg/dt) of all relations at a consistent point.  The rates of the
    nodes without derivative take a least-squares solve, done only when a
    relation near zero depends on them."""
    g = ev.crossings(t, z, d)
    near = np.abs(g) <= NEAR_ZERO * (1.0 + np.abs(g))
    zdot = node_rates(ev, t, z, d, solve=bool(np.any(near & ev.system.relation_needs_rates)))
    h = 1e-7 * max(1.0, abs(t)) / max(1.0, float(np.max(np.abs(zdot))) if zdot.size else 1.0)
    g2 = ev.crossings(t + h, z + h * zdot, d)
    return g, (g2 - g) / h


def resolved_values(system, g, gdot, d, t):
    """Relation values that agree with the motion: from g where it is clearly
    nonzero, from the sign of dg/dt where g is (near) zero, else kept."""
    tau = 1e-9 * max(1.0, abs(t))
    out = np.array(d, dtype=float)
    for k, rel in enumerate(system.relations):
        if abs(g[k]) > abs(gdot[k]) * tau + 1e-13 * max(1.0, abs(g[k])):
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

    def settle(self, t, z, d, held):
        """(z, d) consistent with each other at time t, starting from the
        relation values ``d``."""
        seen = [np.array(d, dtype=float)]
        for _ in range(MAX_ITERATIONS):
            z = self.consistent(t, z, d, held)
            if not len(d):
                return z, d
            g, gdot = crossing_rates(self.ev, t, z, d)
            d_new = resolved_values(self.system, g, gdot, d, t)
            if np.array_equal(d_new, d):
                return z, d
            if any(np.array_equal(d_new, s) for s in seen):
                self.sliding_mode(t, seen + [d_new])
            seen.append(d_new)
            d = d_new
        self.sliding_mode(t, seen)

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
            "where the part should stick). Model sticking in the element (as Clutch does "
            "with stick/slip states) or smooth the relation." % (t, names), time=t)


class ChatterWatch:
    """Stops a run whose events pile up in a vanishing time interval."""

    def __init__(self, system, span):
        self.system, self.span = system, span
        self.recent = []

    def record(self, t, relations):
        self.recent.append((t, tuple(relations)))
        if len(self.recent) > CHATTER_EVENTS:
            self.recent.pop(0)
        if len(self.recent) == CHATTER_EVENTS and \
                self.recent[-1][0] - self.recent[0][0] <= CHATTER_SPAN * self.span:
            counts = {}
            for _, rels in self.recent:
                for k in rels:
                    counts[k] = counts.get(k, 0) + 1
            worst = sorted(counts, key=lambda k: -counts[k])[:3]
            raise EventError(
                "Chattering at t=%.6g: %d events within %.3g s, from the relation %s. The "
                "motion stays at the switching point of the relation (a sliding mode); model "
                "sticking in the element or smooth the relation."
                % (t, CHATTER_EVENTS, self.recent[-1][0] - self.recent[0][0],
                   ", ".join(relation_text(self.system, k) for k in worst)), time=t)


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
