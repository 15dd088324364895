"""Pulley and drum with curved contour ("Bandrolle mit Kurvenkontur", Ebert (2015),
ch. 4.4.5, eq. 4.100-4.122): the circular pulley's ports and balances with
the contact point, tangency and wound length on a :class:`Contour` or
:class:`SupportContour` (see :mod:`acausal2d.library.belt.contour` for the
contour forms and the closed-form arc length, eq. 4.116-4.119).
"""
import math

import casadi as ca
import numpy as np

from acausal2d import BandPort, Frame, Parameter, Variable
from acausal2d.errors import ModelDefinitionError


from .contour import _PI, _TWO_PI, Contour, SupportContour
from .pulley import _Wheel


class _ContourGeometry:
    """Initial geometry of a contact of a curved wheel for the tangent
    construction of belt_layout (see belt.tangent_any)."""

    def __init__(self, cx, cy, phi, contour, side):
        self.cx, self.cy, self.phi, self.contour, self.side = cx, cy, phi, contour, side

    def approx(self):
        return (self.cx, self.cy, self.side * self.contour.r_mean)

    def kappa(self, ux, uy):
        """Contour angle (pulley frame) of the point with outward normal u."""
        return self.contour.support_angle(math.atan2(uy, ux) - self.phi)

    def support(self, ux, uy):
        k = self.kappa(ux, uy)
        px, py = self.contour.point(np.array([k]))
        c, s = math.cos(self.phi), math.sin(self.phi)
        return (self.cx + c * px[0] - s * py[0], self.cy + s * px[0] + c * py[0])

    def __repr__(self):
        return "curved contour at (%g, %g)" % (self.cx, self.cy)


class _CurvedWheel(_Wheel):
    """Shared parts of the curved pulley and drum."""

    def __init__(self, contour, w=None, friction=False, **kw):
        if not isinstance(contour, (Contour, SupportContour)):
            raise ModelDefinitionError("%s: contour must be a Contour (e.g. Contour.circle(0.1)"
                                       ", Contour.from_function(f)), got %r"
                                       % (type(self).__name__, contour))
        for k in ("enumHE1", "enumHE2"):
            if kw.get(k) is not None:
                raise ModelDefinitionError(
                    "%s: %s is checked for the circular Pulley and Drum only; on a curved "
                    "contour the winding direction w_i alone fixes the mounting variant "
                    "(leave %s out)" % (type(self).__name__, k, k))
        super().__init__(w=w, friction=friction, **kw)
        self.contour = contour

    def _band_geometry(self, name, poses):
        """Start geometry of contact ``name`` (the axis placed as for
        :class:`~acausal2d.library.belt.Pulley`), or None."""
        if name not in ("ctrK1", "ctrK2"):
            return None
        s = self.w if name == "ctrK1" else -self.w
        (x, y), _ = self._axis_start(poses)
        return _ContourGeometry(x, y, self.start_value("phi"), self.contour, s)

    def _start_kappa(self, gamma, s):
        """Contact angle (pulley frame) for the leaving angle gamma with the
        wheel on side s: outward normal s * perp(e), at the angle
        gamma + s pi/2 (world), i.e. on the same branch as the circular
        pulley's kappa = gamma + s pi/2 (so the absolute wound lengths agree)."""
        theta = gamma + s * _PI / 2 - self.start_value("phi")
        return self.contour.support_angle(theta)

    def _contact(self, port, kap, side):
        """Contact point (eq. 4.100-4.103) and the tangency residual
        (eq. 4.104-4.115 without atan2) for the contact angle ``kap`` (pulley
        frame) and the leaving angle ``port.gamma``.

        With delta = gamma - (phi + kappa) the span direction measured from
        the radius through the contact, the contour tangent (r', r) in the
        polar basis (4.104-4.107) is parallel to the span iff

            r' sin(delta) - r cos(delta) = 0.

        This is the cross product of the tangent (4.108-4.111) with the span
        direction; the dissertation's atan2/floor construction (4.112, 4.113) and
        additional angle gamma_Z (4.114, 4.115, Tabelle 4.20) are replaced by
        it, the branch (parallel or anti-parallel) being the one of the start
        values (Tabelle 4.21's role), which are computed by belt_layout from
        the winding direction w and then followed continuously."""
        px, py = self.xP1, self.yP1
        if isinstance(self.contour, SupportContour):
            # explicit form (SupportContour docstring): kap is the normal angle
            p, dp = self.contour._sym(kap)
            ang = self.phi + kap
            c, s = ca.cos(ang), ca.sin(ang)
            return (px + p * c - dp * s, py + p * s + dp * c,
                    ang - (port.gamma + side * _PI / 2))
        r, dr = self.contour.r_dr_sym(kap)
        ang = self.phi + kap
        x = px + r * ca.cos(ang)
        y = py + r * ca.sin(ang)
        delta = port.gamma - ang
        return x, y, dr * ca.sin(delta) - r * ca.cos(delta)

    def shapes(self):
        """The wheel as :class:`~acausal2d.library.belt.Pulley` draws it,
        with the contour sampled (240 points) as constant points in the
        pulley frame, turned by the absolute angle ``phi``; ``r`` is the
        largest contour radius."""
        n = 240
        x, y = self.contour.point(np.linspace(0.0, _TWO_PI, n, endpoint=False))
        pts = [[float(a), float(b)] for a, b in zip(x, y)]
        r_max = float(np.max(np.hypot(x, y)))
        out = super().shapes()
        for sh in out:
            if sh["type"] == "pulley":
                sh["r"] = r_max
                sh["contour"] = pts
        return out


