"""First models: a hydraulic circuit with pump, valve and motor.

A pump (20 cm3/rev) run up to 150 rad/s in 0.5 s feeds a 5 l line protected by a
relief valve (250 bar); the oil flows through a throttle valve into a motor
(50 cm3/rev) that lifts a constant load torque of 100 N m, and back to the
tank.  By hand: the pump delivers 4.54e-4 m3/s (27.2 l/min), the motor turns
at 54.2 rad/s, the motor needs 139.6 bar, the valve takes 20 bar more, so the
line runs at 159.6 bar, below the relief valve's 250 bar.  The page
"A hydraulic circuit" of the documentation builds this file step by step.
"""
import math

from acausal2d import Component, start
from acausal2d.library import hydraulics, rotational, signals

# -- step 1: the numbers
W_PUMP = 150.0          # pump shaft speed, rad/s
VG_PUMP = 20e-6         # pump displacement, m3/rev (20 cm3/rev)
VG_MOTOR = 50e-6        # motor displacement, m3/rev (50 cm3/rev)
ETA_V = 0.95            # volumetric efficiency of pump and motor
ETA_HM = 0.90           # mechanical-hydraulic efficiency of pump and motor
T_LOAD = 100.0          # load torque on the motor, N m
G_VALVE = 2.2689e-10    # throttle valve's conductance, m3/(s Pa): about 20 bar at the pump's flow
P_RELIEF = 250e5        # relief valve's cracking pressure, Pa
V_LINE = 5e-3           # oil volume of the line, m3
K_OIL = 1.4e9           # bulk modulus of the oil, Pa
J_SHAFT = 0.01          # motor and load inertia, kg m^2
T_RUN_UP = 0.5          # the pump runs up to speed in 0.5 s
# -- end step 1


class HydraulicCircuit(Component):
    """Pump, line volume with relief valve, throttle valve, motor with a
    constant load torque; the tank at 0 bar gauge."""
    experiment = {"stop_time": 3.0, "intervals": 600, "rtol": 1e-8}
    outputs = ["line.p", "valve.dp", "motor.dp", "shaft.w", "relief.q"]
    figures = [{"name": "first_hydraulic_circuit", "title": "hydraulic circuit",
                "signals": [["line.p", "valve.dp"], ["shaft.w"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: the tank and the pump, driven at a constant speed
        self.tank = hydraulics.PressureSource(p0=0.0)
        self.pump = hydraulics.Pump(Vg=VG_PUMP, eta_v=ETA_V, eta_hm=ETA_HM)
        self.speed = signals.Ramp(height=W_PUMP, duration=T_RUN_UP)
        self.drive = rotational.Speed(phi=start(0.0, fixed=True))
        self.connect(self.speed.y, self.drive.w_in)
        self.connect(self.drive.flange, self.pump.flange)
        self.connect(self.tank.port, self.pump.port_a)
        # -- step 3: the line (an oil volume) and its relief valve back to the tank
        self.line = hydraulics.Volume(V0=V_LINE, K=K_OIL, p=start(0.0, fixed=True))
        self.relief = hydraulics.ReliefValve(p_crack=P_RELIEF, G=1e-9)
        self.connect(self.pump.port_b, self.line.port)
        self.connect(self.line.port, self.relief.port_a)
        self.connect(self.relief.port_b, self.tank.port)
        # -- step 4: the throttle valve and the motor, its return to the tank
        self.valve = hydraulics.Throttle(G=G_VALVE)
        self.motor = hydraulics.Motor(Vg=VG_MOTOR, eta_v=ETA_V, eta_hm=ETA_HM)
        self.connect(self.line.port, self.valve.port_a)
        self.connect(self.valve.port_b, self.motor.port_a)
        self.connect(self.motor.port_b, self.tank.port)
        # -- step 5: the motor's shaft, its inertia and the load torque against it
        self.shaft = rotational.Inertia(J=J_SHAFT, phi=start(0.0, fixed=True),
                                        w=start(0.0, fixed=True))
        self.load = rotational.ConstantTorque(tau_constant=-T_LOAD)
        self.connect(self.motor.flange, self.shaft.flange_a)
        self.connect(self.shaft.flange_b, self.load.flange)
        # -- end step 5


def hand_check():
    """The steady state by hand: {quantity: value}."""
    D_pump = VG_PUMP / (2 * math.pi)               # m3 per radian
    D_motor = VG_MOTOR / (2 * math.pi)
    q = ETA_V * D_pump * W_PUMP                    # the pump's flow (it all reaches the motor)
    dp_motor = T_LOAD / (ETA_HM * D_motor)         # the pressure the load needs
    dp_valve = q / G_VALVE                         # the throttle's drop at that flow
    p = dp_motor + dp_valve                        # the line pressure
    return {"pump flow": q, "shaft.w": ETA_V * q / D_motor, "motor.dp": -dp_motor,
            "valve.dp": dp_valve, "line.p": p, "pump torque": D_pump * p / ETA_HM}


def measure(res):
    """The same quantities at the end of a run of :class:`HydraulicCircuit`."""
    return {"pump flow": res.final("pump.q"), "shaft.w": res.final("shaft.w"),
            "motor.dp": res.final("motor.dp"), "valve.dp": res.final("valve.dp"),
            "line.p": res.final("line.p"), "pump torque": res.final("pump.tau")}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(HydraulicCircuit()))
    for name, value in hand_check().items():
        print("%-12s simulated %12.6g   by hand %12.6g" % (name, simulated[name], value))
