"""Foreign exceptions (CasADi, numpy, SUNDIALS) are translated at one
boundary into the project's errors, without the foreign traceback."""
import numpy as np
import pytest

from acausal2d.errors import (Acausal2dError, InitializationError, SimulationError,
                              StructuralError, translated)


def test_foreign_errors_become_the_projects_without_their_traceback():
    with pytest.raises(SimulationError) as err:
        with translated("simulating Pendulum"):
            raise RuntimeError(".../casadi/core/function.cpp:1401: Error in Function::call "
                               "for 'E' [SXFunction] at .../casadi/core/x_function.hpp:1: bad")
    assert str(err.value).startswith("simulating Pendulum failed: RuntimeError")
    assert err.value.__cause__ is None and err.value.__suppress_context__
    with pytest.raises(StructuralError, match="compiling M failed: LinAlgError"):
        with translated("compiling M", StructuralError):
            np.linalg.inv(np.zeros((2, 2)))


def test_project_errors_and_interrupts_pass_unchanged():
    original = InitializationError("loop cannot close")
    with pytest.raises(InitializationError) as err:
        with translated("simulating M"):
            raise original
    assert err.value is original
    with pytest.raises(KeyboardInterrupt):
        with translated("simulating M"):
            raise KeyboardInterrupt
    assert issubclass(SimulationError, Acausal2dError)
