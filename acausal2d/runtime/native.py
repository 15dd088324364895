"""The native inner loop: IDA driven from C over the output times of a
segment, with the residual, the exact iteration matrix and the event
functions of the formulation as CasADi-generated C.

Per step and per output time the Python path (:func:`~acausal2d.runtime.ida.advance`
through scikit-sundae) calls back into Python for every residual, Jacobian
and event evaluation; measured on the piston engine that is 4-10x the time
CasADi's own IDAS needs for the same system.  Here the generated code and a
small driver (``native_driver.c``) are compiled once per formulation with the
C compiler found at run time (:mod:`~acausal2d.runtime.cbuild`, cached on
disk by a hash of the code) and linked against the SUNDIALS libraries that
the scikit-sundae wheel ships; the driver owns its IDA memory (no pointer is
read out of scikit-sundae's objects on this path).

It makes the same IDA settings as :func:`~acausal2d.runtime.ida.make_solver`
and :func:`~acausal2d.runtime.ida.start_solver` (tolerances, algebraic ids
with ``IDASetSuppressAlg``, :data:`~acausal2d.options.STEPS_PER_OUTPUT` steps per output interval, root directions,
terminal roots) and runs a segment as scikit-sundae's ``solve`` does, so
the steps are the same.  Where there is no compiler or the build fails, the
same driver runs on CasADi's C API (:mod:`~acausal2d.runtime.capi`); where
the SUNDIALS version is not the one the declarations are written for, or IDA
fails in a segment, the Python path (which then reports the failure exactly
as before).  ``ACAUSAL2D_NATIVE=0`` turns it off.

The driver declares the SUNDIALS functions it calls itself (the wheel ships
no headers), for the release named in ``native_driver.c``
(:data:`SUNDIALS_VERSION`).  That release is compared with the one the
shipped core library reports (``SUNDIALSGetVersionNumber``,
:func:`loaded_sundials_version`) before anything is built, and again by
the built library when it is loaded (``a2d_sundials_matches``); another
release makes the process say once on stderr that IDA runs through
scikit-sundae instead (slower, same results).
"""
import ctypes
import os
import re
import sys
import weakref

import casadi as ca
import numpy as np

from . import blt_layout, cbuild, drivers, ordering, tiers
from ..options import STEPS_PER_OUTPUT
from ..threads import libraries_loaded
from .codegen import NATIVE_BELOW, Recipe, eliminated, optimization, too_large  # noqa: F401
from . import codegen
from .notices import notice

LIBRARIES = ("ida", "nvecserial", "sunmatrixdense", "sunlinsoldense", "sunmatrixsparse",
             "core")
OPTIONAL = (("sunlinsollapackdense", "SUNLinSol_LapackDense"),
            ("sunlinsolsuperlumt", "SUNLinSol_SuperLUMT"))
"""The linear solvers the driver is not linked against: their libraries load
OpenBLAS, gfortran and libgomp (measured: the model library's load 5.4 ->
0.9 ms of a process's first run without them).  :func:`_hand_in_optional`
loads them where a run uses LAPACK's dense LU or SuperLU_MT (the bench
tables, or the own LU's op slots not found)."""
SOLVERS = {"dense": 0, "lapack": 1, "sparse": 2, "sparse-lu": 3}
"""IDA's linear solvers the driver can use: SUNDIALS' dense LU, LAPACK's
dense LU, SuperLU_MT (sparse, one thread), the driver's own sparse LU
(``native_lu.c``, in the order of :func:`~acausal2d.runtime.ordering.lu_order`)."""
SPARSE_FROM = 64
"""The driver's IDA uses its own sparse LU (``native_lu.c``) from this many
unknowns, SUNDIALS' dense LU below (benchmarks/bench_floor.py, IDA alone,
CPU s, median of 5: piston engine, 39 unknowns: dense 0.0052, LAPACK 0.0058,
SuperLU_MT 0.0052, sparse LU 0.0032; belt drive, 84: 0.0145, 0.0157,
0.0129, 0.0107; chain of 20 links, 396: 0.333, 0.495, 0.078, 0.040).  The
LU is also the faster one at 39 (the piston's warm simulate 0.0153 ->
0.0129 s), but below 64 the native loop keeps the dense LU of the Python
path, whose steps it takes exactly (piston engine 1463 steps, asserted in
tests/test_native_runtime.py; 1437 with the LU)."""
MAX_PASSES = 256


def _declared_version():
    text = drivers.source("driver")
    return ".".join(re.search(r"#define A2D_SUNDIALS_%s (\d+)" % part, text).group(1)
                    for part in ("MAJOR", "MINOR", "PATCH"))


