"""State re-selection and singular positions during integration.

A dummy block whose determinant decays (watched by zero crossings) calls for
a new state selection if a better-conditioned one exists; if none does, the
mechanism itself is at a singular position.  Positions passed between
output points are found by scanning the block determinants.  Where IDA
gives up just before a singular position (its Newton iteration fails on the
near-singular block), :func:`step_over` predicts the motion through it and
lands on the branch that continues the motion (a crank of a change-point
four-bar turning through the position where the dyad's two branches meet);
a run that can continue nowhere past a singular block ends as a limit
position.
"""
import numpy as np

from .buffered import Buffered
from ..errors import InitializationError, SimulationError
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


class _DeterminantScan:
    """The determinants of a formulation's watched dummy blocks at many
    points: ``det_fn`` mapped over a chunk of points (parameters and
    relation values shared) and evaluated through a :class:`Buffered` on
    arrays filled in place - converting large arrays to CasADi matrices
    would cost ten times the evaluation."""

    CHUNK = 256

    def __init__(self, form):
        K, fn = self.CHUNK, form.det_fn
        self.fn = Buffered(fn.map("det_scan", "serial", K, [3, 4], []),
                           [np.zeros(K), np.zeros(K * form.n), np.zeros(K * form.n),
                            np.zeros(fn.nnz_in(3)), np.zeros(fn.nnz_in(4))])
        t, y, yp, self.p, self.d = self.fn.args
        self.t, self.y, self.yp = t, y.reshape(K, form.n), yp.reshape(K, form.n)
        self.out = self.fn.outs[0].reshape(K, fn.nnz_out(0))

    def __call__(self, T, Y, YP, p, d):
        """Determinants (points x blocks) at times T with rows Y, YP."""
        self.p[:] = p
        self.d[:] = d
        rows = []
        for s in range(0, len(T), self.CHUNK):
            m = min(self.CHUNK, len(T) - s)
            self.t[:m] = T[s:s + m]
            self.y[:m] = Y[s:s + m]
            self.yp[:m] = YP[s:s + m]
            self.fn.eval()
            rows.append(self.out[:m].copy())
        return np.vstack(rows)


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
    if form.det_scan is None:
        form.det_scan = _DeterminantScan(form)
    dets = form.det_scan(T, Y, YP, p, np.asarray(d, float)).T
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


def _taylor(cm, z, h):
    """Node values at time distance h predicted from z by the Taylor series
    along each derivative chain (x + h der(x) + h^2/2 der(der(x)) ...)."""
    A = np.asarray(cm.R.A)
    out = np.array(z, dtype=float)
    idx = np.arange(len(z))
    valid = np.ones(len(z), dtype=bool)
    coef = 1.0
    for k in range(1, 8):
        nxt = np.where(valid, A[idx], -1)
        valid = nxt >= 0
        if not valid.any():
            break
        idx = np.where(valid, nxt, 0)
        coef *= h / k
        out[valid] += coef * z[idx[valid]]
    return out


def _worst_level(cm, selection, t, z, p, d):
    """(relative smallest singular value, level, left singular vector) of the
    worst-conditioned dummy block at z, or None without dummy blocks."""
    worst = None
    for lv in selection.levels:
        cond, u = cm.block_conditioning(t, z, p, d, lv)
        if worst is None or cond < worst[0]:
            worst = (cond, lv, u)
    return worst


def _hermite(history, t_f, gap):
    """Extrapolation of the held states from ``history`` = (times, values,
    derivatives) of accepted integration points before t_f: a Hermite
    polynomial (value and derivative) through up to three points near
    t_f - 2 gap, t_f - gap and t_f.  Returns a function of t, or None if
    the history has fewer than two points far enough apart."""
    if history is None:
        return None
    ts, S, Sd = history
    picks = []
    for target in (t_f - 2.0 * gap, t_f - gap, t_f):
        i = int(np.argmin(np.abs(ts - target)))
        if not picks or ts[i] > ts[picks[-1]] + 0.25 * gap:
            picks.append(i)
    if len(picks) < 2:
        return None
    tau = (ts[picks] - t_f) / gap
    deg = 2 * len(picks)
    q = np.arange(deg)
    M = np.vstack([tau[:, None] ** q[None, :],
                   q[None, :] * tau[:, None] ** np.maximum(q - 1, 0)[None, :]])
    coef = np.linalg.solve(M, np.vstack([S[picks], gap * Sd[picks]]))

    def at(t):
        return ((t - t_f) / gap) ** q @ coef
    return at


