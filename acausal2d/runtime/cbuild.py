"""C sources compiled at run time into shared libraries, cached on disk.

A small self-contained builder for generated C code (CasADi's code
generator, native drivers):

- :func:`find_compiler` looks for a C compiler: ``$CC``, then ``cc``,
  ``gcc``, ``clang`` on the ``PATH``;
- :func:`build` compiles C sources into a shared library in a user cache
  folder (:func:`cache_dir`), named by the SHA-256 of the sources, the flags
  and the compiler, so that a model structure is compiled once per machine;
  the library is written under a temporary name and renamed into place
  (atomic: concurrent processes never load a half-written file), with its
  own SHA-256 beside it, checked before it is used again
  (:mod:`~acausal2d.runtime.cstore`); :func:`load` loads it (a library the
  loader refuses is built again); how the C is compiled (translation units
  in parallel) is :mod:`~acausal2d.runtime.cunits`;
- :func:`sundials_libraries` finds the SUNDIALS libraries the scikit-sundae
  wheel ships (no headers: the native driver declares what it uses, see
  :mod:`~acausal2d.runtime.native`).

Errors a user can act on are :class:`CompilerMissing` (names what to
install) and :class:`BuildFailed` (carries the compiler's message).
"""
import functools
import glob
import os
import shutil
import importlib.util
import weakref

import casadi as ca

from . import cstore as store, cunits as units
from . import drivers
from .notices import notice
from .cstore import CACHE_ENV, _sha256, build_key, cache_dir  # noqa: F401 - names of this module
from .cunits import BuildFailed, CompilerMissing, find_compiler  # noqa: F401 - names of this module

DEFAULT_FLAGS = ("-O2", "-fPIC", "-shared")
INSTALL_HINT = ("install a C compiler (Debian/Ubuntu: 'apt-get install gcc'; macOS: "
                "'xcode-select --install'; or set $CC to one)")


def require_compiler():
    """The path of a C compiler; :class:`CompilerMissing` naming what to
    install if there is none."""
    path = find_compiler()
    if path is None:
        raise CompilerMissing("No C compiler found ($CC, cc, gcc, clang): " + INSTALL_HINT)
    return path


def build(sources, flags=(), libraries=(), library_dirs=(), include_dirs=(), name="lib",
          objects=()):
    """Compile ``sources`` (file name -> C text) into a shared library and
    return its path; an identical build found in the cache folder
    (:func:`store.folder`) whose digest matches is reused, a damaged one is
    rebuilt (one line on stderr).  ``libraries`` are full paths or ``-l``
    names; each folder of ``library_dirs`` is also put on the library's run
    path; ``objects`` are object files (:func:`build_object`) linked in.
    Concurrent builds of one library wait for each other (a lock per
    key) and publish atomically."""
    cc = require_compiler()
    args = list(DEFAULT_FLAGS) + ["-I" + d for d in include_dirs] + list(flags)
    args += ["-L" + d for d in library_dirs] + ["-Wl,-rpath," + d for d in library_dirs]
    args += [lib if os.sep in lib else "-l" + lib for lib in libraries]
    key = build_key(sources, args + [os.path.basename(o) for o in objects], cc)
    folder = store.folder()
    target = os.path.join(folder, "%s-%s.so" % (name, key[:32]))
    if store.verified(target):
        return target
    store.sweep(folder)
    return _once(target, lambda: units.compile_library(cc, sources, args, folder, target,
                                                       objects))


def _once(target, compile_):
    """``target`` after ``compile_()`` made it, under its lock, unless a
    verified one is there (another process may have built it meanwhile)."""
    with store.locked(target):
        if not store.verified(target):
            compile_()
    return target


def _object_target(text, flags, name, cc):
    """(compiler flags, path) of the object file of :func:`build_object`:
    the one installed with the package (:func:`~acausal2d.runtime.drivers.
    prebuilt`), else its place in the cache."""
    args, filename = drivers.object_file(name, text, flags, cc)
    return args, drivers.prebuilt(filename) or os.path.join(store.folder(), filename)


def build_object(text, flags=(), name="obj"):
    """The path of the position-independent object file compiled from the C
    ``text`` with ``flags``, cached and verified as libraries are
    (:func:`build`; its name carries the SHA-256 of the text, flags and
    compiler), or the same object installed with the package
    (:mod:`~acausal2d.runtime.drivers`).  The constant C of the native
    drivers is compiled so once per machine and linked into each
    structure's library: it was most of a small model's compile (piston
    engine: the driver and LU 0.45 s of the model library's 0.64 s of gcc,
    the generated code 0.19 s)."""
    cc = require_compiler()
    args, target = _object_target(text, flags, name, cc)
    if store.verified(target):
        return target
    return _once(target, lambda: units.compile_object(cc, name + ".c", text, args,
                                                      store.folder(), target))


def copy_verified(path, dest):
    """Copy the library ``path`` (from :func:`build`) to ``dest`` and check
    the copy against the digest recorded at its build (``export-fmu`` packs
    only a verified binary); :class:`BuildFailed` where it does not match
    (the copy is removed and the cached library with it: the next build
    compiles it again)."""
    shutil.copy(path, dest)
    want = store.recorded(path)
    if want is None or store.file_digest(dest) != want:
        os.remove(dest)
        store.discard(path)
        raise BuildFailed("the compiled library %s does not match the SHA-256 recorded when it "
                          "was built (the cache was changed meanwhile); it was removed, run the "
                          "command again to rebuild it" % path)
    return dest


