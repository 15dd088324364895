"""The outcome of :func:`acausal2d.analysis.fit.fit`: estimates with their
standard errors, intervals and correlations, the comparison of the fitted
run with the data, and the files ``fit.json``, ``fit.csv`` and plots."""
import json
import os

import numpy as np

from ..io.files import atomic_path
from .compare import DEFAULT_ABS_TOL
from .compare import Comparison, compare
from ..options import DEFAULTS

COMPARE_TUBE = 4.0
"""Half-width of the comparison tube in standard deviations of the noise
estimated from the measured data (:func:`data_noise`)."""

_MAD_NORMAL = 0.6744897501960817
"""The median of |z| for a standard normal z (Phi^-1(0.75))."""


def data_noise(t, y):
    """The standard deviation of the measurement noise of ``y(t)``,
    estimated from the data alone (no model): the pseudo-residuals of
    Gasser, Sroka and Jennen-Steinmetz (1986, Biometrika 73, 625-633),
    ``e_i = a_i y_(i-1) + b_i y_(i+1) - y_i`` with ``a_i = (t_(i+1) - t_i) /
    (t_(i+1) - t_(i-1))``, ``b_i = 1 - a_i`` (the distance of each point
    from the line through its neighbours), scaled by ``c_i = (a_i^2 + b_i^2
    + 1)^-1/2`` so that ``c_i e_i`` has the noise's variance where the
    signal is locally linear; the median of ``|c_i e_i|`` / 0.6745 (robust
    against outliers, events and the signal's curvature at a few points).
    NaN with fewer than 3 distinct times."""
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    keep = np.r_[True, np.diff(t) > 0]           # an event's repeated time: its first row
    t, y = t[keep], y[keep]
    if t.size < 3:
        return float("nan")
    h0, h1 = t[1:-1] - t[:-2], t[2:] - t[1:-1]
    a = h1 / (h0 + h1)
    b = 1.0 - a
    e = (a * y[:-2] + b * y[2:] - y[1:-1]) / np.sqrt(a * a + b * b + 1.0)
    return float(np.median(np.abs(e)) / _MAD_NORMAL)


class FitResult:
    """A fit (see :func:`~acausal2d.analysis.fit.fit`): ``names``,
    ``start``, ``estimate``, ``std``, ``ci95`` (n x 2), ``correlation``,
    ``cost`` and ``cost_start`` (1/2 sum of squared weighted residuals),
    ``success`` (the optimality check), ``message``, ``budget_exhausted``,
    ``evaluations`` (model runs), ``infeasible`` (points whose run failed,
    with the error), ``warnings`` (parameters the data cannot separate),
    ``result`` (the fitted run, a Result), ``wall_time``, ``workers``,
    ``at_bound`` ({name: "lower" or "upper"}: estimates their bound holds;
    their ``std`` and ``ci95`` are NaN and ``success`` is False: not a
    regular optimum), ``abs_tol`` (the user's tolerance of the comparison)
    and ``noise`` ({measured column: noise std estimated from the data})."""

    def __init__(self, names, start, estimate, stats, pairs, data, residuals, cost, cost_start,
                 success, message, budget_exhausted, evaluations, infeasible, result,
                 wall_time, workers, at_bound=None, abs_tol=None, rtol=None):
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
        self.at_bound, self.abs_tol, self.rtol = dict(at_bound or {}), abs_tol, rtol
        self.noise = {ref: data_noise(data[0], data[1][ref]) for ref, _ in pairs}

    @property
    def parameters(self):
        """{name: {"estimate", "std", "ci95", "start"}} (plain floats; None
        for the std and interval of an estimate held by its bound)."""
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
                "budget_exhausted": self.budget_exhausted, "at_bound": self.at_bound,
                "noise": {k: _num(v) for k, v in self.noise.items()},
                "wall_time": self.wall_time, "workers": self.workers}

    def tolerance(self, ref):
        """Half-width of the comparison tube of the measured column ``ref``:
        ``COMPARE_TUBE`` times its noise estimated from the data
        (:func:`data_noise`) plus the user's ``abs_tol``, at least ten
        times the runs' relative tolerance (the model's, else 1e-6) of the data's
        size.  Never the fit's own residual: a fit that misses the data
        (wrong units, a wrong model) fails it.  Without a noise estimate
        (fewer than 3 points) the tube is ``abs_tol`` (default: compare's
        :data:`~acausal2d.analysis.compare.DEFAULT_ABS_TOL`)."""
        y = self.data[1][ref]
        floor = 10.0 * (self.rtol or DEFAULTS["rtol"]) * float(np.max(np.abs(y)))
        noise = self.noise.get(ref, float("nan"))
        if not np.isfinite(noise):
            return max(self.abs_tol if self.abs_tol is not None else DEFAULT_ABS_TOL, floor)
        return max(COMPARE_TUBE * noise + (self.abs_tol or 0.0), floor)

    def compare(self, plot_dir=None):
        """The fitted run against the data (:func:`acausal2d.compare`), each
        measured signal in its tube (:meth:`tolerance`)."""
        t, cols = self.data
        rows, plots = [], []
        for ref, our in self.pairs:
            one = compare(self.result, (t, {ref: cols[ref]}), signals=[ref],
                          mapping={ref: our} if ref != our else None,
                          abs_tol=self.tolerance(ref), plot_dir=plot_dir)
            rows += one.rows
            plots += one.plots
        return Comparison(rows=rows, plots=plots)

    def report(self):
        """Text: the parameter table, cost, correlations, warnings and
        infeasible points."""
        head = "%-24s %12s %12s %12s %26s" % ("parameter", "start", "estimate", "std",
                                              "95% interval")
        lines = [head, "-" * len(head)]
        for n, x0, x, s, (a, b) in zip(self.names, self.start, self.estimate, self.std,
                                       self.ci95):
            if n in self.at_bound:
                lines.append("%-24s %12.6g %12.6g %12s   %26s" % (
                    n, x0, x, "at bound", "none (%s bound holds it)" % self.at_bound[n]))
            else:
                lines.append("%-24s %12.6g %12.6g %12.4g   [%11.6g, %11.6g]" % (n, x0, x, s, a,
                                                                                 b))
        lines.append("cost %.6g -> %.6g (1/2 sum of squared residuals), residual std %.4g, "
                     "%d model runs, %.2f s%s" % (
                         self.cost_start, self.cost, self.residual_std, self.evaluations,
                         self.wall_time, " on %d workers" % self.workers if self.workers else ""))
        lines.append("noise estimated from the data: %s" % ", ".join(
            "%s %.4g" % (k, v) for k, v in self.noise.items()))
        if len(self.names) > 1:
            lines.append("correlation:")
            lines += ["  %-22s %s" % (n, " ".join("%7.4f" % c for c in row))
                      for n, row in zip(self.names, self.correlation)]
        lines += ["warning: " + w for w in self.warnings]
        lines += ["infeasible trial point %s: %s" % (_point(p), e) for p, e in self.infeasible]
        lines.append(("converged: " if self.success else
                      "NOT a regular optimum: " if self.at_bound else "NOT converged: ")
                     + self.message)
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
