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
from .native import compiled, too_large
from .newton import NoConvergence, solve_consistent
from .selection import SINGULAR_CONDITION, singularity, worst_level

MAX_SINGULAR_EVENTS = 60     # then stop watching (a mechanism resting at a singular position)


COND_ROUNDING = 1e4 * float(np.finfo(float).eps)
"""Margin of a change of the conditioning (a smallest singular value
relative to the largest): its rounding error is a few ulps times the
block size, plus the rounding of the Jacobian entries; 1e4 eps (2e-12)
leaves room.  A change above it is a trend, not rounding."""


def conditioning_trend(system, ev, selection, t, z, d, span, levels=None):
    """Which way the worst dummy block's conditioning goes along the
    predicted motion from (t, z) (the drive's direction: the Taylor series
    of the motion, :func:`taylor`): ``(sign, distance)``; sign +1 rising
    (the singular position is behind, the motion moves away from it), -1
    falling (it is ahead), 0 where no change beyond :data:`COND_ROUNDING`
    shows up to 1e-3 of ``span`` ahead (the margin cannot decide);
    ``distance`` the time to the singular position by linear extrapolation
    (None for sign 0).  Probed at distances growing from 1e-9 ``span``
    until the change exceeds the margin."""
    worst = worst_level(system, ev, selection, t, z, d, levels)
    if worst is None:
        return 0, None
    for k in range(9, 2, -1):
        h = 10.0 ** -k * max(span, 1e-9)
        change = worst_level(system, ev, selection, t + h, taylor(system, z, h), d, levels)[0] \
            - worst[0]
        if abs(change) > COND_ROUNDING:
            return (1 if change > 0 else -1), worst[0] * h / abs(change)
    return 0, None


def limit_position(system, ev, selection, t, z, d, span=1.0):
    """``(record, decided)``: the singularity record if the highest dummy
    block is singular at z and the motion does not move away from the
    singular position (its conditioning does not rise along the drive's
    direction beyond :data:`COND_ROUNDING`, see :func:`conditioning_trend`),
    else None; ``decided`` is False where the margin could not tell the
    direction and the drive's rule decided (a position the motion does not
    move away from is a limit) - the run reports that."""
    if not selection.levels:
        return None, True
    levels = selection.levels[:1]
    worst = worst_level(system, ev, selection, t, z, d, levels)
    if worst[0] > SINGULAR_CONDITION:
        return None, True
    sign, _ = conditioning_trend(system, ev, selection, t, z, d, span, levels)
    if sign > 0:
        return None, True     # the singular position lies behind: a passage, not a limit
    return singularity(system, t, "limit position", worst), sign != 0


class DeterminantScan:
    """The determinants of a formulation's watched dummy blocks at many
    points: ``det_fn`` mapped over a chunk of points (parameters and
    relation values shared) and evaluated through a :class:`Buffered` on
    arrays filled in place - converting large arrays to CasADi matrices
    would cost ten times the evaluation.  Compiled to C where a compiler
    is found and the engine ``chosen`` compiles (:func:`~acausal2d.runtime.
    native.compiled`)."""

    CHUNK = 256

    def __init__(self, form, chosen=None, label=None):
        K, fn = self.CHUNK, form.det_fn
        mapped = fn.map("det_scan", "serial", K, [3, 4], [])
        if not too_large(fn):
            mapped = (compiled({"det_scan": mapped}, chosen, label)
                      or {"det_scan": mapped})["det_scan"]
        self.fn = Buffered(mapped,
                           [np.zeros(K), np.zeros(K * form.n), np.zeros(K * form.n),
                            np.zeros(fn.nnz_in(3)), np.zeros(fn.nnz_in(4))])
        t, y, yp, self.p, self.d = self.fn.args
        self.t, self.y, self.yp = t, y.reshape(K, form.n), yp.reshape(K, form.n)
        self.out = self.fn.outs[0].reshape(K, fn.nnz_out(0))

    def __call__(self, T, Y, YP, p, d):
        """Determinants (points x blocks) at times T with rows Y, YP."""
        def fill(s, m):
            self.y[:m] = Y[s:s + m]
            self.yp[:m] = YP[s:s + m]
        return self._evaluate(T, p, d, fill)

    def of_rows(self, T, Z, all_deriv, p, d):
        """Determinants (points x blocks) at output rows (T, Z) of the
        system's unknowns: Y = Z and Y' read from Z's derivative nodes
        (``all_deriv``: the derivative node of each unknown, or -1), filled
        chunk by chunk into the buffers (no array of the size of Z)."""
        st = np.nonzero(all_deriv >= 0)[0]
        src = all_deriv[st]
        self.yp[:] = 0.0

        def fill(s, m):
            self.y[:m] = Z[s:s + m]
            self.yp[:m, st] = Z[s:s + m, src]
        return self._evaluate(T, p, d, fill)

    def _evaluate(self, T, p, d, fill):
        """The determinants at times T, chunk by chunk; ``fill(s, m)`` puts
        rows s..s+m-1 into the buffers y, yp."""
        self.p[:] = p
        self.d[:] = d
        rows = []
        for s in range(0, len(T), self.CHUNK):
            m = min(self.CHUNK, len(T) - s)
            self.t[:m] = T[s:s + m]
            fill(s, m)
            self.fn.eval()
            rows.append(self.out[:m].copy())
        return np.vstack(rows)


