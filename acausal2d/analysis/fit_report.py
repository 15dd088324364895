"""The outcome of :func:`acausal2d.analysis.fit.fit`: estimates with their
standard errors, intervals and correlations, the comparison of the fitted
run with the data, and the files ``fit.json``, ``fit.csv`` and plots."""
import json
import os

import numpy as np

from ..io.files import atomic_path

COMPARE_TUBE = 4.0
"""Half-width of the comparison tube in residual standard deviations."""


class FitResult:
    """A fit (see :func:`~acausal2d.analysis.fit.fit`): ``names``,
    ``start``, ``estimate``, ``std``, ``ci95`` (n x 2), ``correlation``,
    ``cost`` and ``cost_start`` (1/2 sum of squared weighted residuals),
    ``success`` (the optimality check), ``message``, ``budget_exhausted``,
    ``evaluations`` (model runs), ``infeasible`` (points whose run failed,
    with the error), ``warnings`` (parameters the data cannot separate),
    ``result`` (the fitted run, a Result), ``wall_time``, ``workers``."""

    def __init__(self, names, start, estimate, stats, pairs, data, residuals, cost, cost_start,
                 success, message, budget_exhausted, evaluations, infeasible, result,
                 wall_time, workers):
        self.names, self.start, self.estimate = list(names), np.asarray(start), \
            np.asarray(estimate)
        self.std, self.ci95 = stats["std"], stats["ci95"]
        self.correlation, self.warnings = stats["corr"], list(stats["warnings"])
        self.residual_std = float(np.sqrt(stats["s2"]))
        self.dof = stats["dof"]
        self.pairs, self.data, self.residuals = pairs, data, residuals
        self.cost, self.cost_start = cost, cost_start
        self.success, self.message = bool(success), message
        self.budget_exhausted = bool(budget_exhausted)
        self.evaluations, self.infeasible = evaluations, infeasible
        self.result, self.wall_time, self.workers = result, wall_time, workers

    @property
    def parameters(self):
        """{name: {"estimate", "std", "ci95", "start"}} (plain floats)."""
        return {n: {"estimate": float(x), "std": _num(s), "ci95": [_num(a), _num(b)],
                    "start": float(x0)}
                for n, x, s, (a, b), x0 in zip(self.names, self.estimate, self.std, self.ci95,
                                               self.start)}

    def to_dict(self):
        """The content of ``fit.json``."""
        return {"parameters": self.parameters, "cost": self.cost, "cost_start": self.cost_start,
                "success": self.success, "message": self.message,
                "evaluations": self.evaluations, "residual_std": self.residual_std,
                "correlation": [[_num(c) for c in row] for row in self.correlation],
                "warnings": self.warnings,
                "infeasible": [{"point": p, "error": e} for p, e in self.infeasible],
                "budget_exhausted": self.budget_exhausted, "wall_time": self.wall_time,
                "workers": self.workers}

    def compare(self, plot_dir=None):
        """The fitted run against the data (:func:`acausal2d.compare`) in a
        tube of ``COMPARE_TUBE`` residual standard deviations (unweighted,
        the largest over the signals)."""
        from .compare import compare
        t, cols = self.data
        refs = [ref for ref, _ in self.pairs]
        rms = [np.sqrt(np.mean((np.interp(t, self.result.time, self.result[our]) - cols[ref])
                               ** 2)) for ref, our in self.pairs]
        tol = COMPARE_TUBE * max(rms) if max(rms) > 0 else 1e-12
        return compare(self.result, (t, {r: cols[r] for r in refs}), signals=refs,
                       mapping={r: o for r, o in self.pairs if r != o} or None, abs_tol=tol,
                       plot_dir=plot_dir)

    def report(self):
        """Text: the parameter table, cost, correlations, warnings and
        infeasible points."""
        head = "%-24s %12s %12s %12s %26s" % ("parameter", "start", "estimate", "std",
                                              "95% interval")
        lines = [head, "-" * len(head)]
        for n, x0, x, s, (a, b) in zip(self.names, self.start, self.estimate, self.std,
                                       self.ci95):
            lines.append("%-24s %12.6g %12.6g %12.4g   [%11.6g, %11.6g]" % (n, x0, x, s, a, b))
        lines.append("cost %.6g -> %.6g (1/2 sum of squared residuals), residual std %.4g, "
                     "%d model runs, %.2f s%s" % (
                         self.cost_start, self.cost, self.residual_std, self.evaluations,
                         self.wall_time, " on %d workers" % self.workers if self.workers else ""))
        if len(self.names) > 1:
            lines.append("correlation:")
            lines += ["  %-22s %s" % (n, " ".join("%7.4f" % c for c in row))
                      for n, row in zip(self.names, self.correlation)]
        lines += ["warning: " + w for w in self.warnings]
        lines += ["infeasible trial point %s: %s" % (_point(p), e) for p, e in self.infeasible]
        lines.append(("converged: " if self.success else "NOT converged: ") + self.message)
        return "\n".join(lines)

    def write(self, out_dir):
        """Write ``fit.json``, ``fit.csv`` (the fitted run), the comparison
        plots and ``fit.png`` into ``out_dir``; returns the paths."""
        os.makedirs(out_dir, exist_ok=True)
        path = os.path.join(out_dir, "fit.json")
        with atomic_path(path) as tmp:
            with open(tmp, "w", encoding="utf-8") as fh:
                json.dump(self.to_dict(), fh, indent=2)
        csv = self.result.to_csv(os.path.join(out_dir, "fit.csv"))
        cmp = self.compare(plot_dir=os.path.join(out_dir, "compare"))
        return [path, csv, self.plot(os.path.join(out_dir, "fit.png"))] + cmp.plots

    def plot(self, path=None):
        """The measured points and the fitted (and start) curves, one axes
        per signal; writes ``path`` or returns the Figure."""
        from ..visual.fitting import fit_figure
        from ..visual.plotting import save_figure
        fig = fit_figure(self)
        return fig if path is None else save_figure(fig, path)


def _num(v):
    v = float(v)
    return v if np.isfinite(v) else None


def _point(p):
    return ", ".join("%s=%.6g" % kv for kv in p.items())
