"""What the VDI 2729 elements with two sliders share: SSD (Ebert (2015),
Anhang B.7) and SDS (B.8)."""
from acausal2d import Parameter, Variable

from .base import _Linkage, _moment, axes


class _TwoSliders(_Linkage):
    """What SSD (Anhang B.7) and SDS (B.8) share: slider 1 slides on the
    massless guide 1 fixed to the plane at P1 (direction phiU1 = angle of the
    placed frame), ``PS1 = P1 + xG1 e1`` (B.158/B.197) and carries the joint
    point P at the offset ``v1`` (``P = PS1 + v1 n1``, B.164/B.209); slider 2
    slides on guide 2 (angle phiU2), with foot point PS2.  Both sliders have
    mass (bodies S1 in SKS1 at PS1 and S2 in SKS2 at PS2)."""
    v1 = Parameter(0.1, "m", "offset of P from guide 1")

    xG1 = Variable(unit="m", doc="travel of slider 1, P1 -> PS1")
    xG2 = Variable(unit="m", doc="travel of slider 2 along guide 2 to its foot point PS2")
    phiS1 = Variable(unit="rad", doc="angle of slider 1 (= guide 1)")
    phiS2 = Variable(unit="rad", doc="angle of slider 2 (= guide 2)")
    Fn1 = Variable(unit="N", doc="normal force guide 1 -> slider 1")
    T1 = Variable(unit="N.m", doc="moment guide 1 -> slider 1")
    Fn2 = Variable(unit="N", doc="normal force guide 2 -> slider 2")
    T2 = Variable(unit="N.m", doc="moment guide 2 -> slider 2")
    xPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, x (for drawing)")
    yPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, y (for drawing)")
    def _slider1_start(self, x1, y1, a1, xG1):
        """Start values of slider 1 at travel ``xG1``: (PS1, P, guesses)."""
        e1, n1 = axes(a1)
        PS1 = (x1 + xG1 * e1[0], y1 + xG1 * e1[1])
        P = (PS1[0] + self.v1 * n1[0], PS1[1] + self.v1 * n1[1])
        return PS1, P, {"xG1": xG1, "phiS1": a1, "xPS1": PS1[0], "yPS1": PS1[1],
                        **self._mass_start("S1", PS1, a1)}

    def _guide1(self, C1, PS1, N1):
        """Balance of the massless guide 1 (B.182-B.184, B.221-B.223):
        normal force ``N1`` (vector) and moment T1 on slider 1 at PS1."""
        f1 = self.ctr2D1
        return [f1.fx - N1[0] == 0, f1.fy - N1[1] == 0,
                f1.t - self.T1 + _moment(PS1, C1, (-N1[0], -N1[1])) == 0]

    def _slider_shapes(self, PS1, PS2, P, guide2_port=None):
        """Both sliders and the links from their foot points to P; guide 2
        is drawn from its placed point (SDS) or from P (SSD)."""
        P1, _ = self._port_point(1)
        slider2 = self._slider_shape(PS2, "phiS2", guide2_port, "xG2")
        if guide2_port is None:
            slider2["guide"] = [P, PS2]
        return (self._housing_shapes(1, P1, "phiS1")
                + [self._slider_shape(PS1, "phiS1", 1, "xG1"), slider2,
                   {"type": "link", "points": [PS1, P]}])
