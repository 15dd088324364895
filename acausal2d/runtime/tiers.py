"""Tiered execution (issue 30): the first run of a model structure does not
wait for the C compiler.

``ACAUSAL2D_NATIVE`` (and ``acausal2d simulate --native``) chooses:

- ``auto`` (the default): a library that is not in the cache is compiled by
  a background worker (``python -m acausal2d.runtime.background``, a separate
  process at lower priority, one build at a time per library: a lock per
  key), which publishes it into the cache and ends; the run goes on with
  the Python path and switches to the library when it appears
  (:class:`Tiering`); later runs, in this process or another, use it.  A run
  long enough that waiting for the compile pays waits for it (the choice
  and its reason are in the run's ``native`` notes);
- ``now`` (or ``1``): compile first, in this process (before issue 30);
- ``off`` (or ``0``): the Python path only.

A recipe (:class:`~acausal2d.runtime.codegen.Recipe`) says what C a library is generated from - the
CasADi functions, serialized so that the worker rebuilds them - so that the
code generator's time is spent in the worker too.  A background compile
that fails leaves a marker beside the library; later runs say so once and
keep the Python path (``acausal2d cache clear`` removes it).
"""
import os
import time

from . import cbuild, cstore
from .background import failure_path, launch, pending, queue, wait  # noqa: F401 - the worker side

ENV = "ACAUSAL2D_NATIVE"
MODES = ("auto", "now", "off")
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
    ``$ACAUSAL2D_NATIVE`` (see the module docstring; unset: auto)."""
    value = (_chosen[0] or os.environ.get(ENV, "auto")).strip().lower()
    if value in ("0", "off", "no", "false"):
        return "off"
    if value in ("now", "1", "on", "yes", "true"):
        return "now"
    return "auto"


def _failed_before(key, name):
    """The text of the failure marker of ``key``, or None."""
    try:
        with open(failure_path(key, name), encoding="utf-8", errors="replace") as fh:
            return fh.read().strip() or "no message"
    except OSError:
        return None


def obtain(key, recipe, loader):
    """``loader(path)`` of the library of ``key`` made by ``recipe``, or
    None: off, a compile in the background (auto), a compile that failed
    before, or a build or load that fails (``now``)."""
    m = mode()
    if m == "off":
        return None
    path = cbuild.lookup(key, recipe.name)
    if path is None and m == "auto":
        failed = _failed_before(key, recipe.name)
        if failed is not None:
            cstore.notice("the background compile of native code for %s failed (%s; the "
                          "messages are in %s*.failed, 'acausal2d cache clear' retries it); "
                          "this run uses the Python path"
                          % (_label[0], failed.splitlines()[0][:200],
                             os.path.join(cstore.folder(), "")))
        else:
            queue(key, recipe, _label[0])
        return None
    t0 = time.perf_counter()
    if path is None and cbuild.find_compiler() is not None:
        cstore.notice("compiling native code for %s before the run (native mode 'now')"
                      % _label[0])
    try:
        return cbuild.load(key, recipe.make, recipe.name, loader)
    except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError, RuntimeError):
        return None
    finally:
        if path is None:
            _spent[0] += time.perf_counter() - t0


def spent():
    """Seconds this process spent compiling native code in the foreground."""
    return _spent[0]


