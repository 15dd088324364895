"""The tilting-mast cable crane driven by its hydraulic drum drive (Ebert
(2015), ch. 8.1, Bild 8.6): the next model stage after the "rigid" drum
drives of Bild 8.3.

What the text gives: the crane of Bild 8.2-8.5 (models/cable_crane.py:
its layout, ropes, carriage, hook and transfer cycle) and the drive unit
of Bild 8.6 (models/hydraulic_drum_drive.py: a speed-controlled diesel
drives a pressure-controlled pump feeding the two controlled hydraulic
motors of the load-rope drum D1 and the haul-back drum D2, each through a
planetary stage).  The model answered questions on the energy consumption
of the whole system and on design values, e.g. "the relation between the
targeted maximum pressure at the hydraulic motor and the ratio of the
planetary stage" -- the study :meth:`HydraulicCableCrane.pressure_vs_ratio`.

Here the drums of :class:`~cable_crane.CableCrane` no longer follow their
motion laws; each is driven by a string motor -- rotor -- planetary stage
(sun from the motor, ring fixed, carrier on the drum's flange ``ctrR2``),
the motor's displacement set by a PI speed controller whose set point is
the speed of the drum's motion law (its time derivative).  The controller's
integral acts on the angle error (the integral of the speed error), so the
drums follow the cycle's angles too.  The rope forces on the drums are the
crane's own: the load rope's and the haul-back rope's spans end on the
drums' contacts.

Values ASSUMED beyond both models (the text gives no numbers for the
drive):

* the drive unit as in models/hydraulic_drum_drive.py (diesel 1800 rpm,
  2.5 kg m^2, 0..1200 N m, PI k = 50 N m s/rad, Ti = 0.5 s; splitter 1/1.2;
  pump 250 cm^3/rev, eta_v 0.95, eta_hm 0.9, PI on p/p_set k = 5, Ti =
  0.1 s; p_set = 25 MPa; line 20 l, 1.4 GPa; relief valve 28 MPa; leakage
  4e-12 m^3/(s Pa));
* both motors 250 cm^3/rev (MOTOR_VG), eta_v 0.97, eta_hm 0.92, rotor
  0.05 kg m^2; planetary stage ring/sun teeth 9 (RATIO: reduction 10), the
  same on both drums; drum speed controllers PI (k = 1 s/rad, Ti = 0.3 s),
  displacement -1..1 (over centre the motor brakes and feeds back), each
  integrator starting at the displacement that holds its drum's rope force
  at rest (F r / ((1 + ratio) D p_set), no efficiency at standstill);
* the hook of models/cable_crane.py (1000 kg), so the load drum holds
  9.81 kN x 0.5 m and the haul-back drum 5.76 kN x 0.5 m at rest: about
  half the motor's displacement at the ratio 9.

What the run shows about the energy consumption: while lifting, the load
drum's motor takes oil from the line; during the transport the load drum
pays the load rope out under the hook's weight, its motor brakes over
centre and feeds oil back, more than the haul-back motor takes, and the
pump (displacement 0..1) cannot take it: the line pressure rises to the
relief valve (28 MPa), which burns the surplus.  The balance of the whole
system says where the diesel's work goes.

The study :meth:`HydraulicCableCrane.pressure_vs_ratio` answers the
design question: with the line pressure held, the secondary-controlled
motor sets its displacement alpha to the torque; ``alpha p`` is the
pressure a motor of the full displacement would need for that torque (its
load pressure).  Its largest value over the lift, for the planetary ratios
of :data:`STUDY_RATIOS`, is written as a table (CSV) and a plot beside the
quasi-static holding pressure m g r / ((1 + i) D): the smallest ratio whose
load pressure stays below the targeted maximum pressure sizes the stage.

Checks (tests/test_hydraulic_cable_crane.py): the cycle runs with taut
ropes and the drums follow their motion laws; the energy balance of the
whole system -- diesel work = kinetic energy of diesel, rotors, drums,
pulleys, carriage and hook + their potential energy + the ropes' elastic
energy + the oil's + the losses of pump, motors, valves, the ropes'
damping and the strain the ropes lose or gain where they run onto and off
the wheels -- closes to the integration's tolerance.
"""
import math
import os
import sys

