"""The iteration matrix of the index-1 formulation takes the rows of its
equations from the system's dE/dz instead of differentiating them again:
the functions are the same (identical serializations, so identical C and
identical steps) as with the Jacobian derived from the formulation's own
residual."""
import os
import sys

import pytest

import acausal2d
from acausal2d.compiler import index1

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "models"))


@pytest.mark.parametrize("module, name", [("pendulum", "Pendulum"),
                                          ("piston_engine", "PistonEngine")])
def test_iteration_matrix_from_dEdz_is_the_derived_one(module, name, monkeypatch):
    calls = []
    init = index1.Formulation.__init__

    def spy(self, *args):
        init(self, *args)
        calls.append((self, args))
    monkeypatch.setattr(index1.Formulation, "__init__", spy)
    model = getattr(__import__(module), name)()
    acausal2d.compile_model(model).simulate(stop_time=0.01)
    assert calls and all(args[5] is not None for _, args in calls)
    for form, args in calls:
        own = index1.Formulation.__new__(index1.Formulation)
        init(own, *args[:5], None)
        assert form.jac_fn.serialize() == own.jac_fn.serialize()
        assert form.jac_sparsity == own.jac_sparsity
