"""Placement of a wheel's axis by offset (Ebert 2015, Anhang A.1, eq. A.1-A.18,
Tabelle A.1 and 4.15) and the start poses of the frames a wheel may sit on.

A pulley's housing frame PKS1 (origin P1 on the axis) has the constant
offset ``(x10, y10, phi10)`` from the connection frame CKS1 of its port
``ctr2D1`` (``frameRef='relative'``, A.1-A.3), or ``(x10, y10, phi10)`` is
its start pose in the world (``frameRef='global'``), from which the
constant offset follows with the connection's start pose C(0) (A.4-A.6).
While the port is unconnected the connection frame is the world (CKS =
GKS) and both choices place P1 at ``(x10, y10)``.  During the run P1
follows the connection by A.7-A.9 and the port's torque by A.18; the
derivatives A.10-A.15 come from index reduction.

:class:`StartPoses` finds the start pose of the frame ``ctr2D1`` is
connected to from parameters and start values alone (fixed frames, bodies
with start values, rigid rods, rotations and body shapes, revolute joints
with a start angle, prismatic joints with a start travel, nodes and
carriages, and every port of the VDI linkage elements DAN, SAN, DDD, DDS,
DSD, SDS, SSD, FGP by their closed-form start solution of ch. 4.2.1), so
that a pulley on a crank, coupler, slider or body needs no start
coordinates of its own (the tangent construction of the belts needs P1 at
t0).
"""
import math
import warnings

import casadi as ca
import numpy as np

from acausal2d import Frame
from acausal2d.errors import Acausal2dError, ModelDefinitionError
from acausal2d.language.context import ModelContext
from acausal2d.language.unionfind import connector_sets
from acausal2d.library import planar

FRAME_REFS = ("relative", "global")
HALF_PLANES = ("upper", "lower", "left", "right")


def rotate(phi, x, y):
    """Vector (x, y) of a frame with angle phi, resolved in the world
    (A.7, A.8 without the origin; numbers or CasADi expressions)."""
    num = isinstance(phi, (int, float))
    c, s = (math.cos(phi), math.sin(phi)) if num else (ca.cos(phi), ca.sin(phi))
    return c * x - s * y, s * x + c * y


def global_to_relative(pose, conn0):
    """Constant offset (x_rel, y_rel, phi_rel) in the connection frame of the
    world start pose ``pose`` = (x, y, phi), given the connection's start
    pose ``conn0`` (eq. A.4-A.6)."""
    dx, dy = pose[0] - conn0[0], pose[1] - conn0[1]
    c, s = math.cos(conn0[2]), math.sin(conn0[2])
    return dx * c + dy * s, -dx * s + dy * c, pose[2] - conn0[2]


def place(conn, rel):
    """(x, y, phi) of the point frame Pn for the connection frame ``conn``
    (a Frame or a numeric (x, y, phi)) and the offset ``rel`` (A.7-A.9)."""
    x, y, phi = (conn.x, conn.y, conn.phi) if hasattr(conn, "fx") else conn
    dx, dy = rotate(phi, rel[0], rel[1])
    return x + dx, y + dy, phi + rel[2]


def check_frame_ref(owner, frameRef):
    """``frameRef`` if it is one of :data:`FRAME_REFS`, else a
    ModelDefinitionError naming ``owner``."""
    if frameRef not in FRAME_REFS:
        raise ModelDefinitionError(
            "%s: frameRef must be 'relative' (offset in the connection frame of ctr2D1, "
            "Anhang A.1-A.3) or 'global' (start pose in the world, A.4-A.6), not %r"
            % (owner, frameRef))
    return frameRef


def check_half_plane(owner, name, value):
    """The half-plane ``value`` of parameter ``name`` (enumHE1/enumHE2,
    Tabelle 4.16) if valid (None = not given)."""
    if value is not None and value not in HALF_PLANES:
        raise ModelDefinitionError(
            "%s: %s must be one of %s (the half-plane of the contact point around the axis "
            "P1 at t0, Tabelle 4.16), not %r" % (owner, name, ", ".join(map(repr, HALF_PLANES)),
                                                  value))
    return value


