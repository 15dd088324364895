"""An output folder written as one transaction.

Every command that writes a folder (``simulate``, ``sweep``, ``study``,
``fit``, ``optimize``, ``modes``; ``linearize``) runs inside
:class:`OutputFolder`::

    with OutputFolder(args.out, "simulate") as tx:      # checks, lock, clean-up
        res = ...                                       # the long run
        res.to_csv(tx.file("result.csv"))               # into a temporary sibling
        tx.info["model"] = "Pendulum"
    # here every file is in args.out, listed in its acausal2d-run.json

The steps, each for a failure a user met:

1. *Up front*, before anything is computed: the folder is created if
   missing and a probe file is written into it and into its parent, so a
   read-only or misspelt ``--out`` fails at once, not after the run.
2. *One run per folder*: a lock file ``.<name>.acausal2d-lock`` next to the
   folder, held with ``flock`` (the kernel releases it when the process
   ends, even by SIGKILL), names the running process; a second run into the
   same folder stops at once with :class:`OutputFolderBusy` naming it.
3. The previous run's files (those listed in the folder's manifest
   ``acausal2d-run.json``) and what a killed run left (temporary sibling
   folders, half-moved files) are removed: a failing run never leaves earlier
   results that look like its own.  Other files are not touched.  (``study``
   merges instead: it keeps the previous run's files and lists them with
   its own, so ``python model.py``, which runs ``simulate`` and then
   ``study`` into one folder, keeps both.)
4. Files are written into a temporary sibling folder ``.<name>.XXXX.part``
   (:meth:`OutputFolder.file`, :attr:`OutputFolder.path`).
5. On success the entries are moved into the folder (one rename each) and
   the manifest listing them is moved in last; SIGINT and SIGTERM are held
   back during these renames, and one that came meanwhile undoes them.  On
   any failure, including Ctrl-C (SIGINT) and SIGTERM (raised as
   :class:`Terminated` while the transaction is open), the temporary folder
   is removed and nothing of the run remains.  So exit 0 means the folder
   holds the run's complete files, and an interrupted or failed run leaves
   none (nor those of the run before) -- unless the interrupt came after
   the renames (while the summary is printed): then the complete run is
   in place.

A SIGKILL between two renames of step 5 leaves the temporary folder with
the manifest still in it; the next run into the folder reads it and removes
the entries it lists (step 3).
"""
import contextlib
import errno
import json
import os
import shutil
import signal
import tempfile
import threading
import time

from ..errors import Acausal2dError
from .files import (MANIFEST, _TEMPORARY, bounded_name, clear_previous_run, read_manifest,
                    remove_entries, write_manifest)

LOCK_SUFFIX = ".acausal2d-lock"
"""Suffix of the lock file next to an output folder (``.<name>`` + it)."""

PART_SUFFIX = ".part"
"""Suffix of the temporary sibling folder a run writes into."""

_HELD = {signal.SIGINT, signal.SIGTERM}


class OutputFolderError(Acausal2dError):
    """An output folder cannot be written (exists as a file, read-only,
    an entry of the run collides with a foreign folder)."""


class OutputFolderBusy(OutputFolderError):
    """Another process is writing into the same output folder."""


class Terminated(KeyboardInterrupt):
    """SIGTERM arrived while an output transaction was open (handled like
    Ctrl-C: the transaction is rolled back; the command exits 143)."""


class Interrupts:
    """The SIGTERM (and, where Python's own handler had it, SIGINT) handler
    of :func:`terminate_as_interrupt`: raises :class:`Terminated` or
    KeyboardInterrupt and remembers that it did, so that an interrupt
    swallowed on its way up (one that lands in a weakref callback or a
    finaliser is only printed as "Exception ignored") still ends the
    command: :meth:`raise_seen` raises it again before an output transaction
    commits, and the command line exits 130/143, never 0."""

    def __init__(self):
        self.seen = []

    def __call__(self, signum, frame):
        self.seen.append(signum)
        self.raise_seen()

    def raise_seen(self):
        """Raise the interrupt this handler has seen, if any."""
        if signal.SIGTERM in self.seen:
            raise Terminated("terminated (SIGTERM)")
        if self.seen:
            raise KeyboardInterrupt


def interrupt_is_the_end():
    """For a command whose normal end is Ctrl-C or SIGTERM (a server): the
    interrupt it caught is its end, not a swallowed one, so the command line
    exits with the command's own code."""
    for signum in (signal.SIGINT, signal.SIGTERM):
        handler = signal.getsignal(signum)
        if isinstance(handler, Interrupts):
            handler.seen.clear()


@contextlib.contextmanager
def held_signals():
    """SIGINT and SIGTERM held back (delivered when the block ends): for
    renames and clean-ups that must not be cut in half."""
    if threading.current_thread() is not threading.main_thread() or \
            not hasattr(signal, "pthread_sigmask"):
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


