"""Three-rope tilting-mast cable crane (Ebert 2015, ch. 8.1, Bild 8.2-8.5).

Layout of the dissertation (Bild 8.2, 8.3): horizontal span 50 m from mast to
mast, masts 10 m high, slope 15 degrees, mast pulleys 200 mm diameter,
rope drums 1000 mm diameter; 9 pulleys, 2 drums and 12 rope sections; the
drums stand in the valley at the left mast.

- Skyline (Tragseil), 4 sections: anchored in the ground left of the left
  mast (G), over the upper pulley S of the left mast, under the two running
  wheels W1, W2 of the carriage, fastened at the top of the right mast (T).
  Its length is constant (no tensioning drum, as in the dissertation).
- Load rope (Lastseil), 6 sections: drum D1 - pulley ML on the left mast -
  pulley MR on the right mast - three carriage pulleys A, B, C - hook.
- Haul-back rope (Hilfsseil), 2 sections: drum D2 - pulley MH on the left
  mast - fastened on the carriage frame (Hc).

Pulleys: S, ML, MH, MR (masts) and W1, W2, A, B, C (carriage) = 9.  Every
section is an elastic :class:`~acausal2d.library.belt.Belt` span (Ebert 2015,
eq. 4.52-4.66, a spring-damper as in the dissertation's model), every pulley a
:class:`~acausal2d.library.belt.Pulley` (4.87-4.99), the drums
:class:`~acausal2d.library.belt.Drum`; the carriage and the hook are
:class:`~acausal2d.library.belt.crane.Carriage` and
:class:`~acausal2d.library.belt.crane.Hook`.  The carriage rides on the skyline
through its running wheels, so the skyline sags under it (a polygon of
straight massless spans; see library/crane.py).

Transfer cycle (Ebert 2015: "Baumstamm anheben, transportieren und absenken"),
both drums angle-driven (rotational.Position) by C2 cycloidal motion laws:

    0 .. 1 s    at rest (static equilibrium)
    1 .. 7 s    lift: D1 winds up 4 m of load rope (hook 6 m -> 2 m below C)
    8 .. 20 s   transport downhill from x_O = 38 m to x_O = 13 m: D2 winds
                the haul-back in, D1 pays the load rope out (amounts from the
                static solutions at both ends, so the hook keeps its 2 m)
    21 .. 27 s  lower: D1 pays out 4 m
    27 .. 30 s  at rest

Outputs (Bild 8.5): rope forces of the load rope (``load1.F`` at the drum
.. ``load6.F`` at the hook) and of the haul-back rope (``haul1.F``,
``haul2.F``); also the skyline force, carriage and hook positions, drum
torques.

Values the dissertation does not give, chosen here
--------------------------------------------------
- Coordinates: x horizontal, y up; left mast foot (0, 0), right mast foot
  (50, 50 tan 15 deg = 13.397) m; mast tops 10 m higher.
- Mast pulleys (r = 0.1 m, J = 0.05 kg m^2, massless housings fixed in the
  ground): S at (0, 10.0), ML at (0, 9.5), MH at (0, 9.0), MR at
  (50, 22.897) (0.5 m below the right mast top).  Skyline ground anchor G at
  (-15, 0); skyline fastening T at the right mast top (50, 23.397).
- Drums (r = 0.5 m, J = 20 kg m^2, w_i = -1, 20 turns = 31.4 m of rope
  stored at t0): D1 (load rope) at (-8, 1), D2 (haul-back) at (-5, 1).
- Carriage: 400 kg, J = 80 kg m^2 about its centre of gravity at (0, -0.45)
  in the carriage frame (origin O midway between the wheel axes, x along the
  wheel axes); running wheels W1, W2 at (-0.4, 0), (0.4, 0), r = 0.1 m;
  load-rope pulleys A (0.20, -0.30), B (-0.32, -0.60), C (-0.07, -0.97),
  r = 0.1 m, J = 0.05 kg m^2; haul-back fastening Hc at (-0.55, -0.20).
  The load rope runs over A, around the left side and bottom of B, over
  the right side of C and drops from C to the hook.  All pulleys and drums
  are frictionless (no bearing friction; the dissertation gives none) and their
  housings massless; the carriage mass includes its pulleys.
- Hook with log: 1000 kg point mass.
- Ropes (steel wire ropes; c = E A of the metallic cross-section, damping
  d = 0.01 s * c, i.e. a 10 ms relaxation time): skyline 22 mm,
  c = 2e7 N; load and haul-back rope 14 mm, c = 8e6 N.
- Skyline pretension 80 kN with the carriage at rest at x_O = 38 m; the
  skyline's material length is then kept.
- Initial state: static equilibrium at x_O = 38 m with the hook 6 m below
  pulley C, computed by :func:`static_pose` (the carriage pose and the
  haul-back force solve the carriage's force and moment balance, the load
  rope carries m g); every section starts with strain F/c.
- Tolerance rtol = 1e-7.

Checks (tests/test_cable_crane.py): at rest the load rope carries m g in
every section and the haul-back force equals the closed form of a
frictionless carriage on a rope (the two skyline spans carry the same force,
so their resultant is normal to the bisector of their directions; the force
balance along the bisector gives the haul-back force); each drum's payout
equals the change of the unstretched rope length l/(1 + eps) + r beta of its
rope; the skyline keeps its material; no rope goes slack during the cycle.

``acausal2d simulate models/cable_crane.py`` simulates one cycle and writes
the rope forces (Bild 8.5), skyline forces and drum torques (the model's
``figures``); ``acausal2d study models/cable_crane.py`` the paths of carriage
and hook (running the file does both, into ./out).
"""
import math
import os
import sys

