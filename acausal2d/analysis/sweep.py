"""Parameter studies on Dask: many simulations of one model with different
parameter values, spread over the processes of a ``dask.distributed``
cluster.

::

    import acausal2d
    study = acausal2d.sweep("models/pulley_block.py",
                            vary={"U1.mu,L2.mu,U3.mu,L4.mu": "0:0.5:11"},
                            outputs=["rope1.F", "rope5.F"], stop_time=3.0)
    print(study.table())
    study.to_csv("out/sweep.csv"); study.plot(path="out/sweep.png")

How it runs
-----------
Every point is a task ``run_point(model, index, params, settings)``.  A
worker compiles the model the first time it meets it and keeps the
:class:`~acausal2d.compiled.CompiledModel` in a worker-side cache keyed
by the model file's content, class name and constructor arguments; every
further point on that worker only sets the parameter values and simulates
(no recompilation, as :meth:`CompiledModel.simulate` with ``params``).
The model travels as its file's text, so workers on other machines need
acausal2d installed but not the file.

Without ``scheduler`` a ``LocalCluster`` is started with one single-threaded
worker process per core (or ``workers``) and closed afterwards; with a
scheduler address (``"tcp://host:8786"``) the points go to that existing
cluster; ``client=`` reuses a :class:`dask.distributed.Client` across
several sweeps (an optimiser's generations: the workers keep their compiled
models); ``scheduler="serial"`` runs the points in this process, one after
the other (also what a :class:`CompiledModel` passed as ``model`` does).

A point that fails (a parameter value breaking its rule, an integrator
failure, a crashed worker) is recorded in the table with its error; the
sweep goes on.

The table
---------
One row per point, in point order: ``point``, one column per varied
parameter (tied parameters, ``"U1.mu,L2.mu"``, share a column named like
that), one column per output (the signal's value at time ``at``, default the
end of the run) and per metric, then ``status`` (``ok``, ``stopped`` when
the run ended early, ``failed``), ``error`` and ``wall_time`` (s of the
simulation on its worker).  :meth:`SweepResult.to_csv` writes it as CSV
(plain text that any tool reads; the tables are small, one row per run).
"""
import contextlib
import hashlib
import inspect
import itertools
import os
import socket
import urllib.parse
import sys
import time as _time
from typing import Any

import numpy as np
import logging
import tempfile
import csv

from ..errors import Acausal2dError
from ..io.files import atomic_path
from ..compiled import CompiledModel, compile_model
from ..language.dsl import Component
from ..io.loader import load_model
from ..visual.plotting import save_figure, sweep_figure
from ..options import RunOptions
from ..progress import count_progress

_COMPILED: dict = {}
"""Worker-side cache: model key -> CompiledModel (or the exception its
compilation raised)."""

COMPILATIONS = {"count": 0}
"""How many models this process has compiled for sweeps (statistics)."""


# ---------------------------------------------------------------------------
# the model as it travels to the workers

class ModelSpec:
    """A model file (its path and text), the class in it and the
    constructor arguments: what a worker needs to build and compile the
    model.  ``key`` identifies it in the workers' cache."""

    def __init__(self, path, name=None, kwargs=None):
        path = os.path.abspath(os.fspath(path))
        if not os.path.isfile(path):
            raise Acausal2dError("model file %s does not exist" % path)
        with open(path, encoding="utf-8") as fh:
            self.source = fh.read()
        self.path, self.name = path, name
        self.kwargs = dict(kwargs or {})
        text = "%s\0%s\0%r" % (self.source, name, sorted(self.kwargs.items()))
        self.key = hashlib.sha256(text.encode()).hexdigest()[:16]

    @classmethod
    def of(cls, model, name=None, kwargs=None):
        """A spec from a model file path or a Component subclass (its file)."""
        if inspect.isclass(model):
            path = inspect.getsourcefile(model)
            if path is None:
                raise Acausal2dError("cannot find the file of model class %s; give the model "
                                     "file's path" % model.__name__)
            return cls(path, name or model.__name__, kwargs)
        if isinstance(model, (str, os.PathLike)):
            return cls(model, name, kwargs)
        raise Acausal2dError("sweep takes a model file path, a Component subclass, an "
                             "instance or a CompiledModel, not %s" % type(model).__name__)

    def local_path(self):
        """The model file on this machine: its path if it holds the same
        text, else a copy written to a temporary folder."""
        with contextlib.suppress(OSError):
            with open(self.path, encoding="utf-8") as fh:
                if fh.read() == self.source:
                    return self.path
        folder = os.path.join(tempfile.gettempdir(), "acausal2d-sweep-" + self.key)
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, os.path.basename(self.path))
        if not os.path.exists(path):
            with atomic_path(path) as tmp:
                with open(tmp, "w", encoding="utf-8") as fh:
                    fh.write(self.source)
        return path


