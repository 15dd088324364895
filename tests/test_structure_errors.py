"""Unbalanced and structurally singular models raise StructuralError naming
the components and equations involved; DSL misuse raises
ModelDefinitionError."""
import pytest

from acausal2d import (BandPort, Component, ModelDefinitionError, StructuralError,
                       Variable, compile_model, der, start)
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class Pendulum(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation()
        self.body = Body()
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


class OverDetermined(Pendulum):
    """The model adds an equation for an angle the joint already determines."""
    def equations(self):
        return [self.revolute.phi == 0.3]


class FreeVariable(Component):
    """A component declaring a variable without an equation for it."""
    q = Variable(doc="forgotten unknown")

    def equations(self):
        return []


class UnderDetermined(Pendulum):
    def __init__(self):
        super().__init__()
        self.extra = FreeVariable()


class TwoForOne(Component):
    """Two equations for x, none for y: balanced but structurally singular."""
    x = Variable()
    y = Variable()

    def equations(self):
        return [der(self.x) == -self.x, self.x == 2.0]


class Singular(Pendulum):
    def __init__(self):
        super().__init__()
        self.bad = TwoForOne()


def test_over_determined_names_component_and_equation():
    with pytest.raises(StructuralError) as err:
        compile_model(OverDetermined())
    msg = str(err.value)
    assert "over-determined" in msg
    assert "1 too many" in msg
    assert "OverDetermined '<model>' equation 1: revolute.phi == 0.3" in msg


def test_under_determined_names_variable():
    with pytest.raises(StructuralError) as err:
        compile_model(UnderDetermined())
    msg = str(err.value)
    assert "under-determined" in msg
    assert "1 missing" in msg
    assert "extra.q (in FreeVariable 'extra')" in msg


def test_structurally_singular_names_equations_and_variable():
    with pytest.raises(StructuralError) as err:
        compile_model(Singular())
    msg = str(err.value)
    assert "structurally singular" in msg
    assert "TwoForOne 'bad' equation 1" in msg
    assert "TwoForOne 'bad' equation 2" in msg
    assert "bad.y (in TwoForOne 'bad')" in msg


def test_unknown_keyword_is_reported():
    class M(Component):
        def __init__(self):
            super().__init__()
            self.rev = Revolute(phii=start(0.0))
    with pytest.raises(ModelDefinitionError, match="Revolute 'rev' has no parameter or variable 'phii'"):
        compile_model(M())


def test_python_bool_equation_is_reported():
    class Bad(Component):
        x = Variable()

        def equations(self):
            return [1.0 == 2.0]

    class M(Component):
        def __init__(self):
            super().__init__()
            self.bad = Bad()
    with pytest.raises(ModelDefinitionError, match="Bad 'bad' equation 1 is the Python value False"):
        compile_model(M())


def test_band_ports_connect_one_to_one_only():
    class Band(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.port = BandPort()

        def equations(self):
            return [self.port.L == 0, self.port.gamma == 0]

    class M(Component):
        def __init__(self):
            super().__init__()
            self.a, self.b, self.c = Band(), Band(), Band()
            self.connect(self.a.port, self.b.port)
            self.connect(self.b.port, self.c.port)
    with pytest.raises(ModelDefinitionError, match="one-to-one only.*a.port, b.port, c.port"):
        compile_model(M())


def test_connecting_different_kinds_is_reported():
    from acausal2d.library.rotational import Inertia

    class M(Component):
        def __init__(self):
            super().__init__()
            self.body = Body()
            self.inertia = Inertia()
            self.connect(self.body.frame_a, self.inertia.flange_a)
    with pytest.raises(ModelDefinitionError, match="connector kinds differ"):
        M()


class _Pendulum(Component):
    """A pendulum with one of its connections left out."""

    def __init__(self, missing, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        if missing != "joint":
            self.connect(self.revolute.frame_b, self.rod.frame_a)
        if missing != "body":
            self.connect(self.rod.frame_b, self.body.frame_a)


@pytest.mark.parametrize("missing,groups,loose", [
    ("joint", ["Fixed 'fixed', Revolute 'revolute'", "Body 'body', FixedTranslation 'rod'"],
     "revolute.frame_b, rod.frame_a"),
    ("body", ["Fixed 'fixed', FixedTranslation 'rod', Revolute 'revolute'", "Body 'body'"],
     "body.frame_a, rod.frame_b")])
def test_structural_error_names_the_loose_parts(missing, groups, loose):
    with pytest.raises(StructuralError) as err:
        compile_model(_Pendulum(missing))
    msg = str(err.value)
    assert msg.startswith("The model falls apart into 2 separate groups of components:")
    for g in groups:
        assert "  - " + g in msg
    assert "Unconnected connectors (probably one of them should connect the groups): " + loose in msg