@contextlib.contextmanager
def terminate_as_interrupt():
    """SIGTERM raises :class:`Terminated` inside the block (where its
    disposition is the default one), so ``finally`` clauses and rollbacks
    run as for Ctrl-C; SIGINT, where Python's own handler has it, goes
    through the same :class:`Interrupts` handler.  Yields that handler (the
    enclosing block's, when nested), or None where signals are not ours
    (another thread, another SIGTERM handler); the previous handlers are
    restored afterwards."""
    current = signal.getsignal(signal.SIGTERM)
    if threading.current_thread() is not threading.main_thread() or \
            isinstance(current, Interrupts) or current is not signal.SIG_DFL:
        yield current if isinstance(current, Interrupts) else None
        return
    handler = Interrupts()
    old_int = signal.getsignal(signal.SIGINT)
    signal.signal(signal.SIGTERM, handler)
    if old_int is signal.default_int_handler:
        signal.signal(signal.SIGINT, handler)
    try:
        yield handler
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        if old_int is signal.default_int_handler:
            signal.signal(signal.SIGINT, old_int)


def _raise_held():
    """Raise the SIGINT (KeyboardInterrupt) or SIGTERM (:class:`Terminated`)
    that arrived while held back (:func:`held_signals`), taking it off the
    pending ones, so it is raised here and not again when they are let through."""
    if not hasattr(signal, "sigtimedwait") or \
            threading.current_thread() is not threading.main_thread():
        return
    taken = set()
    while True:
        info = signal.sigtimedwait(_HELD, 0)
        if info is None:
            break
        taken.add(info.si_signo)
    if signal.SIGTERM in taken:
        raise Terminated("terminated (SIGTERM)")
    if taken:
        raise KeyboardInterrupt


def check_writable(folder, what="--out"):
    """Write and remove a probe file in ``folder``: raises
    :class:`OutputFolderError` naming ``what`` if that is not possible."""
    try:
        fd, probe = tempfile.mkstemp(prefix=".acausal2d-probe.", dir=folder)
        os.close(fd)
        os.remove(probe)
    except OSError as exc:
        raise OutputFolderError("%s %s is not writable (%s); choose another folder or change "
                                "its permissions" % (what, folder, exc.strerror or exc)) from None


def _prepare(final):
    """Create ``final`` (and its parents) and check it and its parent are
    writable folders."""
    if os.path.exists(final) and not os.path.isdir(final):
        raise OutputFolderError("--out %s exists and is not a folder; choose another --out or "
                                "remove the file" % final)
    try:
        os.makedirs(final, exist_ok=True)
    except OSError as exc:
        raise OutputFolderError("cannot create the output folder --out %s (%s)"
                                % (final, exc.strerror or exc)) from None
    check_writable(final)
    check_writable(os.path.dirname(final), "the folder containing --out,")


class _Lock:
    """``flock`` on ``.<name>.acausal2d-lock`` next to the output folder;
    the file names the holder (pid, command, start time)."""

    def __init__(self, final, command):
        parent, name = os.path.split(final)
        self.path = os.path.join(parent, "." + bounded_name(name, 200) + LOCK_SUFFIX)
        self.final, self.command, self.fd = final, command, None

    def acquire(self):
        """Take the lock or raise :class:`OutputFolderBusy`."""
        try:
            import fcntl
        except ImportError:          # no flock (Windows): runs are not serialised
            return
        for _ in range(100):
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | getattr(os, "O_CLOEXEC", 0), 0o644)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                os.close(fd)
                if exc.errno not in (errno.EWOULDBLOCK, errno.EACCES):
                    raise
                raise OutputFolderBusy(self._busy_message()) from None
            if self._same_file(fd):
                break
            os.close(fd)             # the holder removed the file as we took it: again
        else:
            raise OutputFolderError("cannot lock %s (it keeps being replaced)" % self.path)
        self.fd = fd
        os.ftruncate(fd, 0)
        os.write(fd, json.dumps({"pid": os.getpid(), "command": self.command,
                                 "started": time.strftime("%Y-%m-%d %H:%M:%S %Z")}).encode())

    def _same_file(self, fd):
        try:
            st = os.stat(self.path)
        except FileNotFoundError:
            return False
        return os.path.samestat(st, os.fstat(fd))

    def _busy_message(self):
        try:
            with open(self.path, encoding="utf-8") as fh:
                holder = json.loads(fh.read(4096))
            who = "process %d (acausal2d %s, started %s)" % (
                int(holder["pid"]), holder["command"], holder["started"])
        except (OSError, ValueError, KeyError, TypeError):
            who = "another process"
        return ("--out %s is being written by %s; wait until it ends or choose another --out "
                "(lock file %s)" % (self.final, who, self.path))

    def release(self):
        """Remove the lock file and release the lock."""
        if self.fd is None:
            return
        with contextlib.suppress(OSError):
            os.remove(self.path)
        os.close(self.fd)
        self.fd = None


