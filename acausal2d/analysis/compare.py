"""Comparing simulation results with reference results (e.g. from Dymola or
OpenModelica) inside a tolerance tube.

Typical use::

    from acausal2d.analysis.compare import compare
    cmp = compare("result.csv", "reference.csv", abs_tol=1e-3, plot_dir="plots")
    print(cmp.table())
    assert cmp.passed

Both files are CSV files with one header row.  Our result files have a first
column ``time`` and dotted variable names; Modelica tools write quoted
headers (``"Time","body.phi"``) and repeat rows at events (the two rows at an
event time are the left and the right limit of the signals) and often at the
end of the simulation.  :func:`read_csv` reads both.

How a signal is checked
-----------------------
Our curve is evaluated on the reference time grid with a cubic per piece
(see :class:`_Pieces`): Hermite where our result holds the signal's
derivative ``der(name)`` (a Result object passed directly, or a CSV with
such columns), otherwise a not-a-knot cubic spline through our output
points; at our own output times our values are used as they are.  Its
error is of order h^4 in the output spacing h, below the integrator's own
error at its default tolerance, so a converged result written at a coarse
grid does not fail (linear interpolation, of order h^2, did: 8e-3 on the
double pendulum's 10 ms grid).  Interpolation never crosses an event: the
rows of a file are split into pieces at repeated time values, and each
piece is interpolated on its own.
At a reference event (a repeated reference time) the first reference row is
compared with the left limit of our curve and the last row with the right
limit.  Our event is allowed to lie slightly away from the reference event
(by at most ``event_tol``); a reference point that falls on one of our events
but is not itself an event row is compared with whichever of our limits is
closer.  A step at an event time therefore does not cause a false failure.

The tolerance tube has a constant half-width per signal:

* ``abs_tol`` only: the half-width is ``abs_tol``;
* ``rel_tol`` only: the half-width is ``rel_tol * max(|ref|)``, where the
  maximum is taken over the whole reference signal (so a signal that crosses
  zero is not held to an impossibly tight tolerance near its zero crossings);
* both: the larger of the two;
* neither: ``abs_tol = 2e-3`` (:data:`DEFAULT_ABS_TOL`).

A signal passes if the largest deviation ``|ours - ref|`` over all reference
points is at most the half-width, no value is NaN, and our result covers the
whole reference time range.

The csv-compare tube (``time_tol``)
-----------------------------------
With a time tolerance the check follows Modelica's csv-compare tool: the
reference curve (piecewise linear, vertical at its repeated event rows) is
widened by ``time_tol`` in time and by the half-width in value; the lower
and upper tube at time t are the smallest and largest reference value
within ``[t - time_tol, t + time_tol]``, minus and plus the half-width.  Our
curve must lie inside at every reference time (interpolated as above) and
at every one of our own output points in the reference's time range, both
rows of our events included.  The reported deviation is the distance of our
curve from the reference's time window (0 inside it).  A step or an event
shifted by less than ``time_tol`` therefore passes, a wrong level does not.
``until`` compares the reference points up to that time only.
"""
from typing import Any, Optional
from dataclasses import dataclass, field

import numpy as np

from ..errors import Acausal2dError
from ..io.files import safe_filename  # noqa: F401  (public here since 0.1)
from ..io.tables import CELL_LIMIT, _check_time, _few, read_csv  # noqa: F401  (public here too)
from .compare_inputs import check_options, load_table, select_signals, table_units

DEFAULT_ABS_TOL = 2e-3
"""Absolute tolerance used when neither ``abs_tol`` nor ``rel_tol`` is given."""

EVENT_TIME_TOL = 1e-5
"""Default distance (relative to the reference time span) within which one
of our event times is taken to be the same event as a reference time."""

_RANGE_EPS = 1e-9
"""Relative slack when checking that our result covers the reference times."""


# ---------------------------------------------------------------------------
# evaluating our curve on the reference grid
# ---------------------------------------------------------------------------