def step_over(cm, selection, p, d, t_f, z_f, history, t_end, output_times):
    """Continue the motion through a singular position just ahead of the
    last point (t_f, z_f) that IDA reached.

    Along the Taylor prediction from z_f, the worst dummy block's relative
    smallest singular value has a minimum near zero at t_s.  The motion is
    then re-solved (Newton) at a landing time beyond t_s, at 1, 2, 3, 4, 6
    ... 64 times the distance t_s - t_f past it, with the states held at
    values extrapolated from ``history`` (times, values and derivatives of
    the held states at accepted integration points before t_f; see
    :func:`_hermite`) and the other unknowns started from the Taylor
    prediction.  A landing counts where Newton converges, the block is four
    times better conditioned than at z_f (where IDA could not go on), and
    the displacement since z_f and the velocities agree with the prediction
    (the branch that continues the motion, not the one crossing it).
    Returns ``None`` if there is no such position or landing (a limit
    position, or a failure of another kind), else ``(t_land, z_land,
    record, filled)``: the singularity record and the (time, node values)
    of the output times inside the jump."""
    worst = _worst_level(cm, selection, t_f, z_f, p, d)
    if worst is None:
        return None
    cond_f = worst[0]
    span = t_end - t_f
    if span <= 0 or cond_f <= 0:
        return None

    def cond_at(h):
        return _worst_level(cm, selection, t_f + h, _taylor(cm, z_f, h), p, d)[0]

    # distance to the singular position: the conditioning falls linearly
    delta = 1e-6 * max(span, 1e-3)
    slope = (cond_at(delta) - cond_f) / delta
    if not slope < 0:
        return None
    estimate = min(cond_f / -slope, span)
    grid = np.linspace(0.0, 2.0 * estimate, 41)[1:]
    values = [cond_at(h) for h in grid]
    k = int(np.argmin(values))
    lo = grid[k - 1] if k > 0 else 0.0
    hi = grid[min(k + 1, len(grid) - 1)]
    golden = (np.sqrt(5.0) - 1.0) / 2.0
    for _ in range(40):                  # golden-section search of the minimum
        a, b = hi - golden * (hi - lo), lo + golden * (hi - lo)
        if cond_at(a) < cond_at(b):
            hi = b
        else:
            lo = a
    h_s = 0.5 * (lo + hi)
    z_s = _taylor(cm, z_f, h_s)
    cond_s, lv, u = _worst_level(cm, selection, t_f + h_s, z_s, p, d)
    if cond_s > SINGULAR_CONDITION:
        return None
    form = cm.formulation(selection)
    held = list(np.asarray(form.y_nodes)[form.differential])
    states = _hermite(history, t_f, h_s) if held else None
    R = cm.R
    A = np.asarray(R.A)
    level = np.asarray(R.var_level)
    pos = np.nonzero((level == 0) & (A >= 0))[0]       # positions with a velocity
    vel = A[pos]

    def predict(h):
        guess = _taylor(cm, z_f, h)
        if states is not None:
            guess[held] = states(t_f + h)
        return guess

    def solve_at(t, guess):
        try:
            return solve_consistent(cm.init_system, t, guess, p, d, held, guess[held],
                                    cm.describe_equation, cm.node_name)
        except InitializationError:
            return None

    for m in (1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 16.0, 32.0, 64.0):
        h = h_s * (1.0 + m)
        if h > span:
            h = span
        if h <= h_s:
            break
        guess = predict(h)
        z_new = solve_at(t_f + h, guess)
        if z_new is None:
            continue
        if _worst_level(cm, selection, t_f + h, z_new, p, d)[0] < 4.0 * cond_f:
            continue
        moved = guess[pos] - z_f[pos]
        scale = np.linalg.norm(moved) + 1e-12 * (1.0 + np.linalg.norm(z_f[pos]))
        if np.linalg.norm(z_new[pos] - guess[pos]) > 0.1 * scale:
            continue
        v_pred = guess[vel]
        if np.linalg.norm(z_new[vel] - v_pred) > 0.1 * np.linalg.norm(v_pred) + 1e-9:
            continue
        t_land = t_f + h
        filled = []
        for t_out in output_times[(output_times > t_f) & (output_times < t_land)]:
            g = predict(t_out - t_f)
            z_out = solve_at(float(t_out), g)
            filled.append((float(t_out), z_out if z_out is not None else g))
        record = {"time": t_f + h_s, "elements": cm.singular_elements(lv.eqs, u),
                  "kind": "singular position passed", "condition": cond_s}
        return t_land, z_new, record, filled
    return None
