"""Integration with IDA (SUNDIALS, through scikit-sundae).

Residual, iteration matrix dF/dy + cj dF/dyp and zero-crossing functions
are CasADi functions evaluated through ``Function.buffer()``.  The run is
split into segments at events: a relation changes its value (then the
system is re-initialized with the states held), or a dynamically selected
dummy block becomes ill-conditioned (then the states are re-selected at
that point, see :mod:`acausal2d.runtime.singularities`).  Event instants are
recorded twice (left and right limit).
"""
import os
import sys
import warnings

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402
import sksundae as sun  # noqa: E402

from .buffered import Buffered  # noqa: E402
from ..errors import InitializationError, SimulationError  # noqa: E402
from .initialize import solve_consistent  # noqa: E402
from .singularities import (MAX_SINGULAR_EVENTS, MONITOR_THRESHOLD, consistent_for,  # noqa: E402
                            limit_position, reselect, scan_singular_positions, step_over)



_MAX_STEPS = 5000     # IDA steps per output interval before a run is looked at again
_STALLED = 20         # steps 1e6 times shorter than the longest, in a row: IDA stalls


class _Problem:
    """IDA callbacks of one formulation with fixed parameters and relation
    values; ``monitor`` switches the watching of dummy blocks."""

    def __init__(self, form, p, d, monitor=True):
        n = form.n
        t = np.zeros(1)
        z = np.zeros(n)
        self.form = form
        self.steps, self.t_last = 0, None
        self.res = Buffered(form.res_fn, [t, z, z, p, d])
        self.jac = Buffered(form.jac_fn, [t, z, z, p, d, np.zeros(1)])
        self.ev = Buffered(form.event_fn, [t, z, z, p, d]) if form.event_fn is not None else None
        self.n_rel = form.n_rel
        self.n_mon = form.n_mon if monitor else 0
        self.mon_ref = np.ones(form.n_mon)
        sparsity = form.jac_sparsity
        if form.sparse:
            colind = np.array(sparsity.colind())
            row = np.array(sparsity.row())
            self.pattern = sp.csc_matrix((np.ones(len(row)), row, colind), shape=(n, n))
        else:
            r, c = sparsity.get_triplet()
            self.rows, self.cols = np.array(r, dtype=int), np.array(c, dtype=int)

    def resfn(self, t, y, yp, res):
        if t != self.t_last:          # IDA evaluates each step attempt at a new time
            self.t_last = t
            self.steps += 1
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

    def _eval_events(self, t, y, yp):
        a = self.ev.args
        a[0][0] = t
        a[1][:] = y
        a[2][:] = yp
        self.ev.eval()
        return self.ev.outs[0]

    def monitor_values(self, t, y, yp):
        """|det| of the watched dummy blocks."""
        return np.abs(self._eval_events(t, y, yp)[self.n_rel:])

    def eventsfn(self, t, y, yp, events):
        out = self._eval_events(t, y, yp)
        n = self.n_rel
        events[:n] = out[:n]
        if self.n_mon:
            events[n:] = np.abs(out[n:]) / self.mon_ref - MONITOR_THRESHOLD


def _solver(prob, rtol, atol):
    form = prob.form
    n_ev = prob.n_rel + prob.n_mon
    opts = dict(rtol=rtol, atol=atol, jacfn=prob.jacfn, max_num_steps=_MAX_STEPS,
                algebraic_idx=np.where(~form.differential)[0] if np.any(~form.differential)
                else None)
    if form.sparse:
        opts.update(linsolver="sparse", sparsity=prob.pattern)
    if n_ev:
        ev = prob.eventsfn

        def eventsfn(t, y, yp, events):
            ev(t, y, yp, events)
        eventsfn.terminal = [True] * n_ev
        eventsfn.direction = [0] * prob.n_rel + [-1] * prob.n_mon
        opts.update(eventsfn=eventsfn, num_events=n_ev)
    with warnings.catch_warnings():
        # with a sparsity pattern and our exact jacfn, scikit-sundae notes that its own
        # sparse approximation is not used - which is what we want
        warnings.filterwarnings("ignore", message="Custom sparse Jacobian approximation")
        return sun.ida.IDA(prob.resfn, **opts)


def _worst_variable(cm, form, prob, t, y, yp):
    """Name of the variable most involved in a near-singular iteration matrix."""
    try:
        a = prob.jac.args
        a[0][0], a[1][:], a[2][:], a[5][0] = t, y, yp, 1e3
        prob.jac.eval()
        if form.n > 600:
            return None
        J = np.zeros((form.n, form.n))
        r, c = form.jac_sparsity.get_triplet()
        J[r, c] = prob.jac.outs[0]
        _, _, vt = np.linalg.svd(J)
        k = int(np.argmax(np.abs(vt[-1])))
        return cm.node_names[form.y_nodes[k]]
    except Exception:
        return None


