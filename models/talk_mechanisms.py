"""The mechanisms of Schnabel and Gössner's talk "Lightweight prototypal mechanism simulation on
the web" as node/constraint models, with their coordinates transcribed from
Schnabel and Gössner's example files (github.com/Pasquale19/Beispiele_GT2022).

Coordinates are the files' drawing units, read as millimetres
(``length_unit = 1e-3``); y points up.  Schnabel and Gössner's talk moves its mechanisms by
dragging a node or by adding pi/180 to the crank angle every tick; here the
crank turns at 1 turn/s (``speed(2 pi)``) unless a class says otherwise,
so ``stop_time = 1`` is one crank revolution.  Choose a model with
``--model``, e.g. ``acausal2d check models/talk_mechanisms.py --model
DeepDrawingPress``.

Counts of Schnabel and Gössner's eq. 1/2 (``acausal2d check``): Schnabel and Gössner's talk states them for
its two introductory examples (4 nodes, 1 base, C1 = 3, C2 = 1: the
slider-crank; 4 nodes, 2 base, C1 = 3: the crank-rocker; F = 1, m = 1), the
needle-bar drive (N = 10, N_base = 4, C1 = 11, C2 = 0, F = 1, m = 5), the
deep-drawing press (16, 5, 21, 0, F = 1, m = 10) and the walking mechanism
(14, 2, 1, 11, F = 1, m = 0); the others follow from the listed
constraints."""
import math

import casadi

from acausal2d.library.nodes import NodeModel, drive, ref, speed

TURN = 2 * math.pi          # rad/s: one crank revolution per second
_RUN = {"stop_time": 1.0, "intervals": 360, "rtol": 1e-8}


class _Talk(NodeModel):
    """Common settings: coordinates in mm, no impressed forces (Schnabel and Gössner's
    Q = 0), 360 output intervals per crank turn."""
    length_unit = 1e-3
    experiment = dict(_RUN)

    def nodes(self, spec):
        """Add nodes from {id: (x, y, m)} ('base' as m for fixed nodes)."""
        for nid, (x, y, m) in spec.items():
            if m == "base":
                self.node(nid, x, y, base=True)
            else:
                self.node(nid, x, y, m=m)

    def bars(self, *pairs):
        """len='const' constraints named after their nodes ("AB")."""
        for pair in pairs:
            a, b = pair.split("-")
            self.n2(a + b, a, b, len="const")


class IntroCrankRocker(_Talk):
    """Introductory crank-rocker (talk "Kurbelschwinge", slide 4): A0 (0,0)
    and B0 (200,10) fixed, A (0,50) with m = 2, B (180,110); the three
    bars of cstr().n2(...).  Schnabel and Gössner's talk drags A; here the crank A0A turns.
    Talk eq. 1/2: 4 nodes, 2 base, C1 = 3: F = 1, m = 1."""
    outputs = ["B.x", "B.y", "B0B.w"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "A": (0, 50, 2), "B": (180, 110, 1),
                    "B0": (200, 10, "base")})
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.bars("A-B", "B0-B")


class FourBar(_Talk):
    """Four-bar "Viergelenk" (viergelenk.html, e = 60): A0 (0,0), B0 (3e,-e)
    fixed, A (0,e) with m = 10, B (2e,e); crank A0A, coupler AB, rocker
    B0B.  Used by the animation page's drag test."""
    outputs = ["B.x", "B.y", "B0B.w"]

    def __init__(self, e=60.0, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "B0": (3 * e, -e, "base"), "A": (0, e, 10),
                    "B": (2 * e, e, 1)})
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.bars("A-B", "B0-B")


