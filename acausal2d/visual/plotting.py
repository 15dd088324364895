"""Plots of result signals with units from the declarations.

matplotlib is used through its object API only (``matplotlib.figure.Figure``
with an Agg canvas attached for writing files): no pyplot, no global backend
switch, so a notebook keeps its own backend; matplotlib is imported only
when something is plotted.

A *figure* is a list of signal groups.  The signals of one group that share
a unit are drawn as lines of one axes with a legend (an overlay); signals of
another unit get an axes of their own below it, sharing the x axis.  Every
axis label carries the unit (``rope1.F [N]``, ``time [s]``) and the title
names the model.  The x axis is time or any signal (``x="crank.phi"``): an
angle (unit ``rad``) is unwrapped and shown in degrees.

Models may declare their figures as a class attribute ``figures``, a list of
dicts ``{"signals": [...], "x": name, "title": text, "name": file stem}``
(only ``signals`` is required); ``acausal2d simulate`` then writes those
instead of one figure per declared output.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING
import os

import numpy as np

from ..analysis.poles import transfer
from ..errors import Acausal2dError
from ..io.files import atomic_path
from ..io.files import safe_filename

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..protocols import ResultData


def unit_of(result, name):
    """Unit of the column or parameter ``name`` of ``result`` ('' if unknown;
    see :meth:`acausal2d.result.Result.unit`)."""
    return result.unit(name)


def axis_label(name, unit):
    """``"name [unit]"``; dimensionless or undeclared units show as ``[-]``."""
    return "%s [%s]" % (name, unit or "-")


def x_values(result, x):
    """(values, label) of the x axis: time, or the signal ``x`` (an angle in
    rad unwrapped and converted to degrees)."""
    if x is None or x == "time":
        return np.asarray(result.time), axis_label("time", "s")
    values = np.asarray(result[x], dtype=float)
    unit = unit_of(result, x)
    if unit == "rad":
        return np.degrees(np.unwrap(values)), axis_label(x, "deg")
    return values, axis_label(x, unit)


def panels(result, groups):
    """Split each group of signal names into runs of one unit: a list of
    (unit, [names]) in order, one per axes."""
    out = []
    for group in groups:
        by_unit = {}
        for name in group:
            result[name]                       # unknown names raise here, with suggestions
            by_unit.setdefault(unit_of(result, name), []).append(name)
        out += list(by_unit.items())
    return out


def _ylabel(unit, names):
    if len(names) == 1:
        return axis_label(names[0], unit)
    tails = {n.rsplit(".", 1)[-1] for n in names}
    return axis_label(tails.pop() if len(tails) == 1 else "", unit).lstrip()


def figure_title(result, title=None):
    """The model's class name, followed by ``title`` if given."""
    model = getattr(result, "model", None)
    name = type(model.model).__name__ if model is not None else ""
    return ": ".join(t for t in (name, title) if t)


def figure_plan(result, groups, x=None, title=None):
    """What a figure of the signal ``groups`` (a list of lists of names)
    over ``x`` (time by default) shows, as plain data (picklable: it can be
    drawn in another process, :mod:`~acausal2d.visual.figure_process`): a
    dict with the x values and label, the title and per axes its y label
    and (name, values) lines."""
    plan = panels(result, groups)
    if not plan:
        raise Acausal2dError("nothing to plot: give signal names (the model declares no outputs)")
    xv, xlabel = x_values(result, x)
    axes = [(_ylabel(unit, names), [(name, np.asarray(result[name], dtype=float))
                                    for name in names]) for unit, names in plan]
    return {"x": xv, "xlabel": xlabel, "title": figure_title(result, title), "axes": axes}


