"""Tiered execution: the first run of a model structure does not
wait for the C compiler.

``ACAUSAL2D_NATIVE`` (and ``acausal2d simulate --native``) chooses:

- ``auto`` (the default): a library that is not in the cache is compiled by
  a background worker (:data:`~acausal2d.runtime.background.BOOT`, a separate
  process at lower priority, one build at a time per library: a lock per
  key), which publishes it into the cache and ends; the run goes on with
  the Python path and switches to the library when it appears
  (:class:`Tiering`); later runs, in this process or another, use it.  A
  library expected to compile in less than :data:`FOREGROUND_BELOW` s is
  compiled first (a small model's Python path costs more).  A run
  long enough that waiting for the compile pays waits for it (the choice
  and its reason are in the run's ``native`` notes);
- ``now`` (or ``1``): compile first, in this process;
- ``off`` (or ``0``): the Python path only.

A recipe (:class:`~acausal2d.runtime.codegen.Recipe`) says what C a library is generated from - the
CasADi functions, serialized so that the worker rebuilds them - so that the
code generator's time is spent in the worker too.  A background compile
that fails leaves a marker beside the library; later runs say so once and
keep the Python path (``acausal2d cache clear`` removes it).
"""
import os
import threading
import time

from . import cbuild, cstore
from ..errors import Acausal2dError
from .background import (compile_seconds, failure_path, launch, pending, queue,  # noqa: F401
                         wait)  # the worker side

ENV = "ACAUSAL2D_NATIVE"
MODES = ("auto", "now", "off")
FOREGROUND_BELOW = 0.3
"""Seconds of expected compile (:func:`~acausal2d.runtime.background.
compile_seconds`) below which mode auto
compiles first, in the process: the Python path costs a small model more
than its compile (``acausal2d simulate models/piston_engine.py`` on an
empty cache, CPU seconds of the process and its compilers on a loaded
machine: Python path 6.87, compile first 4.56, full cache 3.04)."""
_notes: list = []        # why libraries were compiled first (the next run log takes them)
_spent = [0.0]          # seconds this process spent compiling native code in the foreground
_label = ["this model"]  # the model of the current run (its notices name it)


def set_label(label):
    """Name the model whose libraries are asked for next (notices)."""
    _label[0] = label or "this model"


_chosen = [None]         # the mode chosen by a command's --native, over the environment


def choose(value):
    """Use mode ``value`` (one of :data:`MODES`, or None: the environment's)
    from now on; returns the previous choice (to restore it)."""
    if value is not None and value not in MODES:
        raise ValueError("native mode must be one of %s, got %r" % (", ".join(MODES), value))
    previous, _chosen[0] = _chosen[0], value
    return previous


def mode():
    """``auto``, ``now`` or ``off``: the mode chosen (:func:`choose`), else
    ``$ACAUSAL2D_NATIVE`` (see the module docstring; unset: auto);
    :class:`NativeModeError` naming the modes for another value."""
    value = (_chosen[0] or os.environ.get(ENV, "auto")).strip().lower()
    if value in ("0", "off", "no", "false"):
        return "off"
    if value in ("now", "1", "on", "yes", "true"):
        return "now"
    if value in ("auto", ""):
        return "auto"
    raise NativeModeError("$%s=%r is not a native mode; give one of %s (or 1/on for now, "
                          "0/off for off), or unset it for auto" % (ENV, os.environ.get(ENV),
                                                                   ", ".join(MODES)))


class NativeModeError(Acausal2dError):
    """``$ACAUSAL2D_NATIVE`` names no mode (:data:`MODES`)."""


def _failed_before(key, name):
    """The text of the failure marker of ``key``, or None."""
    try:
        with open(failure_path(key, name), encoding="utf-8", errors="replace") as fh:
            return fh.read().strip() or "no message"
    except OSError:
        return None


def _first(key, recipe):
    """True where mode auto compiles the missing library of ``recipe``
    first, in this process (:func:`_small`, no failure before)."""
    return _small(recipe) and _failed_before(key, recipe.name) is None


