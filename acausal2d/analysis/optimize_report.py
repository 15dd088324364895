"""The outcome of :func:`acausal2d.analysis.optimize.optimize`: the
optimum, the objective before and after, the active constraints, and the
files ``optimize.json``, ``optimize.csv`` and ``optimize.png``; a grid
around the optimum confirms it independently of the optimiser."""
import itertools
import json
import os

import numpy as np

from ..io.files import atomic_path
from .sweep import expand_params
from .trials import trial_options
from ..visual.fitting import optimize_figure
from ..visual.plotting import save_figure


class OptimizeResult:
    """An optimisation (see :func:`~acausal2d.analysis.optimize.optimize`):
    ``names``, ``start``, ``optimum``, ``objective`` and
    ``objective_start``, ``constraints`` (dicts: text, value, limit,
    active, multiplier), ``success`` (the KKT check), ``message``,
    ``iterations``, ``evaluations`` (model runs), ``infeasible`` (points
    whose run failed, with the error), ``result`` and ``start_result``
    (Results), ``wall_time``, ``workers``."""

    def __init__(self, problem, names, start, optimum, kkt, sol, trials, wall_time):
        self.problem, self.names = problem, list(names)
        self.start, self.optimum = np.asarray(start), np.asarray(optimum)
        self.kkt, self.success, self.message = kkt, bool(kkt.ok), kkt.message()
        self.iterations = int(getattr(sol, "nit", 0))
        self.optimizer_message = str(sol.message)
        self.trials = trials
        cm = trials.compiled()
        self.objective_text = problem.obj.text
        self.start_result = self._run(cm, self.start)
        self.result = self._run(cm, self.optimum)
        self.objective_start = self._metric(problem.obj, self.start_result)
        self.objective = self._metric(problem.obj, self.result)
        self.constraints = self._constraints()
        self.evaluations, self.infeasible = trials.count, list(trials.failures)
        self.wall_time, self.workers = wall_time, trials.workers
        sig = problem.obj.signals
        self.signal = sig[0] if sig else None

    def _run(self, cm, x):
        return cm.simulate(params=expand_params(self.trials.point(x)),
                           options=trial_options(self.trials.settings, self.problem.times))

    def _metric(self, metric, res):
        if metric.expr is None:
            return float(metric.func(res))
        return metric.value(res.time, {n: res[n] for n in metric.signals})

    def _constraints(self):
        rows, k = [], self.problem.sizes[0] if self.problem.epigraph else 0
        mult = self.kkt.multipliers.get("ineq", np.zeros(0))
        active = set(self.kkt.active.get("ineq", []))
        for c, size in zip(self.problem.cons, self.problem.sizes[1:]):
            idx = range(k, k + size)
            rows.append({"constraint": c.text, "value": self._metric(c, self.result),
                         "limit": c.limit, "active": any(i in active for i in idx),
                         "multiplier": float(sum(mult[i] for i in idx)) if len(mult) else 0.0})
            k += size
        return rows

    @property
    def active_bounds(self):
        """Names of the varied parameters at a bound at the optimum."""
        return [self.names[i] for i in sorted(set(self.kkt.active.get("lower", []))
                                              | set(self.kkt.active.get("upper", [])))
                if i < len(self.names)]

    def to_dict(self):
        """The content of ``optimize.json``."""
        return {"optimum": dict(zip(self.names, map(float, self.optimum))),
                "start": dict(zip(self.names, map(float, self.start))),
                "objective": self.objective, "objective_start": self.objective_start,
                "objective_text": self.objective_text, "constraints": self.constraints,
                "active_constraints": [c["constraint"] for c in self.constraints if c["active"]],
                "active_bounds": self.active_bounds, "success": self.success,
                "message": self.message, "optimizer_message": self.optimizer_message,
                "iterations": self.iterations, "evaluations": self.evaluations,
                "infeasible": [{"point": p, "error": e} for p, e in self.infeasible],
                "wall_time": self.wall_time, "workers": self.workers}

    def report(self):
        """Text: optimum, objective before/after, constraints, infeasible points, verdict."""
        lines = ["%-24s %14s %14s" % ("parameter", "start", "optimum"), "-" * 54]
        lines += ["%-24s %14.8g %14.8g" % (n, a, b)
                  for n, a, b in zip(self.names, self.start, self.optimum)]
        lines.append("objective %s: %.8g -> %.8g (%d iterations, %d model runs, %.2f s%s)" % (
            self.objective_text, self.objective_start, self.objective, self.iterations,
            self.evaluations, self.wall_time,
            " on %d workers" % self.workers if self.workers else ""))
        for c in self.constraints:
            lines.append("constraint %s: %.6g%s" % (c["constraint"], c["value"],
                                                    " (active)" if c["active"] else ""))
        if self.active_bounds:
            lines.append("at a bound: " + ", ".join(self.active_bounds))
        lines += ["infeasible trial point %s: %s" % (
            ", ".join("%s=%.6g" % kv for kv in p.items()), e) for p, e in self.infeasible]
        lines.append(("optimum: " if self.success else "NOT an optimum: ") + self.message)
        return "\n".join(lines)

    def grid(self, rel=0.01, points=3):
        """Objective on the grid of ``points`` values per varied parameter
        within +-``rel`` (relative to the scale) around the optimum, inside
        the bounds: returns (grid points (k x n), objective values; NaN
        where the run failed)."""
        p = self.problem
        axes = [np.clip(x + np.linspace(-rel, rel, points) * d, lo, hi)
                for x, d, lo, hi in zip(self.optimum, p.d, p.lo, p.hi)]
        xs = np.array(list(itertools.product(*axes)))
        values = []
        for vals, _ in self.trials.run(list(xs)):
            values.append(np.nan if vals is None else
                          p.obj.value(p.times, vals))
        return xs, np.array(values)

    def write(self, out_dir):
        """Write ``optimize.json``, ``optimize.csv`` (the optimal run) and
        ``optimize.png`` into ``out_dir``; returns the paths."""
        os.makedirs(out_dir, exist_ok=True)
        path = os.path.join(out_dir, "optimize.json")
        with atomic_path(path) as tmp:
            with open(tmp, "w", encoding="utf-8") as fh:
                json.dump(self.to_dict(), fh, indent=2)
        files = [path, self.result.to_csv(os.path.join(out_dir, "optimize.csv"))]
        if self.signal is not None:
            files.append(save_figure(optimize_figure(self),
                                     os.path.join(out_dir, "optimize.png")))
        return files
