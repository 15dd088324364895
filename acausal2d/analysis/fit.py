"""Calibration: fit a model's parameters to measured curves.

::

    import acausal2d
    fr = acausal2d.fit("models/pulley_block.py", "measured.csv",
                       free={"U1.mu,L2.mu,U3.mu,L4.mu": (0.1, 0.0, 0.6)},
                       signals=["rope1.F", "rope5.F"], t_range=(2.0, 4.0))
    print(fr.report()); fr.write("out/fit")

The problem
-----------
With the measured values ``y_k(t_i)`` of the signals k at the measured
times and the model's ``m_k(t_i; p)`` (the compiled model re-simulated at
``p`` without recompiling, its output grid containing the measured times),
the weighted residuals are ``r = w_k (m_k(t_i; p) - y_k(t_i))`` and the fit
minimises ``cost = 1/2 sum r^2`` within the bounds
(``scipy.optimize.least_squares``, trust-region reflective, optional robust
loss).  The Jacobian is the finite-difference one of
:class:`~acausal2d.analysis.trials.Trials` (central differences on the
warm model, in parallel on Dask with ``scheduler``).  A trial point whose
run fails (the integrator, the initialisation, a parameter rule) gets a
residual larger than the start's, so the trust region shrinks and the
search goes on; the point and its error are listed in the report.

What the numbers mean
---------------------
At the optimum, with the Jacobian J of the residuals and the residual
variance ``s^2 = 2 cost / (m - n)`` (m residuals, n parameters), the
covariance of the estimates is ``C = s^2 (J^T J)^-1`` (linearised least
squares; the measurement errors taken independent, of equal variance after
weighting).  ``std = sqrt(diag C)``; the 95 % interval is ``estimate +- t
std`` with t the 97.5 % quantile of Student's t with m - n degrees of
freedom: if the model is right and the noise as assumed, intervals built
this way contain the true value in 95 % of repeated experiments.  The
correlation matrix is ``C_ij / (std_i std_j)``; a pair with ``|corr| >
0.99``, or a Jacobian whose columns scaled to unit length have a
condition number above 1e6, means the data
cannot separate those parameters (e.g. two that enter only as their
product): they are named in ``warnings`` and their intervals are not
meaningful.  With a robust loss the same formulas are applied to the
plain residuals at the robust estimate: an approximation (outliers widen
the intervals instead of being down-weighted).

Success is decided by the optimality check (first-order KKT conditions at
the reported point, :func:`~acausal2d.analysis.optimality.kkt_check`), never by the optimiser's exit flag
alone; an optimiser stopped by its evaluation budget is reported with
``budget_exhausted``.
"""
from typing import TYPE_CHECKING, Any

import numpy as np
import time as _time

from ..errors import Acausal2dError
from ..options import DEFAULTS, RunOptionError, RunOptions
from .trials import Trials, parse_free, trial_options
from .compare_inputs import load_table
from .compare_inputs import select_signals
from .sweep import expand_params
from .trials import check_fixed_apart
from .fit_report import FitResult

if TYPE_CHECKING:
    from .fit_report import FitResult

CORRELATION_LIMIT = 0.99
"""|corr| above which a pair of parameters is reported as not separable."""

CONDITION_LIMIT = 1e6
"""Condition number of the Jacobian with columns scaled to unit length
above which the fit is reported as rank-deficient."""

POLISH_STEPS = 3
"""Gauss-Newton steps after the optimiser at most (see :func:`_polish`)."""

POLISH_TOL = 1e-3
"""Stationarity up to which :func:`_polish` improves the point (100 times
below ``KKT_TOL``, so that the verdict has a margin)."""

KKT_TOL = 1e-2
"""Tolerance of the scaled KKT measures that decide a fit's success: the
point is within about 1 % of a standard error of stationary (see
:func:`_optimality`).  The runs' own tolerance (rtol 1e-8) makes the
finite-difference gradient scatter by up to about 1e-3 standard errors
from run grid to run grid (measured on the pulley block), so 1e-2 leaves a
margin of 10 and is statistically irrelevant."""


class _Problem:
    """The weighted residual vector of a fit and its evaluations."""

    def __init__(self, trials, names, data, weights):
        self.trials, self.names, self.data = trials, names, data
        self.weights = weights
        self.penalty = None
        self.evaluations = 0
        self._last = (None, None)

    def vector(self, values):
        """Weighted residuals of one run's values."""
        return np.concatenate([self.weights[our] * (values[our] - self.data[ref])
                               for ref, our in self.names])

    def residuals(self, x):
        """r(x); a failed run gives the penalty vector (worse than the start)."""
        key = tuple(np.asarray(x, dtype=float))
        if self._last[0] == key:
            return self._last[1]
        self.evaluations += 1
        values, err = self.trials.run([x])[0]
        if values is None:
            if self.penalty is None:
                raise Acausal2dError("the model does not run at the start values: %s" % err)
            return self.penalty
        r = self.vector(values)
        if self.penalty is None:
            self.penalty = np.full(r.size, 10.0 * (np.sqrt(np.mean(r ** 2)) + 1.0))
        self._last = (key, r)
        return r