def _event_groups(t):
    """Index arrays of the rows at each repeated time value, in time order."""
    same = np.diff(t) == 0
    if not same.any():
        return []
    starts = np.flatnonzero(same & ~np.r_[False, same[:-1]])
    groups = []
    for s in starts:
        e = s + 1
        while e + 1 < t.size and t[e + 1] == t[s]:
            e += 1
        groups.append(np.arange(s, e + 1))
    return groups


class _Pieces:
    """Our curve between events: piece k runs over rows ``a[k] .. b[k]``
    (inclusive) of our time vector.  Each piece is interpolated on its own
    with a cubic: Hermite where our result holds the derivative of the
    signal (``der(name)``; states and their aliases), otherwise a not-a-knot
    cubic spline through the output points.  Either has an error of order
    h^4 in the output spacing h, below the integrator's own error at its
    default tolerance (linear interpolation, of order h^2, is not)."""

    def __init__(self, t, a, b):
        self.t, self.a, self.b = t, np.asarray(a), np.asarray(b)

    def piece_of(self, x, events):
        """Index of the piece containing each time of ``x``."""
        if not events.size:
            return np.zeros(np.size(x), dtype=int)
        return np.searchsorted(events, x, side="right")

    def evaluate(self, y, dy, pieces, x):
        """Values of the signal ``y`` (derivative ``dy`` or None) at the
        times ``x``, each in its piece of ``pieces`` (clamped to the piece)."""
        from scipy.interpolate import CubicHermiteSpline, CubicSpline
        pieces = np.asarray(pieces, dtype=int)
        x = np.asarray(x, dtype=float)
        out = np.empty(x.shape)
        for k in np.unique(pieces):
            sel = pieces == k
            i, j = int(self.a[k]), int(self.b[k]) + 1
            tk = self.t[i:j]
            xk = np.clip(x[sel], tk[0], tk[-1])
            if tk.size == 1:
                out[sel] = y[i]
            elif dy is not None:
                out[sel] = CubicHermiteSpline(tk, y[i:j], dy[i:j])(xk)
            elif tk.size >= 4:
                out[sel] = CubicSpline(tk, y[i:j])(xk)
            else:
                out[sel] = np.interp(xk, tk, y[i:j])
            hit = np.minimum(np.searchsorted(tk, xk), tk.size - 1)
            exact = tk[hit] == xk                   # at our own output points: our values
            vals = out[sel]
            vals[exact] = y[i + hit[exact]]
            out[sel] = vals
        return out


class _Plan:
    """How our curve is evaluated at each reference time.  Depends only on
    the two time vectors, so it is built once for all signals."""

    def __init__(self, t_ours, t_ref, event_tol=None):
        self.n_ref = t_ref.size
        self.t_ref = t_ref
        span = float(t_ref[-1] - t_ref[0]) if t_ref.size > 1 else 0.0
        scale = span if span > 0 else max(abs(float(t_ref[0])), 1.0)
        if event_tol is None:
            event_tol = EVENT_TIME_TOL * scale
        eps = _RANGE_EPS * scale

        self.in_range = (t_ref >= t_ours[0] - eps) & (t_ref <= t_ours[-1] + eps)

        groups = _event_groups(t_ours)
        events = np.array([t_ours[g[0]] for g in groups])
        # piece k runs from the last row of event k-1 to the first row of event k
        self.pieces = _Pieces(t_ours, [0] + [g[-1] for g in groups],
                              [g[0] for g in groups] + [t_ours.size - 1])
        # primary evaluation: the piece that contains the reference time
        self.piece = self.pieces.piece_of(t_ref, events)
        # reference points at one of our events: candidates (reference row,
        # piece or -1, our row for a middle event row)
        self.cj, self.cpiece, self.crow = (np.array(v, dtype=int) for v in
                                           _candidates(t_ref, events, groups, event_tol))

    def evaluate(self, y_ours, y_ref, dy_ours=None):
        """Our values on the reference grid."""
        vals = self.pieces.evaluate(y_ours, dy_ours, self.piece, self.t_ref)
        if self.cj.size:
            direct = self.cpiece < 0
            cv = np.empty(self.cj.size)
            cv[direct] = y_ours[self.crow[direct]]
            cv[~direct] = self.pieces.evaluate(y_ours, dy_ours, self.cpiece[~direct],
                                               self.t_ref[self.cj[~direct]])
            d = np.abs(cv - y_ref[self.cj])
            d = np.where(np.isnan(d), np.inf, d)
            order = np.lexsort((d, self.cj))
            cj = self.cj[order]
            first = order[np.r_[True, cj[1:] != cj[:-1]]]
            vals[self.cj[first]] = cv[first]
        return vals


