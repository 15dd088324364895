"""Trial runs for fitting and optimisation: a compiled model simulated at
many parameter points (no recompilation), in this process or on the Dask
cluster of :mod:`acausal2d.analysis.sweep`, and finite-difference
Jacobians of its signals at chosen times.

A trial is ``{parameter or tied columns: value}``; its outcome is
``{signal: values at the requested times}`` or an error text (the run
failed: an integrator failure, an initialisation that does not converge, a
value breaking a parameter's rule).  Failed trials are data, never raised:
the caller decides (a fit takes them as infeasible and backtracks).

Jacobians are central differences (error O(h^2), step ``h = 1e-3 *
max(|x|, scale)``; one-sided next to a bound or where one side fails), all
2n runs of one Jacobian dispatched at once, so on a Dask cluster they run
in parallel.  Finite differences were chosen over CasADi forward
sensitivities because they need nothing from the runtime beyond a run
(events, state re-selection and limit stops are handled as in any run),
the compiled model is warm (a run of the examples takes 10-500 ms) and
the runs of one Jacobian are independent; exact sensitivities are not
implemented (benchmarks/bench_fit.py times the runs and the Jacobians).
"""
import os

import numpy as np

from ..errors import Acausal2dError
from ..options import RunOptions
from .sweep import ModelSpec, cluster, compiled_model, expand_params
from ..compiled import CompiledModel, compile_model
from ..language.dsl import Component
from .sweep import _picklable_metrics

FD_STEP = 1e-3
"""Relative finite-difference step of :meth:`Trials.jacobian`."""


def parse_free(free, option="free"):
    """``{name: start}``, ``{name: (start, lo, hi)}`` or CLI strings
    ``NAME=START[:LO:HI]`` -> (names, start array, lower array, upper array).
    Tied parameters (``"a.mu,b.mu"``) form one column."""
    if isinstance(free, (list, tuple)):
        free = [_parse_item(item, option) for item in free]
    elif isinstance(free, dict):
        free = list(free.items())
    elif free is not None:
        raise Acausal2dError("%s must be a dict {name: start or (start, lower, upper)} or a "
                             "list of NAME=START[:LO:HI], not %s" % (option, type(free).__name__))
    if not free:
        raise Acausal2dError("%s: nothing to vary; give NAME=START[:LO:HI]" % option)
    names, x0, lo, hi = [], [], [], []
    seen = {}
    for name, spec in free:
        name = ",".join(name) if isinstance(name, (tuple, list)) else str(name)
        _once(name, seen, option)
        vals = [float(v) for v in np.atleast_1d(spec)]
        if len(vals) not in (1, 3) or not all(np.isfinite(vals)):
            raise Acausal2dError("%s %s: give a start value or (start, lower, upper) with "
                                 "finite numbers, got %r" % (option, name, spec))
        start, low, high = (vals[0], -np.inf, np.inf) if len(vals) == 1 else vals
        if not low <= start <= high or not low < high:
            raise Acausal2dError("%s %s: the start %g must lie between the bounds %g and %g "
                                 "(lower < upper)" % (option, name, start, low, high))
        names.append(name)
        x0.append(start)
        lo.append(low)
        hi.append(high)
    return names, np.array(x0), np.array(lo), np.array(hi)


def _once(column, seen, option):
    """A parameter may appear in one column only: given twice (also inside
    tied columns ``a.p,b.p``) is an error naming it, never "the last wins"."""
    for name in (n.strip() for n in column.split(",")):
        if name in seen:
            raise Acausal2dError("%s: %s is given twice (%s and %s); give each parameter once"
                                 % (option, name, seen[name], column))
        seen[name] = column


def check_fixed_apart(names, fixed, option="free"):
    """A parameter both varied and held fixed is an error naming it."""
    both = sorted({n.strip() for column in names for n in column.split(",")} & set(fixed or {}))
    if both:
        raise Acausal2dError("%s %s: also given as a fixed value (--set / fixed=); give it "
                             "once, as varied or as fixed" % (option, ", ".join(both)))


