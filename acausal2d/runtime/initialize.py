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
from dataclasses import dataclass

import numpy as np

from ..compiler.matching import Matching
from ..errors import Acausal2dError, InitializationError
from ..language.dsl import STATE_SELECT
from .diagnose import non_finite
from .events import EventIteration, values_from
from .newton import NoConvergence, solve_consistent
from .selection import SINGULAR_CONDITION, select, worst_level


@dataclass
class InitialPoint:
    """Consistent node values ``z``, relation values ``d`` and the dummy
    selection ``selection`` at t0 (None if it must be made at z)."""
    z: np.ndarray
    d: np.ndarray
    selection: object


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


def initialization_error(system, held, exc, p=None):
    """The InitializationError for a Newton failure (largest residuals, or
    the equations that are not finite)."""
    res = exc.residual
    text = non_finite(system, res, p if p is not None else np.zeros(len(system.parameters)))
    if text is not None:
        err = InitializationError("No consistent initial values: " + text)
        err.last = exc.z
        return err
    worst = np.argsort(-np.abs(res))[:6]
    lines = ["  - %s   (residual %.3g)" % (system.describe_equation(i), res[i])
             for i in worst if abs(res[i]) > 1e-10]
    err = InitializationError(
        "No consistent initial values found (the mechanism cannot assemble, or start values "
        "are too far from a solution). Largest remaining residuals:\n%s\nCheck the geometry "
        "(link lengths that cannot close a loop) and the start values of %s."
        % ("\n".join(lines), ", ".join(system.node_name(j) for j in list(held)[:8])))
    err.last = exc.z
    return err


def _guess_selection(system, ev, t0, z, d):
    """A selection at the start guess (to break ties when choosing which
    start values to hold), or None where the guess is singular."""
    try:
        return select(system, ev, t0, z, d)
    except Acausal2dError:
        return None      # a singular or not finite guess: decided at the consistent point


def initial_point(system, ev, t0, p):
    """Consistent :class:`InitialPoint` at t0 for the parameter vector p."""
    s = system.structure
    z = np.zeros(s.n_var)
    z[system.level0] = system.start_fn(p).full().ravel()
    d = values_from(system, ev.crossings(t0, z, np.zeros(len(system.relations))))
    sel = None
    if len(system.fixed_nodes) < s.n_var - s.n_eq:
        sel = _guess_selection(system, ev, t0, z, d)
    states = s.state_nodes(sel) if sel is not None else ()
    held = choose_initial_conditions(s, system.fixed_nodes, system.priority_names,
                                     system.has_start, states)
    z = _first_consistent(system, ev, t0, z, d, held, p)
    d = values_from(system, ev.crossings(t0, z, d))
    z, d = EventIteration(system, ev,
                          lambda t, exc: initialization_error(system, held, exc, p)) \
        .settle(t0, z, d, held)
    if sel is not None:
        worst = worst_level(system, ev, sel, t0, z, d)
        if worst is not None and worst[0] < 1e2 * SINGULAR_CONDITION:
            sel = None          # the guess's choice is poor at the consistent point
    return InitialPoint(z, d, sel)


def _first_consistent(system, ev, t0, z, d, held, p):
    """Newton from the start guess; if it fails, the relations may be the
    wrong ones: retry with those found where Newton ended."""
    for _ in range(10):
        try:
            return solve_consistent(ev, t0, z, d, held, z[held])
        except NoConvergence as exc:
            dn = values_from(system, ev.crossings(t0, exc.z, d))
            if np.array_equal(dn, d):
                raise initialization_error(system, held, exc, p) from None
            d = dn
    raise initialization_error(system, held, NoConvergence(z, ev.residual(t0, z, d)), p)
