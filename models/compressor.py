"""Compressor with belt drive, tensioner, clutch, crank drive and pneumatics
(Ebert 2015, ch. 8.2, Bild 8.7-8.9).

Structure (Ebert 2015, Bild 8.8): an asynchronous motor drives, through the disc
clutch "discClutch1", the drive pulley "FixPulley1".  A closed elastic belt
runs from the drive pulley over the tight span "BeltSpring1" to the driven
pulley "FixPulley2", back over "BeltSpring3" to the tensioner pulley and
over "BeltSpring2" to the drive pulley again.  The tensioner pulley sits on a
bell-crank lever pivoted in the frame and held by a spring-damper ("Belt
Tensor").  The driven pulley (with flywheel) turns the crank of a
slider-crank; the piston compresses air in a cylinder with an intake and a
discharge check valve (library/pneumatics.py).  The clutch closes at
t = 2 s and opens at t = 10 s; the span forces (Bild 8.9) show the start-up
peaks, the periodic steady state of the running compressor and the run-out.

Layout (x to the right, y up, metres; all pulleys turn counter-clockwise
when driven, all winding directions w_i = -1 (eq. 4.95), the belt loop is traversed
counter-clockwise: drive -> span2 -> tensioner -> span3 -> driven -> span1
-> drive):

    drive pulley P1 (0, 0), r1 = 50 mm; driven pulley P2 (0.45, 0),
    r2 = 150 mm (ratio 3); tensioner pulley r3 = 35 mm on the lever arm
    0.10 m from the pivot A (0.12, -0.17), arm at 15 deg at t0, pushing the
    slack span (span2/span3, below the pulleys) outwards; second lever arm
    0.08 m pointing down at t0, the spring-damper from its end B to the
    anchor C = B - (0.15, 0).

Span names as in the dissertation: ``span1`` = BeltSpring1 (tight span, driven ->
drive, on top), ``span2`` = BeltSpring2 (drive -> tensioner),
``span3`` = BeltSpring3 (tensioner -> driven).

Values the dissertation does not give (chosen here):

- motor: 4-pole, 50 Hz asynchronous motor (w_sync = 157.08 rad/s), Kloss
  breakdown torque T_k = 40 N m at s_k = 0.2 (about a 2.2 kW motor), rotor
  inertia 0.01 kg m^2, started at rest at t = 0 (runs up in about 0.1 s with
  the clutch open);
- clutch: mu = 0.3, fn_max = 1500 N, cgeo = 0.11 m (two faces at 55 mm):
  capacity 49.5 N m; closed by a linear ramp of f_normalized 0 -> 1 over
  2.00..2.05 s, opened by a ramp 1 -> 0 over 10.00..10.05 s; regularisation
  width w_s = 0.01 rad/s (library/rotational.py, Clutch);
- pulleys: drive J1 = 2e-3 kg m^2 (pulley + clutch disc), driven pulley with
  flywheel J2 = 0.25 kg m^2, tensioner m = 0.3 kg, J = 1e-4 kg m^2;
  bearing friction only on the crank shaft, modelled as the driven
  pulley's bearing friction (library/belt.py): mu = 0.1 on a 50 mm shaft
  (r_pin = 25 mm), loaded by the belt forces only, sign regularised with
  omega_s = 0.01 rad/s -- it lets the compressor run out to standstill
  after the clutch opens (without it the frictionless crank keeps rocking
  on the gas spring of the trapped air); the other bearings, the slider
  and the piston are frictionless;
- belt (V-belt): stiffness c = 1.5e5 N per unit strain, damping d = 150 N s
  per unit strain, all spans start with the pretension 250 N;
- tensioner: massless lever, spring c_s = 2e4 N/m, damper d_s = 300 N s/m;
  the spring's unstretched length is computed so that the lever is in
  equilibrium at t0 with 250 N in every span (``tensioner_preload``);
- crank drive: crank radius 35 mm (stroke 70 mm), connecting rod 140 mm;
  crank (with counterweight, centre of gravity on the axis) 2 kg,
  I = 0.01 kg m^2; rod 0.4 kg at its middle, I = m l^2/12; piston 0.6 kg;
  the cylinder axis is vertical above the crank shaft (which is the driven
  pulley's axis); start at bottom dead centre at rest (a static
  equilibrium under gravity);
- pneumatics: bore 80 mm, dead-space height 3 mm (15 cm^3, 4.3 % of the
  swept volume 352 cm^3), air (kappa = 1.4, R = 287 J/(kg K)), adiabatic,
  intake from 1 bar / 20 degC, discharge into a reservoir at 8 bar
  (absolute), valve conductances 5e-6 kg/(s Pa) (check valves as events);
- gravity -9.81 m/s^2 in y.

Results (rtol 1e-6): the motor runs up idle in ~0.1 s; when the clutch
closes it slips at its capacity for ~0.08 s, the tight span peaks at about
1090 N; the compressor then runs at ~52 rad/s (500 rpm) and the span forces
repeat every revolution (span 1: 256..648 N, spans 2 and 3: 177..265 N)
from about 2.5 s; per revolution the
cylinder takes 86.2 J (1 % above the ideal adiabatic compressor with
clearance), the bearing 9.1 J, the belt/tensioner/clutch 0.09 J.  After the
clutch opens the compressor stops within a few revolutions and rocks on the
trapped air until the bearing friction has taken that energy (~15 s).

Settling against the dissertation: the dissertation states the structure (Bild 8.8), the
clutch closing at 2 s and opening at 10 s, the force peaks at closing, the
steady state "at about 8 s" and the run-out to standstill (text of Bild
8.9); it gives no parameter at all (motor, clutch, inertias, belt,
tensioner, crank, pneumatics) and the curves of Bild 8.9 are lost.  Here
the drive settles about 0.5 s after the clutch closes, as the assumed data
imply: the motor's slip characteristic near synchronous speed is a viscous
coupling k_m = 2 T_k/(s_k w_sync) = 2.5 N m s, the inertia on the motor
shaft J = 0.041 kg m^2 (flywheel J2/9 included), so the speed settles with
J/k_m = 16 ms, and the tensioner (2e4 N/m, 300 N s/m) is damped within
a few tenths of a second.  Settling after 6 s would need a time constant
of about 1.5 s: with this motor a hundred times the inertia, or a slow
process the dissertation does not describe (e.g. a receiver filling up, which here
is the constant 8 bar reservoir).  No parameter is tuned to the dissertation's 8 s.

Checks (tests/test_compressor.py): the states at bottom dead centre and
the span forces over the crank angle of consecutive revolutions agree
(periodic steady state); over a steady revolution the work of the belt on
the driven pulley equals the indicated work of the cylinder plus the
bearing friction (1e-4); the motor delivers slightly more (belt,
tensioner and clutch losses positive, below 1 %); indicated work and
delivered mass against the ideal compressor; start-up peak, no slack span,
run-out to rest.

``acausal2d simulate models/compressor.py`` writes the span forces (Bild
8.9) and the drive quantities (the model's ``figures``); ``acausal2d study
models/compressor.py`` the steady-state revolutions and the work balance
(running the file does both, into ./out).
"""
import math
import sys

