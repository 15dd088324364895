"""Fuzz classes of the hydrostatic domain (issue 32; the case format: see
tests/fuzz_cases.py): a pump at constant speed charging a volume that a
relief valve protects, a motor with an inertia and a viscous load on it,
an orifice back to the tank.

* ``hydraulics-bad``: one parameter of one element set to a value its
  rule refuses (efficiency 0, above 1 or negative, a non-positive bulk
  modulus, volume, displacement, gradient, cracking pressure, area), in the
  model file (codes (2,): a clear error naming element and parameter) and
  through params= (the API must refuse it);
* ``hydraulics-good``: random admissible data (efficiencies, sizes,
  pressures, speeds of either sign): the run must reach its stop time
  (codes (0,)), with finite results.

Deterministic (fixed seeds).
"""
import random

_MODEL = """
from acausal2d.library import hydraulics

class Model(Component):
    experiment = {'stop_time': 0.2, 'intervals': 40}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.tank = hydraulics.PressureSource()
        self.pump = hydraulics.Pump(Vg=%(vg_p)r, eta_v=%(ev_p)r, eta_hm=%(eh_p)r)
        self.vol = hydraulics.Volume(V0=%(v0)r, K=%(k)r, p=start(%(p0)r, fixed=True))
        self.valve = hydraulics.ReliefValve(p_crack=%(p_crack)r, G=%(g)r)
        self.motor = hydraulics.Motor(Vg=%(vg_m)r, eta_v=%(ev_m)r, eta_hm=%(eh_m)r)
        self.orifice = hydraulics.Orifice(A=%(a)r)
        self.ws = signals.Constant(k=%(w)r)
        self.drive = rotational.Speed(phi=start(0.0, fixed=True))
        self.load = rotational.Inertia(J=0.2, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.damper = rotational.Damper(d=%(d)r)
        self.ground = rotational.Fixed()
        self.connect(self.ws.y, self.drive.w_in)
        self.connect(self.drive.flange, self.pump.flange)
        self.connect(self.tank.port, self.pump.port_a)
        self.connect(self.pump.port_b, self.vol.port)
        self.connect(self.vol.port, self.valve.port_a)
        self.connect(self.valve.port_b, self.tank.port)
        self.connect(self.vol.port, self.motor.port_a)
        self.connect(self.motor.port_b, self.tank.port)
        self.connect(self.vol.port, self.orifice.port_a)
        self.connect(self.orifice.port_b, self.tank.port)
        self.connect(self.motor.flange, self.load.flange_a)
        self.connect(self.load.flange_b, self.damper.flange_a)
        self.connect(self.damper.flange_b, self.ground.flange)
"""

GOOD = dict(vg_p=1e-4, ev_p=0.95, eh_p=0.9, v0=2e-3, k=1.4e9, p0=1e6, p_crack=2.5e7, g=1e-9,
            vg_m=2e-4, ev_m=0.97, eh_m=0.92, a=1e-6, w=150.0, d=5.0)

# (key, parameter path, refused values)
_BAD = [("ev_p", "pump.eta_v", [0.0, 1.5, -0.3]), ("eh_m", "motor.eta_hm", [0.0, 1.01]),
        ("k", "vol.K", [0.0, -1.4e9]), ("v0", "vol.V0", [0.0, -1e-3]),
        ("vg_p", "pump.Vg", [0.0, -1e-4]), ("g", "valve.G", [0.0, -1e-9]),
        ("p_crack", "valve.p_crack", [0.0, -1e7]), ("a", "orifice.A", [0.0, -1e-6])]


def _source(values):
    from fuzz_cases import HEADER
    return HEADER + _MODEL % values


def bad_cases():
    """Each refused value in the file (exit 2) and through params= (API)."""
    from fuzz_cases import _case
    cases = []
    good = _source(GOOD)
    for key, path, values in _BAD:
        for k, value in enumerate(values):
            cases.append(_case("hydraulics-bad-file-%s-%d" % (key, k), "parameters",
                               _source(dict(GOOD, **{key: value})), codes=(2,)))
            cases.append(_case("hydraulics-bad-api-%s-%d" % (key, k), "parameters", good,
                               params={path: value}, codes=(2,)))
    return cases


def good_cases(n=8, seed=32):
    """Random admissible data: the run reaches its stop time."""
    from fuzz_cases import _case
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        values = dict(GOOD, ev_p=rng.choice([0.8, 0.95, 1.0]), eh_p=rng.choice([0.85, 1.0]),
                      ev_m=rng.choice([0.9, 1.0]), eh_m=rng.choice([0.8, 0.95]),
                      v0=rng.choice([1e-4, 2e-3, 5e-2]), p0=rng.choice([0.0, 1e6, 3e7]),
                      w=rng.choice([-150.0, 0.0, 50.0, 300.0]), d=rng.choice([0.5, 5.0, 50.0]),
                      g=rng.choice([1e-10, 1e-9, 1e-8]), a=rng.choice([1e-7, 1e-6]))
        cases.append(_case("hydraulics-good-%d" % k, "hydraulics", _source(values), codes=(0,)))
    return cases


def cases():
    """Every hydraulics fuzz case, in a fixed order."""
    return bad_cases() + good_cases()