def in_half_plane(plane, kappa):
    """True if the contact at the angle ``kappa`` (world) around P1 lies in
    the open half-plane ``plane`` (Tabelle 4.16, Bild 4.20)."""
    c, s = math.cos(kappa), math.sin(kappa)
    return {"upper": s > 0, "lower": s < 0, "left": c < 0, "right": c > 0}[plane]


def half_plane_of(kappa):
    """Names of the half-planes the contact at the angle ``kappa`` lies in,
    the one it lies deeper in first."""
    c, s = math.cos(kappa), math.sin(kappa)
    names = [p for p in HALF_PLANES if in_half_plane(p, kappa)]
    names.sort(key=lambda p: -abs(s if p in ("upper", "lower") else c))
    return " and ".join(names) if names else "on an axis"


_LEGACY = {"x0": "x10", "y0": "y10", "phi0": "phi10"}


def legacy_placement(cls_name, kw):
    """Map the former placement parameters ``x0, y0, phi0`` in ``kw`` onto
    ``x10, y10, phi10`` (changes ``kw``) with a DeprecationWarning saying
    what to write; True if one was given.  They are the axis' start pose in
    the world: ``frameRef='global'`` (on a connected housing they must agree
    with the start pose of what carries it, see :class:`Pulley`)."""
    given = [k for k in _LEGACY if k in kw]
    if not given:
        return False
    clash = [_LEGACY[k] for k in given if _LEGACY[k] in kw]
    if clash:
        raise ModelDefinitionError(
            "%s: give the axis placement either as %s or (deprecated) as %s, not both"
            % (cls_name, ", ".join(clash), ", ".join(given)))
    new = ", ".join("%s=%r" % (_LEGACY[k], kw[k]) for k in given)
    warnings.warn("%s(%s): the parameters x0, y0, phi0 are deprecated; write %s, "
                  "frameRef='global' (Ebert 2015, Tabelle 4.15, Anhang A.1)"
                  % (cls_name, ", ".join("%s=%r" % (k, kw[k]) for k in given), new),
                  DeprecationWarning, stacklevel=4)
    for k in given:
        kw[_LEGACY[k]] = kw.pop(k)
    return True


def winding(cls_name, w, w_i, default=-1):
    """The dissertation's winding direction w_i (eq. 4.95, 4.96: ``w_i = +1`` -- a
    positive turn pays the band out at K1) from ``w_i`` or the deprecated
    ``w`` (``w = -w_i``: ``w = +1`` wound up at K1), with a
    DeprecationWarning for ``w``; ``default`` when neither is given."""
    if w is not None and w_i is not None:
        raise ModelDefinitionError("%s: give the winding direction as w_i (Ebert 2015, eq. 4.95) or "
                                   "(deprecated) as w = -w_i, not both" % cls_name)
    if w is not None:
        if w not in (1, -1):
            raise ModelDefinitionError("%s: winding direction w must be +1 or -1, got %r"
                                       % (cls_name, w))
        warnings.warn("%s(w=%d): w is deprecated; write w_i=%d (the dissertation's winding "
                      "direction, eq. 4.95/4.96: w_i = +1 pays the band out at K1 on a "
                      "positive turn; w_i = -w)" % (cls_name, w, -w),
                      DeprecationWarning, stacklevel=4)
        return -w
    w_i = default if w_i is None else w_i
    if w_i not in (1, -1):
        raise ModelDefinitionError("%s: winding direction w_i must be +1 or -1, got %r"
                                   % (cls_name, w_i))
    return w_i


