"""Planar sensors with the semantics of PlanarMechanics 2.0 (Sensors.*), as
described in the project's reference README, section "Further component
kinds".

Kinematic sensors put no force or torque on any frame; CutForce, CutTorque
and Power are ideal pass-throughs from frame_a to frame_b (same position
and angle, forces and torque passed unchanged).  Outputs are signal
connectors (``RealOutput``), so they can drive signal blocks; in a result
they are read as ``"sensor.output.u"`` (e.g. ``"absolutePosition.phi.u"``).
Vector outputs are split into ``_x`` and ``_y`` components along the axes
of the frame ``resolve_in_frame`` names:

- absolute sensors: ``"world"``, ``"frame_a"`` (default, as in
  PlanarMechanics) or ``"frame_resolve"``;
- relative sensors: ``"world"``, ``"frame_a"`` (default), ``"frame_b"``
  or ``"frame_resolve"``;

``"frame_resolve"`` adds a frame connector ``frame_resolve`` that takes no
force and must be connected.  Ebert (2015), eq. 4.1: the frame flows are the forces
acting on the sensor (zero for the kinematic sensors).
"""
import casadi as ca

from acausal2d import Component, der, Frame, Parameter, RealOutput

from .base import resolve, rotate
from .forces import check_resolve_choice, resolve_frame_angle, resolve_frame_equations

__all__ = ["AbsolutePosition", "AbsoluteVelocity", "AbsoluteAcceleration", "RelativePosition",
           "RelativeVelocity", "RelativeAcceleration", "CutForce", "CutTorque", "Power",
           "Distance"]

_ABSOLUTE = ("world", "frame_a", "frame_resolve")
_RELATIVE = ("world", "frame_a", "frame_b", "frame_resolve")


def _mark(*frames):
    return [{"type": "sensor", "points": [[f + ".x", f + ".y"] for f in frames]}]


def _modelica_names(outputs):
    """PlanarMechanics names of the outputs: a vector ``r`` is the array
    ``r[2]`` there (``r[1]`` -> ``r_x.u``, ``r[2]`` -> ``r_y.u``), a scalar
    ``phi`` is ``phi`` (-> ``phi.u``)."""
    names = {}
    for o in outputs:
        for axis, k in (("_x", 1), ("_y", 2)):
            if o.endswith(axis):
                names["%s[%d]" % (o[:-2], k)] = o + ".u"
        names.setdefault(o, o + ".u")
    return names


class _Sensor(Component):
    """Frames, outputs and the resolve option of a sensor.  Subclasses
    declare ``modelica_names`` (PlanarMechanics array names of their
    outputs, read by ``compare``) from their ``OUTPUTS``."""
    FRAMES: tuple[str, ...] = ("frame_a",)
    OUTPUTS: tuple[str, ...] = ()
    CHOICES: tuple[str, ...] = _ABSOLUTE

    def __init_subclass__(cls, **kw):
        super().__init_subclass__(**kw)
        cls.modelica_names = _modelica_names(cls.OUTPUTS)

    def __init__(self, resolve_in_frame="frame_a", **kw):
        super().__init__(**kw)
        for name in self.FRAMES:
            setattr(self, name, Frame())
        for name in self.OUTPUTS:
            setattr(self, name, RealOutput())
        check_resolve_choice(self, resolve_in_frame, self.CHOICES)
        self.resolve_in_frame = resolve_in_frame

    def _psi(self):
        return resolve_frame_angle(self, self.resolve_in_frame)

    def _passive(self):
        """No force or torque on any frame."""
        eqs = resolve_frame_equations(self, self.resolve_in_frame)
        for name in self.FRAMES:
            f = getattr(self, name)
            eqs += [f.fx == 0, f.fy == 0, f.t == 0]
        return eqs

    def _out(self, names, values):
        return [getattr(self, n).u == v for n, v in zip(names, values)]

    def shapes(self):
        return _mark(*self.FRAMES)


