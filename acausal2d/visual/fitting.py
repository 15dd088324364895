"""Figures of fits and optimisations (matplotlib object API, as
:mod:`acausal2d.visual.plotting`)."""

from .plotting import axis_label, unit_of


def _figure(rows, cols=1, size=None):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size or (7.0, 2.6 * rows + 0.8))
    FigureCanvasAgg(fig)
    return fig, fig.subplots(rows, cols, squeeze=False)


def fit_figure(fr):
    """Measured points and the fitted curve per fitted signal, with the
    estimates (+- standard error) in the title."""
    t, cols = fr.data
    fig, axes = _figure(len(fr.pairs))
    for ax, (ref, our) in zip(axes[:, 0], fr.pairs):
        ax.plot(t, cols[ref], ".", ms=3, color="0.45", label="measured %s" % ref)
        ax.plot(fr.result.time, fr.result[our], "-", lw=1.5, label="fitted model %s" % our)
        ax.set_ylabel(axis_label(our, unit_of(fr.result, our)))
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1, 0].set_xlabel(axis_label("time", "s"))
    est = ", ".join("%s = %.5g (at its %s bound)" % (n, x, fr.at_bound[n]) if n in fr.at_bound
                    else "%s = %.5g +- %.2g" % (n, x, s)
                    for n, x, s in zip(fr.names, fr.estimate, fr.std))
    fig.suptitle("%s fit: %s" % (type(fr.result.model.model).__name__
                                 if hasattr(fr.result.model, "model") else "", est), fontsize=9)
    fig.tight_layout()
    return fig


def optimize_figure(opt, signal=None):
    """The objective signal (or ``signal``) of the start and the optimum."""
    fig, axes = _figure(1)
    ax = axes[0, 0]
    name = signal or opt.signal
    for res, label in ((opt.start_result, "start"), (opt.result, "optimum")):
        if res is not None and name is not None:
            ax.plot(res.time, res[name], label="%s (%s)" % (name, label))
    if name is not None:
        ax.set_ylabel(axis_label(name, unit_of(opt.result, name)))
    ax.set_xlabel(axis_label("time", "s"))
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("objective %s: %.6g -> %.6g" % (opt.objective_text, opt.objective_start,
                                                 opt.objective), fontsize=9)
    fig.tight_layout()
    return fig