class EccentricSliderCrank(_Talk):
    """Eccentric slider-crank "Schubkurbel" (schubkurbel-exzentrisch.html,
    e = 60): A0 (0,0) fixed, the helper node AB0 (0,-e) carrying the guide,
    A (0,e) with m = 10, B (3e,-e).  Crank A0A, rod AB, guide AB0->B
    (angle held: B slides on the line y = -e).  Schnabel and Gössner's count example
    (4 nodes, 1 base, C1 = 3, C2 = 1: F = 1, m = 1) holds AB0 by length and
    angle from A0 (a C2); the example file holds only its length, which
    leaves the helper free to swing (F = 2 by eq. 1), so Schnabel and Gössner's
    version is used."""
    outputs = ["B.x", "AB0B.r"]

    def __init__(self, e=60.0, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "AB0": (0, -e, 1), "A": (0, e, 10),
                    "B": (3 * e, -e, 1)})
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("AB", "A", "B", len="const")
        self.n2("AB0B", "AB0", "B", ang="const")
        self.n2("A0AB0", "A0", "AB0", len="const", ang="const")


class ScotchYoke(_Talk):
    """"Kreuzschubkurbel" (Kreuzschubkurbel.html, e = 60): A slides on the
    line through A0 (-1.5e, 1.5e) towards A02 (1.5e, -1.5e), B on the line
    through B0 (1.5e, 1.5e) towards B02 (-1.5e, -1.5e); A (-e, e) with
    m = 10, B (0, 0), bar AB.  A02 and B02 only draw the guides (no
    constraint uses them, so they are no nodes here).  Schnabel and Gössner's talk drags A;
    here the bar AB turns at constant speed (its angle driven), the two
    sliders oscillating on their perpendicular guides (an elliptic
    trammel).  Eq. 1/2: 4 nodes, 2 base, C1 = 3: F = 1, m = 1."""
    outputs = ["A0A.r", "B0B.r"]

    def __init__(self, e=60.0, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (-1.5 * e, 1.5 * e, "base"), "B0": (1.5 * e, 1.5 * e, "base"),
                    "A": (-e, e, 10), "B": (0, 0, 1)})
        self.n2("A0A", "A0", "A", ang="const")
        self.n2("AB", "A", "B", len="const", ang=speed(TURN))
        self.n2("B0B", "B0", "B", ang="const")


class SlottedSlider(_Talk):
    """"Schubschleife" (Schubschleife.html, e = 60), completed to a
    mechanism: the file is a draft whose free nodes leave F = 3 (its
    constraint B0B is commented out and B0 is no base node).  Here, with
    the file's coordinates: A0 (0,0) and B0 (0, 1.5e) fixed; crank A0A
    with the rigid arm A-A2 (n3 A0-A-A2 const, |AA2| const); B (1.5e,
    1.5e) on the slotted line through A0 at the fixed angle to the crank
    (n3 A0-A-B const) and on the horizontal guide through B0 (B0B angle
    held); the bar B2-B rides with B (length and angle held).  The crank
    swings by +-40 deg about its start (the slot turns horizontal at
    +-45 deg).  Eq. 1/2: N = 6, N_base = 2, C1 = 5, C2 = 1: F = 1, m = 2."""
    outputs = ["B.x", "B0B.r"]
    experiment = {"stop_time": 1.0, "intervals": 360, "rtol": 1e-8}

    def __init__(self, e=60.0, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "B0": (0, 1.5 * e, "base"), "A": (40, -40, 1),
                    "A2": (40 + e, -40 + e + 1.5 * e, 1), "B": (1.5 * e, 1.5 * e, 10),
                    "B2": (-e, 1.5 * e, 10)})
        w0 = math.atan2(-40.0, 40.0)
        self.n2("A0A", "A0", "A", len="const",
                ang=drive(lambda t: w0 + math.radians(40) * _sin(TURN * t)))
        self.n2("AA2", "A", "A2", len="const")
        self.n3("A0AA2", "A0", "A", "A2")
        self.n3("A0AB", "A0", "A", "B")
        self.n2("B0B", "B0", "B", ang="const")
        self.n2("B2B", "B2", "B", len="const", ang="const")



