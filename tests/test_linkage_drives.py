"""Motion presets, sources and measuring modules for the linkage elements."""
import math

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

import acausal2d
from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import (Preset, RelativeAngle, RelativePosition,
                                              TorqueSensor)

TABLE = [(0.0, 0.0), (0.25, 0.4), (0.5, 1.5), (0.75, 2.0), (1.0, 2.2)]


class Drive(Component):
    """Preset -> torque sensor -> crank -> DDD, with measuring modules."""

    def __init__(self, preset, **kw):
        super().__init__(**kw)
        self.preset = preset
        self.sensor = TorqueSensor()
        self.crank = DAN(lL=0.1)
        self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4)
        self.angle = RelativeAngle()
        self.pos = RelativePosition()
        self.connect(self.preset.flange, self.sensor.flange_a)
        self.connect(self.sensor.flange_b, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        self.connect(self.crank.ctr2D2, self.angle.ctr2D1)
        self.connect(self.dyad.ctr2D4, self.angle.ctr2D2)
        self.connect(self.dyad.ctr2D3, self.pos.ctr2D1)
        self.connect(self.dyad.ctr2D4, self.pos.ctr2D2)


def sim(preset):
    return acausal2d.simulate(Drive(preset), stop_time=1.0, rtol=1e-9,
                              output_times=np.linspace(0, 1, 101))


def test_polynomial_preset_and_sensors():
    res = sim(Preset(kind="polynomial", a=(0.2, 1.0, 0.5, -0.3, 0.0, 0.0)))
    t = res.time
    phi = 0.2 + t + 0.5 * t ** 2 - 0.3 * t ** 3
    assert np.max(np.abs(res["crank.phiL"] - phi)) < 1e-12
    assert np.max(np.abs(res["preset.w"] - (1 + t - 0.9 * t ** 2))) < 1e-8
    # torque sensor passes the drive torque; power = tau * w
    assert np.max(np.abs(res["sensor.tau"] - res["preset.tau"])) < 1e-9
    assert np.max(np.abs(res["sensor.power"] - res["preset.power"])) < 1e-8
    assert np.max(np.abs(res["angle.phi_rel"] - (res["dyad.phiL2"] - res["crank.phiL"]))) < 1e-12
    d = np.hypot(res["pos.dx"], res["pos.dy"])
    assert np.max(np.abs(d - np.hypot(res["crank.ctr2D2.x"] - 0.4, res["crank.ctr2D2.y"]))) < 1e-9


def test_table_preset_is_a_c2_spline():
    res = sim(Preset(kind="table", table=TABLE))
    cs = CubicSpline(*np.array(TABLE).T)
    assert np.max(np.abs(res["crank.phiL"] - cs(res.time))) < 1e-10
    assert np.max(np.abs(res["preset.w"] - cs(res.time, 1))) < 1e-6


def test_speed_preset_translational_and_errors():
    with pytest.raises(acausal2d.ModelDefinitionError):
        Preset(kind="jerk")
    with pytest.raises(acausal2d.ModelDefinitionError):
        Preset(kind="table")
    p = Preset(kind="speed", om=2 * math.pi)
    res = sim(p)
    assert res.final("crank.phiL") == pytest.approx(2 * math.pi, abs=1e-12)
