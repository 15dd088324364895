"""Thread limits scoped to our own calls (threadpoolctl), never set for the
user's process: IDA's small dense systems and the Newton steps run fastest
on one BLAS/OpenMP thread, and a sweep's worker processes share the cores.
``import acausal2d`` sets nothing; :func:`our_threads` limits the native
thread pools while a run is inside it and gives the user's limits back on
the way out.

The :class:`threadpoolctl.ThreadpoolController` (which inspects the loaded
libraries: 5-50 ms) is made once per process, lazily at the first run;
entering and leaving a limit then costs well under a millisecond per run
(``benchmarks/bench_threads.py`` measures both)."""
from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator
from typing import Any

__all__ = ["LIMIT", "controller", "libraries_loaded", "our_threads"]

LIMIT = 1
"""Threads of each native pool (BLAS, OpenMP) during our runs."""

_CONTROLLER: list[Any] = []         # [(the modules it saw, ThreadpoolController)]
_ACTIVE: list[Any] = []             # [(limit, ExitStack)] of the runs inside our_threads
WATCHED = ("scipy", "sksundae")
"""Packages whose modules load native thread pools (scipy's and
scikit-sundae's OpenBLAS, libgomp) as they are imported: a controller made
before more of their modules were imported is made anew (nothing of them is
imported here: a native run needs none)."""


def _seen() -> int:
    """How many modules of :data:`WATCHED` are loaded (about 50 us)."""
    return sum(1 for m in list(sys.modules) if m.startswith(WATCHED))


def controller() -> Any:
    """The process's ThreadpoolController: made at the first call and again
    only when a module of :data:`WATCHED` was imported since."""
    if "scipy" in sys.modules:         # its BLAS loads with scipy.linalg, often inside a run
        import scipy.linalg  # noqa: F401
        import scipy.sparse.linalg  # noqa: F401
    seen = _seen()
    if not _CONTROLLER or _CONTROLLER[0][0] != seen:
        from threadpoolctl import ThreadpoolController
        _CONTROLLER[:] = [(seen, ThreadpoolController())]
    return _CONTROLLER[0][1]


def libraries_loaded() -> None:
    """Called where a run imports a module of :data:`WATCHED`: the pools it
    brought are limited too, for the rest of the run."""
    if _CONTROLLER:
        _CONTROLLER[:] = []          # libraries were loaded: the controller is made anew
    if _ACTIVE:
        limit, stack = _ACTIVE[-1]
        stack.enter_context(controller().limit(limits=limit))


@contextlib.contextmanager
def our_threads(limit: int = LIMIT) -> Iterator[None]:
    """Limit the native thread pools to ``limit`` threads inside the block
    only; the limits the user had are restored on exit."""
    with contextlib.ExitStack() as stack:
        _ACTIVE.append((limit, stack))
        try:
            stack.enter_context(controller().limit(limits=limit))
            yield
        finally:
            _ACTIVE.pop()