def _load_data(data, t_range):
    """(times, {column: values}) of the measured data inside ``t_range``."""
    t, cols = load_table(data, "measured data")
    if t_range is not None:
        t0, t1 = (float(v) for v in t_range)
        keep = (t >= t0) & (t <= t1)
        if not keep.any():
            raise Acausal2dError("--t-range %g:%g contains none of the measured times (%g .. %g)"
                                 % (t0, t1, t[0], t[-1]))
        t, cols = t[keep], {k: v[keep] for k, v in cols.items()}
    if t[0] < 0:
        raise Acausal2dError("the measured times start at %g < 0; the model runs from t = 0"
                             % t[0])
    for name, v in cols.items():
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise Acausal2dError("measured column %s has %d values that are not numbers (first "
                                 "at t = %g); remove those rows or use --t-range"
                                 % (name, bad.size, t[bad[0]]))
    return t, cols


def _pairs(cm, cols, signals, mapping):
    """(measured column, our signal) pairs, checked as compare does."""
    ours = {n: None for n in cm.names}
    pairs, unmatched = select_signals(cols, ours, signals, mapping)
    if unmatched:
        raise Acausal2dError(
            "measured column%s %s ha%s no counterpart in %s; name the fitted columns with "
            "--signals (signals=) or pair them with --map MEASURED=OURS (mapping=)"
            % ("s" if len(unmatched) > 1 else "", ", ".join(unmatched),
               "ve" if len(unmatched) > 1 else "s", type(cm.model).__name__))
    return pairs


def _weights(pairs, weights):
    w = {our: 1.0 for _, our in pairs}
    for name, value in dict(weights or {}).items():
        match = [our for ref, our in pairs if name in (ref, our)]
        if not match:
            raise Acausal2dError("weights: %r is not a fitted signal; fitted: %s"
                                 % (name, ", ".join(r for r, _ in pairs)))
        if not (np.isfinite(value) and value > 0):
            raise Acausal2dError("weights: %s must be a positive number, got %r" % (name, value))
        w[match[0]] = float(value)
    return w


def _check_free(cm, names):
    known = set(cm.parameter_names)
    for column in names:
        for name in column.split(","):
            if name.strip() not in known:
                close = [n for n in cm.parameter_names if name.split(".")[-1] in n][:8]
                raise Acausal2dError("unknown parameter %r%s" % (
                    name.strip(), "; similar: " + ", ".join(close) if close else ""))


def statistics(J, r, x, names):
    """Standard errors, 95 % intervals, correlations and warnings at the
    optimum (module documentation).  The Jacobian's columns are scaled to
    unit length for the rank test (column equilibration: units and sizes of
    the parameters drop out, an estimate of 0 included; a column of zeros
    stays zero); a direction of the null space names its parameters."""
    n, m = x.size, r.size
    if m <= n:
        raise Acausal2dError("statistics: %d residuals for %d parameters; at least %d are "
                             "needed" % (m, n, n + 1))
    dof = m - n
    s2 = float(r @ r) / dof
    norms = np.linalg.norm(J, axis=0)
    d = np.where(norms > 0, 1.0 / np.where(norms > 0, norms, 1.0), 1.0)
    _, sv, vt = np.linalg.svd(J * d, full_matrices=False)
    good = sv > sv[0] / CONDITION_LIMIT if sv.size and sv[0] > 0 else np.zeros(n, bool)
    inv = np.where(good, 1.0 / np.where(good, sv, 1.0) ** 2, 0.0)
    cov = (s2 * (vt.T * inv) @ vt) * np.outer(d, d)
    std = np.sqrt(np.maximum(np.diag(cov), 0.0))
    warnings = []
    corr_null = []
    for v in vt[~good]:
        involved = [names[j] for j in np.flatnonzero(np.abs(v) > 0.1)]
        std[np.abs(v) > 0.1] = np.inf
        corr_null.append(np.where(np.outer(np.abs(v) > 0.1, np.abs(v) > 0.1),
                                  np.sign(np.outer(v, v)), np.nan))
        warnings.append("the data cannot identify %s: the Jacobian is rank-deficient "
                        "(condition > %.0e); only a combination of them is determined; fix "
                        "one of them (--set) or add data that separates them"
                        % (" and ".join(involved), CONDITION_LIMIT))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(std, std)
    corr[~np.isfinite(corr)] = np.nan
    for c in corr_null:            # along a null direction the estimates move together
        corr = np.where(np.isfinite(c), c, corr)
    np.fill_diagonal(corr, 1.0)
    warnings += _correlation_warnings(corr, names, warnings)
    half = _t_quantile(dof) * std
    return {"std": std, "ci95": np.column_stack([x - half, x + half]), "corr": corr,
            "s2": s2, "dof": dof, "singular_values": sv, "warnings": warnings}


