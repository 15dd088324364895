"""Position correction of node/constraint models by corrective impulses
(Schnabel and Gössner's eq. 3-16; the algorithm of cstr.js's ``correct()``), and the
velocity correction by impulses of eq. 6-10
(:meth:`PositionCorrection.correct_velocities`).

A constraint between two nodes corrects their positions by the impulse of
eq. 11, ``dq = -W J^T m_c C(q)``, which for the two constraint kinds reads

* orientation (eq. 15, 16): ``d = (p2 - p1) . e~`` with e~ the normal of
  the target direction; ``p1 <- p1 + (m_c/m1) d e~``,
  ``p2 <- p2 - (m_c/m2) d e~``;
* length (eq. 12-14): ``d = |p2 - p1| - r`` (cstr.js corrects only when
  ``|d| > lentol``); ``p1 <- p1 + (m_c/m1) d e``, ``p2 <- p2 - (m_c/m2)
  d e``;

with ``m_c = 1/(1/m1 + 1/m2)`` (eq. 13) and inverse mass 0 for base
nodes.  One *sweep* corrects every constraint once (angle first, then
length).  Sweeps repeat until no correction exceeds ``lentol`` (the
number of sweeps is reported) or ``itrmax`` sweeps are done; then the
positions are undone to the state before the last sweep and the result
reports failure, as cstr.js does.  Details of cstr.js that Schnabel and Gössner's talk does
not show are kept: a node's mass grows by one for every correction it
received in the current sweep (its "dynamic mass" ``dym``), a mass of 0
counts as 1, a three-node constraint moves only its third node.

:class:`PositionCorrection` works on the plain description of a node model
(:meth:`acausal2d.library.nodes.NodeModel.node_system`) and serves as the
kinematic solver (prescribe the drives, correct step by step) and as the
assembly that turns rough coordinates into consistent start values."""
import math

import numpy as np

from acausal2d.errors import ModelDefinitionError

__all__ = ["PositionCorrection", "Correction"]

TWO_PI = 2 * math.pi
_EPS = float(np.finfo(float).eps)


class Correction:
    """Outcome of one :meth:`PositionCorrection.correct`: ``converged``,
    ``iterations`` (sweeps done; Schnabel and Gössner's "itr"), ``undone`` (positions
    reset to before the last sweep after a failure) and the constraint with
    the largest correction in the last sweep (``worst``, ``largest``)."""

    def __init__(self, converged, iterations, worst, largest):
        self.converged, self.iterations = converged, iterations
        self.undone = not converged
        self.worst, self.largest = worst, largest

    def __repr__(self):
        return "Correction(converged=%s, iterations=%d, largest=%.3g in %r)" % (
            self.converged, self.iterations, self.largest, self.worst)


class _Node:
    __slots__ = ("id", "x", "y", "m", "base", "dym")

    def __init__(self, d):
        self.id, self.x, self.y = d["id"], float(d["x"]), float(d["y"])
        self.m = float(d.get("m", 1.0)) or 1.0          # cstr.js: m || 1
        self.base = bool(d.get("base", False))
        self.dym = 0.0


def _weights(n1, n2):
    """Shares m_c/m_1, m_c/m_2 of eq. 13 (cstr.js mc_m1, mc_m2)."""
    im1 = 0.0 if n1.base else 1.0 / (n1.m + n1.dym)
    im2 = 0.0 if n2.base else 1.0 / (n2.m + n2.dym)
    total = im1 + im2
    return (im1 / total, im2 / total) if total else (im1, im2)


