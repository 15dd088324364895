"""IDA (SUNDIALS, through scikit-sundae) on a semi-explicit formulation.

:class:`Problem` holds the callbacks - residual, exact iteration matrix
(dense, or sparse with the formulation's pattern) and event functions - as
CasADi functions evaluated through ``Function.buffer()``; relation values
and parameters are written into the bound arrays, so one IDA object serves
a formulation across events (it is re-initialized, not rebuilt).
:func:`advance` runs it over output times up to a stop time and returns a
typed outcome.  The messages scikit-sundae prints for SUNDIALS errors are
taken out of ``sys.stdout`` while IDA runs (:class:`SundialsMessages`); no
file descriptor is redirected.
"""
import os
import sys
import warnings

import numpy as np

from .rundir import PREFIX, run_dir

# SUNDIALS' own warnings (its logger writes them to stderr by default) go to a
# file in this process's temporary folder (removed when the process ends),
# read into SundialsMessages, read when a context is made
WARNINGS_FILE = os.path.join(run_dir(), "sundials-warnings.log")
if not os.environ.get("SUNLOGGER_WARNING_FILENAME") or \
        os.path.basename(os.path.dirname(os.environ["SUNLOGGER_WARNING_FILENAME"])).startswith(
            PREFIX):        # unset, or a parent process's folder: this process's own
    os.environ["SUNLOGGER_WARNING_FILENAME"] = WARNINGS_FILE

from .buffered import Buffered  # noqa: E402
from .sundials_ext import ida_memory, suppress_algebraic  # noqa: E402
from ..options import STEPS_PER_OUTPUT  # noqa: E402

ALGEBRAIC_ATOL = 1e10    # fallback: an absolute tolerance that leaves an unknown untested
TOO_MUCH_WORK = -1    # IDA's status when it used up STEPS_PER_OUTPUT for one output interval
ROOT_RETURN, TSTOP_RETURN = 2, 1      # IDASolve's flags: a root found, the stop time reached
MONITOR_THRESHOLD = 0.25    # a watched block whose |det| dropped 4x: re-check the selection
NEAR_SINGULAR = 1e-3        # the highest block's |det| this small: a singular position ahead



def _warnings_size():
    try:
        return os.path.getsize(os.environ.get("SUNLOGGER_WARNING_FILENAME", WARNINGS_FILE))
    except OSError:
        return 0


class SundialsMessages:
    """Context manager: while it is active, the lines scikit-sundae prints
    for SUNDIALS errors (``[IDASolve, Error: -3] ...``) are collected in
    ``messages`` instead of reaching ``sys.stdout``; other output passes.
    SUNDIALS' own warnings, which its logger writes to a file of this
    process (:data:`WARNINGS_FILE`), are read into ``warnings``."""

    def __init__(self):
        self.messages, self.warnings = [], []
        self._eat_newline = False
        self._stream = None
        self._start = 0

    def __enter__(self):
        self._stream = sys.stdout
        self._start = _warnings_size()
        sys.stdout = self
        return self

    def __exit__(self, *exc):
        sys.stdout = self._stream
        self.warnings = self._read_warnings()
        return False

    def _read_warnings(self):
        path = os.environ.get("SUNLOGGER_WARNING_FILENAME", WARNINGS_FILE)
        if _warnings_size() <= self._start:
            return []
        with open(path, "r", errors="replace") as fh:
            fh.seek(self._start)
            return [" ".join(line.split("]")[-1].split()) for line in fh if line.strip()]

    def write(self, text):
        if text.startswith("\n[") and ", Error: " in text:
            self.messages.append(" ".join(text.split("]", 1)[-1].split()))
            self._eat_newline = True
            return len(text)
        if self._eat_newline and text == "\n":
            self._eat_newline = False
            return 1
        self._eat_newline = False
        return self._stream.write(text)

    def flush(self):
        self._stream.flush()

    def __getattr__(self, name):
        return getattr(self._stream, name)

    @property
    def text(self):
        """The last SUNDIALS message (earlier ones are retries of the same
        step at nearly the same time)."""
        return self.messages[-1] if self.messages else ""