def draw_plan(plan):
    """A matplotlib Figure (Agg canvas attached) of a :func:`figure_plan`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8, 2.4 * len(plan["axes"]) + 0.9))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(plan["axes"]), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (ylabel, lines) in zip(axes, plan["axes"]):
        for name, values in lines:
            ax.plot(plan["x"], values, lw=1.3, label=name)
        ax.set_ylabel(ylabel, fontsize=9)
        ax.grid(True, alpha=0.3)
        if len(lines) > 1:
            ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel(plan["xlabel"])
    fig.suptitle(plan["title"])
    fig.tight_layout()
    return fig


def make_figure(result, groups, x=None, title=None):
    """A matplotlib Figure (Agg canvas attached) of the signal ``groups``
    (a list of lists of names) over ``x`` (time by default)."""
    return draw_plan(figure_plan(result, groups, x=x, title=title))


def save_figure(fig, path, dpi=110):
    """Write ``fig`` as PNG (or the format of ``path``'s extension)
    atomically; returns ``path``."""
    fmt = os.path.splitext(os.fspath(path))[1][1:].lower() or "png"
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=dpi, format=fmt)
    return path


def plot(result: ResultData, names: Sequence[str] | Sequence[Sequence[str]] | None = None,
         path: str | os.PathLike[str] | None = None, title: str | None = None,
         x: str | None = None) -> Figure | str | os.PathLike[str]:
    """Plot ``names`` (default: the model's declared outputs) over time or
    over the signal ``x``.  ``names`` is a list of signals (one group:
    same-unit signals overlaid with a legend) or a list of such lists.

    With ``path`` the figure is written (PNG unless the extension says
    otherwise, e.g. ``.svg``) and the path returned; otherwise the
    matplotlib Figure is returned (for notebooks)."""
    names = list(names or result.outputs)
    groups = names if names and all(isinstance(n, (list, tuple)) for n in names) else [names]
    fig = make_figure(result, groups, x=x, title=title)
    return fig if path is None else save_figure(fig, path)


def parse_groups(text):
    """``"a,b;c"`` -> ``[["a", "b"], ["c"]]`` (the ``--plot`` option)."""
    groups = [[n.strip() for n in part.split(",") if n.strip()] for part in text.split(";")]
    groups = [g for g in groups if g]
    if not groups:
        raise Acausal2dError("--plot takes signal names: a,b overlays a and b in one figure, "
                             "a,b;c makes two figures; got %r" % text)
    return groups


def declared_figures(model):
    """The model's ``figures`` declaration as a list of dicts with keys
    signals, x, title, name (checked: unknown keys and empty signal lists
    raise :class:`~acausal2d.errors.Acausal2dError`)."""
    specs = getattr(model, "figures", None) or []
    out = []
    for k, spec in enumerate(specs):
        if not isinstance(spec, dict) or not spec.get("signals"):
            raise Acausal2dError("%s.figures[%d] must be a dict with a list 'signals' (and "
                                 "optionally 'x', 'title', 'name')" % (type(model).__name__, k))
        extra = set(spec) - {"signals", "x", "title", "name"}
        if extra:
            raise Acausal2dError("%s.figures[%d]: unknown key(s) %s; known: signals, x, title, "
                                 "name" % (type(model).__name__, k, ", ".join(sorted(extra))))
        signals = spec["signals"]
        groups = signals if all(isinstance(s, (list, tuple)) for s in signals) else [signals]
        out.append({"groups": [list(g) for g in groups], "x": spec.get("x"),
                    "title": spec.get("title"), "name": spec.get("name")})
    return out


def write_figures(result, out_dir, specs, fmt="png"):
    """Write one figure file (``fmt``: png, svg or pdf) per figure spec
    (dicts as from :func:`declared_figures`) into ``out_dir``; the file is
    named by the figure's ``name`` or by its signals.  Returns the paths."""
    return draw_jobs(figure_jobs(result, out_dir, specs, fmt))


def figure_jobs(result, out_dir, specs, fmt="png"):
    """The (path, :func:`figure_plan`) pairs :func:`write_figures` draws:
    signal names checked, values taken from ``result``; no matplotlib."""
    jobs = []
    for spec in specs:
        stem = spec.get("name") or "+".join(n for g in spec["groups"] for n in g)
        plan = figure_plan(result, spec["groups"], x=spec.get("x"), title=spec.get("title"))
        jobs.append((os.path.join(out_dir, safe_filename(stem) + "." + fmt), plan))
    return jobs


def draw_jobs(jobs):
    """Draw and write each (path, :func:`figure_plan`) of ``jobs``; returns
    the paths."""
    return [save_figure(draw_plan(plan), path) for path, plan in jobs]


def _sweep_lines(ax, study, x, names, others):
    """One line per output of ``names`` and combination of the ``others``
    columns' values, over the column ``x`` (failed points left out)."""
    ok = np.array([r.get("status") != "failed" for r in study.rows])
    keys = [tuple(r.get(c) for c in others) for r in study.rows]
    xv = study.column(x)
    for name in names:
        yv = study.column(name)
        for key in dict.fromkeys(keys):
            sel = ok & np.array([k == key for k in keys])
            if sel.any():
                tag = ", ".join("%s=%.4g" % (c, v) for c, v in zip(others, key))
                ax.plot(xv[sel], yv[sel], "o-", ms=3, lw=1.2,
                        label=name + (" (%s)" % tag if tag else ""))


def sweep_figure(study, x, outputs):
    """Figure of a :class:`~acausal2d.analysis.sweep.SweepResult`: the
    ``outputs`` over the varied column ``x``, one axes per unit, one line
    per output and combination of the other varied columns (failed points
    left out)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    if not outputs:
        raise Acausal2dError("the sweep has no outputs to plot; give outputs=[...] or metrics")
    others = [c for c in study.parameters if c != x]
    by_unit = {}
    for name in outputs:
        by_unit.setdefault(study.units.get(name, ""), []).append(name)
    fig = Figure(figsize=(7.5, 2.6 * len(by_unit) + 1.0))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(by_unit), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (unit, names) in zip(axes, by_unit.items()):
        _sweep_lines(ax, study, x, names, others)
        ax.set_ylabel(_ylabel(unit, names), fontsize=9)
        ax.grid(True, alpha=0.3)
        if len(names) > 1 or others:
            ax.legend(fontsize=8, loc="best")
    axes[-1].set_xlabel(axis_label(x, study.units.get(x, "")))
    failed = len(study.failed)
    fig.suptitle("%s: sweep of %d points%s" % (study.model_name or "model", len(study.rows),
                                               ", %d failed" % failed if failed else ""))
    fig.tight_layout()
    return fig


def transfer_figure(result, q, p, orders=(0, 1, 2)):
    """Figure of the transfer functions of ``q`` over the drive coordinate
    ``p`` (Ebert 2015, eq. 2.2-2.4): one axes per order, q, q' = dq/dp and
    q'' = d2q/dp2 from the run's derivatives (see
    :func:`acausal2d.analysis.poles.transfer`), over p (degrees for angles)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    curves = transfer(result, q, p, orders)
    xv, xlabel = x_values(result, p)
    uq, up = unit_of(result, q) or "-", unit_of(result, p) or "-"
    labels = {0: "%s [%s]" % (q, uq), 1: "d%s/d%s [%s/%s]" % (q, p, uq, up),
              2: "d2%s/d%s2 [%s/%s2]" % (q, p, uq, up)}
    fig = Figure(figsize=(8, 2.2 * len(curves) + 0.9))
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(curves), 1, sharex=True, squeeze=False)[:, 0]
    for ax, order in zip(axes, sorted(curves)):
        ax.plot(xv, curves[order], lw=1.3)
        ax.set_ylabel(labels[order], fontsize=8)
        ax.grid(True, alpha=0.3)
    axes[-1].set_xlabel(xlabel)
    fig.suptitle(figure_title(result, "transfer functions of order %s"
                              % ", ".join(map(str, sorted(curves)))))
    fig.tight_layout()
    return fig


def write_transfer_figures(result, out_dir, specs, orders, fmt="png"):
    """One transfer-function figure per signal of the figure ``specs`` over
    each spec's x (the drive coordinate); returns the paths."""
    paths = []
    for spec in specs:
        for q in (n for g in spec["groups"] for n in g):
            fig = transfer_figure(result, q, spec["x"], orders)
            stem = safe_filename("transfer_%s_over_%s" % (q, spec["x"]))
            paths.append(save_figure(fig, os.path.join(out_dir, stem + "." + fmt)))
    return paths


def parse_orders(text):
    """``"0,1,2"`` -> (0, 1, 2) (the ``--transfer`` option)."""
    try:
        orders = tuple(sorted({int(t) for t in text.split(",") if t.strip()}))
    except ValueError:
        orders = ()
    if not orders or any(o not in (0, 1, 2) for o in orders):
        raise Acausal2dError("--transfer takes orders 0, 1, 2 separated by commas (e.g. "
                             "0,1,2); got %r" % text)
    return orders
