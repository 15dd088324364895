"""Fuzz classes of issue 29, Seen 3-5 (tests/fuzz_cases.py's case format):
pulley winding signs (Atwood machines with random masses, radii, band ends
and either sign: the sign that crosses the bands must be refused, the
other must run), unconnected ports (the DDDD four-bar with random
connections left out: ``check`` runs and lists the grounded ports, given
under the extra key ``grounded`` for test_geometry_edges.py) and cam
contours from functions that do not close, close with a kink or close
smoothly (refused, refused, run).  Deterministic (fixed seeds)."""
import random

EXTRA = """
import casadi as ca
from acausal2d.library.belt import Band, Belt, Contour, Pulley, connect_band
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar.cam import CamFollower
"""

_ATWOOD = """
self.pulley = Pulley(r={r}, x10=0.0, y10=0.0, w_i={w_i}, J={J})
self.band1, self.band2 = {span}, {span2}
{left}
self.m2 = Body(m={m2}, I=0.01, x=start({x2}), y=start({y2}))
connect_band(self, self.band1, 2, self.pulley, 1)
connect_band(self, self.band2, 1, self.pulley, 2)
self.connect(self.band2.ctr2D2, self.m2.frame_a)
"""


def winding_cases(n=8, seed=29):
    """Atwood machines: the left band end (a mass or an anchor) hangs under
    K1 on the left, the right mass under K2 on the right (offsets up to
    0.3 r), so w = -1 is the sign that fits; w = +1 crosses the bands."""
    from fuzz_cases import _case, _model
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        r = round(rng.uniform(0.02, 0.3), 3)
        w = -1 if k % 2 == 0 else 1
        x1 = round(-r + rng.uniform(-0.3, 0.3) * r, 4)
        x2 = round(r + rng.uniform(-0.3, 0.3) * r, 4)
        y1, y2 = (round(-rng.uniform(0.3, 2.0), 3) for _ in range(2))
        if rng.random() < 0.3:
            left = "self.m1 = Fixed(r=(%r, %r))\nself.connect(self.m1.frame, self.band1.ctr2D1)" \
                % (x1, y1)
        else:
            left = ("self.m1 = Body(m=%r, I=0.01, x=start(%r), y=start(%r))\n"
                    "self.connect(self.m1.frame_a, self.band1.ctr2D1)"
                    % (round(rng.uniform(0.5, 5.0), 2), x1, y1))
        elastic = rng.random() < 0.3
        span = ("Belt(c=1e6, d=1e2, eps=start(1e-5, fixed=True))" if elastic else "Band()")
        body = _ATWOOD.format(r=r, w_i=-w, J=round(rng.uniform(1e-4, 0.05), 4), span=span,
                              span2=span, left=left, m2=round(rng.uniform(0.5, 5.0), 2),
                              x2=x2, y2=y2)
        cases.append(_case("winding-%d" % k, "winding", _model(body, extra=EXTRA),
                           codes=(0,) if w == -1 else (2,)))
    return cases


_FOURBAR = {
    "preset": "self.connect(self.preset.flange, self.crank.ctrR2)",
    "coupler": "self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)",
}


def unconnected_cases():
    """The DDDD four-bar of models/four_link_mechanisms.py with each subset
    of its two connections left out; ``grounded``: the ports check must
    list (the crank's and the rocker's ground pivots always, the dyad's
    ctr2D1 when the coupler connection is missing)."""
    from fuzz_cases import _case, _model
    cases = []
    for k, kept in enumerate(([], ["preset"], ["coupler"], ["preset", "coupler"])):
        body = ("self.preset = Preset(kind='speed', om=2 * math.pi, phi0=0.0)\n"
                "self.crank = DAN(lL=0.1, mL=0.5, JL=1e-3)\n"
                "self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)\n"
                + "\n".join(_FOURBAR[name] for name in kept))
        grounded = ["crank.ctr2D1", "dyad.ctr2D2"]
        if "coupler" not in kept:
            grounded.insert(1, "dyad.ctr2D1")
        case = _case("unconnected-%d" % k, "unconnected", _model(body, extra=EXTRA),
                     command="check", codes=(0,))
        case["grounded"] = grounded
        cases.append(case)
    return cases


_CAM = """
self.drive = Preset(kind="speed", om=2 * math.pi, phi0=0.0)
self.base = Fixed()
self.shaft = Revolute(use_flange=True)
self.connect(self.drive.flange, self.shaft.flange_a)
self.connect(self.base.frame, self.shaft.frame_a)
self.cam = CamFollower(Contour.from_function(lambda k: {radius}), follower="roller",
                       r_roller=0.0, q=start(math.pi / 2))
self.connect(self.shaft.frame_b, self.cam.frame_a)
self.top = Fixed()
self.guide = Prismatic(r=(0.0, 1.0), s=start({s0}))
self.follower = Body(m=0.5, I=1e-4)
self.connect(self.top.frame, self.guide.frame_a)
self.connect(self.guide.frame_b, self.follower.frame_a)
self.connect(self.guide.frame_b, self.cam.frame_b)
"""


def cam_contour_cases(n=6, seed=30):
    """Cams from functions: a spiral r = R0 + c kappa (open: refused), a
    closed contour with a kink |sin(kappa - k0)| (refused), and the smooth
    harmonic contour R0 + H/2 - H/2 sin(kappa) (runs; the follower is held
    by gravity and a rigid force-closed contact)."""
    from fuzz_cases import _case, _model
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        r0, h = round(rng.uniform(0.03, 0.06), 4), round(rng.uniform(0.002, 0.02), 4)
        kind = ("spiral", "kink", "smooth")[k % 3]
        radius = {"spiral": "%r + %r * k" % (r0, round(rng.uniform(1e-4, 0.01), 5)),
                  "kink": "%r + %r * ca.fabs(ca.sin(k - %r))" % (r0, h,
                                                                 round(rng.uniform(0, 3), 3)),
                  "smooth": "%r + %r - %r * ca.sin(k)" % (r0, h / 2, h / 2)}[kind]
        body = _CAM.format(radius=radius, s0=r0)
        cases.append(_case("cam-contour-%d-%s" % (k, kind), "cam contour",
                           _model(body, extra=EXTRA), codes=(0,) if kind == "smooth" else (2,)))
    return cases


def cases():
    """Every fuzz case of this module, in a fixed order."""
    return winding_cases() + unconnected_cases() + cam_contour_cases()

