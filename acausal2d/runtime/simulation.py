"""The runtime: one simulation run of a compiled system.

:class:`Simulation` owns what changes during a run - the state selection,
the relation values, the IDA objects of the formulations used, the event
and singular-position records - and advances the run segment by segment.
A segment ends with a typed outcome of :mod:`~acausal2d.runtime.ida`
(:class:`~acausal2d.runtime.ida.Reached` a stop time,
:class:`~acausal2d.runtime.ida.RootFound` a relation or a watched block,
:class:`~acausal2d.runtime.ida.Failed`), and a handler of its own deals with
each: time events and state events (:mod:`~acausal2d.runtime.events`),
state re-selection (:mod:`~acausal2d.runtime.selection`), singular positions
passed or reached (:mod:`~acausal2d.runtime.singularities`).
"""
from __future__ import annotations

import time as _time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from ..errors import SimulationError
from . import singularities as sing
from .evaluator import Evaluator
from .event_words import describe_event
from .events import (ChatterWatch, EventIteration, check_assertions, check_jumps,
                     relation_text)
from .failure import Approach
from .ida import (LazySolver, Problem, Reached, RootFound, SundialsMessages, advance,
                  make_solver, start_solver)
from . import tiers
from .background import launch
from .buffered import Buffered
from .capi import engine_ida
from .projection import Projector
from .rows import OutputRows
from .initialize import initial_point, initialization_error
from .locate import exact_point, exact_rows, locate_on_solution
from .newton import NoConvergence, solve_consistent
from .selection import reselect, select, singularity, worst_level

if TYPE_CHECKING:
    from ..compiler.system import System
    from .selection import Singularity


OUTPUTS_PER_CALL = 20000   # output points of one IDA call (budgets are looked at between)
STATE_TOL_FACTOR = 0.03
"""IDA's local error test covers the states only (the algebraic unknowns are
solved exactly at every output point, see :mod:`~acausal2d.runtime.ida`);
it runs at this fraction of the user's tolerances, which keeps the accuracy
per rtol where testing every unknown had it.  Measured at rtol 1e-8: piston
engine energy kept to 1.3e-7 relative over 10 s in 1504 steps (testing every
unknown: 2.8e-7 in 3975 steps); double pendulum over 10 s within 2.5e-4 of
the run at rtol 1e-11 (factor 0.1: 1.2e-3)."""


class Stats:
    """Counters and wall times of a run (plain attributes: a dataclass costs
    about 0.4 ms to create at import, on the path of a process's first run)."""

    COUNTERS = ("segments", "events", "time_events", "reselections", "steps", "nfev", "njev")
    TIMES = ("wall_time", "event_time", "compile_time", "native_compile_time")

    def __init__(self):
        for name in self.COUNTERS:
            setattr(self, name, 0)
        for name in self.TIMES:
            setattr(self, name, 0.0)

    def as_dict(self):
        return {name: getattr(self, name) for name in self.COUNTERS + self.TIMES}


class RunLog:
    """What a run produced: output times and node values, events (time,
    text), singular positions, why it stopped early (None if it reached
    the stop time), its :class:`Stats` and the names of its states."""

    def __init__(self, times, nodes, events, singularities, stopped, stats, states=None):
        self.times, self.nodes, self.events = times, nodes, events
        self.singularities, self.stopped, self.stats = singularities, stopped, stats
        self.states = list(states or [])


def time_resolution(t_end: float) -> float:
    """The smallest time step a run resolves: times closer than this
    (1e-12 s, relative to |t_end| above 1 s) are one time to the run, so
    output times must lie further apart."""
    return 1e-12 * max(1.0, abs(float(t_end)))