def _correlation_warnings(corr, names, known):
    out = []
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            c = corr[i, j]
            if np.isfinite(c) and abs(c) > CORRELATION_LIMIT and \
                    not any(names[i] in w and names[j] in w for w in known):
                out.append("%s and %s are correlated by %.4f: the data can hardly separate "
                           "them (|corr| > %.2f)" % (names[i], names[j], c, CORRELATION_LIMIT))
    return out


def _t_quantile(dof):
    from scipy.stats import t
    return float(t.ppf(0.975, dof))


_LOSS_WEIGHT = {
    "linear": lambda z: np.ones_like(z),
    "soft_l1": lambda z: 1.0 / np.sqrt(1.0 + z),
    "huber": lambda z: np.where(z <= 1.0, 1.0, 1.0 / np.sqrt(np.maximum(z, 1.0))),
    "cauchy": lambda z: 1.0 / (1.0 + z),
    "arctan": lambda z: 1.0 / (1.0 + z ** 2),
}
"""rho'(z) of scipy's robust losses (z = (r / f_scale)^2): the weights of
the residuals in the gradient J^T (rho' r)."""


def _solve(problem, x0, lo, hi, loss, f_scale, max_evaluations):
    from scipy.optimize import least_squares

    def jac(x):
        return problem.trials.jacobian(x, problem.vector, lo, hi)[0]

    try:
        return least_squares(problem.residuals, x0, jac=jac, bounds=(lo, hi), method="trf",
                             loss=loss, f_scale=f_scale, max_nfev=max_evaluations,
                             x_scale="jac", xtol=1e-10, ftol=1e-12, gtol=1e-10)
    except ValueError as exc:                   # scipy: inconsistent problem
        raise Acausal2dError("the fit cannot start: %s" % exc) from None


def _optimality(J, r, x, lo, hi, loss, f_scale, std):
    """The KKT check (:func:`~acausal2d.analysis.optimality.kkt_check`)
    of the bound-constrained fit at ``x``, gradient ``J^T (rho' r)``, in
    units of the standard errors: variables ``x / D`` with ``D`` the
    standard errors (at least 1e-8 relative, the runs' resolution; the
    value itself where a parameter is unidentifiable) and the objective's
    scale the largest ``D_j^2 (J^T J)_jj`` (the cost of moving one standard
    error).  Stationarity below ``KKT_TOL`` then means: a first-order step
    would move no estimate by more than about ``KKT_TOL`` standard errors --
    independent of units, noise level and machine.

    Returns (KKT result, held): ``held`` maps the index of each estimate a
    bound holds to ``"lower"``/``"upper"``: its bound is active and its
    multiplier above ``KKT_TOL`` times the cost scale, i.e. the data pull
    the estimate more than ``KKT_TOL`` standard errors beyond the bound."""
    from .optimality import kkt_check
    w = _LOSS_WEIGHT[loss]((r / f_scale) ** 2)
    rel = np.maximum(np.abs(x), 1e-12)
    D = np.where(np.isfinite(std), np.maximum(std, 1e-8 * rel), rel)
    g = (J.T @ (w * r)) * D
    scale = max(float(np.max(D ** 2 * np.einsum("ij,i,ij->j", J, w, J))), 1e-300)
    kkt = kkt_check(g, x / D, objective=scale, lower=lo / D, upper=hi / D, x_scale=1.0,
                    tol=KKT_TOL)
    held = {int(j): kind for kind in ("lower", "upper") for j in kkt.active.get(kind, [])
            if kkt.multipliers[kind][j] > KKT_TOL * scale}
    return kkt, held


