"""scikit-sundae, imported without ``scipy.optimize``.

scikit-sundae's IDA module imports ``group_columns`` from
``scipy.optimize._numdiff`` when it is loaded; that import runs
``scipy.optimize/__init__`` (about 0.15-0.2 s, most of a run of a small
model).  ``group_columns`` is only called when IDA is given a sparsity
pattern *and* no Jacobian (finite-difference colouring), which acausal2d
never does.  So for the duration of the one import a stand-in module
``scipy.optimize._numdiff`` is placed in ``sys.modules`` whose
``group_columns`` imports the real one on first call; the stand-in is
removed afterwards, so a later ``import scipy.optimize`` loads the real
modules as usual.  Import ``sksundae`` from here (``from .sundae import
sksundae``), never directly, so the first import is this one.

Not guarded against another thread importing ``scipy.optimize`` during
these ~0.1 s (it would find the stand-in): holding the interpreter's import
lock across the import deadlocks against such a thread's module locks.  The
first import happens when the runtime is first used, in practice on the
main thread before any worker threads.
"""
import sys
import types

from ..threads import libraries_loaded

_NUMDIFF = "scipy.optimize._numdiff"


def _group_columns(*args, **kwargs):
    """scipy's ``group_columns``, imported when first called."""
    from scipy.optimize._numdiff import group_columns
    return group_columns(*args, **kwargs)


def _import_sksundae():
    """Import scikit-sundae with the stand-in ``scipy.optimize._numdiff``
    in place (unless scikit-sundae or the real module is loaded already)."""
    if "sksundae" in sys.modules or _NUMDIFF in sys.modules:
        import sksundae
        return sksundae
    stand_in = types.ModuleType(_NUMDIFF)
    stand_in.group_columns = _group_columns
    sys.modules[_NUMDIFF] = stand_in
    try:
        import sksundae
    finally:
        if sys.modules.get(_NUMDIFF) is stand_in:
            del sys.modules[_NUMDIFF]
    return sksundae


sksundae = _import_sksundae()
libraries_loaded()          # its OpenBLAS and libgomp limited too inside a run