import casadi as ca
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cable_crane as crane  # noqa: E402
import hydraulic_drum_drive as drive  # noqa: E402

from acausal2d import Component, study  # noqa: E402
from acausal2d.io.files import write_text  # noqa: E402
from acausal2d.library import hydraulics, rotational  # noqa: E402
from acausal2d.library.controllers import LimPID  # noqa: E402
from acausal2d.library.gears import IdealPlanetary  # noqa: E402
from acausal2d.library.signals import TimeFunction  # noqa: E402

MOTOR_VG = 2.5e-4          # m^3/rev, both motors (assumed)
RATIO = 9.0                # planetary ring/sun teeth (assumed): reduction 1 + RATIO
K_DRUM, TI_DRUM = 1.0, 0.3
STUDY_RATIOS = (5.0, 6.0, 7.0, 9.0, 12.0, 15.0)
"""Planetary ratios of the study (ring/sun teeth; below 5 the load drum's
motor cannot hold the hook at 25 MPa: F r / ((1 + i) D p) > 1)."""
STUDY_STOP = crane.T_LIFT + crane.D_LIFT + 1.0
"""The study runs the lift (rest, lift, 1 s at rest): where the load-rope
motor carries the hook and accelerates it."""


def holding_alpha(force, ratio=RATIO, vg=MOTOR_VG, p=drive.P_SET):
    """Displacement setting that holds the rope force ``force`` on a drum
    at standstill: alpha D p (1 + ratio) = F r (no efficiency at w = 0)."""
    return force * crane.R_DRUM / ((1 + ratio) * vg / (2 * math.pi) * p)


def speed_law(phi):
    """The time derivative of the drum angle law ``phi`` (a function of the
    time symbol), for the speed controller's set point."""
    return lambda t: ca.jacobian(phi(t), t)


class CraneDrumString(Component):
    """One drum string of Bild 8.6 without its drum: controlled motor --
    rotor -- planetary stage (ring fixed); the carrier ``planetary.carrier``
    drives the crane's drum, whose speed ``speed`` measures; the set speed
    follows ``w_law`` (a function of time).  ``motor.port_a`` to the line,
    ``motor.port_b`` to the tank (connected by the parent)."""

    def __init__(self, w_law, force, **kw):
        super().__init__(**kw)
        self.motor = hydraulics.Motor(Vg=MOTOR_VG, eta_v=0.97, eta_hm=0.92, variable=True)
        self.rotor = rotational.Inertia(J=0.05)
        self.planetary = IdealPlanetary(ratio=RATIO)
        self.ring = rotational.Fixed()
        self.speed = rotational.SpeedSensor()
        self.set = TimeFunction(w_law)
        self.control = LimPID(controllerType="PI", initType="InitialState", k=K_DRUM,
                              Ti=TI_DRUM, yMax=1.0, yMin=-1.0,
                              xi_start=holding_alpha(force) / K_DRUM)
        for a, b in [(self.motor.flange, self.rotor.flange_a),
                     (self.rotor.flange_b, self.planetary.sun),
                     (self.planetary.ring, self.ring.flange),
                     (self.planetary.carrier, self.speed.flange),
                     (self.set.y, self.control.u_s), (self.speed.w, self.control.u_m),
                     (self.control.y, self.motor.alpha)]:
            self.connect(a, b)


