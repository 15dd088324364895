"""Circular rope drum (end of Ebert (2015), ch. 4.4.4): the Bandrolle with one contact
point and the rope end fastened on the contour.
"""


from acausal2d import (BandPort, Frame, Parameter, Variable)

from .base import _PI
from .pulley import _Wheel


class Drum(_Wheel):
    """Circular rope drum: one contact point K1, rope end fixed on the
    contour (Ebert 2015, end of 4.4.4: the Bandrolle without ctrK2/ctrB2).

    Winding direction ``w_i`` as the pulley's at K1 (eq. 4.95): ``w_i=-1``
    (default) -- a positive turn winds the rope up; ``w = -w_i`` below (the
    deprecated constructor argument).  Placement and flanges as
    :class:`~acausal2d.library.belt.Pulley`.  The rope end is fastened
    at the angle ``alpha_fix`` of the drum frame; the rope stored on the drum
    is ``l_wound = w r (phi + alpha_fix - kappa1) + 2 pi r n_wound`` (an
    output; it must stay positive -- the drum does not model the rope
    running off its end).  Contact angle ``kappa1 = gamma1 + w pi/2``,
    ``ctrB1.L = -w r (phi - kappa1)`` and the forces as in :class:`Pulley`.
    """
    r = Parameter(0.05, "m", "radius of the belt contour", positive=True)
    alpha_fix = Parameter(0.0, "rad", "angle of the fastened rope end in the drum frame")
    n_wound = Parameter(0.0, "1", "whole turns of rope on the drum")
    kappa1 = Variable(unit="rad", state_select="avoid", doc="contact angle of K1 (world)")
    l_wound = Variable(unit="m", state_select="avoid", doc="rope length stored on the drum")

    def __init__(self, w=None, friction=False, **kw):
        super().__init__(w=w, friction=friction, **kw)
        self.ctrK1 = Frame(required=True, doc="contact point K1")
        self.ctrB1 = BandPort(required=True, doc="band port of K1")

    def equations(self):
        w = self.w
        k1, x1, y1 = self._contact(self.ctrB1, w)
        K1 = self.ctrK1
        eqs = [self.kappa1 == k1, K1.x == x1, K1.y == y1, K1.phi == self.ctrB1.gamma,
               self.ctrB1.L == -w * self.r * (self.phi - self.kappa1),
               self.l_wound == w * self.r * (self.phi + self.alpha_fix - self.kappa1)
               + 2 * _PI * self.r * self.n_wound]
        return eqs + self._balance([(K1, x1, y1)])