class Problem:
    """IDA callbacks of one formulation; ``set_relations`` changes the
    relation values bound into them.  The event functions are, in this
    order: ``n_rel`` relation crossings, ``n_mon`` watched dummy blocks
    (|det| fell 4x since the segment began: re-check the selection),
    ``n_pass`` passages (sign of the highest block's det) and ``n_pass``
    near-singular watches (its |det| below :data:`NEAR_SINGULAR` of its
    typical size)."""

    def __init__(self, form, p, d, progress=None):
        n = form.n
        z = np.zeros(n)
        args = [np.zeros(1), z, z, np.asarray(p, float), np.asarray(d, float)]
        self.form = form
        self.steps, self.t_last = 0, None
        self.res = Buffered(form.res_fn, args)
        self.jac = Buffered(form.jac_fn, args + [np.zeros(1)])
        self.n_rel, self.n_mon, self.n_pass = form.n_rel, form.n_mon, form.n_pass
        self.n_events = self.n_rel + self.n_mon + 2 * self.n_pass
        k = self.n_mon + self.n_pass
        self.ev = Buffered(form.event_fn, args + [np.zeros(2 * k + self.n_rel)]) \
            if self.n_events else None
        self.watched = Buffered(form.watched_fn, args) if k else None
        self.ab = self.ev.args[5] if self.ev is not None else np.zeros(0)
        self.near_ref = np.zeros(self.n_pass)
        self.hook = None          # the events function given to scikit-sundae
        self.native = None        # its native driver (runtime.native), where there is one
        self.progress = progress
        self._pattern(form)
        # roots: crossings and decayed blocks stop IDA, passages do not
        self.terminal = [True] * (self.n_rel + self.n_mon) + [False] * self.n_pass \
            + [True] * self.n_pass
        self.direction = [0] * self.n_rel + [-1] * self.n_mon + [0] * self.n_pass \
            + [-1] * self.n_pass

    def _pattern(self, form):
        sparsity = form.jac_sparsity
        if form.sparse:
            import scipy.sparse as sp     # here: the native path never needs it
            self.pattern = sp.csc_matrix((np.ones(sparsity.nnz()), np.array(sparsity.row()),
                                          np.array(sparsity.colind())), shape=(form.n, form.n))
        else:
            r, c = sparsity.get_triplet()
            self.rows, self.cols = np.array(r, dtype=int), np.array(c, dtype=int)

    def _buffers(self):
        return [b for b in (self.res, self.jac, self.ev, self.watched) if b is not None]

    def set_relations(self, d):
        """Bind the relation values."""
        for b in self._buffers():
            b.args[4][:] = d

    def resfn(self, t, y, yp, res):
        if t != self.t_last:          # IDA evaluates each step attempt at a new time
            self.t_last = t
            self.steps += 1
            if self.progress is not None:
                self.progress(t)
        a = self.res.args
        a[0][0] = t
        a[1][:] = y
        a[2][:] = yp
        self.res.eval()
        res[:] = self.res.outs[0]

    def jacfn(self, t, y, yp, res, cj, JJ):
        a = self.jac.args
        a[0][0] = t
        a[1][:] = y
        a[2][:] = yp
        a[5][0] = cj
        self.jac.eval()
        if self.form.sparse:
            JJ[:] = self.jac.outs[0]
        else:
            JJ.fill(0.0)
            JJ[self.rows, self.cols] = self.jac.outs[0]

    def __call__(self, t, y, yp, events):
        """The events function scikit-sundae calls."""
        a = self.ev.args
        a[0][0] = t
        a[1][:] = y
        a[2][:] = yp
        self.ev.eval()
        events[:] = self.ev.outs[0]

    def watched_values(self, t, y, yp):
        """|det| of the monitored blocks and of the highest block."""
        a = self.watched.args
        a[0][0] = t
        a[1][:] = y
        a[2][:] = yp
        self.watched.eval()
        return np.abs(self.watched.outs[0])

    def reset_events(self):
        """Clear scikit-sundae's record of the events found so far (kept on
        the events function and never reset by it), so that a reused IDA
        object stops at the next terminal event again."""
        if hasattr(self, "_i_cnt"):
            self._i_cnt[:] = 0
            for name in ("_i", "_t", "_y", "_yp"):
                getattr(self, name).clear()

    def reset_monitors(self, t, y, yp, watch=True):
        """Watch the monitored blocks from their current |det| (if
        ``watch``) and the highest block from its typical size."""
        if self.watched is None:
            return
        k, m = self.n_mon + self.n_pass, self.n_mon
        size = self.watched_values(t, y, yp)
        self.note_size(size[m:])
        refs = np.concatenate([np.maximum(size[:m], 1e-300), np.maximum(self.near_ref, 1e-300)])
        on = np.concatenate([np.full(m, watch), size[m:] > NEAR_SINGULAR * self.near_ref])
        self.ab[:k] = np.where(on, 1.0 / refs, 0.0)
        self.ab[k:2 * k] = np.where(on, np.r_[np.full(m, -MONITOR_THRESHOLD),
                                         np.full(self.n_pass, -NEAR_SINGULAR)], 1.0)

    def set_biases(self, g, d, strict):
        """Bias each relation's root function ``g + b`` for the segment
        that starts with the crossing values ``g`` and the relation values
        ``d``: 0 where ``g`` is on the side of its value; where the value
        was decided at the event by the motion or kept (``g`` at or within
        rounding of zero on the other side), ``b`` puts ``g + b`` just on
        the value's side, so that IDA neither stops at once nor takes an
        exact zero for a root it never reports (IDA leaves a root function
        that is zero at the start out until it moves): the relation switches
        back when ``g`` moves past the value it has now."""
        if not self.n_rel:
            return
        k = self.n_mon + self.n_pass
        for i, (gi, di, st) in enumerate(zip(g, d, strict)):
            true = gi > 0 if st else gi >= 0
            side = 1.0 if di > 0.5 else -1.0
            if (true == (di > 0.5)) and gi != 0.0:
                self.ab[2 * k + i] = 0.0
                continue
            m = max(abs(gi) * 1e-12, 1e-300)
            while (gi + (side * m - gi)) * side <= 0.0:
                m *= 2.0
            self.ab[2 * k + i] = side * m - gi

    def note_size(self, size):
        """Let the typical size of the highest block's |det| grow to ``size``."""
        if self.n_pass and len(size):
            np.maximum(self.near_ref, np.max(np.atleast_2d(size), axis=0), out=self.near_ref)


