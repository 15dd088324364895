"""Temporary stand-in for acausal2d.runtime.cbuild (compiler discovery)."""
import os
import shutil
import subprocess

from ..errors import Acausal2dError


def find_compiler():
    """Path of a C compiler ($CC, cc, gcc, clang) or an error saying none was found."""
    for name in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if name and shutil.which(name):
            return shutil.which(name)
    raise Acausal2dError("no C compiler found (tried $CC, cc, gcc, clang): install one "
                         "(e.g. apt-get install gcc) or set CC")


def build_shared(sources, out, include_dirs=()):
    """Compile C ``sources`` into the shared library ``out``."""
    cmd = [find_compiler(), "-shared", "-fPIC", "-O2", "-o", out] + list(sources) + \
        ["-I" + d for d in include_dirs] + ["-lm"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        raise Acausal2dError("the C compiler failed on the FMU sources:\n" + proc.stderr[-2000:])
    return out