class _CapturedStderr:
    """Capture what SUNDIALS and scikit-sundae print while IDA runs: the
    C-level stdout and stderr go to a temporary file, and Python's
    ``sys.stdout``/``sys.stderr`` (scikit-sundae prints its error messages
    with ``print``; in a notebook or under pytest these are Python objects,
    not the descriptors) to a string buffer.  The text is available as
    ``.text``."""

    def __enter__(self):
        import io
        import tempfile
        sys.stdout.flush()
        sys.stderr.flush()
        self._file = tempfile.TemporaryFile(mode="w+b")
        self._saved = [os.dup(1), os.dup(2)]
        os.dup2(self._file.fileno(), 1)
        os.dup2(self._file.fileno(), 2)
        self._streams = (sys.stdout, sys.stderr)
        self._python = io.StringIO()
        sys.stdout = sys.stderr = self._python
        return self

    def __exit__(self, *exc):
        sys.stdout, sys.stderr = self._streams
        try:   # C stdio buffers must be written while the redirection holds
            import ctypes
            ctypes.CDLL(None).fflush(None)
        except (OSError, AttributeError):
            pass
        os.dup2(self._saved[0], 1)
        os.dup2(self._saved[1], 2)
        for fd in self._saved:
            os.close(fd)
        self._file.seek(0)
        text = self._file.read().decode("utf-8", "replace") + self._python.getvalue()
        self.text = text.strip()
        self._file.close()
        return False


class _StartError(Exception):
    pass


def _run_solve(solver, t, remaining, y0, yp0, form, out_t, out_z):
    """One IDA call over all remaining output times; stops at an event."""
    tspan = np.concatenate([[t], remaining])
    mid = len(tspan) == 2
    if mid:   # two times would make IDA return its internal steps
        tspan = np.array([t, 0.5 * (t + tspan[1]), tspan[1]])
    try:
        sol = solver.solve(tspan, y0, yp0)
    except Exception as exc:
        raise _StartError(exc) from None
    ts, ys, yps = np.asarray(sol.t), np.asarray(sol.y), np.asarray(sol.yp)
    event = sol if sol.status == 2 else None
    n = len(ts) - (1 if event is not None else 0)
    keep = np.arange(2 if mid else 1, n)
    if len(keep):
        out_t.extend(ts[keep].tolist())
        out_z.extend(form.nodes_from(ys[keep], yps[keep]))
    if event is not None:
        event = _Event(float(sol.t_events[-1]), np.asarray(sol.y_events)[-1],
                       np.asarray(sol.yp_events)[-1], np.asarray(sol.i_events)[-1])
    last = _Event(float(ts[-1]), ys[-1], yps[-1], None) if len(ts) else None
    return _Outcome(sol, last), event


def _run_steps(solver, t, remaining, y0, yp0, form, out_t, out_z, progress, t_end):
    """Output by output, reporting progress; stops at an event."""
    try:
        solver.init_step(t, y0, yp0)
    except Exception as exc:
        raise _StartError(exc) from None
    sol = None
    for t_out in remaining:
        sol = solver.step(float(t_out))
        if sol.status == 2:
            return _Outcome(sol, None), _Event(float(sol.t), np.asarray(sol.y),
                                               np.asarray(sol.yp), np.asarray(sol.i_events))
        if not sol.success:
            break
        out_t.append(float(sol.t))
        out_z.append(form.nodes_from(sol.y, sol.yp))
        progress(float(sol.t), t_end)
    last = _Event(float(sol.t), np.asarray(sol.y), np.asarray(sol.yp), None) \
        if sol is not None else None
    return _Outcome(sol, last), None


def _approach(prob, rtol, atol, start, t_next, keep):
    """Re-take IDA's internal steps from the point ``start`` (the last
    output it reached) towards the next output time after a failure.

    Returns ``(t, node values, how, steps)`` of the last step completed,
    ``how`` saying why it stopped: "reached" (t_next), "steps" (the step
    budget used up while the run goes well), "stalled" (near a singular
    position IDA may go on with steps of vanishing length) or "failed";
    ``steps`` holds (times, z[keep]) of all steps taken.  None if it cannot
    take a single step."""
    form = prob.form
    solver = _solver(prob, rtol, atol)
    last, how, times, kept = None, "failed", [], []
    try:
        with _CapturedStderr():
            solver.init_step(start.t, start.y, start.yp)
            t_prev, longest, stalled = start.t, 0.0, 0
            for _ in range(_MAX_STEPS):
                sol = solver.step(t_next, method="onestep", tstop=t_next)
                if not sol.success or sol.status == 2:
                    break
                last = (float(sol.t), np.asarray(sol.y).copy(), np.asarray(sol.yp).copy())
                times.append(last[0])
                kept.append(form.nodes_from(last[1], last[2])[keep])
                h = last[0] - t_prev
                t_prev, longest = last[0], max(longest, h)
                stalled = stalled + 1 if h < 1e-6 * longest else 0
                if stalled >= _STALLED:
                    how = "stalled"
                    break
                if last[0] >= t_next:
                    how = "reached"
                    break
            else:
                how = "steps"
    except Exception:
        pass
    if last is None:
        return None
    return last[0], form.nodes_from(last[1], last[2]), how, (times, kept)


