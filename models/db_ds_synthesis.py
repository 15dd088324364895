"""Band synthesis of a DB~DS mechanism with the slider in the ground (Ebert 2015,
ch. 7.2.2, Bild 7.15-7.20): a band from a cam to a slider on a horizontal
slide line through the cam pivot P1 (centric); the slider moves from a
section of small constant speed to a section of larger constant speed, the
transition of the speed a polynomial of degree 5 (shock- and jerk-free).

The model is the dissertation's Bild 7.16: the slider is the linkage element SAN,
driven along its guide by the transfer function, and its slider point is
connected directly to ``Bandkurve`` (no special synthesis element: the band
is fastened to the slider's pivot).  ``Bandkurve(criteria=True)`` computes
involute, evolute (the cam contour, Bild 7.17) and the criteria of ch. 5
(Bild 7.19).  ``acausal2d simulate models/db_ds_synthesis.py`` writes, besides
the result, the contour plot, the assessment plot and report and the cam
contour as CSV, SVG and DXF (the dissertation laser-cut this cam, Bild 7.20).

Values from the dissertation: centric horizontal slide line, slider start xS0 = 100
mm from P1, the band wound up by a counter-clockwise cam turn, speed
transition by a degree-5 polynomial; assessment results: |r_k| (free band
length) between 100 and 350 mm, no sign change of its change, largest cam
radius about 120 mm.

Values chosen here (Bild 7.15 is lost) [guess], so that these results are
met: the drive parameter psi = t runs 0 .. 4 rad at 1 rad/s; the cam turns
clockwise, phi_P1 = -psi, paying the band out (seen the other way round: a
counter-clockwise turn winds it up and pulls the slider in); the slider
travel x_S(psi) = 0.1 m + 0.02 m/rad psi up to psi1 = 0.5 rad, then the
speed dx_S/dpsi goes from 0.02 to 0.12 m/rad with 10 s^3 - 15 s^4 + 6 s^5
(s = (psi - psi1)/3 rad, zero first and second derivative at both ends) up
to psi2 = 3.5 rad, then 0.12 m/rad.  This gives l_Bf = 98 .. 365 mm, max a =
114 mm and a constant S_Bf.
"""
import functools
import os

import casadi as ca
import numpy as np

from acausal2d import Component
from acausal2d.library import rotational, signals, translational
from acausal2d.library.synthesis.assessment import new_figure
from acausal2d.library.synthesis.functional import BandStructure, synthesize
from acausal2d.library.synthesis import Bandkurve
from acausal2d.library.synthesis.contour_export import cam_outline, export_contour
from acausal2d.library.linkage import SAN
from acausal2d.library.planar import Fixed, Revolute
from acausal2d.io.files import write_text
from acausal2d.visual.plotting import save_figure

XS0 = 0.10                    # m, slider start distance from P1
V1, V2 = 0.02, 0.12           # m/rad, slider speeds per radian of cam angle
PSI1, PSI2 = 0.5, 3.5         # rad, speed transition
PSI_END = 4.0                 # rad


def travel(psi):
    """Slider travel x_S(psi) [m] (module docstring) for a number, numpy
    array or CasADi expression ``psi``: linear, speed transition with the
    integral of the degree-5 step, linear."""
    d = PSI2 - PSI1
    s = (psi - PSI1) / d
    x1 = XS0 + V1 * PSI1
    mid = x1 + V1 * (psi - PSI1) + (V2 - V1) * d * s ** 4 * (2.5 - 3.0 * s + s * s)
    x2 = x1 + V1 * d + 0.5 * (V2 - V1) * d
    return ca.if_else(psi < PSI1, XS0 + V1 * psi,
                      ca.if_else(psi < PSI2, mid, x2 + V2 * (psi - PSI2)))


def structure():
    """The functional form (:class:`BandStructure.slider`) over the drive
    parameter psi: cam angle -psi, slider on the x axis."""
    s = BandStructure.slider((0.0, 0.0), (0.0, 0.0), 0.0, travel, cam_angle=lambda p: -p)
    s.name = "DB~DS cam"
    return s


