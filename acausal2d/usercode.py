"""Errors raised by the user's own code (a model file's import, a model's
``__init__``, its ``equations`` and other hooks, its studies): the message
names the file, line and source text of the user's frame where the
exception was raised, and the original exception is chained (``raise ...
from exc``) so that Python shows the whole traceback.  The command line
prints the message alone unless ``--traceback`` is given or the
environment variable ``ACAUSAL2D_TRACEBACK`` is set to 1.

"The user's frame" is the innermost frame of the traceback whose file is
neither part of acausal2d, its library, nor of Python or an installed
package (numpy, CasADi): where the model author's code called what failed.
"""
from __future__ import annotations

import linecache
import os
import sys
import sysconfig
import traceback
from types import TracebackType
from typing import NamedTuple, Optional

TRACEBACK_ENV = "ACAUSAL2D_TRACEBACK"
"""Environment variable: set to 1, the command line prints the whole
traceback of an error (as ``--traceback`` does)."""


class UserFrame(NamedTuple):
    """Where the user's code raised: file, line, function and source text."""
    filename: str
    lineno: int
    function: str
    source: str

    def describe(self) -> str:
        """``at FILE:LINE, in FUNCTION:`` and the source line indented below."""
        text = "at %s:%d, in %s" % (self.filename, self.lineno, self.function)
        return text + (":\n    " + self.source if self.source else "")


def _framework_roots() -> tuple[str, ...]:
    """Folders whose files are not the user's: acausal2d, its library, the
    standard library and the installed packages."""
    here = os.path.dirname(os.path.abspath(__file__))
    roots = [here + os.sep, os.path.join(os.path.dirname(here), "library") + os.sep]
    paths = sysconfig.get_paths()
    for key in ("stdlib", "platstdlib", "purelib", "platlib"):
        if paths.get(key):
            roots.append(os.path.abspath(paths[key]) + os.sep)
    return tuple(roots)


def _is_user_file(filename: str, roots: tuple[str, ...]) -> bool:
    if not filename or filename.startswith("<"):
        return False
    full = os.path.abspath(filename)
    return not full.startswith(roots)


def user_frame(exc: BaseException) -> Optional[UserFrame]:
    """The innermost frame of ``exc``'s traceback in the user's code (see
    the module docstring), or None; a ``SyntaxError`` gives its own line."""
    roots = _framework_roots()
    if isinstance(exc, SyntaxError) and exc.filename and _is_user_file(exc.filename, roots):
        return UserFrame(exc.filename, exc.lineno or 0, "<module>", (exc.text or "").strip())
    found = None
    tb: Optional[TracebackType] = exc.__traceback__
    while tb is not None:
        code = tb.tb_frame.f_code
        if _is_user_file(code.co_filename, roots):
            found = (code.co_filename, tb.tb_lineno, code.co_name)
        tb = tb.tb_next
    if found is None:
        return None
    filename, lineno, function = found
    return UserFrame(filename, lineno, function,
                     linecache.getline(filename, lineno).strip())


def user_error_text(what: str, exc: BaseException) -> str:
    """``WHAT failed: TYPE: MESSAGE`` and, on the next lines, where in the
    user's code it was raised (:func:`user_frame`)."""
    text = "%s failed: %s: %s" % (what, type(exc).__name__, exc)
    frame = user_frame(exc)
    return text + ("\n  " + frame.describe() if frame is not None else "")


def wants_traceback(flag: bool = False) -> bool:
    """Whether the command line shows whole tracebacks: ``flag``
    (``--traceback``) or ``ACAUSAL2D_TRACEBACK=1``."""
    return flag or os.environ.get(TRACEBACK_ENV, "").strip() not in ("", "0")


def print_traceback(exc: BaseException, file=None) -> None:
    """The whole traceback of ``exc`` with its chained causes."""
    traceback.print_exception(type(exc), exc, exc.__traceback__, file=file or sys.stderr)


def has_user_cause(exc: BaseException) -> bool:
    """Whether ``exc`` was raised from an exception of the user's code (its
    cause has a user frame)."""
    cause = exc.__cause__
    return cause is not None and user_frame(cause) is not None
