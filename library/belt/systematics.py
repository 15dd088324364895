"""Structures of four-link band mechanisms (Ebert 2015, ch. 2.5.2, Bild 2.6-2.8)
as runnable models, generated from their structure code.

Notation (Ebert 2015, ch. 2.1 and 2.4): a four-link chain is named by its four
joints read around the loop starting at the frame, so the first and the
last letter are the joints on the frame: D revolute, S prismatic, B band
joint (the band rolls off a disc, f = 1).  ``~`` marks the link between two
joints that is a band: ``DB~DD`` is a cam disc pivoted in the frame whose
band pulls a rocker pivoted in the frame.  A band's end is a pin (D) on the
neighbouring link or a disc (B) carried by it.

How :class:`BandStructure` builds a code (joints J1..J4, links L1 = J1-J2,
L2 = J2-J3, L3 = J3-J4, the frame L0 = J4-J1): the joints sit at the
corners of a skeleton quadrilateral (:data:`SKELETON`, metres).  The rigid
links form two open branches from the frame up to the band's ends: a link
behind a revolute joint is a :class:`~acausal2d.library.linkage.DAN` (its
housing on the frame or on the tip of the link before it), a link behind a
prismatic joint a :class:`~acausal2d.library.linkage.SAN` whose guide runs
from the joint towards the link's next joint.  A disc is a circular
:class:`~acausal2d.library.belt.Drum` (radius :data:`R_DISC`) locked to the
link that carries it (or to the frame); the band is an inextensible
:class:`~acausal2d.library.belt.Band` that closes the loop.  All links are
massless.  The first link of the branches is driven by a speed preset (0.5
rad/s or 0.02 m/s); the link that carries the band's other end is loaded
by a constant torque (force) whose sign is chosen from the start geometry
so that the band pulls with about :data:`F_BAND` N.  A force on a slider
whose guide moves acts between slider and guide (1D sources on both
flanges), so every load is a true external or internal force.

The band as the frame (code with a trailing ``~``, ``"BDDD~"``; see
:meth:`BandStructure._build_band_frame`) is a taut straight band along y =
0 on which discs roll.  Two-band structures are not built by this class;
:mod:`acausal2d.library.belt.structures` derives the structures the rules
define; models/band_systematics.py makes a model of each.
"""
import math

from acausal2d import Component, start
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.belt.drum import Drum
from acausal2d.library.belt.layout import connect_band, tangent
from acausal2d.library.belt.spans import Band
from acausal2d.library.linkage import DAN, SAN
from acausal2d.library.linkage.drives import ForceSource, Preset, TorqueSource
from acausal2d.library.planar import Fixed, IdealRolling

__all__ = ["BandStructure", "parse_structure", "SKELETON", "R_DISC", "F_BAND"]

SKELETON = {1: (0.0, 0.0), 2: (0.05, 0.15), 3: (0.3, 0.22), 4: (0.35, 0.0)}
"""Joint points J1..J4 of the generated mechanisms at t = 0 (m)."""
BAND_FRAME_J3 = (0.2, 0.12)
"""J3 when the band is the frame (with J3 of :data:`SKELETON`, DSDB~ starts
next to a dead position: its disc link's pin would run across the guide's
normal)."""
R_DISC = 0.03
"""Radius of every disc (m)."""
F_BAND = 10.0
"""Band force at t = 0 that the load is sized for (N)."""
OMEGA, SPEED = 0.5, 0.02       # drive: rad/s (revolute) or m/s (prismatic)


