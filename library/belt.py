"""Belt and rope drives: elastic belt spans, circular pulleys ("Bandrolle"),
drums and a driven rope end (seed ch. 4.4, eq. 4.52-4.99).

Elements and ports (seed names)
-------------------------------
- :class:`Belt` -- elastic belt / rope span (eq. 4.52-4.66): mechanical
  ports ``ctr2D1``, ``ctr2D2`` (end points P1, P2) and band ports ``ctrB1``,
  ``ctrB2``.
- :class:`SpringBelt` -- inextensible band with a discrete tension spring and
  damper (eq. 4.78-4.86), same ports.
- :class:`NozzleBelt` -- elastic belt through a frictionless draw-off nozzle
  at ``ctr2D3`` (eq. 4.67-4.77).
- :class:`Pulley` -- circular pulley "Bandrolle" (eq. 4.87-4.99): housing
  frame ``ctr2D1`` (axis P1), contact frames ``ctrK1``, ``ctrK2``, band ports
  ``ctrB1``, ``ctrB2``, rotational flange ``ctrR`` (pulley angle relative to
  the housing; torque acting between housing and pulley).
- :class:`Drum` -- circular drum with one contact point and the rope end
  fixed on the contour (seed end of ch. 4.4.4).
- :class:`RopeDrive` -- a rope end (point) moved along a straight line by the
  signal ``s_in`` (for pulling a rope with a drive function).
- The pulley and drum with curved contour (eq. 4.100-4.122) are in
  :mod:`acausal2d.library.belt_curved` (``CurvedPulley``, ``CurvedDrum``);
  they have the same ports and connect to the spans in the same way.  The
  start values of spans ending on them come from :func:`tangent_any`.

Band connection (seed ch. 4.1)
------------------------------
A :class:`~acausal2d.language.connectors.BandPort` carries two potentials and is
connected one-to-one:

- ``gamma``: the direction (unwrapped angle, world frame) in which the span
  *leaves* the pulley/drum at this contact, i.e. points from the contact into
  the span.  The span computes it: ``ctrB1.gamma = gamma_B`` (direction
  P1 -> P2) and ``ctrB2.gamma = gamma_B + pi``.  The seed hands the same
  gamma_B to both ends and lets the pulley add the mounting-variant angle
  gamma_z (Tabelle 4.16); handing the leaving direction makes the pulley
  independent of the span's orientation, so the mounting variant reduces
  to the winding direction ``w`` (see :class:`Pulley`).
- ``L``: the belt material the pulley has paid out into the span at this
  contact (seed: gewickelte Bandlaenge l_r).  It is an absolute quantity
  (r times an unwrapped angle); only its changes matter, because every span
  integrates its own unstretched length from its initial strain (see
  :class:`Belt`).  A span end that is not connected to a band port (a rope
  end fastened to a frame) has ``L = 0``.

Use :func:`connect_band` to make both connections (frame and band port) of
one span end with one call.

Start values and the mounting variant
-------------------------------------
The span angle gamma is an unwrapped variable determined by the position
equations ``x_P2 - x_P1 = l cos(gamma)``, ``y_P2 - y_P1 = l sin(gamma)``
(no atan2; eq. 4.57 without its branch cut), so it needs a start value on the
right branch.  When a model is compiled, :func:`prepare_belts` (called
automatically) evaluates the tangent construction from the parameter values
at that moment -- pulley centres ``x0, y0``, radii, winding directions,
fixed points, start values of bodies -- and sets the start values of each
span's gamma and length and the full-turn offset of each pulley's wrap
angle.  Per-instance start values given by the user (``gamma=start(...)``)
are kept.  These numbers are evaluated once at compile time: changing
geometry parameters later with ``simulate(params=...)`` keeps the branch and
winding sense chosen at compile time (the seed also evaluates its
additional angles once at the start of the simulation).

Bearing friction
----------------
:class:`Pulley` and :class:`Drum` take ``friction=True`` to add a Coulomb
bearing friction torque ``mu * r_pin * |F_bearing|`` (seed ch. 7.3.1)
opposing the rotation relative to the housing.  Sticking is not modelled by
events; the sign function is regularised as
``w_rel / sqrt(w_rel**2 + omega_s**2)`` with a small ``omega_s`` (default
1e-3 rad/s).  The relative error of the friction torque is
``0.5*(omega_s/w_rel)**2`` at speed ``w_rel``, so quasi-static results at
speeds above 100*omega_s are Coulomb-exact to 5e-5; a pulley at rest carries
no friction torque (it creeps slowly instead of sticking).  ``|F_bearing|`` is
regularised by 1e-6 N so that the torque stays differentiable at zero load.
"""
import math

