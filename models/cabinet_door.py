"""Spring-band balancing of a kitchen wall-cabinet door (Ebert 2015, ch. 7.2.1,
Bild 7.7-7.14), in three parts:

1. :class:`DoorMechanism` -- the door as the coupler of a four-bar linkage
   (one hinge fitting with half the door mass), driven quasi-statically:
   its drive torque is the required balancing torque T(phi) (replaces the
   dissertation's measurement, Bild 7.8), fitted by a regression polynomial;
2. :class:`BalancingSynthesis` -- the dissertation's synthesis model (Bild 7.10):
   presets "Drehpunkt A0" (the cam, turning at 1 rad/s) and "Drehpunkt B0"
   (the spring pivot), ``DB_SD`` (K = -1) fed with the lever arm h(phi) from
   the ch. 6 optimisation, ``Bandkurve`` with the ch. 5 criteria;
3. :class:`BalancedDoor` -- the door with the synthesised cam
   (``CurvedDrum``) on the door-side rocker and the band with the tension
   spring (``SpringBelt``, 938 N/m) to B0: the door is balanced at every
   angle (drive torque ~ 0).

``acausal2d simulate models/cabinet_door.py`` runs the balanced door;
``--model DoorMechanism`` and ``--model BalancingSynthesis`` the other
parts.  Each writes its plots; the synthesis also writes the cam contour
(CSV, SVG, DXF) and the assessment report.  The design (parts 1 -> 2, ch. 6)
is computed once per process by :func:`door_design`.

Values from the dissertation: A0 = (0, 0), B0 = (-296, 0) mm, cam at 1 rad/s, K = -1
(contact right of the line A0 -> B0), spring rate c_S = 0.938 N/mm, lever
arm h < 80 mm, two optimisation runs (free c_S with h < 80 mm, then c_S
fixed), one hinge fitting with half the door-leaf mass; the experiment
(Bild 7.13) balances one four-bar with a 2 kg mass at the coupler's centre
of gravity "to reproduce the real door mass" and the door then stays in
any position, so the design mass on the coupler is 2 kg.

What the dissertation lacks: the dimensions of the four-bar and of the door leaf
(Bild 7.7, 7.12 lost), the measured torque (Bild 7.8), the spring's
extension (pretension) and the coefficients of Bild 7.9.  Run 1 has a
closed form here: the lever arm is largest with the door open, where the
spring's extension is least, so the softest spring keeping h <= h_max is
c_S = T(open)/(h_max x_S(open)).  Its rate is therefore set by the
unstated pretension: with the required torque of this door (T(open) =
2.67 N m) an open extension of 30 mm gives 1114 N/m, 36 mm 928 N/m (and
the earlier 1 kg coupler with 30 mm 562.5 N/m).

Values chosen here (the dissertation's drawings are lost) [guess]:

- four-bar: door-side rocker A0 -> A of 100 mm (the cam sits on its axis),
  second rocker D0 = (-40, -60) mm -> D of 120 mm, coupler A -> D of 100 mm
  (assembly K = +1); the door leaf is the coupler: 2 kg at 250 mm from A
  perpendicular to A -> D (to the right of it), J = 0.04 kg m^2; rockers
  0.05 kg, 1e-4 kg m^2.  The rocker turns from -80 deg (door closed, down
  in front of the cabinet) to +20 deg (open, lifted about 0.5 m): a span of
  100 deg, the cam angle phi = 0 .. 1.745 rad;
- the door opens with the rocker turning counter-clockwise and the cam pays
  the band out (K = -1, h > 0), so the spring is stretched most with the
  door closed.  Eq. 6.5 (T = c_S x_S x_S', x_S the spring extension,
  h = x_S') is solved in the closing angle psi = 1.745 rad - phi, in which
  the spring is stretched as psi grows (the dissertation's sign convention);
- spring: extension X_OPEN = 36 mm with the door open (pretension 33.8 N),
  unloaded length l0 = 100 mm.  **X_OPEN is chosen to match the dissertation's
  number**: run 1 then gives c_S = 928 N/m, and the dissertation's catalogue
  spring, 0.938 N/mm, is the one next to it (1.1 % stiffer, so h stays
  below 80 mm in run 2); the spring eye (the band fixing point, the material
  point P3 of DB~SD) lies between B0 and the cam at l0 + x_S from B0, so
  DB~SD's x0 = -(l0 + x_S(closed));
- regression of the required torque: polynomial of degree 5 (the dissertation used
  degree 3 on measured data, R^2 = 99.7 %; here degree 3 departs from the
  computed torque by up to 0.99 % of its largest value, degree 5 by 0.29 %,
  R^2 = 0.99999);
- ch. 6 ansatz: polynomial of degree 5 (the dissertation used 3, "1 to 5 give good
  results"): degree 3 leaves a torque residual of 2.5 % of the largest
  required torque, degree 5 0.88 %, and the balanced door keeps 0.74 % (the
  test asks for < 1 %).  Run 1 (c_S free, h <= 80 mm): the softest spring
  928 N/m; run 2 fits with the dissertation's c_S = 938 N/m, h = 52.7 .. 77.2 mm;
- space for the cam: radius up to A_MAX = 90 mm (the dissertation bounds the lever
  arm only; with h up to 77 mm the cam reaches 81.5 mm);
- quasi-static runs: rocker speed 0.01 rad/s (inertia torques below 1e-5 N m).
"""
import functools
import math
import os

