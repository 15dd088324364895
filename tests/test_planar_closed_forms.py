"""Closed forms and independent solutions for the PlanarMechanics examples
of issue 14 and the rolling wheel: SpringDemo's frequency and equilibrium,
SpringDamperDemo's energy balance, PendulumExcited against a 1-DOF ODE
(and its cut force by hand), InvertedCraneCrab as an inverse model, and
IdealRolling (no-slip contact, wheel on a slope)."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import acausal2d
from acausal2d import Component, der, start, Variable
from acausal2d.library.planar import Body, IdealRolling, PlanarWorld
from conftest import load_model_class, same_time

G = 9.81


def _model(name):
    return load_model_class("planar_examples.py", name)


# --------------------------------------------------------------------------
# SpringDemo: 0.5 s'' = -10 (s + 0.5) - s' - 0.5 g

W_SPRING = math.sqrt(19.0)
S_EQ = -0.5 - 0.5 * G / 10.0           # -0.9905


def _spring_closed_form(t):
    a = 0.2 - S_EQ
    return S_EQ + np.exp(-t) * (a * np.cos(W_SPRING * t) + a / W_SPRING * np.sin(W_SPRING * t))


def test_spring_demo_equilibrium_and_closed_form():
    """s(t) follows the damped oscillation to 1e-8 (rtol 1e-10) and settles
    at s = -0.5 - 0.5*9.81/10 = -0.9905 m; the body passes through A
    (s = 0, zero spring and damper length) at 0.137 s."""
    times = np.linspace(0.0, 30.0, 6001)
    res = acausal2d.simulate(_model("SpringDemo")(), output_times=times, rtol=1e-10)
    s = res["prismatic.s"]
    assert np.max(np.abs(s - _spring_closed_form(times))) < 1e-8
    assert abs(s[-1] - S_EQ) < 1e-10
    assert abs(res["prismatic.v"][-1]) < 1e-10
    k = np.nonzero(np.diff(np.sign(s)) != 0)[0][0]
    t0 = times[k] - s[k] * (times[k + 1] - times[k]) / (s[k + 1] - s[k])
    assert t0 == pytest.approx(0.137, abs=1e-3)
    assert np.max(np.abs(res["body.x"] - 1.0)) < 1e-12     # the spring's x part is idle
    assert np.max(np.abs(res["body.phi"])) < 1e-12


def test_spring_demo_frequency():
    """The extrema of s (zeros of v) follow each other at half the damped
    period pi/sqrt(19) s (to 1e-6 s)."""
    times = np.linspace(0.0, 5.0, 20001)
    res = acausal2d.simulate(_model("SpringDemo")(), output_times=times, rtol=1e-10)
    v = res["prismatic.v"]
    k = np.nonzero((v[:-1] != 0) & (np.sign(v[:-1]) != np.sign(v[1:])))[0]
    zeros = times[k] - v[k] * (times[k + 1] - times[k]) / (v[k + 1] - v[k])
    assert len(zeros) >= 6
    assert np.max(np.abs(np.diff(zeros) - math.pi / W_SPRING)) < 1e-6
    first_min = np.argmin(res["prismatic.s"])
    assert res["prismatic.s"][first_min] == pytest.approx(-1.5696, abs=1e-4)
    assert times[first_min] == pytest.approx(0.721, abs=1e-3)


# --------------------------------------------------------------------------
# SpringDamperDemo: energy balance

def _audited_spring_damper_demo():
    """SpringDamperDemo with the dissipated energy integrated as a state."""
    base = _model("SpringDamperDemo")

    class Audited(base):
        dissipated = Variable(start=0.0, fixed=True, unit="J", doc="energy dissipated")

        def equations(self):
            return [der(self.dissipated) == self.springDamper.loss_power]

    return Audited()


def test_spring_damper_demo_energy_balance():
    """Stored + kinetic + potential + dissipated energy is constant to 1e-6
    relative at rtol 1e-8 (the total is 15.405 J)."""
    res = acausal2d.simulate(_audited_spring_damper_demo(), stop_time=5.0, rtol=1e-8,
                             output_times=np.linspace(0.0, 5.0, 2001))
    m, inertia = 0.5, 0.1
    kinetic = (0.5 * m * (res["body.vx"] ** 2 + res["body.vy"] ** 2)
               + 0.5 * inertia * res["body.w"] ** 2)
    potential = m * G * res["body.y"]
    total = res["springDamper.energy"] + kinetic + potential + res["dissipated"]
    stored0 = 0.5 * 5.0 * (2.0 ** 2 + 1.0 ** 2)
    assert total[0] == pytest.approx(stored0 + m * G * 1.0, rel=1e-12)
    assert np.max(np.abs(total - total[0])) / total[0] < 1e-6
    assert res["dissipated"][-1] > 10.0                 # most of it is gone by 5 s
    # the body does not turn: within the integrator's atol (rtol 1e-8 x nominal 1)
    assert np.max(np.abs(res["body.phi"])) <= 1e-8 and np.max(np.abs(res["body.w"])) <= 1e-8


def test_spring_damper_demo_closed_forms():
    """Two separate damped oscillators (README closed forms) to 1e-8."""
    times = np.linspace(0.0, 5.0, 501)
    res = acausal2d.simulate(_model("SpringDamperDemo")(), output_times=times, rtol=1e-10)
    e = np.exp(-times)
    x = -1 + e * (2 * np.cos(3 * times) + (2 / 3) * np.sin(3 * times))
    y = -0.981 + e * (1.981 * np.cos(3 * times) + (1.981 / 3) * np.sin(3 * times))
    assert np.max(np.abs(res["body.x"] - x)) < 1e-8
    assert np.max(np.abs(res["body.y"] - y)) < 1e-8


# --------------------------------------------------------------------------
# PendulumExcited: 1.1 phi'' = -g cos(phi) + F(t)

def _excitation(t):
    return np.where(t < 1.8, 0.0, -5.0 * np.sin(2 * np.pi * (t - 1.8)))


def _pendulum_excited_exact(times):
    def rhs(t, x):
        return [x[1], (-G * math.cos(x[0]) + float(_excitation(np.array(t)))) / 1.1]
    first = solve_ivp(rhs, (0.0, 1.8), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
                      dense_output=True)
    second = solve_ivp(rhs, (1.8, times[-1]), first.y[:, -1], method="DOP853", rtol=1e-13,
                       atol=1e-13, dense_output=True)
    return np.where(times < 1.8, first.sol(np.minimum(times, 1.8)),
                    second.sol(np.maximum(times, 1.8)))


def test_pendulum_excited_against_ode_and_cut_force_by_hand():
    """The motion equals the 1-DOF ODE (DOP853) to 1e-7 with the force
    switched on at t = 1.8 s (a time event).  The CutForce output (force
    from the rod on the body, in the rod's axes) equals the hand value
    m (-w^2, phi'') - m g_rod - (0, F), g_rod = R(phi)^T g, to 1e-8."""
    times = np.linspace(0.0, 3.0, 601)
    res = acausal2d.simulate(_model("PendulumExcited")(), output_times=times, rtol=1e-11)
    assert [t for t, _ in res.events] == [pytest.approx(1.8, abs=1e-12)]
    exact = _pendulum_excited_exact(res.time)
    assert np.max(np.abs(res["revolute.phi"] - exact[0])) < 1e-7
    assert np.max(np.abs(res["revolute.w"] - exact[1])) < 1e-7
    phi, w = res["revolute.phi"], res["revolute.w"]
    z = (-G * np.cos(phi) + _excitation(res.time)) / 1.1
    fx = -w ** 2 + G * np.sin(phi)                          # m = 1 kg
    fy = z + G * np.cos(phi) - _excitation(res.time)
    post = np.ones(len(res.time), dtype=bool)
    post[np.nonzero(same_time(res.time, 1.8))[0][:-1]] = False       # left limits at the event
    assert np.max(np.abs(res["cutForce.f_x.u"] - fx)) < 1e-8
    assert np.max(np.abs((res["cutForce.f_y.u"] - fy)[post])) < 1e-8
    assert np.max(np.abs(res["worldForce.fx"] + _excitation(res.time) * np.sin(phi))[post]) < 1e-9


# --------------------------------------------------------------------------
# InvertedCraneCrab: the prescribed angle and the solved force

def _prescribed_angle(t):
    y05 = -0.1 + 0.1 * math.exp(-5.0)
    return np.where(t <= 0.5, -0.6 + t + 0.1 * np.exp(-10 * t), y05 * np.exp(-10 * (t - 0.5)))


def test_inverted_crane_crab_is_an_inverse_model():
    """The revolute angle follows the prescription (ramp through a
    first-order lag with a steady-state start) to 1e-8; the cart obeys
    0.6 phi'' - 0.5 g sin(phi) = 0.5 cos(phi) s'' (s''(0) = 19.033 m/s^2,
    cart motion against an ODE solution to 1e-7); the solved force F is
    Newton's horizontal balance of cart and pendulum."""
    times = np.linspace(0.0, 3.0, 601)
    res = acausal2d.simulate(_model("InvertedCraneCrab")(), output_times=times, rtol=1e-11)
    t = res.time
    phi = res["revolute.phi"]
    assert np.max(np.abs(phi - _prescribed_angle(t))) < 1e-8
    assert np.max(np.abs(res["body.phi"] - phi)) < 1e-12
    assert abs(phi[0] + 0.5) < 1e-12 and abs(res["revolute.w"][0]) < 1e-12
    assert res["firstOrder.y_value"][0] == pytest.approx(-0.5, abs=1e-12)

    def phi_dd(tt):
        y05 = -0.1 + 0.1 * math.exp(-5.0)
        return 10 * math.exp(-10 * tt) if tt < 0.5 else 100 * y05 * math.exp(-10 * (tt - 0.5))

    def rhs(tt, x):
        p = float(_prescribed_angle(np.array(tt)))
        return [x[1], (0.6 * phi_dd(tt) - 0.5 * G * math.sin(p)) / (0.5 * math.cos(p))]

    a = solve_ivp(rhs, (0, 0.5), [0, 0], method="DOP853", rtol=1e-13, atol=1e-13,
                  dense_output=True)
    b = solve_ivp(rhs, (0.5, 3.0), a.y[:, -1], method="DOP853", rtol=1e-13, atol=1e-13,
                  dense_output=True)
    cart = np.where(t <= 0.5, a.sol(np.minimum(t, 0.5)), b.sol(np.maximum(t, 0.5)))
    assert np.max(np.abs(res["prismatic.s"] - cart[0])) < 1e-7
    assert np.max(np.abs(res["prismatic.v"] - cart[1])) < 1e-7
    s_dd, z = res["der(der(prismatic.s))"], res["der(der(revolute.phi))"]
    assert rhs(0.0, [0, 0])[1] == pytest.approx(19.033, abs=1e-3)
    assert s_dd[0] == pytest.approx(rhs(0.0, [0, 0])[1], rel=1e-8)
    assert z[0] == pytest.approx(10.0, rel=1e-8)
    event = np.nonzero(same_time(t, 0.5))[0]
    # the first row at t = 0.5 is the left limit, the last the right one (an
    # output time on a time event gives one more row: tests/test_runtime_repro_14.py)
    assert len(event) >= 2 and z[event[0]] - z[event[-1]] == pytest.approx(10.0, rel=1e-8)
    smooth = np.ones(len(t), dtype=bool)
    smooth[event[:-1]] = False                  # left limit at the event
    zz = np.array([phi_dd(x) for x in t])
    assert np.max(np.abs(z - zz)[smooth]) < 1e-7
    w = res["revolute.w"]
    force = 1.5 * s_dd + 0.5 * (-np.cos(phi) * z + np.sin(phi) * w ** 2)
    assert np.max(np.abs(res["force.f_in.u"] - force)) < 1e-9
    assert res["force.f_in.u"][0] == pytest.approx(1.5 * 19.0329 + 0.5 * -np.cos(0.5) * 10,
                                                   abs=1e-2)


# --------------------------------------------------------------------------
# IdealRolling

class WheelOnSlope(Component):
    """A wheel (m, I about its centre) rolling on a slope of angle alpha:
    the ground line is y = 0 and gravity is tilted by alpha."""

    def __init__(self, alpha=0.3, radius=0.3, m=2.0, inertia=0.05, **kw):
        super().__init__(**kw)
        self.world = PlanarWorld(g=(G * math.sin(alpha), -G * math.cos(alpha)))
        self.rolling = IdealRolling(R=radius, x0=0.2, phi=start(0.0, fixed=True),
                                    w=start(0.0, fixed=True))
        self.body = Body(m=m, I=inertia)
        self.connect(self.rolling.frame_a, self.body.frame_a)


def test_ideal_rolling_wheel_on_slope():
    """The wheel accelerates at g sin(alpha)/(1 + I/(m R^2)) (to 1e-6
    relative); the contact point (x, 0) has zero velocity vx + R w (to
    1e-9); the ground pushes the wheel up the slope with m a - m g
    sin(alpha) through the contact point."""
    alpha, radius, m, inertia = 0.3, 0.3, 2.0, 0.05
    times = np.linspace(0.0, 2.0, 201)
    res = acausal2d.simulate(WheelOnSlope(alpha, radius, m, inertia), output_times=times,
                             rtol=1e-10)
    acc = G * math.sin(alpha) / (1 + inertia / (m * radius ** 2))
    vx = res["rolling.vx"]
    assert np.max(np.abs(vx[1:] / times[1:] - acc)) / acc < 1e-6
    assert np.max(np.abs(res["rolling.x"] - (0.2 + 0.5 * acc * times ** 2))) < 1e-6 * acc
    assert np.max(np.abs(res["der(der(rolling.x))"] - acc)) / acc < 1e-6
    assert np.max(np.abs(vx + radius * res["rolling.w"])) < 1e-9
    assert np.max(np.abs(res["body.y"] - radius)) < 1e-12
    friction = -res["rolling.frame_a.fx"]
    assert np.max(np.abs(friction - (m * acc - m * G * math.sin(alpha)))) < 1e-6
    assert np.max(np.abs(res["rolling.frame_a.t"] - radius * res["rolling.frame_a.fx"])) < 1e-12


@pytest.mark.parametrize("model,dof", [("wheel", 1), ("PendulumExcited", 1), ("MeasureDemo", 2),
                                       ("SpringDemo", 1), ("SpringDamperDemo", 3)])
def test_degree_of_freedom_counts(model, dof):
    """``check`` counts the seed's eq. 2.1 like the structure: the rolling
    contact is a joint of one DOF against the ground, the cut sensors join
    rod and body into one link, force elements and kinematic sensors add no
    link."""
    instance = WheelOnSlope() if model == "wheel" else _model(model)()
    report = acausal2d.check(instance)
    assert report.grubler == dof and report.structural_dof == dof
