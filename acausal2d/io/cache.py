"""Results of slow, deterministic computations kept on disk between
processes (e.g. the synthesis of a non-circular pulley pair), keyed by a
hash of everything they depend on.

The folder is ``$ACAUSAL2D_CACHE_DIR``, else ``$XDG_CACHE_HOME/acausal2d``,
else ``~/.cache/acausal2d`` (the compiled C of the native runtime lives in
its ``cbuild`` subfolder, or in ``$ACAUSAL2D_CACHE_DIR`` itself:
:func:`acausal2d.runtime.cbuild.cache_dir`).  A missing, unreadable or corrupt entry is
recomputed; a folder that cannot be written only costs the time of the
computation.  Entries are written atomically (:func:`~.files.atomic_path`).
"""
import contextlib
import hashlib
import os
import zipfile

import numpy as np

from .files import atomic_path
from ..runtime.cbuild import CACHE_ENV


def cache_dir():
    """The folder of the disk cache (see the module docstring)."""
    if os.environ.get(CACHE_ENV):
        return os.environ[CACHE_ENV]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "acausal2d")


def cache_path(name, key):
    """The file of entry ``name`` for ``key`` (any value with a stable
    ``repr``: numbers, strings, tuples of them)."""
    digest = hashlib.sha256(repr(key).encode("utf-8")).hexdigest()[:24]
    return os.path.join(cache_dir(), "%s-%s.npz" % (name, digest))


def cached_arrays(name, key, compute):
    """The dict of numpy arrays ``compute()`` returns, read from the disk
    cache if an entry for ``(name, key)`` exists, else computed and stored.
    ``key`` must hold every input of ``compute`` (and a version of its code)."""
    path = cache_path(name, key)
    with contextlib.suppress(OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        with np.load(path, allow_pickle=False) as data:
            return {k: data[k] for k in data.files}
    arrays = compute()
    with contextlib.suppress(OSError):
        with atomic_path(path) as tmp:
            with open(tmp, "wb") as fh:
                np.savez(fh, **arrays)
    return arrays
