"""Two-band structures of four-link band mechanisms (Ebert 2015, ch. 2.5.2, Bild
2.6: "optionally two rigid links are replaced by bands", R1), generated from
their code as :mod:`acausal2d.library.belt.systematics` does for one band.

Two bands are never adjacent, so they are L1 and L3 (the frame and the
coupler L2 rigid: ``"D~BD~B"``) or L2 and the frame (``"DB~DB~"``: the
band as the frame, a taut straight band along y = 0).  Every joint is then
a band end (D pin or B disc).

- Bands L1 and L3: the coupler hangs on the two bands only, a free body:
  it is carried by a vertical and a horizontal guide (two massless sliders
  whose guides transmit no force along themselves) and turns about J2 (a
  :class:`~acausal2d.library.linkage.DAN`), so its three planar degrees of
  freedom are free; the bands take two of them.  Its angle is driven (0.5
  rad/s); a vertical force on the vertical slider (the coupler's weight
  turned upwards, the bands pull it towards the frame) is sized for 10 N in
  the band L3 at t = 0.
- Band L2 and the band as the frame (a taut straight band along y = 0):
  J1 is a pivot D on the band frame (the crank L1, driven at 0.5 rad/s
  clockwise), J4 a disc of L3 that rolls on the band frame without slip
  (:class:`~acausal2d.library.planar.IdealRolling`) or a pivot D, the band
  L2 runs from J2 on the crank to J3 on L3; a torque on L3 (a
  :class:`~acausal2d.library.planar.forces.WorldTorque` on the wheel) is
  sized for 10 N in the band L2 at t = 0.  The drive turns clockwise: turned
  the other way from these start points, the band's line reaches the
  wheel's contact point (its instantaneous centre) within 0.04 s, a dead
  position where the band force needed grows without bound (41 N at 0.035
  s, 10 N at t = 0) and the integration stops there.  With a disc B at J1
  as well (BB~DB~, BB~BB~) both frame-side links are wheels and no joint
  takes a speed preset; the disc at J2 is then a winch driven at 0.5 rad/s
  relative to its wheel (a drive on the band's wound length), and both
  wheels carry a torque sized for 10 N in the band: the massless wheels'
  moment balances about their contact points fix where they stand.
"""
import math

from acausal2d import start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import signals
from acausal2d.library.belt.layout import tangent
from acausal2d.library.belt.spans import Band
from acausal2d.library.belt.systematics import (BAND_FRAME_J3, F_BAND, OMEGA, R_DISC, SKELETON,
                                                BandStructure, _angle)
from acausal2d.library.linkage import DAN, SAN
from acausal2d.library.linkage.drives import ForceSource, Preset, TorqueSource
from acausal2d.library.planar import FixedTranslation, IdealRolling
from acausal2d.library.planar.forces import WorldTorque

__all__ = ["TwoBandStructure", "parse_two_bands", "HANGING"]

WINCH = 0.5
"""Speed of the winch (rad/s relative to its wheel) that drives BB~DB~ and
BB~BB~ (the band as the frame)."""
HANGING = {1: (-0.12, 0.25), 2: (0.08, 0.05), 3: (0.28, 0.05), 4: (0.48, 0.25)}
"""Joint points (m) of the structures with bands L1 and L3: the coupler
J2-J3 hangs from the frame points J1, J4, its load pulls it down."""


def parse_two_bands(code):
    """``"D~BD~B"`` -> (letters, (1, 3)); ``"DB~DB~"`` -> (letters, (2, 4)).
    Refuses codes whose bands are adjacent or without a disc, or with a
    prismatic joint (every joint of a two-band chain is a band end)."""
    letters = code.replace("~", "")
    marks = tuple(len(code[:i].replace("~", "")) for i, ch in enumerate(code) if ch == "~")
    if len(letters) != 4 or set(letters) - set("DB") or marks not in ((1, 3), (2, 4)):
        raise ModelDefinitionError(
            "two-band structure %r: give four joint letters D or B with '~' after the first "
            "and third ('D~BD~B': bands L1, L3) or the second and fourth ('DB~DB~': band L2 "
            "and the band as the frame); two bands are never adjacent" % code)
    for b in marks:
        if "B" not in letters[b - 1] + letters[b % 4]:
            raise ModelDefinitionError("two-band structure %r: band L%d has no disc B (Ebert "
                                       "2015, ch. 2.5.2: D-B or B-B)" % (code, b))
    return letters, marks


