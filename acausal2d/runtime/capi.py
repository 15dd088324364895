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
    return next((os.path.join(folder, name) for name in sorted(os.listdir(folder))
                 if name.startswith("libcasadi.so") or name == "libcasadi.dylib"), None)


def _path():
    """The driver's library: installed with the package, else built into the
    cache where a compiler is found; None where neither."""
    found = drivers.prebuilt(drivers.capi_file())
    if found is None and cbuild.find_compiler() is not None:
        found = cbuild.build({drivers.CAPI + ".c": drivers.text(drivers.CAPI)}, name=drivers.CAPI)
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
    """The ids in CasADi's C API of ``owner``'s functions (a formulation's,
    ``what`` "ida": residual, iteration matrix, events or -1; a system's,
    "rows": E and EJ), pushed once per owner; the C API's list is cleared
    where no owner of earlier ids is left (else a study kept every trial's)."""
    with _pushing:
        if not len(_pushed) and lib.casadi.casadi_c_n_loaded():
            lib.casadi.casadi_c_clear()
        done = _pushed.setdefault(owner, {})
        if what not in done:
            ids = _push(lib, _functions(owner, what))
            done[what] = None if ids is None else np.array(ids + [-1] * (3 - len(ids)), np.intc)
        return done[what]


def _functions(owner, what):
    """The CasADi functions of ``owner`` that :func:`_ids` pushes."""
    if what == "ida":
        return [fn for fn in (owner.res_fn, owner.jac_fn, owner.event_fn) if fn is not None]
    args = owner.residual_fn.sx_in()
    return [owner.residual_fn, ca.Function("EJ", args, [owner.residual_fn(*args),
                                                        owner.jacobian_fn(*args)])]


def capi_ida(prob, rtol, atol, solver=None, chosen=None):
    """A :class:`~acausal2d.runtime.native.NativeIDA` of ``prob`` on the
    driver of :func:`driver`, or None: the engine ``chosen`` is the Python
    path, the driver is not here, or the formulation is too large to compile
    (pushing its functions took longer than its runs: the cabinet door 1.2 s,
    its run 0.6 s, and a study compiles it per trial)."""
    form = prob.form
    if tiers.mode(chosen) == "off" or native.too_large(form.res_fn, form.jac_fn,
                                                        form.event_fn or form.res_fn):
        return None
    lib = driver()
    ids = None if lib is None else _ids(lib, form, "ida")
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
    if found is not None or tiers.mode(chosen) == "off" or \
            native.too_large(system.residual_fn, system.jacobian_fn):
        return found
    lib = driver()
    ids = None if lib is None else _ids(lib, system, "rows")
    return None if ids is None else native.projector_on(lib, system, free, ids)
