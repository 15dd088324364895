"""The detached compile of native code (:mod:`~acausal2d.runtime.tiers`):
the queue of a process's missing libraries and the worker process that
builds them after the run (``python -c BOOT JOBFILE``, :data:`BOOT`).

The worker runs at the lowest priority (``os.nice``) in its own session,
builds its jobs one after the other through :func:`~acausal2d.runtime.
cbuild.build` (a lock per library: a second worker of the same structure
waits, then finds the library published) and ends; a job that fails leaves
its marker (:func:`failure_path`) with the message.  It is launched when a
run has ended (:func:`launch`), so it never shares the machine with the run
that asked for it.
"""
import contextlib
import os
import pickle
import sys
import time

from . import cbuild, cstore
from .notices import notice

NICE = 19                # the lowest priority: a later run is never slowed for the compile
_queue: list = []        # (key, recipe, label) not yet handed to a worker
_seen: set = set()      # keys queued by this process
_workers: list = []      # the worker processes (Popen) this process launched


def failure_path(key, name):
    """The marker a failed background compile of ``key`` leaves."""
    return os.path.join(cstore.folder(), "%s-%s.failed" % (name, key[:32]))


def queue(key, recipe, label=None):
    """Queue the background build of ``recipe`` (fingerprint ``key``);
    :func:`launch` starts the worker."""
    if key not in _seen and cbuild.find_compiler() is not None:
        _seen.add(key)
        _queue.append((key, recipe, label))


def _environment():
    """The worker's environment: this acausal2d importable first, the
    cache folder this process uses (it may be a private fallback)."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in [env.get("PYTHONPATH")] if p])
    env[cstore.CACHE_ENV] = cstore.folder()        # the folder this process checked and uses
    return env


def launch(label=None):
    """Start one worker for the queued builds (the model's own library
    first), detached from this process; one notice on stderr naming the
    model (``label``).  Returns whether one was started."""
    if not _queue:
        return False
    jobs = sorted(_queue, key=lambda job: job[1].name != "a2d_model")
    del _queue[:]
    import subprocess                  # a worker started: not on the way of a run
    label = label or next((lab for _, _, lab in jobs if lab), "this model")
    folder = cstore.folder()
    try:
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, "%sjob-%d-%d" % (cstore.TMP_PREFIX, os.getpid(), len(_workers)))
        with open(path, "wb") as fh:
            pickle.dump([(key, recipe) for key, recipe, _ in jobs], fh)
        log = open(path + ".log", "ab")
    except OSError:
        return False
    with log:
        proc = subprocess.Popen([sys.executable, "-c", BOOT, path], env=_environment(),
                                stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                start_new_session=True)
    _workers.append(proc)
    notice("compiling native code for %s in the background, for the runs that follow"
           % label, first_run=True)
    return True


BOOT = """import sys
from acausal2d.runtime.background import _work
_work(sys.argv[1])
"""
"""The worker process's program (``python -c BOOT JOBFILE``)."""


def pending():
    """True while builds are queued or a worker started by this process runs."""
    return bool(_queue) or any(proc.poll() is None for proc in _workers)


def wait(timeout):
    """Wait until no worker of this process runs any more, at most
    ``timeout`` s in all; returns True where none runs (tests, benchmarks:
    a run never waits for a worker)."""
    import subprocess
    end = time.monotonic() + timeout
    try:
        for proc in list(_workers):
            proc.wait(timeout=max(0.0, end - time.monotonic()))
    except subprocess.TimeoutExpired:
        return False
    return True


def _build(key, recipe):
    """Build and publish one job's library; False, with the failure marker
    left, where that fails."""
    try:
        cbuild.publish_index(key, recipe.name, recipe.make())
        return True
    except Exception as exc:       # noqa: BLE001 - recorded for the next run
        cstore.write_atomic(failure_path(key, recipe.name),
                            ("%s: %s" % (type(exc).__name__, exc)).encode("utf-8"))
        return False


BUILDS_AT_ONCE = 2
"""Libraries the worker compiles at once.  Each build runs its units in
parallel, but its units are uneven and its link is one process, so a
second build fills the idle core.  Chain of 81 links, the worker alone on
its two libraries (the next one's C generated meanwhile in both cases),
10 alternating pairs on a loaded 2-core machine: one at a time 4.58 s,
two at once 4.17 s (medians; faster in 8 of the 10 pairs).  The C of each
recipe is generated in the worker's main thread, so CasADi is used by one
thread at a time; the threads of the pool only wait for the compiler."""


def _generate(recipe):
    """Generate ``recipe``'s C; False where that fails (the build meets
    the error again and records it)."""
    try:
        recipe.code()
        return True
    except Exception:              # noqa: BLE001 - Recipe.make raises it again
        return False


def _work(path):
    """The worker: build each job of the job file, up to
    :data:`BUILDS_AT_ONCE` at once, and leave a marker where one fails."""
    with contextlib.suppress(OSError):
        os.nice(NICE)
    from concurrent.futures import ThreadPoolExecutor      # the worker's process only
    with open(path, "rb") as fh:
        jobs = pickle.load(fh)
    try:
        with ThreadPoolExecutor(BUILDS_AT_ONCE, thread_name_prefix="acausal2d-build") as pool:
            for key, recipe in jobs:
                if cbuild.lookup(key, recipe.name) is not None:     # another worker built it
                    continue
                if _generate(recipe):       # CasADi in this thread only; the compilers beside
                    pool.submit(_build, key, recipe)
                else:                       # the build meets the error again and records it
                    _build(key, recipe)
    finally:
        for p in (path, path + ".log"):
            with contextlib.suppress(OSError):
                os.remove(p)