import casadi as ca
import numpy as np

from acausal2d import (BandPort, Component, der, Frame, Outer, Parameter, RealInput,
                       RotationalFlange, Variable)
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.planar import PlanarWorld, is_connected

__all__ = ["Belt", "SpringBelt", "NozzleBelt", "Pulley", "Drum", "RopeDrive",
           "connect_band", "belt_layout", "tangent", "tangent_any", "open_belt_closed_form"]

_PI = math.pi


# --------------------------------------------------------------------------
# common machinery
# --------------------------------------------------------------------------
class _BandElement(Component):
    """Base of the belt-library elements: start values and wrap-angle turns
    from the tangent construction of all belts of the model at t0
    (:func:`belt_layout`, computed once per flattening)."""

    def derived_parameters(self, context):
        return context.shared("belt layout", lambda: belt_layout(context.model)) \
            .params.get(id(self), {})

    def guesses(self, context):
        return context.shared("belt layout", lambda: belt_layout(context.model)) \
            .guesses.get(id(self), {})




# --------------------------------------------------------------------------
# spans
# --------------------------------------------------------------------------
class _Span(_BandElement):
    """Geometry shared by the spans: end frames, band ports, unwrapped span
    angle gamma and free length l (eq. 4.52 and 4.57 without atan2)."""
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
    """Elastic belt or rope span between P1 and P2 (seed 4.4.1, eq. 4.52-4.66).

    Straight, massless and bending-free.  ``l`` is the free length |P2 - P1|
    (4.52), ``gamma`` the span angle (4.57, unwrapped).  The unstretched
    material length of the span is ``l_u = l_u0 + ctrB1.L + ctrB2.L`` (4.53:
    material paid out by the neighbours runs into the span), with the
    constant ``l_u0`` (``der(l_u0) = 0``) found at initialization from the
    initial strain.  Strain ``eps = (l - l_u)/l_u`` (4.54, 4.56).  The force
    (4.58-4.62) is

        F = c*eps + d*der(eps)   while eps > 0,   F = 0 while slack,

    with ``c`` the stiffness per unit strain (the seed's k_Bc, N per unit
    strain = N.m/m; the span's spring rate is c/l_u) and ``d`` the damping per
    unit strain (b_Bc).  ``eps > 0`` is a relation, so slackening and
    re-tensioning are events.  As in the seed, the damping term may make F
    negative for a taut span that is unloaded very quickly.

    Numerics: the strain is normally chosen as the integrator state and
    ``l_u0`` is then recovered from it, so the conservation of belt material
    holds to the integration tolerance (about 1e-6 relative at rtol 1e-8),
    not exactly.  (Making ``l_u0`` the state keeps it exact but, with
    damping, made IDA re-evaluate the Jacobian on almost every step -- see
    the report of issue 4.)  Very stiff belts (c above ~1e8 N) need rtol
    >= 1e-9: the force is c times a difference of lengths, so its round-off
    is about 1e-16 * c.

    Initial state: by default the strain is fixed at 0 (the span starts just
    unstretched, the seed's l_B0 = l_B(t=0)).  Give a pretension with
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
    """Band with a tension spring (seed 4.4.3, eq. 4.78-4.86).

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


class NozzleBelt(_BandElement):
    """Elastic belt through a draw-off nozzle (seed 4.4.2, eq. 4.67-4.77).

    The band runs from P1 through the frictionless nozzle at P3 (``ctr2D3``)
    to P2.  Both pieces form one elastic span of free length
    ``l = l1 + l2`` (4.67-4.69) with the force law of :class:`Belt`; the
    piece angles ``gamma1`` (P1 -> P3) and ``gamma2`` (P3 -> P2) are
    unwrapped variables (4.70, 4.71).  The band ports hand ``gamma1`` at P1
    and ``gamma2 + pi`` at P2 (leaving directions).  The nozzle carries the
    resultant of both piece forces (4.76, 4.77) and no moment.
    """
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


