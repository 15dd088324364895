"""Joints of the planar library (PlanarMechanics.Joints): revolute and
prismatic joints with optional 1D flanges, and ideal rolling on the ground.

Position-level equations and force balances only (Ebert 2015, eq. 4.1 at the
frames); velocities come from index reduction.
"""
import math

import casadi as ca
import numpy as np

from acausal2d import (Component, der, Frame, Parameter, RotationalFlange,
                       TranslationalFlange, Variable)

from .parts import fixed_of


class Revolute(Component):
    """Revolute joint: frame_b turns against frame_a by phi about their common
    origin; w = der(phi).  With ``use_flange=True`` a 1D rotational flange
    (angle phi, driving torque tau) and a support flange (fixed at 0, carried
    by frame_a) are added: the frame_b part receives +tau and the frame_a
    part -tau, so a 1D element that pushes the flange positively drives phi
    positively; the support is grounded inside the joint (PlanarMechanics
    Joints.Revolute).  ``state_select`` applies to phi and w (default
    'prefer'; PlanarMechanics' default is 'default').  Ebert (2015), eq. 2.1 (a joint
    of one degree of freedom), eq. 4.1 at the frames.  Every run holds the
    relative angular acceleration z = der(w) too (PlanarMechanics' z; a
    derived signal, see :mod:`acausal2d.derived`) where index reduction made
    it."""
    phi = Variable(unit="rad", doc="relative angle")
    w = Variable(unit="rad/s", doc="relative angular velocity")
    derived_signals = {"z": ("der(w)", "der(der(phi))")}

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
        """The joint circle; with a flange also the drive torque (the torque
        the frame_b part receives) as a curved arrow."""
        out = [{"type": "joint", "x": "frame_a.x", "y": "frame_a.y"}]
        if self.use_flange:
            out.append({"type": "torque", "x": "frame_a.x", "y": "frame_a.y",
                        "t": "flange_a.tau"})
        return out

    def topology(self):
        return [("joint", self.frame_a, self.frame_b, 1)]


class Prismatic(Component):
    """Prismatic joint: frame_b moves by s along the unit vector of r
    (resolved in frame_a); same angle; v = der(s).  With ``use_flange=True`` a
    1D translational flange (position s, driving force f) and a support flange
    (fixed at 0) are added: the joint pushes the frame_b part with +f e0 and
    the frame_a part with -f e0 (e0 the axis in world), the support is
    grounded inside the joint (PlanarMechanics Joints.Prismatic).
    ``state_select`` applies to s and v.  Ebert (2015), eq. 2.1, eq. 4.1 at the
    frames.  Every run holds the relative acceleration a = der(v) too
    (PlanarMechanics' a; a derived signal) where index reduction made it.

    ``guide=(s_min, s_max)`` (drawing only) is the range of s that the
    animation draws as the guide when one frame is fixed in the world; see
    :meth:`shapes`."""
    r = Parameter((1.0, 0.0), "m", "direction of motion, resolved in frame_a", nonzero=True)
    s = Variable(unit="m", doc="relative position")
    v = Variable(unit="m/s", doc="relative velocity")
    derived_signals = {"a": ("der(v)", "der(der(s))")}

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
                     "guide": [["frame_a.x", "frame_a.y"], ["frame_b.x", "frame_b.y"]]}] \
                + self._drive_arrow()
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
                 "phi": moving + ".phi", "guide": guide}] + self._drive_arrow(moving)

    def _drive_arrow(self, moving="frame_b"):
        """With a flange: the drive force f as an arrow at the moving frame
        along the axis (the frame_b part receives +f e0, the frame_a part
        -f e0)."""
        if not self.use_flange:
            return []
        rx, ry = (float(v) for v in np.ravel(self.parameter_value("r")))
        angle = math.atan2(ry, rx) + (0.0 if moving == "frame_b" else math.pi)
        return [{"type": "arrow", "x": moving + ".x", "y": moving + ".y",
                 "fx": "flange_a.f", "fy": 0.0, "phi": "frame_a.phi", "angle": angle}]

    def topology(self):
        return [("joint", self.frame_a, self.frame_b, 1)]


class IdealRolling(Component):
    """Wheel of radius ``R`` rolling without slip on the ground line y = 0
    (PlanarMechanics Joints.IdealRolling): frame_a is the wheel centre at
    height R, and ``x + R phi = x0`` (rolling, written at position level;
    ``x0`` is the centre's x at phi = 0).  The contact force passes through
    the contact point (x, 0), hence ``frame_a.t = R frame_a.fx``; the
    normal force is whatever holds the centre at y = R (Ebert 2015, eq. 4.1 at the
    frame, eq. 2.1: a joint of one degree of freedom against the ground).

    The wheel's mass is a :class:`Body` at frame_a.  Variables: x, phi,
    vx = der(x), w = der(phi); the contact point's velocity vx + R w is
    zero.  Derived signals (PlanarMechanics' ax, z): ax = der(vx),
    z = der(w), where index reduction made them."""
    R = Parameter(1.0, "m", "radius of the wheel", positive=True)
    x0 = Parameter(0.0, "m", "x of the wheel centre at phi = 0")
    x = Variable(unit="m", doc="x position of the wheel centre")
    phi = Variable(unit="rad", doc="wheel angle")
    vx = Variable(unit="m/s", doc="velocity of the wheel centre")
    w = Variable(unit="rad/s", doc="angular velocity of the wheel")
    derived_signals = {"ax": ("der(vx)", "der(der(x))"), "z": ("der(w)", "der(der(phi))")}

    def __init__(self, state_select="default", **kw):
        super().__init__(**kw)
        for name in ("x", "phi", "w"):
            self.variable(name).state_select = state_select
        self.frame_a = Frame()
        # the ground side of the rolling contact, for topology() only (not a
        # connector of the model: no variables, no equations)
        self.__dict__["_ground_side"] = Frame()

    def equations(self):
        a = self.frame_a
        return [a.x == self.x, a.y == self.R, a.phi == self.phi,
                self.x + self.R * self.phi == self.x0,
                self.vx == der(self.x), self.w == der(self.phi),
                a.t == self.R * a.fx]

    def topology(self):
        """A joint of one degree of freedom between the ground and the
        wheel (Ebert 2015, eq. 2.1: rolling without slip removes two)."""
        return [("ground", [self._ground_side]), ("joint", self._ground_side, self.frame_a, 1)]

    def shapes(self):
        """The wheel (spokes turn with phi) and the ground under it."""
        return [{"type": "ground", "x": "frame_a.x", "y": 0.0},
                {"type": "pulley", "x": "frame_a.x", "y": "frame_a.y",
                 "r": float(self.parameter_value("R")), "phi": "frame_a.phi"}]