def make_solver(prob, rtol, atol):
    """The scikit-sundae IDA object of a problem (see :func:`start_solver`).
    scikit-sundae (and with it scipy) is imported here, on the Python path
    only."""
    from .sundae import sksundae as sun
    form = prob.form
    n_ev = prob.n_events
    tested = form.differential
    alg = np.nonzero(~tested)[0]
    opts = dict(rtol=rtol, atol=atol, jacfn=prob.jacfn, max_num_steps=STEPS_PER_OUTPUT,
                algebraic_idx=alg if len(alg) else None)
    if form.sparse:
        opts.update(linsolver="sparse", sparsity=prob.pattern)
    if n_ev:
        opts.update(eventsfn=prob, num_events=n_ev)
    with warnings.catch_warnings():
        # with a sparsity pattern and our exact jacfn, scikit-sundae notes that its own
        # sparse approximation is not used - which is what we want
        warnings.filterwarnings("ignore", message="Custom sparse Jacobian approximation")
        return sun.ida.IDA(prob.resfn, **opts)


def start_solver(solver, prob, t, y0, yp0, rtol, atol):
    """Initialize ``solver`` at (t, y0, yp0) and leave the algebraic
    unknowns out of its local error test (IDA's ``suppressalg``): their
    values follow the states through the equations in every step, and the
    output rows are solved for them exactly
    (:mod:`~acausal2d.runtime.projection`).  Testing them as well made IDA
    take 40-400 times as many steps near singular positions and stall on
    stiff belts.  Where the setting cannot be reached, the same is done by
    giving them a huge absolute tolerance (a new IDA object)."""
    solver.init_step(t, y0, yp0)
    if suppress_algebraic(ida_memory(solver, t)):
        return solver
    loose = np.where(prob.form.differential, atol, ALGEBRAIC_ATOL * np.abs(atol) / rtol)
    solver = make_solver(prob, rtol, loose)
    solver.init_step(t, y0, yp0)
    return solver


