"""Hydraulic drum drive of the tilting-mast cable crane (Ebert 2015, ch. 8.1,
Bild 8.6).

What the dissertation shows: the "rigid" drum drives of Bild 8.3 (drums following
motion functions) replaced by a drive unit: a speed-controlled diesel
engine drives a hydraulic pump that feeds the two controlled hydraulic
motors of the load-rope drum and the auxiliary-rope drum, each through a
planetary stage.  The model answered questions on the energy consumption
and on design values, e.g. "the relation between the targeted maximum
pressure at the hydraulic motor and the ratio of the planetary stage".
Bild 8.6 shows one such string only as a picture; the dissertation gives no
numbers for the drive.

What is given elsewhere in ch. 8.1 and used here: drum diameter 1000 mm
(r = 0.5 m), payload up to 4 t ([MMF11]).

What is ASSUMED (typical of truck-mounted tower yarders with 150-250 kW
diesels, constant-pressure hydraulics with secondary-controlled winch
motors; values chosen so that every controller works inside its limits):

* diesel: set speed 1800 rpm (188.5 rad/s), inertia of engine, flywheel and
  splitter box 2.5 kg m2, torque 0..1200 N m (about 226 kW at set speed),
  speed controller LimPID (PI, k = 50 N m s/rad, Ti = 0.5 s) -- the
  "speed-controlled diesel" of the dissertation as a controlled torque source;
* splitter (pump drive) gear IdealGear ratio 1/1.2: pump at 2160 rpm;
* pump: variable displacement, Vg = 250 cm3/rev, eta_v 0.95, eta_hm 0.9,
  pressure controller LimPID on p / p_set (PI, k = 5, Ti = 0.1 s, alpha
  0..1) holding p_set = 25 MPa in the line (the "targeted maximum
  pressure"), line volume 20 l, bulk modulus 1.4 GPa, relief valve
  28 MPa (gradient 1e-9 m3/(s Pa)) as protection, and a laminar leakage
  of 4e-12 m3/(s Pa) from the line to the tank (control oil and flushing,
  1e-4 m3/s = 6 l/min at 25 MPa) -- without a consumer at rest the pump
  controller would sit exactly on its lower limit alpha = 0 (a sliding
  mode of the limiter);
* two secondary-controlled motors (displacement set by the drum speed
  controllers, alpha -1..1: over centre they brake and feed back), load
  drum Vg = 710 cm3/rev, auxiliary drum Vg = 250 cm3/rev, eta_v 0.97,
  eta_hm 0.92, rotor inertia 0.05 kg m2 each, speed controllers LimPID
  (PI, k = 1 s/rad, Ti = 0.3 s) on the drum speed;
* planetary stage per drum: IdealPlanetary, ring/sun teeth 9 (sun from the
  motor, ring fixed, carrier to the drum: reduction 10);
* drums: 100 kg m2 each; load rope carries the 4 t payload (rope force
  m g = 39.2 kN, the hook hanging straight below the trolley, rope rigid);
  the auxiliary rope moves trolley and load (4.5 t) with a constant rope
  force of 10 kN (slope component and rolling resistance, lumped).  Each
  drum is a rotational inertia J_drum + m r^2 with the constant rope
  torque -F r: the exact reduction of a rigid rope to the drum axis.

The standard transfer (Bild 8.3's cycle, reduced to a run-up): from rest
with the load hanging, the load drum runs up to 4 rad/s (2 m/s rope) over
[0.5, 2.5] s and the auxiliary drum to 6 rad/s (3 m/s) over [1, 3] s.  At
rest the motors hold the rope torques: the integrators of the drum
controllers start at the holding displacement.

What follows (tests/test_hydraulic_drum_drive.py): the controllers reach
their set speeds and pressure (the pump and diesel controllers start at
the values that feed the leakage at rest: initType "InitialState" with
xi_start); the diesel's work equals the hoisting and
haul work plus the kinetic and oil energy plus the losses in pump, motors
and valve; at 25 MPa the load drum needs alpha = 0.75 of its motor (about
3.5e-3 m3/s), i.e. the pressure level and the planetary ratio fix the
motor size, as the dissertation says.
"""
import math

