"""Folders only their owner can write (the compiled-code cache and its
fallbacks), checked as ssh checks ``~/.ssh`` before it trusts a key: a
folder another local user can write, or one they created, may hold a
library or a job file planted there, and loading it runs their code in
this process.

:func:`problem` creates a missing folder with mode 0700 and checks an
existing one: a real folder (not a symbolic link), owned by the current
user, writable by nobody else.  Group or other *read* bits on a folder of
one's own are removed (nothing could have been planted through them); a
folder of another user, a symbolic link, or one that others can write is
refused with a message naming it and what to do.
"""
import os
import stat

PRIVATE_MODE = 0o700


class Refusal:
    """Why a folder is not used: ``unsafe`` (another user could have written
    into it: never load from it) or only not writable (``unsafe`` False);
    ``message`` names the folder and what to do."""

    def __init__(self, message, unsafe):
        self.message, self.unsafe = message, unsafe

    def __str__(self):
        return self.message


def _create(path):
    """Make ``path`` (parents with the default mode, the folder itself 0700);
    a Refusal if it cannot be created."""
    parent = os.path.dirname(os.path.abspath(path))
    try:
        os.makedirs(parent, exist_ok=True)
        os.mkdir(path, PRIVATE_MODE)
    except FileExistsError:
        return None
    except OSError as exc:
        return Refusal("the folder %s cannot be written (it cannot be created: %s)" % (path, exc.strerror or exc),
                       False)
    return None


def _unsafe(path, st):
    """The Refusal of an existing ``path`` whose lstat is ``st``, or None."""
    me = os.geteuid()
    if stat.S_ISLNK(st.st_mode):
        return Refusal("the folder %s is a symbolic link (to %s); a private folder is used only "
                       "as itself: give the folder it points to, or remove the link"
                       % (path, os.path.realpath(path)), True)
    if not stat.S_ISDIR(st.st_mode):
        return Refusal("%s is not a folder; remove it or choose another folder" % path, False)
    if st.st_uid != me:
        return Refusal("the folder %s belongs to user id %d, not to you (user id %d): another "
                       "user may have created it to plant code; it is not used.  Remove it "
                       "(as its owner) or choose a folder of your own" % (path, st.st_uid, me),
                       True)
    if st.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        return Refusal("the folder %s can be written by other users (mode %04o), so files in "
                       "it may have been placed by them; it is not used.  Remove it (rm -r %s) "
                       "or make it private (chmod 700 %s) once you trust its contents"
                       % (path, stat.S_IMODE(st.st_mode), path, path), True)
    return None


def problem(path):
    """None where ``path`` is (now) a private folder of the current user
    that it can write, else a :class:`Refusal` (see the module docstring)."""
    made = _create(path)
    if made is not None and not os.path.lexists(path):
        return made
    try:
        st = os.lstat(path)
    except OSError as exc:
        return Refusal("the folder %s cannot be written (%s)" % (path, exc.strerror or exc), False)
    bad = _unsafe(path, st)
    if bad is not None:
        return bad
    if stat.S_IMODE(st.st_mode) & 0o077:
        try:
            os.chmod(path, PRIVATE_MODE)
        except OSError as exc:
            return Refusal("the folder %s cannot be made private (%s)"
                           % (path, exc.strerror or exc), True)
    if not os.access(path, os.W_OK | os.X_OK):
        return Refusal("the folder %s cannot be written" % path, False)
    return None


def ours(path):
    """True where the file ``path`` is a regular file (not a link) of the
    current user (or of root, as the files installed with the package) that
    nobody else can write: what is loaded from a private folder is checked
    so too."""
    try:
        st = os.lstat(path)
    except OSError:
        return False
    return stat.S_ISREG(st.st_mode) and st.st_uid in (os.geteuid(), 0) and \
        not st.st_mode & (stat.S_IWGRP | stat.S_IWOTH)
