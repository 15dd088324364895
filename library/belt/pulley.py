"""Circular pulley "Bandrolle" (seed ch. 4.4.4, eq. 4.87-4.99) and the wheel
machinery it shares with the drum and the curved wheels: mass, housing,
flange, wrap angles and the Coulomb bearing friction of seed ch. 7.3.1.
"""
import math

import casadi as ca
import numpy as np

from acausal2d import BandPort, der, Frame, Outer, Parameter, RotationalFlange, Variable
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.planar import PlanarWorld, is_connected

from .base import _PI, _BandElement, _num


class _Wheel(_BandElement):
    """Mass, housing, flange and bearing friction shared by pulley and drum."""
    _layout_kind = "wheel"
    world = Outer(PlanarWorld)
    x0 = Parameter(0.0, "m", "x of the axis P1 at t0 (fixed position if ctr2D1 is unconnected)")
    y0 = Parameter(0.0, "m", "y of the axis P1 at t0 (fixed position if ctr2D1 is unconnected)")
    phi0 = Parameter(0.0, "rad", "housing angle if ctr2D1 is unconnected")
    m = Parameter(0.0, "kg", "mass of the pulley", min=0.0)
    J = Parameter(0.0, "kg.m2", "rotational inertia about the centre of gravity", min=0.0)
    cog = Parameter((0.0, 0.0), "m", "centre of gravity in the pulley frame (x_Srel, y_Srel)")
    mu = Parameter(0.0, "1", "bearing friction coefficient", min=0.0)
    r_pin = Parameter(0.004, "m", "bearing pin radius", min=0.0)
    omega_s = Parameter(1e-3, "rad/s", "regularisation speed of the friction sign", positive=True)

    phi = Variable(unit="rad", state_select="prefer", doc="pulley angle (world), unwrapped")
    phi_rel = Variable(unit="rad", doc="pulley angle relative to the housing")
    w_rel = Variable(unit="rad/s", state_select="prefer", doc="der(phi_rel)")
    T_f = Variable(unit="N.m", doc="bearing friction torque acting on the pulley")
    F_bear = Variable(unit="N", doc="magnitude of the bearing force")

    def __init__(self, w=1, friction=False, **kw):
        if w not in (1, -1):
            raise ModelDefinitionError("%s: winding direction w must be +1 or -1, got %r"
                                       % (type(self).__name__, w))
        super().__init__(**kw)
        self.w = w
        self.friction = friction
        self._dyn = None
        self.ctr2D1 = Frame(ground=lambda c: {"x": c.x0, "y": c.y0, "phi": c.phi0},
                            doc="housing / axis P1 (fixed at x0, y0, phi0 if unconnected)")
        self.ctrR = RotationalFlange(doc="pulley angle relative to the housing; torque "
                                         "between housing and pulley")

    def _band_geometry(self, name):
        """Start geometry (cx, cy, signed radius) of contact ``name`` for the
        tangent construction of :func:`~acausal2d.library.belt.layout.belt_layout`
        (None for a port that is no contact)."""
        if name not in ("ctrK1", "ctrK2"):
            return None
        s = self.w if name == "ctrK1" else -self.w
        return (float(_num(self, "x0")), float(_num(self, "y0")), s * float(_num(self, "r")))

    def _contact(self, port, s):
        """kappa and contact point for the leaving angle port.gamma, with the
        pulley on side s (kappa = gamma + s*pi/2, the seed's gamma_z)."""
        kap = port.gamma + s * _PI / 2
        P = self.ctr2D1
        return kap, P.x + self.r * ca.cos(kap), P.y + self.r * ca.sin(kap)

    def _balance(self, contacts):
        """Force and moment balance (eq. 4.97-4.99).  contacts: list of
        (frame, x, y)."""
        P, R = self.ctr2D1, self.ctrR
        eqs = [self.phi_rel == self.phi - P.phi, self.w_rel == der(self.phi_rel),
               R.phi == self.phi_rel,
               self.F_bear == ca.sqrt(P.fx ** 2 + P.fy ** 2 + 1e-12)]
        if self.friction:
            eqs.append(self.T_f == -self.mu * self.r_pin * self.F_bear * self.w_rel
                       / ca.sqrt(self.w_rel ** 2 + self.omega_s ** 2))
        else:
            eqs.append(self.T_f == 0)
        # housing (massless): ctr2D1.t carries friction and flange torque
        eqs.append(P.t == self.T_f + R.tau)
        m_num = float(np.asarray(self.parameter_value("m")))
        J_num = float(np.asarray(self.parameter_value("J")))
        cog = np.asarray(self.parameter_value("cog"), dtype=float)
        massive = m_num != 0.0
        offset = massive and np.any(cog != 0.0)
        c, s = ca.cos(self.phi), ca.sin(self.phi)
        sx = c * self.cog[0] - s * self.cog[1] if offset else 0.0
        sy = s * self.cog[0] + c * self.cog[1] if offset else 0.0
        Sx, Sy = P.x + sx, P.y + sy
        fx = P.fx + sum(k.fx for k, _, _ in contacts)
        fy = P.fy + sum(k.fy for k, _, _ in contacts)
        mom = (P.x - Sx) * P.fy - (P.y - Sy) * P.fx if offset else 0.0
        for k, x, y in contacts:
            mom = mom + (x - Sx) * k.fy - (y - Sy) * k.fx
        mom = mom + self.T_f + R.tau
        if massive:
            g = self.world.g
            eqs += [self.m * der(der(Sx)) == fx + self.m * g[0],
                    self.m * der(der(Sy)) == fy + self.m * g[1]]
        else:
            eqs += [0 == fx, 0 == fy]
        if massive or J_num != 0.0:
            eqs.append(self.J * der(der(self.phi)) == mom)
        else:
            eqs.append(0 == mom)
        return eqs

    def shapes(self):
        """The wheel at its axis P1, turned by its absolute angle ``phi``
        (radius: the parameter ``r``, so that a changed value is drawn), and
        a ground symbol at the axis when the housing ``ctr2D1`` is
        unconnected (fixed in the ground at ``x0, y0``)."""
        out = ([] if is_connected(self.ctr2D1)
               else [{"type": "ground", "x": "ctr2D1.x", "y": "ctr2D1.y"}])
        out.append({"type": "pulley", "x": "ctr2D1.x", "y": "ctr2D1.y", "r": "r", "phi": "phi"})
        return out

    def topology(self):
        """Planar topology for seed eq. 2.1: the wheel is a link joined to
        its housing ``ctr2D1`` by a revolute joint (f = 1), as the pulley
        ("Rolle") of seed Bild 2.1 c.  The wheel has no frame of its own; its
        contact frames (``ctrK1``, and ``ctrK2`` of a pulley) -- the wheel
        side of the band joints -- stand for it (``("rigid", contacts)``).
        The spans connected there are force elements and declare nothing,
        so the contacts join no other link.  While ``ctr2D1`` is unconnected
        the housing is fixed to ground at ``x0, y0`` (``("ground",
        [ctr2D1])``), like the triangle ports of the linkage elements;
        otherwise it belongs to the link it is connected to."""
        contacts = [self._connectors[n] for n in ("ctrK1", "ctrK2") if n in self._connectors]
        items = [] if is_connected(self.ctr2D1) else [("ground", [self.ctr2D1])]
        return items + [("rigid", contacts), ("joint", self.ctr2D1, contacts[0], 1)] \
            + self._contacts(1)

    def start_checks(self, context):
        """Winding-sign check at t0 of a pulley (circular or curved) (seed eq. 4.87-4.96 and the geometric
        test of the winding sense, spec section 1.6): with ``w`` the bands
        leave the contacts on the sides ``kappa1 = gamma1 + w pi/2``,
        ``kappa2 = gamma2 - w pi/2``; when the two bands then cross each
        other, the band passes through itself -- the sign contradicts how
        the band ends are placed (a pulley between two hanging masses with
        the wrong ``w`` swings them under it).  Bands that both run to other
        wheels are not checked: a crossed belt drive crosses on purpose."""
        if "ctrK2" not in self._connectors:      # a drum: one band, nothing to cross
            return []
        ends = [_band_end(context, getattr(self, "ctrK%d" % k)) for k in (1, 2)]
        if None in ends or all(wheel for _, _, wheel in ends):
            return []
        return [lambda value: self._crossing_message(value, ends)]

    def _crossing_message(self, value, ends):
        """The error text if the bands at K1 and K2 cross at t0, else None."""
        K = [(value(self, "ctrK%d.x" % k), value(self, "ctrK%d.y" % k)) for k in (1, 2)]
        F = [(value(span, far + ".x"), value(span, far + ".y")) for span, far, _ in ends]
        cross = _segments_cross(K[0], F[0], K[1], F[1])
        if cross is None:
            return None
        w, where = self.w, [round(v, 4) + 0.0 for v in cross]
        beta = math.degrees(value(self, "beta"))
        return ("its bands %s (at K1) and %s (at K2) cross each other at (%.4f, %.4f) m at "
                "t0: with w=%+d a positive turn winds the band up at K1 and pays it out at "
                "K2, so the bands leave the pulley on the far sides of their ends and wrap it "
                "by %.1f deg, passing through each other (Ebert 2015, eq. 4.91-4.96).  Use w=%+d "
                "(%s(w=%d)) for the bands to leave it on the sides their ends are on, or "
                "swap the bands between K1 and K2"
                % (ends[0][0].describe(), ends[1][0].describe(), where[0], where[1], w, beta,
                   -w, type(self).__name__, -w))

    def _contacts(self, f):
        """``("contact", band_port, f)`` of each band port: the band joints
        of inextensible spans ending here (seed Tab. 2.1: f = 1 rolling, 2
        sliding)."""
        return [("contact", self._connectors[n], f) for n in ("ctrB1", "ctrB2")
                if n in self._connectors]


