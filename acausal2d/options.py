"""The settings every run takes, in one place: :class:`RunOptions` (stop
time, tolerances, output times, budgets, progress), its defaults
(:data:`DEFAULTS`) and its one validation.  The API (``simulate``,
``CompiledModel.simulate``, ``sweep``, ``study``, ``fit``, ``optimize``,
``modes``), the command line (:func:`acausal2d.cli.args.add_run_options`)
and the FMU export all build a :class:`RunOptions`, so that a bad value
gives the same error, naming the option, wherever it was given."""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Union

import numpy as np

from .errors import Acausal2dError

__all__ = ["RunOptions", "DEFAULTS", "STEPS_PER_OUTPUT", "RunOptionError", "number"]

DEFAULTS: dict[str, float] = {"stop_time": 1.0, "rtol": 1e-6, "intervals": 500,
                              "start_time": 0.0, "max_steps": 1_000_000}
"""Defaults of the settings a model's ``experiment`` does not give: 1 s,
rtol 1e-6, 500 output intervals from t = 0, a budget of 1,000,000 steps."""

STEPS_PER_OUTPUT = 500
"""IDA's ``max_num_steps``: the integrator's steps towards one output time
before it hands the run back to the runtime (which then looks at what went
wrong, or goes on); the run's own budget is ``max_steps``."""

Progress = Union[bool, Callable[[float, float], Any]]
"""``True``: a bar on standard error when it is a terminal; ``False``: none;
a callable ``progress(t, t_end)``: called as the run advances."""

Atol = Union[float, Sequence[float], np.ndarray, None]


class RunOptionError(Acausal2dError):
    """A run option with a value it cannot take; ``option`` names it (and
    ``flag``, its command-line option, where it was given there)."""

    def __init__(self, option: str, message: str, flag: str | None = None) -> None:
        text = "%s %s" % (option, message)
        super().__init__(text if flag is None else "%s: %s" % (flag, text))
        self.option, self.flag, self.message = option, flag, message


