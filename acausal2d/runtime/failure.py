"""What the runtime does when IDA fails.

From the last point IDA reached, :class:`Approach` re-takes its internal
steps one by one towards the next output time.  If that goes well, IDA had
only used up its step budget and the run continues.  If the steps stall or
fail, the motion has run into a singular position: it is stepped over onto
the branch that continues the motion
(:func:`~acausal2d.runtime.singularities.step_over`), or, where it cannot
continue, the run ends at a limit position with a report.  Anything else is
an integration error naming the variable most involved.

Hand-off: :class:`Approach` reads the simulation's state and returns a
:class:`Decision` (where the run goes on, the rows, events and singular
positions to add, why it stopped); the simulation applies it.  Nothing here
writes into the simulation.
"""
import numpy as np

from ..errors import SimulationError
from . import singularities as sing
from .diagnose import non_finite
from .ida import TOO_MUCH_WORK
from ..options import STEPS_PER_OUTPUT
from .newton import NoConvergence, solve_consistent

_STALLED = 20         # steps 1e6 times shorter than the longest, in a row: IDA stalls


def _take_steps(solver, form, start, t_next, keep, max_steps):
    """Steps of IDA from ``start`` towards t_next: (last (t, y, yp) or None,
    how it stopped, times, kept node values)."""
    last, how, times, kept = None, "failed", [], []
    try:
        solver.init_step(start.t, start.y, start.yp)
        t_prev, longest, stalled = start.t, 0.0, 0
        for _ in range(max_steps):
            sol = solver.step(t_next, method="onestep", tstop=t_next)
            if not sol.success or sol.status == 2:
                break
            last = (float(sol.t), np.array(sol.y), np.array(sol.yp))
            times.append(last[0])
            kept.append(last[1][keep])
            h = last[0] - t_prev
            t_prev, longest = last[0], max(longest, h)
            stalled = stalled + 1 if h < 1e-6 * longest else 0
            if stalled >= _STALLED:
                return last, "stalled", times, kept
            if last[0] >= t_next:
                return last, "reached", times, kept
        else:
            how = "steps"
    except Exception:      # scikit-sundae raises where IDA cannot even start
        pass
    return last, how, times, kept


class Decision:
    """What :class:`Approach` decided: ``go_on`` (False ends the run), the
    point ``(t, z)`` the run continues from (None: unchanged), output
    ``rows`` (t, z) to append, ``events`` (t, text) and ``singular``
    position records to add, and ``stopped`` (why the run ended early, or
    None)."""

    def __init__(self, go_on, t=None, z=None, rows=(), events=(), singular=(), stopped=None):
        self.go_on, self.t, self.z = go_on, t, z
        self.rows, self.events, self.singular = list(rows), list(events), list(singular)
        self.stopped = stopped


