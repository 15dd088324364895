"""Runtime reproduction found while building issue 14 (not fixed here: the
runtime belongs to the lead).

A time event that falls on a requested output time gives three result rows
at that time instead of the two (left and right limit) that
:class:`~acausal2d.tools.result.Result` documents ("Event instants appear
twice").  Consumers that split curves at repeated times (compare's event
handling, a left/right-limit lookup) see a spurious extra piece."""
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, der, Variable
from acausal2d.library import signals


class RampIntegral(Component):
    """x' = ramp(t): the ramp's kink at t = 0.5 s is a time event."""
    x = Variable(start=0.0, fixed=True)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ramp = signals.Ramp(duration=0.5)

    def equations(self):
        return [der(self.x) == self.ramp.y.u]


@pytest.mark.xfail(strict=True, reason="an output time on a time event gives three rows "
                   "at that time (output point + left + right limit) instead of two")
def test_time_event_on_an_output_time_gives_two_rows():
    res = acausal2d.simulate(RampIntegral(), output_times=np.linspace(0.0, 1.0, 11))
    assert [t for t, _ in res.events] == [pytest.approx(0.5)]
    assert int(np.sum(res.time == 0.5)) == 2


def test_time_event_between_output_times_gives_two_rows():
    """The same event between two output times: two rows, as documented."""
    res = acausal2d.simulate(RampIntegral(), output_times=np.linspace(0.0, 1.0, 8))
    assert int(np.sum(res.time == 0.5)) == 2
    k = np.nonzero(res.time == 0.5)[0]
    assert res["x"][k[0]] == pytest.approx(0.25, abs=1e-6)