def _candidates(t_ref, events, groups, event_tol):
    """For reference points within ``event_tol`` of one of our events: the
    limits of our curve they may be compared with (see the module doc)."""
    cj, cpiece, crow = [], [], []
    if not events.size:
        return cj, cpiece, crow
    ref_role = _roles(t_ref)
    q = np.clip(np.searchsorted(events, t_ref), 1, events.size) - 1
    q_next = np.minimum(q + 1, events.size - 1)
    q = np.where(np.abs(events[q_next] - t_ref) < np.abs(events[q] - t_ref), q_next, q)
    for j in np.flatnonzero(np.abs(events[q] - t_ref) <= event_tol):
        qe, role = q[j], ref_role[j]
        cands = []
        if role in ("left", "any"):
            cands.append((qe, -1))
        if role in ("right", "any"):
            cands.append((qe + 1, -1))
        if role == "any":
            cands += [(-1, r) for r in groups[qe][1:-1]]
        for piece, row in cands:
            cj.append(j)
            cpiece.append(piece)
            crow.append(row)
    return cj, cpiece, crow


def _roles(t):
    """Per row: 'left' (first row of an event), 'right' (last row of an
    event), or 'any' (a single row, or a middle row of an event)."""
    role = np.array(["any"] * t.size, dtype=object)
    for g in _event_groups(t):
        role[g[0]] = "left"
        role[g[-1]] = "right"
    return role


# ---------------------------------------------------------------------------
# comparison
# ---------------------------------------------------------------------------

@dataclass
class SignalComparison:
    """The outcome for one signal.

    ``name`` is the reference column, ``our_name`` the column of our result
    it was compared with, ``max_deviation`` the largest ``|ours - ref|`` and
    ``time`` the reference time where it occurs, ``tolerance`` the half-width
    of the tube, ``passed`` the verdict and ``message`` an explanation when a
    check other than the tolerance failed (time range, NaN values), ``unit``
    the signal's unit as the result or the reference declares it ('' if
    neither does).
    """
    name: str
    our_name: str
    max_deviation: float
    time: float
    tolerance: float
    passed: bool
    message: str = ""
    unit: str = ""
    # data for plotting
    ref_time: Optional[np.ndarray] = field(default=None, repr=False)
    ref_values: Optional[np.ndarray] = field(default=None, repr=False)
    our_on_ref: Optional[np.ndarray] = field(default=None, repr=False)
    our_time: Optional[np.ndarray] = field(default=None, repr=False)
    our_values: Optional[np.ndarray] = field(default=None, repr=False)
    tube_low: Optional[np.ndarray] = field(default=None, repr=False)
    tube_high: Optional[np.ndarray] = field(default=None, repr=False)