# --------------------------------------------------------------------------
# pulleys and drums
# --------------------------------------------------------------------------
class _Wheel(_BandElement):
    """Mass, housing, flange and bearing friction shared by pulley and drum."""
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
        return items + [("rigid", contacts), ("joint", self.ctr2D1, contacts[0], 1)]


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


class Drum(_Wheel):
    """Circular rope drum: one contact point K1, rope end fixed on the
    contour (seed end of 4.4.4: the Bandrolle without ctrK2/ctrB2).

    ``w=+1``: a positive turn winds the rope up.  The rope end is fastened
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

    def __init__(self, w=1, friction=False, **kw):
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

    def equations(self):
        f = self.frame
        e = (ca.cos(self.angle), ca.sin(self.angle))
        return [f.x == self.x0 + self.s_in.u * e[0], f.y == self.y0 + self.s_in.u * e[1],
                f.phi == 0, self.F == -(f.fx * e[0] + f.fy * e[1])]

    def shapes(self):
        """The driven rope end as a joint."""
        return [{"type": "joint", "x": "frame.x", "y": "frame.y"}]


# --------------------------------------------------------------------------
# wiring and start values
# --------------------------------------------------------------------------
def connect_band(model, span, end, wheel, contact):
    """Connect end ``end`` (1 or 2) of ``span`` to contact ``contact`` (1 or
    2) of ``wheel`` (a :class:`Pulley` or :class:`Drum`): joins the frame
    ``span.ctr2D<end>`` with ``wheel.ctrK<contact>`` and the band ports
    ``span.ctrB<end>`` with ``wheel.ctrB<contact>``."""
    model.connect(getattr(span, "ctr2D%d" % end), getattr(wheel, "ctrK%d" % contact))
    model.connect(getattr(span, "ctrB%d" % end), getattr(wheel, "ctrB%d" % contact))


def tangent(a, b):
    """Tangent construction for one span.

    ``a`` and ``b`` are ``(cx, cy, rho)``: a circle centre and its signed
    radius ``rho = s*r`` where ``s`` says on which side of the span the
    wheel lies (the contact is at ``C + rho*perp(e)`` at the start and
    ``C - rho*perp(e)`` at the end of the span, ``e`` the span direction,
    ``perp`` the counter-clockwise normal); ``rho = 0`` is a point.
    Returns ``(gamma, l)``: the span angle in (-pi, pi] and the free length."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    rho = a[2] + b[2]
    d2 = dx * dx + dy * dy
    if d2 <= rho * rho:
        raise ModelDefinitionError("no tangent between %r and %r: the wheels overlap" % (a, b))
    l = math.sqrt(d2 - rho * rho)
    g = math.atan2(dy, dx) - math.atan2(rho, l)
    g = math.atan2(math.sin(g), math.cos(g))
    return g, l


def tangent_any(a, b):
    """:func:`tangent` for span ends that may also be curved contours.

    ``a`` and ``b`` are ``(cx, cy, rho)`` tuples as in :func:`tangent` or
    geometry objects of curved wheels (``library/belt_curved.py``) with the
    methods ``approx()`` (an equivalent ``(cx, cy, rho)`` circle) and
    ``support(ux, uy)`` (the world contact point whose outward normal is the
    unit vector ``u``).  Starting from the circle approximation, the span
    angle is refined by fixed-point iteration: contact points for the
    current span direction, new direction from the contact points.  Returns
    ``(gamma, l)`` like :func:`tangent`."""
    if isinstance(a, tuple) and isinstance(b, tuple):
        return tangent(a, b)
    ta = a if isinstance(a, tuple) else a.approx()
    tb = b if isinstance(b, tuple) else b.approx()
    g, l = tangent(ta, tb)

    def end(geo, g, sign):
        px, py = -math.sin(g), math.cos(g)
        if isinstance(geo, tuple):
            return geo[0] + sign * geo[2] * px, geo[1] + sign * geo[2] * py
        return geo.support(sign * geo.side * px, sign * geo.side * py)

    for _ in range(200):
        ax, ay = end(a, g, 1.0)
        bx, by = end(b, g, -1.0)
        g_new = math.atan2(by - ay, bx - ax)
        g_new = g + math.remainder(g_new - g, 2 * _PI)
        l = math.hypot(bx - ax, by - ay)
        if abs(g_new - g) < 1e-13:
            g = g_new
            break
        g = g_new
    else:
        raise ModelDefinitionError("no common tangent found between %r and %r" % (a, b))
    return math.atan2(math.sin(g), math.cos(g)), l


