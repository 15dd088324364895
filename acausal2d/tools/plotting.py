"""PNG plots of result signals (matplotlib, Agg backend)."""
import os

from ..errors import Acausal2dError


def plot(result, names=None, path=None, title=None):
    """Plot ``names`` (default: the model's declared outputs) over time.

    With ``path`` the figure is written as PNG and the path returned;
    otherwise the matplotlib Figure is returned (for notebooks)."""
    import matplotlib
    if path is not None:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(names or result.outputs)
    if not names:
        raise Acausal2dError("nothing to plot: give signal names (the model declares no outputs)")
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.2 * len(names) + 0.6), sharex=True,
                             squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        ax.plot(result.time, result[name], lw=1.4)
        ax.set_ylabel(name, fontsize=9)
        ax.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time [s]")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    if path is None:
        return fig
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
