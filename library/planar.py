"""Planar multibody basics with the semantics of the Modelica library
PlanarMechanics (frames resolved in the world frame, phi and t counter-clockwise
positive), as described in the project's reference data README.

Each element states position-level equations, force/torque balances and mass
data only; velocities and accelerations are produced by index reduction.
The flows of a :class:`~acausal2d.language.connectors.Frame` are the force and torque
acting on the element from the connected part (seed eq. 4.1 at the nodes).
"""
import math

import casadi as ca
import numpy as np

from acausal2d import (Component, der, Frame, Outer, Parameter, RotationalFlange,
                       TranslationalFlange, Variable)
from acausal2d.language.unionfind import connector_sets


class PlanarWorld(Component):
    """Gravity field for all bodies of the model (default {0, -9.81} m/s²).

    Place one in a model to change gravity; a model without one gets the
    default automatically (elements that need it declare
    ``world = Outer(PlanarWorld)``)."""
    g = Parameter((0.0, -9.81), "m/s2", "gravity acceleration, world frame")


# --------------------------------------------------------------------------
# connection queries for drawing and topology (shared with library/belt.py)
# --------------------------------------------------------------------------
def is_connected(conn):
    """True if the connector ``conn`` appears in a connect statement of its
    model (see :func:`acausal2d.language.unionfind.connector_sets`)."""
    _, connected = connector_sets(conn.owner.root)
    return id(conn) in connected


def fixed_of(conn):
    """The :class:`Fixed` whose frame is in the connection set of ``conn``
    (directly or through other connections), or None: the frame ``conn`` is
    then fixed in the world at that element's ``r``, ``phi``."""
    root = conn.owner.root
    sets, _ = connector_sets(root)
    k = sets.find(id(conn))
    for comp in root.components():
        if isinstance(comp, Fixed) and sets.find(id(comp.frame)) == k:
            return comp
    return None


class Fixed(Component):
    """Frame fixed in the world at (x, y) with angle phi."""
    r = Parameter((0.0, 0.0), "m", "position of the frame in the world")
    phi = Parameter(0.0, "rad", "angle of the frame")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame = Frame()

    def equations(self):
        f = self.frame
        return [f.x == self.r[0], f.y == self.r[1], f.phi == self.phi]

    def shapes(self):
        return [{"type": "ground", "x": "frame.x", "y": "frame.y", "phi": "frame.phi"}]

    def topology(self):
        return [("ground", [self.frame])]


class Body(Component):
    """Rigid body: point mass m at its frame origin, rotational inertia I about
    that origin, under the world's gravity (PlanarMechanics Body; seed Anhang
    A.3 with the centre of gravity at the frame origin).

    Outputs: x, y, phi of the frame."""
    world = Outer(PlanarWorld)
    m = Parameter(1.0, "kg", "mass", min=0.0)
    I = Parameter(0.1, "kg.m2", "rotational inertia about the frame origin", min=0.0)
    x = Variable(unit="m", doc="x position")
    y = Variable(unit="m", doc="y position")
    phi = Variable(unit="rad", doc="angle")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()

    def equations(self):
        f = self.frame_a
        g = self.world.g
        return [self.x == f.x, self.y == f.y, self.phi == f.phi,
                self.m * der(der(self.x)) == f.fx + self.m * g[0],
                self.m * der(der(self.y)) == f.fy + self.m * g[1],
                self.I * der(der(self.phi)) == f.t]

    def shapes(self):
        return [{"type": "body", "x": "frame_a.x", "y": "frame_a.y"}]

    def topology(self):
        return [("rigid", [self.frame_a])]


class FixedTranslation(Component):
    """Massless rigid rod from frame_a to frame_b; r is resolved in frame_a."""
    r = Parameter((1.0, 0.0), "m", "vector from frame_a to frame_b, in frame_a")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()
        self.frame_b = Frame()

    def equations(self):
        a, b = self.frame_a, self.frame_b
        c, s = ca.cos(a.phi), ca.sin(a.phi)
        rx = c * self.r[0] - s * self.r[1]
        ry = s * self.r[0] + c * self.r[1]
        return [b.x == a.x + rx, b.y == a.y + ry, b.phi == a.phi,
                a.fx + b.fx == 0, a.fy + b.fy == 0,
                a.t + b.t + rx * b.fy - ry * b.fx == 0]

    def shapes(self):
        return [{"type": "link", "points": [["frame_a.x", "frame_a.y"], ["frame_b.x", "frame_b.y"]]}]

    def topology(self):
        return [("rigid", [self.frame_a, self.frame_b])]