@dataclass
class Comparison:
    """Result of :func:`compare`.

    ``rows`` holds one :class:`SignalComparison` per signal, ``plots`` the
    PNG files written; ``passed`` is true if every signal passed.
    """
    rows: list
    plots: list = field(default_factory=list)
    time_tol: Optional[float] = None
    unmatched: list = field(default_factory=list)
    only_common: bool = False

    @property
    def passed(self):
        """True if there is at least one signal, all of them passed, and
        every reference signal was compared (or ``only_common`` was set)."""
        return bool(self.rows) and all(r.passed for r in self.rows) \
            and (self.only_common or not self.unmatched)

    @property
    def failed(self):
        """The rows of the signals that failed."""
        return [r for r in self.rows if not r.passed]

    def table(self):
        """A fixed-width text table: signal, max deviation, at time,
        tolerance, result; followed by explanations of failures and a
        summary line."""
        def num(x, fmt):
            return "n/a" if x is None or not np.isfinite(x) else format(x, fmt)

        head = ("signal", "max deviation", "at time", "tolerance", "result")
        body = []
        for r in self.rows:
            label = r.name if r.our_name == r.name else "%s -> %s" % (r.name, r.our_name)
            body.append((label, num(r.max_deviation, ".4e"), num(r.time, ".6g"),
                         num(r.tolerance, ".4e"), "PASS" if r.passed else "FAIL"))
        widths = [max(len(row[i]) for row in [head] + body) for i in range(len(head))]

        def fmt(row):
            cells = [row[0].ljust(widths[0])]
            cells += [row[i].rjust(widths[i]) for i in range(1, 4)]
            cells.append(row[4].ljust(widths[4]))
            return "  ".join(cells).rstrip()

        lines = [fmt(head), "  ".join("-" * w for w in widths)]
        lines += [fmt(row) for row in body]
        notes = [r for r in self.rows if r.message]
        if notes:
            lines.append("")
            lines += ["%s: %s" % (r.name, r.message) for r in notes]
        n_fail = len(self.failed)
        lines.append("")
        if self.time_tol is not None:
            lines.append("tube with time tolerance %.6g s (deviation: distance from the "
                         "reference within that time)" % self.time_tol)
        lines += self._unmatched_lines()
        lines.append("%d of %d signals passed%s" % (
            len(self.rows) - n_fail, len(self.rows),
            "" if not n_fail else "; FAILED: " + ", ".join(r.name for r in self.failed)))
        return "\n".join(lines)

    def _unmatched_lines(self):
        if not self.unmatched:
            return []
        n = len(self.unmatched)
        return ["%d reference signal%s not compared (no counterpart in the result): %s"
                % (n, "" if n == 1 else "s", ", ".join(self.unmatched)),
                "accepted by --only-common (only_common=True)" if self.only_common else
                "FAILED: every reference signal must be compared; pair them with --map "
                "REF=OURS or accept the common ones with --only-common (only_common=True)"]

    def __str__(self):
        return self.table()


def _tolerance(y_ref, abs_tol, rel_tol):
    """Half-width of the tube of one signal (module documentation)."""
    finite_ref = y_ref[np.isfinite(y_ref)]
    tol = float(abs_tol) if abs_tol is not None else 0.0
    if rel_tol is not None:
        scale = float(np.max(np.abs(finite_ref))) if finite_ref.size else 0.0
        tol = max(tol, float(rel_tol) * scale)
    return tol


def _range_extrema(y, i0, i1):
    """Minimum and maximum of ``y[i0[k]:i1[k]]`` for every k (a sparse table
    of minima and maxima over power-of-two runs; empty runs give +inf and
    -inf)."""
    lo_tab, hi_tab = [y], [y]
    while 2 ** len(lo_tab) <= y.size:
        half = 2 ** (len(lo_tab) - 1)
        lo_tab.append(np.minimum(lo_tab[-1][:-half], lo_tab[-1][half:]))
        hi_tab.append(np.maximum(hi_tab[-1][:-half], hi_tab[-1][half:]))
    length = i1 - i0
    empty = length <= 0
    level = np.floor(np.log2(np.where(empty, 1, length))).astype(int)
    lo = np.full(i0.shape, np.inf)
    hi = np.full(i0.shape, -np.inf)
    for k in np.unique(level[~empty]):
        sel = (level == k) & ~empty
        a, b = i0[sel], i1[sel] - 2 ** k
        lo[sel] = np.minimum(lo_tab[k][a], lo_tab[k][b])
        hi[sel] = np.maximum(hi_tab[k][a], hi_tab[k][b])
    return lo, hi