import numpy as np
from scipy.optimize import fsolve

from acausal2d import Component, start, study
from acausal2d.library import rotational
from acausal2d.library.belt import Belt, Drum, Pulley, connect_band
from acausal2d.library.belt.crane import Carriage, Hook, move, span_geometry
from acausal2d.library.planar import Fixed
from acausal2d.library.signals import TimeFunction

G = 9.81
SPAN = 50.0
H_MAST = 10.0
SLOPE = math.radians(15.0)
Y_RIGHT = SPAN * math.tan(SLOPE)          # right mast foot
R_PULLEY = 0.1
R_DRUM = 0.5
J_PULLEY = 0.05
J_DRUM = 20.0
N_WOUND = 20.0

ANCHOR = (-15.0, 0.0)                      # skyline ground anchor G
TOP = (SPAN, Y_RIGHT + H_MAST)             # skyline fastening T
MAST_PULLEYS = {                           # name: (x10, y10, w = -w_i: side of K1)
    "S": (0.0, H_MAST, -1),
    "ML": (0.0, H_MAST - 0.5, -1),
    "MH": (0.0, H_MAST - 1.0, -1),
    "MR": (SPAN, Y_RIGHT + H_MAST - 0.5, -1),
}
DRUMS = {"D1": (-8.0, 1.0, 1), "D2": (-5.0, 1.0, 1)}
CARRIAGE_PULLEYS = {                       # name: (offset in carriage frame, w = -w_i)
    "W1": ((-0.4, 0.0), 1),
    "W2": ((0.4, 0.0), 1),
    "A": ((0.20, -0.30), 1),
    "B": ((-0.32, -0.60), 1),
    "C": ((-0.07, -0.97), -1),
}
HAUL_MOUNT = (-0.55, -0.20)
M_CARRIAGE = 400.0
J_CARRIAGE = 80.0
COG_CARRIAGE = (0.0, -0.45)
M_HOOK = 1000.0
C_SKY = 2e7
C_ROPE = 8e6
T_RELAX = 0.01
F_SKY0 = 8e4

X_START, X_END = 38.0, 13.0                # carriage reference point O
DROP_LOW, DROP_HIGH = 6.0, 2.0             # hook below pulley C
T_LIFT, D_LIFT = 1.0, 6.0
T_MOVE, D_MOVE = 8.0, 12.0
T_LOWER, D_LOWER = 21.0, 6.0
T_STOP = 30.0

# rope paths: nodes ("fixed", (x, y)), ("pulley", name), ("drum", name),
# ("mount", name) (carriage point), ("hook",)
ROPES = {
    "sky": [("fixed", ANCHOR), ("pulley", "S"), ("pulley", "W1"), ("pulley", "W2"),
            ("fixed", TOP)],
    "load": [("drum", "D1"), ("pulley", "ML"), ("pulley", "MR"), ("pulley", "A"),
             ("pulley", "B"), ("pulley", "C"), ("hook",)],
    "haul": [("drum", "D2"), ("pulley", "MH"), ("mount", "Hc")],
}
STIFFNESS = {"sky": C_SKY, "load": C_ROPE, "haul": C_ROPE}