class CurvedPulley(_CurvedWheel):
    """Pulley with curved contour "Bandrolle mit Kurvenkontur" (Ebert 2015, ch. 4.4.5,
    eq. 4.100-4.122, Tabelle 4.20-4.22).

    ``CurvedPulley(contour, w_i=-1, friction=False, **parameters)`` with a
    :class:`Contour`.  Ports, axis placement (``x10, y10, phi10``,
    ``frameRef``) and flanges (``ctrR1``, ``ctrR2``; deprecated ``ctrR``) as
    :class:`~acausal2d.library.belt.Pulley`; connect the spans with
    :func:`~acausal2d.library.belt.connect_band`.  Winding direction
    ``w_i`` as for the circular pulley (eq. 4.118, 4.119: ``w_i = -1``, the
    default, a positive turn winds the band up at K1; the band wraps
    counter-clockwise from K1 to K2); below ``w = -w_i`` (the deprecated
    constructor argument).

    Equations:

    - contact points (4.100-4.103): ``K_i = P1 + r_C(kappa_i) (cos(phi +
      kappa_i), sin(phi + kappa_i))``, kappa_i the contact angle in the
      pulley frame (unwrapped), phi the absolute pulley angle;
    - tangency (4.104-4.115): ``r_C' sin(delta_i) - r_C cos(delta_i) = 0``
      with ``delta_i = gamma_i - phi - kappa_i`` (see ``_contact``);
    - wound lengths (4.116-4.119): ``ctrB1.L = w s(kappa1)``, ``ctrB2.L = -w
      s(kappa2)`` with the closed-form arc length ``s`` (module docstring);
    - wrap angle ``beta = w (kappa2 - kappa1) + 2 pi n_beta`` (in (0, 2 pi]
      at t0) and wrapped band length ``l_con = w (s(kappa2) - s(kappa1)) +
      n_beta * perimeter``;
    - forces and moments (4.120-4.122): as the circular pulley (mass ``m``,
      inertia ``J``, centre of gravity ``cog`` in the pulley frame, gravity,
      flange torque, optional bearing friction; see
      :meth:`Contour.mass_properties` for a plain disc).

    With a :class:`SupportContour` the contact parameters ``kappa1``,
    ``kappa2`` are the normal angles psi of the contact points (pulley
    frame) instead of their polar angles, and the tangency conditions are the
    explicit relations given there; everything else is the same.

    Start values: :func:`~acausal2d.library.belt.belt_layout` (run at
    compilation) finds the common tangents of the contours at t0 (pulley
    angle = the start value of ``phi``) by fixed-point iteration
    (:func:`~acausal2d.library.belt.tangent_any`) and sets the contact
    angles on the branch of the circular pulley (kappa + phi = gamma +- pi/2
    for a circle), so the absolute wound lengths of a circular contour equal
    the circular pulley's.

    Outputs: ``phi``, ``phi_rel``, ``w_rel``, ``kappa1``, ``kappa2``,
    ``beta``, ``l_con``, ``F_bear``, ``T_f``.
    """
    n_beta = Parameter(0.0, "1", "whole turns added to the wrap angle (set by belt_layout)")
    kappa1 = Variable(unit="rad", state_select="avoid", doc="contact angle of K1 (pulley frame)")
    kappa2 = Variable(unit="rad", state_select="avoid", doc="contact angle of K2 (pulley frame)")
    beta = Variable(unit="rad", state_select="avoid", doc="wrap angle")
    l_con = Variable(unit="m", state_select="avoid", doc="wrapped band length")

    def __init__(self, contour, w=None, friction=False, **kw):
        super().__init__(contour, w=w, friction=friction, **kw)
        self.ctrK1 = Frame(required=True, doc="contact point K1")
        self.ctrK2 = Frame(required=True, doc="contact point K2")
        self.ctrB1 = BandPort(required=True, doc="band port of K1")
        self.ctrB2 = BandPort(required=True, doc="band port of K2")

    def _layout_start(self, g1, g2):
        """Start guesses of the contact angles and the whole turns of the
        wrap angle from the leaving angles at t0 (for belt_layout):
        ({variable: value}, {parameter: value})."""
        w = self.w
        guesses = {}
        if g1 is not None:
            guesses["kappa1"] = self._start_kappa(g1, w)
        if g2 is not None:
            guesses["kappa2"] = self._start_kappa(g2, -w)
        if len(guesses) < 2:
            return guesses, {}
        k1, k2 = (self.start_value(k) if self.is_given(k) else guesses[k]
                  for k in ("kappa1", "kappa2"))
        raw = w * (k2 - k1)
        n = float(-math.floor(raw / _TWO_PI))
        return guesses, {"n_beta": n + 1.0 if raw + _TWO_PI * n == 0.0 else n}

    def equations(self):
        w, C = self.w, self.contour
        K1, K2, B1, B2 = self.ctrK1, self.ctrK2, self.ctrB1, self.ctrB2
        x1, y1, t1 = self._contact(B1, self.kappa1, w)
        x2, y2, t2 = self._contact(B2, self.kappa2, -w)
        s1, s2 = C.s_sym(self.kappa1), C.s_sym(self.kappa2)
        eqs = [K1.x == x1, K1.y == y1, K1.phi == B1.gamma, 0 == t1,
               K2.x == x2, K2.y == y2, K2.phi == B2.gamma, 0 == t2,
               self.beta == w * (self.kappa2 - self.kappa1) + _TWO_PI * self.n_beta,
               self.l_con == w * (s2 - s1) + C.perimeter * self.n_beta,
               B1.L == w * s1,
               B2.L == -w * s2]
        return eqs + self._balance([(K1, x1, y1), (K2, x2, y2)])