def compiled_model(spec):
    """The compiled model of ``spec`` on this process, compiled at the
    first call and cached (a compilation error is cached and raised again)."""
    cm = _COMPILED.get(spec.key)
    if cm is None:
        COMPILATIONS["count"] += 1
        try:
            cm = compile_model(load_model(spec.local_path(), spec.name, **spec.kwargs))
        except Exception as exc:                # noqa: BLE001 - recorded per point
            cm = exc
        _COMPILED[spec.key] = cm
    if isinstance(cm, Exception):
        raise cm
    return cm


# ---------------------------------------------------------------------------
# one point

def _point_options(cm, settings):
    """The RunOptions of one point: the sweep's, resolved for the model,
    with ``at`` among the output times and no progress bar of its own."""
    opts = cm.run_options(settings["options"])
    times = opts.times()
    at = settings.get("at")
    if at is not None:
        times = np.union1d(times, [float(at)])
    return opts.replace(stop_time=None, intervals=None, output_times=times, progress=False)


def _simulate_point(cm, params, settings):
    """Simulate one point; returns (values, status, message)."""
    res = cm.simulate(params=params, options=_point_options(cm, settings))
    at = settings.get("at")
    values = {}
    for name in settings.get("outputs") or ():
        values[name] = res.final(name) if at is None else res.at(name, float(at))
    metrics = settings.get("metrics")
    if metrics is not None:
        values.update({str(k): float(v) for k, v in dict(metrics(res)).items()})
    return values, ("stopped" if res.stopped else "ok"), res.stopped or ""


def run_point(model, index, params, settings):
    """Run point ``index`` (``params``: {column: value}; a column naming
    several tied parameters sets them all) of a sweep on this process and
    return its table row (a dict).  ``model`` is a :class:`ModelSpec` or a
    CompiledModel; errors are caught and recorded in the row."""
    row = {"point": int(index)}
    row.update(params)
    t0 = _time.perf_counter()
    try:
        cm = model if not isinstance(model, ModelSpec) else compiled_model(model)
        values, status, message = _simulate_point(cm, expand_params(params), settings)
        row.update(values)
        row.update(status=status, error=message)
    except Exception as exc:                    # noqa: BLE001 - a failed point is data
        row.update(status="failed", error="%s: %s" % (type(exc).__name__, exc))
    row["wall_time"] = _time.perf_counter() - t0
    return row


def expand_params(params):
    """{column: value} -> {parameter: value}: tied columns (``"a.p,b.p"``)
    set every parameter they name."""
    out = {}
    for column, value in params.items():
        for name in column.split(","):
            out[name.strip()] = value
    return out


def model_info(model, names):
    """The model's class name and {name: unit} of the parameters and
    signals ``names`` (``model``: spec or compiled model); run where the
    model is compiled already."""
    cm = model if not isinstance(model, ModelSpec) else compiled_model(model)
    return {"name": type(cm.model).__name__,
            "units": {n: cm.units.get(n.split(",")[0].strip(), "") for n in names}}


# ---------------------------------------------------------------------------
# the points

MAX_POINTS = 100000
"""Budget of a parameter grid (:func:`grid_points`, ``acausal2d sweep``,
``modes --vary``, a study's ``ctx.sweep``): the number of points, i.e. of
simulations, of all combinations.  A larger grid is refused before anything
is allocated, with its count in the message: its bookkeeping alone (a dict
per point, a row per result, about 1 kB each) would take over 100 MB, and
its simulations days."""


def parse_values(text, name="--vary"):
    """``"0:0.4:21"`` (21 values from 0 to 0.4), ``"0,0.1,0.25"`` or
    ``"5"`` -> a list of floats; a bad spec raises with the accepted forms."""
    text = str(text).strip()
    try:
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise ValueError
            start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
            if count < 1:
                raise ValueError
            _check_budget(count, "%s %s" % (name, text))
            values = np.linspace(start, stop, count).tolist()
        else:
            values = [float(v) for v in text.split(",")]
    except ValueError:
        raise Acausal2dError("%s: %r is not START:STOP:COUNT (e.g. 0:0.4:21, COUNT >= 1) or "
                             "a list of numbers (0,0.1,0.25)" % (name, text)) from None
    if not all(np.isfinite(values)):
        raise Acausal2dError("%s: %r contains a value that is not finite" % (name, text))
    return values


