"""The notices of the runtime (native code compiled, a cache refused or
damaged, a structure compiled again): one line each on standard error,
once per process, through the ``acausal2d`` logger.
"""
from __future__ import annotations

import functools
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import logging

_said: set = set()
WITHOUT_LIBRARY = ("this run goes on without compiled code: on CasADi's C API where "
                   "acausal2d's driver for it is here, else on the Python path")
"""What a run does where a structure's compiled library is not there (the
end of the notices that say why)."""
LOGGER_NAME = "acausal2d"
"""The ``logging`` logger acausal2d's notices go through."""


@functools.cache
def _stderr_handler() -> type:
    """The handler class of :func:`logger`: ``acausal2d: <message>`` on the
    current ``sys.stderr`` (made at the first notice: a run that says
    nothing does not import ``logging``)."""
    import logging

    class _Stderr(logging.Handler):
        def emit(self, record: logging.LogRecord) -> None:
            try:
                print("acausal2d: " + record.getMessage(), file=sys.stderr)
                sys.stderr.flush()
            except Exception:        # noqa: BLE001 - logging never raises into the run
                self.handleError(record)
    return _Stderr


def logger() -> logging.Logger:
    """The ``acausal2d`` logger: its own stderr handler (``acausal2d:
    <message>``), level WARNING, not propagated.  Notices of the first run
    of a structure (native code being compiled) are INFO: quiet in Python
    and in a notebook unless asked for
    (``logging.getLogger("acausal2d").setLevel(logging.INFO)``); the
    command line shows them.  Failures that change how a run goes (a
    compile that failed, a cache that cannot be written) are WARNING."""
    import logging
    handler = _stderr_handler()
    log = logging.getLogger(LOGGER_NAME)
    if not any(isinstance(h, handler) for h in log.handlers):
        log.addHandler(handler())
        log.propagate = False
        if log.level == logging.NOTSET:
            log.setLevel(logging.WARNING)
    return log


def notice(message: str, first_run: bool = False) -> None:
    """Say ``message`` once per process through :func:`logger`: INFO for a
    notice of a first run (``first_run``), else WARNING."""
    if message not in _said:
        _said.add(message)
        import logging
        logger().log(logging.INFO if first_run else logging.WARNING, message)
