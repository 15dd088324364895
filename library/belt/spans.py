"""Belt spans (Ebert 2015, ch. 4.4.1-4.4.3): the elastic belt or rope span (eq.
4.52-4.66), the inextensible band (its rigid limit), the inextensible band with a tension spring and damper (eq.
4.78-4.86) and the elastic belt through a draw-off nozzle (eq. 4.67-4.77).
Slack spans carry no force (events).
"""
import casadi as ca

from acausal2d import BandPort, der, Frame, Parameter, Variable

from .base import _PI, _BandElement


class _Span(_BandElement):
    """Geometry shared by the spans: end frames, band ports, unwrapped span
    angle gamma and free length l (eq. 4.52 and 4.57 without atan2)."""
    _layout_kind = "span"
    l = Variable(start=1.0, unit="m", state_select="avoid", doc="distance P1-P2 (eq. 4.52, l_B)")
    gamma = Variable(unit="rad", state_select="avoid",
                     doc="span angle P1 -> P2, unwrapped (eq. 4.57, gamma_B)")
    F = Variable(unit="N", doc="span force, tension positive (eq. 4.58, F_B)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(doc="end point P1")
        self.ctr2D2 = Frame(doc="end point P2")
        self.ctrB1 = BandPort(ground={"L": 0.0}, doc="band port at P1 (L=0 if unconnected)")
        self.ctrB2 = BandPort(ground={"L": 0.0}, doc="band port at P2 (L=0 if unconnected)")

    def _geometry(self):
        a, b = self.ctr2D1, self.ctr2D2
        c, s = ca.cos(self.gamma), ca.sin(self.gamma)
        return [b.x - a.x == self.l * c, b.y - a.y == self.l * s,
                self.ctrB1.gamma == self.gamma, self.ctrB2.gamma == self.gamma + _PI,
                # eq. 4.63-4.66: the span pulls P1 towards P2 and vice versa
                a.fx == -self.F * c, a.fy == -self.F * s,
                b.fx == self.F * c, b.fy == self.F * s,
                a.t == 0, b.t == 0]

    def shapes(self):
        """A straight belt span from P1 to P2."""
        return [{"type": "belt", "points": [["ctr2D1.x", "ctr2D1.y"], ["ctr2D2.x", "ctr2D2.y"]]}]


class Belt(_Span):
    """Elastic belt or rope span between P1 and P2 (Ebert 2015, ch. 4.4.1, eq. 4.52-4.66).

    Straight, massless and bending-free.  ``l`` is the free length |P2 - P1|
    (4.52), ``gamma`` the span angle (4.57, unwrapped).  The unstretched
    material length of the span is ``l_u = l_u0 + ctrB1.L + ctrB2.L`` (4.53:
    material paid out by the neighbours runs into the span), with the
    constant ``l_u0`` (``der(l_u0) = 0``) found at initialization from the
    initial strain.  Strain ``eps = (l - l_u)/l_u`` (4.54, 4.56).  The force
    (4.58-4.62) is

        F = c*eps + d*der(eps)   while eps > 0,   F = 0 while slack,

    with ``c`` the stiffness per unit strain (the dissertation's k_Bc, N per unit
    strain = N.m/m; the span's spring rate is c/l_u) and ``d`` the damping per
    unit strain (b_Bc).  ``eps > 0`` is a relation, so slackening and
    re-tensioning are events.  As in the dissertation, the damping term may make F
    negative for a taut span that is unloaded very quickly.

    Numerics: the strain is normally chosen as the integrator state and
    ``l_u0`` is then recovered from it, so the conservation of belt material
    holds to the integration tolerance (about 1e-6 relative at rtol 1e-8),
    not exactly.  (Making ``l_u0`` the state keeps it exact but, with
    damping, made IDA re-evaluate the Jacobian on almost every step.)  Very stiff belts (c above ~1e8 N) need rtol
    >= 1e-9: the force is c times a difference of lengths, so its round-off
    is about 1e-16 * c.

    Initial state: by default the strain is fixed at 0 (the span starts just
    unstretched, the dissertation's l_B0 = l_B(t=0)).  Give a pretension with
    ``Belt(eps=start(1e-4, fixed=True))`` or an initial force with
    ``Belt(F=start(250.0, fixed=True), eps=start(1e-4, fixed=False))``.
    """
    c = Parameter(1e6, "N", "stiffness per unit strain (k_Bc)", positive=True)
    d = Parameter(0.0, "N.s", "damping per unit strain (b_Bc)", min=0.0)
    eps = Variable(fixed=True, nominal=1e-5, unit="1", doc="strain (l - l_u)/l_u (eq. 4.56)")
    l_u = Variable(start=1.0, unit="m", state_select="avoid",
                   doc="unstretched material length in the span (l_x)")
    l_u0 = Variable(start=1.0, unit="m", state_select="avoid",
                    doc="constant part of l_u, found at initialization")

    def equations(self):
        F_taut = self.c * self.eps + self.d * der(self.eps)
        return self._geometry() + [
            self.l_u == self.l_u0 + self.ctrB1.L + self.ctrB2.L,
            der(self.l_u0) == 0,
            self.eps * self.l_u == self.l - self.l_u,
            self.F == ca.if_else(self.eps > 0, F_taut, 0.0),
        ]


class SpringBelt(_Span):
    """Band with a tension spring (Ebert 2015, ch. 4.4.3, eq. 4.78-4.86).

    Two inextensible, massless band pieces with a linear spring k and a
    viscous damper b between them.  The spring length is
    ``l_F = l - l_x`` (4.81) with the band material ``l_x = l_x0 + ctrB1.L +
    ctrB2.L`` (4.79, 4.80; ``l_x0`` constant, found at initialization), its
    extension ``l_dF = l_F - l0`` (4.82) and the force (4.84-4.86)

        F = k*l_dF + b*der(l_dF)   while l_dF > 0,   F = 0 otherwise.

    The initial spring extension is fixed by ``l_dF=start(value, fixed=True)``
    (default 0: the spring starts unloaded).
    """
    k = Parameter(1000.0, "N/m", "spring rate", positive=True)
    b = Parameter(0.0, "N.s/m", "damping coefficient of the spring", min=0.0)
    l0 = Parameter(0.1, "m", "unloaded spring length", positive=True)
    l_dF = Variable(fixed=True, unit="m", doc="spring extension (eq. 4.82)")
    l_x = Variable(start=1.0, unit="m", state_select="avoid",
                   doc="band material in both band pieces")
    l_x0 = Variable(start=1.0, unit="m", state_select="avoid",
                    doc="constant part of l_x, found at initialization")

    def equations(self):
        return self._geometry() + [
            self.l_x == self.l_x0 + self.ctrB1.L + self.ctrB2.L,
            der(self.l_x0) == 0,
            self.l_dF == self.l - self.l_x - self.l0,
            self.F == ca.if_else(self.l_dF > 0, self.k * self.l_dF + self.b * der(self.l_dF), 0.0),
        ]

    def shapes(self):
        """The span from P1 to P2 with the spring drawn over it.  The model
        does not locate the spring along the span (the inextensible band
        pieces on both sides are massless), so the zig-zag spans P1 - P2."""
        ends = [["ctr2D1.x", "ctr2D1.y"], ["ctr2D2.x", "ctr2D2.y"]]
        return [{"type": "belt", "points": ends},
                {"type": "spring", "a": ends[0], "b": ends[1]}]


class Band(_Span):
    """Inextensible band or rope span between P1 and P2 (the rigid limit of
    Ebert 2015, ch. 4.4.1, eq. 4.52-4.58: strain zero).

    The free length equals the band material in the span, ``l = l_x0 +
    ctrB1.L + ctrB2.L`` with the constant ``l_x0`` (``der(l_x0) = 0``, found
    at initialization), so ``F`` is a constraint force.  The span is
    bilateral: it carries compression too, so a model with it must keep it
    taut (check ``F > 0``).  Unlike the elastic spans (force elements), a
    band is a link of Ebert (2015), eq. 2.1 (Bild 2.1 b/c: "das Band in zwei
    Abschnitte aufgeteilt"): each end is a pin (f = 1) where it is fastened
    to a frame, or a band joint where it lies on a wheel contact (f = 1
    rolling, 2 sliding, as the wheel declares).
    """
    l_x = Variable(start=1.0, unit="m", state_select="avoid", doc="band material in the span")
    l_x0 = Variable(start=1.0, unit="m", state_select="avoid",
                    doc="constant part of l_x, found at initialization")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.__dict__["_link"] = Frame()     # the band section as a link (not a port)

    def equations(self):
        return self._geometry() + [
            self.l_x == self.l_x0 + self.ctrB1.L + self.ctrB2.L,
            der(self.l_x0) == 0,
            self.l == self.l_x]

    def topology(self):
        """The band section is a link with a joint at each end (Ebert 2015, eq. 2.1,
        Bild 2.1 b/c): ``("band", ...)`` items, a band joint on a wheel
        contact or a pin on a frame."""
        return [("band", self._link, self.ctr2D1, self.ctrB1),
                ("band", self._link, self.ctr2D2, self.ctrB2)]


class NozzleBelt(_BandElement):
    """Elastic belt through a draw-off nozzle (Ebert 2015, ch. 4.4.2, eq. 4.67-4.77).

    The band runs from P1 through the frictionless nozzle at P3 (``ctr2D3``)
    to P2.  Both pieces form one elastic span of free length
    ``l = l1 + l2`` (4.67-4.69) with the force law of :class:`Belt`; the
    piece angles ``gamma1`` (P1 -> P3) and ``gamma2`` (P3 -> P2) are
    unwrapped variables (4.70, 4.71).  The band ports hand ``gamma1`` at P1
    and ``gamma2 + pi`` at P2 (leaving directions).  The nozzle carries the
    resultant of both piece forces (4.76, 4.77) and no moment.
    """
    _layout_kind = "nozzle"
    c = Parameter(1e6, "N", "stiffness per unit strain", positive=True)
    d = Parameter(0.0, "N.s", "damping per unit strain", min=0.0)
    l1 = Variable(start=1.0, unit="m", doc="length P1-P3 (eq. 4.67)")
    l2 = Variable(start=1.0, unit="m", doc="length P3-P2 (eq. 4.68)")
    l = Variable(start=2.0, unit="m", doc="free length l1 + l2 (eq. 4.69)")
    gamma1 = Variable(unit="rad", doc="angle P1 -> P3 (eq. 4.70)")
    gamma2 = Variable(unit="rad", doc="angle P3 -> P2 (eq. 4.71)")
    F = Variable(unit="N", doc="band force")
    eps = Variable(fixed=True, nominal=1e-5, unit="1", doc="strain")
    l_u = Variable(start=2.0, unit="m", state_select="avoid", doc="unstretched material length")
    l_u0 = Variable(start=2.0, unit="m", state_select="avoid", doc="constant part of l_u")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(doc="end point P1")
        self.ctr2D2 = Frame(doc="end point P2")
        self.ctr2D3 = Frame(doc="nozzle P3")
        self.ctrB1 = BandPort(ground={"L": 0.0})
        self.ctrB2 = BandPort(ground={"L": 0.0})

    def equations(self):
        a, b, n = self.ctr2D1, self.ctr2D2, self.ctr2D3
        c1, s1 = ca.cos(self.gamma1), ca.sin(self.gamma1)
        c2, s2 = ca.cos(self.gamma2), ca.sin(self.gamma2)
        F_taut = self.c * self.eps + self.d * der(self.eps)
        return [n.x - a.x == self.l1 * c1, n.y - a.y == self.l1 * s1,
                b.x - n.x == self.l2 * c2, b.y - n.y == self.l2 * s2,
                self.l == self.l1 + self.l2,
                self.ctrB1.gamma == self.gamma1, self.ctrB2.gamma == self.gamma2 + _PI,
                self.l_u == self.l_u0 + self.ctrB1.L + self.ctrB2.L,
                der(self.l_u0) == 0,
                self.eps * self.l_u == self.l - self.l_u,
                self.F == ca.if_else(self.eps > 0, F_taut, 0.0),
                a.fx == -self.F * c1, a.fy == -self.F * s1,          # 4.72, 4.73
                b.fx == self.F * c2, b.fy == self.F * s2,            # 4.74, 4.75
                n.fx == -a.fx - b.fx, n.fy == -a.fy - b.fy,          # 4.76, 4.77
                a.t == 0, b.t == 0, n.t == 0]

    def shapes(self):
        """The band P1 - nozzle P3 - P2 and the nozzle as a joint."""
        return [{"type": "belt", "points": [["ctr2D1.x", "ctr2D1.y"], ["ctr2D3.x", "ctr2D3.y"],
                                            ["ctr2D2.x", "ctr2D2.y"]]},
                {"type": "joint", "x": "ctr2D3.x", "y": "ctr2D3.y"}]