def grid_points(vary):
    """All combinations of the ``vary`` entries ({column: values or spec
    string}; the last column varies fastest) as a list of dicts."""
    if not vary:
        raise Acausal2dError("nothing to vary: give vary={'comp.param': values} or points=[...]")
    columns, values = [], []
    for column, vals in vary.items():
        column = ",".join(column) if isinstance(column, (tuple, list)) else str(column)
        vals = parse_values(vals, column) if isinstance(vals, str) else \
            [float(v) for v in np.atleast_1d(np.asarray(vals, dtype=float))]
        if not vals:
            raise Acausal2dError("vary %s: no values" % column)
        columns.append(column)
        values.append(vals)
    grid_size(dict(zip(columns, values)))
    return [dict(zip(columns, combo)) for combo in itertools.product(*values)]


def grid_size(vary):
    """Number of points of the grid of ``vary`` ({column: values}); raises
    :class:`~acausal2d.errors.Acausal2dError` with the count when it exceeds
    :data:`MAX_POINTS`."""
    count = 1
    for vals in vary.values():
        count *= len(vals)
    _check_budget(count, " x ".join("%s (%d)" % (c, len(v)) for c, v in vary.items()))
    return count


def _check_budget(count, what):
    if count > MAX_POINTS:
        raise Acausal2dError("the parameter grid %s has %d points (about %s of bookkeeping before "
                             "the first run); the budget is %d points "
                             "(acausal2d.analysis.sweep.MAX_POINTS): use fewer values"
                             % (what, count, _bytes(count * 1024), MAX_POINTS))


def _bytes(n):
    for unit in ("B", "kB", "MB", "GB", "TB"):
        if n < 1024 or unit == "TB":
            return "%.3g %s" % (n, unit)
        n /= 1024.0
    return ""


def parse_vary(items):
    """The ``--vary NAME=SPEC`` options -> {column: values}."""
    vary = {}
    for item in items or ():
        if "=" not in item:
            raise Acausal2dError("--vary takes comp.param=START:STOP:COUNT or comp.param=v1,v2,..."
                                 " (tied parameters: a.p,b.p=...), got %r" % item)
        name, spec = item.split("=", 1)
        names = [n.strip() for n in name.split(",")]
        if not all(names):
            raise Acausal2dError("--vary %r: empty parameter name" % item)
        vary[",".join(names)] = parse_values(spec, "--vary " + name.strip())
    return vary


# ---------------------------------------------------------------------------
# running

@contextlib.contextmanager
def cluster(workers=None, scheduler=None):
    """A :class:`dask.distributed.Client`: connected to ``scheduler`` (an
    address) if given, else to a new ``LocalCluster`` of ``workers``
    single-threaded worker processes (default: one per core), closed on
    exit.  Pass it as ``client=`` to run several sweeps on one cluster."""
    from dask.distributed import Client, LocalCluster
    if scheduler is not None:
        try:
            _refuse_unreachable(scheduler)
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError) as exc:
            raise Acausal2dError("cannot reach the Dask scheduler at %s: %s"
                                 % (scheduler, exc)) from None
        with client:
            yield client
        return
    n = int(workers or os.cpu_count() or 1)
    # CRITICAL: a worker's heartbeat that meets the scheduler closing at the end logs an
    # ERROR with Dask's traceback; a point's failure comes back through its future
    with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                      dashboard_address=None, worker_dashboard_address=None,
                      silence_logs=logging.CRITICAL) as local, \
            Client(local) as client:
        yield client


def _refuse_unreachable(scheduler):
    """Raise ConnectionRefusedError where ``scheduler`` is a TCP address
    (``tcp://host:port`` or ``host:port``) at which nothing listens: the
    host refuses at once, where Dask's Client would try again for its whole
    timeout (10 s).  Any other address or outcome is left to the Client."""
    text = str(scheduler)
    parts = urllib.parse.urlsplit(text if "://" in text else "tcp://" + text)
    try:
        host, port = parts.hostname, parts.port
    except ValueError:                # not a port: the Client's own message
        return
    if parts.scheme != "tcp" or not host or port is None:
        return
    try:
        socket.create_connection((host, port), timeout=10).close()
    except ConnectionRefusedError:
        raise
    except OSError:                   # unresolved, unreachable, timed out: the Client decides
        return