def number(name: str, value: object) -> float:
    """``value`` as a float if it is a finite number, else the project's
    error naming the setting ``name``."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise RunOptionError(name, "must be a number, got %r" % (value,))
    if not math.isfinite(float(value)):
        raise RunOptionError(name, "must be finite, got %r" % (value,))
    return float(value)


def _positive(name: str, value: object) -> float:
    v = number(name, value)
    if not v > 0:
        raise RunOptionError(name, "must be larger than 0, got %r" % (value,))
    return v


def _rtol(value: object) -> float:
    v = number("rtol", value)
    if not 0 < v < 0.1:
        raise RunOptionError("rtol", "must be between 0 and 0.1 (a relative tolerance, e.g. "
                             "1e-6), got %r" % (value,))
    return v


def _whole(name: str, value: object) -> int:
    v = number(name, value)
    if v < 1 or int(v) != v:
        raise RunOptionError(name, "must be a whole number of at least 1, got %r" % (value,))
    return int(v)


def _atol(value: object) -> float | tuple[float, ...]:
    bad = "must be a positive number or one positive number per unknown, got %r" % (value,)
    if isinstance(value, (bool, str, bytes, Mapping)):
        raise RunOptionError("atol", bad)
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise RunOptionError("atol", bad) from None
    if a.ndim > 1 or (a.ndim == 1 and a.size == 0) or not np.all(np.isfinite(a)) \
            or not np.all(a > 0):
        raise RunOptionError("atol", bad)
    return float(a) if a.ndim == 0 else tuple(float(x) for x in a)


def _output_times(value: object) -> tuple[float, ...]:
    def bad() -> RunOptionError:      # the message made only for a refusal (a long array's repr)
        return RunOptionError("output_times", "must be at least two finite, increasing times "
                              "(a list of numbers), got %r" % (value,))
    if isinstance(value, (str, bytes, Mapping)):
        raise bad()
    try:
        t = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise bad() from None
    if t.ndim != 1 or len(t) < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
        raise bad()
    return tuple(t.tolist())


def _progress(value: object) -> Progress:
    if isinstance(value, bool) or callable(value):
        return value
    raise RunOptionError("progress", "must be True (a bar on a terminal), False or a function "
                         "progress(t, t_end), got %r" % (value,))


NATIVE_MODES = ("auto", "now", "off")


def _native(value: object) -> str:
    if isinstance(value, str) and value.strip().lower() in NATIVE_MODES:
        return value.strip().lower()
    raise RunOptionError("native", "must be one of %s (or None: $ACAUSAL2D_NATIVE), got %r"
                         % (", ".join(NATIVE_MODES), value))


CHECKS: dict[str, Callable[[Any], Any]] = {
    "stop_time": lambda v: number("stop_time", v),
    "rtol": _rtol,
    "atol": _atol,
    "intervals": lambda v: _whole("intervals", v),
    "start_time": lambda v: number("start_time", v),
    "output_times": _output_times,
    "max_steps": lambda v: _whole("max_steps", v),
    "max_wall_time": lambda v: _positive("max_wall_time", v),
    "progress": _progress,
    "native": _native,
}
"""The one check of each option: value -> the option's normal form, or a
:class:`RunOptionError` naming it (the command line's types call these)."""


@dataclasses.dataclass(frozen=True)
class RunOptions:
    """The settings of a run, checked when made (a bad value is a
    :class:`RunOptionError` naming the option and what it takes).

    stop_time: end time in s (default: the model's ``experiment`` or 1 s);
    rtol: relative tolerance (default: ``experiment`` or 1e-6); atol:
    absolute tolerance, one number or one per unknown (default: rtol times
    each unknown's nominal); intervals: output intervals (default:
    ``experiment`` or 500) from ``start_time``; output_times: the output
    times instead of stop_time and intervals (which, if also given, must
    agree with them); max_steps, max_wall_time:
    budgets of integrator steps and wall-clock seconds after which a run
    stops early with its data so far; progress: ``True`` (a bar on standard
    error when it is a terminal), ``False`` or ``progress(t, t_end)``;
    native: the engine - ``auto`` (native code where its library is in the
    cache, else the Python path and a compile after the run), ``now`` (the
    compiled tier: compile first), ``off`` (the Python path); None:
    ``$ACAUSAL2D_NATIVE``, else auto.  ``None`` leaves a setting to the model and :data:`DEFAULTS`.
    """

    stop_time: float | None = None
    rtol: float | None = None
    atol: float | tuple[float, ...] | None = None
    intervals: int | None = None
    start_time: float = 0.0
    output_times: tuple[float, ...] | None = None
    max_steps: int = int(DEFAULTS["max_steps"])
    max_wall_time: float | None = None
    progress: Progress = True
    native: str | None = None

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if value is not None:
                object.__setattr__(self, f.name, CHECKS[f.name](value))
        if self.output_times is not None:
            self._check_grid(self.output_times)
        if self.stop_time is not None and not self.stop_time > self.start_time:
            raise RunOptionError("stop_time", "(%g s) must be larger than start_time (%g s)"
                                 % (self.stop_time, self.start_time))

    def _check_grid(self, times: tuple[float, ...]) -> None:
        """stop_time and intervals given beside output_times must agree with
        them (the last time, the number of intervals)."""
        end = times[-1]
        if self.stop_time is not None and \
                abs(self.stop_time - end) > 8 * np.finfo(float).eps * max(1.0, abs(end)):
            raise RunOptionError("stop_time", "(%g s) differs from the last of output_times "
                                 "(%g s); give output_times alone" % (self.stop_time, end))
        if self.intervals is not None and self.intervals != len(times) - 1:
            raise RunOptionError("intervals", "(%d) differs from the %d intervals of "
                                 "output_times; give output_times alone"
                                 % (self.intervals, len(times) - 1))

    def replace(self, **changes: Any) -> RunOptions:
        """A copy with ``changes`` (checked alike)."""
        return dataclasses.replace(self, **changes)

    def resolved(self, experiment: Mapping[str, float] | None = None) -> RunOptions:
        """stop_time, rtol and intervals filled in from the model's
        ``experiment`` and then :data:`DEFAULTS` (output_times, when given,
        replaces stop_time and intervals)."""
        exp = dict(experiment or {})
        fill: dict[str, float | None] = {
            k: exp.get(k, DEFAULTS[k]) for k in ("stop_time", "rtol", "intervals")
            if getattr(self, k) is None}
        if self.output_times is not None:            # the grid says stop_time and intervals
            fill = {"stop_time": None, "intervals": None, "rtol": fill.get("rtol", self.rtol)}
        return self.replace(**fill) if fill else self

    def times(self) -> np.ndarray:
        """The output times of resolved options."""
        if self.output_times is not None:
            return np.asarray(self.output_times)
        if self.stop_time is None or self.intervals is None:
            raise RunOptionError("stop_time", "is not resolved: call resolved(experiment) first")
        return np.linspace(self.start_time, self.stop_time, self.intervals + 1)

    @property
    def end(self) -> float | None:
        """The last output time, if known."""
        return self.output_times[-1] if self.output_times is not None else self.stop_time

    @classmethod
    def of(cls, options: RunOptions | None, function: str, **keywords: Any) -> RunOptions:
        """The options of a call that takes ``options=`` and the same
        settings as keywords (``None``: not given): built from the keywords,
        or ``options`` itself; both at once is an error naming both."""
        given = {k: v for k, v in keywords.items() if v is not None}
        if options is None:
            return cls(**given)
        if not isinstance(options, RunOptions):
            raise RunOptionError("options", "of %s must be a RunOptions, got %r"
                                 % (function, options))
        if given:
            raise RunOptionError("options", "and the keyword%s %s are both given to %s; put "
                                 "%s into the RunOptions (options.replace(...)) or leave "
                                 "options out" % ("s" if len(given) > 1 else "",
                                                  ", ".join(sorted(given)), function,
                                                  ", ".join(sorted(given))))
        return options


OPTION_NAMES = tuple(f.name for f in dataclasses.fields(RunOptions))
"""The keyword names of the run options."""