def parse_structure(code):
    """``"DB~DD"`` -> (joint letters "DBDD", index b of the band link
    L_b, 1..3; b = 4 for a trailing ``~``, ``"BDDD~"``: the band is the frame
    between J4 and J1).  Refuses codes that are not four joints with exactly one
    band between two of them, or whose band ends are not D or B with at
    least one B, or whose band lies next to a prismatic joint."""
    letters = code.replace("~", "")
    marks = [i for i, ch in enumerate(code) if ch == "~"]
    if len(letters) != 4 or set(letters) - set("DSB") or len(marks) != 1 or marks[0] == 0:
        raise ModelDefinitionError(
            "band structure %r: give four joint letters D, S, B with one '~' between the two "
            "joints of the band link, e.g. 'DB~DD'" % code)
    b = marks[0]                       # the band link L_b joins J_b and J_b+1 (L4: the frame)
    ends = letters[b - 1] + letters[b % 4]
    if "S" in ends or "B" not in ends:
        raise ModelDefinitionError(
            "band structure %r: the band's joints are %s; each end must be a pin D or a "
            "disc B, at least one B (Ebert 2015, ch. 2.5.2: a band joint does not combine with a "
            "prismatic joint)" % (code, ends))
    if any(ch == "B" and i not in (b - 1, b % 4) for i, ch in enumerate(letters)):
        raise ModelDefinitionError("band structure %r: a disc B is a band joint; here one is "
                                   "away from the band" % code)
    return letters, b


def _angle(p, c):
    return math.atan2(c[1] - p[1], c[0] - p[0])


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]



def _disc(p):
    """The disc of a B joint at ``p``: placed by its axis' start pose
    (x10, y10, frameRef='global', Ebert (2015), Anhang A.1, A.4-A.6) on the
    ground or on the linkage element that carries it (its offset in the
    link's frame follows from the link's start pose)."""
    return Drum(r=R_DISC, w_i=-1, n_wound=2.0, x10=p[0], y10=p[1], frameRef="global")