SUNDIALS_VERSION = _declared_version()
"""The SUNDIALS release the declarations in ``native_driver.c`` are written
for (its ``A2D_SUNDIALS_*`` lines)."""
_P, _I, _L = ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_int), \
    ctypes.POINTER(ctypes.c_long)
_PROGRESS = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_double)


def enabled(chosen=None):
    """False where the engine chosen is the Python path (``chosen``, a
    run's ``RunOptions.native``, else ``ACAUSAL2D_NATIVE``: ``0`` or
    ``off``), scikit-sundae ships no SUNDIALS libraries, or they are not of
    :data:`SUNDIALS_VERSION` (said once on stderr)."""
    if tiers.mode(chosen) == "off" or cbuild.sundials_libraries() is None:
        return False
    loaded = loaded_sundials_version()
    if loaded != SUNDIALS_VERSION:
        _falls_back("SUNDIALS %s is loaded" % (loaded or "of unknown version"))
        return False
    return True


_loaded_version: list = []


def loaded_sundials_version():
    """The release of the SUNDIALS that scikit-sundae ships, as its core
    library reports it (``SUNDIALSGetVersionNumber``), e.g. ``"7.9.0"``, or
    None where it cannot be asked."""
    if not _loaded_version:
        version = None
        try:
            get = ctypes.CDLL(cbuild.sundials_libraries()[1]["core"]).SUNDIALSGetVersionNumber
            get.argtypes = [_I, _I, _I, ctypes.c_char_p, ctypes.c_int]
            parts = [ctypes.c_int(-1) for _ in range(3)]
            if get(*(ctypes.byref(p) for p in parts), ctypes.create_string_buffer(64), 64) == 0:
                version = "%d.%d.%d" % tuple(p.value for p in parts)
        except (TypeError, KeyError, OSError, AttributeError):
            pass
        _loaded_version.append(version)
    return _loaded_version[0]


def _falls_back(why):
    """Say once per process that IDA runs through scikit-sundae, and why."""
    notice("%s, the native driver is declared for SUNDIALS %s: IDA runs through "
           "scikit-sundae instead (the Python path: the same results, slower; "
           "ACAUSAL2D_NATIVE=off chooses it without this message)" % (why, SUNDIALS_VERSION))


def _text(path):
    with open(path, encoding="utf-8") as fh:
        return fh.read()


_module_texts: dict = {}


def _derived(owner):
    """What identifies the Jacobian functions of ``owner`` (a formulation
    or a system) given its residual function: the text of the module that
    derives them from the residual (``casadi.jacobian``; the CasADi version
    is in the fingerprint).  Serializing the Jacobians themselves, three
    times the residual, took 0.026 s of the belt drive's run."""
    path = sys.modules[type(owner).__module__].__file__
    if path not in _module_texts:
        _module_texts[path] = _text(path) + _generator()
    return _module_texts[path]


def _generator():
    """The text of this module (it decides what C is generated: ``cse``,
    the combined EJ function, the size limits), part of every fingerprint,
    so a library generated differently is never found again."""
    if __file__ not in _module_texts:
        _module_texts[__file__] = _text(__file__) + _text(codegen.__file__) + \
            _text(drivers.__file__) + "\n%d" % NATIVE_BELOW
    return _module_texts[__file__]


def _model_recipe(form, libraries, folder):
    """The recipe of a formulation's library: generated functions, linked
    with the driver (an object compiled once per machine; with or without
    events)."""
    events = form.event_fn is not None
    fns = [fn for fn in (form.res_fn, form.jac_fn, form.event_fn) if fn is not None]
    driver = "a2d_driver_events" if events else "a2d_driver"
    return Recipe("a2d_model", [("cse", fns)], libraries=libraries, library_dirs=[folder],
                  objects=[driver])


def _declare(lib):
    libraries_loaded()            # SUNDIALS' pools (libgomp, OpenBLAS): limited in this run
    lib.a2d_create.restype = ctypes.c_void_p
    lib.a2d_create.argtypes = [ctypes.c_int, ctypes.c_int, ctypes.c_double, _P, _P, _I, _I,
                               ctypes.c_long, ctypes.c_int, _P, _P, _P, _I, _I, _I, _I]
    lib.a2d_destroy.argtypes = [ctypes.c_void_p]
    lib.a2d_set_progress.argtypes = [ctypes.c_void_p, _PROGRESS]
    lib.a2d_steps.restype = ctypes.c_long
    lib.a2d_steps.argtypes = [ctypes.c_void_p]
    lib.a2d_set_optional.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
    lib.a2d_lu_usable.restype = ctypes.c_int
    lib.a2d_sundials_matches.restype = ctypes.c_int
    if not lib.a2d_sundials_matches():
        _falls_back("the SUNDIALS loaded with %s is not of the declared release"
                    % os.path.basename(lib._name))
        return None
    lib.a2d_run.restype = ctypes.c_int
    lib.a2d_run.argtypes = [ctypes.c_void_p, _P, ctypes.c_int, _P, _P, _P, _P, _I, _P, _P,
                            _I, ctypes.c_int, _P, _I, _L]
    return lib


