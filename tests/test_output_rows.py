"""Output rows of a run: every row satisfies every equation E(t, z) = 0 to
1e-12 of the equation's scale (the size of its terms, |dE/dz| times the
unknowns' sizes), at the model's default grid and at 20,000 output points;
a coarse and a fine output grid give the same motion to within the
integrator's tolerance (the steps do not depend on the output grid)."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime.simulation import Simulation

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "models"))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "benchmarks"))
from piston_engine import PistonEngine  # noqa: E402
from bench_core import PendulumChain  # noqa: E402


def _run(cm, stop, rtol, intervals):
    opts = cm.run_options(stop_time=stop, intervals=intervals, rtol=rtol)
    times, rtol, atol = opts.times(), opts.rtol, opts.atol
    sim = Simulation(cm.system, cm.parameter_values(None), times, rtol, atol)
    return sim, sim.run()


def _worst_residual(cm, sim, log):
    """max over rows and equations of |E_i| / scale_i."""
    s = cm.system
    n = s.structure.n_var
    rows, cols = s.jacobian_pattern
    E = s.residual_fn.map(len(log.times))
    J = s.jacobian_fn.map(len(log.times))
    args = (log.times, log.nodes.T, sim.p, sim.d)
    Ev = np.array(E(*args)).T
    Jnz = np.array(J(*args).nonzeros()).reshape(len(log.times), -1)
    size = s.nominal[None, :] + np.abs(log.nodes)
    scale = np.zeros((len(log.times), Ev.shape[1]))
    for k in range(len(log.times)):
        np.add.at(scale[k], rows, np.abs(Jnz[k]) * size[k, cols])
    assert n == log.nodes.shape[1]
    return float(np.max(np.abs(Ev) / np.maximum(scale, 1e-300)))


@pytest.fixture(scope="module")
def piston():
    return acausal2d.compile_model(PistonEngine())


@pytest.mark.parametrize("intervals", [5000, 20000])
def test_piston_rows_satisfy_every_equation(piston, intervals):
    sim, log = _run(piston, 10.0, 1e-8, intervals)
    assert len(log.times) == intervals + 1 and not log.events
    assert _worst_residual(piston, sim, log) <= 1e-12


def test_chain_rows_satisfy_every_equation_at_20000_points():
    cm = acausal2d.compile_model(PendulumChain(20))
    sim, log = _run(cm, 2.0, 1e-6, 20000)
    assert len(log.times) == 20001
    assert _worst_residual(cm, sim, log) <= 1e-12


def test_coarse_and_fine_grids_agree_to_the_tolerance(piston):
    rtol = 1e-8
    _, coarse = _run(piston, 10.0, rtol, 100)
    _, fine = _run(piston, 10.0, rtol, 20000)
    assert coarse.stats.steps == fine.stats.steps
    np.testing.assert_allclose(fine.times[::200], coarse.times, rtol=0, atol=1e-12)
    size = piston.system.nominal[None, :] + np.abs(coarse.nodes)
    dev = np.max(np.abs(fine.nodes[::200] - coarse.nodes) / size)
    assert dev <= rtol