def _pulley_data(name, pose):
    """(cx, cy, r, w) of pulley or drum ``name`` for the carriage pose."""
    if name in MAST_PULLEYS:
        x, y, w = MAST_PULLEYS[name]
        return x, y, R_PULLEY, w
    if name in DRUMS:
        x, y, w = DRUMS[name]
        return x, y, R_DRUM, w
    (ax, ay), w = CARRIAGE_PULLEYS[name]
    return _carriage_point((ax, ay), pose) + (R_PULLEY, w)


def _carriage_point(off, pose):
    x, y, phi = pose
    c, s = math.cos(phi), math.sin(phi)
    return (x + c * off[0] - s * off[1], y + s * off[0] + c * off[1])


def rope_geometry(rope, pose, hook=None):
    """Spans of ``rope`` for the carriage pose (x, y, phi): list of dicts
    with gamma, l, contact points p1, p2; and the wrap angles of its pulleys
    (dict name -> (beta, kappa1, kappa2)) and of its drum (kappa1).  For the
    load rope, ``hook`` is the hook position; None puts the hook straight
    below pulley C's contact (its end is then returned with l = 0)."""
    nodes = ROPES[rope]
    spans = []
    for k in range(len(nodes) - 1):
        ends = []
        for node, contact in ((nodes[k], 2), (nodes[k + 1], 1)):
            if node[0] in ("pulley", "drum"):
                cx, cy, r, w = _pulley_data(node[1], pose)
                s = w if (contact == 1 or node[0] == "drum") else -w
                ends.append((cx, cy, s * r))
            elif node[0] == "fixed":
                ends.append((node[1][0], node[1][1], 0.0))
            elif node[0] == "mount":
                ends.append(_carriage_point(HAUL_MOUNT, pose) + (0.0,))
            else:
                ends.append(None)
        if ends[1] is None:            # hook
            if hook is None:
                hook = (ends[0][0] + ends[0][2], ends[0][1] - 1.0)
            ends[1] = (hook[0], hook[1], 0.0)
        gam, l, p1, p2 = span_geometry(ends[0], ends[1])
        spans.append({"gamma": gam, "l": l, "p1": p1, "p2": p2})
    wraps = {}
    for k, node in enumerate(nodes):
        if node[0] == "pulley":
            _, _, r, w = _pulley_data(node[1], pose)
            k1 = spans[k - 1]["gamma"] + math.pi + w * math.pi / 2
            k2 = spans[k]["gamma"] - w * math.pi / 2
            raw = w * (k2 - k1)
            beta = raw - 2 * math.pi * math.floor(raw / (2 * math.pi))
            wraps[node[1]] = (beta if beta > 0 else 2 * math.pi, k1, k2, r)
        elif node[0] == "drum":
            _, _, r, w = _pulley_data(node[1], pose)
            wraps[node[1]] = (0.0, spans[0]["gamma"] + w * math.pi / 2, None, r)
    return spans, wraps


def _carriage_forces(pose, F_sky, F_load, F_haul):
    """Resultant force and moment (about O) of the ropes and gravity on the
    carriage at rest; equal forces on both sides of every pulley."""
    x, y, phi = pose
    fx = fy = mz = 0.0

    def add(point, F, gam):
        nonlocal fx, fy, mz
        f = (F * math.cos(gam), F * math.sin(gam))
        fx += f[0]
        fy += f[1]
        mz += (point[0] - x) * f[1] - (point[1] - y) * f[0]

    sky, _ = rope_geometry("sky", pose)
    add(sky[1]["p2"], F_sky, sky[1]["gamma"] + math.pi)      # S -> W1 pulls towards S
    add(sky[3]["p1"], F_sky, sky[3]["gamma"])                # W2 -> T pulls towards T
    load, _ = rope_geometry("load", pose)
    add(load[2]["p2"], F_load, load[2]["gamma"] + math.pi)   # MR -> A pulls towards MR
    add(load[5]["p1"], F_load, -math.pi / 2)                 # C -> hook pulls down
    haul, _ = rope_geometry("haul", pose)
    add(haul[1]["p2"], F_haul, haul[1]["gamma"] + math.pi)   # MH -> Hc pulls towards MH
    S = _carriage_point(COG_CARRIAGE, pose)
    add(S, M_CARRIAGE * G, -math.pi / 2)
    return np.array([fx, fy, mz])