from acausal2d import Component, start
from acausal2d.library import hydraulics, rotational
from acausal2d.library.blocks import Gain
from acausal2d.library.controllers import LimPID
from acausal2d.library.gears import IdealGear, IdealPlanetary
from acausal2d.library.signals import Constant, Ramp

G = 9.81
P_SET = 2.5e7          # Pa, line pressure held by the pump controller
W_DIESEL = 188.5       # rad/s (1800 rpm)
RATIO = 9.0            # planetary ring/sun teeth: reduction 1 + RATIO = 10
R_DRUM = 0.5           # m (drum diameter 1000 mm, seed ch. 8.1)
J_DRUM = 100.0         # kg m2
K_DRUM = 1.0           # drum speed controller gain (alpha per rad/s)
K_PUMP, K_DIESEL = 5.0, 50.0   # pump (alpha per p/P_SET) and diesel (N m s/rad) controller gains
GEAR = 1 / 1.2         # splitter gear ratio w_diesel / w_pump
VG_PUMP, EV_PUMP, EH_PUMP = 2.5e-4, 0.95, 0.9
G_LEAK = 4e-12         # m3/(s Pa) line -> tank at rest

DRUMS = {
    # name: (motor Vg [m3/rev], rope force [N], moved mass [kg], set speed [rad/s], ramp start [s])
    "hoist": (7.1e-4, 4000.0 * G, 4000.0, 4.0, 0.5),
    "haul": (2.5e-4, 1.0e4, 4500.0, 6.0, 1.0),
}


def holding_alpha(vg, force):
    """Motor displacement setting that holds the rope force at standstill
    (no efficiency at w = 0): alpha Vg / (2 pi) P_SET (1 + RATIO) = F r."""
    return force * R_DRUM / ((1 + RATIO) * vg / (2 * math.pi) * P_SET)


def rest_start():
    """(pump alpha, diesel torque) at rest: the pump feeds the leakage
    G_LEAK P_SET at the pump speed W_DIESEL / GEAR, the diesel carries the
    pump's torque through the splitter gear."""
    D = VG_PUMP / (2 * math.pi)
    alpha = G_LEAK * P_SET / (EV_PUMP * D * W_DIESEL / GEAR)
    return alpha, alpha * D * P_SET / EH_PUMP / GEAR


