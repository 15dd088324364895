"""The native drivers' constant C, compiled once: at install time where a
C compiler is found there, else on first use into the cache.

Every native library links one of three object files compiled from C that
does not depend on the model (:data:`OBJECTS`): the IDA driver
(``native_driver.c``, with or without events) and the output projector
(``native_project.c``), each with the sparse LU (``native_lu.c``).  The
same driver on CasADi's C API (:data:`CAPI`) is a library of its own,
which runs a structure before its library is compiled.  They are
most of a small model's compile (piston engine: 1.0 s of gcc for the two it
uses, 0.19 s for its generated code), so a machine's first run would wait
for them.  ``pip install`` therefore compiles them into the package
(:func:`install`, called by ``setup.py``; a missing or failing compiler
only leaves them out), and :func:`prebuilt` hands them to the build
(:func:`~acausal2d.runtime.cbuild.build_object`) after checking each
against the SHA-256 recorded beside it.  Their names carry the key of the
text, flags and compiler (:func:`~acausal2d.runtime.cstore.build_key`), so
an object built by another compiler or from other C is never taken.
``ACAUSAL2D_PREBUILT=0`` ignores them (they are then compiled into the
cache on first use, as where none were built).

This module and those it imports use the standard library only: ``setup.py``
imports it before the dependencies are installed.
"""
import os

from . import cstore, cunits
from .notices import notice

HERE = os.path.dirname(os.path.abspath(__file__))
PREBUILT = os.path.join(HERE, "prebuilt")
"""Where :func:`install` puts the objects (inside the installed package).

:meta hide-value:
"""
ENV = "ACAUSAL2D_PREBUILT"
_SOURCES = {"lu": "native_lu.c", "driver": "native_driver.c", "project": "native_project.c"}

GENERATED = """#ifndef casadi_real
#define casadi_real double
#endif
#ifndef casadi_int
#define casadi_int long long int
#endif
#define A2D_GENERATED(f) \\
  int f(const casadi_real **arg, casadi_real **res, casadi_int *iw, casadi_real *w, int mem); \\
  int f##_work(casadi_int *sz_arg, casadi_int *sz_res, casadi_int *sz_iw, casadi_int *sz_w);
A2D_GENERATED(res) A2D_GENERATED(iteration_matrix) A2D_GENERATED(events)
A2D_GENERATED(E) A2D_GENERATED(EJ)
"""
"""The declarations of the CasADi-generated functions (their signatures in
CasADi's code) that the drivers call: the drivers are compiled apart from
the generated code (:meth:`~acausal2d.runtime.codegen.Recipe` ``objects``)."""

OBJECTS = {"a2d_driver": ("", "lu", "driver"),
           "a2d_driver_events": ("#define A2D_EVENTS 1\n", "lu", "driver"),
           "a2d_project": ("", "lu", "project")}
"""Object name -> (defines, sources): the C of each object is
:data:`GENERATED`, the defines and the sources in this order."""

CAPI = "a2d_capi"
"""The driver on CasADi's C API (:mod:`~acausal2d.runtime.capi`): a shared
library of the driver, the output projector and the LU with ``A2D_CAPI``
(no generated code, no library linked: the SUNDIALS and C API functions it
calls are bound when it is loaded), so that a machine with no compiler at
run time runs it."""
CAPI_PARTS = ("#define A2D_EVENTS 1\n#define A2D_CAPI 1\n", "lu", "driver", "project")
"""Its defines and sources, as an object's in :data:`OBJECTS`."""
CAPI_FLAGS = ("-O2", "-fPIC", "-shared")
"""Its flags: fixed, so that its name (:func:`capi_file`) is found with no
compiler to ask."""

GCC_LIMITS = ("--param=sccvn-max-alias-queries-per-access=20",
              "--param=dse-max-alias-queries-per-store=20")
"""gcc's alias queries per memory access in value numbering and dead-store
elimination (defaults 1000 and 256).  In a long body of generated code
every load of an input may alias every earlier store of an output, and
walking those chains was 42% of gcc's -O1 time (chain of 81 links, model
library unit of 248 kB: 5.0 -> 3.3 s CPU, ``-ftime-report``); CasADi's code
loads each input element once, so the queries found nothing to reuse."""

_texts: dict = {}


def source(key):
    """The text of one of the drivers' C files (``lu``, ``driver``, ``project``)."""
    if key not in _texts:
        with open(os.path.join(HERE, _SOURCES[key]), encoding="utf-8") as fh:
            _texts[key] = fh.read()
    return _texts[key]