import numpy as np

from acausal2d import Component, simulate, start
from acausal2d.library import signals
from acausal2d.library.synthesis.balancing import spring_band_transfer
from acausal2d.library.synthesis.functional import BandStructure, synthesize
from acausal2d.library.synthesis import Bandkurve, DB_SD
from acausal2d.library.belt import SpringBelt, connect_band
from acausal2d.library.belt.curved import CurvedDrum
from acausal2d.library.synthesis.assessment import new_figure
from acausal2d.library.synthesis.contour_export import analysis_contour, export_contour
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Fixed, Revolute
from acausal2d.io.files import write_text
from acausal2d.visual.plotting import save_figure

A0 = (0.0, 0.0)
B0 = (-0.296, 0.0)
PHI_CLOSED = math.radians(-80.0)
SPAN = math.radians(100.0)
OMEGA_STATIC = 0.01           # rad/s, quasi-static rocker speed
C_SPRING = 938.0              # N/m (0.938 N/mm)
H_MAX = 0.08                  # m
A_MAX = 0.09                  # m, largest cam radius (assumed, see above)
X_OPEN = 0.036                # m, spring extension with the door open (chosen for run 1, see above)
L0_SPRING = 0.10              # m, unloaded spring length
ROCKER_L = 0.10               # m, door-side rocker A0 -> its joint with the coupler
DEGREE = 5
QUASI_STATIC = {"stop_time": SPAN / OMEGA_STATIC, "intervals": 200, "rtol": 1e-9}


def _add_door(model):
    """The four-bar door mechanism (module docstring) with a quasi-static
    speed preset on the door-side rocker, into ``model``."""
    model.rocker = DAN(x10=A0[0], y10=A0[1], lL=ROCKER_L, mL=0.05, JL=1e-4, xSLrel=0.05,
                       phiL0=PHI_CLOSED)
    model.dyad = DDD(x10=-0.04, y10=-0.06, lL1=0.12, lL2=0.10, K=1, mL1=0.05, JL1=1e-4,
                     xSL1rel=0.06, mL2=2.0, JL2=0.04, xSL2rel=0.0, ySL2rel=-0.25)
    model.drive = Preset(kind="speed", om=OMEGA_STATIC, phi0=PHI_CLOSED)
    model.connect(model.drive.flange, model.rocker.ctrR2)
    model.connect(model.rocker.ctr2D2, model.dyad.ctr2D2)


