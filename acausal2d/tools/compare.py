"""Comparing simulation results with reference results (e.g. from Dymola or
OpenModelica) inside a tolerance tube.

Typical use::

    from acausal2d.tools.compare import compare
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
Our curve is evaluated on the reference time grid by linear interpolation.
Interpolation never crosses an event: the rows of a file are split into
pieces at repeated time values, and each piece is interpolated on its own.
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
"""
import csv
import difflib
import io
import os
import re
import sys
from dataclasses import dataclass, field

import numpy as np

from ..errors import Acausal2dError

DEFAULT_ABS_TOL = 2e-3
"""Absolute tolerance used when neither ``abs_tol`` nor ``rel_tol`` is given."""

EVENT_TIME_TOL = 1e-5
"""Default distance (relative to the reference time span) within which one
of our event times is taken to be the same event as a reference time."""

_RANGE_EPS = 1e-9
"""Relative slack when checking that our result covers the reference times."""


# ---------------------------------------------------------------------------
# reading CSV files
# ---------------------------------------------------------------------------

def _detect_delimiter(line):
    for d in (",", ";", "\t"):
        if d in line:
            return d
    return ","


def _find_time_column(names):
    for wanted in ("time", "Time"):
        if wanted in names:
            return names.index(wanted)
    for i, n in enumerate(names):
        if n.lower() == "time":
            return i
    return None


def _few(names, near=None, n=8):
    """A short, readable list of ``names`` (closest matches to ``near`` first)."""
    names = list(names)
    if not names:
        return "(none)"
    chosen = []
    if near is not None:
        chosen = difflib.get_close_matches(near, names, n=n, cutoff=0.5)
    for name in names:
        if len(chosen) >= n:
            break
        if name not in chosen:
            chosen.append(name)
    text = ", ".join(chosen)
    if len(names) > len(chosen):
        text += ", ... (%d in all)" % len(names)
    return text


def read_csv(path):
    """Read a result CSV file.

    Accepts our result files (first column ``time``, other columns named by
    dotted variable names) and Modelica/Dymola-style files (quoted headers,
    time column ``Time`` or ``time``, rows repeated at events and at the
    end).  Blank lines are skipped; the delimiter may be ``,``, ``;`` or a
    tab.

    Returns ``(time, columns)``: ``time`` is a 1-D float array (non-decreasing;
    repeated values are kept, they mark events) and ``columns`` maps every
    other column name to a float array of the same length.

    Raises :class:`~acausal2d.errors.Acausal2dError` if the file is missing,
    has no time column, contains a cell that is not a number (the message
    gives the line), or its time decreases.
    """
    fname = os.fspath(path)
    if not os.path.isfile(fname):
        raise Acausal2dError("CSV file not found: %s" % fname)
    try:
        with open(fname, newline="", encoding="utf-8-sig") as f:
            text = f.read()
    except (OSError, UnicodeDecodeError) as e:
        raise Acausal2dError("cannot read CSV file %s: %s" % (fname, e)) from None

    first = next((ln for ln in text.splitlines() if ln.strip()), None)
    if first is None:
        raise Acausal2dError("CSV file %s is empty" % fname)
    reader = csv.reader(io.StringIO(text), delimiter=_detect_delimiter(first))

    header = None
    rows, lines = [], []
    for row in reader:
        if not any(c.strip() for c in row):
            continue
        if header is None:
            header = [c.strip() for c in row]
            while header and header[-1] == "":      # trailing delimiter
                header.pop()
            for i, name in enumerate(header):
                if name == "":
                    raise Acausal2dError("%s, line %d: column %d of the header has no name"
                                         % (fname, reader.line_num, i + 1))
            seen = set()
            for name in header:
                if name in seen:
                    raise Acausal2dError("%s, line %d: column %r appears twice in the header"
                                         % (fname, reader.line_num, name))
                seen.add(name)
            continue
        ncol = len(header)
        if len(row) > ncol and not any(c.strip() for c in row[ncol:]):
            row = row[:ncol]
        if len(row) != ncol:
            raise Acausal2dError("%s, line %d: %d cells, but the header has %d columns"
                                 % (fname, reader.line_num, len(row), ncol))
        rows.append(row)
        lines.append(reader.line_num)

    itime = _find_time_column(header)
    if itime is None:
        raise Acausal2dError("%s has no time column (expected a column named 'time' or "
                             "'Time'); the header has: %s" % (fname, _few(header)))
    if not rows:
        raise Acausal2dError("%s has a header but no data rows" % fname)

    try:
        data = np.array(rows, dtype=float)
    except ValueError:
        data = np.empty((len(rows), len(header)))
        for r, (row, line) in enumerate(zip(rows, lines)):
            for c, cell in enumerate(row):
                try:
                    data[r, c] = float(cell)
                except ValueError:
                    raise Acausal2dError(
                        "%s, line %d, column %r: cannot read %r as a number"
                        % (fname, line, header[c], cell)) from None

    t = data[:, itime].copy()
    _check_time(t, "%s" % fname, lines)
    columns = {name: data[:, i].copy() for i, name in enumerate(header) if i != itime}
    return t, columns


