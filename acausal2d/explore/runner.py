"""The warm model of an explore server and the queue its runs go through.

:class:`Explorer` compiles the model once and runs every request on one
worker thread (a compiled model is not shared between threads, and the two
cores of a laptop are better spent on one run at a time than on several
half-speed ones).  Runs of one *session* (a browser tab) supersede each
other: a queued run that a newer one of its session has overtaken is never
started, and a running one is stopped at its next output row.  Nothing is
kept between runs but a counter per session (at most ``MAX_SESSIONS``).
"""
import collections
import html
import concurrent.futures
import io
import math
import threading
import time
import warnings

import numpy as np

from ..compiled import compile_model
from ..run_checks import _experiment
from ..errors import Acausal2dError, SimulationError
from ..io.loader import load_model
from ..options import RunOptions
from .drag import movable
from .requests import parse_run
from ..visual.animation import render_html
from ..visual.scene import NO_GEOMETRY, build_scene
from ..visual.plotting import declared_figures
from .drag import drag_start

MAX_SESSIONS = 256
"""Sessions whose latest run number the server remembers (oldest dropped)."""


class Superseded(Acausal2dError):
    """A run overtaken by a newer run of its session (HTTP 409); ``run``:
    its number."""

    def __init__(self, message, run):
        super().__init__(message)
        self.run = run


class _Cancel(Exception):
    """Raised in the progress callback of a run to stop it."""


def _column(values):
    """A signal as a JSON list: NaN and infinities as null."""
    a = np.asarray(values, dtype=float)
    out = a.tolist()
    if not np.isfinite(a).all():
        out = [v if math.isfinite(v) else None for v in out]
    return out


def _short(x):
    """``x`` to 12 significant digits: a slider's end computed as 0.1 + 0.2
    reads 0.3, not 0.30000000000000004."""
    return float("%.12g" % x)


def _slider(decl, value):
    """(low, high) of a slider around ``value`` that obeys the rule of
    ``decl``: from value - 2|value| to value + 2|value| (-1 ... 1 about
    zero), cut at the declared min and max; positive: above |value|/100;
    both to 12 significant digits."""
    half = 2.0 * abs(value) if value != 0 else 1.0
    lo, hi = value - half, value + half
    if decl.positive:
        lo = max(lo, abs(value) / 100.0 if value > 0 else 1e-3)
    if decl.min is not None:
        lo = max(lo, decl.min)
    if decl.max is not None:
        hi = min(hi, decl.max)
    return _short(lo), _short(max(hi, lo))


