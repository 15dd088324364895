"""The two outlook examples of Schnabel and Gössner's talk ("Ausblick": Synthese_Poldreieck.html
and Drehzahlplan.html)
as node models built from the four-node constructions
(:mod:`acausal2d.library.nodes.constructions`).  Schnabel and Gössner's talk gives no
dimensions for either; the ones below are chosen and listed in the class
docstrings.  Coordinates in mm.

* :class:`PoleTriangleSynthesis` - three-position synthesis: A0 and B0 as
  the circumcentres of A1A2A3 and B1B2B3 from perpendicular bisectors (ref
  constraints of ratio 1/2 and offset pi/2), and the pole triangle P12,
  P13, P23 (each pole the intersection of the bisectors of A_iA_j and
  B_iB_j).  The third position turns about A3, so B0, P13 and P23 move.
* :class:`SpeedDiagram` - Kutzbach's speed diagram of a planetary gear:
  radii upwards, circumferential speeds as horizontal lengths; each
  member's speed is read as a length on the line y = h (Willis'
  equation).

``acausal2d simulate models/talk_synthesis.py --model SpeedDiagram``."""
import math

import numpy as np

from acausal2d.library.nodes import NodeModel, drive, ref
from acausal2d.library.nodes.constructions import perpendicular, perpendicular_bisector

TURN = 2 * math.pi
_RUN = {"stop_time": 1.0, "intervals": 200, "rtol": 1e-8}


def _coupler(a, length, angle_deg):
    """End B of a coupler of ``length`` at ``angle_deg`` from A = ``a``."""
    w = math.radians(angle_deg)
    return a[0] + length * math.cos(w), a[1] + length * math.sin(w)


class PoleTriangleSynthesis(NodeModel):
    """Three positions of a coupler AB (length 100 mm): A1 (0,0) at 0 deg,
    A2 (40,50) at -10 deg, A3 (110,60) at -30 deg + 15 deg sin(2 pi t) (B3
    swings about A3; the fixed pivots start near A0 (87,-28), B0 (151,-21)).  Built: the midpoints and perpendicular bisectors of
    A1A2, A1A3, B1B2, B1B3 meeting in A0 and B0 (the fixed pivots of a
    four-bar guiding the coupler through the three positions), and the
    poles P12, P13, P23 (bisectors of A_iA_j and B_iB_j)."""
    length_unit = 1e-3
    experiment = dict(_RUN)
    outputs = ["B0.x", "B0.y", "P13.x", "P13.y"]
    figures = [{"signals": [["A0.x", "A0.y", "B0.x", "B0.y"]], "x": "A3B3.w",
                "title": "fixed pivots over the angle of position 3", "name": "pivots"},
               {"signals": [["P12.x", "P13.x", "P23.x"], ["P12.y", "P13.y", "P23.y"]],
                "x": "A3B3.w", "title": "pole triangle", "name": "pole_triangle"}]

    def __init__(self, **kw):
        super().__init__(**kw)
        pos = {"1": ((0.0, 0.0), 0.0), "2": ((40.0, 50.0), -10.0), "3": ((110.0, 60.0), -30.0)}
        for i, (a, ang) in pos.items():
            self.node("A" + i, *a, base=True)
            self.node("B" + i, *_coupler(a, 100.0, ang), base=i != "3")
            if i != "3":
                self.line("A" + i, "B" + i)
        w3 = math.radians(-30.0)
        self.n2("A3B3", "A3", "B3", len="const",
                ang=drive(lambda t: w3 + math.radians(15.0) * _sin(TURN * t)))
        guesses = {"A0": (90, -30), "B0": (150, -20), "P12": (310, -200), "P13": (170, -180),
                   "P23": (100, -140)}
        for nid, (x, y) in guesses.items():
            self.node(nid, x, y, m=0)
        self._bisectors()

    def _bisectors(self):
        """Segments A_iA_j, B_iB_j, their midpoints and bisectors to the
        pivots (pairs 12, 13) and to the poles (pairs 12, 13, 23)."""
        for pt in ("A", "B"):
            for i, j in (("1", "2"), ("1", "3"), ("2", "3")):
                seg = pt + i + pt + j
                self.n2(seg, pt + i, pt + j, draw=None)
                mid = "M" + seg
                (xi, yi), (xj, yj) = self._start(pt + i), self._start(pt + j)
                u = 2 * self.length_unit
                self.node(mid, (xi + xj) / u, (yi + yj) / u, m=0)
                perpendicular_bisector(self, "b" + seg, seg, mid, "P" + i + j)
                if i == "1":
                    perpendicular(self, "c" + seg, mid, pt + "0", seg)


    def write_outputs(self, res, folder):
        """The synthesis drawn at t = 0 (``pole_triangle_synthesis.png``):
        the three coupler positions, the circles of A and B about A0 and B0,
        the guiding four-bar A0 A1 B1 B0 and the pole triangle."""
        import os

        from acausal2d.visual.plotting import save_figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        pt = {n: (res[n + ".x"][0] * 1e3, res[n + ".y"][0] * 1e3) for n in
              ("A1", "A2", "A3", "B1", "B2", "B3", "A0", "B0", "P12", "P13", "P23")}
        fig = Figure(figsize=(7, 6))
        FigureCanvasAgg(fig)
        ax = fig.subplots()
        for i, c in zip("123", ("#1f77b4", "#ff7f0e", "#2ca02c")):
            ax.plot(*zip(pt["A" + i], pt["B" + i]), "-o", color=c, lw=3, label="position " + i)
        for centre, ends in (("A0", "A"), ("B0", "B")):
            r = np.hypot(*np.subtract(pt[ends + "1"], pt[centre]))
            w = np.linspace(0, 2 * np.pi, 200)
            ax.plot(pt[centre][0] + r * np.cos(w), pt[centre][1] + r * np.sin(w), ":",
                    color="gray", lw=0.8)
        ax.plot(*zip(pt["A0"], pt["A1"], pt["B1"], pt["B0"]), "--", color="k", lw=1,
                label="four-bar A0 A1 B1 B0")
        tri = [pt["P12"], pt["P13"], pt["P23"], pt["P12"]]
        ax.plot(*zip(*tri), "-", color="#16a085", lw=1.5, label="pole triangle")
        for n in ("A0", "B0", "P12", "P13", "P23"):
            ax.annotate(n, pt[n], textcoords="offset points", xytext=(5, 5))
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.legend(fontsize=8, loc="best")
        ax.set_title("PoleTriangleSynthesis: three-position synthesis at t = 0")
        return [save_figure(fig, os.path.join(folder, "pole_triangle_synthesis.png"))]


