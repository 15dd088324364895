"""Rope drives of Ebert (2015), ch. 2.5.1 (Bild 2.4, 2.5): the factor block
(Faktorenflaschenzug), the potential block (Potenzialflaschenzug) and the
differential block (Differenzialflaschenzug), with inextensible ropes
(:class:`~acausal2d.library.belt.Band`) and frictionless pulleys.

The rope end is pulled at the constant speed ``V``, so the load rises at
constant speed and every force is the static one.  Closed forms (all
sections vertical, W the weight carried):

==================  ===========================  ============================
model               pull force F                 pull travel / load travel
==================  ===========================  ============================
FactorBlock         W / n (n = 4 sections)       n
PotentialBlock      ((W/2 + m g)/2 + m g) / 2    2^3 (three loose pulleys)
                    (loose pulleys of mass m)
DifferentialBlock   W (R - r) / (2 R)            2 R / (R - r)
==================  ===========================  ============================

Values the dissertation does not give (Bild 2.4/2.5 are pictures): load 50 kg,
pulley radii 40-60 mm, pull speed 0.1 m/s, 2 s.  ``acausal2d simulate
models/rope_drives.py --model DifferentialBlock`` plots the pull force and
the load height.
"""
import math

from acausal2d import Component, start
from acausal2d.library.belt import Band, Drum, Pulley, RopeDrive, connect_band
from acausal2d.library.planar import Body, Fixed, FixedTranslation
from acausal2d.library.signals import TimeFunction

G = 9.81
MASS = 50.0
V = 0.1
Y_TOP, Y_LOW = 0.0, -1.0


def rope(a, b):
    """An inextensible rope section from point a to point b (start values)."""
    gam = math.atan2(b[1] - a[1], b[0] - a[0])
    length = math.dist(a, b)
    return Band(gamma=start(gam), l=start(length), l_x=start(length), l_x0=start(length))


class _RopeDrive(Component):
    """The pulled rope end: a RopeDrive at ``(x, y)`` moved at speed V in
    direction ``angle`` (down by default)."""
    experiment = {"stop_time": 2.0, "intervals": 100, "rtol": 1e-10}
    outputs = ["pull.F", "load.y"]
    figures = [{"name": "pull_force", "signals": ["pull.F"], "title": "pull force"},
               {"name": "travel", "signals": ["pull.s_in.u", "load.y"],
                "title": "pull travel and load height"}]

    def _pull(self, x, y, angle=-math.pi / 2):
        self.pull = RopeDrive(x0=x, y0=y, angle=angle)
        self.profile = TimeFunction(lambda t: V * t)
        self.connect(self.profile.y, self.pull.s_in)

    def _load(self, name, x, y, m=MASS):
        """A body at a loose pulley's axis (start position fixed)."""
        body = Body(m=m, I=0.01, x=start(x, fixed=True), y=start(y, fixed=True),
                    phi=start(0.0, fixed=True), vx=start(0.0, fixed=True),
                    w=start(0.0, fixed=True))
        setattr(self, name, body)
        return body


class FactorBlock(_RopeDrive):
    """Factor block (Bild 2.4): fixed pulleys U1, U3 and loose pulleys L2,
    L4 on one load body; one rope reeved alternately, n = 4 carrying
    sections: F = W/4, the pull end travels 4 times the load."""
    n = 4

    def __init__(self, **kw):
        super().__init__(**kw)
        r = 0.05
        xs = [i * r for i in range(9)]          # x of the vertical sections
        self.U1 = Pulley(r=r, x10=r, y10=Y_TOP, w_i=1)
        self.U3 = Pulley(r=r, x10=5 * r, y10=Y_TOP, w_i=1)
        self.L2 = Pulley(r=r, w_i=-1)            # on arm2 (3 r, Y_LOW)
        self.L4 = Pulley(r=r, w_i=-1)            # on arm4 (7 r, Y_LOW)
        load = self._load("load", 5 * r, Y_LOW - 0.2)
        for name, x in (("arm2", 3 * r), ("arm4", 7 * r)):
            arm = FixedTranslation(r=(x - 5 * r, 0.2))
            setattr(self, name, arm)
            self.connect(load.frame_a, arm.frame_a)
            self.connect(arm.frame_b, getattr(self, "L" + name[-1]).ctr2D1)
        self._pull(xs[0], -0.5)
        self.anchor = Fixed(r=(xs[8], Y_TOP))
        wheels = [self.U1, self.L2, self.U3, self.L4]
        ys = [Y_TOP, Y_LOW, Y_TOP, Y_LOW]
        self.rope1 = rope((xs[0], -0.5), (xs[0], Y_TOP))
        self.connect(self.pull.frame, self.rope1.ctr2D1)
        connect_band(self, self.rope1, 2, self.U1, 1)
        for k in range(4):
            a = (xs[2 * k + 2], ys[k])
            b = (xs[2 * k + 2], ys[k + 1] if k < 3 else Y_TOP)
            sec = rope(a, b)
            setattr(self, "rope%d" % (k + 2), sec)
            connect_band(self, sec, 1, wheels[k], 2)
            if k < 3:
                connect_band(self, sec, 2, wheels[k + 1], 1)
        self.connect(self.rope5.ctr2D2, self.anchor.frame)
    outputs = ["pull.F", "load.y", "rope2.F", "rope5.F"]