class TwoBandStructure(BandStructure):
    """A four-link mechanism with two bands of the structure ``code`` (class
    attribute), built as the module docstring says.  Metadata for checks:
    ``bands`` ({name: (joint of end 1, joint of end 2)}), ``ends``
    ({joint: the signal prefix of the frame the band pulls at, a pin's frame
    or the disc's contact ``discJ.ctrK1``; None for a pin in the ground}),
    ``load_kind`` ("force", on the coupler's vertical slider) and
    ``load_value``."""
    experiment = {"stop_time": 0.4, "intervals": 8, "rtol": 1e-10}
    outputs = ["drive.tau", "band1.F"]

    def __init__(self, **kw):
        super(BandStructure, self).__init__(**kw)
        letters, marks = parse_two_bands(self.code)
        self._letters, self._pts = letters, dict(SKELETON)
        self.bands, self.ends = {}, {}
        if marks == (1, 3):
            self._coupler_on_bands()
        else:
            self._band_frame_pair()

    def _band_pair(self, name, ja, jb, frames, winch=None):
        """Band ``name`` from J_ja (end 1) to J_jb (end 2); ``frames`` maps a
        joint to (connector, signal prefix) of the frame that carries its pin
        or disc (missing: the ground)."""
        geo = [(*self._pts[j], R_DISC if self._letters[j - 1] == "B" else 0.0) for j in (ja, jb)]
        gam, length = tangent(*geo)
        band = Band(gamma=start(gam), l=start(length), l_x=start(length), l_x0=start(length))
        setattr(self, name, band)
        self.bands[name] = (ja, jb)
        q = {}
        for k, j in ((1, ja), (2, jb)):
            self.ends[j], q[j] = self._end(band, j, k, frames.get(j), gam,
                                           winch if k == 1 else None)
        return gam, q

    def _coupler_on_bands(self):
        """Bands L1 (J1-J2) and L3 (J3-J4); the coupler J2-J3 is free and
        hangs from the frame points (:data:`HANGING`) like a swing."""
        self._pts = dict(HANGING)
        p2, p3 = self._pts[2], self._pts[3]
        self.carrier_y = SAN(x10=p2[0], y10=0.0, phi10=math.pi / 2, mS=0.0, JS=0.0, xS0=p2[1],
                             xG=start(p2[1]))
        self.carrier_x = SAN(phi10=-math.pi / 2, mS=0.0, JS=0.0, xS0=0.0, xG=start(0.0))
        self.connect(self.carrier_y.ctr2D2, self.carrier_x.ctr2D1)
        ang, lL = _angle(p2, p3), math.hypot(p3[0] - p2[0], p3[1] - p2[1])
        self.coupler = DAN(lL=lL, mL=0.0, JL=0.0, phiL0=ang, phiL=start(ang))
        self.connect(self.carrier_x.ctr2D2, self.coupler.ctr2D1)
        self.back = FixedTranslation(r=(-lL, 0.0))          # the coupler's frame at J2
        self.connect(self.coupler.ctr2D2, self.back.frame_a)
        self.drive = Preset(kind="speed", om=OMEGA, phi0=ang)
        self.connect(self.drive.flange, self.coupler.ctrR2)
        g1, _ = self._band_pair("band1", 1, 2, {2: (self.back.frame_b, "back.frame_b")})
        g3, _ = self._band_pair("band3", 3, 4, {3: (self.coupler.ctr2D2, "coupler.ctr2D2")})
        u1 = (-math.cos(g1), -math.sin(g1))                 # at J2 towards J1
        u3 = (math.cos(g3), math.sin(g3))                   # at J3 towards J4
        f1 = -F_BAND * u3[0] / u1[0]
        if f1 <= 0:
            raise ModelDefinitionError("two-band structure %r: the bands cannot both pull the "
                                       "coupler at the skeleton" % self.code)
        self.load_kind, self.load_value = "force", -(f1 * u1[1] + F_BAND * u3[1])
        self.load = ForceSource(f=self.load_value)
        self.connect(self.load.flange, self.carrier_y.ctrT2)

    def _band_frame_pair(self):
        """Band L2 (J2-J3) and the band as the frame (y = 0): J1 and J4 are a
        pivot on the band frame (D) or a disc of the link rolling on it (B,
        :class:`~acausal2d.library.planar.IdealRolling`); the link L1 is
        driven (its pivot's angle), L3 loaded by a torque sized for 10 N in
        the band L2."""
        self.outputs = ["drive.tau", "band2.F"]
        pts = dict(SKELETON)
        pts[3] = BAND_FRAME_J3
        for j in (1, 4):
            if self._letters[j - 1] == "B":
                pts[j] = (pts[j][0], R_DISC)
        self._pts = pts
        frame2, winch = self._link12(pts)
        frame3, pivot = self._link34(pts)
        gam, q = self._band_pair("band2", 2, 3, {2: frame2, 3: frame3}, winch)
        if winch is not None:
            arm1 = (q[2][0] - pts[1][0]) * math.sin(gam) - q[2][1] * math.cos(gam)
            self.load1_value = -F_BAND * arm1                # band pulls J2 along e
            self._wheel_torque("load1", self.roll1, self.load1_value)
        arm = (q[3][0] - pivot[0]) * math.sin(gam) - (q[3][1] - pivot[1]) * math.cos(gam)
        self.load_kind, self.load_value = "torque", F_BAND * arm     # band pulls J3 along -e
        if self._letters[3] == "B":
            self._wheel_torque("load", self.roll, self.load_value)
        else:
            self.load = TorqueSource(tau=self.load_value)
            self.connect(self.load.flange, self.link34.ctrR2)

    def _wheel_torque(self, name, wheel, value):
        """A constant torque ``value`` on ``wheel`` (reaction in the world)."""
        setattr(self, name, WorldTorque())
        setattr(self, name + "_k", signals.Constant(k=value))
        self.connect(getattr(self, name + "_k").y, getattr(self, name).torque)
        self.connect(getattr(self, name).frame_b, wheel.frame_a)

    def _link12(self, pts):
        """The link L1 from J1 to J2: a crank pivoted on the band frame (D),
        driven; or a wheel rolling on it (B) with an arm to J2, whose disc at
        J2 is a winch driven relative to the wheel (nothing else of the chain
        can take a speed preset).  Returns ((connector, prefix) of J2, the
        winch preset or None)."""
        p1, p2 = pts[1], pts[2]
        if self._letters[0] == "D":
            a = _angle(p1, p2)
            self.link12 = DAN(x10=p1[0], y10=p1[1], lL=math.dist(p1, p2), mL=0.0, JL=0.0,
                              phiL0=a, phiL=start(a))
            self.drive = Preset(kind="speed", om=-OMEGA, phi0=a)
            self.connect(self.drive.flange, self.link12.ctrR2)
            return (self.link12.ctr2D2, "link12.ctr2D2"), None
        self.roll1 = IdealRolling(R=R_DISC, x0=p1[0], phi=start(0.0))
        self.arm1 = FixedTranslation(r=(p2[0] - p1[0], p2[1] - p1[1]))
        self.connect(self.roll1.frame_a, self.arm1.frame_a)
        self.drive = Preset(kind="speed", om=WINCH, phi0=0.0, use_support=True)
        return (self.arm1.frame_b, "arm1.frame_b"), self.drive

    def _link34(self, pts):
        """The link L3 from J4 on the band frame to J3: a wheel rolling on the
        band with an arm to J3 (B), or a rocker pivoted on it (D).  Returns
        ((connector, prefix) of J3, the pivot or contact point at t0)."""
        p3, p4 = pts[3], pts[4]
        if self._letters[3] == "D":
            a = _angle(p4, p3)
            self.link34 = DAN(x10=p4[0], y10=p4[1], lL=math.dist(p3, p4), mL=0.0, JL=0.0,
                              phiL0=a, phiL=start(a))
            return (self.link34.ctr2D2, "link34.ctr2D2"), p4
        self.roll = IdealRolling(R=R_DISC, x0=p4[0], phi=start(0.0))
        self.arm3 = FixedTranslation(r=(p3[0] - p4[0], p3[1] - p4[1]))
        self.connect(self.roll.frame_a, self.arm3.frame_a)
        return (self.arm3.frame_b, "arm3.frame_b"), (p4[0], 0.0)
