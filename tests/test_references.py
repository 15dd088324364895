"""The five basic models against reference curves computed by Dymola with
the PlanarMechanics library (absolute tube 2e-3, as in the Modelica
Standard Library's regression tests)."""
import numpy as np
import pytest

import acausal2d
from conftest import load_model_class
from reference_data import REFERENCES

TUBE = 2e-3

CASES = [
    ("pendulum.py", "Pendulum", "Pendulum", None),
    ("crane_crab.py", "CraneCrab", "CraneCrab", None),
    ("piston_engine.py", "PistonEngine", "PistonEngine", None),
    ("piston_engine_dynamic.py", "PistonEngineDynamic", "PistonEngine_DynamicStateSelection",
     None),
    # The double pendulum is chaotic: the reference (DASSL, tolerance 1e-6) leaves the
    # 2e-3 tube around the converged solution after about 6.5 s (see
    # test_double_pendulum_reference_is_inaccurate_late and
    # test_double_pendulum_late_motion_is_too_sensitive_for_the_tube below).
    ("double_pendulum.py", "DoublePendulum", "DoublePendulum", 6.0),
]


def _simulate_on_reference_grid(filename, cls, ref, rtol=1e-8):
    data = np.array(REFERENCES[ref]["rows"])
    times = np.unique(data[:, 0])
    res = acausal2d.simulate(load_model_class(filename, cls)(), output_times=times, rtol=rtol)
    return res, data


@pytest.mark.parametrize("filename,cls,ref,t_max", CASES, ids=[c[1] for c in CASES])
def test_model_reproduces_reference(filename, cls, ref, t_max):
    res, data = _simulate_on_reference_grid(filename, cls, ref)
    cols = REFERENCES[ref]["columns"]
    keep = data[:, 0] <= (t_max if t_max is not None else np.inf)
    assert keep.sum() >= 50
    for k, name in enumerate(cols[1:], start=1):
        ours = np.interp(data[keep, 0], res.time, res[name])
        dev = np.abs(ours - data[keep, k])
        assert dev.max() < TUBE, "%s: max deviation %.3g at t=%.3f" % (
            name, dev.max(), data[keep, 0][np.argmax(dev)])


def _double_pendulum_energy(p1, w1, p2, w2):
    a2, w2a = p1 + p2, w1 + w2
    vx1, vy1 = -np.sin(p1) * w1, np.cos(p1) * w1
    vx2, vy2 = vx1 - 0.4 * np.sin(a2) * w2a, vy1 + 0.4 * np.cos(a2) * w2a
    y1, y2 = np.sin(p1), np.sin(p1) + 0.4 * np.sin(a2)
    return (0.5 * (vx1 ** 2 + vy1 ** 2) + 0.5 * 0.1 * w1 ** 2
            + 0.5 * 0.2 * (vx2 ** 2 + vy2 ** 2) + 0.5 * 0.01 * w2a ** 2
            + 9.81 * (y1 + 0.2 * y2))


def test_double_pendulum_reference_is_inaccurate_late():
    """Why the double pendulum is compared up to 6 s only: over the full run
    our solution is converged (rtol 1e-8 and 1e-11 agree to 5e-4, a quarter of the
    tube, and conserve
    energy to 1e-6 J) while the reference loses 1.5e-4 J; in this chaotic
    motion that error grows beyond the 2e-3 tube late in the run."""
    data = np.array(REFERENCES["DoublePendulum"]["rows"])
    e_ref = _double_pendulum_energy(*data[:, 1:5].T)
    fine, _ = _simulate_on_reference_grid("double_pendulum.py", "DoublePendulum",
                                          "DoublePendulum", rtol=1e-11)
    tight, _ = _simulate_on_reference_grid("double_pendulum.py", "DoublePendulum",
                                           "DoublePendulum", rtol=1e-8)
    e_ours = _double_pendulum_energy(fine["revolute.phi"], fine["revolute.w"],
                                     fine["revolute1.phi"], fine["revolute1.w"])
    assert np.max(np.abs(e_ours - e_ours[0])) < 1e-6
    assert np.max(np.abs(e_ref - e_ref[0])) > 1e-4
    for name in ("revolute.phi", "revolute.w", "revolute1.phi", "revolute1.w"):
        assert np.max(np.abs(fine[name] - tight[name])) < 5e-4


def test_double_pendulum_late_motion_is_too_sensitive_for_the_tube():
    """No solution can keep a 2e-3 tube around the reference over 10 s: a
    start angle changed by 1e-5 rad - ten times less than the reference's
    own accuracy of about 1e-4 (references/README) - moves revolute1.w by
    more than the tube late in the run, while up to 6 s it stays well
    inside (which is where the reference is compared)."""
    cls = load_model_class("double_pendulum.py", "DoublePendulum")
    times = np.linspace(0.0, 10.0, 1001)
    base = acausal2d.simulate(cls(), output_times=times, rtol=1e-10)
    moved = acausal2d.simulate(cls(phi0=1e-5), output_times=times, rtol=1e-10)
    dev = np.abs(moved["revolute1.w"] - base["revolute1.w"])
    assert dev[times <= 6.0].max() < 0.5 * TUBE
    assert dev.max() > TUBE
