"""Fuzz classes of issue 32 (tests/fuzz_cases.py's case format): placements
of a pulley (seed Tabelle 4.15, Anhang A.1) on a hanging body ("lose Rolle"
in a rope loop between two anchors).  Good placements -- random offsets
x10, y10 in the body frame with the body started where the axis hangs
between the anchors -- must run; bad ones must be refused with exit code 2:
a body without start values (the axis' start position is unknown), former
x0/y0 that contradict the body's start, a frameRef or half-plane that does
not exist, and a half-plane enumHE1 the winding direction does not
produce.  Deterministic (fixed seed)."""
import random

EXTRA = """
from acausal2d.library.belt import Belt, Pulley, connect_band
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


def cases(n=12, seed=32):
    """``n`` loose-pulley placements, the kinds in turn."""
    from fuzz_cases import _case, _model
    rng = random.Random(seed)
    out = []
    for k in range(n):
        kind = _KINDS[k % len(_KINDS)]
        body, codes = _loose(rng, kind)
        out.append(_case("pulley-placement-%d-%s" % (k, kind), "placement",
                         _model(body, extra=EXTRA), codes=codes))
    return out
