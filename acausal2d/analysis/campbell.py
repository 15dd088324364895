"""Campbell-like diagrams: natural frequencies over swept parameters.

:func:`campbell` runs :func:`acausal2d.sweep` with the metrics function
:class:`ModeFrequencies`, which linearises every point's run (at its end or
at the static equilibrium of its parameter values) and reports the natural
frequencies f1, f2, ... (Hz); the sweep's ``plot()`` then draws them over
the varied parameter.
"""
import numpy as np

from ..errors import Acausal2dError
from .equilibrium import find_equilibrium
from .linearize import OperatingPoint, linearize_point, relation_values
from .modes import modes_of
from .sweep import sweep


class ModeFrequencies:
    """A ``metrics`` function for :func:`acausal2d.sweep` (a Campbell
    diagram): the natural frequencies ``f1 .. fN`` (Hz) of every point's
    run, at its static equilibrium (``equilibrium=True``) or at the run's
    end (the sweep's ``at`` time is not seen here: set ``stop_time``)."""

    def __init__(self, count=3, equilibrium=False):
        self.count, self.equilibrium = int(count), bool(equilibrium)

    def __call__(self, result):
        cm = result.model
        s = cm.system
        p = np.array([result.parameters[n] for n, *_ in s.parameters], dtype=float)
        if self.equilibrium:
            params = {n: v for n, v in zip((n for n, *_ in s.parameters), p)}
            point = find_equilibrium(cm, params=params).point
        else:
            t = float(result.time[-1])
            z = np.array([result[n][-1] for n in s.node_names], dtype=float)
            point = OperatingPoint(t, z, relation_values(cm, t, z, p), p)
        f = modes_of(linearize_point(cm, point)).frequencies()
        return {"f%d" % (k + 1): (float(f[k]) if k < len(f) else float("nan"))
                for k in range(self.count)}


def campbell(model, vary, count=3, equilibrium=False, stop_time=None, **options):
    """Natural frequencies over swept parameters through
    :func:`acausal2d.sweep` (``vary`` as there; ``count`` frequencies
    ``f1..``); returns the :class:`~acausal2d.analysis.sweep.SweepResult`,
    whose ``plot()`` is the Campbell-like diagram."""
    if not vary:
        raise Acausal2dError("campbell needs a parameter to vary, e.g. "
                             "{'spring.c': '1e3:1e4:10'}")
    if equilibrium and stop_time is None:
        stop_time, options["intervals"] = 1e-3, 1
    table = sweep(model, vary=vary, metrics=ModeFrequencies(count, equilibrium),
                  stop_time=stop_time, **options)
    table.units.update({"f%d" % (k + 1): "Hz" for k in range(count)})
    return table