class Approach:
    """Handles a :class:`~acausal2d.runtime.ida.Failed` outcome of the
    simulation ``sim`` whose current (formulation, problem, IDA) is
    ``solver`` (see module docstring); :meth:`resolve` and :meth:`near`
    return a :class:`Decision`."""

    def __init__(self, sim, failed, solver):
        self.sim, self.failed = sim, failed
        self.form, self.prob, self.solver = solver[:3]
        states = np.asarray(self.form.states, dtype=int)
        self.n_held = len(states)
        self.keep = np.concatenate([states, self.form.all_deriv[states]]).astype(int)

    def resolve(self):
        """A :class:`Decision` to continue the run or to end it at a limit
        position; or raise the integration error."""
        sim, f = self.sim, self.failed
        near = self._near_singular(f)
        if near:       # IDA crawls towards a singular position
            jump = sing.step_over(sim.system, sim.ev, sim.selection, self.form, sim.d, f.t,
                                  np.array(f.y), self._history([], []), sim.t_end, sim.times)
            if jump is not None:
                return self._passed(*jump)
        elif f.status == TOO_MUCH_WORK and f.t > sim.t:
            return self._go_on((f.t, np.array(f.y)), False)   # only the step budget
        later = sim.times[sim.times > f.t + sim.eps]
        t_next = float(later[0]) if len(later) else sim.t_end
        last, how, times, kept = _take_steps(self.solver, self.form, f, t_next, self.keep,
                                             STEPS_PER_OUTPUT)
        if last is not None and how in ("reached", "steps") and last[0] > f.t:
            return self._go_on(last, how == "reached")
        t_f, z_f = (last[0], last[1]) if last is not None else (f.t, np.array(f.y))
        jump = sing.step_over(sim.system, sim.ev, sim.selection, self.form, sim.d, t_f, z_f,
                              self._history(times, kept), sim.t_end, sim.times)
        if jump is not None:
            return self._passed(*jump)
        away = self._step_away(t_f, z_f, times, kept)
        if away is not None:
            return away
        if t_f > sim.t:
            limit, decided = sing.limit_position(sim.system, sim.ev, sim.selection, t_f, z_f,
                                                 sim.d, self._span())
            if limit is not None:
                return self._limit(limit, t_f, z_f, decided)
        raise integration_error(sim, self.form, self.prob, f)

    def near(self):
        """The highest dummy block became nearly singular (a
        :class:`~acausal2d.runtime.ida.RootFound` with ``near``): step over
        the singular position ahead, or let IDA go on without this watch
        (a limit position, or only a dip of the determinant); a
        :class:`Decision`."""
        sim, f = self.sim, self.failed
        z = np.array(f.y)
        jump = sing.step_over(sim.system, sim.ev, sim.selection, self.form, sim.d, f.t, z,
                              self._history([], []), sim.t_end, sim.times)
        if jump is not None:
            return self._passed(*jump)
        held = list(self.form.states)
        try:
            z = solve_consistent(sim.ev, f.t, z, sim.d, held, z[held])
        except NoConvergence:
            pass
        return Decision(True, f.t, z)      # the next segment watches from this |det| on

    def _near_singular(self, f):
        """True if the worst dummy block at IDA's last point is close to
        singular (see :data:`~acausal2d.runtime.singularities.WELL_CONDITIONED`)."""
        sim = self.sim
        worst = sing.worst_level(sim.system, sim.ev, sim.selection, f.t, np.array(f.y), sim.d)
        return worst is not None and worst[0] < sing.WELL_CONDITIONED

    def _go_on(self, last, reached):
        """IDA used up its step budget on a run that goes on well."""
        sim = self.sim
        t = last[0]
        held = list(self.form.states)
        try:
            z = solve_consistent(sim.ev, t, last[1], sim.d, held, last[1][held])
        except NoConvergence:
            z = np.array(last[1])
        rows = [(t, z.copy())] if reached and t in sim.times else []
        return Decision(True, t, z, rows=rows)

    def _history(self, times, kept):
        """(times, values, derivatives) of the held states at the output
        points of the current segment and the steps just taken."""
        if not self.n_held:
            return None
        seg = self.sim.out[self.sim.seg_start:]
        ts = [t for t, _ in seg] + list(times)
        rows = [z[self.keep] for _, z in seg] + list(kept)
        if not ts:
            return None
        ts, order = np.unique(np.asarray(ts), return_index=True)
        rows = np.asarray(rows)[order]
        return ts, rows[:, :self.n_held], rows[:, self.n_held:]

    def _span(self):
        sim = self.sim
        return max(sim.t_end - float(sim.times[0]), 1e-9)

    def _since(self, t_f, z_f):
        """When the singular position behind (t_f, z_f) was passed: the
        last passage recorded closely before, else where the conditioning,
        rising along the motion (:func:`~acausal2d.runtime.singularities.conditioning_trend`),
        extrapolates to zero; None if none is behind."""
        sim = self.sim
        passed = [r["time"] for r in sim.singular if r["kind"] == "singular position passed"]
        if passed and t_f - passed[-1] <= 1e-3 * self._span():
            return passed[-1]
        worst = sing.worst_level(sim.system, sim.ev, sim.selection, t_f, z_f, sim.d)
        if worst is None or worst[0] > sing.SINGULAR_CONDITION:
            return None
        sign, distance = sing.conditioning_trend(sim.system, sim.ev, sim.selection, t_f, z_f,
                                                 sim.d, self._span())
        return t_f - distance if sign > 0 else None

    def _step_away(self, t_f, z_f, times, kept):
        """Just past a singular position IDA fails again: move further on,
        or None if no singular position lies closely behind this point."""
        sim = self.sim
        since = self._since(t_f, z_f)
        if since is None:
            return None
        away = sing.step_away(sim.system, sim.ev, sim.selection, self.form, sim.d, t_f, z_f,
                              self._history(times, kept), sim.t_end, sim.times, since)
        if away is None:
            return None
        return Decision(True, away[0], away[1], rows=away[2])

    def _passed(self, t_land, z, record, filled):
        """A singular position the motion passes through: continue beyond it."""
        event = (record["time"], "singular position passed in %s" % ", ".join(record["elements"]))
        return Decision(True, t_land, z, rows=filled, events=[event], singular=[record])

    def _limit(self, limit, t_f, z_f, decided=True):
        """The run ends at a singular position: report it and keep the data
        up to the last point reached; ``decided`` False: the conditioning
        did not change beyond rounding along the drive's motion, and the
        report says that the drive's rule decided."""
        sim = self.sim
        held = list(self.form.states)
        try:
            z_f = solve_consistent(sim.ev, t_f, z_f, sim.d, held, z_f[held])
        except NoConvergence:
            pass
        stopped = ("stopped at t=%.6g: the mechanism reached a limit position in %s (its "
                   "position equations become singular; the drive cannot move further)"
                   % (limit["time"], ", ".join(limit["elements"])))
        if not decided:
            stopped += ("; the block's conditioning did not change beyond rounding along the "
                        "drive's motion, so the run stops where the drive cannot move it away")
        return Decision(False, rows=[(t_f, np.array(z_f))], singular=[limit], stopped=stopped)


