"""The exceptions acausal2d raises.

Every error a user can act on derives from :class:`Acausal2dError`; the
message names the component, equation or variable involved and what to
change.  Raw CasADi or SUNDIALS errors are translated into these.
"""


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


class SimulationError(Acausal2dError):
    """The integrator failed or the motion cannot go on; the message gives
    the time and names the variable, relation or component responsible.
    ``result`` holds the motion up to that time (a
    :class:`~acausal2d.tools.result.Result`) when there is one."""

    def __init__(self, message, time=None, status=None, variable=None):
        super().__init__(message)
        self.time = time
        self.status = status
        self.variable = variable
        self.result = None