@functools.lru_cache(maxsize=1)
def design(n=401):
    """Functional synthesis over psi = 0 .. 4 rad (exact derivatives)."""
    return synthesize(structure(), np.linspace(0.0, PSI_END, n))


class DBDSSynthesis(Component):
    """DB~DS synthesis model (Ebert 2015, Bild 7.16): cam pivot P1 at the origin,
    turned clockwise at 1 rad/s; SAN slider on the x axis driven by
    :func:`travel`; Bandkurve on the slider point."""
    experiment = {"stop_time": PSI_END, "intervals": 400, "rtol": 1e-10}
    outputs = ["bandkurve.l_Bf", "bandkurve.dl_Bf", "bandkurve.a", "bandkurve.h",
               "bandkurve.rho_cam", "slider.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.P1 = Fixed()
        self.cam = Revolute(use_flange=True)
        self.cam_drive = rotational.Position()
        self.cam_angle = signals.TimeFunction(lambda t: -t)
        self.slider = SAN(x10=0.0, y10=0.0, phi10=0.0, v=0.0, mS=0.2, JS=1e-4)
        self.slide = translational.Position()
        self.motion = signals.TimeFunction(travel)
        self.bandkurve = Bandkurve(criteria=True)
        self.connect(self.P1.frame, self.cam.frame_a)
        self.connect(self.cam_angle.y, self.cam_drive.phi_in)
        self.connect(self.cam_drive.flange, self.cam.flange_a)
        self.connect(self.motion.y, self.slide.s_in)
        self.connect(self.slide.flange, self.slider.ctrT2)
        self.connect(self.cam.frame_b, self.bandkurve.ctr2D1)
        self.connect(self.slider.ctr2D2, self.bandkurve.ctr2D2)

    def write_outputs(self, res, folder):
        """Involute/evolute plot (Bild 7.17), assessment plot and report
        (Bild 7.19) and the contour files."""
        syn = design()
        a = syn.assess(a_max=0.12)
        report = write_text(os.path.join(folder, "db_ds_assessment.txt"), a.report() + "\n")
        return ([_plot(res, os.path.join(folder, "db_ds_involute_evolute.png")),
                 plot_cam(syn, os.path.join(folder, "db_ds_cam.png")),
                 a.plot(os.path.join(folder, "db_ds_criteria.png")), report]
                + export_contour(syn, folder, "db_ds_cam"))


def plot_cam(syn, path):
    """The cam plate (manufacturing outline) in the cam frame with the
    involute of the slider pivot and free bands at every 0.5 rad (the
    picture of the README)."""
    out = cam_outline(syn)
    fig, ax = new_figure(size=(6.5, 6))
    ax.fill(out.x, out.y, color="#dde6f0", ec="#1f4e79", lw=1.5, label="cam plate")
    ax.plot(syn.x_u, syn.y_u, color="#1f4e79", lw=3, label="synthesised contour (evolute)")
    ax.plot(syn.x_e, syn.y_e, color="darkorange", lw=1.2, label="involute of the slider pivot")
    for p in np.arange(0.0, PSI_END + 1e-9, 0.5):
        v = syn.evaluate([p])
        ax.plot([v["x_u"][0], v["x_e"][0]], [v["y_u"][0], v["y_e"][0]], "-", color="gray", lw=0.8)
        ax.plot(v["x_u"], v["y_u"], "o", color="#1f4e79", ms=3)
    ax.plot([0.0], [0.0], "+", color="#c00000", ms=14, mew=2, label="cam pivot")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m] (cam frame)")
    ax.set_ylabel("y [m]")
    ax.set_title("DB~DS cam (Ebert 2015, ch. 7.2.2) with free bands every 0.5 rad")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    return path


def _plot(res, path):
    fig, ax = new_figure(size=(7, 6))
    ax.plot(res["bandkurve.xe"], res["bandkurve.ye"], label="involute (slider pivot)")
    ax.plot(res["bandkurve.xu"], res["bandkurve.yu"], lw=2.5, label="evolute = cam contour")
    ax.plot([0.0], [0.0], "k+", ms=12, mew=2, label="cam pivot P1")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x [m] (cam frame)")
    ax.set_ylabel("y [m]")
    ax.set_title("DB~DS: involute and evolute (Bild 7.17)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)
    return path


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
