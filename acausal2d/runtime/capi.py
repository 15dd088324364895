"""The native engine before a structure's library exists: the driver on
CasADi's C API.  Until a structure's library (:mod:`~acausal2d.runtime.
native`) is in the cache, or where no compiler is found, the same IDA
driver and projector (``native_driver.c``, ``native_project.c`` with
``A2D_CAPI``) run the formulation's own CasADi functions through CasADi's C
API (``casadi_c_eval_id`` of the casadi wheel's libcasadi), pushed to it
once per formulation: 1.5-4x the compiled library's time, a fifth to a
half of the Python path's (``benchmarks/bench_capi.py``, docs/speed.md).

It is built once per machine with no library linked: at install where a
compiler is found (:func:`~acausal2d.runtime.drivers.install`, checked
against its recorded SHA-256), else on first use into the cache.  The
SUNDIALS functions (scikit-sundae's) and the C API's that it calls are
looked up by name in those libraries, each opened locally, and handed to
it (``a2d_bind``) when it is loaded: a later FMU binds its own SUNDIALS.
"""
import ctypes
import os
import tempfile
import threading
import weakref

import casadi as ca
import numpy as np

from . import cbuild, drivers, native, tiers

_loaded: dict = {}          # "lib": the driver once loaded (None: not here)
_pushing = threading.RLock()     # the driver's load, and the C API's list of functions (one
#                                  per process)


def _libcasadi():
    """The path of the libcasadi the casadi wheel ships, or None."""
    folder = os.path.dirname(ca.__file__)
    for name in sorted(os.listdir(folder)):
        if name.startswith("libcasadi.so") or name == "libcasadi.dylib":
            return os.path.join(folder, name)
    return None


def _path():
    """The driver's library: installed with the package, else built into the
    cache where a compiler is found; None where neither."""
    found = drivers.prebuilt(drivers.capi_file())
    if found is None and cbuild.find_compiler() is not None:
        found = cbuild.build({drivers.CAPI + ".c": drivers.capi_text()}, name=drivers.CAPI)
    return found


def _bind(lib, casadi_lib):
    """Hand ``lib`` the addresses of the functions it calls (its
    ``a2d_bound_names``, looked up in scikit-sundae's SUNDIALS libraries and
    ``casadi_lib``); False where one is missing."""
    libs = cbuild.sundials_libraries()[1]
    sources = [ctypes.CDLL(libs[k]) for k in native.LIBRARIES if k in libs] + [casadi_lib]
    table = ctypes.cast(ctypes.addressof(ctypes.c_char_p.in_dll(lib, "a2d_bound_names")),
                        ctypes.POINTER(ctypes.c_char_p))
    addresses = []
    while table[len(addresses)] is not None:
        name = table[len(addresses)].decode()
        fn = next((getattr(s, name) for s in sources if hasattr(s, name)), None)
        if fn is None:
            return False
        addresses.append(ctypes.cast(fn, ctypes.c_void_p).value)
    lib.a2d_bind.argtypes = [ctypes.c_void_p]
    lib.a2d_bind((ctypes.c_void_p * len(addresses))(*addresses))
    return True


def driver():
    """The driver on CasADi's C API, loaded and bound once per process; None
    where it cannot be had here (no SUNDIALS of the declared release, no
    libcasadi, not installed and no compiler, or its build failed)."""
    with _pushing:
        if "lib" not in _loaded:
            _loaded["lib"] = _load()
    return _loaded["lib"]


def _load():
    """:func:`driver` made: loaded, bound and declared, or None."""
    casadi_path = _libcasadi()
    try:
        path = _path() if native.enabled("auto") and casadi_path else None
        if path is None:
            return None
        casadi_lib, lib = ctypes.CDLL(casadi_path), ctypes.CDLL(path)
        if not _bind(lib, casadi_lib):
            return None
    except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError, AttributeError):
        return None
    casadi_lib.casadi_c_push_file.argtypes = [ctypes.c_char_p]
    lib.casadi = casadi_lib
    return native._declare(native.declare_projector(lib))


_pushed: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()   # owner -> {what: C API ids}


def _push(lib, fns):
    """Push the CasADi functions ``fns`` to CasADi's C API, each from a file
    of its serialization (:func:`~acausal2d.runtime.cbuild.serialized`, the
    fingerprint's); their ids, or None where a push fails."""
    ids = []
    for fn in fns:
        fd, path = tempfile.mkstemp(prefix="acausal2d-", suffix=".casadi")
        try:
            with os.fdopen(fd, "w", encoding="latin-1") as fh:
                fh.write(cbuild.serialized(fn))
            ids.append(lib.casadi.casadi_c_n_loaded())
            if lib.casadi.casadi_c_push_file(path.encode()):
                return None
        finally:
            os.remove(path)
    return ids


def _ids(lib, owner, what):
    """The ids in CasADi's C API of the functions of ``owner``: of a
    formulation (``what`` "ida") its residual, iteration matrix and events
    (-1: none); of a system ("rows") E and EJ.  Pushed once per owner; the
    C API's list is cleared where no owner of earlier ids is left (an
    optimisation compiling a model per trial would otherwise keep every
    trial's functions)."""
    with _pushing:
        if not len(_pushed) and lib.casadi.casadi_c_n_loaded():
            lib.casadi.casadi_c_clear()
        return _ids_of(lib, _pushed.setdefault(owner, {}), owner, what)


def _ids_of(lib, done, owner, what):
    """:func:`_ids` with the lock held (``done``: the owner's ids so far)."""
    if what not in done:
        if what == "ida":
            fns = [fn for fn in (owner.res_fn, owner.jac_fn, owner.event_fn) if fn is not None]
        else:
            args = owner.residual_fn.sx_in()       # E and dE/dz as one function, no cse:
            fns = [owner.residual_fn, ca.Function("EJ", args, [owner.residual_fn(*args),
                                                               owner.jacobian_fn(*args)])]
        ids = _push(lib, fns)
        done[what] = None if ids is None else np.array(ids + [-1] * (3 - len(ids)), dtype=np.intc)
    return done[what]


def capi_ida(prob, rtol, atol, solver=None, chosen=None):
    """A :class:`~acausal2d.runtime.native.NativeIDA` of ``prob`` on the
    driver of :func:`driver`, or None (the engine ``chosen`` is the Python
    path, or the driver is not here)."""
    if tiers.mode(chosen) == "off":
        return None
    lib = driver()
    ids = None if lib is None else _ids(lib, prob.form, "ida")
    if ids is None:
        return None
    drv = native.NativeIDA(lib, prob, rtol, atol, prob.terminal, prob.direction, solver, ids)
    return drv if drv.handle else None


def engine_ida(prob, rtol, atol, solver=None, chosen=None, label=None):
    """The native engine of a run's problem: the structure's compiled
    library where the cache has it (or mode ``now`` compiled it), else the
    driver on CasADi's C API; None: the Python path (``chosen`` is
    ``off``, or neither is here)."""
    return native.native_ida(prob, rtol, atol, solver, chosen, label) or \
        capi_ida(prob, rtol, atol, solver, chosen)


def engine_projector(system, free, chosen=None):
    """The C projector of a system's output rows
    (:func:`~acausal2d.runtime.native.row_projector`): the structure's
    library where the cache has it, else on the driver on CasADi's C API;
    None: the Python path."""
    found = native.row_projector(system, free, chosen)
    if found is not None or tiers.mode(chosen) == "off":
        return found
    lib = driver()
    ids = None if lib is None else _ids(lib, system, "rows")
    return None if ids is None else native.projector_on(lib, system, free, ids)
