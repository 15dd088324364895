"""Runtime cases found while building issue 14, fixed in the runtime:

1. A time event that falls on a requested output time gives three result rows
at that time instead of the two (left and right limit) that
:class:`~acausal2d.result.Result` documents ("Event instants appear
twice").  Consumers that split curves at repeated times (compare's event
handling, a left/right-limit lookup) see a spurious extra piece.

2. A residual whose Jacobian is not finite at the start guess (sqrt of a
sum of squares that is zero there, as in a line damper between coinciding
frames) ends the run with a raw ``numpy.linalg.LinAlgError`` ("SVD did not
converge") and LAPACK messages on stdout, instead of an
InitializationError naming the equation."""
import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, der, InitializationError, Variable
from acausal2d.library import signals
from conftest import same_time


class RampIntegral(Component):
    """x' = ramp(t): the ramp's kink at t = 0.5 s is a time event."""
    x = Variable(start=0.0, fixed=True)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ramp = signals.Ramp(duration=0.5)

    def equations(self):
        return [der(self.x) == self.ramp.y.u]


def test_time_event_on_an_output_time_gives_two_rows():
    res = acausal2d.simulate(RampIntegral(), output_times=np.linspace(0.0, 1.0, 11))
    assert [t for t, _ in res.events] == [pytest.approx(0.5)]
    assert int(np.sum(same_time(res.time, 0.5))) == 2


def test_time_event_between_output_times_gives_two_rows():
    """The same event between two output times: two rows, as documented."""
    res = acausal2d.simulate(RampIntegral(), output_times=np.linspace(0.0, 1.0, 8))
    assert int(np.sum(same_time(res.time, 0.5))) == 2
    k = np.nonzero(same_time(res.time, 0.5))[0]
    assert res["x"][k[0]] == pytest.approx(0.25, abs=1e-6)


class SqrtAtZero(Component):
    """sqrt(x^2 + y^2) + x = 2 with y = 2 x, started at x = y = 0 where the
    derivative of the square root is 0/0."""
    x = Variable(start=0.0)
    y = Variable(start=0.0)

    def equations(self):
        return [self.y == 2 * self.x, ca.sqrt(self.x ** 2 + self.y ** 2) + self.x == 2]


def test_nan_jacobian_at_start_is_an_initialization_error():
    with pytest.raises(InitializationError) as err:
        acausal2d.simulate(SqrtAtZero(), stop_time=1.0)
    assert "sqrt" in str(err.value) and "inf or NaN" in str(err.value)