# ------------------------------------------------------------ start poses
def _numbers(vals):
    """{x, y, phi} of a pre-assembly node as floats, or None where the
    pose is incomplete or not a number (it depends on a variable)."""
    if not vals or not all(k in vals for k in ("x", "y", "phi")):
        return None
    out = {}
    for k in ("x", "y", "phi"):
        v = vals[k]
        if isinstance(v, (ca.SX, ca.MX)):
            if not v.is_constant():
                return None
            v = ca.evalf(v)
        out[k] = float(v)
    return out if all(math.isfinite(v) for v in out.values()) else None


class StartPoses:
    """Start poses (x, y, phi) of the frames of a model at t0 from
    parameters and start values alone (numbers, before the model is bound):
    :class:`~acausal2d.library.planar.Fixed` frames, unconnected housings,
    bodies whose start ``x``/``y`` (and ``phi``) are given, frames seeded by
    a component's ``_linkage_seed()`` (nodes, Carriage mounts), propagated over
    FixedTranslation, FixedRotation, BodyShape, Revolute joints (the angle of a
    revolute's frame_b only where its start ``phi`` is given) and Prismatic
    joints with a start ``s``, wheels rolling on the ground (IdealRolling)
    with a start ``phi``, and through the VDI linkage elements (their
    pre-assembly with the parameters' numbers, :meth:`_linkage_pass`), in
    turn until nothing more follows.  ``pose(conn)``
    is None where a frame's start pose does not follow this way (then it
    needs the initialization)."""

    def __init__(self, model):
        self._sets, self._connected = connector_sets(model)
        self._known = {}
        comps = list(model.components())
        for comp in comps:
            self._seed(comp)
        from acausal2d.library.linkage.base import _Linkage   # the linkage imports planar,
        linkage = [c for c in comps if isinstance(c, _Linkage)]  # which imports the belts
        for _ in range(len(comps) + 1):
            while any([self._propagate(c) for c in comps]):
                pass
            if not (linkage and self._linkage_pass(model, comps, linkage)):
                break

    def _linkage_pass(self, model, comps, linkage):
        """Poses of the VDI linkage elements' ports (DAN, SAN, DDD, DDS,
        DSD, SDS, SSD, FGP, ...) from their closed-form start solution
        (the pre-assembly of ch. 4.2.1, evaluated with the parameters'
        numbers), seeded with the frames known so far; True if a frame
        became known.  Elements whose inputs stay unknown are left out
        (no guessed origin)."""
        from acausal2d.library.linkage.base import _Assembly
        frames = [c for comp in comps for c in comp._connectors.values() if isinstance(c, Frame)]
        known = [(c, dict(zip(("x", "y", "phi"), self.pose(c)))) for c in frames
                 if self.pose(c) is not None]
        saved = [(e, dict(e._rel)) for e in linkage]
        try:
            for e, _ in saved:
                e._rel.clear()
            asm = _Assembly(ModelContext(model), known, fallback=False)
        except (Acausal2dError, RuntimeError):
            return False            # the compilation's own assembly names the element
        finally:
            for e, rel in saved:
                e._rel.clear()
                e._rel.update(rel)
        moved = False
        for conn in frames:
            vals = _numbers(asm.get(conn))
            if vals is not None:
                moved |= self._put(conn, vals)
        return moved

    def pose(self, conn):
        """(x, y, phi) of the node of ``conn`` at t0, or None."""
        v = self._known.get(self._sets.find(id(conn)), {})
        return (v["x"], v["y"], v["phi"]) if all(k in v for k in ("x", "y", "phi")) else None

    def _get(self, conn):
        return self._known.get(self._sets.find(id(conn)), {})

    def _put(self, conn, vals):
        cur = self._known.setdefault(self._sets.find(id(conn)), {})
        new = [k for k in vals if k not in cur]
        for k in new:
            cur[k] = float(vals[k])
        return bool(new)

    def _seed(self, comp):
        pv = comp.parameter_value
        if isinstance(comp, planar.Fixed):
            r = np.asarray(pv("r"), dtype=float)
            self._put(comp.frame, {"x": r[0], "y": r[1], "phi": float(pv("phi"))})
        elif isinstance(comp, planar.Body) and (comp.is_given("x") or comp.is_given("y")):
            self._put(comp.frame_a, {k: comp.start_value(k) for k in ("x", "y", "phi")})
        for conn in comp._connectors.values():
            if isinstance(conn.ground, dict) and id(conn) not in self._connected:
                self._put(conn, conn.ground)
        self._seed_frames(comp)
        unplaced = getattr(comp, "_unconnected_pose", None)
        if unplaced is not None and id(comp.ctr2D1) not in self._connected:
            self._put(comp.ctr2D1, unplaced())

    def _seed_frames(self, comp):
        """Frame poses of a component's ``_linkage_seed()`` (node frames,
        Carriage mounts); components without frames (drives start their
        flanges) are skipped."""
        seed = getattr(comp, "_linkage_seed", None)
        if seed is None or not any(isinstance(c, Frame) for c in comp._connectors.values()):
            return
        for conn, vals in seed():
            if isinstance(conn, Frame):
                self._put(conn, {k: vals[k] for k in ("x", "y", "phi") if k in vals})

    def _propagate(self, comp):
        if isinstance(comp, planar.FixedTranslation):
            r = np.asarray(comp.parameter_value("r"), dtype=float)
            return self._rigid(comp.frame_a, comp.frame_b, (r[0], r[1], 0.0))
        if isinstance(comp, planar.FixedRotation):
            return self._rigid(comp.frame_a, comp.frame_b,
                               (0.0, 0.0, float(comp.parameter_value("alpha"))))
        if isinstance(comp, planar.BodyShape):
            r = np.asarray(comp.parameter_value("r"), dtype=float)
            return self._rigid(comp.frame_a, comp.frame_b, (r[0], r[1], 0.0))
        if isinstance(comp, planar.Revolute):
            return self._revolute(comp)
        if isinstance(comp, planar.IdealRolling) and comp.is_given("phi"):
            phi = comp.start_value("phi")                   # x + R phi = x0, y = R
            R = float(comp.parameter_value("R"))
            return self._put(comp.frame_a, {"x": float(comp.parameter_value("x0")) - R * phi,
                                            "y": R, "phi": phi})
        if isinstance(comp, planar.Prismatic) and comp.is_given("s"):
            r = np.asarray(comp.parameter_value("r"), dtype=float)
            r = r * comp.start_value("s") / float(np.hypot(r[0], r[1]))
            return self._rigid(comp.frame_a, comp.frame_b, (r[0], r[1], 0.0))
        return False

    def _rigid(self, a, b, rel):
        """frame_b at the constant offset ``rel`` from frame_a, both ways."""
        pa, pb = self.pose(a), self.pose(b)
        if pa is not None and pb is None:
            x, y, phi = place(pa, rel)
            return self._put(b, {"x": x, "y": y, "phi": phi})
        if pb is not None and pa is None:
            phi = pb[2] - rel[2]
            dx, dy = rotate(phi, rel[0], rel[1])
            return self._put(a, {"x": pb[0] - dx, "y": pb[1] - dy, "phi": phi})
        return False

    def _revolute(self, comp):
        a, b = self._get(comp.frame_a), self._get(comp.frame_b)
        moved = False
        for src, dst in ((a, comp.frame_b), (b, comp.frame_a)):
            if "x" in src and "y" in src:
                moved |= self._put(dst, {"x": src["x"], "y": src["y"]})
        if comp.is_given("phi"):
            dphi = comp.start_value("phi")
            if "phi" in a:
                moved |= self._put(comp.frame_b, {"phi": a["phi"] + dphi})
            elif "phi" in b:
                moved |= self._put(comp.frame_a, {"phi": b["phi"] - dphi})
        return moved
