"""The background compile of native code (:mod:`~acausal2d.runtime.tiers`):
the queue of a process's missing libraries, the worker process that builds
them (``python -c BOOT JOBFILE``, :data:`BOOT`), and
:class:`Tiering`, a run's switch from the Python path to the native loop.

The worker runs at lower priority (``os.nice``) in its own session, builds
its jobs one after the other through :func:`~acausal2d.runtime.cbuild.
build` (a lock per library: a second worker of the same structure waits,
then finds the library published) and ends; a job that fails leaves its
marker (:func:`failure_path`) with the message.
"""
import os
import pickle
import subprocess
import sys
import threading
import time

from . import cbuild, cstore
from .codegen import CHARS_PER_INSTRUCTION, QUICK_FROM

SECONDS_PER_INSTRUCTION = 2e-4
"""Expected wall time of the compile per CasADi instruction of a library
(measured, chain of 81 links: its formulation's 646 kB of C, about 25k
instructions, 10.6 s of gcc's CPU at -O1 in two units on a loaded 2-core
machine)."""
QUICK_SECONDS_PER_INSTRUCTION = 8e-5
"""The same for a large library (:data:`~acausal2d.runtime.codegen.
QUICK_FROM`): built at -O0 first where a function of it stays long, else
at -O1 with its bodies cut into parts (:mod:`~acausal2d.runtime.cparts`).
The chain of 81 links' two libraries, about 51k instructions, were
published 4.8 s after the worker's start with no run beside it (2-core
machine, medians of 3; 8.7e-5 s per instruction after the worker's own
start of 0.4 s)."""
OBJECT_SECONDS = 0.4
"""Seconds of gcc per driver object (compiled once per machine,
:func:`~acausal2d.runtime.cbuild.build_object`; measured: the model
driver with the LU 0.45 s, the rows projector with the LU 0.4 s).  On a
machine that has not compiled them yet, a small model's first run takes
the Python path and the worker compiles them."""
WORKER_START = 2.0
"""Seconds a worker needs before it compiles (Python, CasADi, the code
generator; measured 1.5-8 s for the piston engine's whole worker on a
loaded machine: with 1.0 the piston's first run waited 1.3 s in vain)."""
NATIVE_SPEEDUP = 5.0
"""The native loop against the Python path, low (measured 5-12x)."""
PAYS = 2.0
"""Waiting for the compile is chosen where the Python path's estimated rest
is this many times the compile's plus the native rest: the estimate is from
one stretch between checkpoints (measured, belt drive on a loaded machine:
23 s estimated, 9 s taken), and a wait that ends before the library is
there is lost."""
NICE = 19                # the lowest priority: the run itself is never slowed for the compile
CHUNKS = 4
"""While a library is compiled in the background, a run on the Python path
looks for it at this many checkpoints, evenly spaced over the run
(:meth:`Tiering.pause`)."""
_queue: list = []        # (key, recipe, label) not yet handed to a worker
_seen: set = set()      # keys queued by this process
_workers: list = []      # (Popen, start time, expected seconds, [(key, library name)])
HOLD = ".hold"
FIRST_HOLD = 1.0
"""A worker launched beside a run on the Python path is held
(:meth:`Tiering.held`) until the run's first checkpoint tells whether its
compile can be done before the run ends, but at most this many seconds.
Belt drive, Python path, 7 alternating processes (medians): 1.43 s alone,
1.70 s with the worker compiling beside its first quarter, 1.44 s with the
worker held (it had imported acausal2d and read its jobs; now it waits
before it imports anything, :data:`BOOT`)."""
HELD_AT_MOST = 2.0
"""A held worker (:func:`hold`) is released once the run has gone on this
many times its estimated rest (plus half a second): the estimate from the
first checkpoint was wrong (the compressor's valves start after it: 0.55 s
estimated, 6 s taken), and a formulation met later in the run (after an
event or a state re-selection) may use the library."""
_holds: dict = {}        # hold file of a worker of this process -> its open descriptor


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
    """The worker's environment: this acausal2d importable first."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([root] + [p for p in [env.get("PYTHONPATH")] if p])
    return env


def launch(label=None, held=False):
    """Start one worker for the queued builds (the model's own library
    first); one notice on stderr naming the model (``label``).  Where
    ``held``, the worker waits before its first library until
    :func:`release` (:func:`hold` from its start).  Returns whether one
    was started."""
    if not _queue:
        return False
    jobs = sorted(_queue, key=lambda job: job[1].name != "a2d_model")
    del _queue[:]
    label = label or next((lab for _, _, lab in jobs if lab), "this model")
    folder = cstore.folder()
    try:
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, "%sjob-%d-%d" % (cstore.TMP_PREFIX, os.getpid(), len(_workers)))
        with open(path, "wb") as fh:
            pickle.dump([(key, recipe) for key, recipe, _ in jobs], fh)
        _holds[path + HOLD] = os.open(path + HOLD, os.O_CREAT | os.O_RDWR, 0o600)
        if held:
            from . import posix
            posix.lock(_holds[path + HOLD])
        log = open(path + ".log", "ab")
    except OSError:
        return False
    with log:
        proc = subprocess.Popen([sys.executable, "-c", BOOT, path], env=_environment(),
                                stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                start_new_session=True)
    expected = _expected(recipe for _, recipe, _ in jobs)
    _workers.append((proc, time.perf_counter(), expected,
                     [(key, recipe.name) for key, recipe, _ in jobs]))
    cstore.notice("compiling native code for %s in the background; this run uses the "
                  "Python path" % label)
    return True


BOOT = """import fcntl, os, sys
try:
    fd = os.open(sys.argv[1] + %r, os.O_RDONLY)
    fcntl.flock(fd, fcntl.LOCK_SH)
    os.close(fd)
