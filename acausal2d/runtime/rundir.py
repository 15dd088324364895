"""The temporary folder of this process: files a run needs while it lasts
(SUNDIALS' warnings log) live in one folder of their own,
``<tmp>/acausal2d-run-<pid>-XXXXXXXX`` (mode 0700, created by
``tempfile.mkdtemp``), removed when the process ends: at exit, after
Ctrl-C (SIGINT) and, on the command line, after SIGTERM (the command line
turns it into an interrupt).  A folder left behind by a process killed
outright (SIGKILL, or SIGTERM outside the command line) is removed by the
next process that makes its own: one of this user's whose process is gone.
"""
import atexit
import os
import shutil
import tempfile

PREFIX = "acausal2d-run-"
_made: list = []          # [(pid, path)] of the folder this process made


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:          # another user's process: alive
        return True
    return True


def sweep_stale(base=None):
    """Remove this user's run folders in ``base`` (the system's temporary
    folder) whose process no longer exists; returns their paths."""
    base = base or tempfile.gettempdir()
    removed = []
    try:
        names = os.listdir(base)
    except OSError:
        return removed
    for name in names:
        if not name.startswith(PREFIX):
            continue
        pid = name[len(PREFIX):].split("-", 1)[0]
        path = os.path.join(base, name)
        try:
            st = os.lstat(path)
        except OSError:
            continue
        if not pid.isdigit() or st.st_uid != os.getuid() or int(pid) == os.getpid() or \
                _alive(int(pid)) or not os.path.isdir(path) or os.path.islink(path):
            continue
        shutil.rmtree(path, ignore_errors=True)
        removed.append(path)
    return removed


def run_dir():
    """This process's temporary folder (made on first use)."""
    if _made and _made[0][0] == os.getpid():
        return _made[0][1]
    sweep_stale()
    path = tempfile.mkdtemp(prefix="%s%d-" % (PREFIX, os.getpid()))
    _made[:] = [(os.getpid(), path)]
    return path


def remove():
    """Remove this process's folder (not one a parent process made before
    forking this one)."""
    if _made and _made[0][0] == os.getpid():
        shutil.rmtree(_made[0][1], ignore_errors=True)
        _made.clear()


atexit.register(remove)