class Pulley(_Wheel):
    """Circular pulley "Bandrolle" (seed 4.4.4, eq. 4.87-4.99, Tabelle 4.14-4.17).

    Ports: ``ctr2D1`` housing at the axis P1 (fixed in the ground at
    ``(x0, y0)`` while unconnected, or carried by a link / a free body),
    ``ctrK1``, ``ctrK2`` contact points K1, K2 (connect the span ends),
    ``ctrB1``, ``ctrB2`` band ports, ``ctrR`` rotational flange.

    Winding direction ``w`` (seed w_i, Tabelle 4.15, Bild 4.21; a structural
    constructor argument): ``w=+1`` -- a positive (counter-clockwise) turn of
    the pulley winds the band up at K1 and pays it out at K2, i.e. the band
    wraps the pulley counter-clockwise from K1 to K2; ``w=-1`` the reverse.
    Together with the leaving angles gamma_i handed by the spans this fixes
    the mounting variant: the contact angles are (eq. 4.91, 4.92)

        kappa1 = gamma1 + w*pi/2,   kappa2 = gamma2 - w*pi/2

    (the seed's additional angle gamma_z = +-pi/2 of Tabelle 4.16, chosen
    here from w instead of from the half-plane, which is equivalent and needs
    no branch test), and the contact points are K_i = P1 + r (cos kappa_i,
    sin kappa_i) (4.87-4.90).  The wrap angle is
    ``beta = w (kappa2 - kappa1)`` (4.93, shifted by whole turns so that it
    lies in (0, 2 pi] at t0) and the wrapped arc ``l_con = r beta`` (4.94).

    Wound lengths (4.95, 4.96; material paid out into the span):

        ctrB1.L = -w r (phi - kappa1),   ctrB2.L = w r (phi - kappa2)

    with ``phi`` the absolute (world) angle of the pulley.  They are absolute
    (not zero at t0); the spans only use their changes.

    At t0 (after initialization) the pulley checks that ``w`` fits how its
    bands are placed: if its two bands cross each other (the band would
    pass through itself, e.g. an Atwood machine with the sign flipped), the
    run stops with an error naming the pulley, the bands and the sign to
    use (see :meth:`start_checks`; bands that both run to other wheels, a
    crossed belt drive, are not checked).

    Forces (4.97-4.99): mass ``m`` at the centre of gravity ``cog`` (pulley
    frame), inertia ``J`` about it, gravity from the PlanarWorld, contact
    forces at K1, K2, bearing force at P1, the flange torque ``ctrR.tau``
    (acting between housing and pulley) and the bearing friction ``T_f``
    (``friction=True``, see the module docstring).  The housing is massless;
    ``ctr2D1.t = T_f + ctrR.tau`` is the torque it needs from its support.
    With ``m = J = 0`` (decided from the values at construction) the pulley
    is massless: its force and moment balances are algebraic, so at least
    one of its spans must stay taut.

    Outputs: ``phi``, ``phi_rel``, ``w_rel`` (relative speed), ``kappa1``,
    ``kappa2``, ``beta``, ``l_con``, ``F_bear`` (bearing force magnitude),
    ``T_f``.
    """
    r = Parameter(0.05, "m", "radius of the belt contour", positive=True)
    n_beta = Parameter(0.0, "1", "whole turns added to the wrap angle (set by prepare_belts)")
    kappa1 = Variable(unit="rad", state_select="avoid", doc="contact angle of K1 (world)")
    kappa2 = Variable(unit="rad", state_select="avoid", doc="contact angle of K2 (world)")
    beta = Variable(unit="rad", state_select="avoid", doc="wrap angle (eq. 4.93)")
    l_con = Variable(unit="m", state_select="avoid", doc="wrapped arc length (eq. 4.94)")

    def __init__(self, w=1, friction=False, **kw):
        super().__init__(w=w, friction=friction, **kw)
        self.ctrK1 = Frame(required=True, doc="contact point K1")
        self.ctrK2 = Frame(required=True, doc="contact point K2")
        self.ctrB1 = BandPort(required=True, doc="band port of K1")
        self.ctrB2 = BandPort(required=True, doc="band port of K2")

    def equations(self):
        w = self.w
        k1, x1, y1 = self._contact(self.ctrB1, w)
        k2, x2, y2 = self._contact(self.ctrB2, -w)
        K1, K2 = self.ctrK1, self.ctrK2
        eqs = [self.kappa1 == k1, self.kappa2 == k2,
               K1.x == x1, K1.y == y1, K1.phi == self.ctrB1.gamma,
               K2.x == x2, K2.y == y2, K2.phi == self.ctrB2.gamma,
               self.beta == w * (self.kappa2 - self.kappa1) + 2 * _PI * self.n_beta,
               self.l_con == self.r * self.beta,
               self.ctrB1.L == -w * self.r * (self.phi - self.kappa1),
               self.ctrB2.L == w * self.r * (self.phi - self.kappa2)]
        return eqs + self._balance([(K1, x1, y1), (K2, x2, y2)])