import casadi as ca
import numpy as np

from acausal2d import Component, start, study
from acausal2d.library import rotational, translational
from acausal2d.library.belt import Belt, Pulley, connect_band, tangent
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute
from acausal2d.library.planar.forces import LineSpringDamper
from acausal2d.library.pneumatics import GasCylinder
from acausal2d.library.signals import TimeFunction

G = 9.81
# belt drive
P1 = (0.0, 0.0)
R1 = 0.05
P2 = (0.45, 0.0)
R2 = 0.15
R3 = 0.035
PIVOT = (0.12, -0.17)
ARM1 = 0.10
ARM2 = 0.08
LEVER0 = math.radians(15.0)
SPRING_DX = 0.15
C_BELT = 1.5e5
D_BELT = 150.0
F0 = 250.0
C_SPRING = 2e4
D_SPRING = 300.0
M_TENS = 0.3
# crank drive and cylinder
RC = 0.035
LR = 0.14
BORE = 0.08
H_DEAD = 0.003
# clutch timing
T_CLOSE, T_OPEN, T_RAMP = 2.0, 10.0, 0.05


def clutch_signal(t):
    """f_normalized of the clutch: ramps 0 -> 1 over [2, 2.05] s and
    1 -> 0 over [10, 10.05] s."""
    up = ca.fmin(ca.fmax((t - T_CLOSE) / T_RAMP, 0.0), 1.0)
    down = ca.fmin(ca.fmax((t - T_OPEN) / T_RAMP, 0.0), 1.0)
    return up - down


def tensioner_geometry():
    """Initial points: tensioner axis T, lever ends B and anchor C."""
    T = (PIVOT[0] + ARM1 * math.cos(LEVER0), PIVOT[1] + ARM1 * math.sin(LEVER0))
    B = (PIVOT[0], PIVOT[1] - ARM2)
    C = (B[0] - SPRING_DX, B[1])
    return T, B, C