def _state_history(out_t, out_z, seg_start, approach, keep, n_held):
    """(times, values, derivatives) of the held states at the output points
    of the current segment and the steps of the approach; ``keep`` lists the
    ``n_held`` held nodes followed by their derivative nodes."""
    if not n_held:
        return None
    ts = list(out_t[seg_start:])
    rows = [z[keep] for z in out_z[seg_start:]]
    if approach is not None:
        ts += approach[3][0]
        rows += approach[3][1]
    if not ts:
        return None
    ts, order = np.unique(np.asarray(ts), return_index=True)
    rows = np.asarray(rows)[order]
    return ts, rows[:, :n_held], rows[:, n_held:]


class _Event:
    __slots__ = ("t", "y", "yp", "i_events")

    def __init__(self, t, y, yp, i_events):
        self.t, self.y, self.yp, self.i_events = t, y, yp, i_events


class _Outcome:
    """Status of a segment run and the last point reached."""

    def __init__(self, sol, last):
        self.success = bool(sol.success) if sol is not None else True
        self.status = sol.status if sol is not None else 0
        self.message = str(getattr(sol, "message", ""))
        self.nfev = int(getattr(sol, "nfev", 0) or 0) if sol is not None else 0
        self.njev = int(getattr(sol, "njev", 0) or 0) if sol is not None else 0
        self.last = last