class StephensonII(_Talk):
    """Stephenson II six-bar (stephenson-2-drag.html; talk: "keine
    analytische Lösung", itr 1/1): A0 (0,0), B0 (200,0) fixed, A (0,100)
    with m = 10, B (180,140), C (60,100), D (100,240), E (260,180); bars
    A0A, AC, AD, CD, CB, DE, BE, B0B, B0E.  It contains a class-3 Assur
    group (the ternary link CD-A... closes through B-E), so there is no
    closed-form position solution; the DAE and the position correction
    solve it as any other.  Schnabel and Gössner's talk drags A; here the crank A0A swings
    by +-60 deg about its start (a full turn locks).
    Eq. 1/2: N = 7, N_base = 2, C1 = 9: F = 1, m = 4."""
    outputs = ["E.x", "E.y", "B.x", "B.y"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "B0": (200, 0, "base"), "A": (0, 100, 10),
                    "B": (180, 140, 1), "C": (60, 100, 1), "D": (100, 240, 1),
                    "E": (260, 180, 1)})
        self.n2("A0A", "A0", "A", len="const",
                ang=drive(lambda t: math.pi / 2 + math.radians(60) * _sin(TURN * t)))
        self.bars("A-C", "A-D", "C-D", "C-B", "D-E", "B-E", "B0-B", "B0-E")


class Bobillier(_Talk):
    """Bobillier's construction (bobillier-drag.html, talk: itr 1/60): the
    four-bar A0 (0,0), B0 (160,0) fixed, A (0,40) with m = 10, B (100,100),
    and the auxiliary points (m = 0.1 each) P (-60,200): pole, the meet of
    the lines A0A and B0B; I (-60,0): the meet of AB and A0B0; K (150,100)
    on AB with PK horizontal (the file's ang 0); Bw on B0B and Aw on A0A
    with KBw and KAw parallel to IP (getter angles: ref('IP')).  The
    three-node constraints with ang 0 hold collinearity.  The crank swings
    by +-30 deg about its start (P and I run off to infinity where the
    lines become parallel).  Eq. 1/2: N = 9, N_base = 2, C1 = 13 (3 bars,
    7 n3, PK, KBw, KAw; IP is free): F = 1, m = 6."""
    outputs = ["P.x", "P.y", "I.x", "K.x"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "B0": (160, 0, "base"), "A": (0, 40, 10),
                    "B": (100, 100, 1), "P": (-60, 200, 0.1), "I": (-60, 0, 0.1),
                    "K": (150, 100, 0.1), "Bw": (100, 100, 0.1), "Aw": (0, 40, 0.1)})
        self.n2("A0A", "A0", "A", len="const",
                ang=drive(lambda t: math.pi / 2 + math.radians(30) * _sin(TURN * t)))
        self.bars("A-B", "B0-B")
        self.n3("ABI", "B", "A", "I", 0.0)
        self.n3("A0B0I", "B0", "A0", "I", 0.0)
        self.n3("A0AP", "A0", "A", "P", 0.0)
        self.n3("B0BP", "B0", "B", "P", 0.0)
        self.n2("IP", "I", "P", draw="bar")
        self.n2("PK", "P", "K", ang=0.0, draw="bar")
        self.n3("ABK", "A", "B", "K", 0.0)
        self.n2("KBw", "K", "Bw", ang=ref("IP"), draw="bar")
        self.n3("B0BBw", "B0", "B", "Bw", 0.0)
        self.n2("KAw", "K", "Aw", ang=ref("IP"), draw="bar")
        self.n3("A0AAw", "A0", "A", "Aw", 0.0)