class HydraulicCableCrane(drive.DriveUnit, crane.CableCrane):
    """The cable crane of models/cable_crane.py with the hydraulic drum
    drive of Bild 8.6 in place of its drum motion laws (module docstring:
    data and what is assumed)."""
    experiment = {"stop_time": crane.T_STOP, "intervals": 600, "rtol": 1e-7}
    outputs = ["load1.F", "load6.F", "haul1.F", "sky2.F", "hook.y", "line.p",
               "hoist.control.y_value", "haul.control.y_value", "diesel.w"]
    figures = [{"name": "hydraulic_cable_crane_ropes", "signals": ["load1.F", "load6.F",
                                                                   "haul1.F"],
                "title": "rope forces with the hydraulic drum drive (Bild 8.5, 8.6)"},
               {"name": "hydraulic_cable_crane_drive", "title": "motor displacement settings",
                "signals": ["hoist.control.y_value", "haul.control.y_value",
                            "pump_control.y_value"]}]

    def _drives(self, phi1, phi2):
        """The drive unit and one drum string per drum (module docstring)."""
        self._diesel()
        self._hydraulics()
        st = self.design["start"]
        for name, drum, law, force in (("hoist", self.D1, phi1, st["F_load"]),
                                       ("haul", self.D2, phi2, st["F_haul"])):
            string = CraneDrumString(speed_law(law), force)
            setattr(self, name, string)
            self.connect(string.planetary.carrier, drum.ctrR2)
            self.connect(self.line.port, string.motor.port_a)
            self.connect(string.motor.port_b, self.tank.port)

    @study
    def pressure_vs_ratio(ctx):
        """Largest pressure the load-rope motor needs over the lift against
        the planetary stage's ratio: table and plot."""
        rows = [pressure_point(ctx, i) for i in STUDY_RATIOS]
        path = os.path.join(ctx.out, "hydraulic_cable_crane_pressure.csv")
        write_text(path, pressure_table(rows))
        ctx.files.append(path)
        ctx.save(pressure_figure(rows), "hydraulic_cable_crane_pressure")
        for row in rows:
            ctx.note("ratio %5.1f (reduction %5.1f): max load pressure %6.2f MPa "
                     "(holding %6.2f MPa), max displacement %.3f"
                     % (row["ratio"], 1 + row["ratio"], row["p_max"] / 1e6,
                        row["p_hold"] / 1e6, row["alpha_max"]))


def study_params(ratio):
    """Parameter values of a run with the planetary ratio ``ratio`` on both
    drums (the integrators start at the new holding displacement)."""
    st = crane.drive_design()[0]
    return {"hoist.planetary.ratio": ratio, "haul.planetary.ratio": ratio,
            "hoist.control.xi_start": holding_alpha(st["F_load"], ratio) / K_DRUM,
            "haul.control.xi_start": holding_alpha(st["F_haul"], ratio) / K_DRUM}


def pressure_point(ctx, ratio):
    """One row of the study: the load pressure ``alpha p`` of the load-rope
    motor (the pressure a motor of the full displacement would need for the
    same torque; with the displacement at its limit 1 it is the line
    pressure itself) at its largest over the lift, and its quasi-static
    holding value m g r / ((1 + ratio) D)."""
    res = ctx.simulate(stop_time=STUDY_STOP, params=study_params(ratio), intervals=400,
                       progress=False)
    load = np.abs(res["hoist.control.y_value"]) * res["line.p"]
    k = int(np.argmax(load))
    return {"ratio": ratio, "p_max": float(load[k]), "t_max": float(res.time[k]),
            "alpha_max": float(np.max(np.abs(res["hoist.control.y_value"]))),
            "p_hold": holding_alpha(crane.M_HOOK * crane.G, ratio) * drive.P_SET,
            "line_p_max": float(np.max(res["line.p"]))}


def pressure_table(rows):
    """The study's table as CSV text (pressures in Pa)."""
    head = "ratio,reduction,p_load_max,t_at_max,alpha_max,p_holding,line_p_max"
    lines = ["%g,%g,%.10g,%.6g,%.10g,%.10g,%.10g" % (r["ratio"], 1 + r["ratio"], r["p_max"],
                                               r["t_max"], r["alpha_max"], r["p_hold"],
                                               r["line_p_max"]) for r in rows]
    return "\n".join([head] + lines) + "\n"


def pressure_figure(rows):
    """Largest load pressure of the load-rope motor over the ratio, with the
    holding pressure and the line's set pressure (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(7, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    i = [r["ratio"] for r in rows]
    ax.plot(i, [r["p_max"] / 1e6 for r in rows], "o-", label="largest over the lift (run)")
    ax.plot(i, [r["p_hold"] / 1e6 for r in rows], "--", label="holding the hook, m g r/((1+i) D)")
    ax.axhline(drive.P_SET / 1e6, color="0.4", lw=0.8, label="line set pressure")
    ax.set_xlabel("planetary stage ratio i (ring/sun teeth; reduction 1 + i)")
    ax.set_ylabel("load pressure at the motor [MPa]")
    ax.set_title("HydraulicCableCrane: motor pressure against the planetary ratio")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    return fig


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