def integrate(cm, z0, d0, p, times, rtol, atol, progress=None):
    """Integrate the compiled model ``cm`` from consistent node values z0.

    times: output times (the first is the start time).  progress: optional
    callable(t, t_end) called at every output point (it throttles itself).
    Returns (times, node values [n_times x n_nodes], events, stats); stats
    counts segments, events, state re-selections, integrator steps
    (attempted, including rejected ones), residual and Jacobian evaluations."""
    t_end = float(times[-1])
    t = float(times[0])
    z = np.array(z0, dtype=float)
    d = np.array(d0, dtype=float)
    out_t, out_z = [t], [z.copy()]
    events = []
    stats = {"segments": 0, "events": 0, "reselections": 0, "steps": 0, "nfev": 0, "njev": 0}
    selection = cm.select(t, z, p, d)
    nominal = np.array(cm.nominal)
    singularities = []
    stats["singularities"] = singularities
    n_singular = 0
    monitor = True
    eps = 1e-12 * max(1.0, abs(t_end))
    while t < t_end - eps:
        form = cm.formulation(selection)
        prob = _Problem(form, p, d, monitor)
        seg_start = len(out_t)
        y0, yp0 = form.y_from(z)
        if prob.n_mon:
            prob.mon_ref = np.maximum(prob.monitor_values(t, y0, yp0), 1e-300)
        a = atol if atol is not None else rtol * nominal[form.y_pos]
        solver = _solver(prob, rtol, a)
        remaining = times[times > t + eps]
        stats["segments"] += 1
        event = None
        with _CapturedStderr() as err:
            try:
                if progress is None:
                    sol, event = _run_solve(solver, t, remaining, y0, yp0, form, out_t, out_z)
                else:
                    sol, event = _run_steps(solver, t, remaining, y0, yp0, form, out_t, out_z,
                                            progress, t_end)
                start_error = None
            except _StartError as exc:
                sol, start_error = None, exc.args[0]
        if start_error is not None:
            raise SimulationError("IDA could not start at t=%.6g: %s" % (t, start_error),
                                  time=t) from None
        stats["steps"] += prob.steps
        if sol is not None:
            stats["nfev"] += sol.nfev
            stats["njev"] += sol.njev
        scan_singular_positions(cm, form, selection, p, d, out_t, out_z, seg_start,
                                 singularities)
        limit = None
        failed = event is None and sol is not None and not sol.success and sol.last is not None
        if failed and sol.last.t > t:
            z_last = form.nodes_from(sol.last.y, sol.last.yp)
            new_sel, _ = reselect(cm, selection, form, None, sol.last.t, z_last, p, d)
            if new_sel is not selection:       # the state choice failed, not the mechanism
                stats["reselections"] += 1
                events.append((sol.last.t, "state re-selection"))
                selection, t = new_sel, sol.last.t
                z = consistent_for(cm, selection, t, z_last, p, d)
                continue
        if failed:
            t_next = float(times[times > sol.last.t + eps][0]) \
                if np.any(times > sol.last.t + eps) else t_end
            held = np.asarray(form.y_nodes)[form.differential]
            keep = np.concatenate([held, np.asarray(cm.R.A)[held]]).astype(int)
            approach = _approach(prob, rtol, a, sol.last, t_next, keep)
            if approach is not None and approach[2] in ("reached", "steps") \
                    and approach[0] > sol.last.t:
                # IDA used up its step budget on a run that goes on well: next segment
                t = approach[0]
                z = consistent_for(cm, selection, t, approach[1], p, d)
                if approach[2] == "reached":
                    out_t.append(t)
                    out_z.append(z.copy())
                continue
            history = _state_history(out_t, out_z, seg_start, approach, keep, len(held))
            if approach is None:      # IDA stopped right where it failed: start from there
                approach = (sol.last.t, form.nodes_from(sol.last.y, sol.last.yp), "failed")
            jump = step_over(cm, selection, p, d, approach[0], approach[1], history, t_end,
                             times)
            if jump is not None:
                # a singular position the motion passes through: continue beyond it
                t_land, z, record, filled = jump
                singularities.append(record)
                events.append((record["time"], "singular position passed in %s"
                               % ", ".join(record["elements"])))
                for t_out, z_out in filled:
                    out_t.append(t_out)
                    out_z.append(z_out)
                t = t_land
                continue
            if sol.last.t > t:
                limit = limit_position(cm, selection, p, d, sol.last.t,
                                       form.nodes_from(sol.last.y, sol.last.yp))
        if limit is not None:
            # the run ends at a singular position: report it and keep the data
            singularities.append(limit)
            stats["stopped"] = ("stopped at t=%.6g: the mechanism reached a limit position in %s "
                                "(its position equations become singular; the drive cannot "
                                "move further)" % (limit["time"], ", ".join(limit["elements"])))
            break
        if event is None and sol is not None and not sol.success:
            last = sol.last
            tf = last.t if last is not None else t
            var = _worst_variable(cm, form, prob, tf, last.y, last.yp) if last is not None \
                else None
            detail = " ".join(err.text.split()) or sol.message.strip()
            raise SimulationError(
                "Integration failed at t=%.6g (IDA status %s: %s)%s." % (
                    tf, sol.status, detail,
                    "; the variable most involved is '%s'" % var if var else ""),
                time=tf, status=sol.status, variable=var)
        if event is None:
            break
        te = event.t
        ze = form.nodes_from(event.y, event.yp)
        which = np.nonzero(np.asarray(event.i_events).ravel())[0]
        rel_hits = [int(k) for k in which if k < prob.n_rel]
        out_t.append(te)
        out_z.append(ze)
        if rel_hits:
            stats["events"] += 1
            d_new = d.copy()
            for k in rel_hits:
                d_new[k] = 1.0 - d[k]
            held = list(np.asarray(form.y_nodes)[form.differential])
            text = "; ".join(cm.relations[k].text for k in rel_hits)
            try:
                z_new = solve_consistent(cm.init_system, te, ze, p, d_new, held, ze[held],
                                         cm.describe_equation, cm.node_name)
            except InitializationError as exc:
                raise SimulationError("Re-initialization after the event at t=%.6g (%s) failed:"
                                      "\n%s" % (te, text, exc), time=te) from None
            d = d_new
            events.append((te, text))
            z = z_new
            out_t.append(te)
            out_z.append(z.copy())
        else:
            z = ze
            hits = [int(k) - prob.n_rel for k in which if k >= prob.n_rel]
            new_sel, singular = reselect(cm, selection, form, hits, te, z, p, d)
            if new_sel is not selection:
                stats["reselections"] += 1
                selection = new_sel
                events.append((te, "state re-selection"))
                z = consistent_for(cm, selection, te, z, p, d)
            elif singular is not None:
                if singularities and set(singularities[-1]["elements"]) == \
                        set(singular["elements"]) and singularities[-1]["kind"] == singular["kind"]:
                    singularities[-1]["time"] = te
                    singularities[-1]["condition"] = singular["condition"]
                else:
                    singularities.append(singular)
                    events.append((te, "singular position in %s" % ", ".join(singular["elements"])))
                n_singular += 1
                if n_singular > MAX_SINGULAR_EVENTS:
                    monitor = False
        t = te
    if progress is not None:
        progress(out_t[-1], t_end)
    return np.array(out_t), np.array(out_z), events, stats
