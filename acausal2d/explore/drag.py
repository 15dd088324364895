"""Dragging a point of the mechanism at the start: the start values that put
it where the user let go, found on the model's own (DAE) initialization.

The unknowns moved are the model's declared start positions: level-0
unknowns in m or rad that are fixed or have a start value (a free body's
position, a drive angle, the assembly guess of a joint).  The point's
position at the consistent initial point is a function of them; Gauss-Newton
steps with a finite-difference Jacobian and the least-norm solution (the
position correction of Schnabel and Gössner's eq. 3-16, here on the assembled DAE
instead of node constraints) move them until the point is at the target or
no step brings it closer.  Every trial is a full initialization, so the
answer is always an assembled mechanism.
"""
import numpy as np

from ..errors import Acausal2dError

MAX_NEWTON_STEPS = 12
"""Gauss-Newton steps of one drag."""

MAX_STEP = 0.5
"""Longest step (m or rad, as a vector norm) of the start values in one Gauss-Newton step."""


def movable(compiled):
    """Names of the start values a drag may change (see the module docstring)."""
    s = compiled.system
    units = compiled.units
    return [s.node_names[j] for j in s.level0
            if (s.node_info[j].fixed or s.has_start[j]) and units.get(s.node_names[j]) in ("m", "rad")]


def point_of(compiled, params, start, names):
    """(consistent z at t = 0, the values of the signals ``names`` there)."""
    point = compiled.initial_point(0.0, params, start)
    s = compiled.system
    nodes = {n: j for j, n in enumerate(s.node_names)}
    aliases = None
    out = []
    for name in names:
        if name in nodes:
            out.append(point.z[nodes[name]])
            continue
        if aliases is None:
            aliases = dict(zip(s.alias_names + s.alias_der_names,
                               s.alias_values(point.z[None, :], compiled.parameter_values(params))[0]))
        if name not in aliases:
            raise Acausal2dError("drag: %r is not a position of the mechanism's unknowns; drag "
                                 "a joint or a body" % name)
        out.append(aliases[name])
    return point.z, np.array(out, dtype=float)


def _try(compiled, params, start, names, values, xy):
    """(start, position) with ``values`` for ``names``, or None if the
    mechanism does not assemble there."""
    trial = dict(start, **dict(zip(names, (float(v) for v in values))))
    try:
        return trial, point_of(compiled, params, trial, xy)[1]
    except Acausal2dError:
        return None


def drag_start(compiled, params, start, xy, target):
    """New start values ({name: value}, the given ``start`` updated) that
    put the point whose coordinates are the signals ``xy`` = (x, y) at
    ``target`` at t = 0, as near as the mechanism allows."""
    names = movable(compiled)
    if not names:
        raise Acausal2dError("drag: %s declares no start position (a fixed or start value in m "
                             "or rad) to move" % type(compiled.model).__name__)
    start = dict(start or {})
    z, pos = point_of(compiled, params, start, xy)
    index = {n: j for j, n in enumerate(compiled.system.node_names)}
    u = np.array([z[index[n]] for n in names])
    goal = np.asarray(target, dtype=float)
    for _ in range(MAX_NEWTON_STEPS):
        err = goal - pos
        if np.linalg.norm(err) < 1e-9 * (1.0 + np.linalg.norm(goal)):
            break
        J = np.zeros((2, len(u)))
        for k in range(len(u)):
            h = 1e-6 * (1.0 + abs(u[k]))
            moved = _try(compiled, params, start, names, u + h * np.eye(len(u))[k], xy)
            J[:, k] = 0.0 if moved is None else (moved[1] - pos) / h
        step = np.linalg.lstsq(J, err, rcond=1e-10)[0]
        size = np.linalg.norm(step)
        if size > MAX_STEP:                 # near a dead centre J is small: go in steps
            step *= MAX_STEP / size
        better = _line_search(compiled, params, start, names, u, step, xy, goal, pos)
        if better is None:
            break
        u, start, pos = better
    z = point_of(compiled, params, start, xy)[0]       # the guesses made consistent
    return dict(start, **{n: float(z[index[n]]) for n in names})


def _line_search(compiled, params, start, names, u, step, xy, goal, pos):
    """(u, start, position) of the first of step, step/2, ... (5 tries) that
    brings the point nearer the goal; None if none does."""
    for k in range(5):
        trial_u = u + step / 2 ** k
        tried = _try(compiled, params, start, names, trial_u, xy)
        if tried is not None and np.linalg.norm(goal - tried[1]) < np.linalg.norm(goal - pos):
            return trial_u, tried[0], tried[1]
    return None