def open_belt_closed_form(r1, r2, d):
    """Closed form of the open belt around two circles (centre distance d):
    wrap angles ``(beta1, beta2)`` = (pi + 2 asin((r1-r2)/d),
    pi - 2 asin((r1-r2)/d)) and free span length sqrt(d^2 - (r1-r2)^2)."""
    a = math.asin((r1 - r2) / d)
    return _PI + 2 * a, _PI - 2 * a, math.sqrt(d * d - (r1 - r2) ** 2)


def _num(comp, name):
    return np.asarray(comp.parameter_value(name), dtype=float)


def _frame_geometry(conn):
    """Initial geometry (cx, cy, rho) of the part a span end is connected to
    (see :func:`tangent`), or None."""
    from acausal2d.library import planar
    owner = conn.owner
    name = conn._name
    if hasattr(owner, "_band_geometry") and name in ("ctrK1", "ctrK2"):
        return owner._band_geometry(name)
    if isinstance(owner, _Wheel) and name in ("ctrK1", "ctrK2"):
        s = owner.w if name == "ctrK1" else -owner.w
        return (float(_num(owner, "x0")), float(_num(owner, "y0")),
                s * float(_num(owner, "r")))
    if isinstance(owner, planar.Fixed):
        r = _num(owner, "r")
        return (float(r[0]), float(r[1]), 0.0)
    if isinstance(owner, RopeDrive):
        return (float(_num(owner, "x0")), float(_num(owner, "y0")), 0.0)
    if isinstance(owner, planar.Body) and name == "frame_a" \
            and (owner.is_given("x") or owner.is_given("y")):
        return (owner.start_value("x"), owner.start_value("y"), 0.0)
    return None


class Layout:
    """Result of :func:`belt_layout`: ``guesses[id(element)]`` and
    ``params[id(element)]`` map variable / parameter names to values."""

    def __init__(self):
        self.guesses, self.params = {}, {}

    def guess(self, comp, name, value):
        self.guesses.setdefault(id(comp), {})[name] = value

    def param(self, comp, name, value):
        self.params.setdefault(id(comp), {})[name] = value


