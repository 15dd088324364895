"""The event Newton's stacked matrix (runtime/stacked.py) gives the steps of
the general path (scipy.sparse vstack + splu) to the last bit."""
import os
import sys

import numpy as np
import scipy.sparse as sp

import acausal2d
from acausal2d.runtime import newton
from acausal2d.runtime.evaluator import Evaluator
from acausal2d.runtime.stacked import StackedJacobian
from conftest import assert_copied

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "models"))


def test_stacked_step_is_the_general_step_bitwise():
    from compressor import Compressor
    cm = acausal2d.compile_model(Compressor())
    s = cm.system
    res = cm.simulate(stop_time=0.05)
    ev = Evaluator(s, cm.parameter_values(None))
    assert ev.sparse
    z = np.array([res[n][-1] for n in s.node_names])
    d = np.zeros(ev.n_rel)
    held = [int(j) for j in s.structure.state_nodes(_selection(cm))]
    assert len(held) == ev.n - ev.n_eq          # a square Newton matrix
    t = float(res.time[-1])
    r = np.concatenate([ev.residual(t, z, d), np.zeros(len(held))]) + 1e-3
    stacked = StackedJacobian.of(ev, held)
    assert stacked is not None
    H = sp.csr_matrix((np.ones(len(held)), (np.arange(len(held)), held)),
                      shape=(len(held), ev.n))
    J = sp.vstack([ev.jacobian(t, z, d), H])
    general = newton._step(J, r, True)
    fast = stacked.step(t, z, d, r)
    assert general is not None and fast is not None
    assert_copied(general, fast)        # the same matrix and LU: bitwise is the claim


def _selection(cm):
    """The selection of a short run (its states are the held nodes)."""
    from acausal2d.runtime.simulation import Simulation
    opts = cm.run_options(stop_time=0.01, intervals=2)
    times, rtol, atol = opts.times(), opts.rtol, opts.atol
    sim = Simulation(cm.system, cm.parameter_values(None), times, rtol, atol)
    sim.run()
    return sim.selection