_plans: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()    # owner -> (key, recipe) or None
_loaded: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()   # owner -> library or False


def _library(owner, plan, loader, chosen, label):
    """The loaded library of ``owner`` (a formulation or a system) made as
    ``plan(owner)`` says ((fingerprint, recipe), or None: too large for
    native code), or None where the engine ``chosen``
    (:func:`~acausal2d.runtime.tiers.mode`) is the Python path, it cannot be
    built, or it is not in the cache in mode auto
    (:mod:`~acausal2d.runtime.tiers`: compiled after the run, found by a
    later one).  ``label``: the model, for the notices."""
    if not enabled(chosen):
        return None
    lib = _loaded.get(owner)
    if lib is None:
        if owner not in _plans:
            _plans[owner] = plan(owner)
        if _plans[owner] is None:
            _loaded[owner] = False
            return None
        lib = tiers.obtain(*_plans[owner], loader, chosen, label)
        if lib is not None or tiers.mode(chosen) == "now":     # built, or its build failed
            _loaded[owner] = lib or False
    return lib or None


def _model_plan(form):
    """(fingerprint, recipe) of a formulation's library (:func:`_library`)."""
    if too_large(form.res_fn, form.jac_fn, form.event_fn or form.res_fn):
        return None
    folder, libs = cbuild.sundials_libraries()
    linked = [libs[k] for k in LIBRARIES if k in libs]
    key = cbuild.fingerprint((form.res_fn, form.event_fn), _derived(form),
                             drivers.text("a2d_driver"), *linked)
    return key, _model_recipe(form, linked, folder)


def library(form, chosen=None, label=None):
    """The compiled library of a formulation (cached on disk), or None
    (:func:`_library`)."""
    return _library(form, _model_plan, lambda path: _declare(ctypes.CDLL(path)), chosen, label)


def _hand_in_optional(lib, solver):
    """Load the optional solvers' libraries (:data:`OPTIONAL`) into the
    process and hand their constructors to ``lib``'s driver where ``solver``
    needs one: "lapack", "sparse", or "sparse-lu" where the own LU cannot
    be given to IDA (SuperLU_MT instead).  Done once per library."""
    if solver == "dense" or getattr(lib, "a2d_optional", False):
        return
    if solver == "sparse-lu":
        if not hasattr(lib, "a2d_lu_ok"):         # asked of SUNDIALS once per library
            lib.a2d_lu_ok = bool(lib.a2d_lu_usable())
        if lib.a2d_lu_ok:
            return
        notice("the linear-solver slots of this SUNDIALS (%s) were not found: "
               "IDA's sparse systems use SuperLU_MT instead of the driver's own LU "
               "(the same results, slower)" % SUNDIALS_VERSION)
    libs = cbuild.sundials_libraries()[1]
    found = []
    for name, symbol in OPTIONAL:
        try:
            fn = getattr(ctypes.CDLL(libs[name]), symbol)   # local: an FMU loaded later binds its own SUNDIALS
            found.append(ctypes.cast(fn, ctypes.c_void_p).value)
        except (KeyError, OSError, AttributeError):
            found.append(None)
    lib.a2d_set_optional(*found)
    lib.a2d_optional = True
    libraries_loaded()            # the LAPACK/OpenMP pools they bring: limited in this run


def _ptr(a, kind=_P):
    return a.ctypes.data_as(kind)


