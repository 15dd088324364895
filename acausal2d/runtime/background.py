"""The background compile of native code (:mod:`~acausal2d.runtime.tiers`):
the queue of a process's missing libraries, the worker process that builds
them (``python -m acausal2d.runtime.background JOBFILE``), and
:class:`Tiering`, a run's switch from the Python path to the native loop.

The worker runs at lower priority (``os.nice``) in its own session, builds
its jobs one after the other through :func:`~acausal2d.runtime.cbuild.
build` (a lock per library: a second worker of the same structure waits,
then finds the library published) and ends; a job that fails leaves its
marker (:func:`failure_path`) with the message.
"""
import os
import pickle
import sys
import time
import subprocess

from . import cbuild, cstore

SECONDS_PER_INSTRUCTION = 2e-4
"""Expected wall time of the compile per CasADi instruction of a library
(measured, chain of 81 links: its formulation's 646 kB of C, about 25k
instructions, 10.6 s of gcc's CPU at -O1 in two units on a loaded 2-core
machine)."""
WORKER_START = 2.0
"""Seconds a worker needs before it compiles (Python, CasADi, the code
generator; measured 1.5-8 s for the piston engine's whole worker on a
loaded machine: with 1.0 the piston's first run waited 1.3 s in vain)."""
NATIVE_SPEEDUP = 5.0
"""The native loop against the Python path, low (measured 5-12x)."""
PAYS = 2.0
"""Waiting for the compile is chosen where the Python path's estimated rest
is this many times the compile's plus the native rest: the estimate is from
one piece (measured, belt drive on a loaded machine: 23 s estimated, 9 s
taken), and a wait that ends before the library is there is lost."""
NICE = 19                # the lowest priority: the run itself is never slowed for the compile
CHUNKS = 4
"""While a library is compiled in the background, a run advances in this
many pieces of its output grid and looks for the library between them."""
_queue: list = []        # (key, recipe, label) not yet handed to a worker
_seen: set = set()      # keys queued by this process
_workers: list = []      # (Popen, start time, expected seconds)


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


def launch(label=None):
    """Start one worker for the queued builds (the model's own library
    first); one notice on stderr naming the model (``label``).  Returns
    whether one was started."""
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
        log = open(path + ".log", "ab")
    except OSError:
        return False
    with log:
        proc = subprocess.Popen([sys.executable, "-m", __name__, path], env=_environment(),
                                stdin=subprocess.DEVNULL, stdout=log, stderr=log,
                                start_new_session=True)
    expected = _expected(recipe for _, recipe, _ in jobs)
    _workers.append((proc, time.perf_counter(), expected))
    cstore.notice("compiling native code for %s in the background; this run uses the "
                  "Python path" % label)
    return True


def _expected(recipes):
    """Seconds a worker is expected to take for ``recipes``."""
    return WORKER_START + SECONDS_PER_INSTRUCTION * sum(r.instructions() for r in recipes)


def pending():
    """True while builds are queued or a worker started by this process runs."""
    return bool(_queue) or any(proc.poll() is None for proc, _, _ in _workers)


def expected_left():
    """Seconds the running workers are expected to need still."""
    now = time.perf_counter()
    return max([start + exp - now for proc, start, exp in _workers if proc.poll() is None]
               + [0.0])


def wait(ready, timeout):
    """Wait until ``ready()`` is true, no worker of this process runs any
    more, or ``timeout`` s passed; returns ``ready()``."""
    end = time.perf_counter() + timeout
    while not ready() and pending() and time.perf_counter() < end:
        time.sleep(0.02)
    return bool(ready())


class Tiering:
    """A run's view of the background compile: while it runs the run goes
    in :data:`CHUNKS` pieces (:meth:`outputs`), and after the first piece
    :meth:`decide` waits for the compile where that pays.  ``notes`` say
    what was chosen and why (the run log)."""

    def __init__(self):
        self.notes, self.decided, self.waited = [], False, 0.0
        self.waiting = False       # a library of this run may still appear
        self.mark = None           # (simulated time, wall clock) at the end of the last piece

    def active(self):
        """True while a background compile of this process runs."""
        return bool(_workers) and pending()

    def outputs(self, outputs, n_total):
        """The output times of the next piece of a run."""
        size = max(1, -(-n_total // CHUNKS))
        return outputs[:size]

    def decide(self, t, t_left, now, ready):
        """At the end of a piece on the Python path (simulated time ``t``,
        ``t_left`` s to go, wall clock ``now``): from the second piece on
        (the first carries the run's start-up), wait (until ``ready()``)
        for the compile if the Python path's estimated rest is :data:`PAYS`
        times the compile's plus the native rest."""
        if self.decided or not self.active():
            return
        mark, self.mark = self.mark, (t, now)
        if mark is None or t <= mark[0] or now <= mark[1]:
            return
        self.decided = True
        t_done, wall = t - mark[0], now - mark[1]
        rest, compile_left = t_left / t_done * wall, expected_left()
        if rest > PAYS * (compile_left + rest / NATIVE_SPEEDUP):
            t0 = time.perf_counter()
            wait(ready, min(rest / 2.0, 2.0 * compile_left + 1.0))
            self.waited = time.perf_counter() - t0
            self.notes.append("compile first: the Python path needs about %.3g s more, the "
                              "compile about %.3g s; waited %.3g s for it"
                              % (rest, compile_left, self.waited))
        else:
            self.notes.append("Python path: it needs about %.3g s more, the compile about "
                              "%.3g s" % (rest, compile_left))


def _work(path):
    """The worker: build each job of the job file, leave a marker where
    one fails."""
    try:
        os.nice(NICE)
    except OSError:
        pass
    with open(path, "rb") as fh:
        jobs = pickle.load(fh)
    try:
        for key, recipe in jobs:
            try:
                cbuild.build_indexed(key, recipe.make, recipe.name)
            except Exception as exc:       # noqa: BLE001 - recorded for the next run
                cstore.write_atomic(failure_path(key, recipe.name),
                                    ("%s: %s" % (type(exc).__name__, exc)).encode("utf-8"))
    finally:
        for p in (path, path + ".log"):
            try:
                os.remove(p)
            except OSError:
                pass


if __name__ == "__main__":
    _work(sys.argv[1])
