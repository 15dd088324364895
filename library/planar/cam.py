"""Cam joint "Kurvengelenk" K (Ebert 2015, Tab. 2.1): a follower in contact with a
cam contour, f = 2 (rolling-sliding) or f = 1 (rolling without slip).

The cam contour is given in the forms of the curved pulley
(:mod:`acausal2d.library.belt.contour`): a polar
:class:`~acausal2d.library.belt.Contour` (circle, function, Fourier series,
table, support-function conversion, or a synthesised cam from
:func:`acausal2d.library.synthesis.contour_export.analysis_contour`) or a
:class:`~acausal2d.library.belt.SupportContour`.  The contact parameter
``q`` is the polar angle kappa of the contact point (polar contour) or the
angle psi of the outward normal there (support contour), both in the cam
frame and unwrapped.  The outward normal angle of a polar contour is
``psi = kappa - atan(r'/r)`` (continuous: r > 0), so no atan2 appears.
"""
import math

import casadi as ca
import numpy as np

from acausal2d import Component, der, Frame, Parameter, Variable
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.belt.contour import Contour, SupportContour

_FOLLOWERS = ("roller", "flat")


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _check_choices(follower, closure, contact, rolling):
    """ModelDefinitionError naming the argument of CamFollower that is wrong."""
    for name, value, allowed in (("follower", follower, _FOLLOWERS),
                                 ("closure", closure, ("force", "form")),
                                 ("contact", contact, ("rigid", "compliant"))):
        if value not in allowed:
            raise ModelDefinitionError("CamFollower: %s must be one of %s, not %r"
                                       % (name, ", ".join(allowed), value))
    if contact == "compliant" and (closure == "form" or rolling):
        raise ModelDefinitionError(
            "CamFollower: contact='compliant' is the force-closed sliding contact (a follower "
            "that can lift off); use it with closure='force' and rolling=False, or "
            "contact='rigid' for a grooved cam or rolling without slip")


def contact_geometry(contour, q):
    """(point (x, y), outward normal angle psi, arc length s) of the contour
    at contact parameter ``q``, CasADi expressions in the cam frame."""
    if isinstance(contour, SupportContour):
        p, dp = contour._sym(q)
        c, s = ca.cos(q), ca.sin(q)
        return (p * c - dp * s, p * s + dp * c), q, contour.s_sym(q)
    if isinstance(contour, Contour):
        r, dr = contour.r_dr_sym(q)
        return (r * ca.cos(q), r * ca.sin(q)), q - ca.atan(dr / r), contour.s_sym(q)
    raise ModelDefinitionError("CamFollower: contour must be a Contour or a SupportContour "
                               "(acausal2d.library.belt), got %r" % (contour,))


_TENSILE = ("the contact force turned tensile (Fn < 0): the follower lifts off the cam, "
            "which the rigid contact cannot follow; use contact='compliant' to follow the free "
            "flight (or closure='form' for a grooved cam)")


