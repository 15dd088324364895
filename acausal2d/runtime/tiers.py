"""When a model's native libraries are used: three rules, no estimates.

The engine (``RunOptions(native=...)``, ``acausal2d simulate --native``,
else ``$ACAUSAL2D_NATIVE``) is one of :data:`MODES`:

- ``auto`` (the default): a library in the cache is used (the native
  engine); one that is not is queued, the run is native on the driver on
  CasADi's C API (:mod:`~acausal2d.runtime.capi`: the formulation's own
  CasADi functions evaluated in C, no compiler needed; the Python path
  where that driver is not here), and after the run a detached worker
  (:mod:`~acausal2d.runtime.background`, a separate process at the lowest
  priority) compiles what was queued and publishes it into the cache,
  where later runs, in this process or another, find it.  Nothing of the
  model is compiled or waited for during a run, and no wall-clock
  estimate decides anything;
- ``now`` (or ``1``): the compiled tier: a missing library is compiled
  first, in this process (the C API driver where that fails);
- ``off`` (or ``0``): the Python path only.

A recipe (:class:`~acausal2d.runtime.codegen.Recipe`) says what C a library
is generated from - the CasADi functions, serialized so that the worker
rebuilds them - so that the code generator's time is spent in the worker
too.  A background compile that fails leaves a marker beside the library;
later runs say so once and keep the Python path (``acausal2d cache clear``
removes it).
"""
import os
import time

from . import cbuild, cstore
from ..errors import Acausal2dError
from .notices import WITHOUT_LIBRARY, notice
from .background import failure_path, launch, pending, queue, wait  # noqa: F401 - the worker side

ENV = "ACAUSAL2D_NATIVE"
MODES = ("auto", "now", "off")
_spent = [0.0]          # seconds this process spent compiling native code in the foreground


def mode(chosen=None):
    """``auto``, ``now`` or ``off``: ``chosen`` (a run's
    ``RunOptions.native``), else ``$ACAUSAL2D_NATIVE`` (see the module
    docstring; unset: auto); :class:`NativeModeError` naming the modes for
    another value."""
    value = (chosen or os.environ.get(ENV, "auto")).strip().lower()
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


def obtain(key, recipe, loader, chosen=None, label=None):
    """``loader(path)`` of the library of ``key`` made by ``recipe``, or
    None: off; auto and not in the cache (queued for the compile after the
    run, or said once where it failed before); a build or load that fails.
    ``chosen``: the run's engine (:func:`mode`); ``label``: the model, for
    the notices."""
    m = mode(chosen)
    if m == "off":
        return None
    path = cbuild.lookup(key, recipe.name)
    if path is None and m == "auto":
        _later(key, recipe, label or "this model")
        return None
    if path is None and cbuild.find_compiler() is not None:
        notice("compiling native code for %s before the run (native mode 'now')"
               % (label or "this model"), first_run=True)
    t0 = time.perf_counter()
    try:
        return cbuild.load(key, recipe.make, recipe.name, loader)
    except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError, RuntimeError) as exc:
        why = str(exc).strip().splitlines()[0][:200] if str(exc).strip() else type(exc).__name__
        notice("the native code %s for %s could not be built or loaded (%s); %s"
               % (recipe.name, label or "this model", why, WITHOUT_LIBRARY))
        return None
    finally:
        _spent[0] += time.perf_counter() - t0 if path is None else 0.0


def _later(key, recipe, label):
    """Mode auto, no library: queue its compile after the run, or say
    (once) that an earlier compile failed."""
    failed = _failed_before(key, recipe.name)
    if failed is None:
        queue(key, recipe, label)
        return
    notice("the compile of native code for %s failed (%s; the messages are in "
           "%s*.failed, 'acausal2d cache clear' retries it); %s"
           % (label, failed.splitlines()[0][:200], os.path.join(cstore.folder(), ""),
              WITHOUT_LIBRARY))


def spent():
    """Seconds this process spent compiling native code in the foreground."""
    return _spent[0]