class PotentialBlock(_RopeDrive):
    """Potential block (Bild 2.5 left): three loose pulleys in cascade; each
    rope has one end fastened above and the other on the axis of the next
    pulley; the last one is pulled upwards.  With loose pulleys of mass
    ``M_PULLEY`` the pull force is ((W/2 + m g)/2 + m g)/2."""
    M_PULLEY = 1.0

    def __init__(self, **kw):
        super().__init__(**kw)
        r = [0.04, 0.05, 0.06]
        x, y = [0.0], [-1.2, -0.9, -0.6]
        for k in range(2):
            x.append(x[k] + r[k])           # right section of k ends on the axis of k+1
        for k in range(3):
            setattr(self, "P%d" % (k + 1), Pulley(r=r[k], w_i=-1, J=1e-5))
            body = self._load("load" if k == 0 else "carrier%d" % (k + 1), x[k], y[k],
                              MASS if k == 0 else self.M_PULLEY)
            self.connect(body.frame_a, getattr(self, "P%d" % (k + 1)).ctr2D1)
        self._pull(x[2] + r[2], y[2] + 0.3, angle=math.pi / 2)
        for k in range(3):
            P = getattr(self, "P%d" % (k + 1))
            anchor = Fixed(r=(x[k] - r[k], Y_TOP))
            setattr(self, "anchor%d" % (k + 1), anchor)
            left = rope((x[k] - r[k], y[k]), (x[k] - r[k], Y_TOP))
            setattr(self, "left%d" % (k + 1), left)
            connect_band(self, left, 1, P, 1)
            self.connect(left.ctr2D2, anchor.frame)
            top = y[k + 1] if k < 2 else y[2] + 0.3
            right = rope((x[k] + r[k], y[k]), (x[k] + r[k], top))
            setattr(self, "right%d" % (k + 1), right)
            connect_band(self, right, 1, P, 2)
            nxt = getattr(self, "P%d" % (k + 2)).ctr2D1 if k < 2 else self.pull.frame
            self.connect(right.ctr2D2, nxt)
    outputs = ["pull.F", "load.y", "right1.F", "right2.F"]


class DifferentialBlock(_RopeDrive):
    """Differential block (Bild 2.5 right): the differential pulley (radii R
    and r on one shaft, fixed axis) and a loose pulley carrying the load.
    The load loop leaves the large wheel on the right and the small wheel
    on the left; the pull side comes off the large wheel on the left (the
    slack return loop carries no force and is left out): F = W (R - r)/(2R)."""
    R, r = 0.06, 0.04

    def __init__(self, **kw):
        super().__init__(**kw)
        R, r = self.R, self.r
        self.big = Pulley(r=R, x10=0.0, y10=Y_TOP, w_i=1, J=1e-4)
        self.small = Drum(r=r, x10=0.0, y10=Y_TOP, w_i=1, J=1e-4, alpha_fix=0.0, n_wound=2.0)
        self.connect(self.big.ctrR2, self.small.ctrR2)       # one shaft
        rl, xl = (R + r) / 2, (R - r) / 2
        self.loose = Pulley(r=rl, w_i=-1, J=1e-5)         # on the load at (xl, Y_LOW)
        load = self._load("load", xl, Y_LOW)
        self.connect(load.frame_a, self.loose.ctr2D1)
        self._pull(-R, -0.5)
        self.pull_side = rope((-R, -0.5), (-R, Y_TOP))
        self.load_big = rope((R, Y_TOP), (R, Y_LOW))
        self.load_small = rope((-r, Y_LOW), (-r, Y_TOP))
        self.connect(self.pull.frame, self.pull_side.ctr2D1)
        connect_band(self, self.pull_side, 2, self.big, 1)
        connect_band(self, self.load_big, 1, self.big, 2)
        connect_band(self, self.load_big, 2, self.loose, 2)
        connect_band(self, self.load_small, 1, self.loose, 1)
        connect_band(self, self.load_small, 2, self.small, 1)
    outputs = ["pull.F", "load.y", "load_big.F", "load_small.F"]


MODELS = [FactorBlock, PotentialBlock, DifferentialBlock]