class PositionCorrection:
    """The position correction of eq. 3-16 on a node system (see module
    doc).  ``system``: the dict of
    :meth:`~acausal2d.library.nodes.NodeModel.node_system` (nodes with x,
    y, m, base; constraints with their len/ang specifications).
    ``lentol`` [m] and ``itrmax`` default to the system's values (cstr.js:
    0.1 length units, 256)."""

    def __init__(self, system, lentol=None, itrmax=None):
        self.nodes = {d["id"]: _Node(d) for d in system["nodes"]}
        self.cstrs = [dict(c) for c in system["constraints"]]
        self.by_id = {c["id"]: c for c in self.cstrs}
        self.lentol = float(lentol if lentol is not None else system.get("lentol", 0.1))
        self.itrmax = int(itrmax if itrmax is not None else system.get("itrmax", 256))
        self.t = 0.0
        self._now = {}                       # drive values at self.t
        for c in self.cstrs:
            c["_nodes"] = [self.nodes[c[k]] for k in ("n1", "n2", "n3") if k in c]
            c["_moving"] = [n for n in c["_nodes"] if not n.base]
            if c["type"] == "n2":
                c["wu"] = math.atan2(*reversed(self.vector(c)))

    # ------------------------------------------------------------ geometry
    def vector(self, c, a="n1", b="n2"):
        """Vector from node ``c[a]`` to node ``c[b]`` of constraint record ``c``."""
        p, q = self.nodes[c[a]], self.nodes[c[b]]
        return q.x - p.x, q.y - p.y

    def length(self, cid):
        """Current length |p2 - p1| of constraint ``cid``."""
        return math.hypot(*self.vector(self.by_id[cid]))

    def angle(self, cid):
        """Current angle of constraint ``cid``, unwrapped (continuous with
        its previous value, like mec2's infinite angle)."""
        c = self.by_id[cid]
        a = math.atan2(*reversed(self.vector(c)))
        c["wu"] = a + TWO_PI * round((c["wu"] - a) / TWO_PI)
        return c["wu"]

    def value(self, cid, kind):
        """Current length ('len') or unwrapped angle ('ang') of ``cid``."""
        return self.length(cid) if kind == "len" else self.angle(cid)

    def positions(self):
        """{node id: (x, y)} of all nodes."""
        return {k: (n.x, n.y) for k, n in self.nodes.items()}

    def set_position(self, nid, x, y):
        """Move node ``nid`` (e.g. dragged) before the next correction."""
        self.nodes[nid].x, self.nodes[nid].y = float(x), float(y)

    # ------------------------------------------------------------ targets
    def target(self, c, kind):
        """Target value of the constraint's length or angle at the current
        time, or None where it is free (cstr.js getters, mec2 refs)."""
        spec = c.get(kind) or {"kind": "free"}
        k = spec["kind"]
        if k == "free":
            return None
        if k == "value":
            return spec["value"]
        if k == "drive":
            z = self._drive_value(c["id"], kind, spec)
            if z is None:
                return None                  # released (dragging)
        elif k == "range":
            z = self.value(c["id"], kind)
        else:
            z = self._coupled(c, spec)
        lo, hi = spec.get("lo"), spec.get("hi")
        if hi is not None and z > hi:
            z = hi
        if lo is not None and z < lo:
            z = lo
        return z

    def _drive_value(self, cid, kind, spec):
        key = (cid, kind)
        if key not in self._now:
            at = spec.get("at")
            self._now[key] = None if at is None else at(self.t)
        return self._now[key]

    def _coupled(self, c, spec):
        k = spec["kind"]
        plus = spec["plus"](self.t) if spec.get("plus") is not None else 0.0
        if k == "ref":
            return spec["ratio"] * self.value(spec["ref"], spec["of"]) + spec["offset"] + plus
        if k == "delta":
            w1, w2 = self.angle(spec["from"]), self.angle(spec["to"])
            return w1 + spec["scl"] * (w2 - w1) + spec.get("offset", 0.0)
        if k == "ang_from_len":
            r = self.length(c["id"]) or 1.0
            return spec["base"] + spec["ratio"] * (self.length(spec["ref"]) - spec["ref0"]) / r \
                + plus
        if k == "len_from_ang":
            return spec["base"] + spec["ratio"] * self.length(spec["ref"]) * \
                (self.angle(spec["ref"]) - spec["ref0"]) + plus
        raise ValueError("unknown constraint value kind %r in %s" % (k, c["id"]))

    # ------------------------------------------------------------ corrections
    def _correct_len(self, c, r):
        n1, n2 = c["_nodes"]
        x12, y12 = n2.x - n1.x, n2.y - n1.y
        cur = math.hypot(x12, y12)
        dr = r - cur
        if abs(dr) <= self.lentol:
            return 0.0
        ex, ey = (x12 / cur, y12 / cur) if cur > _EPS else (1.0, 0.0)
        w1, w2 = _weights(n1, n2)
        n1.x -= w1 * dr * ex
        n1.y -= w1 * dr * ey
        n2.x += w2 * dr * ex
        n2.y += w2 * dr * ey
        n1.dym += 1
        n2.dym += 1
        return abs(dr)

    def _correct_ang(self, c, w):
        n1, n2 = c["_nodes"]
        x12, y12 = n2.x - n1.x, n2.y - n1.y
        ca, sa = math.cos(w), math.sin(w)
        de = -x12 * sa + y12 * ca                            # eq. 15: d = (p2 - p1) . e~
        dx, dy = -de * sa, de * ca
        if c.get("dir"):                                     # cstr.js: directional
            re = math.copysign(1.0, c["dir"]) * (x12 * ca + y12 * sa)
            if re <= 0:
                dx, dy = 2 * re * ca - de * sa, 2 * re * sa + de * ca
        w1, w2 = _weights(n1, n2)
        n1.x += w1 * dx                                      # eq. 16
        n1.y += w1 * dy
        n2.x -= w2 * dx
        n2.y -= w2 * dy
        n1.dym += 1
        n2.dym += 1
        return max(abs(dx), abs(dy))

    def _correct_n3(self, c):
        n1, n2, n3 = c["_nodes"]
        x12, y12 = n2.x - n1.x, n2.y - n1.y
        r12 = math.hypot(x12, y12)
        if r12 <= math.sqrt(_EPS):
            return 0.0
        c12, s12 = x12 / r12, y12 / r12
        ca, sa = math.cos(c["value"]), math.sin(c["value"])
        c12a, s12a = c12 * ca - s12 * sa, s12 * ca + c12 * sa
        o13 = -(n3.x - n1.x) * s12a + (n3.y - n1.y) * c12a   # orthogonal projection
        dx, dy = -o13 * s12a, o13 * c12a
        share = _weights(n1, n3)[1]             # cstr.js: im3 / (im1 + im3)
        n3.x -= share * dx
        n3.y -= share * dy
        n3.dym += 1
        return max(abs(dx), abs(dy))

    def _correct_one(self, c):
        """Corrections of one constraint (angle first); the largest move."""
        if c["type"] == "n3":
            return self._correct_n3(c)
        move = 0.0
        w = self.target(c, "ang")
        if w is not None:
            move = self._correct_ang(c, w)
        r = self.target(c, "len")
        if r is not None:
            move = max(move, self._correct_len(c, r))
        return move

    def _sweep(self):
        """One sweep over all constraints; (largest move, its constraint)."""
        for c in self.cstrs:
            for n in c["_moving"]:
                n.dym = 0.0
        largest, worst = 0.0, None
        for c in self.cstrs:
            move = self._correct_one(c)
            if move >= largest:
                largest, worst = move, c["id"]
        return largest, worst

    def correct(self, t=None):
        """Correct the positions at time ``t`` (drive values; default: the
        current time) by sweeps of eq. 14/16; returns a :class:`Correction`.
        On failure after ``itrmax`` sweeps the last sweep is undone."""
        if t is not None and float(t) != self.t:
            self.t, self._now = float(t), {}
        largest, worst = 0.0, None
        for itr in range(1, self.itrmax + 1):
            saved = {k: (n.x, n.y) for k, n in self.nodes.items()}
            largest, worst = self._sweep()
            if largest < self.lentol:
                self._track_angles()
                return Correction(True, itr, worst, largest)
        for k, (x, y) in saved.items():
            self.nodes[k].x, self.nodes[k].y = x, y
        self._track_angles()
        return Correction(False, self.itrmax, worst, largest)

    # ------------------------------------------------ velocities (eq. 6-10)
    def _velocity_rows(self, rates):
        """One row per active two-node length or angle constraint: (id,
        kind, node 1, node 2, unit direction u of its Jacobian J = (-u, u),
        the time-dependent part C_t = -s * rate)."""
        rows = []
        for c in self.cstrs:
            if c["type"] != "n2":
                raise ModelDefinitionError(
                    "constraint %r: the velocity correction takes two-node constraints only "
                    "(type n2), not %r; express it by n2 constraints" % (c["id"], c["type"]))
            n1, n2 = c["_nodes"]
            x12, y12 = n2.x - n1.x, n2.y - n1.y
            cur = math.hypot(x12, y12)
            if cur <= _EPS or not c["_moving"]:
                continue
            ex, ey = x12 / cur, y12 / cur
            for kind, u, s in (("ang", (-ey, ex), cur), ("len", (ex, ey), 1.0)):
                if self.target(c, kind) is not None:
                    rows.append((c["id"], kind, n1, n2, u, -s * rates.get((c["id"], kind), 0.0)))
        return rows

    def correct_velocities(self, velocities, rates=None, tol=1e-12, itrmax=None):
        """Correct node velocities by impulses (Schnabel and Gössner's eq. 6-10) so that
        ``J q' + C_t = 0`` (eq. 4) holds at the current positions.  For each
        active two-node constraint row C (length: ``|p2 - p1| - r``, angle:
        ``(p2 - p1) . e~``) with ``J = (-u, u)`` the violated velocity balance
        ``C' = J q' + C_t`` gets the corrective impulse ``lambda dt = -m_c C'``
        (eq. 9, ``m_c = (J W J^T)^-1 = 1/(1/m1 + 1/m2)``, eq. 13) and the
        velocities change by ``dq' = W J^T lambda dt`` (eq. 10), base nodes
        not at all.  Sweeps over all rows repeat until every ``|C'| <= tol``
        [m/s] or ``itrmax`` sweeps are done (default: the position
        correction's).  ``velocities``: {node id: (vx, vy)} (base nodes may
        be left out: at rest); ``rates``: {(constraint id, 'len' or 'ang'):
        dr/dt or dw/dt} of driven constraints (default 0).  Returns the
        corrected velocities and a :class:`Correction` (``largest`` the
        largest ``|C'|`` met in the last sweep; velocities are never
        undone).  The impulses act along the constraints only (eq. 7, no
        impressed forces), so with C_t = 0 each one is a projection in the
        metric of M: the kinetic energy falls by ``m_c C'^2 / 2`` per
        impulse, and velocities that satisfy eq. 4 are not changed."""
        for n in self.nodes.values():
            n.dym = 0.0                      # the plain masses of eq. 13
        v = {k: [0.0, 0.0] for k in self.nodes}
        for k, (vx, vy) in velocities.items():
            v[k] = [float(vx), float(vy)]
        rows = self._velocity_rows(rates or {})
        itrmax = int(itrmax if itrmax is not None else self.itrmax)
        largest, worst = 0.0, None
        for itr in range(1, itrmax + 1):
            largest, worst = 0.0, None
            for cid, kind, n1, n2, u, c_t in rows:
                v1, v2 = v[n1.id], v[n2.id]
                rate = u[0] * (v2[0] - v1[0]) + u[1] * (v2[1] - v1[1]) + c_t     # C'
                if abs(rate) >= largest:
                    largest, worst = abs(rate), (cid, kind)
                w1, w2 = _weights(n1, n2)                  # m_c/m1, m_c/m2 (eq. 13)
                v1[0] += w1 * rate * u[0]
                v1[1] += w1 * rate * u[1]
                v2[0] -= w2 * rate * u[0]
                v2[1] -= w2 * rate * u[1]
            if largest <= tol:
                break
        report = Correction(largest <= tol, itr, worst, largest)
        report.undone = False
        return {k: tuple(x) for k, x in v.items()}, report

    def _track_angles(self):
        for c in self.cstrs:
            if c["type"] == "n2":
                self.angle(c["id"])

    def kinematics(self, times):
        """The kinematic solver of Schnabel and Gössner's talk: for each time, prescribe the
        drives and correct from the previous positions.  Returns
        ``(positions, reports)``: {node id: array of shape (len(times), 2)}
        and the :class:`Correction` of every step."""
        out = {k: np.empty((len(times), 2)) for k in self.nodes}
        reports = []
        for i, t in enumerate(times):
            reports.append(self.correct(t))
            for k, n in self.nodes.items():
                out[k][i] = n.x, n.y
        return out, reports

    def residuals(self):
        """{constraint id: largest deviation from its targets} at the current
        positions and time: the length error and the distance of node 2
        from the line of the target angle (two-node constraints, length
        units), the sine of the angle error (three-node constraints)."""
        out = {}
        for c in self.cstrs:
            if c["type"] == "n3":
                (x12, y12), (x13, y13) = self.vector(c), self.vector(c, "n1", "n3")
                a = math.atan2(x12 * y13 - y12 * x13, x12 * x13 + y12 * y13) - c["value"]
                out[c["id"]] = abs(math.sin(a))
                continue
            dev = 0.0
            r, w = self.target(c, "len"), self.target(c, "ang")
            if r is not None:
                dev = abs(self.length(c["id"]) - r)
            if w is not None:
                x, y = self.vector(c)
                dev = max(dev, abs(-x * math.sin(w) + y * math.cos(w)))
            out[c["id"]] = dev
        return out