except OSError:
    pass
from acausal2d.runtime.background import _work
_work(sys.argv[1])
""" % HOLD
"""The worker process's program (``python -c BOOT JOBFILE``): a worker
launched held (:func:`launch`) waits before it imports anything, so that
beside the run it costs no more than Python's start.  Its wait is
:func:`_held` written out: importing that would import acausal2d first.  Belt drive, first
run: a worker that imported acausal2d and read its jobs before the hold
took 0.34-0.51 CPU seconds beside the run."""


def hold():
    """Hold this process's workers before their next step (generating or
    compiling a library): the run goes on alone where its compile cannot be
    done before it ends (:meth:`Tiering.decide`).  A worker beside the run
    slowed it although at the lowest priority (belt drive, Python path:
    1.26-1.72 s with the worker compiling, 1.14-1.47 s with it stopped at
    that decision): the two share the machine's caches and memory.  The
    hold is a lock (``fcntl.flock``), so it ends with :func:`release` at
    the run's end, or with this process.  Returns whether a worker is held."""
    from . import posix
    held = False
    for fd in list(_holds.values()):          # a copy: runs in other threads may launch
        try:
            held = posix.lock(fd)
        except OSError:
            pass
    return held


def release():
    """End :func:`hold` (the run ended); the hold files are closed."""
    for path in list(_holds):                 # a copy: runs in other threads may launch
        fd = _holds.pop(path, None)
        try:
            if fd is not None:
                os.close(fd)           # closing drops the lock
        except OSError:
            pass


def _held(path):
    """The worker: wait while the process that launched it holds it (:func:`hold`)."""
    try:
        fd = os.open(path + HOLD, os.O_RDONLY)
    except OSError:
        return
    from . import posix
    try:
        posix.lock(fd, exclusive=False)
    except OSError:
        pass
    finally:
        os.close(fd)


def compile_seconds(recipe):
    """Seconds the compile of ``recipe`` is expected to take until its
    library is published: per CasADi instruction (at -O0 first where the C
    is large, :data:`QUICK_SECONDS_PER_INSTRUCTION`), plus its driver
    objects that are not in the cache (:data:`OBJECT_SECONDS`)."""
    n = recipe.instructions()
    quick = n * CHARS_PER_INSTRUCTION >= QUICK_FROM
    rate = QUICK_SECONDS_PER_INSTRUCTION if quick else SECONDS_PER_INSTRUCTION
    return n * rate + OBJECT_SECONDS * recipe.objects_missing()


def _expected(recipes):
    """Seconds a worker is expected to take until the libraries of
    ``recipes`` are published."""
    return WORKER_START + sum(compile_seconds(recipe) for recipe in recipes)


def pending():
    """True while builds are queued or a worker started by this process runs."""
    return bool(_queue) or any(worker[0].poll() is None for worker in _workers)


def expected_left():
    """Seconds the running workers are expected to need still."""
    now = time.perf_counter()
    return max([start + exp - now for proc, start, exp, _ in _workers if proc.poll() is None]
               + [0.0])


def wait(ready, timeout):
    """Wait until ``ready()`` is true, no worker of this process runs any
    more, or ``timeout`` s passed; returns ``ready()``."""
    end = time.perf_counter() + timeout
    while not ready() and pending() and time.perf_counter() < end:
        time.sleep(0.02)
    return bool(ready())