class DrumString(Component):
    """One string of Bild 8.6: controlled motor -- planetary stage -- drum
    with its rope load; ``motor.port_a`` to the line, ``motor.port_b`` to
    the tank (connected by the parent)."""

    def __init__(self, vg=7.1e-4, force=4000.0 * G, mass=4000.0, w_set=4.0, t_start=0.5,
                 **kw):
        super().__init__(**kw)
        self.motor = hydraulics.Motor(Vg=vg, eta_v=0.97, eta_hm=0.92, variable=True)
        self.rotor = rotational.Inertia(J=0.05)
        self.planetary = IdealPlanetary(ratio=RATIO)
        self.ring = rotational.Fixed()
        self.drum = rotational.Inertia(J=J_DRUM + mass * R_DRUM ** 2,
                                       phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rope = rotational.ConstantTorque(tau_constant=-force * R_DRUM)
        self.speed = rotational.SpeedSensor()
        self.set = Ramp(height=w_set, duration=2.0, startTime=t_start)
        self.control = LimPID(controllerType="PI", initType="InitialState", k=K_DRUM, Ti=0.3,
                              yMax=1.0, yMin=-1.0, xi_start=holding_alpha(vg, force) / K_DRUM)
        for a, b in [(self.motor.flange, self.rotor.flange_a),
                     (self.rotor.flange_b, self.planetary.sun),
                     (self.planetary.ring, self.ring.flange),
                     (self.planetary.carrier, self.drum.flange_a),
                     (self.drum.flange_b, self.rope.flange),
                     (self.drum.flange_a, self.speed.flange),
                     (self.set.y, self.control.u_s), (self.speed.w, self.control.u_m),
                     (self.control.y, self.motor.alpha)]:
            self.connect(a, b)


class DriveUnit:
    """The drive unit of Bild 8.6 up to the line (mixin of a Component):
    speed-controlled diesel, splitter gear, pressure-controlled pump, line
    volume, relief valve, leakage and tank (module docstring: the assumed
    data).  The consumers connect to ``line.port`` and ``tank.port``."""

    def _diesel(self):
        self.diesel = rotational.Inertia(J=2.5, phi=start(0.0, fixed=True),
                                         w=start(W_DIESEL, fixed=True))
        self.engine = rotational.Torque()
        self.diesel_speed = rotational.SpeedSensor()
        self.diesel_set = Constant(k=W_DIESEL)
        self.diesel_control = LimPID(controllerType="PI", initType="InitialState", k=K_DIESEL,
                                     Ti=0.5, yMax=1200.0, yMin=0.0,
                                     xi_start=rest_start()[1] / K_DIESEL)
        self.splitter = IdealGear(ratio=GEAR)
        for a, b in [(self.engine.flange, self.diesel.flange_a),
                     (self.diesel.flange_b, self.diesel_speed.flange),
                     (self.diesel_set.y, self.diesel_control.u_s),
                     (self.diesel_speed.w, self.diesel_control.u_m),
                     (self.diesel_control.y, self.engine.tau_in),
                     (self.diesel.flange_b, self.splitter.flange_a)]:
            self.connect(a, b)

    def _hydraulics(self):
        self.tank = hydraulics.PressureSource()
        self.pump = hydraulics.Pump(Vg=VG_PUMP, eta_v=EV_PUMP, eta_hm=EH_PUMP, variable=True)
        self.line = hydraulics.Volume(V0=0.02, K=1.4e9, p=start(P_SET, fixed=True))
        self.relief = hydraulics.ReliefValve(p_crack=2.8e7, G=1e-9)
        self.leakage = hydraulics.Throttle(G=G_LEAK)
        self.pressure = hydraulics.PressureSensor()
        self.p_norm = Gain(k=1 / P_SET)
        self.p_set = Constant(k=1.0)
        self.pump_control = LimPID(controllerType="PI", initType="InitialState", k=K_PUMP,
                                   Ti=0.1, yMax=1.0, yMin=0.0, xi_start=rest_start()[0] / K_PUMP)
        for a, b in [(self.splitter.flange_b, self.pump.flange),
                     (self.tank.port, self.pump.port_a), (self.pump.port_b, self.line.port),
                     (self.line.port, self.relief.port_a), (self.relief.port_b, self.tank.port),
                     (self.line.port, self.leakage.port_a), (self.leakage.port_b, self.tank.port),
                     (self.line.port, self.pressure.port), (self.pressure.p, self.p_norm.u),
                     (self.p_set.y, self.pump_control.u_s), (self.p_norm.y, self.pump_control.u_m),
                     (self.pump_control.y, self.pump.alpha)]:
            self.connect(a, b)


class HydraulicDrumDrive(DriveUnit, Component):
    """Diesel -- splitter gear -- pressure-controlled pump -- line (volume,
    relief valve) -- two speed-controlled motors with planetary stages and
    drums (module docstring: data and what is assumed)."""
    experiment = {"stop_time": 6.0, "intervals": 600, "rtol": 1e-7}
    outputs = ["diesel.w", "line.p", "pump_control.y_value", "hoist.drum.w", "haul.drum.w",
               "hoist.control.y_value", "haul.control.y_value"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self._diesel()
        self._hydraulics()
        for name, (vg, force, mass, w_set, t0) in DRUMS.items():
            setattr(self, name, DrumString(vg=vg, force=force, mass=mass, w_set=w_set,
                                           t_start=t0))
            string = getattr(self, name)
            self.connect(self.line.port, string.motor.port_a)
            self.connect(string.motor.port_b, self.tank.port)
