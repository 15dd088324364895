"""Runtime reproduction found while building the node front end (issue 11),
now a regression test.

A state event whose crossing function depends on algebraic unknowns only,
in a model without states (a purely algebraic system, as every kinematically
driven mechanism is), was located on IDA's interpolant: x = sin(2 pi t)
crosses 0.5 at t = 1/12 s, the run reported the event at 0.0852 s (2 ms late
at rtol 1e-10) and added spurious events near t = 5/12.  For a driven
mechanism this made a range that stops the drive
(acausal2d.library.nodes.at_most without source) re-initialize the
positions away from the event point, which the runtime then reported as a
jump needing an impulse.  The runtime now locates such events on the exact
solution (acausal2d.runtime.locate)."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, Variable, if_else, time
from conftest import assert_copied


class AlgebraicCrossing(Component):
    """x = sin(2 pi t) (no states); y switches where x >= 0.5."""
    x = Variable()
    y = Variable()

    def equations(self):
        return [self.x == acausal2d.sin(2 * math.pi * time),
                self.y == if_else(self.x >= 0.5, 1.0, 0.0)]


def test_state_event_in_a_model_without_states_falls_on_its_crossing():
    res = acausal2d.simulate(AlgebraicCrossing(), stop_time=1.0, rtol=1e-10)
    times = [t for t, _ in res.events]
    assert len(times) == 2
    assert times[0] == pytest.approx(1 / 12, abs=1e-8)
    assert times[1] == pytest.approx(5 / 12, abs=1e-8)


def test_output_rows_around_located_events_are_exact():
    """The rows IDA produced past the located event are redone, the rows
    between IDA's root and a later exact root are filled: on every row
    y = (x >= 0.5) and x = sin(2 pi t) to the Newton tolerance."""
    res = acausal2d.simulate(AlgebraicCrossing(), stop_time=1.0, rtol=1e-10, intervals=1000)
    x, y, t = res["x"], res["y"], res.time
    assert abs(x - np.sin(2 * math.pi * t)).max() < 1e-10
    inside = (t > 1 / 12 + 1e-9) & (t < 5 / 12 - 1e-9)
    outside = (t < 1 / 12 - 1e-9) | (t > 5 / 12 + 1e-9)
    assert inside.sum() == 333 and outside.sum() == 668 and t.size == 1001 + 4
    assert_copied(y[inside], 1.0)                  # the branches of the pulse
    assert_copied(y[outside], 0.0)
    assert np.all(np.diff(t) >= 0)


def _slider_stop_model():
    from acausal2d.library.nodes import NodeModel, at_most, speed

    class SliderStopModel(NodeModel):
        """Slider-crank (crank 30 mm, rod 100 mm, slider on the x axis) whose
        slider travel |A0B| is limited to 120 mm by a range without source:
        at the limit the crank drive stops."""
        length_unit = 1e-3

        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("A0", 0, 0, base=True)
            self.node("A", -30, 0)
            self.node("B", 70, 0)
            self.n2("A0A", "A0", "A", len="const", ang=speed(2 * math.pi))
            self.n2("AB", "A", "B", len="const")
            self.n2("A0B", "A0", "B", ang="const", len=at_most(120))
    return SliderStopModel()


def test_range_without_source_stops_the_drive_at_the_limit():
    res = acausal2d.simulate(_slider_stop_model(), stop_time=1.0, rtol=1e-10, intervals=100)
    # |A0B| = 120 mm where cos(phi) = (120^2 + 30^2 - 100^2) / (2 30 120)
    phi = 2 * math.pi - math.acos(5300.0 / 7200.0)
    t_stop = (phi - math.pi) / (2 * math.pi)
    assert res.events[0][0] == pytest.approx(t_stop, abs=1e-8)
    late = res.time > t_stop + 1e-6
    assert abs(res["A0B.r"][late] - 0.12).max() < 1e-12
    assert abs(res["A0A.w"][late] - phi).max() < 1e-9