def rope_material(rope, pose, F, hook=None):
    """Unstretched rope material of ``rope`` from its first to its last
    node: sum of l/(1 + F/c) over the spans plus r*beta over the pulleys
    (the drum's stored rope is not included)."""
    spans, wraps = rope_geometry(rope, pose, hook)
    eps = F / STIFFNESS[rope]
    return (sum(s["l"] for s in spans) / (1 + eps)
            + sum(r * beta for beta, _, _, r in wraps.values()))


def static_pose(x_O, drop, F_sky=None, sky_material=None, guess=None):
    """Static equilibrium of carriage and hook with the carriage reference
    point at x = ``x_O`` and the hook ``drop`` below pulley C's contact.

    Give either the skyline force ``F_sky`` or the skyline's unstretched
    material ``sky_material``.  Unknowns: carriage y, phi, haul-back force
    (and skyline force); equations: force and moment balance of the
    carriage (and the skyline material).  The load rope carries m g of the
    hook.  Returns a dict with pose, forces and the hook position."""
    F_load = M_HOOK * G
    if guess is None:
        guess = (H_MAST + x_O * math.tan(SLOPE) - 1.5, SLOPE, 0.6 * F_load,
                 F_sky if F_sky is not None else F_SKY0)

    def unknowns(z):
        y, phi, F_haul = z[:3]
        Fs = F_sky if F_sky is not None else z[3]
        return (x_O, y, phi), F_haul, Fs

    def residual(z):
        pose, F_haul, Fs = unknowns(z)
        r = list(_carriage_forces(pose, Fs, F_load, F_haul) / F_load)
        if F_sky is None:
            r.append(rope_material("sky", pose, Fs) - sky_material)
        return r

    z0 = list(guess[:3]) + ([] if F_sky is not None else [guess[3]])
    z, info, ok, msg = fsolve(residual, z0, full_output=True, xtol=1e-13)
    worst = max(abs(np.asarray(residual(z))))
    if not worst <= 1e-9:      # solved when the force balance holds, whatever fsolve's flag
        raise RuntimeError("static_pose(%g, %g): force balance residual %.3g (of m g) after "
                           "fsolve (%s)" % (x_O, drop, worst, msg))
    pose, F_haul, Fs = unknowns(z)
    load, _ = rope_geometry("load", pose)
    c = load[5]["p1"]
    hook = (c[0], c[1] - drop)
    return {"pose": pose, "F_sky": Fs, "F_load": F_load, "F_haul": F_haul, "hook": hook,
            "sky_material": rope_material("sky", pose, Fs)}


def drive_design():
    """Start state and drum strokes of the cycle from static solutions.

    Returns (start, end, strokes) with ``strokes`` the drum angle changes
    [rad] of D1 for the transport (``"D1_move"``) and of D2
    (``"D2_move"``), and ``"lift"`` for lifting/lowering.  Rope paid out by
    a drum of winding direction w_i = -1: -r dphi + r dkappa1 (library/belt.py
    Drum), so dphi = dkappa1 - d(material)/r."""
    st0 = static_pose(X_START, DROP_LOW, F_sky=F_SKY0)
    st1 = static_pose(X_START, DROP_HIGH, F_sky=F_SKY0)
    st2 = static_pose(X_END, DROP_HIGH, sky_material=st0["sky_material"],
                      guess=(H_MAST + X_END * math.tan(SLOPE) - 1.0, SLOPE,
                             st0["F_haul"], F_SKY0))
    strokes = {"lift": (DROP_LOW - DROP_HIGH) / R_DRUM}
    for rope, drum, F in (("load", "D1", st1["F_load"]), ("haul", "D2", None)):
        Fa = F if F is not None else st1["F_haul"]
        Fb = F if F is not None else st2["F_haul"]
        ma = rope_material(rope, st1["pose"], Fa, st1["hook"])
        mb = rope_material(rope, st2["pose"], Fb, st2["hook"])
        ka = rope_geometry(rope, st1["pose"], st1["hook"])[1][drum][1]
        kb = rope_geometry(rope, st2["pose"], st2["hook"])[1][drum][1]
        strokes[drum + "_move"] = (kb - ka) - (mb - ma) / R_DRUM
    return st0, st2, strokes


