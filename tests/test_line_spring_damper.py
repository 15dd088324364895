"""The line spring-damper (seed Bild 4.1: a planar spring-damper-mass
oscillator; library/planar/forces.py:LineSpringDamper) against closed
forms: the static deflection, natural frequency and damping of the motion
along the line, and the pendulum frequency across it (which a world-axis
spring would not give)."""
import math

import numpy as np

import acausal2d
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed
from acausal2d.library.planar.forces import LineSpringDamper

G = 9.81
M, C, L0 = 2.0, 800.0, 0.3          # kg, N/m, m
L_EQ = L0 + M * G / C                # static length under gravity


class Bild41(Component):
    """A body hung from a fixed point by the line spring-damper, under
    gravity (-y): the planar spring-damper-mass oscillator of seed Bild 4.1.
    The body starts at rest at (x0, -y0) with phi = 0."""

    def __init__(self, x0=0.0, y0=L_EQ, d=0.0, **kw):
        super().__init__(**kw)
        self.anchor = Fixed(r=(0.0, 0.0))
        self.sd = LineSpringDamper(c=C, d=d, s_unstretched=L0)
        self.body = Body(m=M, I=0.01, x=start(x0, fixed=True), y=start(-y0, fixed=True),
                         phi=start(0.0, fixed=True), vx=start(0.0, fixed=True),
                         vy=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.connect(self.anchor.frame, self.sd.frame_a)
        self.connect(self.sd.frame_b, self.body.frame_a)


def test_motion_along_the_line_is_the_damped_oscillator():
    """Released 40 mm below the static length L0 + m g/c: the extension
    beyond it, u, obeys m u'' + d u' + c u = 0 (omega_n = sqrt(c/m) = 20
    rad/s, zeta = d/(2 sqrt(c m)) = 0.1), closed form to 1e-7 m (rtol 1e-11
    on a 0.04 m amplitude, with room); the force is the spring plus the
    damper, the loss power d v^2, the body does not turn."""
    d = 2 * 0.1 * math.sqrt(C * M)
    times = np.linspace(0.0, 2.0, 401)
    res = acausal2d.simulate(Bild41(y0=L_EQ + 0.04, d=d), output_times=times, rtol=1e-11)
    wn, zeta = math.sqrt(C / M), 0.1
    wd = wn * math.sqrt(1 - zeta ** 2)
    u = 0.04 * np.exp(-zeta * wn * times) * (np.cos(wd * times)
                                             + zeta * wn / wd * np.sin(wd * times))
    assert np.max(np.abs(-res["body.y"] - L_EQ - u)) < 1e-7
    assert np.max(np.abs(res["body.x"])) < 1e-9
    assert np.max(np.abs(res["body.phi"])) < 1e-9
    assert np.max(np.abs(res["sd.length"] + res["body.y"])) < 1e-9
    v = -res["body.vy"]
    f = C * (res["sd.length"] - L0) + d * v
    assert np.max(np.abs(res["sd.f"] - f)) < 1e-6 * C * 0.04
    assert np.max(np.abs(res["sd.loss_power"] - d * v ** 2)) < 1e-6
    # about the static deflection m g / c: f - m g = c u + d u'
    du = -0.04 * wn ** 2 / wd * np.exp(-zeta * wn * times) * np.sin(wd * times)
    assert np.max(np.abs(res["sd.f"] - M * G - C * u - d * du)) < 1e-7 * (C + d * wn)


def test_motion_across_the_line_is_the_pendulum():
    """Displaced sideways by theta0 = 1e-3 rad at the static length, the
    undamped body swings as a pendulum of length L0 + m g/c: x = x0
    cos(sqrt(g/L) t) to second order in theta0 (relative 1e-6 over three
    periods), bounded here by 1e-4 x0 (rtol 1e-11).  A spring on the world
    axes (PlanarMechanics Parts.Spring) would give sqrt(c/m) instead."""
    theta0 = 1e-3
    x0, y0 = L_EQ * math.sin(theta0), L_EQ * math.cos(theta0)
    w = math.sqrt(G / L_EQ)
    times = np.linspace(0.0, 3 * 2 * math.pi / w, 601)
    res = acausal2d.simulate(Bild41(x0=x0, y0=y0), output_times=times, rtol=1e-11)
    assert np.max(np.abs(res["body.x"] - x0 * np.cos(w * times))) < 1e-4 * x0
    energy = (0.5 * M * (res["body.vx"] ** 2 + res["body.vy"] ** 2) + M * G * res["body.y"]
              + res["sd.energy"])
    assert np.max(np.abs(energy - energy[0])) < 1e-8 * M * G * L_EQ