class LazySolver:
    """The scikit-sundae IDA object of a problem with a native driver, made
    on first use (the fallback path and the step-over of singular positions
    need it; most runs never do).  Made eagerly and freed unused, its
    SuperLU_MT solver crashes on free (scikit-sundae 1.2)."""

    def __init__(self, make):
        self._make, self._solver = make, None

    def __getattr__(self, name):
        if self._solver is None:
            self._solver = self._make()
        return getattr(self._solver, name)


class Reached:
    """IDA reached the stop time."""

    def __init__(self, t, y, yp, passes=None):
        self.t, self.y, self.yp, self.passes = t, y, yp, passes


class RootFound:
    """A relation crossed (``relations``: state-relation indices) or a
    watched block decayed (``monitors``: monitor indices) at t."""

    def __init__(self, t, y, yp, relations, monitors, near=False, passes=None):
        self.t, self.y, self.yp, self.passes = t, y, yp, passes
        self.relations, self.monitors, self.near = relations, monitors, near


class Failed:
    """IDA stopped with an error; (t, y, yp) is the last point it reached."""

    def __init__(self, t, y, yp, status, message, passes=None):
        self.t, self.y, self.yp, self.passes = t, y, yp, passes
        self.status, self.message = status, message


def _passes(sol, prob, hit):
    """(time, y) of the singular positions passed (non-terminal roots)."""
    if not prob.n_pass or sol.t_events is None:
        return []
    col = prob.n_rel + prob.n_mon
    idx = np.asarray(sol.i_events)
    rows = range(len(idx) - (1 if hit else 0))
    return [(float(sol.t_events[k]), np.array(sol.y_events[k])) for k in rows if idx[k, col]]


def _tspan(t, outputs, t_stop):
    """The times of one IDA call: the start, the output times, the stop time."""
    outputs = np.asarray(outputs, dtype=float)
    end = [t_stop] if not len(outputs) or outputs[-1] < t_stop else []
    if len(outputs) + len(end) == 1:   # two times would make IDA return its internal steps
        return np.array([t, 0.5 * (t + t_stop)] + [float(x) for x in outputs] + end)
    return np.concatenate([[t], outputs, end])


def _member(values, of):
    """``np.isin(values, of)`` for float arrays (exact equality) without
    ``np.unique``, whose first call imports ``numpy.ma`` (~7 ms)."""
    ref = np.sort(np.asarray(of, dtype=float).ravel())
    values = np.asarray(values, dtype=float)
    if ref.size == 0:
        return np.zeros(values.shape, dtype=bool)
    at = np.minimum(np.searchsorted(ref, values), ref.size - 1)
    return ref[at] == values