class NativeIDA:
    """IDA of one :class:`~acausal2d.runtime.ida.Problem` in C (see module
    docstring); :meth:`run` is a segment."""

    def __init__(self, lib, prob, rtol, atol, terminal, direction, solver=None, ids=None):
        form = prob.form
        self.lib, self.prob, self.n = lib, prob, form.n
        self._keep = [np.ascontiguousarray(atol, float),
                      form.differential.astype(float),
                      np.ascontiguousarray(direction or [0], dtype=np.intc),
                      np.ascontiguousarray(terminal or [0], dtype=np.intc)]
        self._pattern = _ccs(form.jac_sparsity)
        solver = solver or default_solver(self.n)
        _hand_in_optional(lib, solver)
        self._order = lu_order(form) if solver == "sparse-lu" else None
        p, d = prob.res.args[3], prob.res.args[4]
        ab = prob.ab if len(prob.ab) else np.zeros(1)
        self._bound = [_backing(p), _backing(d), ab]
        self.handle = lib.a2d_create(
            self.n, prob.n_events, float(rtol), _ptr(self._keep[0]), _ptr(self._keep[1]),
            _ptr(self._keep[2], _I), _ptr(self._keep[3], _I), STEPS_PER_OUTPUT, SOLVERS[solver],
            *(_ptr(b) for b in self._bound), *(_ptr(a, _I) for a in self._pattern),
            None if self._order is None else _ptr(self._order, _I),
            None if ids is None else _ptr(ids, _I))
        self.roots = np.zeros(max(prob.n_events, 1), dtype=np.intc)
        self.counters = np.zeros(2, dtype=np.dtype(ctypes.c_long))
        self.last = np.zeros(1 + 2 * self.n)
        self.steps = 0
        self.raised = None
        if self.handle and prob.progress is not None:      # a progress bar: each output row
            self._progress = _PROGRESS(self._report)
            lib.a2d_set_progress(self.handle, self._progress)

    def _report(self, t):
        """The progress callback; an exception in it (Ctrl-C) stops the run
        and is raised again by :meth:`run` (ctypes would swallow it)."""
        try:
            self.prob.progress(t)
            return 0
        except BaseException as exc:       # noqa: B036 - handed back to the caller
            self.raised = exc
            return 1

    def __del__(self):
        handle, self.handle = getattr(self, "handle", None), None
        if handle:
            self.lib.a2d_destroy(handle)

    def run(self, tspan, y0, yp0):
        """One segment over ``tspan``: (flag, T, Y, passes (T, Y), last
        (t, y, yp), root info, nfev, njev, steps taken)."""
        n, m = self.n, len(tspan)       # rows left unfilled are not handed out: not zeroed
        T, Y = np.empty(m), np.empty((m, n))
        PT, PY = np.empty(MAX_PASSES), np.empty((MAX_PASSES, n))
        n_rows, n_pass = ctypes.c_int(m), ctypes.c_int(MAX_PASSES)
        pass_col = self.prob.n_rel + self.prob.n_mon if self.prob.n_pass else -1
        steps0 = self.lib.a2d_steps(self.handle)
        flag = self.lib.a2d_run(
            self.handle, _ptr(np.ascontiguousarray(tspan, float)), m,
            _ptr(np.ascontiguousarray(y0, float)), _ptr(np.ascontiguousarray(yp0, float)),
            _ptr(T), _ptr(Y), ctypes.byref(n_rows), _ptr(PT), _ptr(PY), ctypes.byref(n_pass),
            pass_col, _ptr(self.last), _ptr(self.roots, _I), _ptr(self.counters, _L))
        if self.raised is not None:
            exc, self.raised = self.raised, None
            raise exc
        k, q = n_rows.value, n_pass.value
        last = (float(self.last[0]), self.last[1:1 + n].copy(), self.last[1 + n:].copy())
        return (flag, T[:k], Y[:k], (PT[:q], PY[:q]), last, self.roots.copy(),
                int(self.counters[0]), int(self.counters[1]),
                int(self.lib.a2d_steps(self.handle) - steps0))


def default_solver(n):
    """The linear solver of a system of n unknowns (see :data:`SPARSE_FROM`)."""
    return "sparse-lu" if n >= SPARSE_FROM else "dense"


_orders: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()   # formulation -> (q, prefer)


def lu_order(form):
    """The pivot order of ``native_lu.c`` for the iteration matrix of
    ``form`` (column order then preferred rows, one C int array)."""
    if form not in _orders:
        colind, row = _ccs(form.jac_sparsity)
        _orders[form] = np.concatenate(ordering.lu_order(form.n, colind, row))
    return _orders[form]


def _ccs(sparsity):
    """(column starts, row indices) of a CasADi sparsity as C int arrays."""
    return (np.ascontiguousarray(sparsity.colind(), dtype=np.intc),
            np.ascontiguousarray(np.r_[sparsity.row(), 0], dtype=np.intc))


def _backing(a):
    """A bound argument array of a Buffered (at least one element: CasADi
    binds none for an empty one, the C code reads none)."""
    return a if a.size else np.zeros(1)


def native_ida(prob, rtol, atol, solver=None, chosen=None, label=None):
    """A :class:`NativeIDA` for ``prob`` with the settings of
    :func:`~acausal2d.runtime.ida.make_solver` (``solver``: a key of
    :data:`SOLVERS`, default the formulation's choice), or None (see module
    docstring; ``chosen``, ``label``: :func:`library`)."""
    lib = library(prob.form, chosen, label)
    if lib is None:
        return None
    drv = NativeIDA(lib, prob, rtol, atol, prob.terminal, prob.direction, solver)
    return drv if drv.handle else None


