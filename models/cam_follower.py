"""Cam joints K of Ebert (2015), Tab. 2.1: a cam turning at constant speed about the
origin lifts a translating follower on a vertical guide above it, held on
the cam by a preloaded spring and gravity.  The follower's lift follows the
cam's design law exactly:

====================  ===========================  ==========================
model                 contour, follower            lift y(theta)
====================  ===========================  ==========================
CamKnifeEdge          polar Fourier series r(k),   R0 + H/2 (1 - cos theta)
                      knife edge (r_roller = 0)
CamFlatFollower       support function p(psi),     R0 + H/2 (1 - cos theta)
                      flat face
CamRollerFollower     eccentric circle (support    e sin theta + sqrt((Rc +
                      function), roller            rr)^2 - e^2 cos^2 theta)
====================  ===========================  ==========================

theta = om t is the cam angle; the follower is on the y axis, so the cam
point under it has the polar angle pi/2 - theta (normal angle pi/2 - theta
for the flat face).  The contact force is the follower's m (y'' + g) plus
the spring force; a fast cam makes it negative: the rigid contact cannot
follow that lift-off and the run ends there with an error (``acausal2d
simulate models/cam_follower.py --model CamFlatFollower --set drive.om=100``).
``CamFlatCompliant`` has the compliant (unilateral) contact: at 100 rad/s
the follower lifts off, flies on its spring and lands again (events, see
``CamFollower.contact_changes``).  ``acausal2d simulate models/cam_follower.py
--model CamFlatFollower`` plots the lift and the contact force.
"""
import math

from acausal2d import Component, start
from acausal2d.library import translational
from acausal2d.library.belt import Contour, SupportContour
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Body, Fixed, Prismatic, Revolute
from acausal2d.library.planar.cam import CamFollower

R0, H = 0.04, 0.02              # base radius and stroke of the harmonic law
RC, E, RR = 0.04, 0.01, 0.01    # eccentric cam: radius, eccentricity, roller radius
M, K_SPRING, F0 = 0.5, 500.0, 5.0
OM = 2 * math.pi                # one turn per second


def harmonic_lift(theta):
    """Design law of CamKnifeEdge and CamFlatFollower."""
    return R0 + H / 2 * (1 - math.cos(theta))


def eccentric_lift(theta):
    """Design law of CamRollerFollower (roller centre height)."""
    return E * math.sin(theta) + math.sqrt((RC + RR) ** 2 - (E * math.cos(theta)) ** 2)


class _Cam(Component):
    """Cam on a driven revolute at the origin, follower on a vertical guide
    (body of mass M on a prismatic joint, spring preload F0 downwards)."""
    experiment = {"stop_time": 1.0, "intervals": 200, "rtol": 1e-10}
    outputs = ["guide.s", "cam.Fn", "cam.lifted"]
    figures = [{"name": "lift", "signals": ["guide.s"], "x": "drive.phi",
                "title": "follower lift over the cam angle"},
               {"name": "contact_force", "signals": ["cam.Fn"], "x": "drive.phi",
                "title": "contact force (compression positive)"}]
    y0 = R0
    flat = False

    def _build(self, cam, s_start=None, v_start=0.0):
        self.drive = Preset(kind="speed", om=OM, phi0=0.0)
        self.base = Fixed()
        self.shaft = Revolute(use_flange=True)
        self.connect(self.drive.flange, self.shaft.flange_a)
        self.connect(self.base.frame, self.shaft.frame_a)
        self.cam = cam
        self.connect(self.shaft.frame_b, cam.frame_a)
        # the guide: frame_b at (0, s); a flat face points along -x (cam below it)
        phi = math.pi if self.flat else 0.0
        self.top = Fixed(phi=phi)
        self.guide = Prismatic(r=(0.0, -1.0) if self.flat else (0.0, 1.0), use_flange=True,
                               s=start(self.y0 if s_start is None else s_start),
                               v=start(v_start, fixed=v_start != 0.0))
        self.follower = Body(m=M, I=1e-4)
        self.connect(self.top.frame, self.guide.frame_a)
        self.connect(self.guide.frame_b, self.follower.frame_a)
        self.connect(self.guide.frame_b, cam.frame_b)
        self.anchor = translational.Fixed()
        self.spring = translational.Spring(c=K_SPRING, s_rel0=self.y0 - F0 / K_SPRING)
        self.connect(self.anchor.flange, self.spring.flange_a)
        self.connect(self.spring.flange_b, self.guide.flange_a)


class CamKnifeEdge(_Cam):
    """Knife edge on the polar contour r = R0 + H/2 - H/2 sin(kappa)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        contour = Contour.fourier(R0 + H / 2, a=(0.0,), b=(-H / 2,))
        self._build(CamFollower(contour, follower="roller", r_roller=0.0,
                                q=start(math.pi / 2)))


class CamFlatFollower(_Cam):
    """Flat face on the support function p = R0 + H/2 - H/2 sin(psi)."""
    flat = True

    def __init__(self, **kw):
        super().__init__(**kw)
        contour = SupportContour(R0 + H / 2, a=(0.0,), b=(-H / 2,))
        self._build(CamFollower(contour, follower="flat", q=start(math.pi / 2)))


class CamRollerFollower(_Cam):
    """Roller of radius RR on an eccentric circle (centre at E on the cam's
    x axis: support function p = RC + E cos(psi))."""
    y0 = eccentric_lift(0.0)

    def __init__(self, **kw):
        super().__init__(**kw)
        contour = SupportContour(RC, a=(E,), b=(0.0,))
        self._build(CamFollower(contour, follower="roller", r_roller=RR,
                                q=start(math.pi / 2)))


class CamFlatCompliant(_Cam):
    """CamFlatFollower with the compliant contact (k_contact = 1e7 N/m,
    d_contact = 300 N s/m, the defaults): the follower may lift off.  It
    starts pressed in by the static penetration (M (H/2 OM^2 + g) + F0)/k."""
    flat = True
    outputs = ["guide.s", "cam.Fn", "cam.delta", "cam.lifted"]
    figures = _Cam.figures + [{"name": "penetration", "signals": ["cam.delta"], "x": "time",
                               "title": "penetration (negative: lifted off)"}]

    def __init__(self, **kw):
        super().__init__(**kw)
        cam = CamFollower(SupportContour(R0 + H / 2, a=(0.0,), b=(-H / 2,)), follower="flat",
                          contact="compliant", q=start(math.pi / 2))
        self._build(cam, s_start=R0 - (M * (H / 2 * OM ** 2 + 9.81) + F0) / cam.k_contact)


MODELS = [CamKnifeEdge, CamFlatFollower, CamRollerFollower, CamFlatCompliant]