def _run_dask(client, model, points, settings, progress):
    from dask.distributed import as_completed
    futures = client.map(run_point, [model] * len(points), range(len(points)), points,
                         [settings] * len(points), pure=False)
    rows = [None] * len(points)
    index = {f.key: k for k, f in enumerate(futures)}
    for future in as_completed(futures):
        k = index[future.key]
        try:
            rows[k] = future.result()
        except Exception as exc:                # noqa: BLE001 - e.g. a worker that died
            rows[k] = dict(points[k], point=k, status="failed",
                           error="%s: %s" % (type(exc).__name__, exc), wall_time=float("nan"))
        progress(rows[k].get("status") == "failed")
    return rows


def _run_serial(model, points, settings, progress):
    rows = []
    for k, params in enumerate(points):
        rows.append(run_point(model, k, params, settings))
        progress(rows[-1].get("status") == "failed")
    return rows


def _picklable_metrics(metrics):
    """Functions defined in a model file (a module the loader made up) are
    sent to the workers by value."""
    module = getattr(metrics, "__module__", "") or ""
    if module.startswith("acausal2d_model_") and module in sys.modules:
        import cloudpickle
        cloudpickle.register_pickle_by_value(sys.modules[module])
    return metrics


# ---------------------------------------------------------------------------
# the result

class SweepResult:
    """The table of a sweep (see the module documentation): ``rows`` (dicts
    in point order), ``parameters`` (varied columns), ``outputs`` (output
    and metric columns), ``units`` ({column: unit}), ``wall_time`` (s,
    the whole sweep) and ``workers`` (processes used, 0: this process)."""

    def __init__(self, rows, parameters, outputs, units, wall_time, workers, model_name):
        self.rows, self.parameters, self.outputs = rows, list(parameters), list(outputs)
        self.units, self.wall_time, self.workers = dict(units), wall_time, workers
        self.model_name = model_name

    @property
    def columns(self):
        """Column names in table order."""
        return (["point"] + self.parameters + self.outputs + ["status", "error", "wall_time"])

    def column(self, name):
        """One column as a numpy array (NaN where a point has no value)."""
        if name not in self.columns:
            raise Acausal2dError("no column %r in the sweep; columns: %s"
                                 % (name, ", ".join(self.columns)))
        if name in ("status", "error"):
            return np.array([r.get(name, "") for r in self.rows], dtype=object)
        return np.array([r.get(name, np.nan) for r in self.rows], dtype=float)

    @property
    def failed(self):
        """Rows of the points that failed."""
        return [r for r in self.rows if r.get("status") == "failed"]

    def to_csv(self, path):
        """Write the table as CSV (atomically); returns ``path``."""
        with atomic_path(path) as tmp:
            with open(tmp, "w", newline="", encoding="utf-8") as fh:
                w = csv.writer(fh)
                w.writerow(self.columns)
                for r in self.rows:
                    w.writerow([_cell(r.get(c, "")) for c in self.columns])
        return path

    def table(self):
        """The table as fixed-width text (errors shortened to one line)."""
        cols = [c for c in self.columns if c != "wall_time"]
        body = [[_cell(r.get(c, ""), 6)[:60] for c in cols] for r in self.rows]
        widths = [max(len(x) for x in [c] + [b[i] for b in body]) for i, c in enumerate(cols)]
        lines = ["  ".join(c.ljust(w) for c, w in zip(cols, widths)).rstrip()]
        lines += ["  ".join(x.ljust(w) for x, w in zip(b, widths)).rstrip() for b in body]
        return "\n".join(lines)

    def summary(self):
        """One line: points, failures, workers and wall time."""
        return "%d points (%d failed) in %.2f s on %s" % (
            len(self.rows), len(self.failed), self.wall_time,
            "%d worker%s" % (self.workers, "" if self.workers == 1 else "s")
            if self.workers else "this process")

    def plot(self, path=None, x=None, outputs=None):
        """Summary plot: every output over the varied parameter ``x``
        (default the first), one line per combination of the other varied
        parameters; one axes per unit.  Writes ``path`` or returns the
        matplotlib Figure."""
        fig = sweep_figure(self, x or self.parameters[0], outputs or self.outputs)
        return fig if path is None else save_figure(fig, path)


