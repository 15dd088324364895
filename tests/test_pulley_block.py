"""Pulley block of seed ch. 7.3.1 (models/pulley_block.py)."""
import math

import numpy as np
import pytest

from acausal2d import compile_model
from conftest import load_model_class

PulleyBlock = load_model_class("pulley_block.py", "PulleyBlock")
friction_factor = load_model_class("pulley_block.py", "friction_factor")
quasi_static_forces = load_model_class("pulley_block.py", "quasi_static_forces")
efficiency_sweep = load_model_class("pulley_block.py", "efficiency_sweep")
RADII = load_model_class("pulley_block.py", "RADII")
PULLEYS = load_model_class("pulley_block.py", "PULLEYS")

MG = 100.0 * 9.81


@pytest.fixture(scope="module")
def compiled_with_friction():
    return compile_model(PulleyBlock(friction=True))


def test_frictionless_force_and_travel():
    res = compile_model(PulleyBlock(friction=False)).simulate(
        stop_time=6.0, rtol=1e-8, output_times=np.linspace(0.0, 6.0, 121))
    t = res.time
    quasi = (t >= 2.0) & (t <= 4.0)
    for k in range(1, 6):
        F = res["rope%d.F" % k][quasi]
        assert np.max(np.abs(F / (MG / 4) - 1.0)) < 1e-4
    assert np.max(np.abs(res["pull.F"][quasi] / (MG / 4) - 1.0)) < 1e-4
    # rope travel = 4 x load travel, during the lift and at rest afterwards
    s = res["pull.s_in.u"]
    dy = res["load.y"] - res["load.y"][0]
    assert s[-1] == pytest.approx(0.8, rel=1e-12)
    assert dy[-1] == pytest.approx(s[-1] / 4, rel=1e-6)
    assert np.max(np.abs(dy[quasi] - s[quasi] / 4)) < 1e-6 * s[-1]


def test_bearing_friction_per_pulley(compiled_with_friction):
    mu = 0.25
    res = compiled_with_friction.simulate(stop_time=4.0, rtol=1e-8,
                                          output_times=np.linspace(0.0, 4.0, 81))
    quasi = (res.time >= 2.0) & (res.time <= 4.0)
    F = [res["rope%d.F" % k][quasi] for k in range(1, 6)]
    for i, p in enumerate(PULLEYS):
        k = friction_factor(RADII[p], mu)
        # 180 degree wrap, parallel sections: T_out = T_in (r - mu r_pin)/(r + mu r_pin)
        assert np.max(np.abs(F[i + 1] / F[i] / k - 1.0)) < 1e-4, p
        assert np.max(np.abs(res[p + ".beta"][quasi] - math.pi)) < 1e-2
    # the closed-form section forces hold to the swing of the free lower block
    ref = quasi_static_forces(mu)
    for i in range(5):
        assert np.max(np.abs(F[i] / ref[i] - 1.0)) < 2e-3
    # the load is lifted: friction costs force, not travel
    assert res["rope1.F"][quasi].mean() > MG / 4 * 1.1


def test_efficiency_sweep_writes_png(compiled_with_friction, tmp_path):
    png = tmp_path / "eff.png"
    mus, eta, util = efficiency_sweep([0.0, 0.25, 0.5], png=str(png),
                                      compiled=compiled_with_friction)
    assert png.exists() and png.stat().st_size > 1000
    assert eta[0] == pytest.approx(1.0, abs=1e-4)
    assert util[0] == pytest.approx(1.0, abs=1e-4)
    assert eta[0] > eta[1] > eta[2]
    assert util[0] > util[1] > util[2]
    ref = quasi_static_forces(0.25)
    assert eta[1] == pytest.approx(MG / (4 * ref[0]), rel=2e-3)
