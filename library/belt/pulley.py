"""Circular pulley "Bandrolle" (Ebert 2015, ch. 4.4.4, eq. 4.87-4.99) and the wheel
machinery it shares with the drum and the curved wheels: mass, housing,
flange, wrap angles and the Coulomb bearing friction of Ebert (2015), ch. 7.3.1.
"""
import math
import warnings

import casadi as ca
import numpy as np

from acausal2d import BandPort, der, Frame, Outer, Parameter, RotationalFlange, Variable
from acausal2d.errors import ModelDefinitionError, StartPoseError
from acausal2d.library.planar import PlanarWorld, is_connected

from .base import _PI, _BandElement, _num
from .placement import (check_frame_ref, check_half_plane, global_to_relative, half_plane_of,
                        in_half_plane, legacy_placement, place, winding)


class _Wheel(_BandElement):
    """Mass, housing, flanges, axis placement and bearing friction shared by
    pulley and drum (see :class:`Pulley`)."""
    _layout_kind = "wheel"
    world = Outer(PlanarWorld)
    x10 = Parameter(0.0, "m", "x of the axis P1 in the reference frame frameRef (Tabelle 4.15, "
                    "Anhang A.1)")
    y10 = Parameter(0.0, "m", "y of the axis P1 in the reference frame frameRef (Tabelle 4.15, "
                    "Anhang A.1)")
    phi10 = Parameter(0.0, "rad", "angle of the housing frame PKS1 against the reference frame "
                      "(Tabelle 4.15, Anhang A.1)")
    x1rel = Parameter(0.0, "m", "offset of P1 in the connection frame for frameRef='global' "
                      "(eq. A.4, set at compilation)")
    y1rel = Parameter(0.0, "m", "offset of P1 in the connection frame for frameRef='global' "
                      "(eq. A.5, set at compilation)")
    phi1rel = Parameter(0.0, "rad", "angle of PKS1 in the connection frame for "
                        "frameRef='global' (eq. A.6, set at compilation)")
    m = Parameter(0.0, "kg", "mass of the pulley", min=0.0)
    J = Parameter(0.0, "kg.m2", "rotational inertia about the centre of gravity", min=0.0)
    cog = Parameter((0.0, 0.0), "m", "centre of gravity in the pulley frame (x_Srel, y_Srel)")
    mu = Parameter(0.0, "1", "bearing friction coefficient", min=0.0)
    r_pin = Parameter(0.004, "m", "bearing pin radius", min=0.0)
    omega_s = Parameter(1e-3, "rad/s", "regularisation speed of the friction sign", positive=True)

    phi = Variable(unit="rad", state_select="prefer", doc="pulley angle (world), unwrapped")
    phi_rel = Variable(unit="rad", doc="pulley angle relative to the housing")
    w_rel = Variable(unit="rad/s", state_select="prefer",
                     doc="der(phi_rel): angular velocity relative to the housing")
    phidot = Variable(unit="rad/s", doc="der(phi): angular velocity in the world frame GKS "
                      "(the start value phidot_0 of Tabelle 4.15 is given for it; it equals "
                      "w_rel only on a housing at rest)")
    T_f = Variable(unit="N.m", doc="bearing friction torque acting on the pulley")
    F_bear = Variable(unit="N", doc="magnitude of the bearing force")
    P_T = Variable(unit="W", doc="power of the inertia force of the wheel, rate of its "
                   "translational kinetic energy (Anhang A.30, as on the linkage bodies)")
    P_R = Variable(unit="W", doc="power of the inertia torque of the wheel, rate of its "
                   "rotational kinetic energy (Anhang A.31)")
    xP1 = Variable(unit="m", state_select="avoid", doc="axis P1, x (eq. A.7)")
    yP1 = Variable(unit="m", state_select="avoid", doc="axis P1, y (eq. A.8)")

    def __init__(self, w=None, friction=False, w_i=None, enumHE1=None, enumHE2=None,
                 frameRef=None, **kw):
        name = type(self).__name__
        legacy = legacy_placement(name, kw)
        super().__init__(**kw)
        self.__dict__["_legacy_xy"] = legacy
        if legacy and frameRef is not None:
            raise ModelDefinitionError("%s: frameRef belongs to x10, y10, phi10; the deprecated "
                                       "x0, y0, phi0 are always global" % name)
        frameRef = "global" if legacy else (frameRef or "relative")
        self.w_i = winding(name, w, w_i)
        self.w = -self.w_i          # the side of K1: kappa1 = gamma1 + w pi/2
        self.frameRef = check_frame_ref(name, frameRef)
        self.enumHE = {1: check_half_plane(name, "enumHE1", enumHE1),
                       2: check_half_plane(name, "enumHE2", enumHE2)}
        self.friction = friction
        self._dyn = None
        self.ctr2D1 = Frame(ground=lambda c: {"x": c.x10, "y": c.y10, "phi": c.phi10},
                            doc="connection of the housing (fixed in the ground with P1 at "
                                "x10, y10 and the angle phi10 if unconnected)")
        self.ctrR1 = RotationalFlange(doc="housing: angle of the housing frame PKS1, torque "
                                          "acting on the housing (Ebert 2015: ctrR1 = T_R1)")
        self.ctrR2 = RotationalFlange(doc="pulley: absolute pulley angle phi, torque acting on "
                                          "the pulley (Ebert 2015: ctrR2 = T_R2)")
        self.ctrR = RotationalFlange(doc="deprecated: pulley angle relative to the housing; "
                                         "torque between housing and pulley (use ctrR2 with "
                                         "the support on ctrR1)")

    def _unconnected_pose(self):
        """Start pose of ``ctr2D1`` while it is unconnected (for
        :class:`~acausal2d.library.belt.placement.StartPoses`)."""
        return {k: float(_num(self, k + "10")) for k in ("x", "y", "phi")}

    def _axis_start(self, poses, need=True):
        """(x, y) of the axis P1 at t0 (A.7, A.8 with the start pose of the
        connection), and the placement parameters the layout sets
        ({x1rel, y1rel, phi1rel} for frameRef='global', A.4-A.6).  Where the
        connection's start pose is unknown: an error if the position is
        needed (``need``, or frameRef='global'), else (None, {})."""
        given = tuple(float(_num(self, k + "10")) for k in ("x", "y", "phi"))
        if not is_connected(self.ctr2D1):
            return given[:2], {}
        c0 = poses.pose(self.ctr2D1)
        if c0 is None:
            if self._legacy_xy:             # former x0, y0: a start estimate
                return given[:2], {}
            if need or self.frameRef == "global":
                raise StartPoseError(self._unknown_start_message())
            return None, {}
        if self.frameRef == "relative":
            return place(c0, given)[:2], {}
        rel = global_to_relative(given, c0)
        if self._legacy_xy:
            _check_legacy(self, given, c0)
            rel = (0.0, 0.0, 0.0)
        return place(c0, rel)[:2], dict(zip(("x1rel", "y1rel", "phi1rel"), rel))

    def _check_half_plane(self, k, kappa):
        """Error if contact Kk at the start angle ``kappa`` (world, from the
        tangent construction) is not in the half-plane enumHE<k> (Tabelle
        4.16, Bild 4.20)."""
        plane = self.enumHE.get(k)
        if plane is None or in_half_plane(plane, kappa):
            return
        raise ModelDefinitionError(
            "%s: enumHE%d=%r, but with w_i=%+d the contact K%d starts at %.1f deg around the "
            "axis P1 (%s; Tabelle 4.16).  Write enumHE%d=%r, or w_i=%+d if the band is "
            "meant to run around the other side of the pulley (the other mounting variant, "
            "Bild 4.20)" % (self.describe(), k, plane, self.w_i, k,
                            math.degrees(math.remainder(kappa, 2 * _PI)), half_plane_of(kappa),
                            k, half_plane_of(kappa).split(" ")[0], -self.w_i))

    def _unknown_start_message(self):
        return ("%s: the start position of its axis P1 is not known: ctr2D1 is connected to a "
                "frame whose start pose does not follow from parameters and start values "
                "(Fixed, Body with start x, y, phi, FixedTranslation, FixedRotation, BodyShape, "
                "Revolute with a start phi, Prismatic with a start s, the ports of the linkage "
                "elements DAN, SAN, DDD, ... once their inputs are known).  Give the body that "
                "carries it start values (e.g. Body(x=start(...), y=start(...), phi=start(...))), "
                "or, for frameRef='global', "
                "the axis' start pose x10, y10 together with those start values"
                % self.describe())

    def _offset(self):
        """Offset (x, y, phi) of P1 in the connection frame (A.1-A.6), or
        None while ``ctr2D1`` is unconnected (P1 is then the port itself);
        x and y are 0.0 where their values are zero, so that P1 = C then
        holds without the rotation terms."""
        names = self._offset_names()
        if names is None:
            return None
        vals = [float(_num(self, n)) for n in names[:2]]
        xy = [getattr(self, n) if v != 0.0 else 0.0 for n, v in zip(names[:2], vals)]
        return xy[0], xy[1], getattr(self, names[2])

    def _offset_names(self):
        """Names of the parameters holding the offset of P1 in the
        connection frame, or None while ``ctr2D1`` is unconnected."""
        if not is_connected(self.ctr2D1):
            return None
        if self.frameRef == "relative" and not self._legacy_xy:
            return ("x10", "y10", "phi10")              # A.1-A.3
        return ("x1rel", "y1rel", "phi1rel")            # A.4-A.6, set by the layout

    def _band_geometry(self, name, poses):
        """Start geometry (cx, cy, signed radius) of contact ``name`` for the
        tangent construction of :func:`~acausal2d.library.belt.layout.belt_layout`
        (None for a port that is no contact)."""
        if name not in ("ctrK1", "ctrK2"):
            return None
        s = self.w if name == "ctrK1" else -self.w
        (x, y), _ = self._axis_start(poses)
        return (x, y, s * float(_num(self, "r")))

    def _contact(self, port, s):
        """kappa and contact point for the leaving angle port.gamma, with the
        pulley on side s (kappa = gamma + s*pi/2, the dissertation's gamma_z)."""
        kap = port.gamma + s * _PI / 2
        return kap, self.xP1 + self.r * ca.cos(kap), self.yP1 + self.r * ca.sin(kap)

    def _housing(self):
        """Axis placement (A.7-A.9), flanges and the massless housing's
        moment balance about the connection point (A.16-A.18): returns
        (equations, housing angle, flange torque on the pulley)."""
        C, R = self.ctr2D1, self.ctrR
        rel = self._offset()
        if rel is None:
            x, y, phi_h = C.x, C.y, C.phi
        else:
            x, y, phi_h = place(C, rel)
        tau = R.tau + self.ctrR2.tau + self.T_f         # torques on the pulley
        moved = rel is not None and not (isinstance(rel[0], float) and isinstance(rel[1], float))
        arm = (self.xP1 - C.x) * C.fy - (self.yP1 - C.y) * C.fx if moved else 0
        eqs = [self.xP1 == x, self.yP1 == y,
               self.phi_rel == self.phi - phi_h, self.w_rel == der(self.phi_rel),
               self.phidot == der(self.phi),
               R.phi == self.phi_rel, self.ctrR1.phi == phi_h, self.ctrR2.phi == self.phi,
               C.t == tau - self.ctrR2.tau - self.ctrR1.tau + arm]
        if is_connected(R):
            warnings.warn("%s: the flange ctrR is deprecated; connect the drive to ctrR2 (the "
                          "pulley) and its support to ctrR1 (the housing)" % self.describe(),
                          DeprecationWarning, stacklevel=2)
        return eqs, tau

    def _balance(self, contacts):
        """Force and moment balance (eq. 4.97-4.99 with the moment sign fixed,
        moments about the centre of gravity).  contacts: list of
        (frame, x, y)."""
        P = self.ctr2D1
        eqs, tau = self._housing()
        eqs.append(self.F_bear == ca.sqrt(P.fx ** 2 + P.fy ** 2 + 1e-12))
        if self.friction:
            eqs.append(self.T_f == -self.mu * self.r_pin * self.F_bear * self.w_rel
                       / ca.sqrt(self.w_rel ** 2 + self.omega_s ** 2))
        else:
            eqs.append(self.T_f == 0)
        m_num = float(np.asarray(self.parameter_value("m")))
        J_num = float(np.asarray(self.parameter_value("J")))
        cog = np.asarray(self.parameter_value("cog"), dtype=float)
        massive = m_num != 0.0
        offset = massive and np.any(cog != 0.0)
        c, s = ca.cos(self.phi), ca.sin(self.phi)
        sx = c * self.cog[0] - s * self.cog[1] if offset else 0.0
        sy = s * self.cog[0] + c * self.cog[1] if offset else 0.0
        Sx, Sy = self.xP1 + sx, self.yP1 + sy
        fx = P.fx + sum(k.fx for k, _, _ in contacts)
        fy = P.fy + sum(k.fy for k, _, _ in contacts)
        mom = (self.xP1 - Sx) * P.fy - (self.yP1 - Sy) * P.fx if offset else 0.0
        for k, x, y in contacts:
            mom = mom + (x - Sx) * k.fy - (y - Sy) * k.fx
        mom = mom + tau
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
        return eqs + self._power((Sx, Sy) if massive else None, massive or J_num != 0.0)

    def _power(self, S, turning):
        """P_T and P_R (Anhang A.30, A.31): ``P_T = m (xS'' xS' + yS'' yS')``
        of the centre of gravity ``S`` (None: massless, P_T = 0) and ``P_R =
        J phi'' phi'`` (0 where the wheel has neither mass nor inertia)."""
        P_T = (self.m * (der(der(S[0])) * der(S[0]) + der(der(S[1])) * der(S[1]))
               if S is not None else 0)
        P_R = self.J * der(der(self.phi)) * der(self.phi) if turning else 0
        return [self.P_T == P_T, self.P_R == P_R]

    def shapes(self):
        """The wheel at its axis P1, turned by its absolute angle ``phi``
        (radius: the parameter ``r``, so that a changed value is drawn), and
        a ground symbol at the axis when the housing ``ctr2D1`` is
        unconnected (fixed in the ground at ``x10, y10``); with an offset
        placement the wheel is drawn at P1 (``xP1, yP1``) with an arm from
        the connection point."""
        out = ([] if is_connected(self.ctr2D1)
               else [{"type": "ground", "x": "ctr2D1.x", "y": "ctr2D1.y"}])
        moved = self._offset_names() is not None and any(
            float(_num(self, n)) != 0.0 for n in self._offset_names()[:2])
        x, y = ("xP1", "yP1") if moved else ("ctr2D1.x", "ctr2D1.y")
        if moved:       # the housing: a rigid arm from the connection point to the axis
            out.append({"type": "link", "points": [["ctr2D1.x", "ctr2D1.y"], [x, y]]})
        out.append({"type": "pulley", "x": x, "y": y, "r": "r", "phi": "phi"})
        return out

    def topology(self):
        """Planar topology for Ebert (2015), eq. 2.1: the wheel is a link joined to
        its housing ``ctr2D1`` by a revolute joint (f = 1), as the pulley
        ("Rolle") of Ebert (2015), Bild 2.1 c.  The wheel has no frame of its own; its
        contact frames (``ctrK1``, and ``ctrK2`` of a pulley) -- the wheel
        side of the band joints -- stand for it (``("rigid", contacts)``).
        The spans connected there are force elements and declare nothing,
        so the contacts join no other link.  While ``ctr2D1`` is unconnected
        the housing is fixed to ground at ``x10, y10`` (``("ground",
        [ctr2D1])``), like the triangle ports of the linkage elements;
        otherwise it belongs to the link it is connected to."""
        contacts = [self._connectors[n] for n in ("ctrK1", "ctrK2") if n in self._connectors]
        items = [] if is_connected(self.ctr2D1) else [("ground", [self.ctr2D1])]
        return items + [("rigid", contacts), ("joint", self.ctr2D1, contacts[0], 1)] \
            + self._contacts(1)

    def start_checks(self, context):
        """Winding-sign check at t0 of a pulley (circular or curved) (Ebert 2015, eq. 4.87-4.96 and the geometric
        test of the winding sense): with ``w`` the bands
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
        w_i, where = self.w_i, [round(v, 4) + 0.0 for v in cross]
        beta = math.degrees(value(self, "beta"))
        return ("its bands %s (at K1) and %s (at K2) cross each other at (%.4f, %.4f) m at "
                "t0: with w_i=%+d a positive turn %s, so the bands leave the pulley on the far "
                "sides of their ends and wrap it by %.1f deg, passing through each other "
                "(Ebert 2015, eq. 4.91-4.96).  Use w_i=%+d (%s(w_i=%d); w=%+d in the deprecated "
                "notation) for the bands to leave it on the sides their ends are on, or swap "
                "the bands between K1 and K2"
                % (ends[0][0].describe(), ends[1][0].describe(), where[0], where[1], w_i,
                   _SENSE[w_i], beta, -w_i, type(self).__name__, -w_i, w_i))

    def _contacts(self, f):
        """``("contact", band_port, f)`` of each band port: the band joints
        of inextensible spans ending here (Ebert 2015, Tab. 2.1: f = 1 rolling, 2
        sliding)."""
        return [("contact", self._connectors[n], f) for n in ("ctrB1", "ctrB2")
                if n in self._connectors]


class Pulley(_Wheel):
    """Circular pulley "Bandrolle" (Ebert 2015, ch. 4.4.4, eq. 4.87-4.99, Tabelle
    4.14-4.17; SimulationX: FixPulley) with the dissertation's ports, parameters
    and signs.

    Ports (Tabelle 4.14): ``ctr2D1`` connection of the housing,
    ``ctrK1``, ``ctrK2`` contact points K1, K2 (connect the span ends),
    ``ctrB1``, ``ctrB2`` band ports, ``ctrR1`` housing flange (angle of
    the housing frame, torque T_R1 acting on the housing) and ``ctrR2``
    pulley flange (absolute pulley angle ``phi``, torque T_R2 acting on the
    pulley).  A 1D drive whose support sits on the housing connects its
    flange to ``ctrR2`` and its support to ``ctrR1``; the housing then
    carries the reaction.  ``ctrR`` (deprecated) is the former relative
    flange: angle ``phi_rel``, its torque acts on the pulley and, reversed,
    on the housing.

    Placement of the axis (Tabelle 4.15, Anhang A.1, see
    :mod:`~acausal2d.library.belt.placement`): ``x10, y10, phi10`` and
    ``frameRef`` (constructor argument) -- ``'relative'`` (default): P1 and
    the housing frame PKS1 sit at the constant offset (x10, y10, phi10) in
    the connection frame of ``ctr2D1`` (A.1-A.3, A.7-A.9); ``'global'``:
    (x10, y10, phi10) is the start pose of PKS1 in the world, the offset
    follows from the connection's start pose (A.4-A.6).  Unconnected,
    ``ctr2D1`` is fixed in the ground at P1 = (x10, y10) with the angle
    phi10.  The housing is massless; its moment balance about the
    connection point gives the port torque (A.16-A.18):
    ``ctr2D1.t = T_f + ctrR.tau - ctrR1.tau + (P1 - C) x F``.  The start
    position of P1, which the tangent construction of the belts needs, is
    taken from what carries the housing (fixed frames, bodies with start
    values, rods, revolute joints with a start angle:
    :class:`~acausal2d.library.belt.placement.StartPoses`); where it cannot
    be found so, compilation stops with an error naming the pulley.  The
    former ``x0, y0, phi0`` are mapped to ``x10, y10, phi10`` with
    ``frameRef='global'`` (DeprecationWarning); on a connected housing they
    are a start estimate that must agree with the start pose of the
    carrier (an error names both otherwise) and the axis is at the
    connection point.

    Winding direction ``w_i`` (Tabelle 4.15, constructor argument) exactly
    as eq. 4.95/4.96: ``w_i = +1`` -- a positive (counter-clockwise) turn
    pays the band out into the span at K1 and winds it up at K2 (the band
    wraps the pulley clockwise from K1 to K2, beta = kappa1 - kappa2 > 0,
    4.93); ``w_i = -1`` the reverse (the default, the former ``w=+1``).
    The dissertation's Tabelle 4.15 and Bild 4.21 describe the opposite sense in
    words; the equations are followed here.  The former
    ``w`` is ``-w_i`` (DeprecationWarning).

    Mounting variant (Tabelle 4.16, Bild 4.20): the contact angles are
    (4.91, 4.92, with gamma_i the direction in which the span leaves the
    contact, see :mod:`acausal2d.library.belt`)

        kappa1 = gamma1 - w_i*pi/2,   kappa2 = gamma2 + w_i*pi/2,

    i.e. the dissertation's gamma_z = +-pi/2 follows from ``w_i``.  ``enumHE1``,
    ``enumHE2`` (``'upper'``, ``'lower'``, ``'left'``, ``'right'``: the
    half-plane around P1 in which K1, K2 lie at t0) are checked against the
    tangent construction at compilation: a half-plane that the winding
    direction does not produce stops with an error naming the pulley, the
    parameter, where the contact is and what to write.  Contact points
    K_i = P1 + r (cos kappa_i, sin kappa_i) (4.87-4.90), wrap angle
    ``beta = w_i (kappa1 - kappa2)`` (4.93, shifted by whole turns into
    (0, 2 pi] at t0), wrapped arc ``l_con = r beta`` (4.94).

    Wound lengths (4.95, 4.96; material paid out into the span):

        ctrB1.L = w_i r (phi - kappa1),   ctrB2.L = -w_i r (phi - kappa2)

    with ``phi`` the absolute (world) angle of the pulley.  They are absolute
    (not zero at t0); the spans only use their changes.

    At t0 (after initialization) the pulley checks that ``w_i`` fits how its
    bands are placed: if its two bands cross each other (the band would
    pass through itself, e.g. an Atwood machine with the sign flipped), the
    run stops with an error naming the pulley, the bands and the sign to
    use (see :meth:`start_checks`; bands that both run to other wheels, a
    crossed belt drive, are not checked).

    Forces (4.97-4.99 with the moment sign fixed):
    mass ``m`` at the centre of gravity ``cog`` (pulley frame), inertia
    ``J`` about it, gravity from the PlanarWorld, contact forces at K1, K2,
    bearing force at P1, the flange torques ``ctrR2.tau`` and ``ctrR.tau``
    and the bearing friction ``T_f`` (``friction=True``, see the module
    docstring).  With ``m = J = 0`` (decided from the values at
    construction) the pulley is massless: its force and moment balances are
    algebraic, so at least one of its spans must stay taut.

    Outputs: ``phi``, ``phi_rel``, ``w_rel`` (relative speed), ``xP1``,
    ``yP1`` (the axis), ``kappa1``, ``kappa2``, ``beta``, ``l_con``,
    ``F_bear`` (bearing force magnitude), ``T_f``.
    """
    r = Parameter(0.05, "m", "radius of the belt contour", positive=True)
    n_beta = Parameter(0.0, "1", "whole turns added to the wrap angle (set by prepare_belts)")
    kappa1 = Variable(unit="rad", state_select="avoid", doc="contact angle of K1 (world)")
    kappa2 = Variable(unit="rad", state_select="avoid", doc="contact angle of K2 (world)")
    beta = Variable(unit="rad", state_select="avoid", doc="wrap angle (eq. 4.93)")
    l_con = Variable(unit="m", state_select="avoid", doc="wrapped arc length (eq. 4.94)")

    def __init__(self, w=None, friction=False, **kw):
        super().__init__(w=w, friction=friction, **kw)
        self.ctrK1 = Frame(required=True, doc="contact point K1")
        self.ctrK2 = Frame(required=True, doc="contact point K2")
        self.ctrB1 = BandPort(required=True, doc="band port of K1")
        self.ctrB2 = BandPort(required=True, doc="band port of K2")

    def equations(self):
        w_i = self.w_i
        k1, x1, y1 = self._contact(self.ctrB1, -w_i)        # 4.87, 4.88, 4.91
        k2, x2, y2 = self._contact(self.ctrB2, w_i)         # 4.89, 4.90, 4.92
        K1, K2 = self.ctrK1, self.ctrK2
        eqs = [self.kappa1 == k1, self.kappa2 == k2,
               K1.x == x1, K1.y == y1, K1.phi == self.ctrB1.gamma,
               K2.x == x2, K2.y == y2, K2.phi == self.ctrB2.gamma,
               self.beta == w_i * (self.kappa1 - self.kappa2) + 2 * _PI * self.n_beta,  # 4.93
               self.l_con == self.r * self.beta,                                        # 4.94
               self.ctrB1.L == w_i * self.r * (self.phi - self.kappa1),                 # 4.95
               self.ctrB2.L == -w_i * self.r * (self.phi - self.kappa2)]                # 4.96
        return eqs + self._balance([(K1, x1, y1), (K2, x2, y2)])


_SENSE = {1: "pays the band out at K1 and winds it up at K2",
          -1: "winds the band up at K1 and pays it out at K2"}


def _check_legacy(wheel, given, c0):
    """Error if the former start coordinates x0, y0 of a wheel whose housing
    is connected contradict the start position of its carrier ``c0``
    (beyond round-off of the same geometry, 1e-9 of the distances)."""
    miss = math.hypot(given[0] - c0[0], given[1] - c0[1])
    if miss <= 1e-9 * max(1.0, math.hypot(c0[0], c0[1])):
        return
    raise ModelDefinitionError(
        "%s: contradictory placement: x0=%.6g, y0=%.6g (deprecated) put the axis there at "
        "t0, but ctr2D1 is connected to a frame that starts at (%.6g, %.6g) m, %.3g m away.  "
        "Drop x0, y0 (the start position is taken from what carries the pulley), or give "
        "the offset in that frame as x10=..., y10=... (frameRef='relative', Anhang A.1)"
        % (wheel.describe(), given[0], given[1], c0[0], c0[1], miss))


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
    "Kurvenkontur" of Ebert (2015), Bild 2.1 b/c): the equations of a massless
    :class:`Pulley` (``m = J = 0`` are required), whose angle ``phi`` is here
    the slip coordinate of the band over the contour (the moment balance
    makes both span forces equal).  Fixed in the ground while ``ctr2D1`` is
    unconnected, or carried by a turning wheel (Bild 2.1 c) connected there.

    Topology (Ebert 2015, eq. 2.1): the contour belongs to the link of its housing;
    the two band joints slide (f = 2) and are coupled by the wrapped band
    (one more constraint), so that Bild 2.1 b counts F = 3(5-1) - [4(3-1) +
    2(3-2) + 1] = 1.
    """

    def __init__(self, w=None, **kw):
        super().__init__(w=w, **kw)
        for name in ("m", "J"):
            if float(np.asarray(self.parameter_value(name))) != 0.0:
                raise ModelDefinitionError("%s: a GuideContour is massless; leave %s at 0 "
                                           "(put the mass on the body that carries it)"
                                           % (type(self).__name__, name))

    def topology(self):
        """Contour and contacts rigid with the housing, two sliding band
        joints (f = 2) and their coupling (Ebert 2015, Bild 2.1 b)."""
        items = [] if is_connected(self.ctr2D1) else [("ground", [self.ctr2D1])]
        return items + [("rigid", [self.ctr2D1, self.ctrK1, self.ctrK2]),
                        ("coupling", 1)] + self._contacts(2)