def _band_end(context, contact):
    """(span, far frame name, far end on a wheel?) of the span connected to
    the pulley contact frame ``contact``, or None: the far end is the span's
    other end point (its nozzle for a :class:`NozzleBelt`)."""
    for c in context.partners(contact):
        kind = getattr(c.owner, "_layout_kind", None)
        if kind == "span" and c._name in ("ctr2D1", "ctr2D2"):
            far = "ctr2D2" if c._name == "ctr2D1" else "ctr2D1"
        elif kind == "nozzle" and c._name in ("ctr2D1", "ctr2D2"):
            far = "ctr2D3"
        else:
            continue
        wheel = any(getattr(o.owner, "_layout_kind", None) == "wheel"
                    and o._name.startswith("ctrK")
                    for o in context.partners(getattr(c.owner, far)))
        return c.owner, far, wheel
    return None


def _segments_cross(a, b, c, d):
    """The point where the segments a-b and c-d cross (each strictly
    between its ends, beyond round-off of the lengths), or None."""
    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])

    scale = max(math.hypot(b[0] - a[0], b[1] - a[1]), math.hypot(d[0] - c[0], d[1] - c[1]))
    tol = 1e-9 * scale * scale
    o1, o2 = orient(a, b, c), orient(a, b, d)
    o3, o4 = orient(c, d, a), orient(c, d, b)
    if not (o1 * o2 < 0 and o3 * o4 < 0 and min(abs(o1), abs(o2), abs(o3), abs(o4)) > tol):
        return None
    s = o1 / (o1 - o2)
    return c[0] + s * (d[0] - c[0]), c[1] + s * (d[1] - c[1])