def _interior_statistics(J, r, x, names, held):
    """:func:`statistics` of the estimates no bound holds (the held ones
    taken as fixed there: they have no standard error or interval, NaN)."""
    n = x.size
    free = [j for j in range(n) if j not in held]
    std, ci95, corr = np.full(n, np.nan), np.full((n, 2), np.nan), np.full((n, n), np.nan)
    np.fill_diagonal(corr, 1.0)
    if not free:
        return {"std": std, "ci95": ci95, "corr": corr, "s2": float(r @ r) / r.size,
                "dof": r.size, "singular_values": np.zeros(0), "warnings": []}
    part = statistics(J[:, free], r, x[free], [names[j] for j in free])
    std[free], ci95[free] = part["std"], part["ci95"]
    corr[np.ix_(free, free)] = part["corr"]
    return dict(part, std=std, ci95=ci95, corr=corr)


def held_message(names, x, lo, hi, held):
    """Why a fit with estimates held by their bounds is not a regular optimum."""
    items = ["%s at its %s bound %g" % (names[j], kind, (lo if kind == "lower" else hi)[j])
             for j, kind in sorted(held.items())]
    return ("the bounds hold %s (the data pull %s beyond; no standard "
            "error or interval); check the data's units and signals, or widen the bound if it "
            "is not physical" % (", ".join(items), "it" if len(held) == 1 else "them"))


def _polish(problem, x, lo, hi, loss, f_scale, names, steps=POLISH_STEPS):
    """Up to ``steps`` (robustly weighted) Gauss-Newton steps from the
    optimiser's point while the KKT stationarity is above ``POLISH_TOL``
    and the cost does not grow (the optimiser stops on its own tolerances,
    the check decides).  Returns (x, J, r, statistics, KKT result, the
    estimates held by their bounds; see :func:`_optimality`)."""
    trials = problem.trials
    r = problem.vector(trials.run([x])[0][0])
    for k in range(steps + 1):
        J, _ = trials.jacobian(x, problem.vector, lo, hi)
        stats = statistics(J, r, x, names)
        kkt, held = _optimality(J, r, x, lo, hi, loss, f_scale, stats["std"])
        if kkt.stationarity <= POLISH_TOL or k == steps:
            break
        sw = np.sqrt(_LOSS_WEIGHT[loss]((r / f_scale) ** 2))
        step = np.linalg.lstsq(J * sw[:, None], sw * r, rcond=1.0 / CONDITION_LIMIT)[0]
        x_new = np.clip(x - step, lo, hi)
        values = trials.run([x_new])[0][0]
        r_new = None if values is None else problem.vector(values)
        if r_new is None or r_new @ r_new > (r @ r) * (1.0 + 1e-6):   # 1e-6: the runs' noise
            break
        x, r = x_new, r_new
    if held:
        stats = _interior_statistics(J, r, x, names, held)
    return x, J, r, stats, kkt, held


def _final_run(cm, trials, x, times):
    """The fitted run on a fine grid (the default number of output
    intervals) with the measured times."""
    grid = np.union1d(np.linspace(0.0, float(times[-1]), int(DEFAULTS["intervals"]) + 1), times)
    return cm.simulate(params=expand_params(trials.point(x)),
                       options=trial_options(trials.settings, grid))


def _check_count(m, names):
    """At least one measured value more than free parameters: the noise
    (s^2 with m - n degrees of freedom) and the intervals need it."""
    n = len(names)
    if m < n + 1:
        raise Acausal2dError(
            "%d measured value%s for %d free parameter%s (%s): a fit needs at least %d (one more "
            "than parameters) to estimate the noise and the intervals; add measured points or "
            "signals, widen --t-range, or hold parameters with --set"
            % (m, "" if m == 1 else "s", n, "" if n == 1 else "s", ", ".join(names), n + 1))


def _fit_options(options, rtol):
    """The fit's RunOptions; its runs end at the measured times, so a stop
    time or output times of its own is an error."""
    opts = RunOptions.of(options, "fit", rtol=rtol)
    for name in ("stop_time", "intervals", "output_times"):
        if getattr(opts, name) is not None:
            raise RunOptionError(name, "is not an option of fit: its runs end at the last "
                                 "measured time; leave it out")
    return opts


def _check_abs_tol(abs_tol):
    if abs_tol is not None and not (isinstance(abs_tol, (int, float)) and not
                                    isinstance(abs_tol, bool) and 0 <= abs_tol < np.inf):
        raise Acausal2dError("abs_tol (--abs-tol) must be a finite number >= 0 in the signals' "
                             "units, got %r" % (abs_tol,))