def _check_time(t, what, lines=None):
    def where(i):
        return "line %d" % lines[i] if lines is not None else "row %d" % (i + 1)

    bad = np.flatnonzero(~np.isfinite(t))
    if bad.size:
        raise Acausal2dError("%s: time is not a finite number at %s" % (what, where(bad[0])))
    dec = np.flatnonzero(np.diff(t) < 0)
    if dec.size:
        i = dec[0] + 1
        raise Acausal2dError("%s: time is not monotonic; it goes back from %.10g to %.10g at %s"
                             % (what, t[i - 1], t[i], where(i)))


def _load(source, role):
    """``(time, columns)`` from a CSV path or a ``(time, columns)`` tuple."""
    if isinstance(source, (str, os.PathLike)):
        return read_csv(source)
    if isinstance(source, tuple) and len(source) == 2:
        t = np.asarray(source[0], dtype=float).ravel()
        if t.size == 0:
            raise Acausal2dError("the %s has no time points" % role)
        columns = {}
        for name, values in dict(source[1]).items():
            v = np.asarray(values, dtype=float).ravel()
            if v.shape != t.shape:
                raise Acausal2dError("the %s column %r has %d values but there are %d time points"
                                     % (role, name, v.size, t.size))
            columns[str(name)] = v
        _check_time(t, "the %s" % role)
        return t, columns
    raise Acausal2dError("the %s must be a CSV file path or a (time, columns) tuple, not %s"
                         % (role, type(source).__name__))


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


def _weights(t, a, b, x):
    """Linear-interpolation indices and weights of points ``x`` inside the
    pieces ``t[a:b+1]`` (clamped to the piece ends)."""
    a = np.asarray(a)
    b = np.asarray(b)
    x = np.asarray(x, dtype=float)
    i0 = np.searchsorted(t, x, side="right") - 1
    i0 = np.clip(i0, a, np.maximum(b - 1, a))
    i1 = np.minimum(i0 + 1, b)
    dt = t[i1] - t[i0]
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(dt > 0, (x - t[i0]) / np.where(dt > 0, dt, 1.0), 0.0)
    return i0, i1, np.clip(w, 0.0, 1.0)