def fingerprint(functions, *texts):
    """SHA-256 (hex) of CasADi functions (their serializations), texts, the
    CasADi version and the compiler: a key of generated code that is found
    without generating it (CasADi's code generator took 0.09 s of the belt
    drive's 0.23 s run; serializing takes a third of that)."""
    h = _sha256()
    parts = [serialized(fn) for fn in functions if fn is not None]
    for part in parts + list(texts) + [ca.__version__, str(find_compiler()), DEFAULT_FLAGS,
                                       units.SCHEME]:
        data = str(part).encode("utf-8")
        h.update(len(data).to_bytes(8, "little"))
        h.update(data)
    return h.hexdigest()


_serial: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()   # Function -> serialize()


def serialized(fn):
    """A CasADi function serialized as a file of CasADi's serializer holds
    it (with its type tag: :func:`deserialized` reads it back, and CasADi's
    C API reads it from a file, :mod:`~acausal2d.runtime.capi`), made once
    per function object: the fingerprint (:func:`fingerprint`), the
    background job (:class:`~acausal2d.runtime.codegen.Recipe`) and the C
    API all need it, and the first run of a new structure pays for it
    before it starts (chain of 81 links: 0.1-0.3 s per serialization of its
    functions on a loaded machine)."""
    text = _serial.get(fn)
    if text is None:
        writer = ca.StringSerializer()
        writer.pack(fn)
        text = _serial[fn] = writer.encode()
    return text


def deserialized(text):
    """The CasADi function of :func:`serialized`'s ``text``."""
    return ca.StringDeserializer(text).unpack()


def index_path(key, name):
    """The index file of fingerprint ``key``: it names the library."""
    return os.path.join(store.folder(), "%s-%s.idx" % (name, key[:32]))


def lookup(key, name="lib"):
    """The verified library indexed by ``key`` (:func:`fingerprint`), or None
    (no index, no library, or a damaged one: removed, one line on stderr)."""
    folder = store.folder()
    index = index_path(key, name)
    try:
        with open(index, encoding="utf-8") as fh:
            named = fh.read(300).strip()
    except FileNotFoundError:
        return None
    except (OSError, UnicodeDecodeError) as exc:
        named = "unreadable: %s" % (getattr(exc, "strerror", None) or type(exc).__name__)
    path = os.path.join(folder, os.path.basename(named))
    if not (path.endswith(".so") and os.path.basename(path).startswith(name + "-")
            and os.path.exists(path)):
        notice("the index %s names no library of the cache (%r); it is compiled again"
               % (index, named[:80]))
        return None
    return path if store.verified(path) else None


def build_indexed(key, make, name="lib"):
    """The library built by ``make()`` (which returns its path, from
    :func:`build`), found again by ``key`` (:func:`fingerprint`) without
    calling ``make``: an index file in the cache folder names the library.
    A missing or unreadable index, or a library that is gone or damaged,
    only costs the call to ``make``."""
    path = lookup(key, name)
    if path is not None:
        return path
    path = make()
    publish_index(key, name, path)
    return path


def publish_index(key, name, path):
    """Write the index of ``key`` naming the library ``path`` (atomically;
    an unwritable folder or a full disk only costs the next lookup: said in
    one line, since every run then compiles again)."""
    try:
        store.write_atomic(index_path(key, name), os.path.basename(path).encode("utf-8"))
    except OSError as exc:
        notice("the index of the compiled library %s could not be written (%s); later "
               "runs compile it again until the cache folder %s can be written"
               % (os.path.basename(path), exc.strerror or exc, store.folder()))


def load(key, make, name, loader):
    """``loader(path)`` of the library of ``key`` (:func:`build_indexed`).
    A library the loader refuses (``OSError``: the dynamic loader,
    ``RuntimeError``: CasADi, ``AttributeError``: a symbol ctypes misses) is reported on stderr, removed and built
    again once."""
    path = build_indexed(key, make, name)
    try:
        return loader(path)
    except (OSError, RuntimeError, AttributeError) as exc:    # AttributeError: a symbol missing
        notice("the cached library %s could not be loaded (%s); rebuilding it"
               % (path, str(exc).strip().splitlines()[0] if str(exc).strip() else exc))
        store.discard(path)
        return loader(build_indexed(key, make, name))


def _sksundae_dir():
    """The folder of the installed ``sksundae`` package, found without
    importing it (its import pulls in scipy.optimize), or None."""
    try:
        spec = importlib.util.find_spec("sksundae")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return list(spec.submodule_search_locations)[0]


@functools.lru_cache(maxsize=None)
def sundials_libraries():
    """(lib folder, short name -> path) of the SUNDIALS libraries that the
    scikit-sundae wheel ships, or None if it is not installed that way;
    listed once per process (each run asked twice: 1.8 ms of the piston
    engine's 39 ms warm simulate)."""
    pkg = _sksundae_dir()
    if pkg is None:
        return None
    folder = os.path.normpath(os.path.join(pkg, "..", "scikit_sundae.libs"))
    found = {}
    for path in sorted(glob.glob(os.path.join(folder, "libsundials_*.so*"))):
        short = os.path.basename(path)[len("libsundials_"):].split("-")[0].split(".")[0]
        found[short] = path
    return (folder, found) if found else None
