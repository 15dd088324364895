"""What a result shows in a Jupyter notebook (its one-line ``repr`` is the
Result's own): ``result._repr_html_()`` a table (model, time span, points,
solver counts, events, states, outputs with their final values) and a small
figure of the outputs, and ``result.animation()`` an :class:`Animation`
whose ``_repr_html_`` embeds the self-contained animation page of
:mod:`acausal2d.visual.animation` in an ``iframe``.
"""
from __future__ import annotations

from typing import TYPE_CHECKING
import base64
import html
import io
from .plotting import plot
from ..io.files import write_text

if TYPE_CHECKING:
    from ..protocols import ResultData

__all__ = ["Animation", "summary_html"]


def _model_name(result):
    model = getattr(result.model, "model", None) if result.model is not None else None
    return type(model).__name__ if model is not None else "model"


def _rows(result):
    st = result.stats
    rows = [("model", _model_name(result)),
            ("time", "%.6g .. %.6g s, %d points" % (result.time[0], result.time[-1],
                                                   len(result.time))),
            ("signals", "%d (and %d parameters)" % (len(result.names), len(result.parameters))),
            ("events", str(len(result.events))),
            ("finished", "stopped early: %s" % result.stopped if result.stopped else
             "reached the stop time")]
    if "steps" in st:
        rows.append(("solver", "%d steps, %d residual evaluations, %.3f s (compile %.3f s)"
                     % (st["steps"], st.get("nfev", 0), st.get("wall_time", 0.0),
                        st.get("compile_time", 0.0))))
    states = getattr(result, "states", None)
    if states:
        rows.append(("states", ", ".join(states)))
    for name in _plotted(result):
        rows.append(("final " + name, "%.6g %s" % (result.final(name), result.unit(name))))
    return rows


def _plotted(result, most=4):
    """Signals of the small figure: the declared outputs, else the states."""
    names = list(result.outputs) or list(getattr(result, "states", None) or [])
    return [n for n in names if n in result.names][:most]


def _figure_png(result):
    """The outputs over time as a small PNG (base64), or '' if none."""
    names = _plotted(result)
    if not names or len(result.time) < 2:
        return ""
    fig = plot(result, [[n] for n in names])
    fig.set_size_inches(6, 1.6 + 1.4 * len(names))
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=60)
    return base64.b64encode(buf.getvalue()).decode("ascii")


def summary_html(result: ResultData) -> str:
    """The notebook display of a result: the summary table and a small
    figure of its outputs (an inline PNG)."""
    cells = "".join("<tr><th style='text-align:left'>%s</th><td style='text-align:left'>%s"
                    "</td></tr>" % (html.escape(k), html.escape(v)) for k, v in _rows(result))
    png = _figure_png(result)
    img = "<img alt='outputs over time' src='data:image/png;base64,%s'/>" % png if png else ""
    return "<div class='acausal2d-result'><table>%s</table>%s</div>" % (cells, img)


class Animation:
    """The animation of a result as a notebook shows it: ``_repr_html_``
    embeds the self-contained page (see
    :func:`acausal2d.visual.animation.render_html`) in an ``iframe``;
    ``html`` is that page and ``save(path)`` writes it."""

    def __init__(self, page: str, height: int = 560) -> None:
        self.html = page
        self.height = int(height)

    def _repr_html_(self):
        return ("<iframe srcdoc=\"%s\" style=\"width:100%%;height:%dpx;border:0\" "
                "sandbox=\"allow-scripts\"></iframe>" % (html.escape(self.html, quote=True),
                                                         self.height))

    def save(self, path):
        """Write the page to ``path`` (atomically); returns the path."""
        return write_text(path, self.html)

    def __repr__(self):
        return "<Animation: %d characters of HTML; display it in a notebook or save(path)>" \
            % len(self.html)