def text(name):
    """The C of the object ``name`` (a key of :data:`OBJECTS`) or of the
    driver on CasADi's C API (:data:`CAPI`)."""
    defines, *parts = CAPI_PARTS if name == CAPI else OBJECTS[name]
    return GENERATED + defines + "".join(source(p) for p in parts)


def capi_file():
    """The file name of the driver on CasADi's C API: it carries the key of
    its text and flags (not of a compiler: it is looked up where none is)."""
    return "%s-%s.so" % (CAPI, cstore.build_key({CAPI + ".c": text(CAPI)}, CAPI_FLAGS)[:32])


def is_gcc(compiler):
    """True where ``compiler`` is gcc (``cc`` is often a link to it)."""
    return bool(compiler) and "gcc" in os.path.basename(os.path.realpath(compiler))


def flags(compiler):
    """The flags the drivers' objects are compiled with: ``-O1`` (the LU
    and projector raise their own functions to -O2 by pragma), gcc's alias
    query limits (:data:`GCC_LIMITS`) where ``compiler`` is gcc."""
    return ["-O1"] + (list(GCC_LIMITS) if is_gcc(compiler) else [])


def object_file(name, text_, flags_, compiler):
    """(compile arguments, file name) of an object: its name carries the
    key of the text, the flags and the compiler."""
    args = ["-fPIC"] + list(flags_)
    key = cstore.build_key({name + ".c": text_}, args, compiler)
    return args, "%s-%s.o" % (name, key[:32])


def prebuilt(filename):
    """The path of the object ``filename`` built at install time, where it
    is there, matches its recorded SHA-256 and ``ACAUSAL2D_PREBUILT`` is not
    ``0``; else None (a damaged one is said once on stderr, and left: the
    package folder may not be ours to change)."""
    path = os.path.join(PREBUILT, filename)
    if os.environ.get(ENV, "1").strip() == "0" or not os.path.exists(path):
        return None
    if _matches(path):
        return path
    notice("the driver object %s installed with acausal2d does not match its recorded "
           "SHA-256; it is compiled into the cache instead (reinstall acausal2d to "
           "mend the installation)" % path)
    return None


def installed():
    """(file name, whether its SHA-256 matches) of the objects in the
    package (:data:`PREBUILT`), for ``acausal2d cache list``."""
    try:
        names = sorted(f for f in os.listdir(PREBUILT) if f.endswith((".o", ".so")))
    except OSError:
        return []
    return [(name, _matches(os.path.join(PREBUILT, name))) for name in names]


def _matches(path):
    """True where the installed object ``path`` has its recorded SHA-256
    (unlike :func:`~acausal2d.runtime.cstore.verified`, nothing is removed)."""
    try:
        return cstore.file_digest(path) == cstore.recorded(path)
    except OSError:
        return False


def install(dest=PREBUILT, compiler=None, log=print):
    """Compile every object of :data:`OBJECTS` and the driver on CasADi's C
    API (:data:`CAPI`) into ``dest`` (each with its SHA-256 beside it) with
    ``compiler`` (default: the one found at run time,
    :func:`~acausal2d.runtime.cunits.find_compiler`); the paths built.
    Nothing is built where there is no compiler, and a file the compiler
    refuses is left out (``log`` says why): a run builds it into the cache
    then, where it finds a compiler."""
    cc = compiler or cunits.find_compiler()
    if cc is None:
        log("acausal2d: no C compiler found; the native drivers are compiled on first use")
        return []
    os.makedirs(dest, exist_ok=True)
    built = []
    for name in OBJECTS:
        args, filename = object_file(name, text(name), flags(cc), cc)
        target = os.path.join(dest, filename)
        try:
            cunits.compile_object(cc, name + ".c", text(name), args, dest, target)
        except cunits.BuildFailed as exc:
            log("acausal2d: %s not compiled at install (%s); it is compiled on first use"
                % (name, str(exc).splitlines()[0]))
            continue
        built.append(target)
    target = os.path.join(dest, capi_file())
    try:
        cunits.compile_library(cc, {CAPI + ".c": text(CAPI)}, CAPI_FLAGS, dest, target)
        built.append(target)
    except cunits.BuildFailed as exc:
        log("acausal2d: %s not built at install (%s); it is built on first use where a "
            "compiler is found" % (CAPI, str(exc).splitlines()[0]))
    return built