def _parse_item(item, option):
    if "=" not in str(item):
        raise Acausal2dError("%s takes NAME=START or NAME=START:LO:HI (e.g. U1.mu=0.2:0:0.5), "
                             "got %r" % (option, item))
    name, spec = str(item).split("=", 1)
    try:
        vals = tuple(float(v) for v in spec.split(":"))
    except ValueError:
        raise Acausal2dError("%s %s: %r is not START or START:LO:HI" % (option, name, spec)) \
            from None
    if len(vals) not in (1, 3):
        raise Acausal2dError("%s %s: %r is not START or START:LO:HI" % (option, name, spec))
    return name.strip(), vals if len(vals) == 3 else vals[0]


def _check_fixed(fixed):
    for name, value in fixed.items():
        if not np.all(np.isfinite(np.asarray(value, dtype=float))):
            raise Acausal2dError("fixed value of %s must be finite, got %r" % (name, value))


def trial_options(settings, times):
    """The RunOptions of a trial: the caller's (tolerances, budgets) with
    the output ``times`` and no progress bar of its own."""
    return settings["options"].replace(stop_time=None, intervals=None, output_times=times,
                                       progress=False)


def run_trial(model, params, settings):
    """Simulate one trial on this process; returns ({signal: values at
    ``settings['times']``}, "") or (None, error text).  ``model``: a
    :class:`ModelSpec` (compiled once per process) or a CompiledModel."""
    try:
        cm = model if not isinstance(model, ModelSpec) else compiled_model(model)
        times = np.asarray(settings["times"], dtype=float)
        res = cm.simulate(params=expand_params(params),
                          options=trial_options(settings, np.union1d([0.0], times)))
        if res.stopped:
            return None, "the run stopped early: %s" % res.stopped
        t = np.asarray(res.time)
        out = {}
        for name in settings["signals"]:
            y = np.asarray(res[name], dtype=float)
            out[name] = np.interp(times, t, y)
            if not np.all(np.isfinite(out[name])):
                return None, "signal %s is not finite" % name
        for k, func in enumerate(settings.get("functions") or ()):
            if func is not None:
                out["__f%d" % k] = np.array([float(func(res))])
        return out, ""
    except Exception as exc:                    # noqa: BLE001 - a failed trial is data
        return None, "%s: %s" % (type(exc).__name__, " ".join(str(exc).split())[:300])