class Revolute(Component):
    """Revolute joint: frame_b turns against frame_a by phi about their common
    origin; w = der(phi).  With ``use_flange=True`` a 1D rotational flange
    (angle phi, driving torque tau) and a support flange (fixed at 0, carried
    by frame_a) are added.  ``state_select`` applies to phi and w (default
    'prefer', as in PlanarMechanics)."""
    phi = Variable(unit="rad", doc="relative angle")
    w = Variable(unit="rad/s", doc="relative angular velocity")

    def __init__(self, use_flange=False, state_select="prefer", **kw):
        super().__init__(**kw)
        self.variable("phi").state_select = state_select
        self.variable("w").state_select = state_select
        self.frame_a = Frame()
        self.frame_b = Frame()
        self.use_flange = use_flange
        if use_flange:
            self.flange_a = RotationalFlange()
            self.support = RotationalFlange()

    def equations(self):
        a, b = self.frame_a, self.frame_b
        eqs = [b.x == a.x, b.y == a.y, b.phi == a.phi + self.phi,
               self.w == der(self.phi),
               a.fx + b.fx == 0, a.fy + b.fy == 0, a.t + b.t == 0]
        if self.use_flange:
            eqs += [self.flange_a.phi == self.phi, b.t == -self.flange_a.tau,
                    self.support.phi == 0]
        else:
            eqs.append(b.t == 0)
        return eqs

    def shapes(self):
        return [{"type": "joint", "x": "frame_a.x", "y": "frame_a.y"}]

    def topology(self):
        return [("joint", self.frame_a, self.frame_b, 1)]


class Prismatic(Component):
    """Prismatic joint: frame_b moves by s along the unit vector of r
    (resolved in frame_a); same angle; v = der(s).  With ``use_flange=True`` a
    1D translational flange (position s, driving force f) and a support flange
    (fixed at 0) are added.  ``state_select`` applies to s and v.

    ``guide=(s_min, s_max)`` (drawing only) is the range of s that the
    animation draws as the guide when one frame is fixed in the world; see
    :meth:`shapes`."""
    r = Parameter((1.0, 0.0), "m", "direction of motion, resolved in frame_a")
    s = Variable(unit="m", doc="relative position")
    v = Variable(unit="m/s", doc="relative velocity")

    def __init__(self, use_flange=False, state_select="prefer", guide=None, **kw):
        super().__init__(**kw)
        self.variable("s").state_select = state_select
        self.variable("v").state_select = state_select
        if guide is not None:
            guide = (float(guide[0]), float(guide[1]))
        self.guide_range = guide
        self.frame_a = Frame()
        self.frame_b = Frame()
        self.use_flange = use_flange
        if use_flange:
            self.flange_a = TranslationalFlange()
            self.support = TranslationalFlange()

    def equations(self):
        a, b = self.frame_a, self.frame_b
        n = ca.sqrt(self.r[0] ** 2 + self.r[1] ** 2)
        c, s = ca.cos(a.phi), ca.sin(a.phi)
        ex = (c * self.r[0] - s * self.r[1]) / n
        ey = (s * self.r[0] + c * self.r[1]) / n
        axial = ex * b.fx + ey * b.fy
        eqs = [b.x == a.x + self.s * ex, b.y == a.y + self.s * ey, b.phi == a.phi,
               self.v == der(self.s),
               a.fx + b.fx == 0, a.fy + b.fy == 0,
               a.t + b.t + self.s * (ex * b.fy - ey * b.fx) == 0]
        if self.use_flange:
            eqs += [self.flange_a.s == self.s, axial == -self.flange_a.f,
                    self.support.s == 0]
        else:
            eqs.append(axial == 0)
        return eqs

    def shapes(self):
        """The slider block on its guide.

        When one frame is fixed in the world -- its connection set holds the
        frame of a :class:`Fixed` (see :func:`fixed_of`) -- and the other is
        not, the block is drawn at the moving frame (``frame_a`` when
        ``frame_b`` is the fixed one, as in a slider-crank whose cylinder is
        the ground) and the guide as a constant line through the fixed
        frame along the axis r: it covers the positions of the moving frame
        for s in ``guide`` (constructor argument), by default from s = 0
        (the fixed frame) to twice the start value of s, or s = -|r|/2 ..
        |r|/2 when that start value is 0.  Its end points are numbers from
        the parameter values of the Fixed and of r at drawing time.  When
        neither frame is fixed, the block is at frame_b and the guide runs
        from frame_a to it."""
        fixed_a, fixed_b = fixed_of(self.frame_a), fixed_of(self.frame_b)
        if fixed_a is None and fixed_b is None:
            return [{"type": "slider", "x": "frame_b.x", "y": "frame_b.y", "phi": "frame_a.phi",
                     "guide": [["frame_a.x", "frame_a.y"], ["frame_b.x", "frame_b.y"]]}]
        if fixed_a is None:
            moving, ground, sign = "frame_a", fixed_b, -1.0     # frame_a = frame_b - s e
        else:
            moving, ground, sign = "frame_b", fixed_a, 1.0      # frame_b = frame_a + s e
        gx, gy = (float(v) for v in np.ravel(ground.parameter_value("r")))
        gphi = float(ground.parameter_value("phi"))
        rx, ry = (float(v) for v in np.ravel(self.parameter_value("r")))
        norm = math.hypot(rx, ry)
        cg, sg = math.cos(gphi), math.sin(gphi)
        ex, ey = (cg * rx - sg * ry) / norm, (sg * rx + cg * ry) / norm
        if self.guide_range is not None:
            ends = self.guide_range
        else:
            s0 = self.start_value("s")
            ends = (0.0, 2.0 * s0) if s0 != 0.0 else (-norm / 2, norm / 2)
        guide = [[gx + sign * e * ex, gy + sign * e * ey] for e in ends]
        return [{"type": "slider", "x": moving + ".x", "y": moving + ".y",
                 "phi": moving + ".phi", "guide": guide}]

    def topology(self):
        return [("joint", self.frame_a, self.frame_b, 1)]
