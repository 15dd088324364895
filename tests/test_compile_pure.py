"""Compiling never writes into the user's model (issue 34): the compiler
binds its symbols, the parameters' values and the resolved ``world`` into a
copy of its own, so compiling twice, or compiling another instance with
another parameter value, gives the closed-form answer for each."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError, start
from acausal2d.library import translational
from conftest import assert_copied, load_model_class

RTOL = 1e-8


class Oscillator(Component):
    """Mass m on a spring c from s = 0.1 at rest: s(t) = 0.1 cos(sqrt(c/m) t)."""

    def __init__(self, c=100.0, **kw):
        super().__init__(**kw)
        self.ground = translational.Fixed()
        self.spring = translational.Spring(c=c)
        self.mass = translational.Mass(m=1.0, s=start(0.1, fixed=True), v=start(0.0, fixed=True))
        self.connect(self.ground.flange, self.spring.flange_a)
        self.connect(self.spring.flange_b, self.mass.flange_a)


Pendulum = load_model_class("pendulum.py", "Pendulum")      # the models/ example


def _snapshot(value, depth=0):
    """A comparable picture of an attribute value: components and
    connectors by their own attributes (recursively, parents by identity)."""
    if isinstance(value, (Component, acausal2d.Connector)):
        return (type(value).__name__, id(value))
    if isinstance(value, dict):
        return {k: _snapshot(v, depth + 1) for k, v in value.items()}
    if isinstance(value, (list, tuple, set)):
        return (type(value).__name__, [_snapshot(v, depth + 1) for v in value])
    if isinstance(value, np.ndarray):
        return ("ndarray", value.dtype.str, value.shape, value.tobytes())
    if isinstance(value, (int, float, str, bool, type(None))):
        return (type(value).__name__, repr(value))
    return (type(value).__name__, id(value), repr(vars(value)) if hasattr(value, "__dict__")
            else repr(value))


def _attributes(model):
    """Every attribute of every component and connector of ``model``."""
    out = {}
    for comp in model.components():
        out[id(comp)] = {k: _snapshot(v) for k, v in vars(comp).items()}
        for name, conn in comp._connectors.items():
            out[(id(comp), name)] = {k: _snapshot(v) for k, v in vars(conn).items()}
        for name, decl in comp._var_decls.items():
            out[(id(comp), "var", name)] = {k: _snapshot(v) for k, v in vars(decl).items()}
    return out


@pytest.mark.parametrize("cls", [Oscillator, Pendulum])
def test_compiling_leaves_every_attribute_of_every_component_as_it_was(cls):
    model = cls()
    before = _attributes(model)
    names_before = set(vars(model))
    acausal2d.compile_model(model)
    assert set(vars(model)) == names_before          # no `world` appears in the user's model
    assert _attributes(model) == before
    acausal2d.compile_model(model)                    # and a second compile starts from the same
    assert _attributes(model) == before


def test_parameters_read_as_given_after_compiling():
    model = Pendulum()
    acausal2d.compile_model(model)
    assert_copied(model.body.parameter_value("m"), 1.0)     # a number, not a bound symbol
    assert not hasattr(model, "world")


@pytest.mark.parametrize("which, c", [("the same instance", 100.0), ("another", 400.0)])
def test_the_same_instance_compiled_twice_and_another_value_give_the_closed_form(which, c):
    first = Oscillator(c=100.0)
    acausal2d.compile_model(first)                    # compiled once already
    model = first if which == "the same instance" else Oscillator(c=c)
    res = acausal2d.compile_model(model).simulate(stop_time=1.0, rtol=RTOL, atol=RTOL * 1e-2)
    t = np.asarray(res.time)
    exact = 0.1 * np.cos(math.sqrt(c) * t)
    # global error of IDA's BDF at rtol 1e-8 stays within a few hundred rtol of the amplitude
    assert np.max(np.abs(np.asarray(res["mass.s"]) - exact)) < 1e3 * RTOL * 0.1


def test_an_attribute_that_cannot_be_copied_is_named():
    import threading
    model = Pendulum()
    model.body.lock = threading.Lock()
    with pytest.raises(ModelDefinitionError, match=r"Body 'body'\.lock"):
        acausal2d.compile_model(model)