class CouplerCurve(_Talk):
    """Crank-rocker with a coupler point (Kurbelschwinge_Koppelkurve.html):
    A0 (0,0), B0 (200,40) fixed, A (0,50), B (120,140), coupler point K
    (60,140) rigid with AB (bars AK, KB); the crank A0A is driven (the
    file adds pi/180 to its angle each tick).  The animation traces K.
    Eq. 1/2: N = 5, N_base = 2, C1 = 5: F = 1, m = 2."""
    outputs = ["K.x", "K.y"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.nodes({"A0": (0, 0, "base"), "A": (0, 50, 1), "B": (120, 140, 1),
                    "B0": (200, 40, "base"), "K": (60, 140, 1)})
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.bars("A-B", "B0-B", "A-K", "K-B")


def _simtrf(a, b, lam, mu):
    """v2.js simtrf: a + lam (b - a) + mu (b - a)~ (similarity transform)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    return a[0] + lam * dx - mu * dy, a[1] + lam * dy + mu * dx


def _mirror(p, a, b):
    """p mirrored in the line through a and b."""
    ux, uy = b[0] - a[0], b[1] - a[1]
    s = ((p[0] - a[0]) * ux + (p[1] - a[1]) * uy) / (ux * ux + uy * uy)
    fx, fy = a[0] + s * ux, a[1] + s * uy
    return 2 * fx - p[0], 2 * fy - p[1]


class _CouplerPair(_Talk):
    """Both assemblies of one four-bar on a common crank: A0, B0 fixed, the
    crank A0A (m = 2) driven, the coupler point K = A + tan(beta) AB +
    AB~ (the files' simtrf(mu, lam) with mu = tan beta, lam = 1), and the
    second assembly B2 (B mirrored in the line A B0) with its point K2.
    Eq. 1/2: N = 7, N_base = 2, C1 = 9: F = 1, m = 4."""
    outputs = ["K.x", "K.y", "K2.x", "K2.y"]
    crank_pin, coupler_pin, beta = (0.0, 0.0), (0.0, 0.0), 0.0

    def crank(self):
        """The crank drive: a full turn per second."""
        return speed(TURN)

    def __init__(self, **kw):
        super().__init__(**kw)
        A0, B0, A, B = (0.0, 0.0), (200.0, 0.0), self.crank_pin, self.coupler_pin
        B2 = _mirror(B, A, B0)
        mu = math.tan(math.radians(self.beta))
        K, K2 = _simtrf(A, B, mu, 1.0), _simtrf(A, B2, mu, 1.0)
        self.nodes({"A0": (*A0, "base"), "A": (*A, 2), "B": (*B, 1), "B0": (*B0, "base"),
                    "K": (*K, 1), "B2": (*B2, 1), "K2": (*K2, 1)})
        self.n2("A0A", "A0", "A", len="const", ang=self.crank())
        self.bars("A-B", "B0-B", "K-A", "K-B", "A-B2", "B0-B2", "A-K2", "B2-K2")


class OnePartCouplerCurve(_CouplerPair):
    """One-part coupler curve (Koppelkurve_einteilig.html): A (-17.64,
    76.47), B (118.3, 61.76), beta = 51 deg.  The four-bar is no
    crank-rocker (|A0A| + |A0B0| > |AB| + |B0B|): the crank rocks between
    its limit positions at +-110.5 deg, and the two assemblies' points K
    and K2 together run on one closed curve.  Here the crank angle is
    103 deg cos(2 pi t) (its start, inside the limits)."""
    crank_pin, coupler_pin, beta = (-17.64, 76.47), (118.3, 61.76), 51.0

    def crank(self):
        """The crank drive: 103 deg cos(2 pi t), inside the limit positions."""
        w0 = math.atan2(76.47, -17.64)
        return drive(lambda t: w0 * _cos(TURN * t))


class TwoPartCouplerCurve(_CouplerPair):
    """Two-part coupler curve (Koppelkurve_zweiteilig.html): A (75, 0),
    B (165, 131.42), B2 = (B.x, -B.y), beta = 48 deg; a crank-rocker, so
    the crank turns fully and the two assemblies' points K and K2 run on
    the two separate parts of the curve."""
    crank_pin, coupler_pin, beta = (75.0, 0.0), (165.0, 131.42), 48.0



NEEDLE_BAR = {"A0": (0.0, 0.0, "base"), "A": (28.743585, 8.591085, 2),
              "B0": (188.4, -51.75, "base"), "B": (182.76258, 54.66318, 1),
              "C": (49.460895, 155.66535, 1), "D": (92.242725, 68.847375, 1),
              "D0": (158.7, 216.0, "base"), "E": (4.357155, 208.81428, 1),
              "F": (4.64784, 419.82531, 1), "F0": (4.64784, 375.0, "base"),
              "G": (-33.0, 542.805, 1)}
"""Nodes of the needle-bar drive (Textilmaschine.html): (x, y, m or 'base')."""


class NeedleBarDrive(_Talk):
    """Needle-bar drive of a textile machine (Textilmaschine.html, talk:
    8 links, N = 10, N_base = 4 with G not counted, C1 = 11, C2 = 0,
    F = 1, m = 5).  Crank A0A (length held, angle driven: the file's
    +pi/180 per tick), the four-bar A-B-B0 with the coupler point C
    (AB, B0B, AC, BC), the rocker D0-D-E driven by DC (DC, D0D, D0E, DE),
    the connecting rod EF and the needle bar F sliding on the vertical
    line through F0 (F0F angle held); the needle point G is rigid with F
    (FG length and angle held) and not counted, as in Schnabel and Gössner's talk.  Output:
    the needle-bar travel F0F.r over one crank turn."""
    outputs = ["F0F.r", "G.y"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.nodes(dict((k, v) for k, v in NEEDLE_BAR.items() if k != "G"))
        self.node("G", *NEEDLE_BAR["G"][:2], m=1, counted=False)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.bars("A-B", "B0-B", "A-C", "B-C", "D-C", "D0-D", "D0-E", "D-E", "E-F")
        self.n2("F0F", "F0", "F", ang="const")
        self.n2("FG", "F", "G", len="const", ang="const")


PRESS_BASE = {"A0": (0.0, 600.0), "B0": (330.0, 945.0), "D0": (450.0, 426.0),
              "H0": (20.727, 400.0), "K0": (30.138, 100.0)}
"""Fixed nodes of the deep-drawing press (Erfurt-Getriebe_chart.html)."""
PRESS_MOVING = {"A": (63.98787, 633.00837, 10), "B": (465.19434, 839.9721, 1),
                "C": (519.22338, 723.92193, 1), "D": (408.22914, 506.39622, 1),
                "E": (398.41071, 600.65061, 1), "F": (57.16677, 503.10723, 1),
                "G": (175.00254, 583.2744, 1), "H": (20.727, 349.0, 1),
                "I": (325.68372, 699.35976, 1), "J": (249.10329, 575.64357, 1),
                "K": (30.138, 32.68239, 1)}
"""Moving nodes of the press: (x, y, m)."""
PRESS_BARS = ("A-B", "B0-B", "B0-C", "B-C", "C-D", "D0-D", "D0-E", "D-E", "D0-I", "E-I",
              "I-J", "A-J", "E-F", "A0-F", "A0-G", "F-G", "G-H", "J-K")
"""The 18 bars of the press (len held)."""


class DeepDrawingPress(_Talk):
    """14-link deep-drawing crank press (Charts/Erfurt-Getriebe_chart.html;
    talk "Tiefziehkurbelpresse": N = 16, N_base = 5, C1 = 21, C2 = 0,
    F = 1, m = 10; Schnabel and Gössner's talk reports itr(max/cur) = 494/328 and 848/582
    with cstr.js).  Crank A0A (length held, angle driven, the file adds
    pi/360 per tick), 18 bars, and the two rams H and K sliding on
    vertical lines through H0 and K0 (H0H, K0K angle held).  Outputs: the
    ram positions H0H.r and K0K.r over the crank angle (the file charts
    H0H.r - 50 and K0K.r - 50).

    ``lengths="numbers"`` gives the bar lengths as numbers (computed from
    the coordinates) instead of 'const', so that the nodes may start from
    rough coordinates (``rough=``: a dict {id: (x, y)} replacing the
    moving nodes' coordinates) which the node assembly (talk eq. 3-16)
    turns into the closed position; a dict {constraint id: length in mm}
    gives those lengths and the computed ones elsewhere."""
    outputs = ["H0H.r", "K0K.r"]
    lentol, itrmax = 0.02, 1024            # the file's cstr.lentol, cstr.itrmax

    def __init__(self, lengths="const", rough=None, **kw):
        super().__init__(**kw)
        exact = dict(PRESS_BASE, **{k: v[:2] for k, v in PRESS_MOVING.items()})
        for nid, (x, y) in PRESS_BASE.items():
            self.node(nid, x, y, base=True)
        for nid, (x, y, m) in PRESS_MOVING.items():
            x, y = (rough or {}).get(nid, (x, y))
            self.node(nid, x, y, m=m)
        (ax, ay), (bx, by) = exact["A0"], exact["A"]
        w0 = math.atan2(by - ay, bx - ax)
        self.n2("A0A", "A0", "A", len=self._length(exact, "A0", "A", lengths),
                ang=speed(TURN, start=w0))
        for pair in PRESS_BARS:
            a, b = pair.split("-")
            self.n2(a + b, a, b, len=self._length(exact, a, b, lengths))
        self.n2("H0H", "H0", "H", ang=-math.pi / 2)
        self.n2("K0K", "K0", "K", ang=-math.pi / 2)

    @staticmethod
    def _length(exact, a, b, lengths):
        if lengths == "const":
            return "const"
        if isinstance(lengths, dict) and a + b in lengths:
            return lengths[a + b]
        (xa, ya), (xb, yb) = exact[a], exact[b]
        return math.hypot(xb - xa, yb - ya)


class WalkingMechanism(_Talk):
    """Walking mechanism "Schreitkrabbler" (Schreitkrabbler2_final.html;
    talk: N = 14, N_base = 2, C1 = 1, C2 = 11, F = 1, m = 0, itr 1/1):
    e = 50, cranks of radius R = e about A0 (0,0) and B0 (9e, 0), each
    with three pins at 0, 120, -120 deg (m = 8); A01 has its length held
    and its angle driven (the file drags A1), A02 and A03 follow A01's
    angle +-120 deg (cstr.js ang.from), B01..B03 follow A01..A03 (the 1:1
    coupling of both cranks); legs C_i, D_i (m = 1) hang at l4 = 2.5 e
    below the pins (length and angle -pi/2 held: the file's "magnets").
    The coupler bars A_i-B_i are drawn, not constrained (the coupling keeps
    them parallel)."""
    outputs = ["C1.x", "C1.y", "D1.y"]

    def __init__(self, e=50.0, **kw):
        super().__init__(**kw)
        R, l3, l4 = e, 9 * e, 2.5 * e
        self.node("A0", 0, 0, base=True)
        self.node("B0", l3, 0, base=True)
        for i, a in ((1, 0.0), (2, 2 * math.pi / 3), (3, -2 * math.pi / 3)):
            for hub, x0 in (("A", 0.0), ("B", l3)):
                self.node("%s%d" % (hub, i), x0 + R * math.cos(a), R * math.sin(a), m=8)
        for i in (1, 2, 3):
            for hub, leg in (("A", "C"), ("B", "D")):
                p = self._nodes["%s%d" % (hub, i)]
                self.node("%s%d" % (leg, i), p.parameter_value("x0") / self.length_unit,
                          p.parameter_value("y0") / self.length_unit - l4, m=1)
        self.n2("A01", "A0", "A1", len=R, ang=speed(TURN))
        self.n2("A02", "A0", "A2", len=R, ang=ref("A01", offset=2 * math.pi / 3))
        self.n2("A03", "A0", "A3", len=R, ang=ref("A01", offset=-2 * math.pi / 3))
        for i in (1, 2, 3):
            self.n2("B0%d" % i, "B0", "B%d" % i, len=R, ang=ref("A0%d" % i))
        for i in (1, 2, 3):
            self.n2("A%dC%d" % (i, i), "A%d" % i, "C%d" % i, len=l4, ang=-math.pi / 2)
            self.n2("B%dD%d" % (i, i), "B%d" % i, "D%d" % i, len=l4, ang=-math.pi / 2)
            self.line("A%d" % i, "B%d" % i)


def _sin(x):
    return casadi.sin(x)


def _cos(x):
    return casadi.cos(x)