class CurvedDrum(_CurvedWheel):
    """Drum with curved contour: one contact point K1, rope end fastened on
    the contour at the contour angle ``alpha_fix`` (the curved counterpart of
    :class:`~acausal2d.library.belt.Drum`; Ebert 2015, end of ch. 4.4.4 / 4.4.5).

    ``w_i=-1`` (default; ``w = -w_i`` below): a positive turn winds the rope
    up.  Contact point and tangency
    as :class:`CurvedPulley` (4.100-4.115), ``ctrB1.L = w s(kappa1)``
    (4.116-4.118) and the rope stored on the drum ``l_wound = w (s(alpha_fix)
    - s(kappa1)) + n_wound * perimeter`` (an output that must stay
    positive).  The contour angle ``alpha_fix`` is structural here (it is
    evaluated through the contour's arc-length series at compile time) and
    is given to the constructor."""
    n_wound = Parameter(0.0, "1", "whole turns of rope on the drum")
    kappa1 = Variable(unit="rad", state_select="avoid", doc="contact angle of K1 (pulley frame)")
    l_wound = Variable(unit="m", state_select="avoid", doc="rope length stored on the drum")

    def __init__(self, contour, w=None, alpha_fix=0.0, friction=False, **kw):
        super().__init__(contour, w=w, friction=friction, **kw)
        self.alpha_fix = float(alpha_fix)
        self.ctrK1 = Frame(required=True, doc="contact point K1")
        self.ctrB1 = BandPort(required=True, doc="band port of K1")

    def _layout_start(self, g1, g2):
        """Start guess of the contact angle (for belt_layout)."""
        if g1 is None:
            return {}, {}
        return {"kappa1": self._start_kappa(g1, self.w)}, {}

    def equations(self):
        w, C = self.w, self.contour
        K1, B1 = self.ctrK1, self.ctrB1
        x1, y1, t1 = self._contact(B1, self.kappa1, w)
        s1 = C.s_sym(self.kappa1)
        s_fix = float(C.s(np.array([self.alpha_fix]))[0])
        eqs = [K1.x == x1, K1.y == y1, K1.phi == B1.gamma, 0 == t1,
               B1.L == w * s1,
               self.l_wound == w * (s_fix - s1) + C.perimeter * self.n_wound]
        return eqs + self._balance([(K1, x1, y1)])