class Tiering:
    """A run's view of the background compile: while it runs, the run on
    the Python path stops at :data:`CHUNKS` checkpoints (:meth:`pause`, at
    output times, IDA going on where nothing changes) and looks for the
    library there; :meth:`decide` stops the checks where the library cannot
    come before the run ends, and waits for the compile where that pays.
    ``notes`` say what was chosen and why (the run log)."""

    def __init__(self):
        self.notes, self.decided, self.waited = [], False, 0.0
        self.waiting = False       # a library of this run may still appear
        self.mark = None           # (simulated time, wall clock) since the speed is measured
        self.every = self.next_check = None    # the checkpoints' spacing, the next one
        self.pieces = 0            # stretches between checkpoints measured
        self.gave_up = False       # the run ends before any compile: no more checks
        self.held_until = None     # wall clock at which a held worker is released

    def active(self):
        """True while a background compile of this process runs."""
        return bool(_workers) and pending()

    def held(self, now):
        """A worker was launched held (:func:`launch`) at wall clock ``now``
        beside this run on the Python path: it waits for the first
        :meth:`decide`, at most :data:`FIRST_HOLD` s (:meth:`overdue`)."""
        self.held_until = now + FIRST_HOLD

    def tick(self):
        """:meth:`overdue` now; called on each step of IDA on the Python
        path (a call of IDA can be long) while a worker is held."""
        if self.held_until is not None:
            self.overdue(time.perf_counter())

    def begin(self, t, now, t_end):
        """A call of IDA on the Python path, looking for the library, starts
        at simulated time ``t``, wall clock ``now``; the run ends at ``t_end``."""
        self.mark = (t, now)
        if self.next_check is None:
            self.every = (t_end - t) / CHUNKS
            self.next_check = t + self.every

    def pause(self, t, t_left, now, ready):
        """At output time ``t`` of the Python path (``t_left`` s to go, wall
        clock ``now``): True where the call of IDA ends here because the
        library is there (``ready()``) or the run waited for it.  Acts at
        the checkpoints only; between them, and after :meth:`decide` gave
        up, IDA goes on (every new call re-initializes it: belt drive,
        1434 steps against 1387 when its run was cut once)."""
        if not self.waiting or self.next_check is None or t < self.next_check:
            return False
        self.next_check += self.every
        if not ready():
            self.decide(t, t_left, now, ready)
        self.mark = (t, time.perf_counter())
        return self.waiting and ready()

    def decide(self, t, t_left, now, ready):
        """At a checkpoint of the Python path (simulated time ``t``,
        ``t_left`` s to go, wall clock ``now``), from the Python path's
        estimated rest: where it is shorter than the compile, no more
        checks, and the worker is held until the run ends; from the second
        checkpoint on (the stretch before the first carries the run's
        start-up), wait (until ``ready()``) for the compile if the rest is
        :data:`PAYS` times the compile's plus the native rest.  A worker
        held since its launch (:meth:`held`) is released where its compile
        can be done first."""
        if self.decided or not self.active() or self.mark is None:
            return
        mark = self.mark
        if t <= mark[0] or now <= mark[1]:
            return
        self.pieces += 1
        rest, compile_left = (t_left / (t - mark[0])) * (now - mark[1]), expected_left()
        if rest < compile_left:
            self.decided, self.waiting, self.gave_up = True, False, True
            if hold():
                self.held_until = now + HELD_AT_MOST * rest + 0.5
            self.notes.append("Python path: it needs about %.3g s more, the compile about "
                              "%.3g s; the compile waits for the run's end" % (rest, compile_left))
            return
        if self.held_until is not None:      # held since its launch: it can finish first
            self._free()
        if self.pieces >= 2:
            self.decided = True
            self._wait_if_it_pays(rest, compile_left, ready)

    def overdue(self, now):
        """Release a held worker where the run has outlived its estimate
        (:data:`HELD_AT_MOST`) or, held since its launch, no decision came
        within :data:`FIRST_HOLD` s; called between segments (and
        by :meth:`tick`) at wall clock ``now``."""
        if self.held_until is not None and now > self.held_until:
            self._free()
            self.notes.append("the run outlived its estimate: the compile goes on beside it"
                              if self.decided else "no decision within %g s: the compile goes "
                              "on beside the run" % FIRST_HOLD)

    def _free(self):
        """Release the held worker (:func:`release`); nothing is held any more."""
        self.held_until = None
        release()

    def _wait_if_it_pays(self, rest, compile_left, ready):
        if rest > PAYS * (compile_left + rest / NATIVE_SPEEDUP):
            t0 = time.perf_counter()
            wait(ready, min(rest / 2.0, 2.0 * compile_left + 1.0))
            self.waited = time.perf_counter() - t0
            self.notes.append("compile first: the Python path needs about %.3g s more, the "
                              "compile about %.3g s; waited %.3g s for it"
                              % (rest, compile_left, self.waited))
        else:
            self.notes.append("Python path until the library appears: it needs about %.3g s "
                              "more, the compile about %.3g s" % (rest, compile_left))


