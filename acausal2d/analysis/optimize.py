"""Design optimisation through the DAE: choose parameter values that
minimise a run metric, subject to bounds and metric constraints.

::

    import acausal2d
    opt = acausal2d.optimize("models/cabinet_door.py",
                             vary={"spring.k": (938, 500, 1500), "B0.r[0]": (-0.296, -0.4, -0.2)},
                             objective="max(abs(drive.tau))")
    print(opt.report()); opt.write("out/optimize")

How it works
------------
Every evaluation simulates the compiled model at the trial values (no
recompilation); the objective and the constraints are metrics of the run
(:mod:`acausal2d.analysis.metrics`) or, in Python, functions of the
Result.  The optimiser is SLSQP (``scipy.optimize.minimize``) on the
parameters scaled by ``max(|start|, (upper - lower)/10)``, with the
central-difference Jacobians of :class:`~acausal2d.analysis.trials.Trials`
(all runs of one Jacobian at once, in parallel on Dask with
``scheduler``).  A peak objective ``max(E)`` (e.g. ``max(abs(drive.tau))``,
the peak residual torque) is not differentiable where the peak moves from
one time to another; it is solved in epigraph form: minimise a bound ``s``
subject to ``E(t_i) <= s`` at every output time (``abs`` gives two smooth
constraints per time), a smooth problem whose solution is the minimax
design.

A peak constraint ``max(E) <= V`` (and ``min(E) >= V``) stays one
constraint for SLSQP: its value is the largest ``E(t_i) - V`` over the
output points and its gradient that of the point where the peak lies (the
gradient of the maximum wherever the peak stays at one point).  One row
per output time instead makes SLSQP's linearised
subproblem inconsistent from a start that violates the constraint: points
before and after the peak ask for opposite steps (the mass-spring-damper
of tests/test_optimize_edges.py stopped after 3 runs from d = 10 and 25;
with one row it reaches the analytic d* = 33.0800 from 10, 25 and 50).
The KKT check at the returned point takes the constraint as its rows
``E(t_i) <= V`` at every output time, the same feasible set, so a peak
reached at several times at once (a tie) gets a multiplier per time.  At
such a tie the one row converges more slowly (measured: 18 SLSQP
iterations instead of 5 for two equal peaks at the ends of the run).

A trial point whose run fails gets a large objective and violated
constraints (the line search steps back) and is listed in ``infeasible``.
Success is decided by the KKT check of
:func:`~acausal2d.analysis.optimality.kkt_check` at the returned point
(gradients and constraint Jacobians recomputed there), never by SLSQP's
exit flag; the constraints active at the optimum are reported with their
multipliers.
"""
import time as _time
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.optimize import Bounds, minimize

from ..errors import Acausal2dError
from ..options import RunOptions
from .metrics import Expression, parse_constraint
from .trials import Trials, check_fixed_apart, parse_free
from .optimality import kkt_check
from .fit import _check_free
from .optimize_report import OptimizeResult

if TYPE_CHECKING:
    from .optimize_report import OptimizeResult

KKT_TOL = 1e-5
"""Tolerance of the scaled KKT measures that decide success (finite
differences of runs at rtol 1e-8 give gradients to about 1e-6)."""


ACTIVE_TOL = 1e-6
"""Scaled distance below which a constraint (a peak of the objective
included) counts as active in the KKT check: SLSQP meets its active
constraints to about 1e-10; neighbouring output points of a peak, a
distance of O(h^2) below it, are not active."""