def _envelope(t_ref, y_ref, t_check, time_tol):
    """Lowest and highest value of the reference curve (piecewise linear,
    vertical at repeated event rows) within ``time_tol`` of each time of
    ``t_check``."""
    a = np.clip(t_check - time_tol, t_ref[0], t_ref[-1])
    b = np.clip(t_check + time_tol, t_ref[0], t_ref[-1])
    lo, hi = _range_extrema(y_ref, np.searchsorted(t_ref, a, side="left"),
                            np.searchsorted(t_ref, b, side="right"))
    for edge in (a, b):
        v = np.interp(edge, t_ref, y_ref)
        lo, hi = np.minimum(lo, v), np.maximum(hi, v)
    return lo, hi


def _tube_check(t_ref, y_ref, ours_on_ref, t_ours, y_ours, time_tol):
    """csv-compare tube: our curve at the reference times and at our own
    output points (inside the reference's time range) against the envelope
    of the reference within ``time_tol``.  Returns (time, deviation beyond
    the envelope) of every checked point and the envelope at the reference
    times (for the plot)."""
    inside = (t_ours >= t_ref[0]) & (t_ours <= t_ref[-1])
    t_chk = np.concatenate([t_ref, t_ours[inside]])
    y_chk = np.concatenate([ours_on_ref, y_ours[inside]])
    lo, hi = _envelope(t_ref, y_ref, t_chk, time_tol)
    dev = np.maximum(np.maximum(lo - y_chk, y_chk - hi), 0.0)
    dev[np.isnan(y_chk) | np.isnan(lo) | np.isnan(hi)] = np.nan
    return t_chk, dev, lo[:t_ref.size], hi[:t_ref.size]


def _verdict(times, dev, usable, messages):
    """(max deviation, its time, NaN message or None) over the usable points."""
    nan = usable & np.isnan(dev)
    if nan.any():
        first = np.flatnonzero(nan)[0]
        messages.append("%d value%s NaN (first at t=%.6g)"
                        % (nan.sum(), " is" if nan.sum() == 1 else "s are", times[first]))
        usable = usable & ~nan
    if not usable.any():
        return float("nan"), float("nan")
    idx = np.flatnonzero(usable)
    k = idx[np.argmax(dev[idx])]
    return float(dev[k]), float(times[k])


def _compare_signal(plan, t_ours, cols, t_ref, y_ref, names, tol, time_tol, range_msg):
    """The :class:`SignalComparison` of one (reference name, our name) pair."""
    ref_name, our_name = names
    y_ours = cols[our_name]
    ours = plan.evaluate(y_ours, y_ref, cols.get("der(%s)" % our_name))
    messages = [range_msg] if range_msg else []
    if time_tol is None:
        times, dev = t_ref, np.abs(ours - y_ref)
        usable = plan.in_range.copy()
        lo = hi = y_ref
    else:
        times, dev, lo, hi = _tube_check(t_ref, y_ref, ours, t_ours, y_ours, time_tol)
        usable = np.r_[plan.in_range, np.ones(times.size - t_ref.size, dtype=bool)]
    max_dev, at = _verdict(times, dev, usable, messages)
    passed = not messages and max_dev <= tol
    return SignalComparison(
        name=ref_name, our_name=our_name, max_deviation=max_dev, time=at,
        tolerance=tol, passed=bool(passed), message="; ".join(messages),
        ref_time=t_ref, ref_values=y_ref, our_on_ref=np.where(plan.in_range, ours, np.nan),
        our_time=t_ours, our_values=y_ours, tube_low=lo - tol, tube_high=hi + tol)


def _range_message(plan, t_ref, t_ours):
    n_out = int((~plan.in_range).sum())
    if not n_out:
        return ""
    return ("the reference runs from t=%.6g to %.6g but the result only from t=%.6g to %.6g "
            "(%d reference point%s outside)" % (t_ref[0], t_ref[-1], t_ours[0], t_ours[-1],
                                                n_out, "" if n_out == 1 else "s"))


def _cut(t_ref, ref_cols, until):
    """The reference rows up to time ``until``."""
    if until is None:
        return t_ref, ref_cols
    keep = t_ref <= until
    if not keep.any():
        raise Acausal2dError("until=%g lies before the reference's first time %g"
                             % (until, t_ref[0]))
    return t_ref[keep], {k: v[keep] for k, v in ref_cols.items()}