def _cell(value, digits=17):
    if isinstance(value, float):
        return "%.*g" % (digits, value)
    return str(value)


def sweep(model: Any, vary: Any = None, points: Any = None, outputs: Any = None,
          metrics: Any = None, at: Any = None, stop_time: Any = None, rtol: Any = None,
          intervals: Any = None, params: Any = None, scheduler: Any = None, workers: Any = None,
          client: Any = None, progress: Any = None, model_name: Any = None,
          model_kwargs: Any = None, options: "RunOptions | None" = None) -> "SweepResult":
    """Simulate ``model`` once per parameter point and collect a table.

    model: a model file path, a Component subclass (from an importable
    file) or a CompiledModel (then the points run in this process);
    ``model_name``/``model_kwargs`` choose the class in the file and its
    constructor arguments.  vary: {parameter: values} (values a sequence or
    ``"start:stop:count"``; ``"a.p,b.p"`` ties parameters to one value); all
    combinations are run.  points: an explicit list of {parameter: value}
    dicts instead (e.g. an optimiser's candidates).  params: values held
    fixed for every point.  outputs: signals recorded at time ``at``
    (default: the end of the run); metrics: a function ``result -> {name:
    number}`` run on the worker after each simulation.  options: the
    :class:`~acausal2d.options.RunOptions` of every point, or its
    stop_time, rtol, intervals and progress as keywords (not both);
    progress: a bar over the points on standard error when it is a
    terminal (the points themselves show none).  scheduler: ``None``
    (a LocalCluster of ``workers`` processes, default one per core), a Dask
    scheduler address, or ``"serial"`` (this process); client: an open
    ``dask.distributed.Client`` (see :func:`cluster`).  Returns a
    :class:`SweepResult`.
    """
    opts = RunOptions.of(options, "sweep", stop_time=stop_time, rtol=rtol, intervals=intervals,
                         progress=progress)
    points = grid_points(vary) if points is None else [dict(p) for p in points]
    if params:
        points = [dict(params, **p) for p in points]
    if not points:
        raise Acausal2dError("the sweep has no points")
    if isinstance(model, Component):         # an instance runs in this process, compiled once
        model = compile_model(model)
    compiled = isinstance(model, CompiledModel)
    spec = model if compiled else ModelSpec.of(model, model_name, model_kwargs)
    settings = {"outputs": list(outputs or ()), "metrics": _picklable_metrics(metrics),
                "at": at, "options": opts.replace(progress=False)}
    t0 = _time.perf_counter()
    with count_progress(len(points), "points", opts.progress is not False) as bar:
        rows, n_workers, info = _dispatch(spec, points, settings, bar, compiled, scheduler,
                                          workers, client)
    return _result(rows, points, params, settings, _time.perf_counter() - t0, n_workers, info)


def _dispatch(spec, points, settings, bar, compiled, scheduler, workers, client):
    """Run the points; returns (rows, number of worker processes, model info)."""
    names = list(points[0]) + list(settings["outputs"])
    if compiled or scheduler == "serial":
        rows = _run_serial(spec, points, settings, bar)
        return rows, 0, _info(lambda: model_info(spec, names))
    if client is not None:
        return _run_on(client, spec, points, settings, bar, names)
    with cluster(workers, scheduler) as own:
        return _run_on(own, spec, points, settings, bar, names)


def _run_on(client, spec, points, settings, bar, names):
    rows = _run_dask(client, spec, points, settings, bar)
    n_workers = len(client.scheduler_info().get("workers", {}))
    return rows, n_workers, _info(lambda: client.submit(model_info, spec, names,
                                                        pure=False).result())


def _info(fetch):
    """Model name and units, or empty ones if the model does not compile."""
    try:
        return fetch()
    except Exception:                           # noqa: BLE001 - the points carry the error
        return {"name": "", "units": {}}


def _result(rows, points, params, settings, wall, n_workers, info):
    fixed = set(params or ())
    varied = [c for c in points[0] if c not in fixed]
    outputs = list(settings["outputs"])
    for r in rows:
        outputs += [k for k in r if k not in outputs and k not in points[0]
                    and k not in ("point", "status", "error", "wall_time")]
    return SweepResult(rows, varied, outputs, info["units"], wall, n_workers, info["name"])