class AbsolutePosition(_Sensor):
    """Position and angle of frame_a (PlanarMechanics
    Sensors.AbsolutePosition): ``(r_x, r_y) = R(psi)^T (x, y)`` and ``phi =
    frame_a.phi - psi``, psi the angle of the resolve frame (world: the
    plain x, y, phi).  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    OUTPUTS = ("r_x", "r_y", "phi")

    def equations(self):
        a, psi = self.frame_a, self._psi()
        return self._passive() + self._out(self.OUTPUTS,
                                           resolve(psi, a.x, a.y) + (a.phi - psi,))


class AbsoluteVelocity(_Sensor):
    """Velocity of frame_a's origin (PlanarMechanics
    Sensors.AbsoluteVelocity): ``(v_x, v_y) = R(psi)^T der((x, y))`` and
    ``w = der(phi)``.  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    OUTPUTS = ("v_x", "v_y", "w")

    def equations(self):
        a, psi = self.frame_a, self._psi()
        return self._passive() + self._out(
            self.OUTPUTS, resolve(psi, der(a.x), der(a.y)) + (der(a.phi),))


class AbsoluteAcceleration(_Sensor):
    """Acceleration of frame_a's origin (PlanarMechanics
    Sensors.AbsoluteAcceleration): ``(a_x, a_y) = R(psi)^T
    der(der((x, y)))`` and ``z = der(der(phi))``.  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    OUTPUTS = ("a_x", "a_y", "z")

    def equations(self):
        a, psi = self.frame_a, self._psi()
        return self._passive() + self._out(
            self.OUTPUTS, resolve(psi, der(der(a.x)), der(der(a.y))) + (der(der(a.phi)),))


class RelativePosition(_Sensor):
    """Position of frame_b against frame_a (PlanarMechanics
    Sensors.RelativePosition): ``(r_rel_x, r_rel_y) = R(psi)^T (r_b -
    r_a)``, ``phi_rel = phi_b - phi_a``.  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    FRAMES = ("frame_a", "frame_b")
    OUTPUTS = ("r_rel_x", "r_rel_y", "phi_rel")
    CHOICES = _RELATIVE

    def equations(self):
        a, b, psi = self.frame_a, self.frame_b, self._psi()
        return self._passive() + self._out(
            self.OUTPUTS, resolve(psi, b.x - a.x, b.y - a.y) + (b.phi - a.phi,))


def _relative_velocity(sensor):
    """PlanarMechanics' relative velocity: the offset q = R(phi_a)^T (r_b -
    r_a), resolved in frame_a, is differentiated as it stands and the
    result re-expressed in the resolve frame: R(psi)^T R(phi_a) der(q)."""
    a, b = sensor.frame_a, sensor.frame_b
    qx, qy = resolve(a.phi, b.x - a.x, b.y - a.y)
    wx, wy = rotate(a.phi, der(qx), der(qy))
    return resolve(sensor._psi(), wx, wy)


class RelativeVelocity(_Sensor):
    """Relative velocity (PlanarMechanics Sensors.RelativeVelocity): the
    offset ``q = R(phi_a)^T (r_b - r_a)`` is differentiated in frame_a's
    axes and re-expressed in the resolve frame, ``v_rel = R(psi)^T R(phi_a)
    der(q)`` (for psi = phi_a simply der(q)); ``w_rel = der(phi_b -
    phi_a)``.  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    FRAMES = ("frame_a", "frame_b")
    OUTPUTS = ("v_rel_x", "v_rel_y", "w_rel")
    CHOICES = _RELATIVE

    def equations(self):
        a, b = self.frame_a, self.frame_b
        return self._passive() + self._out(
            self.OUTPUTS, _relative_velocity(self) + (der(b.phi - a.phi),))


class RelativeAcceleration(_Sensor):
    """Relative acceleration (PlanarMechanics Sensors.RelativeAcceleration):
    ``a_rel = der(v_rel)`` of the :class:`RelativeVelocity` vector in the
    same resolve frame, differentiated as it stands (no rotation terms
    added); ``z_rel = der(der(phi_b - phi_a))``.  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    FRAMES = ("frame_a", "frame_b")
    OUTPUTS = ("a_rel_x", "a_rel_y", "z_rel")
    CHOICES = _RELATIVE

    def equations(self):
        a, b = self.frame_a, self.frame_b
        vx, vy = _relative_velocity(self)
        return self._passive() + self._out(
            self.OUTPUTS, (der(vx), der(vy), der(der(b.phi - a.phi))))


