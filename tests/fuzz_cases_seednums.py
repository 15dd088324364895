"""Fuzz class of the line spring-damper (library/planar/forces.py:
LineSpringDamper; the case format: see tests/fuzz_cases.py): a body on the
line spring-damper from a fixed point, under gravity,

* ``line-spring``: random rates, damping and unstretched lengths (0
  included), the body started anywhere, at the anchor itself (zero length)
  or thrown through it: every case must run to its stop time (codes (0,));
* ``line-spring-bad``: a negative rate, damping or unstretched length is
  refused before the run with the project's error (codes (2,)).

Deterministic (fixed seed).
"""
import random

_MODEL = """
from acausal2d.library.planar.forces import LineSpringDamper


class Model(Component):
    experiment = {'stop_time': 0.5, 'intervals': 50}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.anchor = Fixed(r=(0.0, 0.0))
        self.sd = LineSpringDamper(c=%(c)r, d=%(d)r, s_unstretched=%(l0)r)
        self.body = Body(m=%(m)r, I=0.01, x=start(%(x)r, fixed=True), y=start(%(y)r, fixed=True),
                         phi=start(0.0, fixed=True), vx=start(%(vx)r, fixed=True),
                         vy=start(%(vy)r, fixed=True), w=start(0.0, fixed=True))
        self.connect(self.anchor.frame, self.sd.frame_a)
        self.connect(self.sd.frame_b, self.body.frame_a)
"""


def _source(values):
    from fuzz_cases import HEADER
    return HEADER + _MODEL % values


def cases(n=6, seed=32):
    """``n`` runnable cases and three refused ones."""
    from fuzz_cases import _case
    rng = random.Random(seed)
    out = []
    for k in range(n):
        values = dict(c=rng.choice([0.0, 10.0, 1e3, 1e5]), d=rng.choice([0.0, 1.0, 50.0]),
                      l0=rng.choice([0.0, 0.1, 0.5]), m=rng.choice([0.1, 1.0]),
                      x=rng.choice([0.0, 0.2]), y=rng.choice([0.0, -0.3]),
                      vx=rng.choice([0.0, -1.0]), vy=rng.choice([0.0, 2.0]))
        out.append(_case("line-spring-%d" % k, "line-spring", _source(values), codes=(0,)))
    bad = dict(c=100.0, d=1.0, l0=0.1, m=1.0, x=0.1, y=-0.3, vx=0.0, vy=0.0)
    for name, value in (("c", -1.0), ("d", -1.0), ("l0", -0.1)):
        values = dict(bad, **{name: value})
        out.append(_case("line-spring-bad-%s" % name, "line-spring", _source(values),
                         codes=(2,)))
    return out