class _Metric:
    """An objective or constraint: an :class:`Expression` or a Python
    function of the Result (run on the worker as ``functions[k]``)."""

    def __init__(self, spec, known, index, sense=1.0, limit=0.0, label=None):
        self.sense, self.limit = float(sense), float(limit)
        if callable(spec):
            self.expr, self.func, self.key = None, spec, "__f%d" % index
            self.text = label or getattr(spec, "__name__", "function")
            self.kind = None
        else:
            self.expr = spec if isinstance(spec, Expression) else Expression(spec, known)
            self.func, self.key, self.text = None, None, label or self.expr.text
            self.kind = self.expr.kind

    @property
    def signals(self):
        return [] if self.expr is None else [s for s in self.expr.signals if s != "time"]

    def value(self, t, values):
        """The metric's number."""
        if self.expr is None:
            return float(np.asarray(values[self.key]).ravel()[0])
        return self.expr.evaluate(t, values)

    def smooth(self, t, values, peak):
        """The metric as g <= 0 values: the series of a peak (``peak``: the
        kind that is split per time point), else one value."""
        if self.kind == peak and peak is not None:
            return self.expr.vector(t, values)
        return np.array([self.value(t, values)])


def _metrics(objective, constraints, known):
    obj = _Metric(objective, known, 0)
    cons = []
    for k, c in enumerate(constraints or ()):
        if isinstance(c, str):
            expr, sense, limit = parse_constraint(c, known)
            cons.append(_Metric(expr, known, k + 1, sense, limit, c))
        else:
            func, op, limit = c
            if op not in ("<=", ">="):
                raise Acausal2dError("a constraint is (function, '<=' or '>=', value), got %r"
                                     % (op,))
            cons.append(_Metric(func, known, k + 1, 1.0 if op == "<=" else -1.0, limit,
                                "%s %s %g" % (getattr(func, "__name__", "function"), op, limit)))
    return obj, cons


