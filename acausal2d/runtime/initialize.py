"""Consistent initialization.

Solves all equations of the index-reduced system (every derivative order)
for all variable nodes at t0, together with the fixed start values.  When
fewer values are fixed than the system has degrees of freedom, start values
of further state candidates are held, chosen by priority and by structural
matching so that the initial system is square and structurally regular.
The relations start with the values the start point gives them and are
settled by the event iteration (:mod:`~acausal2d.runtime.events`).  The
dummy-derivative selection made here is handed on to the integration.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from ..compiler.matching import Matching
from ..errors import Acausal2dError, InitializationError
from ..language.dsl import STATE_SELECT
from .diagnose import non_finite
from .events import EventIteration, values_from
from .newton import NoConvergence, solve_consistent
from .selection import SINGULAR_CONDITION, select, worst_level

if TYPE_CHECKING:
    from ..compiler.system import System
    from .evaluator import Evaluator


class InitialPoint:
    """Consistent node values ``z``, relation values ``d`` and the dummy
    selection ``selection`` at t0 (None if it must be made at z)."""

    def __init__(self, z, d, selection):
        self.z, self.d, self.selection = z, d, selection


def choose_initial_conditions(s, fixed_nodes, priority, has_start, states=()):
    """Which node values to hold at t0: the user's ``fixed_nodes`` plus, if
    the system has more freedom, start values of state candidates picked by
    priority, then by having a start value, then by being among ``states``
    (the states a selection at the start guess would integrate), and by
    structural matching."""
    need = s.n_var - s.n_eq
    held = list(dict.fromkeys(fixed_nodes))
    if len(held) >= need:
        return held
    m = Matching([list(v) for v in s.eq_vars] + [[j] for j in held], s.n_var).match_all()
    held_set, states = set(held), set(states)
    cands = [j for j in range(s.n_var) if s.var_to_diff[j] >= 0 and j not in held_set]
    cands.sort(key=lambda j: (-STATE_SELECT.index(priority[j]), 0 if has_start[j] else 1,
                              0 if j in states else 1, s.var_level[j], str(s.var_sym[j])))
    for j in cands:
        if len(held) >= need:
            break
        if m.add_row([j]):
            held.append(j)
    return held


def _guess_hints(system, ev, held, exc, rows):
    """'name (try about value)' of the free start guesses that most change
    the residuals ``rows`` at the last Newton iterate: the least-squares
    correction of the level-0 unknowns, ranked by its size."""
    s = system.structure
    held = set(int(j) for j in held)
    free = [j for j in system.level0 if j not in held and s.var_to_diff[j] >= 0]
    preferred = [j for j in free if system.priority[j] >= STATE_SELECT.index("prefer")]
    free = preferred or free          # joint angles and travels first
    if ev is None or not free or not rows:
        return []
    J = ev.jacobian(exc.t, exc.z, exc.d, dense=True)[np.ix_(rows, free)]
    if not np.all(np.isfinite(J)):
        return []
    with np.errstate(all="ignore"):
        dz = np.linalg.lstsq(J, -exc.residual[rows], rcond=1e-10)[0]
    z = exc.z[free]
    size = np.abs(dz) / (system.nominal[free] + np.abs(z))
    order = [k for k in np.argsort(-size) if size[k] > 1e-3][:5]
    return ["%s (try about %.4g)" % (s.var_sym[free[k]].name(), z[k] + dz[k]) for k in order]


def initialization_error(system, held, exc, p=None, ev=None):
    """The InitializationError for a Newton failure: the equations whose
    residuals are not finite, or the position-level residuals left (loop
    closure) with the start guesses that would reduce them most, or the
    largest residuals of the derivative levels."""
    res = exc.residual
    p = p if p is not None else np.zeros(len(system.parameters))
    text = non_finite(system, res, p)
    if text is None and ev is not None:
        text = _non_finite_derivatives(system, ev, exc, p)
    if text is None:
        text = _residual_report(system, held, exc, ev)
    err = InitializationError("No consistent initial values: " + text)
    err.last = exc.z
    return err


def _non_finite_derivatives(system, ev, exc, p):
    """Text naming the equations whose derivatives are inf or NaN at the
    last Newton iterate (Newton cannot step there), or None."""
    J = ev.jacobian(exc.t, exc.z, exc.d, dense=False).tocsr()
    bad = ~np.isfinite(J.data)
    if not bad.any():
        return None
    marks = np.zeros(system.structure.n_eq)
    marks[np.unique(J.nonzero()[0][bad])] = np.nan
    return "the derivatives of " + non_finite(system, marks, p) + \
        " (a square root or norm of zero has no derivative there: give start values away from it)"


def _residual_report(system, held, exc, ev):
    res = exc.residual
    s = system.structure
    level0 = [i for i in np.argsort(-np.abs(res)) if abs(res[i]) > 1e-10 and s.eq_level[i] == 0
              and all(s.var_to_diff[j] >= 0 for j in s.eq_vars[i])]
    rows = level0 or [i for i in np.argsort(-np.abs(res)) if abs(res[i]) > 1e-10]
    lines = ["  - %s   (residual %.3g)" % (system.describe_equation(i), res[i]) for i in rows[:6]]
    what = ("the position equations do not close (loop closure or fixed positions)" if level0
            else "the equations are not met")
    hints = _guess_hints(system, ev, held, exc, level0) if level0 else []
    kept = ", ".join(system.node_name(j) for j in list(held)[:8]) or "none"
    return ("%s; the largest residuals:\n%s\n%sHeld at their start values: %s.  Check the "
            "geometry (link lengths that cannot close a loop) and the start values." % (
                what, "\n".join(lines),
                "Start guesses that would reduce them most: %s.\n" % ", ".join(hints)
                if hints else "", kept))


def _guess_selection(system, ev, t0, z, d):
    """A selection at the start guess (to break ties when choosing which
    start values to hold), or None where the guess is singular."""
    try:
        return select(system, ev, t0, z, d)
    except Acausal2dError:
        return None      # a singular or not finite guess: decided at the consistent point


def initial_point(system: System, ev: Evaluator, t0: float, p: NDArray[np.float64],
                  start: dict[int, float] | None = None) -> InitialPoint:
    """Consistent :class:`InitialPoint` at t0 for the parameter vector p;
    ``start`` ({level-0 node index: value}) replaces those start values
    (a fixed one stays fixed, a guess counts as given)."""
    s = system.structure
    z = np.zeros(s.n_var)
    z[system.level0] = system.start_fn(p).full().ravel()
    has_start = system.has_start
    if start:
        z[list(start)] = list(start.values())
        has_start = tuple(h or j in start for j, h in enumerate(has_start))
    d = values_from(system, ev.start_crossings(t0, z, np.zeros(len(system.relations))))
    sel = None
    if len(system.fixed_nodes) < s.n_var - s.n_eq:
        sel = _guess_selection(system, ev, t0, z, d)
    states = s.state_nodes(sel) if sel is not None else ()
    held = choose_initial_conditions(s, system.fixed_nodes, system.priority_names,
                                     has_start, states)
    z = _first_consistent(system, ev, t0, z, d, held, p)
    d = values_from(system, ev.start_crossings(t0, z, d))
    z, d = EventIteration(system, ev,
                          lambda t, exc: initialization_error(system, held, exc, p, ev)) \
        .settle(t0, z, d, held)
    if sel is not None:
        worst = worst_level(system, ev, sel, t0, z, d)
        if worst is not None and worst[0] < 1e2 * SINGULAR_CONDITION:
            sel = None          # the guess's choice is poor at the consistent point
    check_start(system, p, z)
    return InitialPoint(z, d, sel)


def check_start(system, p, z):
    """Run the components' start checks
    (:meth:`~acausal2d.language.dsl.Component.start_checks`) on the
    consistent node values ``z``; the first that fails raises an
    :class:`InitializationError` naming its component."""
    def value(comp, name):
        return system.value("%s.%s" % (comp.path, name) if comp.path else name, z, p)

    for comp, check in system.start_checks:
        message = check(value)
        if message:
            raise InitializationError("%s: %s" % (comp.describe(), message))


def _contradicted_fixed(system, ev, t0, z, d, held):
    """For an over-determined start (more values held than the system has
    freedom): the first fixed value the equations contradict, found by
    releasing each fixed node in turn, as an InitializationError naming
    the variable, its fixed value and the value the equations give; or None."""
    s = system.structure
    if len(held) <= s.n_var - s.n_eq:
        return None
    for j in [j for j in held if j in set(system.fixed_nodes)]:
        rest = [k for k in held if k != j]
        try:
            zj = solve_consistent(ev, t0, z, d, rest, z[rest])
        except NoConvergence:
            continue
        name = system.node_name(j)
        return InitializationError(
            "%s has the fixed start value %.10g, but the equations give %s = %.10g with the "
            "other start values held (the initialization is over-determined); drop "
            "fixed=True from %s or change its start value to %.10g"
            % (name, z[j], name, zj[j], name, zj[j]))
    return None


def _first_consistent(system, ev, t0, z, d, held, p):
    """Newton from the start guess; if it fails, the relations may be the
    wrong ones: retry with those found where Newton ended."""
    for _ in range(10):
        try:
            return solve_consistent(ev, t0, z, d, held, z[held])
        except NoConvergence as exc:
            dn = values_from(system, ev.crossings(t0, exc.z, d))
            if np.array_equal(dn, d):
                raise (_contradicted_fixed(system, ev, t0, z, d, held)
                       or initialization_error(system, held, exc, p, ev)) from None
            d = dn
    raise initialization_error(system, held, NoConvergence(z, ev.residual(t0, z, d), t0, d), p,
                               ev)
