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
from collections.abc import Iterator
from typing import Any

__all__ = ["LIMIT", "controller", "our_threads"]

LIMIT = 1
"""Threads of each native pool (BLAS, OpenMP) during our runs."""

_CONTROLLER: list[Any] = []


def controller() -> Any:
    """The process's ThreadpoolController, made at the first call (it
    limits the libraries loaded by then: numpy's and scipy's BLAS)."""
    if not _CONTROLLER:
        import scipy.linalg  # noqa: F401  (loads scipy's BLAS, which the runs use, before the
        import scipy.sparse.linalg  # noqa: F401  controller lists the loaded libraries)
        from threadpoolctl import ThreadpoolController
        _CONTROLLER.append(ThreadpoolController())
    return _CONTROLLER[0]


@contextlib.contextmanager
def our_threads(limit: int = LIMIT) -> Iterator[None]:
    """Limit the native thread pools to ``limit`` threads inside the block
    only; the limits the user had are restored on exit."""
    with controller().limit(limits=limit):
        yield
