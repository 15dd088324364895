"""Linkage assembly errors: a four-bar that cannot close names the element."""
import math

import pytest

import acausal2d
from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD, DSD, AssemblyError
from acausal2d.library.linkage.drives import Preset


class FourBar(Component):
    """Crank 0.1 m at the origin, coupler lL1, rocker lL2 about (d, 0)."""

    def __init__(self, lL1, lL2, d, **kw):
        super().__init__(**kw)
        self.preset = Preset(om=2 * math.pi)
        self.crank = DAN(lL=0.1)
        self.dyad = DDD(lL1=lL1, lL2=lL2, x20=d, y20=0.0)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


def test_four_bar_that_cannot_close_names_the_element():
    with pytest.raises(acausal2d.InitializationError) as info:
        acausal2d.simulate(FourBar(lL1=0.2, lL2=0.2, d=1.0), stop_time=0.1)
    msg = str(info.value)
    assert "DDD 'dyad'" in msg and "cannot assemble" in msg
    assert isinstance(info.value, AssemblyError)


def test_four_bar_that_closes_runs():
    res = acausal2d.simulate(FourBar(lL1=0.5, lL2=0.4, d=0.6), stop_time=0.2, rtol=1e-8)
    assert res.final("crank.phiL") == pytest.approx(0.4 * math.pi, abs=1e-10)


def test_dsd_offset_larger_than_distance():
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.preset = Preset(om=1.0)
            self.crank = DAN(lL=0.1)
            self.dyad = DSD(v=0.5, x10=0.2, y10=0.0)
            self.connect(self.preset.flange, self.crank.ctrR2)
            self.connect(self.crank.ctr2D2, self.dyad.ctr2D2)
    with pytest.raises(acausal2d.InitializationError, match="DSD 'dyad'"):
        acausal2d.compile_model(M())


def test_double_rocker_driven_past_its_range_stops_at_limit():
    """Non-Grashof four-bar (crank 0.1, coupler 0.15, rocker 0.2, ground 0.3):
    the input link can only swing while |P P2| <= coupler + rocker; driven at
    constant speed it reaches that limit (coupler and rocker stretched) and
    the run stops there with a report naming the dyad."""
    a, b, c, d = 0.1, 0.15, 0.2, 0.3
    phi0 = math.radians(60.0)
    model = FourBar(lL1=b, lL2=c, d=d)
    res = acausal2d.simulate(model, stop_time=1.0, rtol=1e-8, intervals=200,
                             params={"preset.om": 1.0, "preset.phi0": phi0})
    # the input range ends where |P - P2| = b + c: cos(phi) = (a^2 + d^2 - (b+c)^2) / (2 a d)
    phi_lim = math.acos((a * a + d * d - (b + c) ** 2) / (2 * a * d))
    t_lim = phi_lim - phi0
    assert 0 < t_lim < 1.0
    assert res.stopped is not None and "limit position" in res.stopped
    assert "DDD 'dyad'" in res.stopped
    sing = res.singularities[-1]
    assert sing["kind"] == "limit position"
    assert sing["time"] == pytest.approx(t_lim, abs=1e-4)
    assert res.final("crank.phiL") == pytest.approx(phi_lim, abs=1e-4)
