"""State events located on the exact solution.

IDA finds the root of a crossing function on its interpolant of the
unknowns.  The states are tested by its error control, so their interpolant
is as good as the run; the algebraic unknowns are not (IDA's
``suppressalg``, see :mod:`~acausal2d.runtime.ida`), and in a formulation
without states - a kinematically driven mechanism, where every unknown is a
function of time alone - nothing limits IDA's step size: the interpolant
between its large steps misses the crossing by milliseconds and crosses
where the solution does not.

So the runtime re-solves the equations at IDA's root:

* the left limit of an event is the exact solution at the root time, with
  the states held at IDA's values and the old relation values
  (:func:`exact_point`);
* without states the solution is known exactly at every time, so the root
  itself is located on it (:func:`locate_on_solution`): a regula falsi
  (Illinois) on the crossing function between the last exact point before
  the root with the relation on its old side and the first with it on the
  new side, to :data:`TIME_TOL` of the time.  A root of the interpolant that
  the exact solution does not have is no event (the run continues from the
  exact point).
"""
import numpy as np

from .newton import NoConvergence, solve_consistent

TIME_TOL = 4e-16          # relative width of the final bracket: a few floating-point steps
MAX_ITERATIONS = 100      # regula falsi steps (Illinois: superlinear, a dozen as a rule)
POLISH_ITERATIONS = 12    # Newton steps of one exact point (it stops where rounding stops it)


def exact_point(ev, t, z, d, held):
    """z solved at time t with the nodes ``held`` kept at their values in
    ``z`` and the relation values ``d``; ``z`` itself if Newton fails."""
    z_exact = _solved(ev, t, z, d, held)
    return np.array(z, dtype=float) if z_exact is None else z_exact


def _solved(ev, t, z, d, held=()):
    """z solved at time t (``held`` kept) down to rounding: Newton goes on
    while it reduces the residuals, which must end below the runtime's
    tolerance 1e-10; None if they do not."""
    held = list(held)
    try:
        return solve_consistent(ev, t, z, d, held, np.asarray(z)[held], tol=0.0,
                                max_iter=POLISH_ITERATIONS)
    except NoConvergence as exc:
        return exc.z if np.max(np.abs(exc.residual), initial=0.0) < 1e-10 else None


def _line(left, right, t):
    """z at t on the line through the (t, z) points ``left`` and ``right``."""
    w = (t - left[0]) / (right[0] - left[0])
    return (1.0 - w) * left[1] + w * right[1]


def _between(ev, d, left, right, t):
    """The exact point at t, Newton started on the line from ``left`` to
    ``right`` (t may lie beyond ``right``); None if Newton fails."""
    return _solved(ev, t, _line(left, right, t), d)


def crossed(system, g, d, candidates):
    """The relations among ``candidates`` whose crossing values ``g`` give
    another value than ``d``."""
    return [k for k in candidates if system.relations[k].value(g[k]) != d[k]]


def locate_on_solution(system, ev, d, points, candidates, horizon):
    """Earliest crossing of the relations ``candidates`` on the exact
    solution of a formulation without states.

    ``points`` are exact (t, z) points in time order, the first (the start
    of the segment) taken to have every candidate on its side ``d``, the
    last IDA's root (its z is re-solved).  If no candidate has crossed
    there, the solution is looked at one interval further (the last
    interval of ``points`` again, not beyond ``horizon``, the next time
    event): IDA's root may fall just before the exact one.  Returns (t, z,
    flipped): the first time (to :data:`TIME_TOL`) at which the relations
    ``flipped`` have changed sides, z exact there; or (t, z, []) at IDA's
    root if the solution has no crossing (a root of the interpolant only)."""
    exact = [(t, np.asarray(z, dtype=float)) for t, z in points[:-1]]
    exact.append((points[-1][0], exact_point(ev, points[-1][0], points[-1][1], d, [])))
    ahead = _look_ahead(ev, d, exact[-2], exact[-1], horizon)
    sides = [[]] + [crossed(system, ev.crossings(t, z, d), d, candidates)
                    for t, z in exact[1:] + ahead]
    first = next((i for i, s in enumerate(sides) if s), None)
    if first is None:
        return exact[-1] + ([],)
    left, right = (exact + ahead)[first - 1], (exact + ahead)[first]
    t, z = min((_illinois(system, ev, d, k, left, right) for k in sides[first]),
               key=lambda p: p[0])
    g = ev.crossings(t, z, d)
    return t, z, [k for k in candidates if system.relations[k].value(g[k]) != d[k]
                  or (g[k] == 0.0 and k in sides[first])]


def _look_ahead(ev, d, before, root, horizon):
    """[(t, z)] one interval past IDA's root (none at the horizon or where
    Newton fails)."""
    t = min(horizon, root[0] + (root[0] - before[0]))
    z = _between(ev, d, before, root, t) if t > root[0] else None
    return [] if z is None else [(t, z)]


def exact_rows(ev, d, left, right, times):
    """Exact (t, z) rows at ``times`` (between or after the two exact
    points ``left`` and ``right``); the start guess if Newton fails."""
    rows = []
    for t in times:
        z = _between(ev, d, left, right, t)
        rows.append((float(t), z if z is not None else _line(left, right, t)))
    return rows


def _illinois(system, ev, d, k, left, right):
    """(t, z) at the root of relation k's crossing function between
    ``left`` (old side) and ``right`` (new side) on the exact solution:
    where it is zero, else just past it."""
    (ta, za), (tb, zb) = left, right
    ga, gb = ev.crossings(ta, za, d)[k], ev.crossings(tb, zb, d)[k]
    kept = 0
    for _ in range(MAX_ITERATIONS):
        if ga == 0.0:
            return float(ta), za
        if tb - ta <= TIME_TOL * max(1.0, abs(tb)):
            break
        t = tb - gb * (tb - ta) / (gb - ga) if gb != ga else 0.5 * (ta + tb)
        if not ta < t < tb:
            t = 0.5 * (ta + tb)
        z = exact_point(ev, t, _line((ta, za), (tb, zb), t), d, [])
        g = ev.crossings(t, z, d)[k]
        if system.relations[k].value(g) != d[k]:
            tb, zb, gb = t, z, g
            ga, kept = (0.5 * ga if kept == 1 else ga), 1
        else:
            ta, za, ga = t, z, g
            gb, kept = (0.5 * gb if kept == -1 else gb), -1
    return float(tb), zb

