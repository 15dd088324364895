"""A rope end driven along a straight line by a signal (for pulling a rope
with a drive function, as the dissertation's drum drive functions of ch. 8.1).
"""
import casadi as ca

from acausal2d import (Frame, Parameter, RealInput,
                       Variable)

from .base import _PI, _BandElement, _num


class RopeDrive(_BandElement):
    """A point driven along a straight line: ``frame`` is at
    ``(x0, y0) + s_in * (cos(angle), sin(angle))`` with angle 0; the force
    needed to move it is the reaction ``-frame.fx, -frame.fy``.  Use it to
    pull a rope end with a drive function (``s_in`` from a signal source);
    velocities follow by index reduction, so the signal must be twice
    differentiable."""
    x0 = Parameter(0.0, "m", "x at s = 0")
    y0 = Parameter(0.0, "m", "y at s = 0")
    angle = Parameter(-_PI / 2, "rad", "direction of motion (default: downwards)")
    F = Variable(unit="N", doc="pulling force along the direction of motion")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.frame = Frame()
        self.s_in = RealInput()

    def _band_geometry(self, name, poses):
        """Start geometry of the rope end for the tangent construction (a
        point at s = 0)."""
        return (float(_num(self, "x0")), float(_num(self, "y0")), 0.0)

    def equations(self):
        f = self.frame
        e = (ca.cos(self.angle), ca.sin(self.angle))
        return [f.x == self.x0 + self.s_in.u * e[0], f.y == self.y0 + self.s_in.u * e[1],
                f.phi == 0, self.F == -(f.fx * e[0] + f.fy * e[1])]

    def shapes(self):
        """The driven rope end as a joint."""
        return [{"type": "joint", "x": "frame.x", "y": "frame.y"}]
