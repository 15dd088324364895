"""Piston engine: energy conservation, loop closure, dead centres."""
import numpy as np
import pytest

import acausal2d
from conftest import load_model_class

E0 = 0.3125  # 0.5*0.1*2.5**2 at the dead centre (piston at rest)


@pytest.fixture(scope="module")
def engine_result(compiled_model):
    engine = compiled_model("piston_engine.py", "PistonEngine")
    return engine.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)


def test_energy_is_conserved(engine_result):
    r = engine_result
    w = r["revoluteDrive.w"]
    xdot = r["der(bodyPiston.x)"]
    ydot = r["der(bodyPiston.y)"]
    energy = 0.5 * 0.1 * w ** 2 + 0.5 * 3.0 * (xdot ** 2 + ydot ** 2)
    assert abs(energy[0] - E0) < 1e-12
    assert np.max(np.abs(energy - E0)) / E0 < 1e-6


def test_loop_closure_holds(engine_result):
    r = engine_result
    phi = r["revoluteDrive.phi"]
    x_piston = -r["prismatic.s"]          # frame_b of the prismatic joint is fixed at the origin
    y_piston = r["bodyPiston.y"]
    # crank end (0.3 cos phi, 0.3 sin phi); the rod of length 0.8 reaches the piston on y = 0
    residual = np.hypot(x_piston - 0.3 * np.cos(phi), y_piston - 0.3 * np.sin(phi)) - 0.8
    assert np.max(np.abs(residual)) < 1e-8
    assert np.max(np.abs(y_piston)) < 1e-12
    assert len(r.time) == 5001


def test_end_values_match_reference(engine_result):
    # end values from ../shared/references/README.md (Dymola)
    assert engine_result.final("revoluteDrive.phi") == pytest.approx(-16.8149394961727, abs=2e-3)
    assert engine_result.final("revoluteDrive.w") == pytest.approx(-1.59426627944, abs=2e-3)


def test_no_state_priority_passes_dead_centres():
    """All joints 'default': the compiler chooses the states; the run starts at
    the dead centre (piston position unusable as a state) and passes the
    following dead centres (crank angle a multiple of pi) without failing."""
    model = load_model_class("piston_engine_dynamic.py", "PistonEngineDynamic")()
    r = acausal2d.simulate(model, stop_time=10.0, rtol=1e-8, intervals=2000)
    phi = r["revoluteDrive.phi"]
    passes = int(np.floor(-phi[-1] / np.pi))
    assert passes >= 5                     # dead centres at phi = -pi, -2pi, ... -5pi
    s = r["prismatic.s"]
    # the piston reverses at every dead centre: s = -1.1 (outer) and -0.5 (inner)
    assert np.min(s) == pytest.approx(-1.1, abs=1e-6)
    assert np.max(s) == pytest.approx(-0.5, abs=1e-4)
    w = r["revoluteDrive.w"]
    xdot = r["der(bodyPiston.x)"]
    energy = 0.5 * 0.1 * w ** 2 + 0.5 * 3.0 * xdot ** 2
    assert np.max(np.abs(energy - E0)) / E0 < 1e-6