def _advance_native(prob, tspan, y0, yp0, outputs):
    """:func:`advance` by the native driver (:mod:`~acausal2d.runtime.native`);
    None where IDA failed (the caller repeats the segment on the Python path,
    which reports the failure), except for a used-up step budget, which is
    a :class:`Failed` outcome as on the Python path (the runtime looks at
    the run and goes on)."""
    flag, T, Y, passes, last, roots, nfev, njev, steps = prob.native.run(tspan, y0, yp0)
    budget = flag == TOO_MUCH_WORK and last[0] > tspan[0]
    if flag < 0 and not budget:
        return None
    prob.steps += steps
    keep = _member(T, outputs)
    if budget:       # only the step budget of one output interval: as the Python path reports it
        outcome = Failed(*last, TOO_MUCH_WORK, "IDA took %d steps without reaching the next "
                         "output time" % STEPS_PER_OUTPUT)
    elif flag == ROOT_RETURN:
        idx = np.nonzero(roots)[0]
        m = prob.n_rel + prob.n_mon
        outcome = RootFound(last[0], last[1], last[2], [int(k) for k in idx if k < prob.n_rel],
                            [int(k) - prob.n_rel for k in idx if prob.n_rel <= k < m],
                            bool(any(k >= m + prob.n_pass for k in idx)))
    else:
        outcome = Reached(*last)
    outcome.passes = [(float(t), np.array(y)) for t, y in zip(*passes)]
    if keep.all():        # every row an output time (the usual case): no copy
        return outcome, T, Y, nfev, njev
    return outcome, T[keep], Y[keep], nfev, njev


def _solve(solver, prob, tspan, y0, yp0):
    """scikit-sundae's ``solve(tspan, y0, yp0)`` output time by output
    time through its ``init_step``/``step`` (the same IDA calls: one
    initialization, the stop time ``tspan[-1]``, the events recorded on
    ``prob`` and a terminal one ending the call).  Returns (times, y, yp,
    the last step's result: status, message, events and counts)."""
    sol = solver.init_step(tspan[0], y0, yp0)
    T, Y, YP = [sol.t], [sol.y], [sol.yp]
    t_stop, last = float(tspan[-1]), len(tspan) - 1
    k = 1
    while True:
        sol = solver.step(float(tspan[k]), "normal", t_stop)
        stop = sol.status < 0 or sol.status == TSTOP_RETURN or k == last
        if sol.status == ROOT_RETURN:      # a passage goes on; a terminal event ends the call
            stop = bool(np.any(prob._i_cnt >= prob._max_events))
            if not stop:
                continue
        T.append(sol.t)
        Y.append(sol.y)
        YP.append(sol.yp)
        if stop:
            return np.array(T), np.array(Y), np.array(YP), sol
        k += 1


def advance(solver, prob, t, y0, yp0, outputs, t_stop):
    """Integrate from (t, y0, yp0) to ``t_stop`` through ``outputs`` (the
    output times in (t, t_stop]), natively where the problem has a native
    driver.  Returns (outcome, times and rows of the output points reached,
    nfev, njev); ``outcome.passes`` lists the singular positions passed."""
    tspan = _tspan(t, outputs, t_stop)
    if getattr(prob, "native", None) is not None:
        done = _advance_native(prob, tspan, y0, yp0, outputs)
        if done is not None:
            return done
    prob.reset_events()
    ts, ys, yps, sol = _solve(solver, prob, tspan, y0, yp0)
    hit = sol.status == ROOT_RETURN
    n = len(ts) - (1 if hit else 0)
    keep = np.isin(ts[1:n], outputs)
    stats = (ts[1:n][keep], ys[1:n][keep], int(sol.nfev or 0), int(sol.njev or 0))
    passes = _passes(sol, prob, hit)
    last = len(ts) - 1
    if hit:
        idx = np.nonzero(np.asarray(sol.i_events)[-1])[0]
        y, yp = np.asarray(sol.y_events)[-1], np.asarray(sol.yp_events)[-1]
        m = prob.n_rel + prob.n_mon
        outcome = RootFound(float(sol.t_events[-1]), y, yp,
                            [int(k) for k in idx if k < prob.n_rel],
                            [int(k) - prob.n_rel for k in idx if prob.n_rel <= k < m],
                            bool(any(k >= m + prob.n_pass for k in idx)))
    elif not sol.success:
        outcome = Failed(float(ts[last]), ys[last], yps[last], sol.status, str(sol.message))
    else:
        outcome = Reached(float(ts[last]), ys[last], yps[last])
    outcome.passes = passes
    return (outcome, *stats)
