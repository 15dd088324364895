"""Writing result files atomically: the data goes to a temporary file in the
target's folder, which then replaces the target in one rename, so a reader
never sees a half-written file and an interrupted run leaves the old one."""
import contextlib
import hashlib
import json
import os
import re
import tempfile
import shutil
import numpy as np

from ..errors import Acausal2dError

NAME_LIMIT = 120
"""Longest file name (UTF-8 bytes) the writers make: longer names (a plot
named after many joined signals) are shortened with a hash
(:func:`bounded_name`), which leaves room for the temporary names under the
file systems' 255-byte limit."""

JSON_MAX_DEPTH = 64
"""Deepest nesting of arrays and objects :func:`read_json` accepts."""

JSON_MAX_BYTES = 64 << 20
"""Largest JSON file :func:`read_json` reads (64 MiB)."""


@contextlib.contextmanager
def atomic_path(path):
    """Context manager yielding a temporary path next to ``path`` (folders
    created); on success the temporary file is renamed to ``path``, on an
    error it is removed.  ``with atomic_path(p) as tmp: fig.savefig(tmp)``."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    stem, ext = os.path.splitext(bounded_name(os.path.basename(path)))
    fd, tmp = tempfile.mkstemp(prefix="." + stem + ".", suffix=".tmp" + ext, dir=folder)
    os.close(fd)
    os.chmod(tmp, 0o666 & ~_umask())         # mkstemp's 0600 -> what open() would give
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def _umask():
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def write_text(path, text):
    """Write ``text`` (UTF-8) to ``path`` atomically; returns ``path``."""
    with atomic_path(path) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
    return path


MANIFEST = "acausal2d-run.json"
"""File in an output folder listing what the last run wrote there."""


def clear_previous_run(folder):
    """Remove the entries the previous run listed in ``folder``'s manifest
    (and the manifest) and temporary files a killed run left: a new run,
    successful or not, never leaves earlier results that look like its own.
    Other files are not touched."""
    path = os.path.join(folder, MANIFEST)
    remove_entries(folder, read_manifest(path, missing_ok=True))
    with contextlib.suppress(OSError):
        os.remove(path)


def remove_entries(folder, names):
    """Remove the files and folders ``names`` of ``folder`` (those gone already
    are skipped)."""
    for name in names:
        target = os.path.join(folder, name)
        if os.path.isdir(target) and not os.path.islink(target):
            shutil.rmtree(target, ignore_errors=True)
        else:
            with contextlib.suppress(OSError):
                os.remove(target)
    with contextlib.suppress(OSError):
        for name in os.listdir(folder):
            if _TEMPORARY.match(name):          # left by a killed run (SIGKILL)
                with contextlib.suppress(OSError):
                    os.remove(os.path.join(folder, name))


def read_manifest(path, missing_ok=False):
    """The entry names a run's manifest ``path`` lists (plain names in its
    folder only); [] for a missing file if ``missing_ok``.  A file that is
    not a manifest raises :class:`~acausal2d.errors.Acausal2dError` naming
    it and the position."""
    if missing_ok and not os.path.exists(path):
        return []
    data = read_json(path, what="the run manifest")
    listed = data.get("files") if isinstance(data, dict) else None
    if not isinstance(listed, list):
        raise Acausal2dError("%s is not a manifest of an acausal2d run (no list 'files'); "
                             "remove it" % path)
    return [n for n in listed if isinstance(n, str) and n not in ("", ".", "..")
            and os.path.basename(n) == n]


def read_json(path, error=Acausal2dError, what="JSON file"):
    """The JSON document in ``path``, read with limits: at most
    :data:`JSON_MAX_BYTES`, strict UTF-8, nesting at most
    :data:`JSON_MAX_DEPTH`.  Violations and syntax errors raise ``error``
    naming the file, line and column."""
    with open(path, "rb") as fh:
        raw = fh.read(JSON_MAX_BYTES + 1)
    if len(raw) > JSON_MAX_BYTES:
        raise error("%s %s is larger than %d MiB" % (what, path, JSON_MAX_BYTES >> 20))
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        line, col = _line_column(raw[:exc.start].decode("utf-8", "replace"))
        raise error("%s %s is not UTF-8 text: byte 0x%02x at line %d, column %d (byte %d)"
                    % (what, path, raw[exc.start], line, col, exc.start)) from None
    deep = _too_deep(text)
    if deep is not None:
        line, col = _line_column(text[:deep])
        raise error("%s %s nests arrays/objects deeper than %d levels (line %d, column %d)"
                    % (what, path, JSON_MAX_DEPTH, line, col))
    try:
        return json.loads(text)
    except json.JSONDecodeError as exc:
        raise error("%s is no valid JSON: %s (line %d, column %d)"
                    % (path, exc.msg, exc.lineno, exc.colno)) from None
    except RecursionError:               # not reached after _too_deep; kept as a guard
        raise error("%s %s nests too deeply" % (what, path)) from None


def _line_column(prefix):
    return prefix.count("\n") + 1, len(prefix) - (prefix.rfind("\n") + 1) + 1


def _too_deep(text):
    """Index of the first bracket nesting deeper than JSON_MAX_DEPTH in
    ``text`` (brackets inside strings ignored), or None."""
    plain = re.sub(r'"(?:[^"\\]|\\.)*"', lambda m: " " * len(m.group()), text)
    codes = np.frombuffer(plain.encode("utf-32-le"), dtype=np.uint32)
    step = np.isin(codes, (0x5B, 0x7B)).astype(np.int64) - np.isin(codes, (0x5D, 0x7D))
    depth = np.cumsum(step)
    over = np.flatnonzero(depth > JSON_MAX_DEPTH)
    return int(over[0]) if len(over) else None


_TEMPORARY = re.compile(r"^\.[^/]+\.[a-z0-9_]{8}\.tmp(\.\w+)?$")
"""Names :func:`atomic_path` gives its temporary files (mkstemp's 8 random
characters between the stem and ``.tmp``)."""


def write_manifest(folder, files, **info):
    """List ``files`` (paths in ``folder``) and ``info`` as the run's manifest."""
    names = sorted({os.path.basename(os.fspath(f)) for f in files})
    write_text(os.path.join(folder, MANIFEST),
               json.dumps(dict(info, files=names), indent=1, sort_keys=True) + "\n")


def safe_filename(name):
    """``name`` (a signal such as ``der(body.x)``) as a file name: characters
    other than letters, digits, ``.``, ``_`` and ``-`` become ``_``; a stem
    longer than :data:`NAME_LIMIT` minus 8 bytes (room for an extension such
    as ``.png``) is shortened with a hash (:func:`bounded_name`)."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip()
    if not s or s.startswith("."):
        s = "_" + s
    return bounded_name(s, NAME_LIMIT - 8, keep_extension=False)


def bounded_name(name, limit=NAME_LIMIT, keep_extension=True):
    """``name`` if it has at most ``limit`` UTF-8 bytes, else its beginning,
    ``-`` and 16 hex digits of its SHA-256, followed by its extension if
    ``keep_extension`` and that is short: distinct long names stay distinct."""
    if len(name.encode("utf-8")) <= limit:
        return name
    stem, ext = os.path.splitext(name)
    if not keep_extension or len(ext.encode("utf-8")) > 16:
        stem, ext = name, ""
    tag = "-" + hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:16]
    keep = limit - len(tag) - len(ext.encode("utf-8"))
    head = stem.encode("utf-8")[:keep].decode("utf-8", "ignore")
    return head + tag + ext
