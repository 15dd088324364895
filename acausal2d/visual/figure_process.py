"""Figures drawn by a second process that imports matplotlib while the run
goes on.

``acausal2d simulate`` writes its figures after the run, and importing
matplotlib's figure and Agg modules takes longer than compiling and
simulating a small model (measured on the 2-core machine, bytecode cached:
import 0.23 s; drawing and writing the pendulum's two PNGs 0.10 s; the
whole command without figures 0.20 s).  :meth:`FigureProcess.start` forks a
child at the start of the command; the child imports matplotlib on the
other core while the parent compiles, simulates and writes the CSV, then
draws the figures it is sent (:func:`~acausal2d.visual.plotting.draw_jobs`,
the same code as in-process; each file written atomically) and reports
their paths or the error.  The parent waits for that answer: the command
still ends with every file written, or with the drawing error.

Where there is no ``fork`` (Windows), or the process runs other threads
(forking them is unsafe), :meth:`FigureProcess.start` returns None and the
figures are drawn in-process as before.
"""
import os
import pickle
import signal
import struct
import sys
import threading

from ..errors import Acausal2dError
from . import plotting

_HEADER = struct.Struct("!Q")


def _send(fd, obj):
    data = pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL)
    view = memoryview(_HEADER.pack(len(data)) + data)
    while len(view):
        view = view[os.write(fd, view):]


def _receive(fd):
    """The next object from ``fd``, or None at end of file."""
    head = _read(fd, _HEADER.size)
    if head is None:
        return None
    data = _read(fd, _HEADER.unpack(head)[0])
    return None if data is None else pickle.loads(data)


def _read(fd, n):
    chunks, left = [], n
    while left:
        chunk = os.read(fd, min(left, 1 << 20))
        if not chunk:
            return None
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)


def _interrupt_once(signum, frame):
    """The child's SIGINT/SIGTERM handler: one KeyboardInterrupt, later
    signals ignored (a second Ctrl-C must not cut the way out short)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    raise KeyboardInterrupt


def _silent(unraisable):
    """The child's ``sys.unraisablehook``: an interrupt that lands in a
    finaliser or weakref callback (importlib's module-lock callback while
    matplotlib is imported) is not printed: the child ends silently."""


def _child(jobs_fd, answers_fd, mask):
    """The child: import matplotlib, then draw each batch of jobs it is
    sent and answer ("ok", paths) or ("error", text); ends at end of file
    or at SIGINT/SIGTERM (one KeyboardInterrupt here, also where the parent
    ignores SIGINT; ``mask``: the signal mask to restore), silently (nothing on stderr)."""
    sys.unraisablehook = _silent
    try:
        signal.signal(signal.SIGINT, _interrupt_once)
        signal.signal(signal.SIGTERM, _interrupt_once)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        _yield_cpu()
        draw = _drawing()
        while True:
            jobs = _receive(jobs_fd)
            if jobs is None:
                break
            try:
                _send(answers_fd, ("ok", draw(jobs)))
            except Exception as exc:     # noqa: BLE001 - handed to the parent, which raises
                _send(answers_fd, ("error", "%s: %s" % (type(exc).__name__, exc)))
    except BaseException:                # noqa: B036 - Ctrl-C or a broken pipe: just end
        pass


NICE = 5
"""The child's priority below the parent's: its import of matplotlib must
not slow what the parent does meanwhile (compiling a new structure's
native code on both cores); while the parent writes the CSV and the
child draws, each has a core and the priority changes nothing."""


def _yield_cpu():
    try:
        os.nice(NICE)
    except OSError:
        pass


def _drawing():
    """:func:`~acausal2d.visual.plotting.draw_jobs` with matplotlib imported
    (the import this process is for), or a function raising the import's
    error for the parent to report."""
    try:
        import matplotlib.backends.backend_agg  # noqa: F401
        import matplotlib.figure  # noqa: F401
        return plotting.draw_jobs
    except Exception as exc:             # noqa: BLE001 - e.g. matplotlib missing
        def fail(jobs, _exc=exc):
            raise _exc
        return fail


class FigureProcess:
    """A forked child that draws figures (see module docstring)."""

    def __init__(self, pid, jobs_fd, answers_fd):
        self.pid, self.jobs_fd, self.answers_fd = pid, jobs_fd, answers_fd
        self.used, self.failed = False, None

    @classmethod
    def start(cls):
        """A running :class:`FigureProcess`, or None where figures are drawn
        in-process (no ``fork``, other threads running, or fork failed)."""
        if not hasattr(os, "fork") or not hasattr(signal, "pthread_sigmask") or \
                threading.active_count() > 1:
            return None
        jobs_r, jobs_w = os.pipe()
        answers_r, answers_w = os.pipe()
        # SIGINT blocked across the fork: one sent to the child at once (close()
        # right after start()) must not raise before the child is in _child,
        # or the child would go on running the caller's code
        mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
        try:
            pid = os.fork()
        except OSError:
            pid = -1
        if pid == 0:
            try:
                os.close(jobs_w)
                os.close(answers_r)
                _child(jobs_r, answers_w, mask)
            finally:
                os._exit(0)          # never back into the caller's code
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        os.close(jobs_r)
        os.close(answers_w)
        if pid < 0:
            os.close(jobs_w)
            os.close(answers_r)
            return None
        return cls(pid, jobs_w, answers_r)

    def submit(self, jobs):
        """Hand ``jobs`` (a list of (path, figure plan)) to the child, which
        draws and writes them while the caller goes on; :meth:`collect`
        waits for the answer."""
        self.used = True
        try:
            _send(self.jobs_fd, jobs)
        except OSError as exc:
            self.failed = "the figure process ended (%s)" % exc

    def collect(self):
        """The paths the child wrote for the last :meth:`submit`.  Raises
        :class:`~acausal2d.errors.Acausal2dError` with the child's error."""
        answer = ("error", self.failed) if self.failed else None
        if answer is None:
            try:
                answer = _receive(self.answers_fd) or \
                    ("error", "the figure process ended before answering")
            except OSError as exc:
                answer = ("error", "the figure process ended (%s)" % exc)
        if answer[0] != "ok":
            raise Acausal2dError("drawing the figures failed: %s" % answer[1])
        return answer[1]

    def close(self):
        """End the child and reap it.  A child that was never sent figures
        (the run failed, or there is nothing to plot) may still be importing
        matplotlib: it is interrupted (SIGINT, so that matplotlib's own
        clean-up of its cache lock runs) rather than waited for."""
        if not self.used:
            try:
                os.kill(self.pid, signal.SIGINT)
            except ProcessLookupError:
                pass
        for fd in (self.jobs_fd, self.answers_fd):
            try:
                os.close(fd)
            except OSError:
                pass
        try:
            os.waitpid(self.pid, 0)
        except ChildProcessError:
            pass
