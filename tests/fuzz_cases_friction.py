"""Fuzz classes of issue 29's friction items (the case format: see
tests/fuzz_cases.py): clutches between two inertias

* ``friction-sign``: the normal-force input of either sign, constant or a
  signal through zero (a clutch is free for fn <= 0, as Modelica's Clutch);
* ``friction-stiff``: stiff stick laws, w_s from 1e-5 down to 1e-9 rad/s,
  with random splits of the capacity into mu, cgeo and fn_max (the split
  decided whether main 3ead139's event iteration found the lock) and a
  torque that makes the clutch lock and unlock.

Every case must run to its stop time (codes (0,)): a clutch has no sliding
mode to report.  Deterministic (fixed seeds).
"""
import random

_MODEL = """
class Model(Component):
    experiment = {'stop_time': %(stop)r, 'intervals': 50}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.a = rotational.Inertia(J=%(ja)r, phi=start(0.0, fixed=True), w=start(%(wa)r, fixed=True))
        self.b = rotational.Inertia(J=%(jb)r, phi=start(0.0, fixed=True), w=start(%(wb)r, fixed=True))
        self.clutch = rotational.Clutch(mu=%(mu)r, fn_max=%(fn_max)r, cgeo=%(cgeo)r, w_s=%(w_s)r, law="zone")
        self.eng = signals.%(engage)s
        self.connect(self.eng.y, self.clutch.f_normalized)
        self.connect(self.a.flange_b, self.clutch.flange_a)
        self.connect(self.clutch.flange_b, self.b.flange_a)
        self.drive = signals.Sine(amplitude=%(torque)r, f=2.5)
        self.src = rotational.Torque()
        self.connect(self.drive.y, self.src.tau_in)
        self.connect(self.src.flange, self.a.flange_a)
"""

# f_normalized: constant, oscillating through zero, a ramp through zero, a
# step to minus the level (two structures only, so that the compiled code is
# shared between the cases: the values are parameters)
_ENGAGE = ["Sine(amplitude=0.0, offset=%(level)r)", "Sine(amplitude=%(level)r, f=3.0)",
           "Ramp(offset=%(level)r, height=%(minus2)r, duration=0.25)",
           "Ramp(offset=%(level)r, height=%(minus2)r, duration=1e-3, start_time=0.1)"]


def _split(rng, capacity):
    """(mu, cgeo, fn_max) with mu * cgeo * fn_max = capacity."""
    mu = rng.choice([0.1, 0.3, 1.0])
    cgeo = rng.choice([0.05, 0.1, 1.0, 10.0])
    return mu, cgeo, capacity / (mu * cgeo)


def _source(values):
    from fuzz_cases import HEADER
    return HEADER + _MODEL % values


def sign_cases(n=12, seed=29):
    """Normal-force inputs of either sign (constant, oscillating, a ramp
    through zero, a step to negative)."""
    from fuzz_cases import _case
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        level = rng.choice([-1.0, -0.5, -1e-3, 0.0, 1e-3, 0.5, 1.0])
        mu, cgeo, fn_max = _split(rng, rng.choice([1.0, 10.0, 30.0]))
        values = dict(stop=0.4, ja=rng.choice([0.1, 1.0]), jb=rng.choice([0.3, 1.0]),
                      wa=rng.choice([-10.0, 0.0, 10.0]), wb=rng.choice([0.0, 2.0]),
                      mu=mu, cgeo=cgeo, fn_max=fn_max, w_s=rng.choice([1e-3, 1e-5]),
                      engage=rng.choice(_ENGAGE) % dict(level=level, minus2=-2 * level),
                      torque=0.0)
        cases.append(_case("friction-sign-%d" % k, "friction", _source(values), codes=(0,)))
    return cases


def stiff_cases(n=12, seed=30):
    """Stiff stick laws: lock of two inertias, and lock/unlock under a
    sinusoidal torque, for w_s from 1e-5 to 1e-9."""
    from fuzz_cases import _case
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        capacity = rng.choice([1.0, 10.0, 20.0, 30.0])
        mu, cgeo, fn_max = _split(rng, capacity)
        torque = 0.0 if k % 2 == 0 else 3.0 * capacity
        values = dict(stop=0.5, ja=rng.choice([0.1, 1.0, 2.0]), jb=rng.choice([0.3, 1.0]),
                      wa=rng.choice([1.0, 10.0]), wb=0.0, mu=mu, cgeo=cgeo, fn_max=fn_max,
                      w_s=rng.choice([1e-5, 3e-6, 1e-6, 1e-7, 1e-8, 1e-9]),
                      engage=_ENGAGE[0] % dict(level=1.0), torque=torque)
        cases.append(_case("friction-stiff-%d" % k, "friction", _source(values), codes=(0,)))
    return cases


def cases():
    """Every friction case, in a fixed order."""
    return sign_cases() + stiff_cases()