def obtain(key, recipe, loader):
    """``loader(path)`` of the library of ``key`` made by ``recipe``, or
    None: off, a compile in the background (auto), a compile that failed
    before (auto), or a build or load that fails."""
    m = mode()
    if m == "off":
        return None
    waited = _join(key)
    path = cbuild.lookup(key, recipe.name)
    first = path is None and m == "auto" and _first(key, recipe)
    if path is None and m == "auto" and not first:
        _later(key, recipe)
        return None
    if first:
        _notes.append("compile first: %s is small (about %.2g s to compile)"
                      % (recipe.name, compile_seconds(recipe)))
    elif path is None and cbuild.find_compiler() is not None:
        cstore.notice("compiling native code for %s before the run (native mode 'now')"
                      % _label[0])
    t0 = time.perf_counter()
    try:
        return cbuild.load(key, recipe.make, recipe.name, loader)
    except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError, RuntimeError) as exc:
        _failed_now(key, recipe, exc, first)
        return None
    finally:
        _spent[0] += waited + (time.perf_counter() - t0 if path is None else 0.0)


def _failed_now(key, recipe, exc, first):
    """Say in one line that the native code of ``recipe`` is not used and
    why (a compiler missing or killed, a full disk, a library the loader
    refused twice); a compile made first leaves its failure marker, as a
    failed background compile does (a marker that cannot be written, on a
    full disk, is only said)."""
    why = str(exc).strip().splitlines()[0][:200] if str(exc).strip() else type(exc).__name__
    cstore.notice("the native code %s for %s could not be built or loaded (%s); this run "
                  "uses the Python path" % (recipe.name, _label[0], why))
    if first:
        try:
            cstore.write_atomic(failure_path(key, recipe.name),
                                ("%s: %s" % (type(exc).__name__, exc)).encode("utf-8"))
        except OSError:
            pass


_ahead: dict = {}       # key -> the thread compiling its library ahead (:func:`ahead`)


def ahead(key, recipe):
    """Start compiling the library of ``key`` now, beside the foreground
    compile that comes next, where :func:`obtain` would compile it first
    (mode now, or auto and small): the C projector's library is so compiled
    while the model's library is (two compilers on two cores; piston
    engine's first run, medians of 5 alternating: compile 0.35 -> 0.22 s,
    run 0.45 -> 0.33 s).
    CasADi's code generator runs here, in this thread; a thread runs only
    the compiler (and publishes the library); :func:`obtain` of ``key``
    waits for it.  A build that fails there is made again, and reported,
    by :func:`obtain`."""
    m = mode()
    if m == "off" or key in _ahead or cbuild.find_compiler() is None or \
            cbuild.lookup(key, recipe.name) is not None:
        return
    if m == "auto":
        if not _first(key, recipe):
            return
        _notes.append("compile first: %s is small (about %.2g s to compile), beside the "
                      "next library" % (recipe.name, compile_seconds(recipe)))
    recipe.code()
    thread = threading.Thread(target=_build_ahead, args=(key, recipe), daemon=True,
                              name="acausal2d-compile-%s" % recipe.name)
    _ahead[key] = thread
    thread.start()


def _build_ahead(key, recipe):
    try:
        cbuild.build_indexed(key, recipe.make, recipe.name)
    except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError):
        pass                    # obtain() builds it again and reports the failure


def _join(key):
    """Wait for the compile of ``key`` started by :func:`ahead`; the seconds waited."""
    thread = _ahead.pop(key, None)
    if thread is None:
        return 0.0
    t0 = time.perf_counter()
    thread.join()
    return time.perf_counter() - t0


def _later(key, recipe):
    """Mode auto, no library: queue its background compile, or say (once)
    that an earlier compile failed."""
    failed = _failed_before(key, recipe.name)
    if failed is None:
        queue(key, recipe, _label[0])
        return
    cstore.notice("the compile of native code for %s failed (%s; the messages are in "
                  "%s*.failed, 'acausal2d cache clear' retries it); this run uses the "
                  "Python path" % (_label[0], failed.splitlines()[0][:200],
                                   os.path.join(cstore.folder(), "")))


def _small(recipe):
    """True where compiling ``recipe`` first costs less than the Python
    path would (:data:`FOREGROUND_BELOW`) and a compiler is there.  Only
    SX functions are judged by their instructions: a map counts only its
    own few (the chain of 20 links' row maps, 60 instructions, were 1 MB of C)."""
    plain = all(fn.is_a("SXFunction") for _, fns in recipe.parts for fn in fns)
    return plain and compile_seconds(recipe) < FOREGROUND_BELOW and \
        cbuild.find_compiler() is not None


def take_notes():
    """The notes on libraries compiled first since the last call (a run's log)."""
    notes, _notes[:] = list(_notes), []
    return notes


def spent():
    """Seconds this process spent compiling native code in the foreground."""
    return _spent[0]


