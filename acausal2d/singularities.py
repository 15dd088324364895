"""State re-selection and singular positions during integration.

A dummy block whose determinant decays (watched by zero crossings) calls for
a new state selection if a better-conditioned one exists; if none does, the
mechanism itself is at a singular position.  Positions passed between
output points are found by scanning the block determinants; a run that
cannot continue at a singular block ends as a limit position.
"""
import numpy as np

from .errors import InitializationError, SimulationError
from .initialize import solve_consistent

MONITOR_THRESHOLD = 0.25     # re-check the state selection when a block's |det| drops 4x
MAX_SINGULAR_EVENTS = 60     # then stop watching (a mechanism resting at a singular position)
SINGULAR_CONDITION = 1e-4    # relative smallest singular value of a singular block


def reselect(cm, selection, form, hits, t, z, p, d):
    """After a watched dummy block decayed (``hits``: monitor indices; None:
    all levels): returns (selection, singularity) - a better-conditioned new
    selection and None, or the current selection with a singularity record
    if the mechanism itself is singular there (None if it is only less well
    conditioned than before)."""
    worst = None
    levels = range(len(selection.levels)) if hits is None else \
        [form.monitor_levels[m] for m in hits]
    for k in levels:
        lv = selection.levels[k]
        cond, u = cm.block_conditioning(t, z, p, d, lv)
        if worst is None or cond < worst[0]:
            worst = (cond, lv, u)
    if worst is None:            # no dummy derivatives: nothing to re-select
        return selection, None
    cond, lv, u = worst
    try:
        new = cm.select(t, z, p, d)
    except SimulationError:
        new = None
    if new is not None and new.dummies != selection.dummies:
        better = min(cm.block_conditioning(t, z, p, d, nl)[0] for nl in new.levels)
        if better > 2.0 * cond:
            return new, None
    if cond > SINGULAR_CONDITION:
        return selection, None      # decayed, but far from singular: keep watching
    return selection, {"time": t, "elements": cm.singular_elements(lv.eqs, u),
                       "kind": "singular position", "condition": cond}


def consistent_for(cm, selection, t, z, p, d):
    """Node values made exactly consistent while holding the states of
    ``selection`` (IDA's interpolated derivatives at an event are only
    accurate to the tolerance, and a new state choice turns some of them
    into algebraic unknowns)."""
    form = cm.formulation(selection)
    held = list(np.asarray(form.y_nodes)[form.differential])
    try:
        return solve_consistent(cm.init_system, t, z, p, d, held, z[held],
                                cm.describe_equation, cm.node_name)
    except InitializationError as exc:
        raise SimulationError("Re-initialization after the state re-selection at t=%.6g "
                              "failed:\n%s" % (t, exc), time=t) from None


def limit_position(cm, selection, p, d, t, z):
    """Singularity record if the highest dummy block is singular at z."""
    lv = selection.levels[0] if selection.levels else None
    if lv is None:
        return None
    cond, u = cm.block_conditioning(t, z, p, d, lv)
    if cond > SINGULAR_CONDITION:
        return None
    return {"time": t, "elements": cm.singular_elements(lv.eqs, u), "kind": "limit position",
            "condition": cond}


def scan_singular_positions(cm, form, selection, p, d, out_t, out_z, start, found):
    """Find singular positions passed in the output points of a segment: the
    determinant of a watched dummy block changes sign, or has a local minimum
    far below its typical size."""
    n = len(out_t) - start
    if form.det_fn is None or n < 3:
        return
    Z = np.array(out_z[start:])
    T = np.array(out_t[start:])
    Y = Z[:, form.y_pos]
    YP = np.zeros_like(Y)
    st = form.state_deriv >= 0
    YP[:, st] = Z[:, form.state_deriv[st]]
    dets = form.det_fn.map(n)(T[None, :], Y.T, YP.T, np.repeat(p[:, None], n, 1),
                              np.repeat(np.asarray(d, float)[:, None], n, 1)).full()
    for row, k in zip(dets, form.scan_levels):
        scale = np.max(np.abs(row))
        if scale == 0:
            continue
        a = np.abs(row) / scale
        sign = np.sign(row)
        for i in range(1, n - 1):
            crossing = sign[i] != sign[i + 1] and sign[i] != 0
            minimum = a[i] < 1e-3 and a[i] <= a[i - 1] and a[i] < a[i + 1]
            if not (crossing or minimum):
                continue
            lv = selection.levels[k]
            cond, u = cm.block_conditioning(T[i], Z[i], p, d, lv)
            found.append({"time": float(T[i]), "elements": cm.singular_elements(lv.eqs, u),
                          "kind": "singular position passed", "condition": cond})