class Explorer:
    """A compiled model ready for the explore server's runs.

    ``path``, ``model``: the model file and class (as for ``simulate``);
    ``max_stop_time``: longest run a request may ask for (default ten times
    the model's ``experiment`` stop time, or 10 s); ``max_wall_time``: the
    wall-clock budget of one run (s), after which it stops early and
    answers what it has."""

    def __init__(self, path, model=None, max_stop_time=None, max_wall_time=10.0):
        self.path = path
        self.compiled = compile_model(load_model(path, model))
        exp = _experiment(self.compiled.model)
        run = RunOptions().resolved(exp)
        stop = run.stop_time
        self.defaults = {"stop_time": stop, "intervals": run.intervals,
                         "max_stop_time": float(max_stop_time or 10.0 * stop),
                         "signals": self._figure_signals()}
        if self.defaults["stop_time"] > self.defaults["max_stop_time"]:
            self.defaults["stop_time"] = self.defaults["max_stop_time"]
        self.max_wall_time = max_wall_time
        self._worker = concurrent.futures.ThreadPoolExecutor(1, "acausal2d-explore")
        self._latest = collections.OrderedDict()
        self._lock = threading.Lock()
        self.runs = 0
        self._diagrams, self.flow_names = None, []

    # ---------------------------------------------------------------- model
    def figures(self):
        """The figures the page draws: the model's declared ``figures``, else
        one per declared output (dicts groups, x, title)."""
        specs = declared_figures(self.compiled.model) or \
            [{"groups": [[n]], "x": None, "title": None} for n in self.compiled.outputs]
        return [{"groups": s["groups"], "x": s["x"], "title": s["title"]} for s in specs]

    def _figure_signals(self):
        names = []
        for spec in self.figures():
            names += [n for g in spec["groups"] for n in g] + ([spec["x"]] if spec["x"] else [])
        return list(dict.fromkeys(n for n in names if n != "time"))

    def parameters(self):
        """Every parameter (vectors as a whole): name, value (a list), unit,
        rule, doc, min, max, positive, nonzero and the slider's range per
        component (``GET /api/params``); not the parameters read while
        compiling (:attr:`~acausal2d.compiled.CompiledModel.structural`:
        a slider would change nothing, a request changing one is refused
        naming it)."""
        cm = self.compiled
        vals = cm.parameter_values()
        out = []
        for name, (decl, idx) in cm.parameter_declarations.items():
            if name in cm.structural:
                continue
            v = [float(vals[i]) for i in idx]
            out.append({"name": name, "value": v, "unit": decl.unit or "", "rule": decl.rule,
                        "doc": decl.doc or "", "min": decl.min, "max": decl.max,
                        "positive": decl.positive, "nonzero": bool(getattr(decl, "nonzero", False)),
                        "range": [list(_slider(decl, x)) for x in v]})
        return out

    def describe(self):
        """The model as the page needs it (``GET /api/params``)."""
        cm = self.compiled
        units = cm.units
        return {"model": type(cm.model).__name__, "file": str(self.path),
                "parameters": self.parameters(), "figures": self.figures(),
                "signals": [{"name": n, "unit": units.get(n, "")} for n in cm.names],
                "outputs": list(cm.outputs), "stop_time": self.defaults["stop_time"],
                "structural": sorted(cm.structural),
                "movable": movable(cm),
                "max_stop_time": self.defaults["max_stop_time"],
                "intervals": self.defaults["intervals"], "max_wall_time": self.max_wall_time,
                "diagrams": self.diagrams(), "planar": has_geometry(cm.model)}

    def diagrams(self):
        """The model's diagram and each sub-model's (``[{"path", "svg"}]``,
        the model first; see :mod:`acausal2d.visual.diagram`), made once."""
        if self._diagrams is None:
            from ..visual.diagram import diagram_svg, structure, submodel_paths
            model, names = self.compiled.model, set(self.compiled.names)
            levels = [""] + submodel_paths(model)
            try:
                self._diagrams = [{"path": p, "svg": diagram_svg(model, path=p)}
                                  for p in levels]
                self.flow_names = [f for p in levels for ln in structure(model, path=p).lines
                                   for f in ln.flows if f in names]
            except Exception as exc:     # noqa: BLE001 - the page works without its diagram
                warnings.warn("explore: no diagram of the model (%s: %s)"
                              % (type(exc).__name__, exc))
                self._diagrams, self.flow_names = [], []
        return self._diagrams

    def parse(self, raw, drag=False):
        """A checked :class:`~acausal2d.explore.requests.RunSpec` from a
        request body (with ``drag``: of ``/api/start``);
        :class:`~acausal2d.explore.requests.BadRequest` naming the field
        otherwise."""
        return parse_run(raw, self.compiled, self.defaults, drag)

    def submit_drag(self, spec):
        """Queue the drag of ``spec`` (see :mod:`acausal2d.explore.drag`);
        a future of the answer ``{"start": {unknown: value}}``."""
        d = spec.drag

        def move():
            return {"start": drag_start(self.compiled, spec.params, spec.start,
                                        (d["x"], d["y"]), d["to"])}
        return self._worker.submit(move)

    # ---------------------------------------------------------------- runs
    def warm(self):
        """One run with the model's values (the native code compiled or
        loaded from the disk cache) before the server answers anyone; a model
        that cannot run raises its error here."""
        spec = self.parse(b"{}")
        spec.scene = True
        return self.submit(spec, lambda res, elapsed: self.answer(spec, res, elapsed)).result()

    def submit(self, spec, render):
        """Queue the run of ``spec``; a future of ``render(result)`` (on the
        worker thread).  Raises :class:`Superseded` (from the future) when a
        newer run of the same session overtakes it."""
        number = self._ticket(spec.session)
        return self._worker.submit(self._execute, spec, number, render)

    def _ticket(self, session):
        with self._lock:
            self.runs += 1
            if session is not None:
                self._latest[session] = self.runs
                self._latest.move_to_end(session)
                while len(self._latest) > MAX_SESSIONS:
                    self._latest.popitem(last=False)
            return self.runs

    def _current(self, session, number):
        return session is None or self._latest.get(session, number) == number

    def _execute(self, spec, number, render):
        if not self._current(spec.session, number):
            raise Superseded("superseded by a newer run of session %r before it started"
                             % spec.session, number)

        def progress(t, t_end):
            if not self._current(spec.session, number):
                raise _Cancel()
        t0 = time.perf_counter()
        try:
            res = self.compiled.simulate(stop_time=spec.stop_time, params=spec.params,
                                         intervals=spec.intervals, progress=progress,
                                         max_wall_time=self.max_wall_time, start=spec.start)
        except SimulationError:
            if not self._current(spec.session, number):
                raise Superseded("stopped: a newer run of session %r came" % spec.session,
                                 number) from None
            raise
        spec.run = number
        return render(res, time.perf_counter() - t0)

    def answer(self, spec, res, elapsed):
        """The JSON answer of a run: time, the chosen signals, elapsed_s
        (the run's wall time), stopped, events and the page when asked."""
        out = {"time": _column(res.time),
               "signals": {n: _column(res[n]) for n in spec.signals},
               "elapsed_s": elapsed, "stopped": res.stopped, "run": spec.run,
               "events": len(res.events), "stop_time": spec.stop_time,
               "set": {k: list(v) if isinstance(v, tuple) else v
                       for k, v in spec.params.items()}, "start": spec.start}
        if spec.scene:
            out["scene"] = scene_page(res)
            self.diagrams()
            out["flows"] = {n: _column(res[n]) for n in self.flow_names}
        return out

    @staticmethod
    def csv_text(res):
        """The run as CSV text (all columns, as ``simulate`` writes result.csv)."""
        buf = io.StringIO(newline="")
        res.write_csv(buf)
        return buf.getvalue()

    def close(self):
        """Stop the worker (waits for the run in progress)."""
        self._worker.shutdown(wait=True, cancel_futures=True)


def has_geometry(model):
    """True if a component of ``model`` draws itself in the animation (a
    planar mechanism); the page shows a drive train or a hydraulic circuit
    by its diagram only."""
    for comp in model.components():
        try:
            if comp.shapes():
                return True
        except Exception:        # noqa: BLE001 - a drawing hook that fails: no geometry
            continue
    return False


def scene_page(res):
    """The animation page of a run (the scene of ``simulate``'s
    animation.html, at most 1000 frames); a model without geometry gets a
    page that says so in one line, never an empty grid."""
    model = res.model.model if res.model is not None else None
    if model is not None and not has_geometry(model):
        return "<!DOCTYPE html><html><body><p>%s</p></body></html>" % html.escape(
            NO_GEOMETRY % type(model).__name__)
    return render_html(build_scene(res), max_frames=1000)