class _Plan:
    """How our curve is evaluated at each reference time.  Depends only on
    the two time vectors, so it is built once for all signals."""

    def __init__(self, t_ours, t_ref, event_tol=None):
        self.n_ref = t_ref.size
        span = float(t_ref[-1] - t_ref[0]) if t_ref.size > 1 else 0.0
        scale = span if span > 0 else max(abs(float(t_ref[0])), 1.0)
        if event_tol is None:
            event_tol = EVENT_TIME_TOL * scale
        eps = _RANGE_EPS * scale

        self.in_range = (t_ref >= t_ours[0] - eps) & (t_ref <= t_ours[-1] + eps)

        groups = _event_groups(t_ours)
        events = np.array([t_ours[g[0]] for g in groups])
        # piece k runs from the last row of event k-1 to the first row of event k
        seg_a = np.array([0] + [g[-1] for g in groups])
        seg_b = np.array([g[0] for g in groups] + [t_ours.size - 1])

        # primary evaluation: the piece that contains the reference time
        k = np.searchsorted(events, t_ref, side="right") if events.size else \
            np.zeros(t_ref.size, dtype=int)
        self.i0, self.i1, self.w = _weights(t_ours, seg_a[k], seg_b[k], t_ref)

        # reference points at one of our events: candidate values
        cj, ci0, ci1, cw = [], [], [], []
        if events.size:
            ref_role = _roles(t_ref)
            q = np.clip(np.searchsorted(events, t_ref), 1, events.size) - 1
            q_next = np.minimum(q + 1, events.size - 1)
            q = np.where(np.abs(events[q_next] - t_ref) < np.abs(events[q] - t_ref), q_next, q)
            near = np.flatnonzero(np.abs(events[q] - t_ref) <= event_tol)
            for j in near:
                qe = q[j]
                role = ref_role[j]
                cands = []
                if role in ("left", "any"):
                    cands.append(_weights(t_ours, seg_a[qe], seg_b[qe], t_ref[j]))
                if role in ("right", "any"):
                    cands.append(_weights(t_ours, seg_a[qe + 1], seg_b[qe + 1], t_ref[j]))
                if role == "any":
                    for r in groups[qe][1:-1]:
                        cands.append((r, r, 0.0))
                for c0, c1, cwt in cands:
                    cj.append(j)
                    ci0.append(int(c0))
                    ci1.append(int(c1))
                    cw.append(float(cwt))
        self.cj = np.array(cj, dtype=int)
        self.ci0 = np.array(ci0, dtype=int)
        self.ci1 = np.array(ci1, dtype=int)
        self.cw = np.array(cw, dtype=float)

    def evaluate(self, y_ours, y_ref):
        """Our values on the reference grid."""
        vals = y_ours[self.i0] * (1.0 - self.w) + y_ours[self.i1] * self.w
        if self.cj.size:
            cv = y_ours[self.ci0] * (1.0 - self.cw) + y_ours[self.ci1] * self.cw
            d = np.abs(cv - y_ref[self.cj])
            d = np.where(np.isnan(d), np.inf, d)
            order = np.lexsort((d, self.cj))
            cj = self.cj[order]
            first = order[np.r_[True, cj[1:] != cj[:-1]]]
            vals[self.cj[first]] = cv[first]
        return vals


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
    check other than the tolerance failed (time range, NaN values).
    """
    name: str
    our_name: str
    max_deviation: float
    time: float
    tolerance: float
    passed: bool
    message: str = ""
    # data for plotting
    ref_time: np.ndarray = field(default=None, repr=False)
    ref_values: np.ndarray = field(default=None, repr=False)
    our_on_ref: np.ndarray = field(default=None, repr=False)
    our_time: np.ndarray = field(default=None, repr=False)
    our_values: np.ndarray = field(default=None, repr=False)


@dataclass
class Comparison:
    """Result of :func:`compare`.

    ``rows`` holds one :class:`SignalComparison` per signal, ``plots`` the
    PNG files written; ``passed`` is true if every signal passed.
    """
    rows: list
    plots: list = field(default_factory=list)

    @property
    def passed(self):
        """True if there is at least one signal and all of them passed."""
        return bool(self.rows) and all(r.passed for r in self.rows)

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
        lines.append("%d of %d signals passed%s" % (
            len(self.rows) - n_fail, len(self.rows),
            "" if not n_fail else "; FAILED: " + ", ".join(r.name for r in self.failed)))
        return "\n".join(lines)

    def __str__(self):
        return self.table()


def _select_signals(ref_cols, our_cols, signals, mapping):
    mapping = dict(mapping or {})
    if signals is None:
        missing_ref = [k for k in mapping if k not in ref_cols]
        if missing_ref:
            raise Acausal2dError(
                "mapped signal%s not in the reference: %s; the reference has: %s"
                % ("s" if len(missing_ref) > 1 else "", ", ".join(missing_ref),
                   _few(ref_cols, missing_ref[0])))
        pairs = [(n, mapping.get(n, n)) for n in ref_cols if mapping.get(n, n) in our_cols]
        missing_ours = [(k, v) for k, v in mapping.items() if v not in our_cols]
        if missing_ours:
            raise Acausal2dError(
                "mapped signal%s not in the result: %s; the result has: %s"
                % ("s" if len(missing_ours) > 1 else "",
                   ", ".join("%s -> %s" % kv for kv in missing_ours),
                   _few(our_cols, missing_ours[0][1])))
        if not pairs:
            raise Acausal2dError(
                "the result and the reference have no signal in common; the reference has: "
                "%s; the result has: %s (use mapping= to pair differently named signals)"
                % (_few(ref_cols), _few(our_cols)))
        return pairs

    if isinstance(signals, str):
        signals = [signals]
    signals = list(signals)
    missing_ref = [s for s in signals if s not in ref_cols]
    if missing_ref:
        raise Acausal2dError(
            "signal%s not in the reference: %s; the reference has: %s"
            % ("s" if len(missing_ref) > 1 else "", ", ".join(missing_ref),
               _few(ref_cols, missing_ref[0])))
    pairs = [(s, mapping.get(s, s)) for s in signals]
    missing_ours = [(s, o) for s, o in pairs if o not in our_cols]
    if missing_ours:
        raise Acausal2dError(
            "signal%s not in the result: %s; the result has: %s"
            % ("s" if len(missing_ours) > 1 else "",
               ", ".join(o if o == s else "%s (mapped from %s)" % (o, s) for s, o in missing_ours),
               _few(our_cols, missing_ours[0][1])))
    return pairs


def compare(result, reference, signals=None, mapping=None, abs_tol=None, rel_tol=None,
            plot_dir=None, event_tol=None):
    """Compare our ``result`` with a ``reference`` signal by signal.

    ``result`` and ``reference`` are CSV file paths (see :func:`read_csv`) or
    ``(time, columns)`` tuples.  ``signals`` lists the reference columns to
    check (default: every reference column that also exists in the result,
    after ``mapping``).  ``mapping`` maps reference names to our names, for
    signals named differently.

    Tolerance: the tube half-width is ``abs_tol``, or ``rel_tol`` times the
    largest absolute value of the reference signal over the whole run, or the
    larger of the two if both are given; ``abs_tol`` defaults to
    :data:`DEFAULT_ABS_TOL` (2e-3) if neither is given.  ``event_tol``
    (seconds; default :data:`EVENT_TIME_TOL` times the reference time span)
    is how far one of our events may lie from a reference event.  See the
    module documentation for how events are handled.

    Reference times outside the time range of our result make the signal
    fail (with a message).  Signals missing from either side raise
    :class:`~acausal2d.errors.Acausal2dError`.

    With ``plot_dir``, one PNG per signal is written there (``<signal>.png``,
    unsafe characters replaced by ``_``) showing the reference, our curve,
    the tolerance tube and the deviation.

    Returns a :class:`Comparison`.
    """
    if abs_tol is None and rel_tol is None:
        abs_tol = DEFAULT_ABS_TOL
    for name, v in (("abs_tol", abs_tol), ("rel_tol", rel_tol)):
        if v is not None and not (np.isfinite(v) and v >= 0):
            raise Acausal2dError("%s must be a non-negative number, not %r" % (name, v))

    t_ours, our_cols = _load(result, "result")
    t_ref, ref_cols = _load(reference, "reference")
    pairs = _select_signals(ref_cols, our_cols, signals, mapping)

    plan = _Plan(t_ours, t_ref, event_tol)
    n_out = int((~plan.in_range).sum())
    range_msg = ""
    if n_out:
        range_msg = ("the reference runs from t=%.6g to %.6g but the result only from t=%.6g "
                     "to %.6g (%d reference point%s outside)"
                     % (t_ref[0], t_ref[-1], t_ours[0], t_ours[-1], n_out,
                        "" if n_out == 1 else "s"))

    rows = []
    for ref_name, our_name in pairs:
        y_ref = ref_cols[ref_name]
        y_ours = our_cols[our_name]
        ours = plan.evaluate(y_ours, y_ref)
        dev = np.abs(ours - y_ref)

        finite_ref = y_ref[np.isfinite(y_ref)]
        tol = 0.0
        if abs_tol is not None:
            tol = float(abs_tol)
        if rel_tol is not None:
            scale = float(np.max(np.abs(finite_ref))) if finite_ref.size else 0.0
            tol = max(tol, float(rel_tol) * scale)

        messages = []
        if range_msg:
            messages.append(range_msg)
        usable = plan.in_range.copy()
        nan = usable & np.isnan(dev)
        if nan.any():
            first = np.flatnonzero(nan)[0]
            messages.append("%d value%s NaN (first at t=%.6g)"
                            % (nan.sum(), " is" if nan.sum() == 1 else "s are", t_ref[first]))
            usable &= ~nan
        if usable.any():
            idx = np.flatnonzero(usable)
            k = idx[np.argmax(dev[idx])]
            max_dev, at = float(dev[k]), float(t_ref[k])
        else:
            max_dev, at = float("nan"), float("nan")
        passed = not messages and max_dev <= tol
        rows.append(SignalComparison(
            name=ref_name, our_name=our_name, max_deviation=max_dev, time=at,
            tolerance=tol, passed=bool(passed), message="; ".join(messages),
            ref_time=t_ref, ref_values=y_ref, our_on_ref=np.where(plan.in_range, ours, np.nan),
            our_time=t_ours, our_values=y_ours))

    cmp = Comparison(rows=rows)
    if plot_dir is not None:
        cmp.plots = plot_comparison(cmp, plot_dir)
    return cmp


# ---------------------------------------------------------------------------
# plots
# ---------------------------------------------------------------------------

def safe_filename(name):
    """``name`` (a signal such as ``der(body.x)``) as a file name: characters
    other than letters, digits, ``.``, ``_`` and ``-`` become ``_``."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip()
    if not s or s.startswith("."):
        s = "_" + s
    return s