class OutputFolder:
    """Context manager writing the output folder ``out`` of ``command`` as
    one transaction (see the module docstring).  Inside the block write into
    :attr:`path` (or :meth:`file`); :attr:`info` goes into the manifest.
    After a successful block :meth:`final` maps a written path to its place
    in ``out`` and :attr:`entries` lists what was moved in.  ``merge``: the
    previous run's files are kept and listed with this run's (``study``
    adds its figures to those of ``simulate``); a failing run leaves them
    as they were."""

    def __init__(self, out, command, merge=False):
        self.out = os.fspath(out)
        self.merge = merge
        self._kept = []
        self.final_folder = os.path.abspath(self.out)
        self.command = command
        self.info = {}
        self.path = None
        self.entries = []
        self._lock = _Lock(self.final_folder, command)
        self._signals = None
        self._interrupts = None

    def __enter__(self):
        if not self.out.strip():
            raise OutputFolderError("--out %r names no folder (it would write into the current "
                                    "folder); give one, e.g. --out out" % self.out)
        if os.path.basename(self.final_folder) == "":
            raise OutputFolderError("--out %s: choose a folder below the root" % self.out)
        self._signals = terminate_as_interrupt()
        self._interrupts = self._signals.__enter__()
        try:
            with held_signals():            # a Ctrl-C meanwhile is raised after the block
                _prepare(self.final_folder)
                self._lock.acquire()
                self._clean()
                parent, name = os.path.split(self.final_folder)
                self.path = tempfile.mkdtemp(prefix="." + bounded_name(name, 200) + ".",
                                             suffix=PART_SUFFIX, dir=parent)
        except BaseException:
            self._rollback()
            raise
        return self

    def file(self, name):
        """Where to write the entry ``name`` of this run (in the temporary
        folder)."""
        return os.path.join(self.path, name)

    def final(self, path):
        """``path`` (written in :attr:`path`) as it is named in ``out``."""
        rel = os.path.relpath(os.fspath(path), self.path)
        return os.path.join(self.out, rel) if not rel.startswith(os.pardir) else os.fspath(path)

    def __exit__(self, kind, exc, tb):
        try:
            if kind is None:
                with held_signals():
                    if self._interrupts is not None:    # a Ctrl-C swallowed on its way up
                        self._interrupts.raise_seen()
                    self._commit()
        finally:
            self._rollback()
        return False

    def _parts(self):
        parent, name = os.path.split(self.final_folder)
        prefix = "." + bounded_name(name, 200) + "."
        return [os.path.join(parent, n) for n in os.listdir(parent)
                if n.startswith(prefix) and n.endswith(PART_SUFFIX)]

    def _clean(self):
        """The previous run's files (unless merging: then they are kept and
        listed again) and a killed run's leftovers (the lock makes every
        temporary sibling folder a dead run's)."""
        for part in self._parts():
            _remove_listed(self.final_folder, os.path.join(part, MANIFEST))
            shutil.rmtree(part, ignore_errors=True)
        if self.merge:
            self._kept = read_manifest(os.path.join(self.final_folder, MANIFEST), missing_ok=True)
        else:
            clear_previous_run(self.final_folder)

    def _commit(self):
        names = sorted(n for n in os.listdir(self.path) if not _TEMPORARY.match(n))
        for name in names:
            target = os.path.join(self.final_folder, name)
            if os.path.isdir(target) and not os.path.islink(target):
                if name not in self._kept:
                    raise OutputFolderError(
                        "--out %s already has a folder %s that no earlier run listed in its "
                        "%s; move it away or choose another --out" % (self.out, name, MANIFEST))
                shutil.rmtree(target)       # an earlier run's, replaced by this one's
        kept = [n for n in self._kept if n not in names
                and os.path.lexists(os.path.join(self.final_folder, n))]
        write_manifest(self.path, names + kept, command=self.command, **self.info)
        moved = []
        try:
            for name in names + [MANIFEST]:
                os.replace(os.path.join(self.path, name), os.path.join(self.final_folder, name))
                moved.append(name)
            _raise_held()                   # Ctrl-C during the renames: as before them
        except BaseException as exc:
            remove_entries(self.final_folder, moved)
            if kept:
                write_manifest(self.final_folder, kept, command="kept")
            if isinstance(exc, OSError):
                raise OutputFolderError("moving the results into --out %s failed (%s); nothing "
                                        "of this run is kept" % (self.out, exc)) from None
            raise
        self.entries = [os.path.join(self.out, n) for n in names]

    def _rollback(self):
        with held_signals():
            if self.path is not None:
                shutil.rmtree(self.path, ignore_errors=True)
            self._lock.release()
            if self._signals is not None:
                signals, self._signals = self._signals, None
                signals.__exit__(None, None, None)


def _remove_listed(folder, manifest):
    """Remove from ``folder`` the entries ``manifest`` (a killed run's, in
    its temporary folder) lists: moved in before the run was killed."""
    remove_entries(folder, read_manifest(manifest, missing_ok=True))

