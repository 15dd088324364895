"""The exceptions acausal2d raises.

Every error a user can act on derives from :class:`Acausal2dError`; the
message names the component, equation or variable involved and what to
change.  Raw CasADi or SUNDIALS errors are translated into these.
"""
from __future__ import annotations

from types import TracebackType
from typing import Literal


class Acausal2dError(Exception):
    """Base class of all errors raised by acausal2d."""


class ModelDefinitionError(Acausal2dError):
    """A model file or component is written incorrectly (unknown parameter,
    bad connection, malformed equation, ...)."""


class StructuralError(Acausal2dError):
    """The equation system is unbalanced or structurally singular."""


class InitializationError(Acausal2dError):
    """No consistent initial values were found (e.g. a loop that cannot
    assemble)."""


class StartPoseError(InitializationError, ModelDefinitionError):
    """The start pose of a part does not follow from the model's parameters
    and start values (often: a frame it hangs on is connected to nothing);
    raised while the model is compiled."""


class SimulationError(Acausal2dError):
    """The integrator failed or the motion cannot go on; the message gives
    the time and names the variable, relation or component responsible.
    ``result`` holds the motion up to that time (a
    :class:`~acausal2d.result.Result`) when there is one."""

    partial: object
    """The run's log up to where it stopped (a
    :class:`~acausal2d.runtime.simulation.RunLog`, set by the run that raised
    it; the errors module imports nothing of the package)."""

    def __init__(self, message, time=None, status=None, variable=None):
        super().__init__(message)
        self.time = time
        self.status = status
        self.variable = variable
        self.result = None


class translated:
    """Context manager at the boundary between the user and the compiler or
    runtime: an exception that is not the project's own (CasADi's
    ``RuntimeError``, a numpy or SUNDIALS failure) becomes ``error`` (an
    :class:`Acausal2dError` subclass) saying what was being done, without
    the foreign traceback; the project's errors and interrupts pass."""

    def __init__(self, what: str, error: type[Acausal2dError] | None = None) -> None:
        self.what = what
        self.error = error or SimulationError

    def __enter__(self) -> translated:
        return self

    def __exit__(self, kind: type[BaseException] | None, exc: BaseException | None,
                 tb: TracebackType | None) -> Literal[False]:
        if exc is None or isinstance(exc, (Acausal2dError, KeyboardInterrupt, SystemExit,
                                           MemoryError)):
            return False
        first = " ".join(str(exc).split())
        if ".../casadi/" in first or "casadi" in first.lower():
            first = first.split("]")[-1].strip() or first
        raise self.error("%s failed: %s: %s" % (self.what, type(exc).__name__, first[:400])) \
            from None
