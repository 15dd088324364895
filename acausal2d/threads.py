"""Thread limits scoped to our own calls (threadpoolctl), never set for the
user's process: IDA's small dense systems and the Newton steps run fastest
on one BLAS/OpenMP thread, and a sweep's worker processes share the cores.
``import acausal2d`` sets nothing; :func:`our_threads` limits the native
thread pools while a run is inside it and gives the user's limits back on
the way out.

The :class:`threadpoolctl.ThreadpoolController` (which inspects the loaded
libraries: 5-50 ms) is made at the first run and made anew only when a
library that carries a thread pool (a file name threadpoolctl knows:
OpenBLAS, MKL, BLIS, FlexiBLAS, an OpenMP runtime) was loaded since: the
loaded libraries are read with the C library's ``dl_iterate_phdr``, whose
load and unload counters answer "nothing was loaded" in about 3 us; their
names are read (about 0.1 ms) only when the counters moved.  Entering and
leaving a limit costs well under a millisecond per run
(``benchmarks/bench_threads.py`` measures both)."""
from __future__ import annotations

import contextlib
import ctypes
import os
import sys
from collections.abc import Iterator
from typing import Any

__all__ = ["LIMIT", "controller", "libraries_loaded", "our_threads", "pool_libraries"]

LIMIT = 1
"""Threads of each native pool (BLAS, OpenMP) during our runs."""

_CONTROLLER: list[Any] = []         # [(pool_libraries() it saw, ThreadpoolController)]
_ACTIVE: list[Any] = []             # [(limit, ExitStack)] of the runs inside our_threads
_LOADED: list[tuple[tuple[int, int], frozenset[str]]] = []   # [(counters, pools)] of the last look


class _PhdrInfo(ctypes.Structure):
    """The head of glibc's and musl's ``struct dl_phdr_info`` (dl_iterate_phdr(3))."""
    _fields_ = [("dlpi_addr", ctypes.c_size_t), ("dlpi_name", ctypes.c_char_p),
                ("dlpi_phdr", ctypes.c_void_p), ("dlpi_phnum", ctypes.c_uint16),
                ("dlpi_adds", ctypes.c_ulonglong), ("dlpi_subs", ctypes.c_ulonglong)]


_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.POINTER(_PhdrInfo), ctypes.c_size_t,
                             ctypes.c_void_p)


def _libc() -> ctypes.CDLL | None:
    """The process's C library if it has ``dl_iterate_phdr`` (Linux, BSD), else None."""
    try:
        libc = ctypes.CDLL(None)
    except (OSError, TypeError):            # Windows: no dlopen(NULL)
        return None
    return libc if hasattr(libc, "dl_iterate_phdr") else None


_LIBC = _libc()


def _counters(libc: ctypes.CDLL) -> tuple[int, int] | None:
    """(objects loaded, objects unloaded) since the process started, from the
    first entry dl_iterate_phdr gives; None where the C library has no
    counters (nothing then can be told unchanged)."""
    seen: list[tuple[int, int] | None] = [None]

    def first(info: Any, size: int, data: Any) -> int:
        if size >= ctypes.sizeof(_PhdrInfo):
            seen[0] = (int(info.contents.dlpi_adds), int(info.contents.dlpi_subs))
        return 1                            # one entry is enough
    libc.dl_iterate_phdr(_CALLBACK(first), None)
    return seen[0]


def _names(libc: ctypes.CDLL) -> list[str]:
    """Paths of every shared library loaded in the process."""
    names: list[bytes] = []

    def each(info: Any, size: int, data: Any) -> int:
        if info.contents.dlpi_name:
            names.append(info.contents.dlpi_name)
        return 0
    libc.dl_iterate_phdr(_CALLBACK(each), None)
    return [os.fsdecode(n) for n in names]


def _prefixes() -> tuple[str, ...]:
    """File-name prefixes of the libraries threadpoolctl controls (the
    ``filename_prefixes`` of its controller classes, registered ones too)."""
    from threadpoolctl import LibController
    found: set[str] = set()
    todo = list(LibController.__subclasses__())
    while todo:
        cls = todo.pop()
        found.update(getattr(cls, "filename_prefixes", ()))
        todo.extend(cls.__subclasses__())
    return tuple(sorted(found))


def pool_libraries() -> frozenset[str] | None:
    """Paths of the loaded shared libraries that carry a thread pool
    threadpoolctl controls, or None where the loaded libraries cannot be
    listed (no ``dl_iterate_phdr``: macOS, Windows)."""
    if _LIBC is None:
        return None
    counters = _counters(_LIBC)
    if counters is not None and _LOADED and _LOADED[0][0] == counters:
        return _LOADED[0][1]
    prefixes = _prefixes()
    pools = frozenset(n for n in _names(_LIBC)
                      if os.path.basename(n).lower().startswith(prefixes))
    _LOADED[:] = [(counters, pools)] if counters is not None else []
    return pools


def controller() -> Any:
    """The process's ThreadpoolController: made at the first call and again
    only when a library with a thread pool was loaded since (where the
    libraries cannot be listed: when the number of imported modules changed,
    as threadpoolctl's own cache does)."""
    if "scipy" in sys.modules:         # its BLAS loads with scipy.linalg, often inside a run
        import scipy.linalg  # noqa: F401
        import scipy.sparse.linalg  # noqa: F401
    pools = pool_libraries()
    key: Any = pools if pools is not None else len(sys.modules)
    if not _CONTROLLER or _CONTROLLER[0][0] != key:
        from threadpoolctl import ThreadpoolController
        _CONTROLLER[:] = [(key, ThreadpoolController())]
    return _CONTROLLER[0][1]


def libraries_loaded() -> None:
    """Called where a run loads native libraries (the native driver,
    scikit-sundae): the thread pools they brought, if any, are limited too,
    for the rest of the run.  Loading nothing new costs microseconds."""
    if pool_libraries() is None:
        _CONTROLLER[:] = []          # cannot tell what was loaded: the controller is made anew
    if _ACTIVE:
        made = _CONTROLLER[0][1] if _CONTROLLER else None
        current = controller()
        if current is not made:
            limit, stack = _ACTIVE[-1]
            stack.enter_context(current.limit(limits=limit))


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