def _passed(row, n, sign_changes):
    """Indices i where a determinant row has a deep local minimum at i or
    (with ``sign_changes``) changes sign after i."""
    scale = np.max(np.abs(row))
    if scale == 0:
        return []
    a, sign = np.abs(row[:n]) / scale, np.sign(row[:n])
    mid = a[1:-1]
    hit = (mid < 1e-3) & (mid <= a[:-2]) & (mid < a[2:])
    if sign_changes:
        hit |= (sign[1:-1] != sign[2:]) & (sign[1:-1] != 0)
    return (np.nonzero(hit)[0] + 1).tolist()


def scan_singular_positions(system, ev, form, selection, p, d, T, Z, found, before=None,
                            chosen=None):
    """Find singular positions passed between the output points (T, Z) of a
    segment (after the point ``before`` = (t, z), if given): the determinant
    of a watched dummy block changes sign (except the highest level's, whose
    sign changes IDA locates as roots), or has a local minimum far below its
    typical size (``chosen``: the run's engine).  Returns {level: largest
    |det| seen}."""
    n = len(T) + (before is not None)
    if form.det_fn is None or n < 3:
        return {}
    if getattr(form, "det_scan", None) is None:
        form.det_scan = DeterminantScan(form, chosen, getattr(system, "model_name", None))
    d = np.asarray(d, float)
    dets = form.det_scan.of_rows(T, Z, form.all_deriv, p, d)
    if before is not None:
        first = form.det_scan.of_rows(np.array([before[0]]), np.asarray(before[1])[None, :],
                                      form.all_deriv, p, d)
        dets = np.vstack([first, dets])
    dets = dets.T
    point = (lambda i: (T[i - 1], Z[i - 1])) if before is not None else (lambda i: (T[i], Z[i]))
    found_sizes = {k: float(np.max(np.abs(row))) for row, k in zip(dets, form.scan_levels)}
    for row, k in zip(dets, form.scan_levels):
        lv = selection.levels[k]
        for i in _passed(row, n, k != 0 or not form.n_pass):
            t, z = point(i)
            found.append(singularity(system, float(t), "singular position passed",
                                     worst_level(system, ev, selection, t, z, d, [lv])))
    return found_sizes


def taylor(system, z, h):
    """Node values at time distance h predicted from z by the Taylor series
    along each derivative chain (x + h der(x) + h^2/2 der(der(x)) ...)."""
    A = np.asarray(system.structure.var_to_diff.to_diff)
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


def _golden_minimum(f, lo, hi, iterations=45):
    """Minimum of f on [lo, hi] by golden-section search (one new
    evaluation per iteration)."""
    golden = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = hi - golden * (hi - lo), lo + golden * (hi - lo)
    fa, fb = f(a), f(b)
    for _ in range(iterations):
        if fa < fb:
            hi, b, fb = b, a, fa
            a = hi - golden * (hi - lo)
            fa = f(a)
        else:
            lo, a, fa = a, b, fb
            b = lo + golden * (hi - lo)
            fb = f(b)
    return 0.5 * (lo + hi)


def _singular_time(system, ev, selection, t_f, z_f, d, span):
    """Time distance h_s from (t_f, z_f) to the minimum of the worst dummy
    block's conditioning along the Taylor prediction, if it is singular
    there: (h_s, worst) or None."""
    worst = worst_level(system, ev, selection, t_f, z_f, d)
    if worst is None or span <= 0 or worst[0] <= 0:
        return None

    def cond_at(h):
        return worst_level(system, ev, selection, t_f + h, taylor(system, z_f, h), d)[0]

    # distance to the singular position: the conditioning falls linearly
    # (probed closer and closer: the position may be very near)
    delta = 1e-6 * max(span, 1e-3)
    slope = (cond_at(delta) - worst[0]) / delta
    while not slope < 0 and delta > 1e-13 * max(span, 1e-3):
        delta *= 0.01
        slope = (cond_at(delta) - worst[0]) / delta
    if not slope < 0:
        return None
    estimate = min(worst[0] / -slope, span)
    grid = np.linspace(0.0, 2.0 * estimate, 41)[1:]
    k = int(np.argmin([cond_at(h) for h in grid]))
    lo, hi = (grid[k - 1] if k > 0 else 0.0), grid[min(k + 1, len(grid) - 1)]
    h_s = _golden_minimum(cond_at, lo, hi)
    at_s = worst_level(system, ev, selection, t_f + h_s, taylor(system, z_f, h_s), d)
    dip = at_s[0] <= max(SINGULAR_CONDITION, 0.01 * worst[0])    # a clear singular point
    return (h_s, at_s, worst[0]) if dip else None