class Trials:
    """Runs of ``model`` at parameter points: ``run(points)`` returns the
    outcomes in order, ``jacobian(x)`` the finite-difference derivatives.

    model: a model file path, a Component subclass, an instance or a
    CompiledModel; ``names``: the varied columns; ``signals`` and ``times``: what every
    run returns; ``fixed``: values held for every run; ``options``: the
    runs' :class:`~acausal2d.options.RunOptions` (tolerances, budgets); ``scheduler``: None
    (this process), ``"local"``/a number of workers (a LocalCluster), a
    Dask scheduler address, or ``client=`` an open Client.  Use it as a
    context manager (the cluster is closed on exit).  ``count`` counts the
    runs, ``failures`` lists (point, error) of the failed ones."""

    def __init__(self, model, names, signals, times, fixed=None, options=None, scheduler=None,
                 workers=None, client=None, model_name=None):
        if isinstance(model, Component):      # an instance runs in this process, compiled once
            model = compile_model(model)
        self.names, self.fixed = list(names), dict(fixed or {})
        _check_fixed(self.fixed)
        self.settings = {"signals": list(signals), "times": np.asarray(times, dtype=float),
                         "options": options or RunOptions()}
        self.count, self.failures, self.client = 0, [], client
        self._cluster = None
        parallel = client is not None or scheduler not in (None, "serial")
        if isinstance(model, CompiledModel):
            if parallel:
                raise Acausal2dError("a CompiledModel runs in this process only; give the model "
                                     "file's path to run on a Dask cluster")
            self.model = model
        else:
            self.model = ModelSpec.of(model, model_name)
        if parallel and client is None:
            local = scheduler in ("local", "dask") or str(scheduler).isdigit()
            n = int(scheduler) if str(scheduler).isdigit() else workers
            self._cluster = cluster(n or os.cpu_count(), None if local else scheduler)
            self.client = self._cluster.__enter__()

    @property
    def workers(self):
        """Worker processes used (0: this process)."""
        if self.client is None:
            return 0
        return len(self.client.scheduler_info().get("workers", {}))

    def compiled(self):
        """The compiled model on this process (for the final run)."""
        return self.model if not isinstance(self.model, ModelSpec) else \
            compiled_model(self.model)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self._cluster is not None:
            self._cluster.__exit__(*exc)
            self._cluster = self.client = None

    def point(self, x):
        """The parameter dict of the vector ``x``."""
        p = dict(self.fixed)
        p.update({n: float(v) for n, v in zip(self.names, x)})
        return p

    def run(self, xs):
        """Outcomes ``(values or None, error)`` of the vectors ``xs``."""
        points = [self.point(x) for x in xs]
        if self.client is None:
            out = [run_trial(self.model, p, self.settings) for p in points]
        else:
            out = self._run_dask(points)
        self.count += len(points)
        for p, (values, err) in zip(points, out):
            if values is None:
                self.failures.append(({n: p[n] for n in self.names}, err))
        return out

    def _run_dask(self, points):
        settings = dict(self.settings, functions=[
            None if f is None else _picklable_metrics(f) for f in
            self.settings.get("functions") or ()])
        futures = self.client.map(run_trial, [self.model] * len(points), points,
                                  [settings] * len(points), pure=False)
        out = []
        for fut in futures:
            try:
                out.append(fut.result())
            except Exception as exc:            # noqa: BLE001 - e.g. a worker that died
                out.append((None, "the Dask worker failed: %s" % exc))
        return out

    def jacobian(self, x, vector, lo, hi, scale=None):
        """Central-difference Jacobian of ``vector(values)`` (a function of
        a run's signal values returning a 1-D array) at ``x``; returns (J,
        number of columns that could not be formed).  Steps stay inside
        [lo, hi]."""
        x = np.asarray(x, dtype=float)
        scale = np.ones_like(x) if scale is None else np.asarray(scale, dtype=float)
        h = FD_STEP * np.maximum(np.abs(x), scale)
        plus, minus = np.minimum(x + h, hi), np.maximum(x - h, lo)
        xs = []
        for j in range(x.size):
            for v in (plus[j], minus[j]):
                e = x.copy()
                e[j] = v
                xs.append(e)
        out = self.run(xs)
        columns, bad = [], 0
        for j in range(x.size):
            col = _difference(out[2 * j], out[2 * j + 1], plus[j], minus[j], x[j], vector,
                              lambda: self.run([x])[0])
            bad += col is None
            columns.append(col)
        width = next((c.size for c in columns if c is not None), 0)
        J = np.column_stack([c if c is not None else np.zeros(width) for c in columns]) \
            if width else np.zeros((0, x.size))
        return J, bad


def _difference(up, down, xp, xm, x, vector, centre):
    """One Jacobian column from the runs at ``xp`` and ``xm`` (central),
    or one side and the centre run."""
    if up[0] is not None and down[0] is not None and xp > xm:
        return (vector(up[0]) - vector(down[0])) / (xp - xm)
    side, xs = (up, xp) if up[0] is not None and xp != x else (down, xm)
    if side[0] is None or xs == x:
        return None
    mid = centre()
    if mid[0] is None:
        return None
    return (vector(side[0]) - vector(mid[0])) / (xs - x)
