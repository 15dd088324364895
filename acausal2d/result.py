"""Simulation results: every variable by its dotted name."""
import csv
import difflib

import numpy as np

from .errors import Acausal2dError
from .io.files import atomic_path
from .visual.plotting import plot
from .visual.scene import animate
from .visual.animation import render_html
from .visual.notebook import Animation
from .visual.scene import build_scene
from .io.dymola_mat import write_mat
from .visual.notebook import summary_html


class Result:
    """Time series of a simulation.

    ``result["revolute.phi"]`` gives a numpy array over ``result.time`` for
    any unknown, eliminated alias, derivative (``"der(revolute.phi)"``) or
    parameter.  Event instants appear twice (left and right limit).
    ``events`` lists (time, description); ``stats`` holds counters and wall
    times.  ``singularities`` lists the singular positions met during the
    run (dicts with time, element, kind) and ``stopped`` says why a run
    ended early (None if it reached its stop time); ``success`` and
    ``message`` say the same as scipy's and scikit-sundae's results do.
    ``units`` maps every signal and parameter to its declared unit.
    """

    def __init__(self, time, node_names, node_values, alias_names, alias_values,
                 param_names, param_values, events=(), stats=None, outputs=(), model=None):
        self.time = np.asarray(time)
        self._index = {}
        self._cols = []
        for names, values in ((node_names, node_values), (alias_names, alias_values)):
            if hasattr(values, "column"):      # computed when first read
                for k, name in enumerate(names):
                    self._index[name] = len(self._cols)
                    self._cols.append(_Lazy(values, k))
                continue
            values = np.asarray(values).reshape(len(self.time), -1) if len(names) else None
            for k, name in enumerate(names):
                self._index[name] = len(self._cols)
                self._cols.append(values[:, k])
        self.parameters = dict(zip(param_names, (float(v) for v in param_values)))
        self.events = list(events)
        self.stats = dict(stats or {})
        self.outputs = list(outputs)
        self.model = model
        self.singularities = []
        self.stopped = None

    def add_columns(self, columns):
        """Append (name, values over ``time``) columns, e.g. the derived
        signals of :mod:`acausal2d.derived`."""
        for name, values in columns:
            self._index[name] = len(self._cols)
            self._cols.append(np.asarray(values, dtype=float))

    @property
    def success(self):
        """True if the run reached its stop time (``stopped`` is None)."""
        return self.stopped is None

    @property
    def message(self):
        """Why the run ended: "reached the stop time" or the reason it
        stopped early (``stopped``)."""
        return "reached the stop time" if self.stopped is None else str(self.stopped)

    @property
    def units(self):
        """{name: unit} of ``time``, every column and every parameter, from
        the components' declarations ('' where none is declared)."""
        return {n: self.unit(n) for n in ["time"] + self.names + list(self.parameters)}

    @property
    def names(self):
        """Names of all time-varying columns (unknowns, aliases, derivatives)."""
        return list(self._index)

    def __contains__(self, name):
        return name in self._index or name in self.parameters or name == "time"

    def __getitem__(self, name):
        if name == "time":
            return self.time
        k = self._index.get(name)
        if k is not None:
            if isinstance(self._cols[k], _Lazy):
                self._cols[k] = self._cols[k].values()
            return self._cols[k]
        if name in self.parameters:
            return np.full(len(self.time), self.parameters[name])
        raise Acausal2dError("no variable %r in the result%s" % (name, _did_you_mean(
            name, list(self._index) + list(self.parameters))))

    def at(self, name, t):
        """Value of ``name`` at time ``t`` (linear interpolation)."""
        return float(np.interp(t, self.time, self[name]))

    def final(self, name):
        """Value of ``name`` at the end of the run."""
        return float(self[name][-1])

    def unit(self, name):
        """Unit of a column or parameter from its declaration ('' if none)."""
        if name == "time":
            return "s"
        return self.model.units.get(name, "") if self.model is not None else ""

    def to_csv(self, path, names=None):
        """Write a CSV file with a ``time`` column and the given variables (all
        by default, derivatives excluded); creates the folder if needed and
        replaces an existing file atomically."""
        with atomic_path(path) as tmp:
            with open(tmp, "w", newline="") as fh:
                self.write_csv(fh, names)
        return path

    def write_csv(self, fh, names=None):
        """The CSV text of :meth:`to_csv` written to the open text stream
        ``fh`` (a file opened with ``newline=""``, or an ``io.StringIO``)."""
        if names is None:
            names = [n for n in self._index if not n.startswith("der(")]
        w = csv.writer(fh)
        w.writerow(["time"] + list(names))
        cols = [self.time] + [self[n] for n in names]
        for row in zip(*cols):
            w.writerow(["%.17g" % v for v in row])

    def plot(self, names=None, path=None, title=None, x=None):
        """Plot signals (default: the model's outputs) over time or over the
        signal ``x``, with units in the labels; same-unit signals share an
        axes with a legend.  Writes ``path`` or returns a matplotlib Figure.
        See :func:`acausal2d.visual.plotting.plot`."""
        return plot(self, names, path, title, x=x)

    def animate(self, path, traces=(), title=None, arrows=(), signal=None, autoplay=False,
                poles=None):
        """Write a self-contained HTML animation of the mechanism, drawn from
        the components' ``shapes()``; ``traces`` are frame names (or
        ``"x_name:y_name"`` pairs) whose path is drawn, ``arrows`` frames or
        rotational flanges whose forces and torques are drawn, ``signal`` a
        signal plotted under the mechanism with a cursor synced to the time
        slider, ``autoplay`` starts playback, ``poles`` ({label: link}, see
        :meth:`poles`) draws the instantaneous poles on a layer.  See
        :mod:`acausal2d.visual.scene` and :mod:`acausal2d.visual.animation`."""
        return animate(self, path, traces, title, arrows, signal, autoplay, poles)

    def animation(self, traces=(), title=None, arrows=(), signal=None, autoplay=False,
                  poles=None, height=560):
        """The animation (options as for :meth:`animate`) as an object a
        notebook displays inline (:class:`acausal2d.visual.notebook.Animation`,
        whose ``save(path)`` writes the page)."""
        scene = build_scene(self, traces, title, arrows, signal, autoplay, poles)
        return Animation(render_html(scene), height)

    # ------------------------------------------------- other formats
    def to_pandas(self, names=None):
        """A :class:`pandas.DataFrame` indexed by ``time`` with the given
        columns (all by default, derivatives included); event instants
        appear twice in the index, as in the result.  Needs pandas."""
        try:
            import pandas as pd
        except ImportError:
            raise Acausal2dError("Result.to_pandas needs pandas, an optional dependency: "
                                 "pip install 'acausal2d[pandas]' (or pip install pandas)") from None
        names = self.names if names is None else list(names)
        frame = pd.DataFrame({n: self[n] for n in names}, index=pd.Index(self.time, name="time"))
        frame.attrs["units"] = {n: self.unit(n) for n in names}
        return frame

    def to_mat(self, path, names=None):
        """Write the result in Dymola's result format (MAT v4 ``Aclass``,
        ``name``, ``description``, ``dataInfo``, ``data_1`` with the
        parameters, ``data_2`` with the trajectories; columns equal to
        another or its negation shared) for Modelica plotting tools; every
        column (derivatives included) unless ``names`` is given.  See
        :mod:`acausal2d.io.dymola_mat`.  Returns ``path``."""
        names = self.names if names is None else list(names)
        units = {n: self.unit(n) for n in list(names) + list(self.parameters)}
        return write_mat(path, self.time, {n: self[n] for n in names}, self.parameters,
                         {n: "[%s]" % u for n, u in units.items() if u})

    def __repr__(self):
        """``<Result PistonEngine: t 0..1 s, 5001 points, 126 signals, success:
        reached the stop time>`` (or ``stopped early: <why>``)."""
        t = self.time
        span = "t %.6g..%.6g s" % (t[0], t[-1]) if len(t) else "no time points"
        model = getattr(self.model, "model", None) if self.model is not None else None
        return "<Result %s: %s, %d points, %d signals, %d events, %s: %s>" % (
            type(model).__name__ if model is not None else "model", span, len(t),
            len(self._index), len(self.events),
            "success" if self.success else "stopped early", self.message)

    def _repr_html_(self):
        """Jupyter's display: a summary table and a small figure of the outputs."""
        return summary_html(self)


def _did_you_mean(name, names):
    """'; did you mean a, b?' with the names closest to ``name`` (spelling,
    then the same last part), or ''."""
    close = difflib.get_close_matches(name, names, n=4, cutoff=0.75)
    last = name.split(".")[-1]
    close += [n for n in names if n.split(".")[-1] == last and n not in close][:4]
    return "; did you mean %s?" % ", ".join(close[:6]) if close else ""


class _Lazy:
    """A column of a Result computed when first read (``source.column(k)``)."""
    __slots__ = ("source", "k")

    def __init__(self, source, k):
        self.source, self.k = source, k

    def values(self):
        return self.source.column(self.k)