class _Problem:
    """The scaled optimisation problem: variables ``z = x / d`` (and the
    epigraph bound ``s / f0`` last when the objective is a peak)."""

    def __init__(self, trials, obj, cons, times, d, lo, hi):
        self.trials, self.obj, self.cons, self.times = trials, obj, cons, times
        self.d, self.lo, self.hi = d, lo, hi
        self.epigraph = obj.kind == "max"
        self._cache = {}
        self.f0 = self.g_scale = None

    def parts(self, values):
        """(objective vector, [constraint vectors as g <= 0 in their units])."""
        t = self.times
        f = self.obj.smooth(t, values, "max")
        gs = []
        for c in self.cons:
            peak = "max" if c.sense > 0 else "min"
            gs.append(c.sense * (c.smooth(t, values, peak) - c.limit))
        return f, gs

    def flat(self, values):
        f, gs = self.parts(values)
        return np.concatenate([f] + gs)

    def x_of(self, z):
        return np.asarray(z[:self.d.size]) * self.d

    def evaluate(self, z):
        """(objective vector, constraint list) at z; None for a failed run
        or a metric that is not a number there (listed as infeasible)."""
        key = tuple(np.round(self.x_of(z), 15))
        if key not in self._cache:
            values, _ = self.trials.run([self.x_of(z)])[0]
            parts = None if values is None else self.parts(values)
            bad = None if parts is None else self.not_a_number(parts)
            if bad is not None:
                self.trials.failures.append((dict(zip(self.trials.names, self.x_of(z))),
                                             "%s is not a number there" % bad))
                parts = None
            self._cache[key] = parts
        return self._cache[key]

    def not_a_number(self, parts):
        """The text of the first metric with a NaN or infinite value, or None."""
        f, gs = parts
        for metric, v in zip([self.obj] + self.cons, [f] + list(gs)):
            if not np.all(np.isfinite(v)):
                return "%s %s" % ("the objective" if metric is self.obj else "the constraint",
                                  metric.text)
        return None

    def jacobian(self, z):
        """Jacobian of the flat vector [f, g...] with respect to z (x part)."""
        key = ("J",) + tuple(np.round(self.x_of(z), 15))
        if key not in self._cache:
            J, _ = self.trials.jacobian(self.x_of(z), self.flat, self.lo, self.hi,
                                        scale=self.d)
            self._cache[key] = J * self.d
        return self._cache[key]

    # --- the scaled problem as SLSQP and the KKT check see it -------------------

    def setup(self, z0):
        """Scales from the start run (raises if the start does not run)."""
        parts = self.evaluate(z0)
        if parts is None:
            point, err = self.trials.failures[-1]
            nan = err.endswith("is not a number there")
            raise Acausal2dError("at the start values %s: %s; choose another start%s" % (
                ", ".join("%s=%g" % kv for kv in point.items()),
                err if nan else "the model does not run: " + err,
                " or a metric that is a number there" if nan else ""))
        f, gs = parts
        self.f0 = max(float(np.max(np.abs(f))), 1e-300)
        self.g_scale = [max(abs(c.limit), float(np.max(np.abs(g))), 1e-12)
                        for c, g in zip(self.cons, gs)]
        self.sizes = [f.size] + [g.size for g in gs]
        return f

    def objective(self, z):
        if self.epigraph:
            return float(z[-1])
        parts = self.evaluate(z)
        return 10.0 if parts is None else float(parts[0][0]) / self.f0

    def objective_grad(self, z):
        if self.epigraph:
            return np.r_[np.zeros(self.d.size), 1.0]
        return self.jacobian(z)[0] / self.f0

    def g_values(self, z, split=True):
        """All inequality values, g <= 0 feasible, scaled: a peak
        constraint ``max(E) <= V`` as one row per output time (``split``,
        the KKT check's exact rows) or as one row, its largest (SLSQP's)."""
        parts = self.evaluate(z)
        if parts is None:
            rows = self.sizes[1:] if split else [1] * len(self.cons)
            return np.ones(sum(rows) + (self.sizes[0] if self.epigraph else 0))
        f, gs = parts
        out = [f / self.f0 - z[-1]] if self.epigraph else []
        out += [g / s if split else np.array([np.max(g) / s]) for g, s in zip(gs, self.g_scale)]
        return np.concatenate(out + [np.zeros(0)])

    def g_jacobian(self, z, split=True):
        """Jacobian of :meth:`g_values`; a constraint's one row (not
        ``split``) is the row of its largest output point at ``z``: the
        gradient of the maximum wherever the peak stays at one point."""
        J = self.jacobian(z)
        rows, k = [], self.sizes[0]
        if self.epigraph:
            rows.append(np.column_stack([J[:k] / self.f0, -np.ones(k)]))
        parts = self.evaluate(z)
        for i, (size, s) in enumerate(zip(self.sizes[1:], self.g_scale)):
            block = J[k:k + size] / s
            if not split:
                top = int(np.argmax(parts[1][i])) if parts is not None else 0
                block = block[top:top + 1]
            rows.append(np.column_stack([block, np.zeros(len(block))]) if self.epigraph
                        else block)
            k += size
        n = self.d.size + self.epigraph
        return np.vstack(rows) if rows else np.zeros((0, n))

    def bounds(self):
        lo, hi = self.lo / self.d, self.hi / self.d
        if self.epigraph:
            lo, hi = np.r_[lo, -np.inf], np.r_[hi, np.inf]
        return lo, hi


def _slsqp(problem, z0, max_iterations, split=False):
    lo, hi = problem.bounds()
    cons = []
    if problem.epigraph or problem.cons:
        cons = [{"type": "ineq", "fun": lambda z: -problem.g_values(z, split),
                 "jac": lambda z: -problem.g_jacobian(z, split)}]
    return minimize(problem.objective, z0, jac=problem.objective_grad, method="SLSQP",
                    bounds=Bounds(lo, hi), constraints=cons,
                    options={"maxiter": max_iterations, "ftol": 1e-12})