def _worst_variable(sim, form, prob, f):
    """Name of the variable (of its derivative, for a derivative node) most
    involved in a near-singular iteration matrix."""
    if form.n > 600:
        return None
    a = prob.jac.args
    a[0][0], a[1][:], a[2][:], a[5][0] = f.t, f.y, f.yp, 1e3
    prob.jac.eval()
    J = np.zeros((form.n, form.n))
    r, c = form.jac_sparsity.get_triplet()
    J[r, c] = prob.jac.outs[0]
    if not np.all(np.isfinite(J)):
        bad = np.nonzero(~np.all(np.isfinite(J), axis=0))[0]
        return sim.system.node_info[int(bad[0])].name if len(bad) else None
    _, _, vt = np.linalg.svd(J)
    return sim.system.node_info[int(np.argmax(np.abs(vt[-1])))].name


def _non_finite_ahead(sim, f):
    """Text naming the equations that become inf or NaN just after IDA's
    last point (along the Taylor prediction), or None."""
    z = np.array(f.y)
    span = max(sim.t_end - float(sim.times[0]), 1e-9)
    for h in [0.0] + list(span * np.logspace(-12, -2, 11)):
        zz = sing.taylor(sim.system, z, h) if h else z
        text = non_finite(sim.system, sim.ev.residual(f.t + h, zz, sim.d), sim.p)
        if text is not None:
            return text
    return None


def integration_error(sim, form, prob, f):
    """The SimulationError for a failure the runtime cannot resolve."""
    text = _non_finite_ahead(sim, f)
    if text is not None:
        return SimulationError("At t=%.6g the motion runs into values where %s"
                               % (f.t, text), time=f.t)
    try:
        var = _worst_variable(sim, form, prob, f)
    except (np.linalg.LinAlgError, ValueError):
        var = None
    detail = sim.messages.text or f.message.strip()
    return SimulationError(
        "Integration failed at t=%.6g (IDA status %s: %s)%s." % (
            f.t, f.status, detail,
            "; the variable most involved is '%s'" % var if var else ""),
        time=f.t, status=f.status, variable=var)
