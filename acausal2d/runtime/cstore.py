"""The native cache on disk, verified: every compiled library
has its SHA-256 beside it (``<library>.sha256``), written when it is
published and checked before it is loaded, so a truncated file (SIGBUS at
``dlopen``), a flipped byte in its code (SIGILL) or in its constants (wrong
numbers, exit 0) is found before the dynamic loader sees it: the library is
removed and built again, with one line on stderr.

- :func:`folder`: the cache folder in use, the configured one
  (:func:`cache_dir`) or, where that cannot be written or is not private
  (owned by the user, mode 0700, not a link: :mod:`~acausal2d.runtime.private_dir`,
  so that no other user can plant a library, a digest or a job in it), a
  private fallback (one line on stderr) - never the slow path because of a
  read-only home;
- :func:`publish`: a library and its digest moved into place atomically;
- :func:`locked`: one builder per library at a time (``flock`` on
  ``<library>.lock``, :mod:`~acausal2d.runtime.posix`; a second waits, then finds the library built);
- :func:`sweep`: build folders and temporary files left by a killed build
  removed (those whose lock nobody holds).
"""
import contextlib
import os
import tempfile
import shutil
import time

from . import private_dir
from . import posix
from .notices import WITHOUT_LIBRARY, notice

try:                    # CPython's own SHA-256 (3.12+: _sha2; 3.11: _sha256): the digests
    from _sha2 import sha256 as _sha256          # of hashlib.sha256, without the OpenSSL
except ImportError:     # start-up of importing hashlib (2.8 ms of a process's first run)
    try:
        from _sha256 import sha256 as _sha256
    except ImportError:
        from hashlib import sha256 as _sha256

CACHE_ENV = "ACAUSAL2D_CACHE_DIR"
DIGEST = ".sha256"
LOCK = ".lock"
BUILD_PREFIX = ".build-"
TMP_PREFIX = ".tmp-"
def cache_dir():
    """The configured folder of compiled libraries: ``$ACAUSAL2D_CACHE_DIR``,
    else ``$XDG_CACHE_HOME/acausal2d/cbuild``, else ``~/.cache/acausal2d/cbuild``
    (:func:`folder` is the one used: this one, or a writable fallback)."""
    if os.environ.get(CACHE_ENV):
        return os.environ[CACHE_ENV]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "acausal2d", "cbuild")


def fallback_folders():
    """The folders tried, in order, where the configured cache cannot be
    used: ``$XDG_RUNTIME_DIR/acausal2d-cbuild`` (a folder of the user's own
    that others cannot enter) and ``acausal2d-cbuild-<uid>`` in the
    temporary directory (checked as the configured one: a folder another
    user created there is refused); :func:`folder` falls back on a new
    private folder of this process (``mkdtemp``) after them."""
    found = []
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    if runtime and os.path.isabs(runtime):
        found.append(os.path.join(runtime, "acausal2d-cbuild"))
    found.append(os.path.join(tempfile.gettempdir(), "acausal2d-cbuild-%d" % os.getuid()))
    return found


_own: list = []        # the private folder made for this process (last resort), once
NOWHERE = os.path.join(os.devnull, "acausal2d-cbuild")
"""The folder of a process that has none it may use: nothing can be
written or loaded there, so native code is not used."""


def _own_folder():
    if not _own:
        try:
            _own.append(tempfile.mkdtemp(prefix="acausal2d-cbuild-%d-" % os.getuid()))
        except OSError:
            _own.append(NOWHERE)
    return _own[0]


def folder():
    """The cache folder in use (see the module docstring): the configured
    one where it is private (:mod:`~acausal2d.runtime.private_dir`) and
    writable, else the first usable fallback (:func:`fallback_folders`),
    with one line on stderr saying why and what to do."""
    want = cache_dir()
    why = private_dir.problem(want)
    if why is None:
        return want
    for other in [f for f in fallback_folders() if f != want] + [None]:
        if other is None:
            other = _own_folder()
            if other == NOWHERE:
                notice("%s; no private folder could be made for native code, so %s"
                       % (why, WITHOUT_LIBRARY))
                return other
        else:
            refused = private_dir.problem(other)
            if refused is not None:
                if refused.unsafe:            # said: someone may be planting code there
                    notice(refused.message)
                continue
        notice("%s; using %s instead (set $%s to a private folder of your own)"
               % (why, other, CACHE_ENV))
        return other


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


def file_digest(path):
    """SHA-256 (hex) of a file's bytes."""
    h = _sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _identity(st):
    """What the cheap check at load compares (:func:`verified`): size,
    modification time (ns), inode and mode of a file's ``os.stat``."""
    return "%d %d %d %o" % (st.st_size, st.st_mtime_ns, st.st_ino, st.st_mode)


def _record(path):
    """(digest, identity) recorded beside ``path``: the digest file's first
    line, and its second (:func:`_identity` at publish), either None."""
    try:
        with open(path + DIGEST, encoding="ascii") as fh:
            lines = fh.read(400).splitlines()
    except (OSError, UnicodeDecodeError):
        return None, None
    digest = lines[0].strip() if lines else ""
    if len(digest) != 64:
        return None, None
    return digest, (lines[1].strip() if len(lines) > 1 else None)


def recorded(path):
    """The digest recorded for ``path``, or None (missing or unreadable)."""
    return _record(path)[0]


def _write_record(path, digest, st):
    """Record ``digest`` and the identity of ``st`` beside ``path``."""
    write_atomic(path + DIGEST, ("%s\n%s\n" % (digest, _identity(st))).encode("ascii"))