def plot_comparison(comparison, plot_dir):
    """Write one PNG per signal of ``comparison`` into ``plot_dir`` (created
    if needed): the reference, our curve and the tolerance tube, and below
    them the deviation with the tolerance limits.  Returns the paths."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(plot_dir, exist_ok=True)
    paths, used = [], set()
    for r in comparison.rows:
        base = safe_filename(r.name)
        stem, n = base, 2
        while stem.lower() in used:
            stem = "%s_%d" % (base, n)
            n += 1
        used.add(stem.lower())
        path = os.path.join(os.fspath(plot_dir), stem + ".png")

        fig, (ax, axd) = plt.subplots(2, 1, sharex=True, figsize=(8, 6),
                                      gridspec_kw={"height_ratios": [3, 1.3]})
        try:
            ax.fill_between(r.ref_time, r.ref_values - r.tolerance, r.ref_values + r.tolerance,
                            color="tab:blue", alpha=0.2, linewidth=0,
                            label="tolerance \u00b1%.3g" % r.tolerance)
            ax.plot(r.ref_time, r.ref_values, color="tab:blue", linewidth=1.5, label="reference")
            label = "result" if r.our_name == r.name else "result (%s)" % r.our_name
            ax.plot(r.our_time, r.our_values, color="tab:orange", linewidth=1.0,
                    linestyle="--", label=label)
            if np.isfinite(r.time):
                ax.axvline(r.time, color="tab:red", linewidth=0.8, alpha=0.6)
            ax.set_ylabel(r.name)
            ax.grid(True, alpha=0.3)
            ax.legend(loc="best", fontsize="small")
            verdict = "PASS" if r.passed else "FAIL"
            title = "%s: %s, max deviation %.3g at t=%.6g (tol %.3g)" % (
                r.name, verdict, r.max_deviation, r.time, r.tolerance)
            if r.message:
                title += "\n" + r.message
            ax.set_title(title, fontsize="medium", color="black" if r.passed else "tab:red")

            axd.plot(r.ref_time, r.our_on_ref - r.ref_values, color="tab:orange", linewidth=1.0)
            axd.axhline(r.tolerance, color="tab:blue", linewidth=0.8, linestyle=":")
            axd.axhline(-r.tolerance, color="tab:blue", linewidth=0.8, linestyle=":")
            axd.set_ylabel("result \u2212 ref")
            axd.set_xlabel("time [s]")
            axd.grid(True, alpha=0.3)
            fig.tight_layout()
            fig.savefig(path, dpi=80)
        finally:
            plt.close(fig)
        paths.append(path)
    return paths


# ---------------------------------------------------------------------------
# command-line helper
# ---------------------------------------------------------------------------

def run_compare_cli(result_csv, reference_csv, signals=None, mapping=None, abs_tol=None,
                    rel_tol=None, out_dir=None, stream=None):
    """Compare two CSV files, print the table to ``stream`` (default: the
    current ``sys.stdout``, looked up at call time) (and write plots
    into ``out_dir`` if given); return 0 if every signal passed, else 1.
    :class:`~acausal2d.errors.Acausal2dError` is left to the caller."""
    if stream is None:
        stream = sys.stdout
    cmp = compare(result_csv, reference_csv, signals=signals, mapping=mapping,
                  abs_tol=abs_tol, rel_tol=rel_tol, plot_dir=out_dir)
    print(cmp.table(), file=stream)
    if cmp.plots:
        print("%d plot%s written to %s" % (len(cmp.plots), "" if len(cmp.plots) == 1 else "s",
                                           out_dir), file=stream)
    return 0 if cmp.passed else 1