class _PassThrough(_Sensor):
    """frame_a and frame_b coincide; forces and torque pass unchanged."""
    FRAMES = ("frame_a", "frame_b")

    def _through(self):
        a, b = self.frame_a, self.frame_b
        return [a.x == b.x, a.y == b.y, a.phi == b.phi,
                a.fx + b.fx == 0, a.fy + b.fy == 0, a.t + b.t == 0] \
            + resolve_frame_equations(self, self.resolve_in_frame)

    def shapes(self):
        return _mark("frame_a")

    def topology(self):
        """frame_a and frame_b are one point of one link (Ebert 2015, eq. 2.1)."""
        return [("rigid", [self.frame_a, self.frame_b])]


class CutForce(_PassThrough):
    """Cut force (PlanarMechanics Sensors.CutForce): an ideal pass-through
    from frame_a to frame_b whose output is the force flowing in at
    frame_a, ``(f_x, f_y) = R(psi)^T (frame_a.fx, frame_a.fy)`` (default
    resolve frame: frame_a).  No influence on the motion.  Ebert (2015), eq. 4.1 (the flows
    pass from frame_a to frame_b)."""
    OUTPUTS = ("f_x", "f_y")

    def equations(self):
        a = self.frame_a
        return self._through() + self._out(self.OUTPUTS, resolve(self._psi(), a.fx, a.fy))


class CutTorque(_PassThrough):
    """Cut torque (PlanarMechanics Sensors.CutTorque): pass-through from
    frame_a to frame_b; output ``torque = frame_a.t``.  A planar torque is
    the same in every frame; ``resolve_in_frame`` is accepted for
    parity.  Ebert (2015), eq. 4.1 (the flows
    pass from frame_a to frame_b)."""
    OUTPUTS = ("torque",)

    def equations(self):
        return self._through() + self._out(self.OUTPUTS, (self.frame_a.t,))


class Power(_PassThrough):
    """Power flowing from frame_a to frame_b (PlanarMechanics
    Sensors.Power): ``power = (frame_a.fx, frame_a.fy) . der((x, y)) +
    frame_a.t der(phi)``, the power the frame_a side delivers into the
    frame_b side through the cut.  Ebert (2015), eq. 4.1 (the flows
    pass from frame_a to frame_b)."""
    OUTPUTS = ("power",)

    def __init__(self, **kw):
        super().__init__("world", **kw)

    def equations(self):
        a = self.frame_a
        return self._through() + self._out(
            self.OUTPUTS, (a.fx * der(a.x) + a.fy * der(a.y) + a.t * der(a.phi),))


class Distance(_Sensor):
    """Distance of the frame origins (PlanarMechanics Sensors.Distance),
    no forces.  PlanarMechanics smooths the square root below ``s_small``;
    here ``distance = L^2/sqrt(L^2 + s_small^2)``, L = |r_b - r_a|: equal
    to L to a relative ``(s_small/L)^2/2``, zero with zero slope at L = 0
    (smooth, no event).  Ebert (2015), Anhang A.1 (frame
    transforms), eq. 4.1 (zero flows)."""
    FRAMES = ("frame_a", "frame_b")
    OUTPUTS = ("distance",)
    s_small = Parameter(1e-10, "m", "length below which the distance is smoothed",
                        positive=True)

    def __init__(self, **kw):
        super().__init__("world", **kw)

    def equations(self):
        a, b = self.frame_a, self.frame_b
        L2 = (b.x - a.x) ** 2 + (b.y - a.y) ** 2
        return self._passive() + self._out(self.OUTPUTS,
                                           (L2 / ca.sqrt(L2 + self.s_small ** 2),))
