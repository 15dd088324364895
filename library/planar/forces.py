"""Planar force elements with the semantics of PlanarMechanics 2.0
(Parts.Spring, Parts.Damper, Parts.SpringDamper, Sources.WorldForce,
Sources.WorldTorque, Sources.RelativeForce), as described in the project's
reference README, section "Further component kinds", and the line
spring-damper :class:`LineSpringDamper` (Ebert 2015, Bild 4.1; the line-force
semantics of Modelica.Mechanics.MultiBody.Forces.SpringDamperParallel).

Sign of flows (Ebert 2015, eq. 4.1): the flows (fx, fy, t) of a frame are the
force and torque acting ON the element through that frame; the element
pushes the part attached there with their negative.

``resolve_in_frame`` of the sources says in which frame the force signals
are given: ``"world"``, ``"frame_a"``, ``"frame_b"`` (the signals are
components along the axes of that frame and turn with it) or
``"frame_resolve"`` (an extra frame connector ``frame_resolve`` that takes
no force and must be connected).
"""
import casadi as ca

from acausal2d import Component, der, Frame, Parameter, RealInput, Variable
from acausal2d.errors import ModelDefinitionError

from .base import rotate

__all__ = ["Spring", "Damper", "SpringDamper", "LineSpringDamper", "WorldForce", "WorldTorque", "RelativeForce",
           "check_resolve_choice", "resolve_frame_angle", "resolve_frame_equations"]


def _ends():
    """The two frame origins as shape points."""
    return {"a": ["frame_a.x", "frame_a.y"], "b": ["frame_b.x", "frame_b.y"]}