class BandStructure(Component):
    """A four-link band mechanism of the structure ``code`` (class
    attribute, e.g. ``"DB~DD"``), built as the module docstring says.

    Metadata for checks (set at construction): ``drive_link`` and
    ``load_link`` (names of the driven and loaded link elements),
    ``load_kind`` ("torque" or "force"), ``load_value``, ``load_point``
    (the frame whose point the band pulls on the loaded link: a link tip
    ``ctr2D2`` or a disc contact ``ctrK1``) and ``load_end`` (the band end,
    1 or 2, at the loaded link); ``drive_point`` and ``drive_end`` the same
    for the driven link when it carries the band's other end (else None)."""
    code = None
    experiment = {"stop_time": 0.4, "intervals": 8, "rtol": 1e-10}
    outputs = ["drive.tau", "band.F"]

    def __init__(self, **kw):
        super().__init__(**kw)
        letters, b = parse_structure(self.code)
        self._letters, self._band_link = letters, b
        self._pts = dict(SKELETON)
        self._angles, self._pivots, self._tip_at = {}, {}, {}
        if b == 4:
            self._build_band_frame(letters)
            return
        left = [(1, 2)] + ([(2, 3)] if b == 3 else []) if b > 1 else []
        right = [(4, 3)] + ([(3, 2)] if b == 1 else []) if b < 3 else []
        self._ends = (b, b + 1)
        geo = [(*self._pts[j], R_DISC if letters[j - 1] == "B" else 0.0) for j in self._ends]
        self._gam, self._length = tangent(*geo)
        tips = {}
        for branch in (left, right):
            parent = None
            for jp, jc in branch:
                parent = self._link(letters[jp - 1], jp, jc, parent)
                tips[jc] = parent
        chains = [br for br in (left, right) if br]
        self.drive_link = self._link_name(chains[0][0])
        self.load_link = self._link_name(chains[-1][-1])
        self._drive(self.drive_link)
        self._band(b, tips)

    @staticmethod
    def _link_name(pair):
        return "link%d%d" % (min(pair), max(pair))

    def _link(self, joint, jp, jc, parent):
        """The rigid link from joint jp (letter ``joint``) to jc, on the
        frame (parent None) or on the tip of the link ``parent``."""
        name = self._link_name((jp, jc))
        p, c = self._pts[jp], self._pts[jc]
        ang, length = _angle(p, c), math.hypot(c[0] - p[0], c[1] - p[1])
        rel = ang - (self._angles[parent] if parent else 0.0)
        at = self._placement(p, parent)
        if joint == "D":
            link = DAN(lL=length, mL=0.0, JL=0.0, phiL0=ang, phiL=start(ang), **at)
        elif joint == "S":
            ang = self._guide_angle(jc, ang)
            rel = ang - (self._angles[parent] if parent else 0.0)
            e, d = (math.cos(ang), math.sin(ang)), (c[0] - p[0], c[1] - p[1])
            x_s = e[0] * d[0] + e[1] * d[1]
            link = SAN(phi10=rel, v=_cross(e, d), mS=0.0, JS=0.0, xS0=x_s, xG=start(x_s), **at)
        else:
            raise ModelDefinitionError("band structure %r: the joint J%d between rigid links "
                                       "is %s; only D or S join two rigid links"
                                       % (self.code, jp, joint))
        setattr(self, name, link)
        self._angles[name], self._pivots[name], self._tip_at[name] = ang, p, c
        if parent:
            self.connect(self._out(parent), link.ctr2D1)
        return name

    def _out(self, name):
        """The output frame of link ``name`` (a link's tip, a wheel's centre)."""
        part = getattr(self, name)
        return part.ctr2D2 if hasattr(part, "ctr2D2") else part.frame_a

    def _placement(self, p, parent):
        """Placement (Anhang A.1) of the point p: on the frame, or relative
        to the output frame of ``parent`` turned by its start angle."""
        if not parent:
            return {"x10": p[0], "y10": p[1]}
        q, a = self._tip_at[parent], self._angles[parent]
        dx, dy = p[0] - q[0], p[1] - q[1]
        c, s = math.cos(a), math.sin(a)
        return {"x10": c * dx + s * dy, "y10": -s * dx + c * dy}

    def _guide_angle(self, j, ang):
        """Guide direction of a slider whose next joint is J_j: at 0.5 rad to
        the band when the slider carries a band end (a guide across the band
        would be a dead position; turned to opposite sides at the two ends, so
        that two such guides are not parallel), else ``ang`` (towards J_j)."""
        if j not in self._ends:
            return ang
        return self._gam + (0.5 if j == self._ends[0] else math.pi - 0.5)

    def _drive(self, name, on_wheel=False):
        """Speed preset on the link ``name``; a slider whose guide is on a
        rolling wheel (``on_wheel``) is driven relative to its guide, which
        takes the reaction."""
        link = getattr(self, name)
        if isinstance(link, DAN):
            self.drive = Preset(kind="speed", om=OMEGA, phi0=self._angles[name])
            self.connect(self.drive.flange, link.ctrR2)
        else:
            self.drive = Preset(kind="speed", translational=True, om=SPEED,
                                phi0=float(link.parameter_value("xS0")), use_support=on_wheel)
            self.connect(self.drive.flange, link.ctrT2)
            if on_wheel:
                self.connect(self.drive.support, link.ctrT1)

    def _end(self, band, j, k, frame, gam, winch=None):
        """End k (1, 2) of ``band`` at joint j: a pin or a locked disc on the
        frame ``frame`` = (connector, signal prefix), None for the ground; with
        ``winch`` (a :class:`Preset`) the disc is not locked but turned by it
        relative to its frame, winding the band.
        Returns (the prefix of the frame the band pulls at: the pin's frame,
        None for a ground pin, or the disc's ``discJ.ctrK1``; that point at
        t0)."""
        p = self._pts[j]
        conn, name = frame or (None, None)
        if self._letters[j - 1] == "D":
            if conn is None:
                setattr(self, "pin%d" % j, Fixed(r=p))
                conn = getattr(self, "pin%d" % j).frame
            self.connect(getattr(band, "ctr2D%d" % k), conn)
            return name, p
        disc = _disc(p)
        setattr(self, "disc%d" % j, disc)
        if winch is None:                   # the disc is locked to its housing
            self.connect(disc.ctrR1, disc.ctrR2)
        else:                               # turned relative to its housing (Tab. 4.14)
            self.connect(winch.flange, disc.ctrR2)
            self.connect(winch.support, disc.ctrR1)
        if conn is not None:
            self.connect(conn, disc.ctr2D1)
        connect_band(self, band, k, disc, 1)
        side = 1.0 if k == 1 else -1.0        # contact at C +- rho perp(e) (tangent())
        q = (p[0] - side * R_DISC * math.sin(gam), p[1] + side * R_DISC * math.cos(gam))
        return "disc%d.ctrK1" % j, q

    def _band(self, b, tips):
        """The band between J_b (end 1) and J_b+1 (end 2), and the load."""
        (ja, jb), gam, length = self._ends, self._gam, self._length
        self.band = Band(gamma=start(gam), l=start(length), l_x=start(length),
                         l_x0=start(length))
        holders = {ja: tips.get(ja), jb: tips.get(jb)}
        frames = {j: (self._out(h), h + ".ctr2D2") if h else None for j, h in holders.items()}
        pts = {j: self._end(self.band, j, k, frames[j], gam) for k, j in ((1, ja), (2, jb))}
        k = 1 if holders[ja] == self.load_link else 2
        j = ja if k == 1 else jb
        self.load_end, (self.load_point, q) = k, pts[j]
        self.drive_end = 3 - k if holders[(jb, ja)[k - 1]] == self.drive_link else None
        self.drive_point = pts[(jb, ja)[k - 1]][0] if self.drive_end else None
        u = (math.cos(gam), math.sin(gam)) if k == 1 else (-math.cos(gam), -math.sin(gam))
        self._load(q, u)

    def _load(self, q, u):
        """Constant load on the loaded link, sized for F_BAND at t0."""
        link = getattr(self, self.load_link)
        if isinstance(link, DAN):
            p = self._pivots[self.load_link]
            arm = _cross((q[0] - p[0], q[1] - p[1]), u)
            self.load_kind, self.load_value = "torque", -F_BAND * arm
        else:
            e = self._angles[self.load_link]
            along = u[0] * math.cos(e) + u[1] * math.sin(e)
            self.load_kind, self.load_value = "force", -F_BAND * along
        self._apply_load(link)

    def _apply_load(self, link):
        """The constant load ``load_value`` on ``link``: a torque, or a force
        between slider and guide."""
        if self.load_kind == "torque":
            self.load = TorqueSource(tau=self.load_value)
            self.connect(self.load.flange, link.ctrR2)
            return
        self.load = ForceSource(f=self.load_value)
        self.connect(self.load.flange, link.ctrT2)
        self.support = ForceSource(f=-self.load_value)     # the reaction on the guide
        self.connect(self.support.flange, link.ctrT1)

    def _build_band_frame(self, letters):
        """The band as the frame (code ``"BDDD~"``): a taut straight band along
        y = 0 in the ground; a D end is a pivot on it, a B end a disc of the
        neighbouring link that rolls on it without slip
        (:class:`~acausal2d.library.planar.IdealRolling`, bilateral).  The
        chain of the three rigid links starts at the pivot (driven) and ends
        at the rolling disc (loaded); with two discs, the first disc's link
        rolls freely and the coupler is driven (a slider relative to its
        guide on that link, BSSB~)."""
        self.outputs = ["drive.tau", "roll.x"]
        self._ends, self._gam = (4, 1), 0.0        # a slider with the disc: guide at 0.5 rad to it
        self._pts[3] = BAND_FRAME_J3
        for j in (1, 4):
            if letters[j - 1] == "B":
                self._pts[j] = (self._pts[j][0], R_DISC)
        if letters[3] == "D":
            chain, parent = [(4, 3), (3, 2), (2, 1)], None
        else:
            chain, parent = [(1, 2), (2, 3), (3, 4)], None
            if letters[0] == "B":
                self.wheel = IdealRolling(R=R_DISC, x0=self._pts[1][0], phi=start(0.0))
                self._angles["wheel"], self._tip_at["wheel"] = 0.0, self._pts[1]
                chain, parent = chain[1:], "wheel"
        for jp, jc in chain:
            parent = self._link(letters[jp - 1], jp, jc, parent)
        first = self._link_name(chain[0])
        self.drive_link, self.load_link = first, parent
        self._drive(first, on_wheel=hasattr(self, "wheel"))
        j = chain[-1][1]
        self.roll = IdealRolling(R=R_DISC, x0=self._pts[j][0] + R_DISC * self._angles[parent],
                                 phi=start(0.0))
        self.connect(self._out(parent), self.roll.frame_a)
        self.load_point, self.load_end, self.drive_point, self.drive_end = "roll", None, None, None
        link = getattr(self, parent)
        self.load_kind = "torque" if isinstance(link, DAN) else "force"
        self.load_value = F_BAND * (0.1 if self.load_kind == "torque" else 1.0)
        self._apply_load(link)