class DoorMechanism(Component):
    """Part 1: the door mechanism without balancing (Ebert 2015, Bild 7.7), driven
    quasi-statically from closed to open; ``drive.tau`` is the required
    balancing torque on the door-side rocker.  (Its ``experiment`` is set
    per instance, so that the file's default model is :class:`BalancedDoor`,
    its subclass.)"""
    outputs = ["drive.tau", "rocker.phiL"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.experiment = dict(QUASI_STATIC)
        _add_door(self)

    def write_outputs(self, res, folder):
        """Required torque over the cam angle with its regression (Bild 7.8)."""
        return [_plot_torque(res, os.path.join(folder, "cabinet_door_torque.png"))]


class DoorDesign:
    """The balancing design (module docstring): ``phi``, ``T`` required
    torque samples over the cam angle, ``regression`` (polynomial
    coefficients, highest first) and ``r2``, ``run1`` and ``fit`` (ch. 6
    fits, :class:`SpringBandFit` over the closing angle psi), ``structure``
    and ``synthesis`` (functional DB~SD synthesis over the cam angle),
    ``contour`` (:class:`AnalysisContour` for the CurvedDrum), ``x_closed``
    spring extension with the door closed, ``x0`` of DB~SD."""

    def __init__(self):
        res = simulate(DoorMechanism(), rtol=1e-9)
        self.phi = res["rocker.phiL"] - PHI_CLOSED
        self.T = res["drive.tau"]
        self.regression = np.polyfit(self.phi, self.T, DEGREE)
        fit_T = np.polyval(self.regression, self.phi)
        self.r2 = 1.0 - np.sum((self.T - fit_T) ** 2) / np.sum((self.T - self.T.mean()) ** 2)
        psi = np.linspace(0.0, SPAN, 201)
        torque = np.polyval(self.regression, SPAN - psi)
        self.run1 = spring_band_transfer(psi, torque, None, ("poly", DEGREE), x_start=X_OPEN,
                                         h_max=H_MAX)
        self.fit = spring_band_transfer(psi, torque, C_SPRING, ("poly", DEGREE),
                                        x_start=X_OPEN, h_max=H_MAX)
        self.x_closed = float(self.fit.x_at([SPAN])[0])
        self.x0 = -(L0_SPRING + self.x_closed)
        self.structure = BandStructure.dbsd(A0, B0, self.travel, -1, self.x0)
        self.structure.name = "cabinet door cam (DB~SD)"
        self.synthesis = synthesize(self.structure, np.linspace(0.0, SPAN, 301))
        self.contour = analysis_contour(self.synthesis, n_harm=300)

    def travel(self, p):
        """DB~SD travel x(phi) = x_S(closed) - x_S(psi) (eq. 4.49), CasADi."""
        return self.x_closed - self.fit.x_expr(SPAN - p)

    def lever_arm(self, p):
        """DB~SD input h(phi) = dx_S/dpsi at psi = span - phi, CasADi."""
        return self.fit.h_expr(SPAN - p)

    def required_torque(self, phi):
        """Regression of the required torque at cam angles ``phi``."""
        return np.polyval(self.regression, phi)


@functools.lru_cache(maxsize=1)
def door_design():
    """The :class:`DoorDesign`, computed once per process."""
    return DoorDesign()


class BalancingSynthesis(Component):
    """Part 2: DB~SD + Bandkurve synthesis of the balancing cam (Ebert 2015, Bild
    7.10, 7.11): the cam turns about A0 at 1 rad/s (cam angle = time), the
    band passes B0, the lever arm h(phi) of the ch. 6 run 2 drives
    ``dbsd.in1``.  (Its ``experiment`` is set per instance, so that the file's
    default model is :class:`BalancedDoor`.)"""
    outputs = ["bandkurve.xu", "bandkurve.yu", "bandkurve.l_Bf", "bandkurve.dl_Bf",
               "bandkurve.h", "bandkurve.a"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.experiment = {"stop_time": SPAN, "intervals": 300, "rtol": 1e-10}
        des = door_design()
        self.A0 = Fixed(r=A0)
        self.cam = Revolute(use_flange=True)
        self.preset = Preset(kind="speed", om=1.0, phi0=0.0)
        self.B0 = Fixed(r=B0)
        self.h = signals.TimeFunction(des.lever_arm)
        self.dbsd = DB_SD(K=-1, x0=des.x0)
        self.bandkurve = Bandkurve(criteria=True)
        self.connect(self.A0.frame, self.cam.frame_a)
        self.connect(self.preset.flange, self.cam.flange_a)
        self.connect(self.cam.frame_b, self.dbsd.ctr2D1)
        self.connect(self.cam.frame_b, self.bandkurve.ctr2D1)
        self.connect(self.B0.frame, self.dbsd.ctr2D2)
        self.connect(self.h.y, self.dbsd.in1)
        self.connect(self.dbsd.ctr2D3, self.bandkurve.ctr2D2)

    def write_outputs(self, res, folder):
        """Involute/evolute plot (Bild 7.11), the ch. 6 transfer function
        (Bild 7.9), the assessment plot and report (ch. 5) and the cam
        contour files (CSV, SVG, DXF)."""
        des = door_design()
        a = des.synthesis.assess(a_max=A_MAX)
        report = write_text(os.path.join(folder, "cabinet_door_assessment.txt"),
                            _design_text(des) + "\n" + a.report() + "\n")
        return ([_plot_synthesis(res, os.path.join(folder, "cabinet_door_involute.png")),
                 _plot_transfer(des, os.path.join(folder, "cabinet_door_transfer.png")),
                 a.plot(os.path.join(folder, "cabinet_door_criteria.png")), report]
                + export_contour(des.synthesis, folder, "cabinet_door_cam"))


class BalancedDoor(DoorMechanism):
    """Part 3: the door with the synthesised cam on the door-side rocker and
    the band with the 938 N/m spring to B0 (Ebert 2015, Bild 7.12), driven
    quasi-statically from closed to open: ``drive.tau`` is the torque left
    over (0 for a perfect balance); ``spring.F`` the spring force."""
    experiment = QUASI_STATIC
    outputs = ["drive.tau", "spring.F", "spring.l_dF"]

    def __init__(self, **kw):
        super().__init__(**kw)
        des = door_design()
        k_closed = float(des.contour.kappa([0.0])[0])
        k_open = float(des.contour.kappa([SPAN])[0])
        v = des.synthesis.evaluate([0.0])
        gamma = math.atan2(B0[1] - v["y_u"][0], B0[0] - v["x_u"][0])
        # the cam sits on the rocker, its axis on the rocker's pivot A0 (the
        # offset -lL from the rocker's end in the rocker's frame, Anhang A.1)
        # and locked to it; its housing is turned by -PHI_CLOSED so that the
        # cam angle is the rocker's angle from the closed door
        self.cam = CurvedDrum(des.contour.contour, w_i=1, x10=-ROCKER_L, y10=0.0,
                              phi10=-PHI_CLOSED,
                              alpha_fix=k_closed + 0.1 * math.copysign(1.0, k_closed - k_open),
                              kappa1=start(k_closed))
        self.connect(self.rocker.ctr2D2, self.cam.ctr2D1)
        self.connect(self.cam.ctrR1, self.cam.ctrR2)
        self.spring = SpringBelt(k=C_SPRING, l0=L0_SPRING, gamma=start(gamma),
                                 l_dF=start(des.x_closed, fixed=True))
        self.B0 = Fixed(r=B0)
        connect_band(self, self.spring, 1, self.cam, 1)
        self.connect(self.spring.ctr2D2, self.B0.frame)

    def write_outputs(self, res, folder):
        """Drive torque of the balanced door against the required torque."""
        return [_plot_balance(res, os.path.join(folder, "cabinet_door_balance.png"))]


# --------------------------------------------------------------------------
# reports and plots
# --------------------------------------------------------------------------
def _design_text(des):
    f1, f2 = des.run1, des.fit
    return "\n".join([
        "Cabinet door balancing (Ebert 2015, ch. 7.2.1)",
        "  required torque %.3f .. %.3f N m, regression degree %d, R^2 = %.6f"
        % (des.T.min(), des.T.max(), DEGREE, des.r2),
        "  run 1 (c_S free, h <= %.0f mm, x_S(open) = %.0f mm): c_S = %.1f N/m, rms %.2e N m"
        % (H_MAX * 1e3, X_OPEN * 1e3, f1.c_S, f1.rms),
        "  run 2 (c_S = %.0f N/m): rms %.2e N m, max %.2e N m, h = %.1f .. %.1f mm, "
        "x_S = %.1f .. %.1f mm" % (f2.c_S, f2.rms, f2.max_abs, f2.h.min() * 1e3,
                                   f2.h.max() * 1e3, f2.x.min() * 1e3, f2.x.max() * 1e3),
        "  coefficients of x_S(psi) [m] (eq. 6.7): " + ", ".join("%.6g" % c
                                                               for c in f2.coefficients)])


def _save(fig, path):
    fig.tight_layout()
    return save_figure(fig, path, dpi=100)


def _plot_torque(res, path):
    des_phi = res["rocker.phiL"] - PHI_CLOSED
    coef = np.polyfit(des_phi, res["drive.tau"], DEGREE)
    fig, ax = new_figure()
    ax.plot(np.degrees(des_phi), res["drive.tau"], "o", ms=3, label="quasi-static drive torque")
    ax.plot(np.degrees(des_phi), np.polyval(coef, des_phi), "-", label="regression, degree %d"
            % DEGREE)
    ax.set_xlabel("cam angle (rocker from closed) [deg]")
    ax.set_ylabel("required balancing torque [N m]")
    ax.set_title("Cabinet door: required torque (Bild 7.8)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return _save(fig, path)


def _plot_transfer(des, path):
    fig, ax = new_figure(1, 2, (10, 4))
    psi = des.fit.phi
    ax[0].plot(np.degrees(psi), des.fit.x * 1e3, label="x_S, ansatz (run 2)")
    ax[0].plot(np.degrees(psi), des.fit.x_exact * 1e3, "--", label="exact (eq. 6.5)")
    ax[0].set_ylabel("spring extension x_S [mm]")
    ax[1].plot(np.degrees(psi), des.fit.h * 1e3, label="h = x_S'")
    ax[1].axhline(H_MAX * 1e3, color="red", ls="--", lw=1, label="h_max")
    ax[1].set_ylabel("lever arm h [mm]")
    for a in ax:
        a.set_xlabel("closing angle psi [deg]")
        a.grid(True, alpha=0.3)
        a.legend()
    fig.suptitle("Cabinet door: transfer functions (Bild 7.9)")
    return _save(fig, path)


def _plot_synthesis(res, path):
    fig, ax = new_figure(size=(6, 6))
    ax.plot(res["bandkurve.xe"], res["bandkurve.ye"], label="involute (material point)")
    ax.plot(res["bandkurve.xu"], res["bandkurve.yu"], lw=2.5, label="evolute = cam contour")
    ax.plot(res["dbsd.ctr2D3.x"], res["dbsd.ctr2D3.y"], ":", label="path k_PS of the spring eye")
    ax.plot([A0[0], B0[0]], [A0[1], B0[1]], "k+", ms=12, mew=2)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title("Cabinet door cam: involute and evolute (Bild 7.11)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, path)


def _plot_balance(res, path):
    des = door_design()
    phi = res["cam.phi"]
    fig, ax = new_figure()
    ax.plot(np.degrees(phi), des.required_torque(phi), label="required torque (door alone)")
    ax.plot(np.degrees(phi), res["drive.tau"], label="drive torque with the spring-band cam")
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("torque [N m]")
    ax.set_title("Balanced cabinet door (Bild 7.12)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return _save(fig, path)


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
