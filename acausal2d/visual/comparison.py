"""Comparison plots: for each compared signal the reference, our curve and
the tolerance tube, and below them the deviation with its limits."""
import os

import numpy as np

from ..io.files import safe_filename
from .plotting import axis_label, save_figure


def plot_comparison(comparison, plot_dir):
    """Write one PNG per signal of ``comparison`` into ``plot_dir`` (created
    if needed): the reference, our curve and the tolerance tube, and below
    them the deviation with the tolerance limits.  Returns the paths."""
    os.makedirs(plot_dir, exist_ok=True)
    paths, used = [], set()
    for r in comparison.rows:
        base = safe_filename(r.name)
        stem, n = base, 2
        while stem.lower() in used:
            stem = "%s_%d" % (base, n)
            n += 1
        used.add(stem.lower())
        paths.append(_plot_signal(r, os.path.join(os.fspath(plot_dir), stem + ".png")))
    return paths


def _plot_signal(r, path):
    """The comparison plot of one :class:`SignalComparison` (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(8, 6))
    FigureCanvasAgg(fig)
    ax, axd = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1.3]})
    ax.fill_between(r.ref_time, r.tube_low, r.tube_high, color="tab:blue", alpha=0.2,
                    linewidth=0, label="tolerance \u00b1%.3g" % r.tolerance)
    ax.plot(r.ref_time, r.ref_values, color="tab:blue", linewidth=1.5, label="reference")
    label = "result" if r.our_name == r.name else "result (%s)" % r.our_name
    ax.plot(r.our_time, r.our_values, color="tab:orange", linewidth=1.0, linestyle="--",
            label=label)
    if np.isfinite(r.time):
        ax.axvline(r.time, color="tab:red", linewidth=0.8, alpha=0.6)
    ax.set_ylabel(axis_label(r.name, r.unit))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    title = "%s: %s, max deviation %.3g at t=%.6g (tol %.3g)" % (
        r.name, "PASS" if r.passed else "FAIL", r.max_deviation, r.time, r.tolerance)
    if r.message:
        title += "\n" + r.message
    ax.set_title(title, fontsize="medium", color="black" if r.passed else "tab:red")
    axd.plot(r.ref_time, r.our_on_ref - r.ref_values, color="tab:orange", linewidth=1.0)
    axd.axhline(r.tolerance, color="tab:blue", linewidth=0.8, linestyle=":")
    axd.axhline(-r.tolerance, color="tab:blue", linewidth=0.8, linestyle=":")
    axd.set_ylabel(axis_label("result \u2212 ref", r.unit))
    axd.set_xlabel("time [s]")
    axd.grid(True, alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, path, dpi=80)
