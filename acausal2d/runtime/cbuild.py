"""C sources compiled at run time into shared libraries, cached on disk.

A small self-contained builder for generated C code (CasADi's code
generator, native drivers):

- :func:`find_compiler` looks for a C compiler: ``$CC``, then ``cc``,
  ``gcc``, ``clang`` on the ``PATH``;
- :func:`build` compiles C sources into a shared library in a user cache
  folder (:func:`cache_dir`), named by the SHA-256 of the sources, the flags
  and the compiler, so that a model structure is compiled once per machine;
  the library is written under a temporary name and renamed into place
  (atomic: concurrent processes never load a half-written file);
- :func:`sundials_dirs` gives the SUNDIALS include and library folders of
  the scikit-sundae install, if its headers are there (the wheel ships the
  libraries; headers may come from ``$SUNDIALS_INCLUDE_DIR``).

Errors a user can act on are :class:`CompilerMissing` (names what to
install) and :class:`BuildFailed` (carries the compiler's message).
"""
import glob
import os
import shutil
import tempfile

from ..errors import Acausal2dError

try:                    # CPython's own SHA-256 (3.12+: _sha2; 3.11: _sha256): the digests
    from _sha2 import sha256 as _sha256          # of hashlib.sha256, without the OpenSSL
except ImportError:     # start-up of importing hashlib (2.8 ms of a process's first run)
    try:
        from _sha256 import sha256 as _sha256
    except ImportError:
        from hashlib import sha256 as _sha256

COMPILERS = ("cc", "gcc", "clang")
DEFAULT_FLAGS = ("-O2", "-fPIC", "-shared")
CACHE_ENV = "ACAUSAL2D_CACHE_DIR"
INSTALL_HINT = ("install a C compiler (Debian/Ubuntu: 'apt-get install gcc'; macOS: "
                "'xcode-select --install'; or set $CC to one)")


class CompilerMissing(Acausal2dError):
    """No C compiler was found."""


class BuildFailed(Acausal2dError):
    """The C compiler refused the sources."""


def find_compiler():
    """The path of a C compiler (``$CC``, ``cc``, ``gcc``, ``clang``), or None."""
    names = [os.environ["CC"]] if os.environ.get("CC") else []
    for name in names + list(COMPILERS):
        path = shutil.which(name.split()[0]) if name.strip() else None
        if path:
            return path
    return None


def require_compiler():
    """The path of a C compiler; :class:`CompilerMissing` naming what to
    install if there is none."""
    path = find_compiler()
    if path is None:
        raise CompilerMissing("No C compiler found ($CC, cc, gcc, clang): " + INSTALL_HINT)
    return path


def cache_dir():
    """The folder of compiled libraries: ``$ACAUSAL2D_CACHE_DIR``, else
    ``$XDG_CACHE_HOME/acausal2d/cbuild``, else ``~/.cache/acausal2d/cbuild``."""
    if os.environ.get(CACHE_ENV):
        return os.environ[CACHE_ENV]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "acausal2d", "cbuild")


def build_key(sources, flags=(), compiler=""):
    """SHA-256 (hex) of the sources (name -> text), the flags and the compiler."""
    h = _sha256()
    for name in sorted(sources):
        for part in (name, sources[name]):
            data = part.encode("utf-8")
            h.update(len(data).to_bytes(8, "little"))
            h.update(data)
    for part in list(flags) + [compiler]:
        h.update(b"\0" + str(part).encode("utf-8"))
    return h.hexdigest()


def build(sources, flags=(), libraries=(), library_dirs=(), include_dirs=(), name="lib"):
    """Compile ``sources`` (file name -> C text) into a shared library and
    return its path; an identical build found in :func:`cache_dir` is
    reused.  ``libraries`` are full paths or ``-l`` names; each folder of
    ``library_dirs`` is also put on the library's run path."""
    cc = require_compiler()
    args = list(DEFAULT_FLAGS) + ["-I" + d for d in include_dirs] + list(flags)
    args += ["-L" + d for d in library_dirs] + ["-Wl,-rpath," + d for d in library_dirs]
    args += [lib if os.sep in lib else "-l" + lib for lib in libraries]
    key = build_key(sources, args, cc)
    folder = cache_dir()
    target = os.path.join(folder, "%s-%s.so" % (name, key[:32]))
    if os.path.exists(target):
        return target
    os.makedirs(folder, exist_ok=True)
    _compile(cc, sources, args, folder, target)
    return target


def fingerprint(functions, *texts):
    """SHA-256 (hex) of CasADi functions (their serializations), texts, the
    CasADi version and the compiler: a key of generated code that is found
    without generating it (CasADi's code generator took 0.09 s of the belt
    drive's 0.23 s run; serializing takes a third of that)."""
    import casadi as ca
    h = _sha256()
    parts = [fn.serialize() for fn in functions if fn is not None]
    for part in parts + list(texts) + [ca.__version__, str(find_compiler()), DEFAULT_FLAGS]:
        data = str(part).encode("utf-8")
        h.update(len(data).to_bytes(8, "little"))
        h.update(data)
    return h.hexdigest()