class GuideContour(Pulley):
    """Circular contour over which a band slides without friction (the
    "Kurvenkontur" of seed Bild 2.1 b/c): the equations of a massless
    :class:`Pulley` (``m = J = 0`` are required), whose angle ``phi`` is here
    the slip coordinate of the band over the contour (the moment balance
    makes both span forces equal).  Fixed in the ground while ``ctr2D1`` is
    unconnected, or carried by a turning wheel (Bild 2.1 c) connected there.

    Topology (seed eq. 2.1): the contour belongs to the link of its housing;
    the two band joints slide (f = 2) and are coupled by the wrapped band
    (one more constraint), so that Bild 2.1 b counts F = 3(5-1) - [4(3-1) +
    2(3-2) + 1] = 1.
    """

    def __init__(self, w=1, **kw):
        super().__init__(w=w, **kw)
        for name in ("m", "J"):
            if float(np.asarray(self.parameter_value(name))) != 0.0:
                raise ModelDefinitionError("%s: a GuideContour is massless; leave %s at 0 "
                                           "(put the mass on the body that carries it)"
                                           % (type(self).__name__, name))

    def topology(self):
        """Contour and contacts rigid with the housing, two sliding band
        joints (f = 2) and their coupling (seed Bild 2.1 b)."""
        items = [] if is_connected(self.ctr2D1) else [("ground", [self.ctr2D1])]
        return items + [("rigid", [self.ctr2D1, self.ctrK1, self.ctrK2]),
                        ("coupling", 1)] + self._contacts(2)
