"""Simulation results: every variable by its dotted name."""
from __future__ import annotations

import csv
import difflib
import os
import pathlib
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Protocol, TypeVar, Union, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import Acausal2dError

if TYPE_CHECKING:
    from .visual.notebook import Animation
    from _typeshed import SupportsWrite
    from matplotlib.figure import Figure
    import pandas

    from .protocols import CompiledData
    from .runtime.selection import Singularity

PathT = TypeVar("PathT", bound=Union[str, "os.PathLike[str]"])
"""A file path, handed back as it was given (a str or a path object)."""


@runtime_checkable
class ColumnSource(Protocol):
    """Columns computed on demand: ``column(k)`` gives the values of the
    k-th name over the result's time (e.g. the system's
    :class:`~acausal2d.compiler.system.AliasColumns`)."""

    def column(self, k: int) -> NDArray[np.float64]:
        """The values of column ``k`` over ``time``."""


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

    time: NDArray[np.float64]
    parameters: dict[str, float]
    events: list[tuple[float, str]]
    stats: dict[str, float]
    outputs: list[str]
    model: CompiledData | None
    """The compiled model that made the result (None for a result made otherwise)."""
    singularities: list[Singularity]
    stopped: str | None
    states: list[str]
    """Names of the states the run integrated (set by the run)."""
    native_notes: list[str]
    """What the native runtime said about the run (set by the run)."""

    def __init__(self, time: ArrayLike, node_names: Sequence[str],
                 node_values: ArrayLike | ColumnSource, alias_names: Sequence[str],
                 alias_values: ArrayLike | ColumnSource, param_names: Iterable[str],
                 param_values: Iterable[float], events: Iterable[tuple[float, str]] = (),
                 stats: Mapping[str, float] | None = None, outputs: Iterable[str] = (),
                 model: CompiledData | None = None) -> None:
        self.time = np.asarray(time)
        self._index: dict[str, int] = {}
        self._cols: list[NDArray[np.float64] | _Lazy] = []
        for names, values in ((node_names, node_values), (alias_names, alias_values)):
            if isinstance(values, ColumnSource):      # computed when first read
                for k, name in enumerate(names):
                    self._index[name] = len(self._cols)
                    self._cols.append(_Lazy(values, k))
                continue
            if not len(names):
                continue
            table = np.asarray(values).reshape(len(self.time), -1)
            for k, name in enumerate(names):
                self._index[name] = len(self._cols)
                self._cols.append(table[:, k])
        self.parameters = dict(zip(param_names, (float(v) for v in param_values)))
        self.events = list(events)
        self.short_names: dict[str, str] = {}
        """{name as written: column}: a signal connector's value by the
        connector's name (``close.y`` for the column ``close.y.u``)."""
        self.event_texts: list[tuple[float, str]] = list(self.events)
        """(time, text) of every event in the elements' own words
        (:mod:`acausal2d.runtime.event_words`); ``events`` holds the raw
        relation expressions."""
        self.stats = dict(stats or {})
        self.outputs = list(outputs)
        self.model = model
        self.singularities = []
        self.stopped = None

    def add_columns(self, columns: Iterable[tuple[str, ArrayLike]]) -> None:
        """Append (name, values over ``time``) columns, e.g. the derived
        signals of :mod:`acausal2d.derived`."""
        for name, values in columns:
            self._index[name] = len(self._cols)
            self._cols.append(np.asarray(values, dtype=float))

    @property
    def success(self) -> bool:
        """True if the run reached its stop time (``stopped`` is None)."""
        return self.stopped is None

    @property
    def message(self) -> str:
        """Why the run ended: "reached the stop time" or the reason it
        stopped early (``stopped``)."""
        return "reached the stop time" if self.stopped is None else str(self.stopped)

    @property
    def units(self) -> dict[str, str]:
        """{name: unit} of ``time``, every column and every parameter, from
        the components' declarations ('' where none is declared)."""
        return {n: self.unit(n) for n in ["time"] + self.names + list(self.parameters)}

    @property
    def names(self) -> list[str]:
        """Names of all time-varying columns (unknowns, aliases, derivatives)."""
        return list(self._index)

    def __contains__(self, name: object) -> bool:
        return name in self._index or name in self.parameters or name == "time" \
            or name in self.short_names

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        """The values of ``name`` (a column, a parameter or ``"time"``) over
        ``time``; an unknown name is an error that suggests close names."""
        if name == "time":
            return self.time
        k = self._index.get(self.short_names.get(name, name))
        if k is not None:
            column = self._cols[k]
            if isinstance(column, _Lazy):
                column = self._cols[k] = column.values()
            return column
        if name in self.parameters:
            return np.full(len(self.time), self.parameters[name])
        raise Acausal2dError("no variable %r in the result%s" % (name, _did_you_mean(
            name, list(self._index) + list(self.parameters))))

    def at(self, name: str, t: float) -> float:
        """Value of ``name`` at time ``t`` (linear interpolation)."""
        return float(np.interp(t, self.time, self[name]))

    def final(self, name: str) -> float:
        """Value of ``name`` at the end of the run."""
        return float(self[name][-1])

    def unit(self, name: str) -> str:
        """Unit of a column or parameter from its declaration ('' if none)."""
        if name == "time":
            return "s"
        name = self.short_names.get(name, name)
        return self.model.units.get(name, "") if self.model is not None else ""

    def to_csv(self, path: PathT, names: Iterable[str] | None = None) -> PathT:
        """Write a CSV file with a ``time`` column and the given variables (all
        by default, derivatives excluded); creates the folder if needed and
        replaces an existing file atomically."""
        from .io.files import atomic_path
        with atomic_path(path) as tmp:
            with open(tmp, "w", newline="") as fh:
                self.write_csv(fh, names)
        return path

    def write_csv(self, fh: SupportsWrite[str], names: Iterable[str] | None = None) -> None:
        """The CSV text of :meth:`to_csv` written to the open text stream
        ``fh`` (a file opened with ``newline=""``, or an ``io.StringIO``)."""
        columns = [n for n in self._index if not n.startswith("der(")] if names is None \
            else list(names)
        w = csv.writer(fh)
        w.writerow(["time"] + columns)
        cols = [self.time] + [self[n] for n in columns]
        for row in zip(*cols):
            w.writerow(["%.17g" % v for v in row])

    def plot(self, names: Sequence[str] | Sequence[Sequence[str]] | None = None,
             path: str | os.PathLike[str] | None = None, title: str | None = None,
             x: str | None = None) -> Figure | str | os.PathLike[str]:
        """Plot signals (default: the model's outputs) over time or over the
        signal ``x``, with units in the labels; same-unit signals share an
        axes with a legend.  Writes ``path`` or returns a matplotlib Figure.
        See :func:`acausal2d.visual.plotting.plot`."""
        from .visual.plotting import plot
        return plot(self, names, path, title, x=x)

    def animate(self, path: str | os.PathLike[str], traces: Iterable[str] = (),
                title: str | None = None, arrows: Iterable[str] = (), signal: str | None = None,
                autoplay: bool = False, poles: Mapping[str, str] | None = None) -> pathlib.Path:
        """Write a self-contained HTML animation of the mechanism, drawn from
        the components' ``shapes()``; ``traces`` are frame names (or
        ``"x_name:y_name"`` pairs) whose path is drawn, ``arrows`` frames or
        rotational flanges whose forces and torques are drawn, ``signal`` a
        signal plotted under the mechanism with a cursor synced to the time
        slider, ``autoplay`` starts playback, ``poles`` ({label: link}, see
        :meth:`poles`) draws the instantaneous poles on a layer.  See
        :mod:`acausal2d.visual.scene` and :mod:`acausal2d.visual.animation`."""
        from .visual.scene import animate
        return animate(self, path, traces, title, arrows, signal, autoplay, poles)

    def animation(self, traces: Iterable[str] = (), title: str | None = None,
                  arrows: Iterable[str] = (), signal: str | None = None, autoplay: bool = False,
                  poles: Mapping[str, str] | None = None, height: int = 560) -> Animation:
        """The animation (options as for :meth:`animate`) as an object a
        notebook displays inline (:class:`acausal2d.visual.notebook.Animation`,
        whose ``save(path)`` writes the page)."""
        from .visual.animation import render_html
        from .visual.notebook import Animation
        from .visual.scene import NO_GEOMETRY, build_scene, has_geometry
        if self.model is not None and not has_geometry(self.model.model):
            raise Acausal2dError(NO_GEOMETRY % type(self.model.model).__name__)
        scene = build_scene(self, traces, title, arrows, signal, autoplay, poles)
        return Animation(render_html(scene), height)

    # ------------------------------------------------- other formats
    def to_pandas(self, names: Iterable[str] | None = None) -> pandas.DataFrame:
        """A :class:`pandas.DataFrame` indexed by ``time`` with the given
        columns (all by default, derivatives included); event instants
        appear twice in the index, as in the result.  Needs pandas."""
        try:
            import pandas as pd
        except ImportError:
            raise Acausal2dError("Result.to_pandas needs pandas, an optional dependency: "
                                 "pip install 'acausal2d[pandas]' (or pip install pandas)") from None
        columns = self.names if names is None else list(names)
        frame: pandas.DataFrame = pd.DataFrame({n: self[n] for n in columns},
                                               index=pd.Index(self.time, name="time"))
        frame.attrs["units"] = {n: self.unit(n) for n in columns}
        return frame

    def to_mat(self, path: PathT, names: Iterable[str] | None = None) -> PathT:
        """Write the result in Dymola's result format (MAT v4 ``Aclass``,
        ``name``, ``description``, ``dataInfo``, ``data_1`` with the
        parameters, ``data_2`` with the trajectories; columns equal to
        another or its negation shared) for Modelica plotting tools; every
        column (derivatives included) unless ``names`` is given.  See
        :mod:`acausal2d.io.dymola_mat`.  Returns ``path``."""
        from .io.dymola_mat import write_mat
        columns = self.names if names is None else list(names)
        units = {n: self.unit(n) for n in columns + list(self.parameters)}
        return write_mat(path, self.time, {n: self[n] for n in columns}, self.parameters,
                         {n: "[%s]" % u for n, u in units.items() if u})

    def __repr__(self) -> str:
        """``<Result PistonEngine: t 0..1 s, 5001 points, 126 signals, success:
        reached the stop time>`` (or ``stopped early: <why>``)."""
        t = self.time
        span = "t %.6g..%.6g s" % (t[0], t[-1]) if len(t) else "no time points"
        model = getattr(self.model, "model", None) if self.model is not None else None
        return "<Result %s: %s, %d points, %d signals, %d events, %s: %s>" % (
            type(model).__name__ if model is not None else "model", span, len(t),
            len(self._index), len(self.events),
            "success" if self.success else "stopped early", self.message)

    def _repr_html_(self) -> str:
        """Jupyter's display: a summary table and a small figure of the outputs."""
        from .visual.notebook import summary_html
        return summary_html(self)


def _did_you_mean(name: str, names: list[str]) -> str:
    """'; did you mean a, b?' with the names closest to ``name`` (spelling,
    then the same last part), or ''."""
    close = difflib.get_close_matches(name, names, n=4, cutoff=0.75)
    last = name.split(".")[-1]
    close += [n for n in names if n.split(".")[-1] == last and n not in close][:4]
    return "; did you mean %s?" % ", ".join(close[:6]) if close else ""


class _Lazy:
    """A column of a Result computed when first read (``source.column(k)``)."""
    __slots__ = ("source", "k")

    def __init__(self, source: ColumnSource, k: int) -> None:
        self.source, self.k = source, k

    def values(self) -> NDArray[np.float64]:
        """The column's values (computed now)."""
        return self.source.column(self.k)
