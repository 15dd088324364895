"""Parts of the planar library (PlanarMechanics.Parts): fixed frames, bodies
with mass, rigid rods and rotations.

Each element states position-level equations, force/torque balances and mass
data only; velocities and accelerations are produced by index reduction.
The flows of a :class:`~acausal2d.language.connectors.Frame` are the force and torque
acting on the element from the connected part (Ebert 2015, eq. 4.1 at the nodes).
"""
import casadi as ca

from acausal2d import Component, der, Frame, Outer, Parameter, Variable
from acausal2d.errors import ModelDefinitionError

from acausal2d.language.unionfind import connector_sets

from .base import PlanarWorld, rotate


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
    that origin, under the world's gravity (PlanarMechanics Body; Ebert (2015), Anhang
    A.3 with the centre of gravity at the frame origin).

    Outputs: x, y, phi of the frame and the velocities vx = der(x),
    vy = der(y), w = der(phi) (PlanarMechanics' r, v, phi, w); give them
    start values to start a free body moving (``vx=start(1, fixed=True)``).
    Every run also holds the accelerations ax = der(vx), ay = der(vy) and
    the angular acceleration z = der(w) (PlanarMechanics' a, z), read from
    the derivatives index reduction made (derived signals, no equations)."""
    world = Outer(PlanarWorld)
    m = Parameter(1.0, "kg", "mass", min=0.0)
    I = Parameter(0.1, "kg.m2", "rotational inertia about the frame origin", min=0.0)
    x = Variable(unit="m", doc="x position")
    y = Variable(unit="m", doc="y position")
    phi = Variable(unit="rad", doc="angle")
    vx = Variable(unit="m/s", doc="x velocity der(x)")
    vy = Variable(unit="m/s", doc="y velocity der(y)")
    w = Variable(unit="rad/s", doc="angular velocity der(phi)")
    modelica_names = {"r[1]": "x", "r[2]": "y", "v[1]": "vx", "v[2]": "vy",
                      "a[1]": "ax", "a[2]": "ay"}
    """PlanarMechanics' array names of the variables (read by ``compare``)."""
    derived_signals = {"ax": ("der(vx)", "der(der(x))"), "ay": ("der(vy)", "der(der(y))"),
                       "z": ("der(w)", "der(der(phi))")}
    """Accelerations of the frame origin and angular acceleration (see
    :mod:`acausal2d.derived`)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()

    def equations(self):
        f = self.frame_a
        g = self.world.g
        return [self.x == f.x, self.y == f.y, self.phi == f.phi,
                self.vx == der(self.x), self.vy == der(self.y), self.w == der(self.phi),
                self.m * der(der(self.x)) == f.fx + self.m * g[0],
                self.m * der(der(self.y)) == f.fy + self.m * g[1],
                self.I * der(der(self.phi)) == f.t]

    def shapes(self):
        return [{"type": "body", "x": "frame_a.x", "y": "frame_a.y"}]

    def topology(self):
        return [("rigid", [self.frame_a])]


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


class FixedRotation(Component):
    """Rigid rotation by the constant angle ``alpha`` (PlanarMechanics
    Parts.FixedRotation): frame_b has frame_a's origin and the angle
    ``frame_a.phi + alpha``; forces and torque pass unchanged (Ebert 2015,
    Anhang A.1 placement of a frame, eq. 4.1 at the frames)."""
    alpha = Parameter(0.0, "rad", "angle of frame_b against frame_a")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()
        self.frame_b = Frame()

    def equations(self):
        a, b = self.frame_a, self.frame_b
        return [b.x == a.x, b.y == a.y, b.phi == a.phi + self.alpha,
                a.fx + b.fx == 0, a.fy + b.fy == 0, a.t + b.t == 0]

    def shapes(self):
        """A small mark at the common origin (the element has no extent)."""
        return [{"type": "sensor", "points": [["frame_a.x", "frame_a.y"]]}]

    def topology(self):
        return [("rigid", [self.frame_a, self.frame_b])]


_BODY_SHAPES = ("rod", "box")


class BodyShape(Component):
    """Rigid link with mass (PlanarMechanics Parts.BodyShape): frame_b at
    ``r`` from frame_a (resolved in frame_a, as :class:`FixedTranslation`),
    the centre of mass at ``r_CM`` from frame_a, mass ``m`` and inertia
    ``I`` about the centre of mass, under the world's gravity (Ebert 2015, Anhang
    A.2/A.3: centre-of-gravity transform and inertia forces).

    Newton-Euler at the centre of mass C:
    ``m der(der(r_C)) = f_a + f_b + m g`` and
    ``I der(der(phi)) = t_a + t_b + (r_a - r_C) x f_a + (r_b - r_C) x f_b``.

    Drawn as a rod (``shape='rod'``) or a box (``shape='box'``) of width
    ``width`` from frame_a to frame_b, with the mass at C.  Variables: x, y
    (centre of mass), phi, vx, vy, w."""
    world = Outer(PlanarWorld)
    r = Parameter((1.0, 0.0), "m", "vector from frame_a to frame_b, in frame_a")
    r_CM = Parameter((0.5, 0.0), "m", "vector from frame_a to the centre of mass, in frame_a")
    m = Parameter(1.0, "kg", "mass", min=0.0)
    I = Parameter(0.1, "kg.m2", "rotational inertia about the centre of mass", min=0.0)
    width = Parameter(0.1, "m", "width of the drawn rod or box", positive=True)
    x = Variable(unit="m", doc="x position of the centre of mass")
    y = Variable(unit="m", doc="y position of the centre of mass")
    phi = Variable(unit="rad", doc="angle")
    vx = Variable(unit="m/s", doc="x velocity of the centre of mass")
    vy = Variable(unit="m/s", doc="y velocity of the centre of mass")
    w = Variable(unit="rad/s", doc="angular velocity")
    modelica_names = {"body." + k: v for k, v in Body.modelica_names.items()}
    modelica_names.update({"body.phi": "phi", "body.w": "w", "body.z": "z"})
    derived_signals = Body.derived_signals

    def __init__(self, shape="rod", **kw):
        super().__init__(**kw)
        if shape not in _BODY_SHAPES:
            raise ModelDefinitionError("%s: shape must be one of %s, not %r"
                                       % (type(self).__name__, ", ".join(_BODY_SHAPES), shape))
        self.shape = shape
        self.frame_a = Frame()
        self.frame_b = Frame()

    def equations(self):
        a, b, g = self.frame_a, self.frame_b, self.world.g
        rbx, rby = rotate(a.phi, self.r[0], self.r[1])
        rcx, rcy = rotate(a.phi, self.r_CM[0], self.r_CM[1])
        moment = (-rcx * a.fy + rcy * a.fx) + ((rbx - rcx) * b.fy - (rby - rcy) * b.fx)
        return [b.x == a.x + rbx, b.y == a.y + rby, b.phi == a.phi,
                self.x == a.x + rcx, self.y == a.y + rcy, self.phi == a.phi,
                self.vx == der(self.x), self.vy == der(self.y), self.w == der(self.phi),
                self.m * der(der(self.x)) == a.fx + b.fx + self.m * g[0],
                self.m * der(der(self.y)) == a.fy + b.fy + self.m * g[1],
                self.I * der(der(self.phi)) == a.t + b.t + moment]

    def shapes(self):
        ends = {"a": ["frame_a.x", "frame_a.y"], "b": ["frame_b.x", "frame_b.y"]}
        if self.shape == "box":
            first = dict(type="box", width=float(self.parameter_value("width")), **ends)
        else:
            first = {"type": "link", "points": [ends["a"], ends["b"]],
                     "width": float(self.parameter_value("width"))}
        return [first, {"type": "body", "x": "x", "y": "y"}]

    def topology(self):
        return [("rigid", [self.frame_a, self.frame_b])]