def build_indexed(key, make, name="lib"):
    """The library built by ``make()`` (which returns its path, from
    :func:`build`), found again by ``key`` (:func:`fingerprint`) without
    calling ``make``: an index file in :func:`cache_dir` names the library.
    A missing or unreadable index, or a library that is gone, only costs the
    call to ``make``."""
    folder = cache_dir()
    index = os.path.join(folder, "%s-%s.idx" % (name, key[:32]))
    try:
        with open(index, encoding="utf-8") as fh:
            path = os.path.join(folder, os.path.basename(fh.read().strip()))
        if path.endswith(".so") and os.path.exists(path):
            return path
    except OSError:
        pass
    path = make()
    try:
        with tempfile.NamedTemporaryFile("w", dir=folder, prefix=".idx-", delete=False,
                                         encoding="utf-8") as fh:
            fh.write(os.path.basename(path))
        os.replace(fh.name, index)
    except OSError:
        pass
    return path


def _compile(cc, sources, args, folder, target):
    """Compile in a temporary folder and rename the library into ``target``.
    (``subprocess`` is imported here: a run that finds its library in the
    cache never needs it.)"""
    import subprocess
    with tempfile.TemporaryDirectory(dir=folder, prefix=".build-") as tmp:
        files = []
        for fname, text in sorted(sources.items()):
            path = os.path.join(tmp, os.path.basename(fname))
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
            if path.endswith(".c"):
                files.append(path)
        out = os.path.join(tmp, "out.so")
        cmd = [cc] + files + ["-o", out] + args
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        except (OSError, subprocess.TimeoutExpired) as exc:
            raise BuildFailed("The C compiler %s could not run: %s" % (cc, exc)) from None
        if proc.returncode != 0:
            raise BuildFailed("The C compiler %s failed (exit %d):\n%s"
                              % (cc, proc.returncode, proc.stderr.strip()[-4000:]))
        os.replace(out, target)


class SundialsDirs:
    """Where the SUNDIALS of scikit-sundae is: ``include`` (headers),
    ``lib`` (the shipped shared libraries), ``libraries`` (short name, e.g.
    ``"ida"``, -> full path) and ``version``."""

    def __init__(self, include, lib, libraries, version):
        self.include, self.lib, self.libraries, self.version = include, lib, libraries, version


def _sksundae_dir():
    """The folder of the installed ``sksundae`` package, found without
    importing it (its import pulls in scipy.optimize), or None."""
    import importlib.util
    try:
        spec = importlib.util.find_spec("sksundae")
    except (ImportError, ValueError):
        return None
    if spec is None or not spec.submodule_search_locations:
        return None
    return list(spec.submodule_search_locations)[0]


def sundials_libraries():
    """(lib folder, short name -> path) of the SUNDIALS libraries that the
    scikit-sundae wheel ships, or None if it is not installed that way."""
    pkg = _sksundae_dir()
    if pkg is None:
        return None
    folder = os.path.normpath(os.path.join(pkg, "..", "scikit_sundae.libs"))
    found = {}
    for path in sorted(glob.glob(os.path.join(folder, "libsundials_*.so*"))):
        short = os.path.basename(path)[len("libsundials_"):].split("-")[0].split(".")[0]
        found[short] = path
    return (folder, found) if found else None


def _header_version(include):
    path = os.path.join(include, "sundials", "sundials_config.h")
    try:
        with open(path, encoding="utf-8", errors="replace") as fh:
            for line in fh:
                if line.startswith("#define SUNDIALS_VERSION "):
                    return line.split('"')[1]
    except (OSError, IndexError):
        return None
    return None


def sundials_dirs():
    """The SUNDIALS include and library folders of the scikit-sundae
    install (:class:`SundialsDirs`) if its headers exist - in the package's
    ``include`` folder or in ``$SUNDIALS_INCLUDE_DIR`` - and are of the
    version of the shipped libraries; else None."""
    libs = sundials_libraries()
    if libs is None:
        return None
    version = _shipped_version()
    candidates = [os.environ.get("SUNDIALS_INCLUDE_DIR", ""),
                  os.path.join(_sksundae_dir(), "include")]
    for inc in candidates:
        if inc and os.path.exists(os.path.join(inc, "ida", "ida.h")) and \
                _header_version(inc) == version:
            return SundialsDirs(inc, libs[0], libs[1], version)
    return None


def _shipped_version():
    """The SUNDIALS version scikit-sundae was built with (its config file)."""
    pkg = _sksundae_dir()
    if pkg is None:
        return None
    path = os.path.join(pkg, "py_config.pxi")
    try:
        with open(path, encoding="utf-8") as fh:
            for line in fh:
                if line.startswith("SUNDIALS_VERSION"):
                    return line.split('"')[1]
    except (OSError, IndexError):
        return None
    return None
