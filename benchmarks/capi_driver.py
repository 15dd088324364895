"""The native driver built once with no model code: it evaluates a
formulation's serialized CasADi functions through CasADi's C API
(``casadi_c_eval_id`` of the libcasadi the casadi wheel ships), so a new
structure would need no compiler.  benchmarks/bench_capi.py measures it
against the per-model compiled library; outside 1.2x of it, runs do not
use it, so it lives here, beside its benchmark, not in the package.

The C put before ``native_driver.c`` (:data:`BEFORE`) defines how the
driver evaluates a function (``A2D_EVAL``) and makes and releases its work
arrays; the C after it (:data:`AFTER`) takes them from CasADi's C API.
"""
import ctypes
import os
import tempfile
import weakref

import casadi as ca
import numpy as np

from acausal2d.runtime import cbuild, drivers, native

BEFORE = """int casadi_c_eval_id(int id, const casadi_real **arg, casadi_real **res, casadi_int *iw,
                     casadi_real *w, int mem);
int casadi_c_work_id(int id, casadi_int *sz_arg, casadi_int *sz_res, casadi_int *sz_iw,
                     casadi_int *sz_w);
int casadi_c_checkout_id(int id);
void casadi_c_release_id(int id, int mem);
static void a2d_alloc_id(void *work, int id);
#define A2D_EVAL(x, fn) casadi_c_eval_id((x).id, (x).arg, (x).res, (x).iw, (x).w, (x).mem)
#define A2D_ALLOC(x, fn, k) a2d_alloc_id(&(x), ids[k])
#define A2D_RELEASE(x) if ((x).arg && (x).id >= 0) casadi_c_release_id((x).id, (x).mem)
"""
AFTER = """
static void a2d_alloc_id(void *work, int id) {
  a2d_work *w = (a2d_work *)work;
  w->id = id;
  if (id < 0) return;
  casadi_c_work_id(id, &w->sz_arg, &w->sz_res, &w->sz_iw, &w->sz_w);
  w->mem = casadi_c_checkout_id(id);
  a2d_alloc_arrays(w);
}
"""


def _libcasadi():
    """(folder, path) of the libcasadi the casadi wheel ships, or None."""
    folder = os.path.dirname(ca.__file__)
    for name in sorted(os.listdir(folder)):
        if name.startswith("libcasadi.so") or name == "libcasadi.dylib":
            return folder, os.path.join(folder, name)
    return None


_loaded: dict = {}       # "lib": the driver once loaded (or None)


def driver():
    """The driver on CasADi's C API, built on first use into the cache;
    None where it cannot be built or loaded."""
    if "lib" not in _loaded:
        _loaded["lib"] = None
        found, casadi_lib = cbuild.sundials_libraries(), _libcasadi()
        if found is not None and casadi_lib is not None:
            folder, libs = found
            text = drivers.GENERATED + "#define A2D_EVENTS 1\n" + BEFORE + \
                drivers.source("lu") + drivers.source("driver") + AFTER
            try:
                path = cbuild.build({"a2d_capi.c": text}, flags=drivers.flags(cbuild.find_compiler()),
                                    libraries=[libs[k] for k in native.LIBRARIES if k in libs] +
                                    [casadi_lib[1]], library_dirs=[folder, casadi_lib[0]],
                                    name="a2d_capi")
                lib = native._declare(ctypes.CDLL(path))
                lib.casadi_c_push_file.argtypes = [ctypes.c_char_p]
                _loaded["lib"] = lib
            except (cbuild.CompilerMissing, cbuild.BuildFailed, OSError):
                pass
    return _loaded["lib"]


_pushed: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()   # formulation -> C API ids


def _ids(lib, form):
    """The ids (residual, iteration matrix, events; -1: none) of ``form``'s
    functions in CasADi's C API, pushed once per formulation."""
    if form not in _pushed:
        fns = [fn for fn in (form.res_fn, form.jac_fn, form.event_fn) if fn is not None]
        fd, path = tempfile.mkstemp(suffix=".casadi")
        os.close(fd)
        try:
            writer = ca.FileSerializer(path)
            writer.pack(fns)
            del writer
            base = lib.casadi_c_n_loaded()
            if lib.casadi_c_push_file(path.encode()):
                return None
        finally:
            os.remove(path)
        ids = [base, base + 1, base + 2 if form.event_fn is not None else -1]
        _pushed[form] = np.array(ids, dtype=np.intc)
    return _pushed[form]


def capi_ida(prob, rtol, atol, solver=None):
    """A :class:`~acausal2d.runtime.native.NativeIDA` of ``prob`` on the
    driver of :func:`driver` (no per-model library), or None."""
    lib = driver()
    ids = None if lib is None else _ids(lib, prob.form)
    if ids is None:
        return None
    drv = native.NativeIDA(lib, prob, rtol, atol, prob.terminal, prob.direction, solver, ids)
    return drv if drv.handle else None
