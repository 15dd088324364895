"""Hain's spring-lever balance (Ebert 2015, ch. 3.4, eq. 3.10-3.12, Bild 3.11 a).

A lever of length r turns about the ground pivot O and carries a mass m at
the distance k; a tension spring (rate c_S, free length a) runs from the
ground point B at the distance b straight above O to the lever end.  With
phi the angle between the lever and the line O -> B, the spring's torque
about O is (eq. 3.10)

    T(phi) = r b c_S sin(phi) (1 - a / sqrt(r^2 + b^2 - 2 r b cos(phi))),

for a = 0 (the ideal zero-free-length spring) T = r b c_S sin(phi) (3.11),
and the weight's torque m g k sin(phi) is balanced at every angle for

    c_S = m g k / (r b)                                               (3.12).

Model: the lever is the linkage element DAN (lever length r, mass m at k,
driven at a constant speed by a Preset); the spring is a line of library
elements: ``planar.Fixed`` at B, a ``Revolute``, a ``Prismatic`` whose travel
is the spring length and a ``translational.Spring`` (s_rel0 = a) on its
flange, a second ``Revolute`` at the lever end.  At constant speed the lever
has no angular acceleration, so the drive torque ``drive.tau`` is the
static torque left over: zero for the balance 3.12.

Values [guess] (the mec2 example loads_3.json of Schnabel and Gössner's web tool has
this configuration): r = b = 0.5 m, the two 1 kg masses of that example at
0.5 m and 1.5 m replaced by m = 2 kg at their centre k = 1 m, lever inertia
0.5 kg m^2, g = 9.81 m/s^2, so c_S = 78.48 N/m (mec2 uses g = 10: 80 N/m);
the lever turns from -1.2 rad to +1.2 rad measured from the horizontal (phi
= 2.77 .. 0.37 rad from the vertical), avoiding phi = 0 where the lever end
(r = b) meets B; speed 0.5 rad/s.
"""
import math
import os

import numpy as np

from acausal2d import Component, start
from acausal2d.library import translational
from acausal2d.library.synthesis.assessment import new_figure
from acausal2d.library.linkage import DAN
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Fixed, Prismatic, Revolute
from acausal2d.visual.plotting import save_figure

R_LEVER = 0.5
B_HEIGHT = 0.5
MASS = 2.0
K_COG = 1.0
G = 9.81
C_BALANCE = MASS * G * K_COG / (R_LEVER * B_HEIGHT)      # eq. 3.12
THETA0, THETA1 = -1.2, 1.2                               # lever angle from the horizontal
OMEGA = 0.5


def spring_torque(phi, c_S, a=0.0, r=R_LEVER, b=B_HEIGHT):
    """Spring torque about the pivot, Ebert (2015), eq. 3.10 (phi from the vertical)."""
    return r * b * c_S * np.sin(phi) * (1.0 - a / np.sqrt(r * r + b * b - 2 * r * b * np.cos(phi)))


class HainSpringLever(Component):
    """Lever with mass and spring (module docstring).  ``c_S`` (default: the
    balance 3.12) and ``a`` (free spring length) are parameters of
    ``spring`` (``spring.c``, ``spring.s_rel0``)."""
    experiment = {"stop_time": (THETA1 - THETA0) / OMEGA, "intervals": 240, "rtol": 1e-10}
    outputs = ["drive.tau", "lever.phiL", "slide.s"]

    def __init__(self, c_S=C_BALANCE, a=0.0, **kw):
        super().__init__(**kw)
        self.lever = DAN(x10=0.0, y10=0.0, lL=R_LEVER, mL=MASS, JL=0.5, xSLrel=K_COG,
                         phiL0=THETA0)
        self.drive = Preset(kind="speed", om=OMEGA, phi0=THETA0)
        self.connect(self.drive.flange, self.lever.ctrR2)
        end = (R_LEVER * math.cos(THETA0), R_LEVER * math.sin(THETA0))
        dx, dy = end[0], end[1] - B_HEIGHT
        self.B = Fixed(r=(0.0, B_HEIGHT))
        self.pivot_B = Revolute(phi=start(math.atan2(dy, dx)))
        self.slide = Prismatic(r=(1.0, 0.0), use_flange=True, s=start(math.hypot(dx, dy)))
        self.pivot_end = Revolute()
        self.spring = translational.Spring(c=c_S, s_rel0=a)
        self.connect(self.B.frame, self.pivot_B.frame_a)
        self.connect(self.pivot_B.frame_b, self.slide.frame_a)
        self.connect(self.slide.frame_b, self.pivot_end.frame_a)
        self.connect(self.pivot_end.frame_b, self.lever.ctr2D2)
        self.connect(self.slide.support, self.spring.flange_a)
        self.connect(self.slide.flange_a, self.spring.flange_b)

    def write_outputs(self, res, folder):
        """Drive torque against the torques of weight and spring (3.10-3.12)."""
        phi = math.pi / 2 - res["lever.phiL"]
        fig, ax = new_figure(size=(7, 4.5))
        ax.plot(np.degrees(phi), MASS * G * K_COG * np.sin(phi), label="weight m g k sin(phi)")
        ax.plot(np.degrees(phi), spring_torque(phi, res["spring.c"][0], res["spring.s_rel0"][0]),
                "--", label="spring, eq. 3.10")
        ax.plot(np.degrees(phi), res["drive.tau"], label="drive torque (simulation)")
        ax.set_xlabel("lever angle phi from the vertical [deg]")
        ax.set_ylabel("torque [N m]")
        ax.set_title("Hain's spring-lever balance (eq. 3.10-3.12)")
        ax.grid(True, alpha=0.3)
        ax.legend()
        fig.tight_layout()
        path = os.path.join(folder, "hain_torques.png")
        save_figure(fig, path, dpi=100)
        return [path]


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
