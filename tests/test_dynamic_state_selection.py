"""Dynamic state selection: a pendulum in Cartesian coordinates has no
coordinate that can serve as state over a whole swing (x is useless where
the rod is horizontal, y where it hangs vertically); the compiler must
re-select the states during the run.

Accuracy note: IDA integrates this index-reduced Cartesian form less
accurately than the joint-angle form at the same tolerance (measured with a
hand-written residual of the same equations, independent of acausal2d:
energy drift 7e-4 J at rtol 1e-6 over 0.6 s of fast swinging, against 2e-7 J
for the angle form).  The comparison tolerances below reflect that, not the
state switching, which is exact (the constraint holds to 1e-10 throughout)."""
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, Variable, der, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class CartesianPendulum(Component):
    """Point mass m on a massless rod of length L about the origin, written as
    x^2 + y^2 = L^2 with the rod force lam (no angle variable)."""
    m = acausal2d.Parameter(1.0, "kg", "mass")
    L = acausal2d.Parameter(1.0, "m", "rod length")
    x = Variable(start=1.0, fixed=True)
    y = Variable(start=0.0)
    lam = Variable(doc="rod force per unit length")

    def equations(self):
        g = 9.81
        return [self.m * der(der(self.x)) == -self.lam * self.x,
                self.m * der(der(self.y)) == -self.lam * self.y - self.m * g,
                self.x ** 2 + self.y ** 2 == self.L ** 2]


class RevolutePendulum(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=(1.0, 0.0))
        self.body = Body(m=1.0, I=0.0)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)


def test_cartesian_pendulum_reselects_states_and_matches_joint_pendulum():
    times = np.linspace(0.0, 4.0, 401)
    cart = acausal2d.simulate(CartesianPendulum(), output_times=times, rtol=1e-10)
    joint = acausal2d.simulate(RevolutePendulum(), output_times=times, rtol=1e-10)
    assert cart.stats["reselections"] >= 2
    assert any(text == "state re-selection" for _, text in cart.events)
    t = cart.time
    for name_c, name_j in (("x", "body.x"), ("y", "body.y")):
        ours = np.interp(times, t, cart[name_c])
        assert np.max(np.abs(ours - joint[name_j])) < 1e-4
    assert np.max(np.abs(cart["x"] ** 2 + cart["y"] ** 2 - 1.0)) < 1e-10
    energy = 0.5 * (cart["der(x)"] ** 2 + cart["der(y)"] ** 2) + 9.81 * cart["y"]
    assert np.max(np.abs(energy)) < 1e-4          # of a kinetic energy up to 9.81 J
    # it swings through the bottom to the other side (x = -1) and back
    assert np.min(cart["x"]) == pytest.approx(-1.0, abs=1e-4)
    assert cart.stats["reselections"] >= 4
