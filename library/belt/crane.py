"""Cable-crane elements (Ebert 2015, ch. 8.1, Bild 8.3 and 8.4): the carriage
("Laufkatze") as a rigid body carrying pulleys and rope fastenings, the
crane hook with its load, smooth drum drive functions, and the static
equilibrium of a rope-supported carriage.

The carriage runs on the skyline through two running wheels, which are
ordinary :class:`~acausal2d.library.belt.Pulley` elements carried by the
carriage (their housings ``ctr2D1`` connected to carriage mounts) and
wrapped by the skyline from below.  The skyline is therefore an elastic,
massless rope of straight spans (Ebert 2015, eq. 4.52-4.66) that sags under the
carriage: the carriage position on it is not prescribed but follows from
the rope lengths, the rope forces and the carriage's equations of motion.
A weightless rope loaded by point forces is exactly polygonal, so the
"sagging skyline" is the polygon anchor - mast pulley - wheel W1 - wheel
W2 - mast top (the catenary sag of the rope's own weight is not modelled).

Elements
--------
- :class:`Carriage` -- rigid body (mass ``m``, inertia ``J`` about the
  centre of gravity ``cog``) with one frame per mount, placed at fixed
  offsets in the carriage frame (Ebert 2015, Anhang A.3 rigid body with several
  frames; mass data in 4.97-4.99 style).
- :class:`Hook` -- point mass (hook and load) hanging from the rope end.

Helpers
-------
- :func:`cycloid` -- C2 motion law for drum drive functions.
- :func:`span_geometry` -- tangent construction of one span with its
  contact points (used for the static solution of a model).
"""
import math

import casadi as ca
import numpy as np

from acausal2d import Component, der, Frame, Outer, Parameter, Variable
from acausal2d.errors import ModelDefinitionError
from .layout import tangent
from acausal2d.library.planar import PlanarWorld

__all__ = ["Carriage", "Hook", "cycloid", "move", "span_geometry"]


class Carriage(Component):
    """Carriage of a cable crane: a rigid body with named mount frames.

    ``mounts`` (structural constructor argument) maps mount names to their
    offsets ``(x, y)`` in the carriage frame; each becomes a frame attribute
    of that name (e.g. ``carriage.W1``), with the carriage angle as its
    angle.  Connect pulley housings (``Pulley.ctr2D1``), rope ends or other
    frames to them.  The reference point O of the carriage frame is at
    ``(x, y)`` with angle ``phi`` (outputs; give start values with
    :func:`~acausal2d.language.dsl.start`); ``frame_a`` is a frame at O.

    Equations: mount positions ``r_i = O + R(phi) a_i``; Newton-Euler at the
    centre of gravity ``S = O + R(phi) cog``:

        m S'' = sum_i f_i + m g,
        J phi'' = sum_i (r_i - S) x f_i + sum_i t_i

    with ``f_i``, ``t_i`` the forces and torques acting on the mounts (the
    pulley housings hand their bearing forces and, with bearing friction,
    their friction torques to the carriage).  Velocities and accelerations
    come from index reduction.
    """
    world = Outer(PlanarWorld)
    m = Parameter(400.0, "kg", "mass of the carriage (with its pulleys)", min=0.0)
    J = Parameter(80.0, "kg.m2", "rotational inertia about the centre of gravity", min=0.0)
    cog = Parameter((0.0, 0.0), "m", "centre of gravity in the carriage frame")
    x = Variable(unit="m", state_select="prefer", doc="x of the reference point O")
    y = Variable(unit="m", state_select="prefer", doc="y of the reference point O")
    phi = Variable(unit="rad", state_select="prefer", doc="carriage angle")

    def __init__(self, mounts=None, **kw):
        super().__init__(**kw)
        mounts = dict(mounts or {})
        if "frame_a" in mounts:
            raise ModelDefinitionError("Carriage: 'frame_a' is reserved for the reference point")
        self.mount_offsets = {"frame_a": (0.0, 0.0)}
        self.frame_a = Frame(doc="reference point O")
        for name, off in mounts.items():
            if len(off) != 2:
                raise ModelDefinitionError("Carriage mount %r: offset must be (x, y), got %r"
                                           % (name, off))
            self.mount_offsets[name] = (float(off[0]), float(off[1]))
            setattr(self, name, Frame(doc="mount at %r in the carriage frame" % (off,)))

    def _linkage_seed(self):
        """Start poses [(mount frame, {x, y, phi})] from the start values of
        x, y, phi (all three given), for the tangent construction of the
        belts (:class:`~acausal2d.library.belt.placement.StartPoses`) and
        the linkage pre-assembly (``_linkage_seed`` protocol of
        library/linkage/base.py)."""
        if not all(self.is_given(k) for k in ("x", "y", "phi")):
            return []
        x, y, phi = (float(self.start_value(k)) for k in ("x", "y", "phi"))
        c, s = math.cos(phi), math.sin(phi)
        return [(getattr(self, name), {"x": x + c * ax - s * ay, "y": y + s * ax + c * ay,
                                       "phi": phi})
                for name, (ax, ay) in self.mount_offsets.items()]

    def equations(self):
        c, s = ca.cos(self.phi), ca.sin(self.phi)
        eqs = []
        fx = fy = mom = 0.0
        Sx = self.x + c * self.cog[0] - s * self.cog[1]
        Sy = self.y + s * self.cog[0] + c * self.cog[1]
        for name, (ax, ay) in self.mount_offsets.items():
            f = getattr(self, name)
            rx, ry = c * ax - s * ay, s * ax + c * ay
            eqs += [f.x == self.x + rx, f.y == self.y + ry, f.phi == self.phi]
            fx = fx + f.fx
            fy = fy + f.fy
            mom = mom + (self.x + rx - Sx) * f.fy - (self.y + ry - Sy) * f.fx + f.t
        g = self.world.g
        eqs += [self.m * der(der(Sx)) == fx + self.m * g[0],
                self.m * der(der(Sy)) == fy + self.m * g[1],
                self.J * der(der(self.phi)) == mom]
        return eqs

    def shapes(self):
        # outline through the mounts, ordered by their angle about their mean
        offs = self.mount_offsets
        cx = sum(a for a, _ in offs.values()) / len(offs)
        cy = sum(b for _, b in offs.values()) / len(offs)
        names = sorted(offs, key=lambda n: math.atan2(offs[n][1] - cy, offs[n][0] - cx))
        pts = [[name + ".x", name + ".y"] for name in names]
        # the mounts (pulley axes, rope fastenings) as pins on the outline
        pins = [{"type": "joint", "x": name + ".x", "y": name + ".y"}
                for name in self.mount_offsets if name != "frame_a"]
        return [{"type": "link", "points": pts + [pts[0]], "width": 0.05},
                {"type": "trace", "x": "frame_a.x", "y": "frame_a.y"}] + pins

    def topology(self):
        return [("rigid", [getattr(self, name) for name in self.mount_offsets])]

    def world_point(self, name, x, y, phi):
        """World position of mount ``name`` for the pose (x, y, phi) (numeric)."""
        ax, ay = self.mount_offsets[name]
        c, s = math.cos(phi), math.sin(phi)
        return x + c * ax - s * ay, y + s * ax + c * ay