def _build(key, recipe, quick):
    """Build and publish one job's library (at -O0 where ``quick``);
    False, with the failure marker left, where that fails."""
    try:
        cbuild.publish_index(key, recipe.name, recipe.make(quick))
        return True
    except Exception as exc:       # noqa: BLE001 - recorded for the next run
        cstore.write_atomic(failure_path(key, recipe.name),
                            ("%s: %s" % (type(exc).__name__, exc)).encode("utf-8"))
        return False


def _optimize(key, recipe):
    """The second build of a library published at -O0: the -O1 library
    replaces it in the index, and the -O0 file goes (a process that loaded
    it keeps its copy).  A failure keeps the -O0 library."""
    before = cbuild.lookup(key, recipe.name)
    try:
        path = recipe.make()
    except Exception:              # noqa: BLE001 - the -O0 library stays in use
        return
    cbuild.publish_index(key, recipe.name, path)
    if before is not None and before != path:
        cstore.discard(before)


BUILDS_AT_ONCE = 2
"""Libraries the worker compiles at once.  Each build runs its units in
parallel, but its units are uneven and its link is one process, so a
second build fills the idle core.  Chain of 81 links, the worker alone on
its two libraries (the next one's C generated meanwhile in both cases),
10 alternating pairs on a loaded 2-core machine: one at a time 4.58 s,
two at once 4.17 s (medians; faster in 8 of the 10 pairs)."""


class _Builds:
    """The worker's builds, each in a thread of its own (the compiler runs
    in processes; the threads only wait for it).  The C of a recipe is
    generated before, in the worker's main thread, so CasADi is used by
    one thread at a time."""

    def __init__(self):
        self.running, self.twice = [], []

    def start(self, key, recipe, generated):
        """Build ``recipe`` (published under ``key``) beside the others;
        where its C could not be ``generated``, the build meets the error
        again, in this thread, and records it."""
        if not generated:
            _build(key, recipe, False)
            return
        for build in [b for b in self.running if not b[0].is_alive()]:
            self.running.remove(build)
            self._finish(build)
        while len(self.running) >= BUILDS_AT_ONCE:
            self._finish(self.running.pop(0))
        quick = recipe.builds_twice()
        box = []
        thread = threading.Thread(target=lambda: box.append(_build(key, recipe, quick)),
                                  daemon=True, name="acausal2d-build-%s" % recipe.name)
        thread.start()
        self.running.append((thread, key, recipe, quick, box))

    def _finish(self, build):
        thread, key, recipe, quick, box = build
        thread.join()
        if quick and box == [True]:
            self.twice.append((key, recipe))

    def finish(self):
        """Wait for every build; the libraries published at -O0 first."""
        while self.running:
            self._finish(self.running.pop(0))
        return self.twice


def _generate(recipe):
    """Generate ``recipe``'s C; False where that fails (the build meets
    the error again and records it)."""
    try:
        recipe.code()
        return True
    except Exception:              # noqa: BLE001 - Recipe.make raises it again
        return False


def _work(path):
    """The worker: build each job of the job file - large ones at -O0
    first, all of them published before any is optimized
    (:meth:`~acausal2d.runtime.codegen.Recipe.builds_twice`), up to
    :data:`BUILDS_AT_ONCE` at once - and leave a marker where one fails."""
    try:
        os.nice(NICE)
    except OSError:
        pass
    with open(path, "rb") as fh:
        jobs = pickle.load(fh)
    try:
        builds = _Builds()
        for key, recipe in jobs:
            _held(path)
            if cbuild.lookup(key, recipe.name) is not None:     # another worker built it
                continue
            generated = _generate(recipe)
            _held(path)
            builds.start(key, recipe, generated)
        for key, recipe in builds.finish():
            _held(path)
            _optimize(key, recipe)
    finally:
        for p in (path, path + ".log", path + HOLD):
            try:
                os.remove(p)
            except OSError:
                pass

