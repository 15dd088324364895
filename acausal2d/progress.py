"""Progress of runs and sweeps on standard error with tqdm: shown only when
standard error is a terminal (tqdm's ``disable=None``), never as ``\\r``
lines in a log file, and only for work that takes longer than
:data:`DELAY` seconds.  ``progress=False`` (``RunOptions``) and ``--quiet``
(the command line) turn it off."""
from __future__ import annotations

import contextlib
import sys
from collections.abc import Callable, Iterator
from typing import Any

__all__ = ["DELAY", "time_progress", "count_progress"]

DELAY = 1.0
"""Seconds of wall time before a bar appears (a short run shows none)."""


def on_terminal() -> bool:
    """True where standard error is a terminal, the one place a bar is
    drawn (tqdm's ``disable=None``).  Elsewhere no bar is made: tqdm is not
    imported (its import, with ``importlib.metadata``, was about 25 ms of
    every run) and a run gets no progress callback at all."""
    isatty = getattr(sys.stderr, "isatty", None)
    try:
        return bool(isatty is not None and isatty())
    except (ValueError, OSError):        # a closed or detached stream
        return False


def _bar(total: float, unit: str, **kw: Any) -> Any:
    from tqdm import tqdm
    return tqdm(total=total, unit=unit, file=sys.stderr, delay=DELAY, disable=None,
                leave=False, **kw)


@contextlib.contextmanager
def time_progress(progress: bool | Callable[[float, float], Any], t0: float,
                  t_end: float) -> Iterator[Callable[[float, float], Any] | None]:
    """The ``progress(t, t_end)`` callback of a run from ``t0`` to ``t_end``:
    ``progress`` itself if it is a function, a tqdm bar over simulated time
    if it is True and standard error is a terminal (:func:`on_terminal`),
    else None (the run then calls nothing per step or output row)."""
    if callable(progress) and not isinstance(progress, bool):
        yield progress
        return
    if not progress or not on_terminal():
        yield None
        return
    bar = _bar(t_end - t0, "s", bar_format="{l_bar}{bar}| t = {n:.4g} / {total:.4g} s "
               "[{elapsed}<{remaining}]")

    def advance(t: float, _end: float) -> None:
        bar.update(min(max(t - t0, 0.0), bar.total) - bar.n)

    try:
        yield advance
    finally:
        bar.close()


@contextlib.contextmanager
def count_progress(total: int, unit: str, enabled: bool = True) -> Iterator[Callable[[bool], None]]:
    """``done(failed)`` counts one finished item (a sweep's point) on a tqdm
    bar of ``total`` items, with the failed ones in its postfix; a no-op
    when ``enabled`` is False (or standard error is not a terminal)."""
    if not enabled or not on_terminal():
        yield lambda failed: None
        return
    bar = _bar(total, unit)
    failures = [0]

    def done(failed: bool) -> None:
        if failed:
            failures[0] += 1
            bar.set_postfix_str("%d failed" % failures[0], refresh=False)
        bar.update(1)

    try:
        yield done
    finally:
        bar.close()