class Simulation:
    """One run of ``system`` with parameter vector ``p`` over ``times``
    (the first is the start time); ``start``: {level-0 node index: value}
    replacing those start values (see :func:`.initialize.initial_point`);
    ``native``: the engine, ``auto``, ``now`` or ``off`` (None: the
    environment's, :func:`~acausal2d.runtime.tiers.mode`); see module
    docstring."""

    def __init__(self, system: System, p: NDArray[np.float64], times: NDArray[np.float64],
                 rtol: float, atol: float | NDArray[np.float64] | None = None,
                 progress: Callable[[float, float], object] | None = None,
                 max_steps: int | None = None, max_wall_time: float | None = None,
                 start: dict[int, float] | None = None, native: str | None = None) -> None:
        self.system, self.p = system, np.asarray(p, dtype=float)
        self.start = start
        self.max_steps, self.max_wall_time = max_steps, max_wall_time
        self.times = np.asarray(times, dtype=float)
        self.t_end = float(self.times[-1])
        self.rtol = rtol * STATE_TOL_FACTOR
        self.atol = None if atol is None else atol * STATE_TOL_FACTOR
        self.progress = progress
        self.ev = Evaluator(system, self.p)
        self.out = OutputRows(system.structure.n_var)
        self.events: list[tuple[float, str]] = []
        self.words: dict[int, str] = {}      # event index: the event in the elements' words
        self.singular: list[Singularity] = []
        self.stats = Stats()
        self.stopped: str | None = None
        self.solvers: dict[Any, tuple[Any, Any, Any, Projector]] = {}
        self.n_singular, self.watch = 0, True
        self.chatter = ChatterWatch(system, self.t_end - float(self.times[0]))
        self.eps = time_resolution(self.t_end)
        self.native = native
        self.label = getattr(system, "model_name", None)
        self._timed: tuple[Buffered, list[NDArray[np.int_]]] | None = None

    # ------------------------------------------------------------ run
    def run(self) -> RunLog:
        """Integrate to the stop time (or an early stop); returns a :class:`RunLog`."""
        wall = _time.perf_counter()
        self.spent0 = tiers.spent()
        if self.system.structure.n_var == 0:     # everything is determined: evaluate
            self.selection = None
            self.out.add_block(self.times, np.zeros((len(self.times), 0)))
            return self._log(wall)
        with SundialsMessages() as self.messages:
            self._start()
            try:
                check_assertions(self.system, self.p, self.t, self.z)
                while self.t < self.t_end - self.eps and self._step():
                    if self._over_budget(wall):
                        self._keep_last_point()
                        break
            except SimulationError as exc:
                exc.partial = self._log(wall)       # the motion up to where it stopped
                raise
            finally:       # the libraries this run asked for: compiled after it, detached
                launch(self.label)
        if self.progress is not None:
            self.progress(self.out[-1][0], self.t_end)
        return self._log(wall)

    def _log(self, wall):
        """The run log; the time spent compiling native code in this process
        (native mode ``now``) is reported apart from the simulation's wall
        time."""
        native = tiers.spent() - getattr(self, "spent0", tiers.spent())
        self.stats.native_compile_time = native
        self.stats.wall_time = _time.perf_counter() - wall - native
        T, Z = self.out.arrays()
        states = [self.system.display_name(j) for j in self.system.structure.state_nodes(
            self.selection)] if self.selection is not None else []
        log = RunLog(T, Z, self.events, self.singular, self.stopped, self.stats, states)
        log.event_texts = [(t, self.words.get(i, raw)) for i, (t, raw) in enumerate(self.events)]
        log.native_notes = []
        return log

    def _over_budget(self, wall):
        """True (and the reason in ``stopped``) when the step or wall-clock
        budget of the run is used up."""
        if self.max_steps is not None and self.stats.steps >= self.max_steps:
            self.stopped = ("stopped at t=%.6g: the step budget of %d steps is used up (raise "
                            "it with max_steps / --max-steps, or simulate a shorter time)"
                            % (self.t, self.max_steps))
        elif self.max_wall_time is not None and \
                _time.perf_counter() - wall >= self.max_wall_time:
            self.stopped = ("stopped at t=%.6g: the wall-clock budget of %g s is used up (raise "
                            "it with max_wall_time / --max-wall-time)"
                            % (self.t, self.max_wall_time))
        return self.stopped is not None

    def _keep_last_point(self):
        """A run stopped early ends with the point it reached."""
        if self.out and self.t > self.out[-1][0]:
            self.out.append((self.t, np.array(self.z)))

    def _start(self):
        t0 = float(self.times[0])
        point = initial_point(self.system, self.ev, t0, self.p, self.start)
        self.t, self.z, self.d = t0, point.z, point.d
        self.selection = point.selection or select(self.system, self.ev, t0, self.z, self.d)
        self.out.append((t0, self.z.copy()))

    def _step(self):
        """Run one segment and handle its outcome; False ends the run."""
        outcome = self._segment()
        if isinstance(outcome, Reached):
            return self._reached(outcome)
        if isinstance(outcome, RootFound):
            return self._root(outcome)
        return self._failed(outcome)

    # ------------------------------------------------------------ segments
    def _solver(self):
        """(formulation, problem, IDA) of the current selection, made once."""
        key = self.selection.dummies
        if key not in self.solvers:
            form = self.system.formulation(self.selection)
            prob = Problem(form, self.p, self.d, self._progress_hook())
            atol = self.atol if self.atol is not None else self.rtol * self.system.nominal
            atol = np.broadcast_to(np.asarray(atol, dtype=float), (form.n,)).copy()
            y0, yp0 = form.y_from(self.z)
            prob.native = engine_ida(prob, self.rtol, atol, chosen=self.native, label=self.label)
            prob.atol = atol
            solver = LazySolver(lambda t=self.t: start_solver(
                make_solver(prob, self.rtol, atol), prob, t, y0, yp0, self.rtol, atol))
            if prob.native is None:
                solver = solver._make()
            self.solvers[key] = (form, prob, solver,
                                 Projector(self.system, form, self.p, self.native))
        return self.solvers[key]

    def _progress_hook(self):
        if self.progress is None:
            return None
        t_end, progress = self.t_end, self.progress
        return lambda t: progress(t, t_end)

    def _segment(self):
        form, prob, solver, projector = self._solver()
        prob.set_relations(self.d)
        self._bias(prob)
        y0, yp0 = form.y_from(self.z)
        prob.reset_monitors(self.t, y0, yp0, self.watch)
        t_stop, outputs = self._stop_and_outputs()
        n0 = self.seg_start = len(self.out)
        self.seg_left = (self.t, np.array(self.z))
        steps0 = prob.steps
        try:
            outcome, T, Y, nfev, njev = advance(solver, prob, self.t, y0, yp0, outputs, t_stop)
        except Exception as exc:       # scikit-sundae raises on bad input at the start
            raise SimulationError("IDA could not start at t=%.6g: %s" % (self.t, exc),
                                  time=self.t) from None
        rows = projector.project(T, Y, self.d, overwrite=True)     # Y: this segment's own
        self.out.add_block(T, rows)
        self.stats.segments += 1
        self.stats.steps += prob.steps - steps0
        self.stats.nfev += nfev
        self.stats.njev += njev
        self._record_passes(outcome.passes)
        self._scan(form, n0, T, rows)
        return outcome

    def _bias(self, prob):
        """Root functions of the state relations on the side of their
        values (:meth:`~acausal2d.runtime.ida.Problem.set_biases`)."""
        rels = self.system.state_relations
        if rels and prob.n_rel:
            g = self.ev.crossings(self.t, self.z, self.d)[list(rels)]
            prob.set_biases(g, self.d[list(rels)], [self.system.relations[k].strict
                                                   for k in rels])

    def _stop_and_outputs(self):
        """(stop time, output times) of the next IDA call: up to the next
        time event, with at most :data:`OUTPUTS_PER_CALL` output points (a
        call re-initializes IDA, so the steps, and with them the solution,
        do not depend on the output grid of ordinary runs)."""
        self.time_event = self._next_time_event()
        outputs = self.times[(self.times > self.t + self.eps) & (self.times <= self.time_event)]
        if len(outputs) > OUTPUTS_PER_CALL:
            outputs = outputs[:OUTPUTS_PER_CALL]
            return float(outputs[-1]), outputs
        return self.time_event, outputs

    def _record_passes(self, passes):
        """Singular positions IDA passed (roots of the highest block's det)."""
        level = self.selection.levels[:1]
        for t, y in passes or ():
            worst = worst_level(self.system, self.ev, self.selection, t, y, self.d, level)
            self.singular.append(singularity(self.system, t, "singular position passed", worst))

    def _scan(self, form, n0, T, Z):
        """Singular positions passed between the new output points (times
        T, rows Z, after the row n0 - 1 of ``out``)."""
        if len(self.out) - n0 + 1 < 3:
            return
        before = self.out[n0 - 1] if n0 > 0 else None
        T, Z = np.asarray(T, dtype=float), np.asarray(Z, dtype=float)
        sizes = sing.scan_singular_positions(self.system, self.ev, form, self.selection, self.p,
                                             self.d, T, Z, self.singular, before, self.native)
        if 0 in sizes:
            self._solver()[1].note_size([sizes[0]])

    def _next_time_event(self):
        """The earliest scheduled time event after t (or the stop time)."""
        if self.system.time_event_fn is None:
            return self.t_end
        g, rate = self._time_relation_values()
        best = self.t_end
        for gk, rk in zip(g, rate):
            if rk != 0.0:
                tk = self.t - gk / rk
                if self.t + self.eps < tk < best:
                    best = tk
        return best

    def _time_relation_values(self):
        """(g, dg/dt) of the time relations at t: ``time_event_fn`` through
        a :class:`~acausal2d.runtime.buffered.Buffered` bound once per run (a
        plain CasADi call converts its arguments: 0.2-0.3 ms at each of the
        compressor's 292 segments)."""
        if self._timed is None:
            fn = self.system.time_event_fn
            self._timed = (Buffered(fn, [np.zeros(1), self.p]),
                           [np.asarray(fn.sparsity_out(k).find(), dtype=int) for k in (0, 1)])
        buf, where = self._timed
        buf.args[0][0] = self.t
        buf.eval()
        n = len(self.system.time_relations)
        g, rate = np.zeros(n), np.zeros(n)
        g[where[0]], rate[where[1]] = buf.outs
        return g, rate

    # ------------------------------------------------------------ outcomes
    def _reached(self, outcome):
        self.t, self.z = outcome.t, np.array(outcome.y)
        if self.t >= self.t_end - self.eps:
            return False
        if self.t >= self.time_event - self.eps:
            self._time_event()
        elif len(self.out) and self.out[-1][0] == self.t:
            self.z = self.out[-1][1].copy()         # the consistent output row
        return True

    def _time_event(self):
        """Flip the time relations due now and settle."""
        g, rate = self._time_relation_values()
        due = [k for k, gk, rk in zip(self.system.time_relations, g, rate)
               if rk != 0.0 and abs(gk / rk) <= 1e-9 * max(1.0, abs(self.t))]
        self.stats.time_events += 1
        self._event(self.z, due)

    def _root(self, outcome):
        self.t = outcome.t
        if outcome.relations:
            rels = [self.system.state_relations[k] for k in outcome.relations]
            self._state_event(outcome, rels)
            return True
        if outcome.near:
            return self._apply(Approach(self, outcome, self._solver()).near())
        self.z = np.array(outcome.y)
        self._monitor(outcome.monitors)
        return True

    def _state_event(self, outcome, rels):
        """The relations ``rels`` crossed on IDA's interpolant: the event on
        the exact solution (:mod:`~acausal2d.runtime.locate`).  With states,
        at IDA's root with the other unknowns re-solved; without, at the
        root of the exact solution - none if it has no root there."""
        states = list(self._solver()[0].states)
        if states:
            self._event(exact_point(self.ev, self.t, outcome.y, self.d, states), rels)
            return
        rows = [row for row in self.out[self.seg_start:] if row[0] < outcome.t]
        points = [self.seg_left] + rows + [(outcome.t, np.array(outcome.y))]
        t, z, flipped = locate_on_solution(self.system, self.ev, self.d, points, rels,
                                           self.time_event)
        self.out.keep_until(t, self.seg_start)
        late = self.times[(self.times > outcome.t) & (self.times < t)]
        self.out.extend(exact_rows(self.ev, self.d, points[-2], (t, z), late))
        self.t = t
        if flipped:
            self._event(z, flipped)
        else:
            self.z = z

    def _event(self, z_left, flipped):
        """Relations ``flipped`` switch at t: record both limits, settle."""
        wall = _time.perf_counter()
        form = self._solver()[0]
        if not (self.out and self.out[-1][0] == self.t):     # an output row may be there
            self.out.append((self.t, z_left.copy()))
        d = self.d.copy()
        d[flipped] = 1.0 - d[flipped]
        held = list(form.states)
        it = EventIteration(self.system, self.ev, self._reinit_failure)
        z, d = it.settle(self.t, z_left, d, held)
        changed = list(np.nonzero(d != self.d)[0])
        check_jumps(self.system, self.t, z_left, z, changed)
        d_left, self.z, self.d = self.d, z, d
        self.out.append((self.t, z.copy()))
        reinits = it.reinit.texts() if it.reinit is not None else []
        if changed or reinits:   # else a root IDA found again just past one settled by its rate
            self.stats.events += 1
            text = "; ".join([self.system.relations[k].text for k in changed] + reinits)
            words = describe_event(self, changed, z_left, d_left, z, d) if changed else ""
            self.words[len(self.events)] = "; ".join([w for w in [words] if w] + reinits)
            self.events.append((self.t, text))
        self.chatter.record(self.t, changed or flipped)
        self.stats.event_time += _time.perf_counter() - wall
        check_assertions(self.system, self.p, self.t, z)

    def _reinit_failure(self, t, exc):
        text = "; ".join(relation_text(self.system, k) for k in range(len(self.system.relations)))
        return SimulationError("Re-initialization after the event at t=%.6g failed (relations "
                               "%s):\n%s" % (t, text, initialization_error(
                                   self.system, [], exc)), time=t)

    def _monitor(self, monitors):
        """A watched dummy block decayed: re-select, or record a singular position."""
        form = self._solver()[0]
        levels = [self.selection.levels[form.monitor_levels[m]] for m in monitors]
        new, singular = reselect(self.system, self.ev, self.selection, levels, self.t, self.z,
                                 self.d)
        if new is not self.selection:
            self._switch(new)
        elif singular is not None:
            self._record_singular(singular)

    def _switch(self, selection):
        """Continue with a new state selection from the current point."""
        self.stats.reselections += 1
        self.events.append((self.t, "state re-selection"))
        self.selection = selection
        form = self._solver()[0]
        try:
            self.z = solve_consistent(self.ev, self.t, self.z, self.d, list(form.states),
                                      self.z[list(form.states)])
        except NoConvergence as exc:
            raise SimulationError("Re-initialization after the state re-selection at t=%.6g "
                                  "failed:\n%s" % (self.t, initialization_error(
                                      self.system, form.states, exc)), time=self.t) from None

    def _record_singular(self, singular):
        last = self.singular[-1] if self.singular else None
        if last is not None and set(last["elements"]) == set(singular["elements"]) \
                and last["kind"] == singular["kind"]:
            last["time"], last["condition"] = singular["time"], singular["condition"]
        else:
            self.singular.append(singular)
            self.events.append((self.t, "singular position in %s"
                                % ", ".join(singular["elements"])))
        self.n_singular += 1
        if self.n_singular > sing.MAX_SINGULAR_EVENTS:
            self.watch = False

    def _failed(self, outcome):
        """IDA failed: a better state choice, a step budget used up, a
        singular position to step over, a limit position - or an error."""
        if outcome.t > self.t:
            new, _ = reselect(self.system, self.ev, self.selection, None, outcome.t,
                              np.array(outcome.y), self.d)
            if new is not self.selection:
                self.t, self.z = outcome.t, np.array(outcome.y)
                self._switch(new)
                return True
        return self._apply(Approach(self, outcome, self._solver()).resolve())

    def _apply(self, decision):
        """Carry out a :class:`~acausal2d.runtime.failure.Decision`; False ends the run."""
        self.out.extend(decision.rows)
        self.events.extend(decision.events)
        self.singular.extend(decision.singular)
        if decision.t is not None:
            self.t, self.z = decision.t, decision.z
        if decision.stopped is not None:
            self.stopped = decision.stopped
        return decision.go_on