def tensioner_preload(F=F0):
    """Unstretched spring length for lever equilibrium at t0 with the force
    F in both spans at the tensioner and gravity on the tensioner pulley."""
    T, B, C = tensioner_geometry()
    # span2: drive K2 -> tensioner K1; span3: tensioner K2 -> driven K1
    g2, _ = tangent((P1[0], P1[1], -R1), (T[0], T[1], R3))
    g3, _ = tangent((T[0], T[1], -R3), (P2[0], P2[1], R2))
    Rx = F * (math.cos(g3) - math.cos(g2))
    Ry = F * (math.sin(g3) - math.sin(g2)) - M_TENS * G
    M = (T[0] - PIVOT[0]) * Ry - (T[1] - PIVOT[1]) * Rx
    ls = math.hypot(C[0] - B[0], C[1] - B[1])
    ux, uy = (C[0] - B[0]) / ls, (C[1] - B[1]) / ls
    arm = (B[0] - PIVOT[0]) * uy - (B[1] - PIVOT[1]) * ux
    Fs = -M / arm
    if Fs <= 0:
        raise ValueError("the tensioner spring would have to push (F_s = %g N)" % Fs)
    return ls - Fs / C_SPRING, Fs


class Compressor(Component):
    """Compressor drive of Ebert (2015), ch. 8.2 (see the module docstring).

    Outputs: span forces ``span1.F`` (tight span), ``span2.F``,
    ``span3.F``; motor speed ``motor.w``; crank angle/speed
    ``crank.phi``/``crank.w``; clutch torque ``clutch.tau``; cylinder
    pressure ``cyl.p``; tensioner lever angle ``lever.phi``."""
    experiment = {"stop_time": 16.0, "intervals": 3200, "rtol": 1e-6}
    outputs = ["span1.F", "span2.F", "span3.F", "motor.w", "crank.w", "clutch.tau",
               "cyl.p", "lever.phi"]
    figures = [{"name": "compressor_span_forces", "signals": ["span1.F", "span2.F", "span3.F"],
                "title": "span forces, clutch closes at 2 s, opens at 10 s (Bild 8.9)"},
               {"name": "compressor_drive", "title": "drive",
                "signals": [["motor.w", "crank.w"], ["clutch.tau", "motor.T_el"], ["cyl.p"],
                            ["lever.phi"]]}]

    @study
    def steady_state(ctx):
        """Span forces over the crank angle of consecutive steady revolutions
        and the work balance of the last one (a 0.1 ms output window over
        9.4 .. 10 s)."""
        steady_state_report(ctx)

    def __init__(self, **kw):
        super().__init__(**kw)
        _, _, C = tensioner_geometry()
        self._motor_and_belt()
        self._tensioner(C)
        self._crank_drive()

    def _motor_and_belt(self):
        """Motor, clutch and the three-pulley belt drive (the tensioner
        pulley placed by the lever, :meth:`_tensioner`)."""
        # --- motor and clutch
        self.motor = rotational.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2,
                                           phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.clutch = rotational.Clutch(mu=0.3, fn_max=1500.0, cgeo=0.11, w_s=0.01, law="zone")
        self.engage = TimeFunction(clutch_signal)
        self.connect(self.engage.y, self.clutch.f_normalized)
        self.connect(self.motor.flange, self.clutch.flange_a)
        # --- belt drive
        self.drive = Pulley(r=R1, x10=P1[0], y10=P1[1], w_i=-1, J=2e-3)
        self.driven = Pulley(r=R2, x10=P2[0], y10=P2[1], w_i=-1, J=0.25, friction=True,
                             mu=0.1, r_pin=0.025, omega_s=0.01)
        # on the lever's arm: its start position comes from the lever (T)
        self.tens = Pulley(r=R3, w_i=-1, m=M_TENS, J=1e-4)
        self.connect(self.clutch.flange_b, self.drive.ctrR2)
        eps0 = F0 / C_BELT
        for k in (1, 2, 3):
            setattr(self, "span%d" % k, Belt(c=C_BELT, d=D_BELT, eps=start(eps0, fixed=True)))
        connect_band(self, self.span1, 1, self.driven, 2)
        connect_band(self, self.span1, 2, self.drive, 1)
        connect_band(self, self.span2, 1, self.drive, 2)
        connect_band(self, self.span2, 2, self.tens, 1)
        connect_band(self, self.span3, 1, self.tens, 2)
        connect_band(self, self.span3, 2, self.driven, 1)

    def _tensioner(self, C):
        """Bell-crank lever with the "Belt Tensor" spring-damper (a
        :class:`LineSpringDamper`, Ebert (2015), Bild 8.8) anchored at C."""
        l0_spring, _ = tensioner_preload()
        self.pivot = Fixed(r=PIVOT)
        self.lever = Revolute(phi=start(LEVER0, fixed=True), w=start(0.0, fixed=True))
        self.arm1 = FixedTranslation(r=(ARM1, 0.0))
        self.arm2 = FixedTranslation(r=(-ARM2 * math.sin(LEVER0), -ARM2 * math.cos(LEVER0)))
        self.anchor = Fixed(r=C)
        self.spring = LineSpringDamper(c=C_SPRING, d=D_SPRING, s_unstretched=l0_spring)
        self.connect(self.pivot.frame, self.lever.frame_a)
        self.connect(self.lever.frame_b, self.arm1.frame_a)
        self.connect(self.lever.frame_b, self.arm2.frame_a)
        self.connect(self.arm1.frame_b, self.tens.ctr2D1)
        self.connect(self.arm2.frame_b, self.spring.frame_a)
        self.connect(self.spring.frame_b, self.anchor.frame)

    def _crank_drive(self):
        """Crank drive on the driven pulley's shaft, cylinder above it."""
        self.shaft = Fixed(r=P2)
        self.crank = Revolute(use_flange=True, state_select="always",
                              phi=start(-math.pi / 2, fixed=True), w=start(0.0, fixed=True))
        self.crank_body = Body(m=2.0, I=0.01)
        self.crank_arm = FixedTranslation(r=(RC, 0.0))
        self.pin = Revolute(phi=start(math.pi))
        self.rod_a = FixedTranslation(r=(LR / 2, 0.0))
        self.rod_body = Body(m=0.4, I=0.4 * LR ** 2 / 12)
        self.rod_b = FixedTranslation(r=(LR / 2, 0.0))
        self.wrist = Revolute(phi=start(-math.pi / 2))
        self.piston = Body(m=0.6, I=1e-3)
        self.guide = Prismatic(r=(0.0, 1.0), use_flange=True, s=start(LR - RC))
        self.connect(self.driven.ctrR2, self.crank.flange_a)
        self.connect(self.shaft.frame, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.crank_body.frame_a)
        self.connect(self.crank.frame_b, self.crank_arm.frame_a)
        self.connect(self.crank_arm.frame_b, self.pin.frame_a)
        self.connect(self.pin.frame_b, self.rod_a.frame_a)
        self.connect(self.rod_a.frame_b, self.rod_body.frame_a)
        self.connect(self.rod_a.frame_b, self.rod_b.frame_a)
        self.connect(self.rod_b.frame_b, self.wrist.frame_a)
        self.connect(self.wrist.frame_b, self.piston.frame_a)
        self.connect(self.shaft.frame, self.guide.frame_a)
        self.connect(self.guide.frame_b, self.piston.frame_a)
        area = math.pi * BORE ** 2 / 4
        self.cyl = GasCylinder(A=area, p_amb=1e5, p_in=1e5, p_out=8e5,
                               G_in=5e-6, G_out=5e-6)
        self.head = translational.Fixed(s0=LR + RC + H_DEAD)
        self.connect(self.guide.flange_a, self.cyl.flange_a)
        self.connect(self.cyl.flange_b, self.head.flange)

    def topology(self):
        """The shaft coupling for Ebert (2015), eq. 2.1.  The driven pulley and the
        crank are one shaft at P2: the pulley's flange drives the crank
        joint's flange (``driven.ctrR2`` = ``crank.flange_a``), so the two
        revolute joints there (pulley bearing, crank joint) are coupled.
        Eq. 2.1 sees only the joints (pulley and crank as two links), so
        the coupling is declared as one more restriction, like the "+ 1"
        for the coupled band joints of Ebert (2015), Bild 2.1 b/c: a joint with
        f = 2 (3 - f = 1) between the pulley and the crank.  Count: links
        ground, drive, driven, tensioner pulley, lever, crank, rod, piston
        (n = 8); revolute joints of the three pulleys, lever, crank, pin,
        wrist and the prismatic guide (8 x f = 1) plus the coupling:
        F = 3 (8 - 1) - 8 x 2 - 1 = 4 (drive pulley, tensioner lever,
        tensioner pulley, crank shaft)."""
        return [("joint", self.driven.ctrK1, self.crank.frame_b, 2)]