def drum_angles(strokes):
    """Drive functions phi_D1(t), phi_D2(t) (w_i = -1: positive winds up)."""
    def phi1(t):
        return (move(t, T_LIFT, D_LIFT, strokes["lift"])
                + move(t, T_MOVE, D_MOVE, strokes["D1_move"])
                - move(t, T_LOWER, D_LOWER, strokes["lift"]))

    def phi2(t):
        return move(t, T_MOVE, D_MOVE, strokes["D2_move"])
    return phi1, phi2


class CableCrane(Component):
    """Three-rope cable crane of Ebert (2015), ch. 8.1 (see the module docstring)."""
    experiment = {"stop_time": T_STOP, "intervals": 600, "rtol": 1e-7}
    outputs = ["load1.F", "load3.F", "load6.F", "haul1.F", "haul2.F", "sky2.F",
               "carriage.x", "carriage.y", "hook.x", "hook.y", "D1.ctrR2.tau", "D2.ctrR2.tau"]
    figures = [{"name": "cable_crane_rope_forces", "signals": ["load1.F", "load6.F", "haul1.F"],
                "title": "rope forces of load and haul-back rope (Bild 8.5)"},
               {"name": "cable_crane_skyline_drums", "title": "skyline forces, drum torques",
                "signals": ["sky2.F", "sky4.F", "D1.ctrR2.tau", "D2.ctrR2.tau"]}]

    @study
    def paths(ctx):
        """Paths of carriage and hook over the cycle with the skyline at the
        start, the middle of the transport and the end."""
        res = ctx.result
        for name in ("load1.F", "load6.F", "haul1.F", "sky2.F"):
            v = res[name]
            ctx.note("%-8s start %9.1f N  min %9.1f N  max %9.1f N" % (name, v[0], v.min(),
                                                                       v.max()))
        ctx.save(paths_figure(res), "cable_crane_paths")

    def __init__(self, **kw):
        super().__init__(**kw)
        st0, st_end, strokes = drive_design()
        self.design = {"start": st0, "end": st_end, "strokes": strokes}
        pose = st0["pose"]
        forces = {"sky": st0["F_sky"], "load": st0["F_load"], "haul": st0["F_haul"]}
        mounts = {name: off for name, (off, _) in CARRIAGE_PULLEYS.items()}
        mounts["Hc"] = HAUL_MOUNT
        self.carriage = Carriage(mounts=mounts, m=M_CARRIAGE, J=J_CARRIAGE, cog=COG_CARRIAGE,
                                 x=start(pose[0], fixed=True), y=start(pose[1], fixed=True),
                                 phi=start(pose[2], fixed=True))
        self.hook = Hook(m=M_HOOK, x=start(st0["hook"][0], fixed=True),
                         y=start(st0["hook"][1], fixed=True))
        for name, (x0, y0, w) in MAST_PULLEYS.items():
            setattr(self, name, Pulley(r=R_PULLEY, x10=x0, y10=y0, w_i=-w, J=J_PULLEY))
        for name, (_, w) in CARRIAGE_PULLEYS.items():     # axis at the carriage's port
            p = Pulley(r=R_PULLEY, w_i=-w, J=J_PULLEY)
            setattr(self, name, p)
            self.connect(getattr(self.carriage, name), p.ctr2D1)
        for name, (x0, y0, w) in DRUMS.items():
            setattr(self, name, Drum(r=R_DRUM, x10=x0, y10=y0, w_i=-w, J=J_DRUM, n_wound=N_WOUND))
        self.anchor = Fixed(r=ANCHOR)
        self.top = Fixed(r=TOP)
        self._drives(*drum_angles(strokes))
        for rope, nodes in ROPES.items():
            self._rope(rope, nodes, forces[rope], pose, st0["hook"])

    def _drives(self, phi1, phi2):
        """The "rigid" drum drives of Bild 8.3: each drum's angle follows
        its motion law (``phi1``, ``phi2``: functions of time)."""
        self.drive1, self.drive2 = rotational.Position(), rotational.Position()
        self.law1, self.law2 = TimeFunction(phi1), TimeFunction(phi2)
        self.connect(self.law1.y, self.drive1.phi_in)
        self.connect(self.law2.y, self.drive2.phi_in)
        self.connect(self.drive1.flange, self.D1.ctrR2)
        self.connect(self.drive2.flange, self.D2.ctrR2)

    def _rope(self, rope, nodes, F, pose, hook):
        """The spans of one rope along its ``nodes``, pretensioned to F."""
        c = STIFFNESS[rope]
        spans, _ = rope_geometry(rope, pose, hook)
        for k in range(len(nodes) - 1):
            kw_start = {"eps": start(F / c, fixed=True)}
            if nodes[k + 1][0] in ("mount", "hook"):
                # ends prepare_belts does not know: give the branch here
                g, l = spans[k]["gamma"], spans[k]["l"]
                kw_start.update(gamma=start(g), l=start(l), l_u=start(l), l_u0=start(l))
            span = Belt(c=c, d=T_RELAX * c, **kw_start)
            setattr(self, "%s%d" % (rope, k + 1), span)
            for node, end in ((nodes[k], 1), (nodes[k + 1], 2)):
                self._attach(span, end, node)

    def _attach(self, span, end, node):
        """Connect end ``end`` of ``span`` to the rope node ``node``."""
        port = getattr(span, "ctr2D%d" % end)
        if node[0] in ("pulley", "drum"):
            contact = 1 if (node[0] == "drum" or end == 2) else 2
            connect_band(self, span, end, getattr(self, node[1]), contact)
        elif node[0] == "fixed":
            self.connect((self.anchor if node[1] == ANCHOR else self.top).frame, port)
        elif node[0] == "mount":
            self.connect(self.carriage.Hc, port)
        else:
            self.connect(self.hook.frame, port)


    def shapes(self):
        """The masts standing on the sloped terrain, a ground symbol at each
        foot: from the foot to the skyline pulley S on the left, to the
        skyline fastening T on the right (the pulley housings on the masts
        are drawn by the pulleys).  The terrain runs from the skyline's
        ground anchor G."""
        terrain = [["anchor.frame.x", "anchor.frame.y"], [0.0, 0.0], [SPAN, Y_RIGHT],
                   [SPAN + 5.0, Y_RIGHT + 5.0 * math.tan(SLOPE)]]
        masts = ((("S.ctr2D1.x", "S.ctr2D1.y"), (0.0, 0.0)),
                 (("top.frame.x", "top.frame.y"), (SPAN, Y_RIGHT)))
        return ([{"type": "link", "points": terrain, "width": 0.15, "color": "#a0522d"}]
                + [{"type": "link", "points": [list(top), list(foot)], "width": 0.35,
                    "color": "#5d6d7e"} for top, foot in masts]
                + [{"type": "ground", "x": foot[0], "y": foot[1]} for _, foot in masts])