def _kkt(problem, z):
    lo, hi = problem.bounds()
    if problem.epigraph:
        f = problem.evaluate(z)[0]
        z = np.r_[z[:-1], float(np.max(f)) / problem.f0]       # the bound made tight
    g = problem.g_values(z)
    J = problem.g_jacobian(z) if g.size else None
    # objective scale: the start's (1 after scaling), so that a zero minimum is judged
    # by its gradient against the objective's size over the search, not against 0
    return z, kkt_check(problem.objective_grad(z), z,
                        objective=max(abs(problem.objective(z)), 1.0),
                        ineq_values=g if g.size else None, ineq_jacobian=J, lower=lo, upper=hi,
                        x_scale=1.0, tol=KKT_TOL, active_tol=ACTIVE_TOL)


def _check_bounds(names, x0, lo, hi):
    """Every design parameter needs finite bounds: they scale it and bound
    the search (SLSQP's steps, the grid around the optimum)."""
    for name, start, a, b in zip(names, x0, lo, hi):
        if not (np.isfinite(a) and np.isfinite(b)):
            raise Acausal2dError("vary %s: give its bounds, NAME=START:LO:HI (e.g. %s=%g:%g:%g) "
                                 "or (start, lower, upper); optimize searches between them"
                                 % (name, name, start, start - max(abs(start), 1.0),
                                    start + max(abs(start), 1.0)))


def optimize(model: Any, vary: Any, objective: Any, constraints: Any = (), fixed: Any = None,
             stop_time: Any = None, intervals: Any = None, rtol: Any = None,
             max_iterations: int = 60, scheduler: Any = None, workers: Any = None,
             client: Any = None, model_name: Any = None,
             options: "RunOptions | None" = None) -> "OptimizeResult":
    """Minimise ``objective`` over the parameters ``vary``.

    model: a model file path, a Component subclass or a CompiledModel (this
    process only).  vary: ``{name: (start, lower, upper)}`` (or a start
    value only; ``"a.p,b.p"`` ties parameters).  objective: a metric
    expression (``"max(abs(drive.tau))"``, see
    :mod:`acausal2d.analysis.metrics`) or a function of the Result
    returning a number.  constraints: ``"EXPR<=VALUE"``/``"EXPR>=VALUE"``
    strings or ``(function, "<=", value)`` tuples.  fixed: values held;
    options: the runs' :class:`~acausal2d.options.RunOptions`, or its
    stop_time, intervals and rtol as keywords (default: the model's
    experiment); max_iterations: SLSQP's budget; scheduler, workers,
    client: the Jacobians' runs on Dask as for :func:`acausal2d.fit`.
    Returns an :class:`~acausal2d.analysis.optimize_report.OptimizeResult`.
    """
    names, x0, lo, hi = parse_free(vary, "vary")
    _check_bounds(names, x0, lo, hi)
    check_fixed_apart(names, fixed, "vary")
    span = np.where(np.isfinite(hi - lo), (hi - lo) / 10.0, 1.0)
    d = np.maximum(np.abs(x0), span)
    opts = RunOptions.of(options, "optimize", stop_time=stop_time, intervals=intervals,
                         rtol=rtol)
    t0 = _time.perf_counter()
    with Trials(model, names, [], [0.0], fixed, opts, scheduler, workers, client,
                model_name) as trials:
        cm = trials.compiled()
        _check_free(cm, names)
        obj, cons = _metrics(objective, constraints, set(cm.names))
        times = cm.run_options(opts).times()
        trials.settings.update(times=times, functions=[m.func for m in [obj] + cons],
                               signals=list(dict.fromkeys(s for m in [obj] + cons
                                                          for s in m.signals)))
        problem = _Problem(trials, obj, cons, times, d, lo, hi)
        f_start = problem.setup(x0 / d)
        z0 = np.r_[x0 / d, float(np.max(f_start)) / problem.f0] if problem.epigraph else x0 / d
        sol = _slsqp(problem, z0, max_iterations)
        z, kkt = _kkt(problem, sol.x)
        return OptimizeResult(problem, names, x0, problem.x_of(z), kkt, sol, trials,
                              _time.perf_counter() - t0)