# --------------------------------------------------------------------------
# evaluation helpers (used by the tests and the plots)
# --------------------------------------------------------------------------
def revolutions(res, t_from, t_to):
    """Start times of the crank revolutions in [t_from, t_to] (the crank
    angle passing bottom dead centre, -pi/2 + 2 pi k)."""
    t = res.time
    phi = res["crank.phi"] + math.pi / 2
    k = np.floor(phi / (2 * math.pi))
    idx = np.nonzero(np.diff(k) != 0)[0]
    out = []
    for i in idx:
        target = 2 * math.pi * max(k[i], k[i + 1])
        # linear interpolation of the crossing
        a = (target - phi[i]) / (phi[i + 1] - phi[i])
        tc = t[i] + a * (t[i + 1] - t[i])
        if t_from <= tc <= t_to:
            out.append(tc)
    return out


def over_crank_angle(res, name, t0, t1, n=360):
    """``name`` sampled at n equidistant crank angles of the revolution
    starting at t0 and ending at t1 (linear interpolation in time)."""
    t = res.time
    sel = (t >= t0 - 1e-3) & (t <= t1 + 1e-3)
    phi = res["crank.phi"][sel]
    grid = phi[0] + (np.interp(t1, t[sel], res["crank.phi"][sel]) - phi[0]) * np.arange(n) / n
    grid[0] = np.interp(t0, t[sel], res["crank.phi"][sel])
    return np.interp(grid, phi, res[name][sel])


