"""A crank-rocker four-bar on an elastic drive shaft, for its natural
frequency at a crank angle (``acausal2d modes``).

Links as BodyShapes (mass at the middle, I = m l^2 / 12 about it): crank
a = 0.10 m (0.5 kg), coupler b = 0.35 m (1.2 kg), rocker c = 0.25 m
(0.8 kg), ground D = 0.30 m (Grashof: a + b < c + D, the crank turns).  No
gravity.  The crank is held at the angle ``hold.phi0`` by a torsion spring
(``shaft``, c = 200 N.m/rad; a motor shaft standing still), so the
mechanism rests at that crank angle and oscillates about it with

    omega = sqrt(c / J_red(phi)),

J_red the inertia of all links reduced to the crank (the kinetic energy
2 T / phi'^2), which changes with the crank angle: a one-degree-of-freedom
linkage has one mode whose frequency follows the angle.

    acausal2d modes models/four_bar_modes.py --equilibrium --set hold.phi0=1.2
    acausal2d modes models/four_bar_modes.py --equilibrium \
        --vary hold.phi0=0:6.283:25 --count 1

The second line draws the frequency over the crank angle (campbell.png).
"""
import math

import numpy as np

from acausal2d import Component, start
from acausal2d.library import rotational
from acausal2d.library.planar import BodyShape, Fixed, Revolute
from acausal2d.library.planar.base import PlanarWorld

A, B, C, D = 0.10, 0.35, 0.25, 0.30
MASS = {"crank": 0.5, "coupler": 1.2, "rocker": 0.8}
C_SHAFT = 200.0
PHI0 = math.radians(60.0)


def assembly(phi):
    """Coupler angle theta and rocker angle psi (direction D -> C) of the
    crank angle phi, on the branch with the coupler above the ground line."""
    bx, by = A * math.cos(phi), A * math.sin(phi)
    dx, dy = D - bx, -by
    L = math.hypot(dx, dy)
    ex, ey = dx / L, dy / L
    x = (B * B - C * C + L * L) / (2 * L)
    h = math.sqrt(B * B - x * x)
    cx, cy = bx + x * ex - h * ey, by + x * ey + h * ex
    return math.atan2(cy - by, cx - bx), math.atan2(cy, cx - D)


def reduced_inertia(phi):
    """J_red(phi) = 2 T / phi'^2 of the three links (closed form: velocity
    ratios from the derivative of the loop closure a e^(i phi) + b e^(i theta)
    = D + c e^(i psi))."""
    th, ps = assembly(phi)
    M = np.array([[-B * math.sin(th), C * math.sin(ps)], [B * math.cos(th), -C * math.cos(ps)]])
    rhs = np.array([A * math.sin(phi), -A * math.cos(phi)])
    dth, dps = np.linalg.solve(M, rhs)
    vb = A * np.array([-math.sin(phi), math.cos(phi)])
    vcm = vb + B / 2 * dth * np.array([-math.sin(th), math.cos(th)])
    inertia = {k: m * l * l / 12 for (k, m), l in zip(MASS.items(), (A, B, C))}
    return (inertia["crank"] + MASS["crank"] * A * A / 4
            + MASS["coupler"] * vcm @ vcm + inertia["coupler"] * dth ** 2
            + (inertia["rocker"] + MASS["rocker"] * C * C / 4) * dps ** 2)


def _link(length, mass):
    return BodyShape(r=(length, 0.0), r_CM=(length / 2, 0.0), m=mass,
                     I=mass * length * length / 12, width=0.02)


class FourBarOnShaft(Component):
    """The four-bar resting at crank angle ``hold.phi0`` on its elastic
    drive shaft (see the module docstring)."""
    experiment = {"stop_time": 0.2, "intervals": 400}
    outputs = ["ja.phi", "jd.phi"]

    def __init__(self, **kw):
        super().__init__(**kw)
        th, ps = assembly(PHI0)
        self.world = PlanarWorld(g=(0.0, 0.0))
        self.ground_a = Fixed()
        self.ground_d = Fixed(r=(D, 0.0))
        self.hold = rotational.Fixed(phi0=PHI0)
        self.shaft = rotational.Spring(c=C_SHAFT)
        self.ja = Revolute(use_flange=True, phi=start(PHI0, fixed=True), w=start(0.0, fixed=True))
        self.crank = _link(A, MASS["crank"])
        self.jb = Revolute(phi=start(th - PHI0))
        self.coupler = _link(B, MASS["coupler"])
        self.jc = Revolute(phi=start(ps + math.pi - th))
        self.rocker = _link(C, MASS["rocker"])            # from C to D
        self.jd = Revolute(phi=start(-ps - math.pi))      # back to the ground frame
        self.connect(self.hold.flange, self.shaft.flange_a)
        self.connect(self.shaft.flange_b, self.ja.flange_a)
        self.connect(self.ground_a.frame, self.ja.frame_a)
        self.connect(self.ja.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.jb.frame_a)
        self.connect(self.jb.frame_b, self.coupler.frame_a)
        self.connect(self.coupler.frame_b, self.jc.frame_a)
        self.connect(self.jc.frame_b, self.rocker.frame_a)
        self.connect(self.rocker.frame_b, self.jd.frame_a)
        self.connect(self.jd.frame_b, self.ground_d.frame)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import main
    sys.exit(main(["modes", __file__, "--equilibrium"] + sys.argv[1:]))