SECTIONS = {"load": ["load%d" % k for k in range(1, 7)],
            "haul": ["haul1", "haul2"],
            "sky": ["sky%d" % k for k in range(1, 5)]}


def paths_figure(res):
    """Paths of carriage and hook with the skyline at three instants and the
    masts (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(9, 4.5))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ax.plot([-20, 0, SPAN, SPAN + 5], [0, 0, Y_RIGHT, Y_RIGHT + 5 * math.tan(SLOPE)],
            color="sienna", label="ground")
    ax.plot([0, 0], [0, H_MAST], "k", lw=3)
    ax.plot([SPAN, SPAN], [Y_RIGHT, Y_RIGHT + H_MAST], "k", lw=3)
    ax.plot(res["carriage.x"], res["carriage.y"], label="carriage O")
    ax.plot(res["hook.x"], res["hook.y"], label="hook")
    for k in (0, int(np.searchsorted(res.time, T_MOVE + D_MOVE / 2)), len(res.time) - 1):
        sx = [ANCHOR[0], MAST_PULLEYS["S"][0], res["sky3.ctr2D1.x"][k],
              res["sky3.ctr2D2.x"][k], TOP[0]]
        sy = [ANCHOR[1], MAST_PULLEYS["S"][1] + R_PULLEY, res["sky3.ctr2D1.y"][k],
              res["sky3.ctr2D2.y"][k], TOP[1]]
        ax.plot(sx, sy, color="0.5", lw=0.8, label="skyline" if k == 0 else None)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title("CableCrane: paths of carriage and hook")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def plot_cycle(res, out):
    """Write the declared figures (rope forces, Bild 8.5; skyline forces and
    drum torques) and the paths of carriage and hook as PNG files into
    ``out``; returns the paths."""
    from acausal2d.visual.plotting import declared_figures, save_figure, write_figures
    paths = write_figures(res, out, declared_figures(res.model.model))
    paths.append(save_figure(paths_figure(res), os.path.join(out, "cable_crane_paths.png")))
    return paths


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
