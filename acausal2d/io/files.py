"""Writing result files atomically: the data goes to a temporary file in the
target's folder, which then replaces the target in one rename, so a reader
never sees a half-written file and an interrupted run leaves the old one."""
import contextlib
import os
import re
import tempfile


@contextlib.contextmanager
def atomic_path(path):
    """Context manager yielding a temporary path next to ``path`` (folders
    created); on success the temporary file is renamed to ``path``, on an
    error it is removed.  ``with atomic_path(p) as tmp: fig.savefig(tmp)``."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    stem, ext = os.path.splitext(os.path.basename(path))
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
    """Remove the files the previous run listed in ``folder``'s manifest
    (and the manifest) and temporary files a killed run left: a new run,
    successful or not, never leaves earlier results that look like its own.
    Other files are not touched."""
    import json
    path = os.path.join(folder, MANIFEST)
    try:
        with open(path, encoding="utf-8") as fh:
            listed = json.load(fh).get("files", [])
    except (OSError, ValueError, AttributeError):
        listed = []
    for name in listed if isinstance(listed, list) else []:
        if isinstance(name, str) and os.path.basename(name) == name:
            with contextlib.suppress(OSError):
                os.remove(os.path.join(folder, name))
    with contextlib.suppress(OSError):
        os.remove(path)
    with contextlib.suppress(OSError):
        for name in os.listdir(folder):
            if _TEMPORARY.match(name):          # left by a killed run (SIGKILL)
                with contextlib.suppress(OSError):
                    os.remove(os.path.join(folder, name))


_TEMPORARY = re.compile(r"^\.[^/]+\.[a-z0-9_]{8}\.tmp(\.\w+)?$")
"""Names :func:`atomic_path` gives its temporary files (mkstemp's 8 random
characters between the stem and ``.tmp``)."""


def write_manifest(folder, files, **info):
    """List ``files`` (paths in ``folder``) and ``info`` as the run's manifest."""
    import json
    names = sorted({os.path.basename(os.fspath(f)) for f in files})
    write_text(os.path.join(folder, MANIFEST),
               json.dumps(dict(info, files=names), indent=1, sort_keys=True) + "\n")


def safe_filename(name):
    """``name`` (a signal such as ``der(body.x)``) as a file name: characters
    other than letters, digits, ``.``, ``_`` and ``-`` become ``_``."""
    s = re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip()
    if not s or s.startswith("."):
        s = "_" + s
    return s