def compare(result: Any, reference: Any, signals: Any = None, mapping: Any = None,
            abs_tol: Any = None, rel_tol: Any = None, plot_dir: Any = None,
            event_tol: Any = None, time_tol: Any = None, until: Any = None,
            only_common: bool = False) -> "Comparison":
    """Compare our ``result`` with a ``reference`` signal by signal.

    ``result`` is a :class:`~acausal2d.result.Result`, a CSV file path
    (see :func:`read_csv`) or a ``(time, columns)`` tuple; ``reference`` a
    CSV path or a tuple.  ``signals`` lists the reference columns to check
    (default: every reference column).  A reference column is matched by
    its name, by ``mapping`` (reference name: our name) or by the Modelica
    array names the library declares (``body.r[1]`` is our ``body.x``, see
    :mod:`acausal2d.analysis.compare_inputs`).  Reference columns without
    a counterpart are listed in the table and in ``Comparison.unmatched``
    and make the comparison fail unless ``only_common=True``.  NaN or
    infinite values are an error naming the file, signal and row.
    ``until`` compares the reference points up to that time only.

    Our curve is evaluated at the reference times with a cubic interpolant
    per event-free piece (Hermite where the result holds ``der(name)``),
    see :class:`_Pieces`.

    Tolerance: the tube half-width is ``abs_tol``, or ``rel_tol`` times the
    largest absolute value of the reference signal over the whole run, or the
    larger of the two if both are given; ``abs_tol`` defaults to
    :data:`DEFAULT_ABS_TOL` (2e-3) if neither is given.  Without
    ``time_tol`` the deviation is measured at the reference points;
    ``event_tol`` (seconds; default :data:`EVENT_TIME_TOL` times the
    reference time span) is how far one of our events may lie from a
    reference event.  With ``time_tol`` (seconds) the check is Modelica
    csv-compare's tube: the reference curve widened by ``time_tol`` in time
    and the tolerance in value must contain our curve at the reference
    times and at our own output points, so a step shifted by less than
    ``time_tol`` passes.  See the module documentation.

    Reference times outside the time range of our result make the signal
    fail (with a message).  Signals missing from either side raise
    :class:`~acausal2d.errors.Acausal2dError`.

    With ``plot_dir``, one PNG per signal is written there (``<signal>.png``,
    unsafe characters replaced by ``_``) showing the reference, our curve,
    the tolerance tube and the deviation.

    Returns a :class:`Comparison`.
    """
    check_options(abs_tol, rel_tol, time_tol, until, event_tol, signals, mapping, plot_dir,
                  only_common)
    if abs_tol is None and rel_tol is None:
        abs_tol = DEFAULT_ABS_TOL
    t_ours, our_cols = load_table(result, "result")
    t_ref, ref_cols = load_table(reference, "reference")
    t_ref, ref_cols = _cut(t_ref, ref_cols, until)
    pairs, unmatched = select_signals(ref_cols, our_cols, signals, mapping)
    plan = _Plan(t_ours, t_ref, event_tol)
    range_msg = _range_message(plan, t_ref, t_ours)
    rows = [_compare_signal(plan, t_ours, our_cols, t_ref, ref_cols[ref_name],
                            (ref_name, our_name), _tolerance(ref_cols[ref_name], abs_tol, rel_tol),
                            time_tol, range_msg)
            for ref_name, our_name in pairs]
    units = {**table_units(reference), **table_units(result)}
    for r in rows:
        r.unit = units.get(r.our_name) or units.get(r.name, "")
    cmp = Comparison(rows=rows, time_tol=time_tol, unmatched=unmatched, only_common=only_common)
    if plot_dir is not None:
        cmp.plots = plot_comparison(cmp, plot_dir)
    return cmp


def plot_comparison(comparison, plot_dir):
    """Write one PNG per signal of ``comparison`` into ``plot_dir`` (see
    :func:`acausal2d.visual.comparison.plot_comparison`); returns the paths."""
    from ..visual.comparison import plot_comparison as plot   # matplotlib only when drawing
    return plot(comparison, plot_dir)
