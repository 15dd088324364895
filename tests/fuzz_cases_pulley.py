"""Fuzz classes of issue 32 (tests/fuzz_cases.py's case format): placements
of a pulley (seed Tabelle 4.15, Anhang A.1) on a hanging body ("lose Rolle"
in a rope loop between two anchors).  Good placements -- random offsets
x10, y10 in the body frame with the body started where the axis hangs
between the anchors -- must run; bad ones must be refused with exit code 2:
a body without start values (the axis' start position is unknown), former
x0/y0 that contradict the body's start, a frameRef or half-plane that does
not exist, and a half-plane enumHE1 the winding direction does not
produce.  Pulleys on a driven DAN crank at random offsets, placed by
either frameRef, must run.  Deterministic (fixed seed)."""
import math
import random

EXTRA = """
from acausal2d.library.belt import Belt, Pulley, connect_band
from acausal2d.library.linkage import DAN
from acausal2d.library.linkage.drives import Preset
"""

_LOOSE = """
self.body = Body(m={m}, I=0.02{start})
self.pulley = Pulley(r={r}, J=1e-4, {place})
self.connect(self.body.frame_a, self.pulley.ctr2D1)
self.left, self.right = Fixed(r=(-{r}, 0.0)), Fixed(r=({r}, 0.0))
self.s1 = Belt(c=1e5, d=50.0, eps=start({eps}, fixed=True))
self.s2 = Belt(c=1e5, d=50.0, eps=start({eps}, fixed=True))
self.connect(self.left.frame, self.s1.ctr2D1)
connect_band(self, self.s1, 2, self.pulley, 1)
connect_band(self, self.s2, 1, self.pulley, 2)
self.connect(self.s2.ctr2D2, self.right.frame)
"""

_KINDS = ("good", "no-start", "contradiction", "frameRef", "half-plane-name", "half-plane")


def _loose(rng, kind):
    """Model body and expected exit codes of one placement of ``kind``."""
    r = round(rng.uniform(0.03, 0.2), 3)
    m = round(rng.uniform(0.5, 5.0), 2)
    dx, dy = round(rng.uniform(-0.2, 0.2), 3), round(rng.uniform(-0.2, 0.2), 3)
    depth = round(rng.uniform(0.3, 2.0), 3)
    start = ", x=start(%r), y=start(%r), phi=start(0.0, fixed=True)" % (-dx, -depth - dy)
    place = "x10=%r, y10=%r, w_i=-1" % (dx, dy)
    if kind == "no-start":
        start = ""
    elif kind == "contradiction":
        place = "x0=%r, y0=%r, w=1" % (dx + 0.01 + rng.uniform(0, 0.1), -depth)
    elif kind == "frameRef":
        place += ", frameRef=%r" % rng.choice(["world", "Global", "", "CKS"])
    elif kind == "half-plane-name":
        place += ", enumHE1=%r" % rng.choice(["top", "obere", "Upper", 1])
    elif kind == "half-plane":      # K1 hangs left of the axis: 'right' is impossible
        place += ", enumHE1='right'"
    body = _LOOSE.format(m=m, start=start, r=r, place=place, eps=round(m * 9.81 / 2e5, 9))
    return body, (0,) if kind == "good" else (2,)


_ON_CRANK = """
self.crank = DAN(lL={l}, mL=0.2, JL=1e-3)
self.turn = Preset(kind="speed", om={om}, phi0={phi0})
self.connect(self.turn.flange, self.crank.ctrR2)
self.pulley = Pulley(r={r}, J=1e-4, w_i=1, {place})
self.connect(self.crank.ctr2D2, self.pulley.ctr2D1)
self.left, self.right = Fixed(r=({q1x}, {q1y})), Fixed(r=({q2x}, {q2y}))
self.s1 = Belt(c=1e5, d=50.0, eps=start(1e-3, fixed=True))
self.s2 = Belt(c=1e5, d=50.0, eps=start(1e-3, fixed=True))
self.connect(self.left.frame, self.s1.ctr2D1)
connect_band(self, self.s1, 2, self.pulley, 1)
connect_band(self, self.s2, 1, self.pulley, 2)
self.connect(self.s2.ctr2D2, self.right.frame)
"""


def _on_crank(rng):
    """A pulley on the end of a driven DAN crank (Ebert (2015), Anhang A.1
    on a linkage element) at a random offset, placed by frameRef
    'relative' or by its world start pose ('global'), between two anchors
    below it: must run."""
    l, phi0 = round(rng.uniform(0.1, 0.4), 3), round(rng.uniform(-math.pi, math.pi), 3)
    dx, dy = round(rng.uniform(-0.1, 0.1), 3), round(rng.uniform(-0.1, 0.1), 3)
    c, s = math.cos(phi0), math.sin(phi0)
    P = (l * c + c * dx - s * dy, l * s + s * dx + c * dy)
    if rng.random() < 0.5:
        place = "x10=%r, y10=%r" % (dx, dy)
    else:
        place = "x10=%r, y10=%r, phi10=%r, frameRef='global'" % (P[0], P[1], phi0)
    body = _ON_CRANK.format(l=l, om=round(rng.uniform(-1.0, 1.0), 3), phi0=phi0,
                            r=round(rng.uniform(0.02, 0.06), 3), place=place,
                            q1x=round(P[0] - 1.0, 3), q1y=round(P[1] - 1.5, 3),
                            q2x=round(P[0] + 1.0, 3), q2y=round(P[1] - 1.5, 3))
    return body, (0,)


def cases(n=12, seed=32, on_crank=4):
    """``n`` loose-pulley placements, the kinds in turn, and ``on_crank``
    pulleys on a driven crank."""
    from fuzz_cases import _case, _model
    rng = random.Random(seed)
    out = []
    for k in range(n):
        kind = _KINDS[k % len(_KINDS)]
        body, codes = _loose(rng, kind)
        out.append(_case("pulley-placement-%d-%s" % (k, kind), "placement",
                         _model(body, extra=EXTRA), codes=codes))
    for k in range(on_crank):
        body, codes = _on_crank(rng)
        out.append(_case("pulley-on-crank-%d" % k, "placement", _model(body, extra=EXTRA),
                         codes=codes))
    return out