def verified(path, full=False):
    """True where ``path`` exists and its bytes have the recorded digest.
    The check at load is cheap: where the file's size, modification time,
    inode and mode are those recorded at publish (:func:`publish`), its
    bytes are taken as published; where any of them changed (or ``full``,
    ``acausal2d cache verify``) its SHA-256 is computed and compared, and a
    match records the new identity.  A library that exists but does not
    match (or has no digest, or cannot be read) is removed, with one line
    on stderr; False then."""
    try:
        st = os.stat(path)
    except OSError:
        return False
    if not private_dir.ours(path) or (os.path.lexists(path + DIGEST)
                                      and not private_dir.ours(path + DIGEST)):
        notice("the cached library %s (or its digest) is not a file of your own that only "
               "you can write; it is removed and built again" % path)
        discard(path)
        return False
    want, identity = _record(path)
    if not full and want is not None and identity == _identity(st) and \
            os.access(path, os.R_OK):
        return True
    try:
        got = file_digest(path)
    except FileNotFoundError:
        return False
    except OSError as exc:
        got, why = None, "unreadable: %s" % exc.strerror
    if want is not None and got == want:
        with contextlib.suppress(OSError):           # an unwritable folder: checked in full
            _write_record(path, want, st)
        return True
    if got is not None:
        why = "no digest recorded" if want is None else "its SHA-256 does not match the " \
            "recorded one"
    notice("the cached library %s is damaged (%s); rebuilding it" % (path, why))
    discard(path)
    return False


def discard(path):
    """Remove a library and its digest (errors ignored)."""
    for p in (path, path + DIGEST):
        try:
            os.remove(p)
        except OSError:
            pass


def write_atomic(path, data):
    """Write bytes to ``path`` through a temporary sibling and a rename."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix=TMP_PREFIX)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def publish(built, target):
    """Move the library ``built`` to ``target`` with its digest and its
    identity (:func:`verified`; the rename keeps size, times, inode and
    mode), the record first: a reader never finds a library without one."""
    _write_record(target, file_digest(built), os.stat(built))
    os.replace(built, target)


@contextlib.contextmanager
def locked(target, wait=True):
    """Hold the lock of library ``target`` (yields True), or, with
    ``wait=False`` where another process holds it, yield False at once.
    A lock file that cannot be created (read-only folder) locks nothing."""
    try:
        fh = open(target + LOCK, "a")
    except OSError:
        yield True
        return
    with fh:
        if not posix.lock(fh, wait=wait):
            yield False
            return
        try:
            yield True
        finally:
            posix.unlock(fh)


def busy(target):
    """True where a process holds the lock of ``target`` (builds it now)."""
    with locked(target, wait=False) as got:
        return not got


def build_folder(folder, target):
    """A new build folder for ``target`` (named by it: :func:`sweep`)."""
    return tempfile.mkdtemp(dir=folder, prefix="%s%s-" % (BUILD_PREFIX, os.path.basename(target)))


def sweep(folder, older_than=600.0):
    """Remove build folders whose library's lock nobody holds, and
    temporary files older than ``older_than`` seconds (a build killed
    with SIGKILL leaves them)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    now = time.time()
    for name in names:
        path = os.path.join(folder, name)
        if name.startswith(BUILD_PREFIX):
            lib = name[len(BUILD_PREFIX):].rsplit("-", 1)[0]
            if not busy(os.path.join(folder, lib)):
                shutil.rmtree(path, ignore_errors=True)
        elif name.startswith(TMP_PREFIX):
            with contextlib.suppress(OSError):
                if now - os.path.getmtime(path) > older_than:
                    os.remove(path)


SUFFIXES = (".so", ".o", DIGEST, LOCK, ".idx", ".failed")


def entries():
    """([(library file name, bytes)] of the cache folder, total bytes of the
    cache's files: libraries, digests, indexes, locks, failure markers and
    leftovers of builds)."""
    where = folder()
    try:
        names = sorted(os.listdir(where))
    except OSError:
        return [], 0
    libs, total = [], 0
    for name in names:
        path = os.path.join(where, name)
        if not _ours(name):
            continue
        size = _size(path)
        total += size
        if name.endswith(".so"):
            libs.append((name, size))
    return libs, total


def verify_all():
    """Check every library and object of the cache folder in full (its
    SHA-256, :func:`verified` with ``full``; a damaged one is removed, one
    line on stderr each); returns (files checked, names of those removed)."""
    where = folder()
    try:
        names = sorted(n for n in os.listdir(where) if n.endswith((".so", ".o")))
    except OSError:
        return 0, []
    damaged = [name for name in names if not verified(os.path.join(where, name), full=True)]
    return len(names), damaged


def _ours(name):
    return name.endswith(SUFFIXES) or name.startswith((BUILD_PREFIX, TMP_PREFIX))


def _size(path):
    if os.path.isdir(path):
        return sum(_size(os.path.join(path, n)) for n in os.listdir(path))
    try:
        return os.path.getsize(path)
    except OSError:
        return 0


def clear():
    """Remove the cache's files (not those of a build running now: their
    library's lock is held); returns (files removed, files kept)."""
    where = folder()
    try:
        names = os.listdir(where)
    except OSError:
        return 0, 0
    removed = kept = 0
    for name in names:
        if not _ours(name):
            continue
        path = os.path.join(where, name)
        lib = name[len(BUILD_PREFIX):].rsplit("-", 1)[0] if name.startswith(BUILD_PREFIX) else \
            name[:-len(LOCK)] if name.endswith(LOCK) else None
        if lib is not None and busy(os.path.join(where, lib)):
            kept += 1
            continue
        try:
            shutil.rmtree(path) if os.path.isdir(path) else os.remove(path)
            removed += 1
        except OSError:
            kept += 1
    return removed, kept