def fit(model: Any, data: Any, free: Any, signals: Any = None, mapping: Any = None,
        weights: Any = None, t_range: Any = None, fixed: Any = None, loss: str = "linear",
        f_scale: float = 1.0, rtol: Any = None, max_evaluations: int = 100,
        scheduler: Any = None, workers: Any = None, client: Any = None, model_name: Any = None,
        abs_tol: Any = None, options: "RunOptions | None" = None) -> "FitResult":
    """Fit the parameters ``free`` of ``model`` to the measured ``data``.

    model: a model file path, a Component subclass or a CompiledModel (this
    process only); data: a CSV file (ours or Modelica's, as
    :func:`~acausal2d.analysis.compare.compare` reads) or a ``(time,
    columns)`` tuple.  free: ``{name: start}`` or ``{name: (start, lower,
    upper)}`` (``"a.mu,b.mu"`` ties parameters to one value; a parameter
    given twice, or also in ``fixed``, is an error).  signals,
    mapping: the measured columns to fit and their names in the model, as
    for ``compare``; weights: ``{signal: w}`` (default 1); t_range: ``(t0,
    t1)`` measured times to use; fixed: parameter values held; loss:
    ``"linear"`` (least squares) or a robust loss of
    ``scipy.optimize.least_squares`` (``"soft_l1"``, ``"huber"``,
    ``"cauchy"``, ``"arctan"``) with ``f_scale``; options: the runs'
    :class:`~acausal2d.options.RunOptions` (tolerances, budgets; the runs
    end at the measured times) or its ``rtol`` as a keyword; max_evaluations: budget
    of optimiser steps; scheduler/workers/client: the Jacobian's runs on
    Dask (``"local"`` or a number of workers for a LocalCluster, a
    scheduler address, or an open Client); abs_tol: the tolerance (in the
    signals' units) added to the comparison tube of the fitted run, which
    is otherwise the noise estimated from the data
    (:meth:`~acausal2d.analysis.fit_report.FitResult.compare`).  The
    measured values (points times signals) must outnumber the free
    parameters.  Returns a :class:`~acausal2d.analysis.fit_report.FitResult`.
    """
    if loss not in _LOSS_WEIGHT:
        raise Acausal2dError("loss must be one of %s, got %r" % (", ".join(_LOSS_WEIGHT), loss))
    _check_abs_tol(abs_tol)
    names, x0, lo, hi = parse_free(free)
    check_fixed_apart(names, fixed)
    t, cols = _load_data(data, t_range)
    opts = _fit_options(options, rtol)
    t0 = _time.perf_counter()
    with Trials(model, names, [], t, fixed, opts, scheduler, workers, client,
                model_name) as trials:
        cm = trials.compiled()
        _check_free(cm, names)
        pairs = _pairs(cm, cols, signals, mapping)
        _check_count(t.size * len(pairs), names)
        trials.settings["signals"] = list(dict.fromkeys(our for _, our in pairs))
        problem = _Problem(trials, pairs, cols, _weights(pairs, weights))
        return _run(problem, cm, (x0, lo, hi), (t, cols), loss, f_scale,
                    opts.resolved(getattr(cm.model, "experiment", None)).rtol,
                    max_evaluations, dict(abs_tol=abs_tol, t_start=t0))


def _run(problem, cm, start, data, loss, f_scale, rtol, max_evaluations, extra):
    """The fit's search, polish and verdict; the FitResult."""
    (x0, lo, hi), (t, cols), trials = start, data, problem.trials
    names = trials.names
    r0 = problem.residuals(x0)
    sol = _solve(problem, x0, lo, hi, loss, f_scale, max_evaluations)
    x, J, r, stats, kkt, held = _polish(problem, sol.x, lo, hi, loss, f_scale, names,
                                        POLISH_STEPS if sol.status != 0 else 0)   # 0: budget
    for j, kind in held.items():     # within the KKT check's active distance of the bound
        x[j] = (lo if kind == "lower" else hi)[j]
    why = kkt.message()
    if kkt.ok and held:
        why = "%s; %s" % (held_message(names, x, lo, hi, held), why)
    elif not kkt.ok and sol.status == 0:
        why = "the optimiser's budget of %d evaluations ran out; %s" % (max_evaluations, why)
    return FitResult(names=names, start=x0, estimate=x, stats=stats, pairs=problem.names,
                     data=(t, cols), residuals=r, cost=0.5 * float(r @ r),
                     cost_start=0.5 * float(r0 @ r0), success=kkt.ok and not held,
                     message=why, budget_exhausted=sol.status == 0 and not kkt.ok,
                     evaluations=trials.count, infeasible=list(trials.failures),
                     result=_final_run(cm, trials, x, t),
                     wall_time=_time.perf_counter() - extra["t_start"], workers=trials.workers,
                     at_bound={names[j]: kind for j, kind in held.items()},
                     abs_tol=extra["abs_tol"], rtol=rtol)
