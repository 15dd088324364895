"""Ideal gears of Modelica.Mechanics.Rotational.Components (Modelica Standard Library 4.0):
:class:`IdealGear` and :class:`IdealPlanetary`.

Both are re-exported by :mod:`acausal2d.library.rotational`, where a
Modelica user looks for them (``rotational.IdealGear``).  The sign
convention is Modelica's and the library's: ``flange.tau`` is the torque
acting on the element from the connected part (Ebert 2015, eq. 4.1 at the
flanges).  Gears are massless and lossless: the power flowing in equals
the power flowing out at every instant."""
from acausal2d import Component, Parameter, RotationalFlange, TranslationalFlange, Variable


class IdealGear(Component):
    """Ideal gear without inertia, elasticity, backlash or losses
    (Modelica.Mechanics.Rotational.Components.IdealGear, which extends
    PartialElementaryTwoFlangesAndSupport2)::

        phi_a = flange_a.phi - support.phi
        phi_b = flange_b.phi - support.phi
        phi_a = ratio * phi_b
        0 = ratio * flange_a.tau + flange_b.tau
        support.tau = -flange_a.tau - flange_b.tau

    ``ratio`` is the transmission ratio ``flange_a.phi / flange_b.phi``
    (relative to the support), e.g. 5 for a gear reducing the speed of
    flange_a to a fifth at flange_b and multiplying its torque by 5.  The
    support flange is Modelica's optional support: left unconnected it is
    fixed to ground at the angle 0 (``useSupport = false``); connect it to a
    housing that moves or to a torque sensor to take the reaction torque
    ``support.tau`` there.  The power balance ``flange_a.tau * w_a +
    flange_b.tau * w_b + support.tau * w_support = 0`` holds exactly."""
    ratio = Parameter(1.0, "1", "transmission ratio (flange_a.phi/flange_b.phi)", nonzero=True)
    phi_a = Variable(unit="rad", doc="angle of flange_a relative to the support")
    phi_b = Variable(unit="rad", doc="angle of flange_b relative to the support")

    power_sides = (("flange_a",), ("flange_b",))

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange_a = RotationalFlange(doc="driving flange (input shaft)")
        self.flange_b = RotationalFlange(doc="driven flange (output shaft)")
        self.support = RotationalFlange(ground={"phi": 0.0},
                                        doc="housing (fixed at 0 if unconnected)")

    def equations(self):
        return [self.phi_a == self.flange_a.phi - self.support.phi,
                self.phi_b == self.flange_b.phi - self.support.phi,
                self.phi_a == self.ratio * self.phi_b,
                0 == self.ratio * self.flange_a.tau + self.flange_b.tau,
                self.support.tau == -self.flange_a.tau - self.flange_b.tau]


class IdealPlanetary(Component):
    """Ideal planetary gear box (Modelica.Mechanics.Rotational.Components.
    IdealPlanetary): a sun wheel, a carrier with the planet wheels and a
    ring wheel, massless and lossless.  ``ratio`` is the number of ring
    teeth over the number of sun teeth (e.g. 100/50).  Equations (Willis'
    equation for the angles, and the torque balance of a lossless gear)::

        (1 + ratio) * carrier.phi = sun.phi + ratio * ring.phi
        ring.tau = ratio * sun.tau
        carrier.tau = -(1 + ratio) * sun.tau

    With the carrier held, the sun drives the ring backwards at
    ``-1/ratio`` of its speed; with the ring held, the carrier turns at
    ``1/(1 + ratio)`` of the sun's speed (the usual reduction stage)."""
    ratio = Parameter(2.0, "1", "number of ring teeth / number of sun teeth", positive=True)

    power_sides = (("sun",), ("carrier",), ("ring",))

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sun = RotationalFlange(doc="sun wheel")
        self.carrier = RotationalFlange(doc="carrier of the planet wheels")
        self.ring = RotationalFlange(doc="ring wheel")

    def equations(self):
        r = self.ratio
        return [(1 + r) * self.carrier.phi == self.sun.phi + r * self.ring.phi,
                self.ring.tau == r * self.sun.tau,
                self.carrier.tau == -(1 + r) * self.sun.tau]


class IdealGearR2T(Component):
    """Gearbox transforming rotational into translational motion
    (Modelica Standard Library 4.0, Modelica.Mechanics.Rotational.Components.IdealGearR2T, with
    both supports fixed)::

        flangeR.phi = ratio * flangeT.s
        0 = ratio * flangeR.tau + flangeT.f

    ``ratio`` in rad/m (flangeR.phi / flangeT.s); no losses, no inertia."""
    ratio = Parameter(1.0, "rad/m", "transmission ratio flangeR.phi / flangeT.s")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flangeR = RotationalFlange()
        self.flangeT = TranslationalFlange()

    def equations(self):
        return [self.flangeR.phi == self.ratio * self.flangeT.s,
                0 == self.ratio * self.flangeR.tau + self.flangeT.f]


class IdealRollingWheel(Component):
    """Ideal rolling wheel (Modelica Standard Library 4.0, Modelica.Mechanics.
    Rotational.Components.IdealRollingWheel, with both supports fixed)::

        flangeR.phi * radius = flangeT.s
        0 = radius * flangeT.f + flangeR.tau

    Rolls without slip; no inertia (add an Inertia and a Mass)."""
    radius = Parameter(0.3, "m", "radius of the wheel", positive=True)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flangeR = RotationalFlange()
        self.flangeT = TranslationalFlange()

    def equations(self):
        return [self.flangeR.phi * self.radius == self.flangeT.s,
                0 == self.radius * self.flangeT.f + self.flangeR.tau]