_MULTIPLES = (1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 16.0, 32.0, 64.0)
WELL_CONDITIONED = 10 * SINGULAR_CONDITION   # a landing IDA can go on from


class _Landing:
    """Predictions and Newton solves beyond a singular position."""

    def __init__(self, system, ev, selection, form, d, t_f, z_f, states):
        self.system, self.ev, self.selection, self.d = system, ev, selection, d
        self.t_f, self.z_f, self.states = t_f, z_f, states
        self.held = list(form.states)
        s = system.structure
        A, level = np.asarray(s.var_to_diff.to_diff), np.asarray(s.var_level)
        self.pos = np.nonzero((level == 0) & (A >= 0))[0]       # positions with a velocity
        self.vel = A[self.pos]

    def first(self, h_min, distances, t_end, cond_f):
        """(t, z) at the first of ``distances`` (beyond h_min) where Newton
        converges on the continuing branch, preferring landings that are
        well conditioned (:data:`WELL_CONDITIONED`); None if there is none."""
        found = []
        for h in distances:
            h = min(h, t_end - self.t_f)
            if h <= h_min:
                break
            guess = self.predict(h)
            z_new = self.solve(self.t_f + h, guess)
            if z_new is None:
                continue
            cond = self.continues(h, z_new, guess, cond_f)
            if cond is not None and cond >= WELL_CONDITIONED:
                return self.t_f + h, z_new
            if cond is not None:
                found.append((self.t_f + h, z_new))
        return found[0] if found else None

    def fill(self, output_times, t_land):
        """(time, values) of the output times inside the jump."""
        filled = []
        for t_out in output_times[(output_times > self.t_f) & (output_times < t_land)]:
            g = self.predict(t_out - self.t_f)
            z_out = self.solve(float(t_out), g)
            filled.append((float(t_out), z_out if z_out is not None else g))
        return filled

    def predict(self, h):
        guess = taylor(self.system, self.z_f, h)
        if self.states is not None:
            guess[self.held] = self.states(self.t_f + h)
        return guess

    def solve(self, t, guess):
        try:
            return solve_consistent(self.ev, t, guess, self.d, self.held, guess[self.held],
                                    max_iter=20)
        except NoConvergence:
            return None

    def continues(self, h, z_new, guess, cond_f):
        """The conditioning at z_new if it is better than where IDA stopped
        and z_new lies on the branch that continues the predicted motion,
        else None."""
        t = self.t_f + h
        cond = worst_level(self.system, self.ev, self.selection, t, z_new, self.d)[0]
        if cond < 4.0 * cond_f:
            return None
        pos, vel, z_f = self.pos, self.vel, self.z_f
        moved = guess[pos] - z_f[pos]
        scale = np.linalg.norm(moved) + 1e-12 * (1.0 + np.linalg.norm(z_f[pos]))
        if np.linalg.norm(z_new[pos] - guess[pos]) > 0.1 * scale:
            return None
        if np.linalg.norm(z_new[vel] - guess[vel]) > 0.1 * np.linalg.norm(guess[vel]) + 1e-9:
            return None
        return cond


def step_over(system, ev, selection, form, d, t_f, z_f, history, t_end, output_times):
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
    found = _singular_time(system, ev, selection, t_f, z_f, d, t_end - t_f)
    if found is None:
        return None
    h_s, at_s, cond_f = found
    states = _hermite(history, t_f, h_s) if len(form.states) else None
    land = _Landing(system, ev, selection, form, d, t_f, z_f, states)
    landed = land.first(h_s, [h_s * (1.0 + m) for m in _MULTIPLES], t_end, cond_f)
    if landed is None:
        return None
    t_land, z_new = landed
    record = singularity(system, t_f + h_s, "singular position passed", at_s)
    return t_land, z_new, record, land.fill(output_times, t_land)


def step_away(system, ev, selection, form, d, t_f, z_f, history, t_end, output_times, since):
    """Move on from (t_f, z_f), just past a singular position (passed at
    ``since``), where IDA fails again because the dummy block is still
    nearly singular: the motion is re-solved further on, at 1, 2, 4, ... 2^12
    times the distance from the passage, until the block is well enough
    conditioned.  Returns ``(t_land, z_land, filled)`` or None."""
    worst = worst_level(system, ev, selection, t_f, z_f, d)
    if worst is None:
        return None
    h0 = max(t_f - since, 1e-9 * max(1.0, abs(t_f)))
    states = _hermite(history, t_f, h0) if len(form.states) else None
    land = _Landing(system, ev, selection, form, d, t_f, z_f, states)
    landed = land.first(0.0, [h0 * 2.0 ** k for k in range(13)], t_end, worst[0])
    if landed is None:
        return None
    return landed[0], landed[1], land.fill(output_times, landed[0])