class _WorldAxisSpring(Component):
    """Shared part of :class:`Spring` and :class:`SpringDamper`: the
    world-axis offsets and the forces of the two axis springs."""
    c_x = Parameter(1.0, "N/m", "spring constant in world x", min=0.0)
    c_y = Parameter(1.0, "N/m", "spring constant in world y", min=0.0)
    c_phi = Parameter(1.0e5, "N.m/rad", "rotational spring constant", min=0.0)
    s_relx0 = Parameter(0.0, "m", "unstretched x offset")
    s_rely0 = Parameter(0.0, "m", "unstretched y offset")
    phi_rel0 = Parameter(0.0, "rad", "unstretched relative angle")
    s_relx = Variable(unit="m", doc="x_b - x_a")
    s_rely = Variable(unit="m", doc="y_b - y_a")
    phi_rel = Variable(unit="rad", doc="phi_b - phi_a")
    f_x = Variable(unit="N", doc="force of the x spring (on frame_b: -f_x)")
    f_y = Variable(unit="N", doc="force of the y spring (on frame_b: -f_y)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()
        self.frame_b = Frame()

    def _offsets(self):
        a, b = self.frame_a, self.frame_b
        return [self.s_relx == b.x - a.x, self.s_rely == b.y - a.y,
                self.phi_rel == b.phi - a.phi,
                b.fx == self.f_x, a.fx == -self.f_x, b.fy == self.f_y, a.fy == -self.f_y]


class Spring(_WorldAxisSpring):
    """PlanarMechanics Parts.Spring: NOT a line spring but two independent
    linear springs on the world-x and world-y offsets of the frame origins,
    ``f_x = c_x (s_relx - s_relx0)``, ``f_y = c_y (s_rely - s_rely0)``
    (never rotated into a body frame).  The frame_b part is pushed with
    (-f_x, -f_y), the frame_a part with (+f_x, +f_y); both frame torques
    are zero.  ``c_phi`` and ``phi_rel0`` are declared, as in
    PlanarMechanics, but take part in no equation (``phi_rel`` is only
    reported).  Stored energy ``energy = c_x (s_relx - s_relx0)^2/2 +
    c_y (s_rely - s_rely0)^2/2``.  Ebert (2015), eq. 4.1 at the frames."""
    energy = Variable(unit="J", doc="energy stored in the two axis springs")

    def equations(self):
        dx, dy = self.s_relx - self.s_relx0, self.s_rely - self.s_rely0
        return self._offsets() + [
            self.f_x == self.c_x * dx, self.f_y == self.c_y * dy,
            self.frame_a.t == 0, self.frame_b.t == 0,
            self.energy == 0.5 * self.c_x * dx ** 2 + 0.5 * self.c_y * dy ** 2]

    def shapes(self):
        return [dict(type="spring", **_ends())]


class SpringDamper(_WorldAxisSpring):
    """PlanarMechanics Parts.SpringDamper: the :class:`Spring` with a
    viscous term per world axis, ``f_x = c_x (s_relx - s_relx0) + d_x
    der(s_relx)`` (``f_y`` likewise), and, unlike the Spring, an active
    rotational part ``tau = c_phi (phi_rel - phi_rel0) + d_phi
    der(phi_rel)``.  The frame_b part receives (-f_x, -f_y) and -tau, the
    frame_a part (+f_x, +f_y) and +tau.  ``energy`` is the energy stored in
    the three springs, ``loss_power = d_x v_relx^2 + d_y v_rely^2 + d_phi
    w_rel^2`` the power dissipated.  Ebert (2015), eq. 4.1 at the frames."""
    d_x = Parameter(1.0, "N.s/m", "damping constant in world x", min=0.0)
    d_y = Parameter(1.0, "N.s/m", "damping constant in world y", min=0.0)
    d_phi = Parameter(1.0, "N.m.s/rad", "rotational damping constant", min=0.0)
    v_relx = Variable(unit="m/s", doc="der(s_relx)")
    v_rely = Variable(unit="m/s", doc="der(s_rely)")
    w_rel = Variable(unit="rad/s", doc="der(phi_rel)")
    tau = Variable(unit="N.m", doc="torque of the rotational part (on frame_b: -tau)")
    energy = Variable(unit="J", doc="energy stored in the springs")
    loss_power = Variable(unit="W", doc="power dissipated by the dampers")

    def equations(self):
        dx, dy = self.s_relx - self.s_relx0, self.s_rely - self.s_rely0
        dphi = self.phi_rel - self.phi_rel0
        return self._offsets() + [
            self.v_relx == der(self.s_relx), self.v_rely == der(self.s_rely),
            self.w_rel == der(self.phi_rel),
            self.f_x == self.c_x * dx + self.d_x * self.v_relx,
            self.f_y == self.c_y * dy + self.d_y * self.v_rely,
            self.tau == self.c_phi * dphi + self.d_phi * self.w_rel,
            self.frame_b.t == self.tau, self.frame_a.t == -self.tau,
            self.energy == 0.5 * (self.c_x * dx ** 2 + self.c_y * dy ** 2
                                  + self.c_phi * dphi ** 2),
            self.loss_power == self.d_x * self.v_relx ** 2 + self.d_y * self.v_rely ** 2
            + self.d_phi * self.w_rel ** 2]

    def shapes(self):
        return [dict(type="spring", **_ends()), dict(type="damper", offset=12, **_ends())]


class Damper(Component):
    """PlanarMechanics Parts.Damper: a line (point-to-point) damper without
    torques.  With ``r = r_b - r_a``, the unit vector ``e = r/|r|`` and
    ``v = e . (v_b - v_a)`` (the rate of change of the distance) it pushes
    the frame_b part with ``-d v e`` and the frame_a part with ``+d v e``
    and dissipates ``loss_power = d v^2``.

    PlanarMechanics divides by ``max(|r|, s_small)`` without events, so the
    force fades out when the origins coincide; here ``e = r/sqrt(|r|^2 +
    s_small^2)``, which is the same to a relative ``(s_small/|r|)^2/2``
    (below 1e-12 for |r| > 1e-4 m with the default s_small) and smooth
    through |r| = 0 (no event, no division by zero).  Ebert (2015), eq. 4.1 at the
    frames."""
    d = Parameter(1.0, "N.s/m", "damping constant", min=0.0)
    s_small = Parameter(1e-10, "m", "length below which the force fades out", positive=True)
    length = Variable(unit="m", doc="distance of the frame origins, |r|^2/sqrt(|r|^2 + s_small^2)")
    v = Variable(unit="m/s", doc="rate of change of the distance")
    f = Variable(unit="N", doc="damping force d v (pulls the frames together when > 0)")
    loss_power = Variable(unit="W", doc="power dissipated")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()
        self.frame_b = Frame()

    def equations(self):
        return _line_equations(self) + [self.f == self.d * self.v,
                                        self.loss_power == self.d * self.v ** 2]

    def shapes(self):
        return [dict(type="damper", **_ends())]


def _line_equations(comp):
    """The line kinematics and forces shared by :class:`Damper` and
    :class:`LineSpringDamper`: ``length``, its rate ``v`` and the frame
    flows of the line force ``f`` (tension positive) along ``e = r/sqrt(|r|^2
    + s_small^2)``, no frame torques."""
    a, b = comp.frame_a, comp.frame_b
    rx, ry = b.x - a.x, b.y - a.y
    norm = ca.sqrt(rx ** 2 + ry ** 2 + comp.s_small ** 2)
    ex, ey = rx / norm, ry / norm
    return [comp.length == (rx ** 2 + ry ** 2) / norm,
            comp.v == ex * der(rx) + ey * der(ry),
            b.fx == comp.f * ex, b.fy == comp.f * ey,
            a.fx == -comp.f * ex, a.fy == -comp.f * ey,
            a.t == 0, b.t == 0]


class LineSpringDamper(Component):
    """A linear spring and a viscous damper in parallel acting along the
    line between the origins of frame_a and frame_b: the 2D spring-damper
    of Ebert (2015), Bild 4.1 (ch. 4.1: the planar spring-damper-mass oscillator,
    whose elements the dissertation does not define) with the line-force
    semantics of Modelica.Mechanics.MultiBody.Forces.SpringDamperParallel:
    with the distance ``length = |r_b - r_a|`` and its rate ``v``,

        f = c (length - s_unstretched) + d v,

    tension positive: for ``f > 0`` the parts at frame_a and frame_b are
    pulled towards each other with ``f`` along the line (frame flows, Ebert (2015),
    eq. 4.1: ``frame_b.f = f e``, ``frame_a.f = -f e``, no torques).  The
    element declares position-level quantities only (length, force); it
    pushes as well as pulls (a band, which only pulls, is
    :class:`acausal2d.library.belt.Belt`, Ebert (2015), eq. 4.52-4.66).  ``energy``
    is the energy of the spring, ``loss_power = d v^2`` the power of the
    damper.  The unit vector is ``e = r/sqrt(|r|^2 + s_small^2)`` as in
    :class:`Damper` (the same to a relative ``(s_small/|r|)^2/2``, smooth
    through |r| = 0)."""
    c = Parameter(1.0e4, "N/m", "spring constant", min=0.0)
    d = Parameter(0.0, "N.s/m", "damping constant", min=0.0)
    s_unstretched = Parameter(0.1, "m", "unstretched spring length", min=0.0)
    s_small = Parameter(1e-10, "m", "length below which the direction fades out", positive=True)
    length = Variable(unit="m", doc="distance of the frame origins, |r|^2/sqrt(|r|^2 + s_small^2)")
    v = Variable(unit="m/s", doc="rate of change of the distance")
    f = Variable(unit="N", doc="line force, tension positive (pulls the frames together)")
    energy = Variable(unit="J", doc="energy stored in the spring")
    loss_power = Variable(unit="W", doc="power dissipated by the damper")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame_a = Frame()
        self.frame_b = Frame()

    def equations(self):
        stretch = self.length - self.s_unstretched
        return _line_equations(self) + [
            self.f == self.c * stretch + self.d * self.v,
            self.energy == 0.5 * self.c * stretch ** 2,
            self.loss_power == self.d * self.v ** 2]

    def shapes(self):
        return [dict(type="spring", **_ends()), dict(type="damper", offset=12, **_ends())]


_ABSOLUTE = ("world", "frame_b", "frame_resolve")
_RELATIVE = ("world", "frame_a", "frame_b", "frame_resolve")


def check_resolve_choice(comp, choice, allowed):
    """Raise :class:`ModelDefinitionError` naming ``comp`` and the allowed
    values unless ``choice`` is one of ``allowed``; create the connector
    ``frame_resolve`` of ``comp`` (a frame that must be connected and
    takes no force) when ``choice`` asks for it."""
    if choice not in allowed:
        raise ModelDefinitionError("%s: resolve_in_frame must be one of %s, not %r"
                                   % (comp.describe(), ", ".join(repr(a) for a in allowed),
                                      choice))
    if choice == "frame_resolve":
        comp.frame_resolve = Frame(required=True)


def resolve_frame_angle(comp, choice):
    """The angle of the frame ``choice`` names for ``comp``: 0 for
    ``"world"``, else that frame connector's phi (symbolic)."""
    return 0.0 if choice == "world" else getattr(comp, choice).phi


def resolve_frame_equations(comp, choice):
    """``frame_resolve`` takes no force (when ``choice`` created it)."""
    if choice != "frame_resolve":
        return []
    f = comp.frame_resolve
    return [f.fx == 0, f.fy == 0, f.t == 0]


class _ForceSignals(Component):
    """Signal inputs force_x, force_y, torque and the resolve option."""

    def __init__(self, resolve_in_frame, allowed, **kw):
        super().__init__(**kw)
        self.frame_b = Frame()
        self.force_x = RealInput()
        self.force_y = RealInput()
        self.torque = RealInput()
        check_resolve_choice(self, resolve_in_frame, allowed)
        self.resolve_in_frame = resolve_in_frame

    def _applied(self):
        """World components of the force the frame_b part receives."""
        psi = resolve_frame_angle(self, self.resolve_in_frame)
        return rotate(psi, self.force_x.u, self.force_y.u)


class WorldForce(_ForceSignals):
    """PlanarMechanics Sources.WorldForce: applies to the part at frame_b
    the force ``R(psi) (force_x, force_y)`` and the torque ``torque`` (the
    three signal inputs), the reaction going to the world.  ``psi`` is the
    angle of the frame ``resolve_in_frame`` names: ``"frame_b"`` (default:
    the signals are components along the attached body's own axes and
    turn with it), ``"world"`` (psi = 0) or ``"frame_resolve"``.
    Variables: ``fx``, ``fy`` (the applied force in world components) and
    ``tau`` (the applied torque).  Ebert (2015), eq. 4.1 at the frame."""
    fx = Variable(unit="N", doc="applied force, world x")
    fy = Variable(unit="N", doc="applied force, world y")
    tau = Variable(unit="N.m", doc="applied torque")

    def __init__(self, resolve_in_frame="frame_b", **kw):
        super().__init__(resolve_in_frame, _ABSOLUTE, **kw)

    def equations(self):
        fx, fy = self._applied()
        b = self.frame_b
        return [self.fx == fx, self.fy == fy, self.tau == self.torque.u,
                b.fx == -self.fx, b.fy == -self.fy, b.t == -self.tau] \
            + resolve_frame_equations(self, self.resolve_in_frame)

    def shapes(self):
        return [{"type": "arrow", "x": "frame_b.x", "y": "frame_b.y", "fx": "fx", "fy": "fy"},
                {"type": "torque", "x": "frame_b.x", "y": "frame_b.y", "t": "tau"}]


class WorldTorque(Component):
    """A torque from the signal input ``torque`` on the part at frame_b,
    the reaction going to the world (the torque part of PlanarMechanics'
    WorldForce).  A planar torque is the same in every frame, so
    ``resolve_in_frame`` (``"frame_b"``, ``"world"`` or
    ``"frame_resolve"``) is accepted for parity and changes nothing but the
    ``frame_resolve`` connector.  Variable ``tau``: the applied torque.
    Ebert (2015), eq. 4.1 at the frame."""
    tau = Variable(unit="N.m", doc="applied torque")

    def __init__(self, resolve_in_frame="frame_b", **kw):
        super().__init__(**kw)
        self.frame_b = Frame()
        self.torque = RealInput()
        check_resolve_choice(self, resolve_in_frame, _ABSOLUTE)
        self.resolve_in_frame = resolve_in_frame

    def equations(self):
        b = self.frame_b
        return [self.tau == self.torque.u, b.fx == 0, b.fy == 0, b.t == -self.tau] \
            + resolve_frame_equations(self, self.resolve_in_frame)

    def shapes(self):
        return [{"type": "torque", "x": "frame_b.x", "y": "frame_b.y", "t": "tau"}]


class RelativeForce(_ForceSignals):
    """PlanarMechanics Sources.RelativeForce: the part at frame_b receives
    the force ``R(psi) (force_x, force_y)`` and the torque ``torque``, the
    part at frame_a the opposite force and torque (like PlanarMechanics,
    no couple is added for the offset of the two origins).  ``psi``: the
    angle of ``resolve_in_frame`` = ``"frame_a"`` (default), ``"frame_b"``,
    ``"world"`` or ``"frame_resolve"``.  Variables ``fx``, ``fy``, ``tau``:
    force (world components) and torque on the frame_b part.  Ebert (2015), eq. 4.1
    at the frames."""
    fx = Variable(unit="N", doc="force on the frame_b part, world x")
    fy = Variable(unit="N", doc="force on the frame_b part, world y")
    tau = Variable(unit="N.m", doc="torque on the frame_b part")

    def __init__(self, resolve_in_frame="frame_a", **kw):
        super().__init__(resolve_in_frame, _RELATIVE, **kw)
        self.frame_a = Frame()

    def equations(self):
        fx, fy = self._applied()
        a, b = self.frame_a, self.frame_b
        return [self.fx == fx, self.fy == fy, self.tau == self.torque.u,
                b.fx == -self.fx, b.fy == -self.fy, b.t == -self.tau,
                a.fx + b.fx == 0, a.fy + b.fy == 0, a.t + b.t == 0] \
            + resolve_frame_equations(self, self.resolve_in_frame)

    def shapes(self):
        """The force and torque on each part: the frame_b part receives the
        flows of frame_a and vice versa."""
        out = []
        for here, other in (("frame_b", "frame_a"), ("frame_a", "frame_b")):
            out += [{"type": "arrow", "x": here + ".x", "y": here + ".y",
                     "fx": other + ".fx", "fy": other + ".fy"},
                    {"type": "torque", "x": here + ".x", "y": here + ".y", "t": other + ".t"}]
        return out