class CamFollower(Component):
    """Cam joint K (Ebert 2015, Tab. 2.1) between the cam (``frame_a``, the frame
    the contour is given in) and the follower (``frame_b``).

    ``CamFollower(contour, follower="roller"|"flat", rolling=False,
    closure="force"|"form", contact="rigid"|"compliant", r_roller=...,
    q=start(...))``.

    - ``follower="roller"``: ``frame_b`` is the roller centre, at the
      distance ``r_roller`` from the contour along its outward normal (a
      knife edge with ``r_roller = 0``).  f = 2: the roller slides and
      rolls (its spin does not matter: frame_b's angle is free); with
      ``rolling=True`` (f = 1) frame_b is the roller itself and rolls
      without slip: ``s(q) + r_roller (phi_a + psi - phi_b) = s0``.
    - ``follower="flat"``: ``frame_b`` lies on the flat face, whose line has
      the direction angle ``phi_b``; the cam touches it from the left
      (the cam's outward normal at the contact is ``phi_b - pi/2``).  f = 2;
      ``rolling=True``: ``s(q) - (K - B).e_b = s0``.

    Position equations only: the contact point ``K`` (``xK, yK``), the
    normal angle ``psi`` (world ``phi_a + psi``) and the constant ``s0``
    (rolling; found at initialization).  Forces: the normal force ``Fn``
    (compression positive, pushing the follower away from the cam) and the
    tangential force ``Ft`` (rolling only) act at K; the element is massless.

    ``contact="rigid"`` (default): a bilateral constraint.  With
    ``closure="form"`` (a groove) the contact force takes both signs.  With
    ``closure="force"`` (kraftschluessig: a spring or gravity holds the
    follower on the cam) the run ends with an error naming this element and
    the time when ``Fn`` turns negative (``lifted`` becomes 1 at that event).

    ``contact="compliant"`` (force closure, sliding): the follower keeps its
    freedom along the normal; ``delta`` is the penetration from the geometry
    (roller: ``r_roller - (B - K).u`` with K the contour point whose normal
    passes through B; flat: ``(K - B).u`` with K the contour point whose
    normal is the face's) and the normal force is the compression-only law
    ``Fn = k_contact delta + d_contact der(delta)`` while ``delta > 0`` and
    that is positive, else 0 (``Fs`` is the linear law, ``lifted`` = 1
    while ``delta <= 0``).  Lift-off and re-contact are the events
    ``cam.delta <= 0`` and ``max(cam.Fs, 0)``.  The element is then a
    force element (no joint in eq. 2.1).
    """
    r_roller = Parameter(0.0, "m", "roller radius (0: knife edge)", min=0.0)
    k_contact = Parameter(1e7, "N/m", "normal contact stiffness (compliant contact)",
                          positive=True)
    d_contact = Parameter(300.0, "N*s/m", "normal contact damping (compliant contact)", min=0.0)

    q = Variable(unit="rad", doc="contact parameter (polar or normal angle in the cam frame)")
    psi = Variable(unit="rad", doc="outward normal angle of the contour at K (cam frame)")
    xK = Variable(unit="m", doc="contact point K, x")
    yK = Variable(unit="m", doc="contact point K, y")
    Fn = Variable(unit="N", doc="normal contact force (compression positive)")
    Ft = Variable(unit="N", doc="tangential contact force (rolling; 0 otherwise)")
    s0 = Variable(unit="m", state_select="avoid", doc="rolling constant (found at start)")
    lifted = Variable(unit="1", doc="1 when the follower is off the cam (or Fn < 0, rigid)")
    delta = Variable(unit="m", doc="penetration (compliant contact; 0 rigid)")
    Fs = Variable(unit="N", doc="linear law k delta + d der(delta) (compliant; Fn rigid)")

    def __init__(self, contour, follower="roller", rolling=False, closure="force",
                 contact="rigid", **kw):
        _check_choices(follower, closure, contact, rolling)
        super().__init__(**kw)
        if contact == "compliant" and follower == "roller" and not self.r_roller > 0:
            raise ModelDefinitionError(
                "CamFollower: a compliant knife edge (r_roller = 0) has no contact normal when "
                "its tip touches the contour; give r_roller > 0 (e.g. 1e-4 m)")
        contact_geometry(contour, ca.SX.sym("q"))       # refuses other contours early
        self.contour, self.follower = contour, follower
        self.rolling, self.closure, self.contact = bool(rolling), closure, contact
        self.frame_a = Frame(doc="cam frame (the contour's frame)")
        self.frame_b = Frame(doc="follower: roller centre or a point of the flat face")

    def _world(self):
        """Contact point K, outward unit normal u and its angle (world)."""
        a = self.frame_a
        (px, py), psi, s = contact_geometry(self.contour, self.q)
        c, sn = ca.cos(a.phi), ca.sin(a.phi)
        K = (a.x + c * px - sn * py, a.y + sn * px + c * py)
        ang = a.phi + self.psi
        return K, (ca.cos(ang), ca.sin(ang)), ang, psi, s

    def _placement(self, K, u, ang, s):
        """Where the follower is against the contact point: (equations,
        penetration or None for the rigid contact, rolling expression)."""
        b = self.frame_b
        BK = (K[0] - b.x, K[1] - b.y)
        if self.follower == "roller":
            roll = s + self.r_roller * (ang - b.phi)
            if self.contact == "compliant":
                return [_cross(BK, u) == 0], self.r_roller + BK[0] * u[0] + BK[1] * u[1], roll
            return [b.x == K[0] + self.r_roller * u[0],
                    b.y == K[1] + self.r_roller * u[1]], None, roll
        roll = s - (BK[0] * ca.cos(b.phi) + BK[1] * ca.sin(b.phi))
        pen = BK[0] * u[0] + BK[1] * u[1]
        if self.contact == "compliant":
            return [ang == b.phi - math.pi / 2], pen, roll
        return [ang == b.phi - math.pi / 2, pen == 0], None, roll

    def _normal_force(self, pen):
        """Closure and contact law: Fn, delta, Fs and lifted."""
        if pen is None:
            eqs = [self.delta == 0, self.Fs == self.Fn]
            if self.closure == "force":
                return eqs + [self.lifted == ca.if_else(self.Fn < 0, 1.0, 0.0)]
            return eqs + [self.lifted == 0]
        off = self.delta <= 0
        return [self.delta == pen,
                self.Fs == self.k_contact * self.delta + self.d_contact * der(self.delta),
                self.Fn == ca.if_else(off, 0.0, ca.fmax(self.Fs, 0.0)),
                self.lifted == ca.if_else(off, 1.0, 0.0)]

    def equations(self):
        a, b = self.frame_a, self.frame_b
        K, u, ang, psi, s = self._world()
        t = (-u[1], u[0])
        eqs = [self.psi == psi, self.xK == K[0], self.yK == K[1]]
        place, pen, roll = self._placement(K, u, ang, s)
        eqs += place + self._normal_force(pen)
        if self.rolling:
            eqs += [roll == self.s0, der(self.s0) == 0]
        else:
            eqs += [self.Ft == 0, self.s0 == 0]
        fB = (-(self.Fn * u[0] + self.Ft * t[0]), -(self.Fn * u[1] + self.Ft * t[1]))
        tB = _cross((K[0] - b.x, K[1] - b.y), fB)
        return eqs + [b.fx == fB[0], b.fy == fB[1], b.t == tB,
                      a.fx + b.fx == 0, a.fy + b.fy == 0,
                      a.t + b.t + _cross((b.x - a.x, b.y - a.y), fB) == 0]

    def assertions(self):
        """A rigid force-closed contact ends the run when Fn turns tensile."""
        if self.contact == "rigid" and self.closure == "force":
            return [("lifted", _TENSILE)]
        return []

    def topology(self):
        """A joint of f = 2 (rolling-sliding) or 1 (rolling) between cam and
        follower (Ebert 2015, Tab. 2.1, eq. 2.1); none for the compliant contact
        (a force element: the follower keeps its freedom)."""
        if self.contact == "compliant":
            return []
        return [("joint", self.frame_a, self.frame_b, 1 if self.rolling else 2)]

    def shapes(self):
        """The cam contour (sampled, turned with frame_a, drawn as a pulley
        of that outline), the contact point and the line to the follower."""
        x, y = self.contour.point(np.linspace(0.0, 2 * math.pi, 240, endpoint=False))
        pts = [[float(a), float(b)] for a, b in zip(x, y)]
        return [{"type": "pulley", "x": "frame_a.x", "y": "frame_a.y",
                 "r": float(np.max(np.hypot(x, y))), "phi": "frame_a.phi", "contour": pts},
                {"type": "link", "points": [["xK", "yK"], ["frame_b.x", "frame_b.y"]],
                 "width": 0.01},
                {"type": "joint", "x": "xK", "y": "yK"}]

    def lift_off(self, res):
        """Time of the first lift-off in the result ``res`` (the first
        output time with ``lifted = 1``), or None."""
        changes = self.contact_changes(res)
        return changes[0][0] if changes and changes[0][1] == "lift-off" else None

    def contact_changes(self, res):
        """[(t, "lift-off" | "re-contact")] of the result ``res``: the
        switches of ``lifted`` (at the event times, which are output rows)."""
        flag = np.asarray(res[self.path + ".lifted"]) > 0.5
        idx = np.nonzero(flag[1:] != flag[:-1])[0] + 1
        return [(float(res.time[k]), "lift-off" if flag[k] else "re-contact") for k in idx]