_compiled: dict = {}     # fingerprint of the functions -> {name: external Function}


def compiled(functions, chosen=None, label=None):
    """CasADi functions (their names -> Function) as compiled C, loaded back
    as CasADi functions (``casadi.external``) of the same names and signatures,
    or None where the engine ``chosen`` is the Python path, they cannot be
    built or are not in the cache in mode auto (the caller keeps its own);
    ``label``: the model, for the notices."""
    if tiers.mode(chosen) == "off":
        return None
    key = cbuild.fingerprint(functions.values(), _generator(), *functions)
    if key not in _compiled:
        recipe = Recipe("a2d_functions", [("plain", list(functions.values()))])
        found = tiers.obtain(key, recipe, lambda path: {name: ca.external(name, path)
                                                          for name in functions}, chosen, label)
        if found is None:
            return None
        _compiled[key] = found
    return _compiled[key]


def _projector_plan(system):
    """(fingerprint, recipe) of the C projector's library of ``system``
    (:func:`_library`)."""
    if too_large(system.residual_fn, system.jacobian_fn):
        return None
    key = cbuild.fingerprint((system.residual_fn,), _derived(system), drivers.text("a2d_project"))
    return key, Recipe("a2d_rows", [("cse", [system.residual_fn]),
                                    ("ej", [system.residual_fn, system.jacobian_fn])],
                       objects=["a2d_project"])


def _declare_projector(path):
    return declare_projector(ctypes.CDLL(path))


def declare_projector(lib):
    """``lib`` with the argument types of its ``a2d_project``."""
    lib.a2d_project.argtypes = [ctypes.c_int, _P, _P, _P, _P, ctypes.c_int, ctypes.c_int, _I,
                                _P, ctypes.c_double, ctypes.c_int, ctypes.c_int, _I, _I, _I, _I,
                                _I]
    return lib


def row_projector(system, free, chosen=None):
    """A function (T, Z, p, d, tol, max_iter, slow, overwrite=False) -> (Z
    solved for the unknowns ``free`` - in a copy, or in Z where ``overwrite``
    and Z is C-ordered floats -, converged rows) in C (``native_project.c``,
    LU of dE/dz_free's block lower-triangular form, ``native_lu.c`` per block,
    :func:`~acausal2d.runtime.blt_layout.layout`), or None where the engine
    ``chosen`` is the Python path, it cannot be built (or is not in the cache
    in mode auto) or dE/dz_free is structurally singular.  Each row gets at
    most ``max_iter`` Newton iterations; after a row that needed more than
    ``slow`` of them the next row takes a new LU."""
    lib = _library(system, _projector_plan, _declare_projector, chosen,
                   getattr(system, "model_name", None))
    return None if lib is None else projector_on(lib, system, free)


def projector_on(lib, system, free, ids=None):
    """The function of :func:`row_projector` on the library ``lib`` (a
    structure's, or with ``ids`` of E and EJ the driver on CasADi's C API,
    :mod:`~acausal2d.runtime.capi`); None where dE/dz_free is structurally
    singular."""
    colind, row = _ccs(system.jacobian_fn.sparsity_out(0))
    ints = blt_layout.layout(system, free)
    if ints is None:
        return None
    n_var, n_eq = system.structure.n_var, system.structure.n_eq
    col_of = np.full(n_var, -1, dtype=np.intc)
    col_of[free] = np.arange(len(free), dtype=np.intc)
    nominal = np.ascontiguousarray(system.nominal, dtype=float)

    def project(T, Z, p, d, tol, max_iter, slow, overwrite=False):
        T = np.ascontiguousarray(T, float)
        Z = np.require(Z, float, ["C", "W"]) if overwrite else np.array(Z, dtype=float, order="C")
        ok = np.zeros(len(T), dtype=np.intc)
        p_, d_ = (np.ascontiguousarray(np.r_[np.asarray(a, float).ravel(), 0.0]) for a in (p, d))
        lib.a2d_project(len(T), _ptr(T), _ptr(Z), _ptr(p_), _ptr(d_), n_var, n_eq,
                        _ptr(col_of, _I), _ptr(nominal), float(tol), int(max_iter), int(slow),
                        _ptr(colind, _I), _ptr(row, _I), _ptr(ints, _I), _ptr(ok, _I),
                        None if ids is None else _ptr(ids, _I))
        return Z, ok.astype(bool)
    return project
