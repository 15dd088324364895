"""Checks of a run's settings against the model before anything is
allocated or integrated (used by :class:`acausal2d.compiled.CompiledModel`,
the FMU export and the live page): ``atol`` per unknown, the result's size,
output times the clock can tell apart, and the model's ``experiment``."""
from __future__ import annotations

from typing import TYPE_CHECKING, Sequence

import numpy as np
from numpy.typing import NDArray

from .errors import Acausal2dError, ModelDefinitionError
from .options import CHECKS, RunOptionError, number
from .runtime.simulation import time_resolution

if TYPE_CHECKING:
    from .language.dsl import Component


def _check_atol(atol: float | tuple[float, ...] | None, names: Sequence[str]) -> None:
    """atol of one number per unknown has as many values as the model has
    unknowns (``names``, in that order)."""
    if isinstance(atol, tuple) and len(atol) != len(names):
        raise RunOptionError("atol", "has %d values; give one number, or one per unknown "
                             "(%d: %s)" % (len(atol), len(names), ", ".join(list(names)[:6])
                                            + (", ..." if len(names) > 6 else "")))


def _check_size(intervals: int, columns: int) -> None:
    """Refuse a result too large for memory (:data:`MAX_RESULT_BYTES`)."""
    size = 8.0 * (intervals + 1) * (columns + 1)
    if size > MAX_RESULT_BYTES:
        raise RunOptionError("intervals", "too many: %d output intervals of %d signals would "
                             "take %.3g GB of memory (at most %.3g GB); ask for fewer intervals"
                             % (intervals, columns, size / 1e9, MAX_RESULT_BYTES / 1e9))


def _check_clock(times: NDArray[np.float64]) -> None:
    """Refuse output times the run cannot tell apart: when their mean spacing
    is below the run's time resolution the clock would not advance, and the
    run would write one row and call it done.  Single pairs closer together
    inside a longer grid (an event time beside a grid point) are fine: the
    run passes both."""
    spacing = float(times[-1] - times[0]) / (len(times) - 1)
    res = time_resolution(times[-1])
    if spacing <= res:
        raise Acausal2dError(
            "the run cannot advance the clock: its output times lie %.3g s apart on average "
            "(stop time %.6g s), below the integrator's time resolution of %.3g s at that "
            "time; give a later stop_time or fewer intervals" % (spacing, times[-1], res))


MAX_RESULT_BYTES = 4e9
"""Largest result (output points times columns, 8 bytes each) a run makes."""

_EXPERIMENT_KEYS = ("stop_time", "rtol", "intervals")


def _experiment(model: Component) -> dict[str, float]:
    """The model's ``experiment`` settings, checked."""
    exp = getattr(model, "experiment", None) or {}
    if not isinstance(exp, dict):
        raise ModelDefinitionError("%s: experiment must be a dict like {'stop_time': 2.0}, got %r"
                                   % (type(model).__name__, exp))
    unknown = sorted(set(exp) - set(_EXPERIMENT_KEYS))
    if unknown:
        raise ModelDefinitionError("%s: experiment has unknown settings %s; known: %s"
                                   % (type(model).__name__, ", ".join(map(repr, unknown)),
                                      ", ".join(_EXPERIMENT_KEYS)))
    for key, value in exp.items():
        number("%s: experiment['%s']" % (type(model).__name__, key), value)
        try:
            CHECKS[key](value)
        except RunOptionError as exc:
            raise ModelDefinitionError("%s: experiment['%s']: %s"
                                       % (type(model).__name__, key, exc)) from None
    return dict(exp)
