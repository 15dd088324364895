"""The POSIX-only parts of the runtime in one place: file locks
(``fcntl.flock``) of the native cache and of the background compile.

``fcntl`` is imported inside these functions only, where a lock is taken
(never on the way to a simulation on the Python path): where it is missing
(Windows), a lock locks nothing (:func:`lock` returns True, as for a lock
file that cannot be made), and the Python path runs as everywhere.
"""


def _fcntl():
    """The ``fcntl`` module, or None where the platform has none."""
    try:
        import fcntl
    except ImportError:
        return None
    return fcntl


def lock(fd, exclusive=True, wait=True):
    """Take an ``flock`` on the open file (or descriptor) ``fd``: exclusive
    or shared, waiting for it or not.  Returns False where ``wait`` is
    False and another process holds it; True otherwise (also where there
    are no file locks)."""
    fcntl = _fcntl()
    if fcntl is None:
        return True
    how = (fcntl.LOCK_EX if exclusive else fcntl.LOCK_SH) | (0 if wait else fcntl.LOCK_NB)
    try:
        fcntl.flock(fd, how)
    except BlockingIOError:
        return False
    return True


def unlock(fd):
    """Drop the ``flock`` taken by :func:`lock` on ``fd``."""
    fcntl = _fcntl()
    if fcntl is not None:
        fcntl.flock(fd, fcntl.LOCK_UN)
