"""Drives and measuring modules for the linkage elements (Ebert 2015, ch. 3.2, 4.2,
7.1: ``preset1`` and the VDI 2729 measuring modules).

* :class:`Preset` - motion preset for a rotational flange (angle) or a
  translational flange (position): constant speed, polynomial of time, or a
  table with smooth (C2 cubic spline) interpolation.  It also reports the
  drive torque/force it applies and the drive power.
* :class:`TorqueSource`, :class:`ForceSource` - constant or time-function
  torque/force on a flange (reaction to ground).
* :class:`RelativeAngle`, :class:`RelativePosition` - relative angle and
  relative displacement of two planar frames (pure measurement, no forces).
* :class:`RelativeDisplacement` - s_b - s_a of two translational flanges.
* :class:`TorqueSensor`, :class:`ForceSensor` - torque/force passed through
  and the power.

All positions are position-level equations; velocities (``w``/``v``) and
power use ``der()`` of the compiler.
"""
import casadi as ca
import numpy as np

from acausal2d import (Component, der, Frame, Parameter, RotationalFlange, time,
                       TranslationalFlange, Variable)
from acausal2d.errors import ModelDefinitionError

__all__ = ["Preset", "TorqueSource", "ForceSource", "RelativeAngle", "RelativePosition",
           "RelativeDisplacement", "TorqueSensor", "ForceSensor"]

_KINDS = ("speed", "polynomial", "table")


def _spline_expr(t, table):
    """C2 cubic spline through ``table`` [(t_k, y_k), ...] as a CasADi
    expression of t (piecewise with if_else on time: time events); outside
    the table the end pieces are extended."""
    from scipy.interpolate import CubicSpline
    tab = np.asarray(table, dtype=float)
    if tab.ndim != 2 or tab.shape[1] != 2 or tab.shape[0] < 2:
        raise ModelDefinitionError("Preset table must be a list of at least two (t, value) pairs")
    if np.any(np.diff(tab[:, 0]) <= 0):
        raise ModelDefinitionError("Preset table times must increase strictly")
    if tab.shape[0] == 2:
        k = (tab[1, 1] - tab[0, 1]) / (tab[1, 0] - tab[0, 0])
        return tab[0, 1] + k * (t - tab[0, 0])
    cs = CubicSpline(tab[:, 0], tab[:, 1], bc_type="not-a-knot" if len(tab) > 3 else "natural")
    x, c = cs.x, cs.c

    def piece(i):
        dt = t - x[i]
        return ((c[0, i] * dt + c[1, i]) * dt + c[2, i]) * dt + c[3, i]
    expr = piece(len(x) - 2)
    for i in range(len(x) - 3, -1, -1):
        expr = ca.if_else(t < x[i + 1], piece(i), expr)
    return expr


class Preset(Component):
    """Motion preset (the dissertation's ``preset1``): prescribes the angle of a
    rotational flange (default) or, with ``translational=True``, the position
    of a translational flange.

    kind='speed': ``phi = phi0 + om t`` (constant speed, Anhang C: om = 1.5
    rad/s, phi0 = 0); kind='polynomial': ``phi = sum a[k] t^k`` (k = 0..5);
    kind='table': C2 cubic spline through ``table=[(t, phi), ...]`` (the
    table is structural: changing it recompiles).  Outputs: ``phi`` (angle or
    position), ``w = der(phi)``, ``tau`` the torque (force) the preset
    applies to the driven flange and ``power = tau w`` (drive torque and
    power, as the VDI measuring modules).  The reaction goes to ground;
    with ``use_support=True`` it goes to the flange ``support`` and the
    preset prescribes the flange's position relative to it (a drive between
    two moving links, Modelica's useSupport; e.g. a SAN's guide flange
    ``ctrT1``).
    """
    om = Parameter(1.0, "rad/s", "speed (kind 'speed'; m/s when translational)")
    phi0 = Parameter(0.0, "rad", "angle (position) at t = 0 (kind 'speed')")
    a = Parameter((0.0, 0.0, 0.0, 0.0, 0.0, 0.0), "", "polynomial coefficients a0..a5")

    phi = Variable(unit="rad", doc="prescribed angle (position)")
    w = Variable(unit="rad/s", doc="prescribed speed")
    tau = Variable(unit="N.m", doc="drive torque (force) applied to the flange")
    power = Variable(unit="W", doc="drive power tau * w")

    def __init__(self, kind="speed", table=None, translational=False, use_support=False, **kw):
        super().__init__(**kw)
        if kind not in _KINDS:
            raise ModelDefinitionError("Preset kind must be one of %s, not %r"
                                       % (", ".join(_KINDS), kind))
        if kind == "table" and table is None:
            raise ModelDefinitionError("Preset(kind='table') needs table=[(t, value), ...]")
        self.kind = kind
        self.table = table
        self.translational = translational
        self.flange = TranslationalFlange() if translational else RotationalFlange()
        self.use_support = use_support
        if use_support:
            self.support = TranslationalFlange() if translational else RotationalFlange()

    def topology(self):
        """Nothing: the dissertation's eq. 2.1 counts the degree of freedom of the
        mechanism; a preset uses that DOF up (the driven flange follows the
        motion) but adds no link or joint to the planar chain."""
        return []

    def motion(self, t):
        """The prescribed angle (position) as an expression of time t."""
        if self.kind == "speed":
            return self.phi0 + self.om * t
        if self.kind == "polynomial":
            return sum(self.a[k] * t ** k for k in range(6))
        return _spline_expr(t, self.table)

    def _linkage_seed(self):
        """Start pose for the linkage pre-assembly: position and speed at t = 0
        (the motion holds parameters and time only: its time derivative is
        the partial one, also outside a flattening)."""
        pot = "s" if self.translational else "phi"
        w0 = ca.substitute(ca.jacobian(ca.SX(self.motion(time)), time), time, ca.SX(0.0))
        return [(self.flange, {pot: self.motion(0.0), "w": w0})]

    def equations(self):
        pot = self.flange.s if self.translational else self.flange.phi
        flow = self.flange.f if self.translational else self.flange.tau
        eqs = [self.phi == self.motion(time), self.w == der(self.phi), self.tau == -flow,
               self.power == self.tau * self.w]
        if not self.use_support:
            return eqs + [pot == self.phi]
        pot_s = self.support.s if self.translational else self.support.phi
        flow_s = self.support.f if self.translational else self.support.tau
        return eqs + [pot - pot_s == self.phi, flow_s == -flow]


