"""How a library's C is compiled.

:func:`compile_library` writes the sources into a build folder in the
cache, compiles every ``.c`` file as its own translation unit - in parallel,
one compiler process per core - links the objects into a shared library and
publishes it with its digest (:mod:`~acausal2d.runtime.cstore`).

A compiler that cannot run, fails, or exits 0 without writing its output
(e.g. ``CC=/bin/true``) is a :class:`BuildFailed`
naming the compiler, the command and its output.
"""
import contextlib
import os
import shutil

from ..errors import Acausal2dError
from . import cstore

COMPILERS = ("cc", "gcc", "clang")
SCHEME = "units-5"
"""Names how sources are cut and compiled: part of every fingerprint, so a
library built another way is never found again."""
TIMEOUT = 600.0   # s per compiler process


class CompilerMissing(Acausal2dError):
    """No C compiler was found."""


class BuildFailed(Acausal2dError):
    """The C compiler refused the sources, or wrote no library."""


def find_compiler():
    """The path of a C compiler (``$CC``, ``cc``, ``gcc``, ``clang``), or None."""
    names = [os.environ["CC"]] if os.environ.get("CC") else []
    for name in names + list(COMPILERS):
        path = shutil.which(name.split()[0]) if name.strip() else None
        if path:
            return path
    return None


def workers():
    """Compiler processes run at once: the cores this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):
        return max(1, os.cpu_count() or 1)


def _failed(cc, cmd, why, output=""):
    text = "The C compiler %s %s.\ncommand: %s" % (cc, why, " ".join(cmd))
    if output.strip():
        text += "\noutput:\n" + output.strip()[-4000:]
    return BuildFailed(text)


def _run_all(cc, commands):
    """Run compiler commands, at most :func:`workers` at a time; each must
    exit 0 and write its output file (the last argument after ``-o``)."""
    import subprocess                  # compiling only: not on the way of a run
    pending, running = list(commands), []
    try:
        while pending or running:
            while pending and len(running) < workers():
                cmd = pending.pop(0)
                try:
                    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE,
                                            stderr=subprocess.STDOUT, text=True)
                except OSError as exc:
                    raise _failed(cc, cmd, "could not run (%s)" % exc) from None
                running.append((cmd, proc))
            cmd, proc = running.pop(0)
            try:
                output = proc.communicate(timeout=TIMEOUT)[0]
            except subprocess.TimeoutExpired:
                raise _failed(cc, cmd, "did not finish within %g s" % TIMEOUT) from None
            if proc.returncode != 0:
                raise _failed(cc, cmd, "failed (exit %d)" % proc.returncode, output)
            out = cmd[cmd.index("-o") + 1]
            if not os.path.isfile(out) or os.path.getsize(out) == 0:
                raise _failed(cc, cmd, "exited 0 but wrote no %s" % os.path.basename(out),
                              output)
    finally:
        for _, proc in running:
            proc.kill()
            proc.wait()


@contextlib.contextmanager
def _build_folder(folder, target):
    """A build folder for ``target``, removed afterwards."""
    tmp = cstore.build_folder(folder, target)
    try:
        yield tmp
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def compile_object(cc, fname, text, args, folder, target):
    """Compile one C text (file name ``fname``) with the flags ``args`` into
    the object file ``target``, published with its digest."""
    with _build_folder(folder, target) as tmp:
        path = os.path.join(tmp, fname)
        with open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        _run_all(cc, [[cc, "-c", path, "-o", path[:-2] + ".o"] + list(args)])
        cstore.publish(path[:-2] + ".o", target)


def compile_library(cc, sources, args, folder, target, prebuilt=()):
    """Compile ``sources`` (file name -> C text) with the flags ``args``
    (optimisation, ``-fPIC -shared``, include and link options) into
    ``target`` (see the module docstring), linked with the object files
    ``prebuilt``.  One translation unit is compiled and linked by one
    compiler process (a small model's library: 0.03 s less than two)."""
    with _build_folder(folder, target) as tmp:
        units = []
        for fname, text in sorted(sources.items()):
            path = os.path.join(tmp, os.path.basename(fname))
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(text)
            if fname.endswith(".c"):
                units.append(path)
        out = os.path.join(tmp, "out.so")
        if len(units) > 1:
            compile_flags = [a for a in args if a.startswith("-") and a != "-shared" and
                             not a.startswith(("-l", "-L", "-Wl,"))]
            objects = [u[:-2] + ".o" for u in units]
            _run_all(cc, [[cc, "-c", u, "-o", o] + compile_flags for u, o in zip(units, objects)])
            units = objects
        _run_all(cc, [[cc] + units + list(prebuilt) + ["-o", out] + list(args)])
        cstore.publish(out, target)