def _partners(model):
    """partners(conn): the other connectors connected to ``conn``."""
    parent, conns = {}, {}

    def find(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    for comp in model.components():
        for a, b in comp._connections:
            for c in (a, b):
                conns[id(c)] = c
                parent.setdefault(id(c), id(c))
            ra, rb = find(id(a)), find(id(b))
            if ra != rb:
                parent[ra] = rb
    groups = {}
    for k in parent:
        groups.setdefault(find(k), []).append(conns[k])

    def partners(conn):
        return [c for c in groups[find(id(conn))] if c is not conn] if id(conn) in parent else []
    return partners


def _nozzle_layout(span, ends, layout):
    a, b, n = ends("ctr2D1"), ends("ctr2D2"), ends("ctr2D3")
    if a is None or b is None or n is None:
        return None
    g1, l1 = tangent_any(a, (n[0], n[1], 0.0))
    g2, l2 = tangent_any((n[0], n[1], 0.0), b)
    for name, val in (("gamma1", g1), ("gamma2", g2), ("l1", l1), ("l2", l2),
                      ("l", l1 + l2), ("l_u", l1 + l2), ("l_u0", l1 + l2)):
        layout.guess(span, name, val)
    return g1, g2 + _PI


def _span_layout(span, ends, layout):
    if span.is_given("gamma"):
        gam = span.start_value("gamma")
        return gam, gam + _PI
    a, b = ends("ctr2D1"), ends("ctr2D2")
    if a is None or b is None:
        return None
    gam, length = _named_tangent(span, ends, a, b)
    layout.guess(span, "gamma", gam)
    names = set(span.variable_names())
    for name in ("l", "l_u", "l_u0", "l_x", "l_x0"):
        if name in names:
            layout.guess(span, name, length)
    return gam, gam + _PI


def _named_tangent(span, ends, a, b):
    """:func:`tangent_any` of a span's two ends; wheels that overlap, or
    that leave no tangent, are refused naming the span and both parts."""
    one, two = ends.owner("ctr2D1"), ends.owner("ctr2D2")
    where = "%s runs from %s to %s" % (span.describe(), one.describe(), two.describe())
    if isinstance(a, tuple) and isinstance(b, tuple) and a[2] and b[2]:
        dist = math.hypot(b[0] - a[0], b[1] - a[1])
        if dist < abs(a[2]) + abs(b[2]):
            raise ModelDefinitionError(
                "%s, which overlap: centre distance %.6g m < sum of the radii %.6g m; move "
                "them apart (x0, y0) or make them smaller (r)" % (where, dist,
                                                                 abs(a[2]) + abs(b[2])))
    try:
        return tangent_any(a, b)
    except ModelDefinitionError as exc:
        raise ModelDefinitionError("%s: %s" % (where, exc)) from None


def _wheel_layout(wheel, g1, g2, layout):
    """Contact-angle guesses and wrap turns of a circular wheel (curved
    wheels compute their own: ``_layout_start``)."""
    if hasattr(wheel, "_layout_start"):
        guesses, params = wheel._layout_start(g1, g2)
        for name, v in guesses.items():
            layout.guess(wheel, name, v)
        for name, v in params.items():
            layout.param(wheel, name, v)
        return
    w = wheel.w
    if g1 is None:
        return
    k1 = g1 + w * _PI / 2
    if "kappa1" in wheel.variable_names():
        layout.guess(wheel, "kappa1", k1)
    if isinstance(wheel, Pulley) and g2 is not None:
        k2 = g2 - w * _PI / 2
        layout.guess(wheel, "kappa2", k2)
        if wheel.is_given("kappa2"):
            k2 = wheel.start_value("kappa2")
        raw = w * (k2 - k1)
        n = float(-math.floor(raw / (2 * _PI)))
        layout.param(wheel, "n_beta", n + 1.0 if raw + 2 * _PI * n == 0.0 else n)


class _SpanEnds:
    """The parts a span's ends are connected to: ``ends(frame_name)`` is
    the start geometry of that end (see :func:`_frame_geometry`) or None,
    ``ends.owner(frame_name)`` the component it belongs to."""

    def __init__(self, span, partners):
        self.span, self.partners = span, partners

    def _find(self, frame_name):
        for c in self.partners(getattr(self.span, frame_name)):
            g = _frame_geometry(c)
            if g is not None:
                return g, c.owner
        return None, None

    def __call__(self, frame_name):
        return self._find(frame_name)[0]

    def owner(self, frame_name):
        return self._find(frame_name)[1]


def belt_layout(model):
    """Start values and wrap-angle offsets of all belt elements in ``model``
    from the tangent construction at t0 (see the module docstring), as a
    :class:`Layout`; a start value the model gives wins."""
    partners = _partners(model)
    layout = Layout()

    def end_geometry(span):
        return _SpanEnds(span, partners)

    leaving = {}   # (id(wheel), contact) -> leaving angle at t0
    comps = list(model.components())
    for span in comps:
        if isinstance(span, NozzleBelt):
            gams = _nozzle_layout(span, end_geometry(span), layout)
        elif isinstance(span, _Span):
            gams = _span_layout(span, end_geometry(span), layout)
        else:
            continue
        if gams is None:
            continue
        for frame_name, gam in zip(("ctr2D1", "ctr2D2"), gams):
            for c in partners(getattr(span, frame_name)):
                if isinstance(c.owner, _Wheel) and c._name in ("ctrK1", "ctrK2"):
                    leaving[(id(c.owner), int(c._name[-1]))] = gam
    for wheel in comps:
        if isinstance(wheel, _Wheel):
            _wheel_layout(wheel, leaving.get((id(wheel), 1)), leaving.get((id(wheel), 2)),
                          layout)
    return layout
