"""First models: a drive train with motor, clutch, gear and brake.

A motor with a constant torque of 2 N m runs up its rotor (0.02 kg m^2)
alone; at 0.5 s a friction clutch (6 N m when closed) closes onto a gear
(ratio 4) and a load (0.8 kg m^2); at 2 s a brake (40 N m) stops the load
against the motor and holds it.  By hand: 50 rad/s when the clutch closes,
a slip of 0.15625 s, 23.44 J lost in the clutch, the load at rest at 2.5 s,
and the motor's work equal to the clutch's and the brake's losses.  The page
"A drive train" of the documentation builds this file step by step.
"""
from acausal2d import Component, start
from acausal2d.library import rotational, signals

# -- step 1: the numbers
TAU_M = 2.0        # motor torque, N m
J_M = 0.02         # motor rotor, kg m^2
RATIO = 4.0        # gear ratio: the motor side turns 4 times as fast as the load
J_L = 0.8          # load, kg m^2
T_CLOSE = 0.5      # the clutch closes, s
T_BRAKE = 2.0      # the brake is applied, s
# clutch: mu cgeo fn_max = 0.3 * 0.1 m * 200 N = 6 N m sliding torque
MU_C, CGEO_C, FN_C = 0.3, 0.1, 200.0
# brake: mu cgeo fn_max = 0.4 * 0.1 m * 1000 N = 40 N m sliding torque
MU_B, CGEO_B, FN_B = 0.4, 0.1, 1000.0
# -- end step 1


class DriveTrain(Component):
    """Constant-torque motor, friction clutch closing at 0.5 s, ideal gear,
    load inertia and a brake applied at 2 s."""
    experiment = {"stop_time": 3.0, "intervals": 600, "rtol": 1e-8}
    outputs = ["rotor.w", "load.w", "clutch.w_rel", "clutch.tau", "brake.tau"]
    figures = [{"name": "first_drive_train", "title": "drive train: speeds and friction torques",
                "signals": [["rotor.w", "load.w"], ["clutch.tau", "brake.tau"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: the motor (a constant torque) on its rotor, which starts at rest
        self.motor = rotational.ConstantTorque(tau_constant=TAU_M)
        self.rotor = rotational.Inertia(J=J_M, phi=start(0.0, fixed=True),
                                        w=start(0.0, fixed=True))
        self.connect(self.motor.flange, self.rotor.flange_a)
        # -- step 3: the clutch between rotor and gear, closed by a step of its normal force
        self.clutch = rotational.Clutch(mu=MU_C, cgeo=CGEO_C, fn_max=FN_C)
        self.close = signals.Step(height=1.0, startTime=T_CLOSE)
        self.connect(self.close.y, self.clutch.f_normalized)
        self.connect(self.rotor.flange_b, self.clutch.flange_a)
        # -- step 4: gear and load (the gear's support, left unconnected, is the ground)
        self.gear = rotational.IdealGear(ratio=RATIO)
        self.load = rotational.Inertia(J=J_L, phi=start(0.0, fixed=True),
                                       w=start(0.0, fixed=True))
        self.connect(self.clutch.flange_b, self.gear.flange_a)
        self.connect(self.gear.flange_b, self.load.flange_a)
        # -- step 5: the brake on the load shaft, applied by a step
        self.brake = rotational.Brake(mu_pos=[[0.0, MU_B]], cgeo=CGEO_B, fn_max=FN_B)
        self.apply = signals.Step(height=1.0, startTime=T_BRAKE)
        self.connect(self.apply.y, self.brake.f_normalized)
        self.connect(self.load.flange_b, self.brake.flange_a)
        # -- end step 5


def hand_check():
    """The run by hand, phase by phase: {quantity: value}."""
    T_c = MU_C * CGEO_C * FN_C                     # clutch's sliding torque, 6 N m
    T_b = MU_B * CGEO_B * FN_B                     # brake's sliding torque, 40 N m
    w_close = TAU_M * T_CLOSE / J_M                # the rotor alone: 50 rad/s
    # slipping: the rotor slows, the gear's input (load side times RATIO) speeds up
    a_rotor = (TAU_M - T_c) / J_M                  # -200 rad/s^2
    a_input = RATIO ** 2 * T_c / J_L               # 120 rad/s^2 at the gear's input
    t_slip = w_close / (a_input - a_rotor)         # 0.15625 s
    w_lock = a_input * t_slip                      # 18.75 rad/s at the motor
    E_clutch = T_c * w_close * t_slip / 2          # torque times the mean slip speed, times time
    # locked: one inertia J_M + J_L / RATIO^2 seen at the motor
    J_total = J_M + J_L / RATIO ** 2
    w_brake = w_lock + TAU_M / J_total * (T_BRAKE - T_CLOSE - t_slip)
    # braking (the clutch stays closed): the brake and the motor act on the same inertia
    a_braking = (TAU_M - T_b / RATIO) / J_total    # at the motor, negative
    t_stop = T_BRAKE - w_brake / a_braking
    E_kin = J_total * w_brake ** 2 / 2
    W_motor_braking = TAU_M * w_brake ** 2 / (-2 * a_braking)
    return {"rotor.w at close": w_close, "slip time": t_slip, "rotor.w at lock": w_lock,
            "clutch loss": E_clutch, "rotor.w at brake": w_brake, "stop time": t_stop,
            "brake loss": E_kin + W_motor_braking,
            "motor work": E_clutch + E_kin + W_motor_braking}


def measure(res):
    """The same quantities read from a result of :class:`DriveTrain`."""
    import numpy as np
    t, w = res.time, res["rotor.w"]
    slipping = np.flatnonzero(np.abs(res["clutch.w_rel"]) > 1e-2)
    t_lock = t[slipping[-1] + 1]                      # first output point after the slip
    moving = np.flatnonzero(np.abs(res["load.w"]) > 1e-2)
    energy = lambda power: float(np.sum((power[1:] + power[:-1]) / 2 * np.diff(t)))  # noqa: E731
    return {"rotor.w at close": float(np.interp(T_CLOSE, t, w)),
            "slip time": t_lock - T_CLOSE, "rotor.w at lock": float(np.interp(t_lock, t, w)),
            "clutch loss": energy(np.abs(res["clutch.tau"] * res["clutch.w_rel"])),
            "rotor.w at brake": float(np.interp(T_BRAKE, t, w)),
            "stop time": float(t[moving[-1] + 1]),
            "brake loss": energy(np.abs(res["brake.tau"] * res["brake.w"])),
            "motor work": TAU_M * res.final("rotor.phi")}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(DriveTrain()))
    for name, value in hand_check().items():
        print("%-18s simulated %12.6g   by hand %12.6g" % (name, simulated[name], value))