class Hook(Component):
    """Crane hook with its load: a point mass ``m`` at ``frame`` under
    gravity; the frame does not turn (``phi = 0``), so a rope end fastened
    to it needs no torque.  Outputs ``x``, ``y``."""
    world = Outer(PlanarWorld)
    m = Parameter(1000.0, "kg", "mass of hook and load", min=0.0)
    x = Variable(unit="m", state_select="prefer", doc="x of the hook")
    y = Variable(unit="m", state_select="prefer", doc="y of the hook")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame = Frame(doc="rope fastening of the hook")

    def equations(self):
        f = self.frame
        g = self.world.g
        return [f.x == self.x, f.y == self.y, f.phi == 0,
                self.m * der(der(self.x)) == f.fx + self.m * g[0],
                self.m * der(der(self.y)) == f.fy + self.m * g[1]]

    def shapes(self):
        # the load as a disc of the default screen size (a world radius of
        # a few decimetres vanishes in the view of a whole crane)
        return [{"type": "body", "x": "x", "y": "y"},
                {"type": "trace", "x": "x", "y": "y"}]


# --------------------------------------------------------------------------
# drive functions
# --------------------------------------------------------------------------
def cycloid(u):
    """Cycloidal motion law on u in [0, 1]: ``u - sin(2 pi u)/(2 pi)``.
    Position, velocity and acceleration are continuous at both ends
    (velocity and acceleration zero there), so a drive built from it is C2;
    peak velocity 2 (times stroke/duration), peak acceleration 2 pi."""
    return u - ca.sin(2 * ca.pi * u) / (2 * ca.pi)


def move(t, t0, duration, stroke):
    """``stroke * cycloid((t - t0)/duration)`` between t0 and t0 + duration,
    0 before and ``stroke`` after (a C2 time function; the switching times
    become time events).  ``t`` is a number or the CasADi time symbol."""
    u = (t - t0) / duration
    return ca.if_else(t < t0, 0.0, ca.if_else(t < t0 + duration, stroke * cycloid(u), stroke))


# --------------------------------------------------------------------------
# statics helpers
# --------------------------------------------------------------------------
def span_geometry(a, b):
    """Tangent construction of one span with its contact points.

    ``a``, ``b``: ``(cx, cy, rho)`` as for :func:`acausal2d.library.belt.tangent`
    (signed radius: ``s*r`` with ``s = w`` at a contact K1 and ``s = -w`` at
    a contact K2 of a pulley with winding direction w; 0 for a point).
    Returns ``(gamma, l, (x1, y1), (x2, y2))``: span angle, free length and
    the contact points at both ends."""
    gam, l = tangent(a, b)
    e = np.array([math.cos(gam), math.sin(gam)])
    n = np.array([-e[1], e[0]])
    p1 = np.array(a[:2]) + a[2] * n
    p2 = np.array(b[:2]) - b[2] * n
    return gam, l, tuple(p1), tuple(p2)