def cycle_work(res, t0, t1):
    """Works over [t0, t1] (trapezoidal rule on the output grid):
    W_belt -- belt on the driven pulley (tight minus slack side times r2,
    times the pulley's angle), W_ind -- indicated work of the cylinder
    (integral of (p - p_amb) dV, taken by the gas), W_motor -- motor
    mechanical work, W_fric -- work dissipated by the crank-shaft bearing
    friction."""
    t = res.time
    sel = (t >= t0) & (t <= t1)
    tt = t[sel]

    def integ(y):
        return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(tt)))
    w2 = res["driven.w_rel"][sel]
    M2 = (res["span1.F"][sel] - res["span3.F"][sel]) * R2
    return {"W_belt": integ(M2 * w2), "W_ind": integ(res["cyl.P_gas"][sel]),
            "W_motor": integ(res["motor.P_mech"][sel]),
            "W_fric": -integ(res["driven.T_f"][sel] * w2)}


def steady_state_figure(res, revs):
    """Span forces over the crank angle of the last revolutions (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(7, 4))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ang = np.arange(360)
    for k in (1, 2, 3):
        for j in range(len(revs) - 3, len(revs) - 1):
            ax.plot(ang, over_crank_angle(res, "span%d.F" % k, revs[j], revs[j + 1]),
                    lw=0.8, label="span%d.F, revolution %d" % (k, j))
    ax.set_xlabel("crank angle from bottom dead centre [deg]")
    ax.set_ylabel("F [N]")
    ax.set_title("Compressor: steady state, consecutive revolutions")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def steady_state_report(ctx):
    """The steady-state study (:meth:`Compressor.steady_state`)."""
    stop = Compressor.experiment["stop_time"]
    ot = np.unique(np.concatenate([
        np.linspace(0.0, stop, Compressor.experiment["intervals"] + 1),
        np.linspace(9.4, 10.0, 6001)]))
    res = ctx.simulate(output_times=ot)
    revs = revolutions(res, 9.4, 10.0)
    if len(revs) >= 2:
        w = cycle_work(res, revs[-2], revs[-1])
        ctx.note("last steady revolution %.4f..%.4f s: belt work on the driven pulley %.2f J, "
                 "indicated work %.2f J, bearing friction %.2f J, motor work %.2f J"
                 % (revs[-2], revs[-1], w["W_belt"], w["W_ind"], w["W_fric"], w["W_motor"]))
    sel = (res.time > 8.0) & (res.time < 10.0)
    for k in (1, 2, 3):
        F = res["span%d.F" % k]
        ctx.note("span%d: max %.1f N (all), steady range %.1f .. %.1f N"
                 % (k, F.max(), F[sel].min(), F[sel].max()))
    if len(revs) >= 3:
        ctx.save(steady_state_figure(res, revs), "compressor_steady_state")


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
