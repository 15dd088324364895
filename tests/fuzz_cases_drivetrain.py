"""Fuzz classes of the drive-train elements and signal blocks (issue 32;
the case format: see tests/fuzz_cases.py):

* ``drivetrain-bad``: a motor - gear - planetary - brake drive train and a
  LimPID speed loop with one parameter made invalid (ratio 0, negative
  fn_max, Ti <= 0, yMax < yMin, peak < 1, a falling friction table, an
  unknown initType, ...): refused at definition (exit 2) with a message
  naming the component's class and the parameter (the case's ``words``,
  checked by tests/test_drivetrain_fuzz.py);
* ``drivetrain-good``: the same model with random valid parameters: runs to
  its stop time (codes (0,)); the brake and the limiter switch on and off.

Deterministic (fixed seeds).
"""
import random

_MODEL = """
class Model(Component):
    experiment = {'stop_time': 0.5, 'intervals': 50}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sp = signals.Step(height=%(speed)r, startTime=0.05)
        self.pid = signals.LimPID(%(pid)s)
        self.fb = signals.Gain(k=1.0)
        self.motor = rotational.Torque()
        self.rotor = rotational.Inertia(J=0.01, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.gear = rotational.IdealGear(%(gear)s)
        self.planet = rotational.IdealPlanetary(%(planet)s)
        self.ring = rotational.Fixed()
        self.load = rotational.Inertia(J=2.0)
        self.brake = rotational.Brake(%(brake)s)
        self.press = signals.Ramp(height=1.0, duration=0.1, startTime=%(brake_at)r)
        self.sensor = rotational.AngleSensor()
        self.speed = signals.Derivative(k=1.0, T=1e-3, initType="SteadyState")
        self.connect(self.sp.y, self.pid.u_s)
        self.connect(self.pid.y, self.motor.tau_in)
        self.connect(self.motor.flange, self.rotor.flange_a)
        self.connect(self.rotor.flange_b, self.gear.flange_a)
        self.connect(self.gear.flange_b, self.planet.sun)
        self.connect(self.ring.flange, self.planet.ring)
        self.connect(self.planet.carrier, self.load.flange_a)
        self.connect(self.load.flange_b, self.brake.flange_a)
        self.connect(self.press.y, self.brake.f_normalized)
        self.connect(self.rotor.flange_b, self.sensor.flange)
        self.connect(self.sensor.phi, self.speed.u)
        self.connect(self.speed.y, self.fb.u)
        self.connect(self.fb.y, self.pid.u_m)
"""

_GOOD = dict(speed=50.0, pid="k=0.5, Ti=0.2, Td=0.01, yMax=5.0",
             gear="ratio=4.0", planet="ratio=2.5",
             brake="mu_pos=[[0.0, 0.4]], cgeo=0.2, fn_max=50.0, peak=1.2",
             brake_at=0.3)

# (what to change, the words the error must hold)
_BAD = [({"gear": "ratio=0.0"}, ("IdealGear", "ratio")),
        ({"planet": "ratio=0.0"}, ("IdealPlanetary", "ratio")),
        ({"planet": "ratio=-2.0"}, ("IdealPlanetary", "ratio")),
        ({"brake": "fn_max=-10.0"}, ("Brake", "fn_max")),
        ({"brake": "peak=0.9"}, ("Brake", "peak")),
        ({"brake": "mu_pos=[[0.0, 0.4], [-1.0, 0.3]]"}, ("Brake", "mu_pos")),
        ({"brake": "mu_pos=[[0.0, -0.4]]"}, ("Brake", "mu_pos")),
        ({"brake": "cgeo=float('nan')"}, ("Brake", "cgeo")),
        ({"pid": "Ti=0.0"}, ("LimPID", "Ti")),
        ({"pid": "Ti=-0.5"}, ("LimPID", "Ti")),
        ({"pid": "yMax=1.0, yMin=2.0"}, ("LimPID", "yMax", "yMin")),
        ({"pid": "k=0.0"}, ("LimPID", "k")),
        ({"pid": "Nd=0.0"}, ("LimPID", "Nd")),
        ({"pid": "Td=-0.1"}, ("LimPID", "Td")),
        ({"pid": "initType='Steady'"}, ("LimPID", "initType")),
        ({"pid": "controllerType='PIDD'"}, ("LimPID", "controllerType")),
        ({"pid": "wp=-1.0"}, ("LimPID", "wp"))]


def _source(values):
    from fuzz_cases import HEADER
    return HEADER + _MODEL % values


def bad_cases():
    """One invalid parameter each: exit 2 with the component and parameter."""
    from fuzz_cases import _case
    cases = []
    for k, (change, words) in enumerate(_BAD):
        case = _case("drivetrain-bad-%d" % k, "drivetrain", _source(dict(_GOOD, **change)),
                     codes=(2,))
        case["words"] = words
        cases.append(case)
    return cases


def good_cases(n=4, seed=32):
    """Random valid drive trains: run to the stop time."""
    from fuzz_cases import _case
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        values = dict(_GOOD, speed=rng.choice([-80.0, 20.0, 50.0, 200.0]),
                      gear="ratio=%r" % rng.choice([-3.0, 0.5, 4.0, 10.0]),
                      planet="ratio=%r" % rng.choice([1.5, 2.5, 4.0]),
                      pid="controllerType=%r, k=%r, Ti=0.2, Td=0.01, yMax=%r" % (
                          rng.choice(["PI", "PID"]), rng.choice([0.1, 0.5, 2.0]),
                          rng.choice([1.0, 5.0, 50.0])),
                      brake_at=rng.choice([0.1, 0.3, 0.6]))
        cases.append(_case("drivetrain-good-%d" % k, "drivetrain", _source(values), codes=(0,)))
    return cases


def cases():
    """All drive-train fuzz cases."""
    return bad_cases() + good_cases()