def _sin(x):
    import casadi
    return casadi.sin(x)


class SpeedDiagram(NodeModel):
    """Kutzbach speed diagram of a simple planetary gear: sun radius
    r1 = 30, planet r2 = 15, ring r3 = r1 + 2 r2 = 60, reading line
    y = h = 100 (mm).  The speeds of the sun and the ring are given as
    lengths n_s = 40 + 30 sin(2 pi t) and n_r = -20 on the reading line
    (n = omega h per unit of the drawing scale).  Drawn: the sun's speed
    line O -> V_S (V_S at height r1: the circumferential speed at the mesh),
    the ring's O -> V_R (at r3), the planet's V_S -> V_R with the carrier
    point V_C at r1 + r2, the carrier's line O -> V_C, and the parallel
    to the planet's line through O.  Read on y = h: the carrier's speed
    ``Nc.x`` and the planet's (absolute) speed ``Np.x``; Willis:
    (n_s - n_c) / (n_r - n_c) = -r3 / r1."""
    length_unit = 1e-3
    experiment = dict(_RUN)
    r1, r2, h = 30.0, 15.0, 100.0
    outputs = ["Ns.x", "Nr.x", "Nc.x", "Np.x"]
    figures = [{"signals": [["Ns.x", "Nr.x", "Nc.x", "Np.x"]], "x": "Ns.x",
                "title": "speeds read as lengths on y = h", "name": "speeds"}]

    def __init__(self, **kw):
        super().__init__(**kw)
        r1, r3, h = self.r1, self.r1 + 2 * self.r2, self.h
        for nid, y in (("O", 0), ("Y1", r1), ("Y2", r1 + self.r2), ("Y3", r3), ("H", h)):
            self.node(nid, -80 if nid[0] == "Y" else 0, y, base=True)
        for nid, x, y in (("Ns", 40, h), ("Nr", -20, h), ("Vs", 12, r1), ("Vr", -12, r3),
                          ("Vc", 0, r1 + self.r2), ("Nc", 0, h), ("Np", -50, h)):
            self.node(nid, x, y, m=0)
        self.n2("HNs", "H", "Ns", len=drive(lambda t: 40 + 30 * _sin(TURN * t)),
                ang="const", draw=None)
        self.n2("HNr", "H", "Nr", len="const", ang="const", draw=None)
        self.n2("ONs", "O", "Ns", draw="bar")
        self.n2("ONr", "O", "Nr", draw="bar")
        self._speed_point("Vs", "ONs", "Y1")
        self._speed_point("Vr", "ONr", "Y3")
        self.n2("VsVr", "Vs", "Vr", draw="bar")
        self._speed_point("Vc", "VsVr", "Y2", start="Vs")
        self.n2("OVc", "O", "Vc", draw="bar")
        self._speed_point("Nc", "OVc", "H")
        self._speed_point("Np", "VsVr", "H")

    def _speed_point(self, nid, line, level, start="O"):
        """Node ``nid`` on the line through ``start`` parallel to ``line``
        and on the horizontal through the base node ``level``."""
        self.n2(start + "_" + nid, start, nid, ang=ref(line), draw="bar")
        self.n2(level + nid, level, nid, ang="const", draw=None)