class TorqueSource(Component):
    """Torque ``tau`` (parameter; or ``func(time)`` if given) acting on the
    flange, reaction to ground."""
    tau = Parameter(0.0, "N.m", "torque (used when func is None)")

    def __init__(self, func=None, **kw):
        super().__init__(**kw)
        self.func = func
        self.flange = RotationalFlange()

    def equations(self):
        value = self.tau if self.func is None else self.func(time)
        return [self.flange.tau == -value]


class ForceSource(Component):
    """Force ``f`` (parameter; or ``func(time)``) acting on a translational
    flange, reaction to ground."""
    f = Parameter(0.0, "N", "force (used when func is None)")

    def __init__(self, func=None, **kw):
        super().__init__(**kw)
        self.func = func
        self.flange = TranslationalFlange()

    def equations(self):
        value = self.f if self.func is None else self.func(time)
        return [self.flange.f == -value]


class _FramePair(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame()
        self.ctr2D2 = Frame()

    def _no_forces(self):
        out = []
        for f in (self.ctr2D1, self.ctr2D2):
            out += [f.fx == 0, f.fy == 0, f.t == 0]
        return out


class RelativeAngle(_FramePair):
    """Relative angle ``phi_rel = ctr2D2.phi - ctr2D1.phi`` of two planes
    (VDI measuring module), no forces."""
    phi_rel = Variable(unit="rad", doc="relative angle")

    def equations(self):
        return self._no_forces() + [self.phi_rel == self.ctr2D2.phi - self.ctr2D1.phi]


class RelativePosition(_FramePair):
    """Relative position of point 2 against point 1 (VDI measuring module),
    no forces: ``dx, dy`` in the world frame and ``s_rel, n_rel`` resolved in
    frame 1 (``s_rel`` is a relative slider travel when frame 1 is a guide)."""
    dx = Variable(unit="m", doc="x2 - x1")
    dy = Variable(unit="m", doc="y2 - y1")
    s_rel = Variable(unit="m", doc="displacement along the x-axis of frame 1")
    n_rel = Variable(unit="m", doc="displacement along the y-axis of frame 1")

    def equations(self):
        a, b = self.ctr2D1, self.ctr2D2
        c, s = ca.cos(a.phi), ca.sin(a.phi)
        return self._no_forces() + [
            self.dx == b.x - a.x, self.dy == b.y - a.y,
            self.s_rel == c * self.dx + s * self.dy,
            self.n_rel == -s * self.dx + c * self.dy]


class RelativeDisplacement(Component):
    """``s_rel = flange_b.s - flange_a.s`` of two translational flanges, no force."""
    s_rel = Variable(unit="m", doc="relative displacement")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()

    def equations(self):
        return [self.s_rel == self.flange_b.s - self.flange_a.s,
                self.flange_a.f == 0, self.flange_b.f == 0]


class TorqueSensor(Component):
    """Torque ``tau`` passed from flange_a to flange_b (acting on the part at
    flange_b) and the power ``tau * der(phi)``."""
    tau = Variable(unit="N.m", doc="torque through the sensor")
    power = Variable(unit="W", doc="power through the sensor")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange()
        self.flange_b = RotationalFlange()

    def equations(self):
        a, b = self.flange_a, self.flange_b
        return [a.phi == b.phi, a.tau + b.tau == 0, self.tau == a.tau,
                self.power == self.tau * der(a.phi)]


class ForceSensor(Component):
    """Force ``f`` passed from flange_a to flange_b and the power ``f der(s)``."""
    f = Variable(unit="N", doc="force through the sensor")
    power = Variable(unit="W", doc="power through the sensor")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = TranslationalFlange()
        self.flange_b = TranslationalFlange()

    def equations(self):
        a, b = self.flange_a, self.flange_b
        return [a.s == b.s, a.f + b.f == 0, self.f == a.f,
                self.power == self.f * der(a.s)]
