"""Elements of the node/constraint front end (Schnabel and Gössner's talk "Lightweight
prototypal mechanism simulation on the web", Schnabel/Goessner; cstr.js
and mec2): nodes are point masses, constraints the polar vector between two
nodes (talk eq. 3: ``p2 - p1 = r e(w)``).

Build models with :class:`acausal2d.library.nodes.NodeModel`; this module
holds what a node model compiles into:

* :class:`NodePort` - the connector of a node: position x, y; force fx, fy
  acting on the element from the node (flows sum to zero at the node).
* :class:`Node` - a point mass m (talk "Nodes": x, y, m, base) or, with
  ``base=True``, a point fixed to ground.  Talk eq. 5 with Q = gravity:
  ``m p'' = sum of constraint forces + m g``.  Its lazily created
  :attr:`Node.frame` joins library frames to the node (a pin).
* :class:`Link` - the two-node constraint ``n2`` in polar form (eq. 3): the
  unknowns r (length) and w (angle, unwrapped, no atan2) with
  ``p2 - p1 = r (cos w, sin w)``; the length is the potential of the
  translational flange ``len`` and the angle that of the rotational flange
  ``ang``.  An unconnected flange carries no force: the value is free.
  Holding, driving or coupling a value is done by the element connected to
  its flange (:class:`AngleHold`/:class:`LengthHold`,
  :class:`AngleDrive`/:class:`LengthDrive`,
  :class:`Coupling`), whose flange force is the constraint force (the
  Lagrange multiplier of eq. 5).  :attr:`Link.frame` is the plane of the
  constraint at p1 (angle w) for library elements riding on it.
* :class:`IncludedAngle` - the three-node constraint ``n3``: the angle from
  n1->n2 to n1->n3 (the lines, not the rays: cstr.js corrects only the
  orthogonal component).
* :class:`NodeForce`, :class:`NodeSpring` - the loads of mec2.

All elements are massless except the nodes; each writes position-level
equations and force balances only."""
from typing import Optional
import casadi as ca

from acausal2d import (Component, Connector, der, Frame, Outer, Parameter, RotationalFlange,
                       time, TranslationalFlange, Variable)
from acausal2d.language.dsl import add_declarations
from acausal2d.library.planar import PlanarWorld

__all__ = ["NodePort", "Node", "Link", "IncludedAngle", "AngleHold", "LengthHold",
           "AngleDrive", "LengthDrive", "Coupling", "NodeForce", "NodeSpring"]


class NodePort(Connector):
    """Connector of a node: position x, y [m] (potentials) and the force
    fx, fy [N] acting on the element from the node (flows)."""
    kind = "NodePort"
    potentials = ("x", "y")
    flows = ("fx", "fy")
    units = {"x": "m", "y": "m", "fx": "N", "fy": "N"}


def _lazy_frame(comp):
    """The component's frame, created on first use (a frame nobody connects
    would leave its angle undetermined)."""
    if "frame" not in comp._connectors:
        comp.frame = Frame(doc="frame for library elements")
    return comp._connectors["frame"]


def _assembly_guesses(comp, context):
    """Start guesses of ``comp`` from the node assembly of the node model
    it belongs to (nothing outside a node model)."""
    owner = _owner(comp)
    return owner.node_guesses(context, comp) if owner is not None else {}


def _owner(comp):
    owner = comp._parent
    while owner is not None and not hasattr(owner, "node_guesses"):
        owner = owner._parent
    return owner


def _frame_seed(comp, values):
    """Start pose of the component's frame for the VDI pre-assembly of
    linkage elements riding on it (``_linkage_seed`` protocol of
    library/linkage.py)."""
    frame = comp._connectors.get("frame")
    owner = _owner(comp)
    if frame is None or owner is None:
        return []
    start = owner.assembly_values().get(id(comp), {})
    return [(frame, values(start))] if start else []


def _force_terms(comp):
    """(fx, fy) of the optional frame (zero without one)."""
    f = comp._connectors.get("frame")
    return (f.fx, f.fy) if f is not None else (0, 0)


class Node(Component):
    """A node of Schnabel and Gössner's talk (slide "4) Implementierung - Nodes": x, y, m,
    base): a point mass without extent and rotation (talk eq. 5,
    ``m p'' = J^T lambda + Q`` with Q the weight), or a point fixed to
    ground at (x0, y0) when ``base=True`` (m = infinity).

    ``x0, y0`` are the coordinates as given: the position of a base node,
    the rough start of a moving node (the node assembly, talk eq. 3-16,
    turns them into consistent start values).  ``m = 0`` makes a massless
    point (decided when the model is compiled).  ``counted=False`` leaves
    the node and its constraints out of Schnabel and Gössner's eq. 1/2 counts (the
    needle-bar drive's point G, "G nicht beachtet").

    Connectors: ``port`` (the constraints), ``frame`` (created on first
    use): a pin at the node for frames of library elements - a base
    node's frame is fixed to ground with angle 0; a moving node's frame
    passes no torque (t = 0), so its angle must come from the element
    connected to it (a link plane such as a VDI output frame)."""
    world = Outer(PlanarWorld)
    x0 = Parameter(0.0, "m", "x coordinate as given (base: position; else rough start)")
    y0 = Parameter(0.0, "m", "y coordinate as given (base: position; else rough start)")
    m = Parameter(1.0, "kg", "mass of the node (0: massless point)", min=0.0)
    x = Variable(unit="m", doc="x position")
    y = Variable(unit="m", doc="y position")

    def __init__(self, base=False, counted=True, **kw):
        super().__init__(**kw)
        self.base = bool(base)
        self.counted = bool(counted)
        self.port = NodePort(doc="constraints and loads")

    @property
    def frame(self):
        """Frame at the node for library elements (see class doc)."""
        return _lazy_frame(self)

    def _linkage_seed(self):
        """The frame's start pose for VDI elements on it (a moving node's
        angle comes from the element itself)."""
        base = self.base
        return _frame_seed(self, lambda v: dict(
            {"x": v["x"], "y": v["y"]}, **({"phi": 0.0} if base else {})))

    def guesses(self, context):
        """Start values from the node assembly (talk eq. 3-16)."""
        return _assembly_guesses(self, context)

    def equations(self):
        p, fr = self.port, self._connectors.get("frame")
        eqs = [p.x == self.x, p.y == self.y]
        if fr is not None:
            eqs += [fr.x == self.x, fr.y == self.y]
        if self.base:
            eqs += [self.x == self.x0, self.y == self.y0]
            if fr is not None:
                eqs.append(fr.phi == 0)
            return eqs
        if fr is not None:
            eqs.append(fr.t == 0)
        ffx, ffy = _force_terms(self)
        g = self.world.g
        if float(self.parameter_value("m")) == 0.0:
            return eqs + [0 == p.fx + ffx, 0 == p.fy + ffy]
        return eqs + [self.m * der(der(self.x)) == p.fx + ffx + self.m * g[0],
                      self.m * der(der(self.y)) == p.fy + ffy + self.m * g[1]]

    def shapes(self):
        label = {"type": "label", "x": "x", "y": "y", "text": self._name or ""}
        if self.base:
            return [{"type": "ground", "x": "x", "y": "y"}, label]
        return [{"type": "joint", "x": "x", "y": "y"}, label]


class Link(Component):
    """Two-node constraint ``n2`` in polar form (talk eq. 3,
    ``C(q) = (p2 - p1) - r e(w) = 0``): r and w are unknowns with
    ``p2 - p1 = r (cos w, sin w)``; w is continuous (unwrapped), r may turn
    negative only where nothing holds it (a free length along a held
    direction: cstr.js's ``dir = 0``).

    The massless link's balances (virtual work with the node forces b.f at
    p2, a.f at p1, the frame's force and torque at p1 and the flange
    forces): ``a.f + b.f + frame.f = 0``, along r: ``e.b.f + len.f = 0``,
    about p1 for w: ``r n.b.f + frame.t + ang.tau = 0`` (n = e rotated by
    90 deg).  With a flange unconnected its force is zero, so the value is
    free; an element holding the value supplies the constraint force
    (talk eq. 5, ``J^T lambda``; mec2's ``force = -lambda_r``, ``moment``).

    Connectors: ``a`` (node 1), ``b`` (node 2), ``len``
    (TranslationalFlange, s = r), ``ang`` (RotationalFlange, phi = w),
    ``frame`` (created on first use): the constraint's plane at p1, angle w.
    ``draw``: 'bar' (a rigid link), 'slider' (a guide along w with a block
    at node 2) or None.  r and w are preferred states (the natural
    coordinates of a node mechanism that moves under forces: a crank angle,
    a slider travel), so a free-moving model starts exactly at its given
    angles."""
    r = Variable(unit="m", doc="length |p2 - p1| (signed where only the angle is held)",
                 state_select="prefer")
    w = Variable(unit="rad", doc="angle of p2 - p1 against the x axis (unwrapped)",
                 state_select="prefer")

    def __init__(self, draw="bar", **kw):
        super().__init__(**kw)
        self.draw = draw
        self.a = NodePort(doc="node 1")
        self.b = NodePort(doc="node 2")
        self.len = TranslationalFlange(doc="length r")
        self.ang = RotationalFlange(doc="angle w")

    @property
    def frame(self):
        """The constraint's plane at node 1, angle w (see class doc)."""
        return _lazy_frame(self)

    def _linkage_seed(self):
        """The frame's start pose (node 1, angle w) for VDI elements on it."""
        return _frame_seed(self, lambda v: {"x": v["x1"], "y": v["y1"], "phi": v["w"]})

    def guesses(self, context):
        """Start values from the node assembly (talk eq. 3-16)."""
        return _assembly_guesses(self, context)

    def equations(self):
        a, b, fr = self.a, self.b, self._connectors.get("frame")
        c, s = ca.cos(self.w), ca.sin(self.w)
        ffx, ffy = _force_terms(self)
        torque = fr.t if fr is not None else 0
        eqs = [b.x - a.x == self.r * c, b.y - a.y == self.r * s,          # talk eq. 3
               self.len.s == self.r, self.ang.phi == self.w,
               a.fx + b.fx + ffx == 0, a.fy + b.fy + ffy == 0,
               c * b.fx + s * b.fy + self.len.f == 0,
               self.r * (-s * b.fx + c * b.fy) + torque + self.ang.tau == 0]
        if fr is not None:
            eqs += [fr.x == a.x, fr.y == a.y, fr.phi == self.w]
        return eqs

    def shapes(self):
        p1, p2 = ["a.x", "a.y"], ["b.x", "b.y"]
        if self.draw == "bar":
            return [{"type": "link", "points": [p1, p2]}]
        if self.draw == "slider":
            return [{"type": "slider", "x": "b.x", "y": "b.y", "phi": "w", "guide": [p1, p2]}]
        return []


class IncludedAngle(Component):
    """Three-node constraint ``n3`` (cstr.js): the angle from the line
    n1->n2 to the line n1->n3 is held at ``value`` (rad).  Polar unknowns
    ``p2 - p1 = r12 e(w12)``, ``p3 - p1 = r13 e(w13)`` (r signed: lines, as
    cstr.js corrects only the orthogonal component), ``w13 - w12 = value``.
    Balances of the massless element: the forces at n2 and n3 are normal to
    their lines (mu2, mu3), all forces sum to zero and their moment about
    n1 vanishes (``r12 mu2 + r13 mu3 = 0``)."""
    value = Parameter(0.0, "rad", "included angle from n1->n2 to n1->n3")
    r12 = Variable(unit="m", doc="signed distance n1 -> n2")
    w12 = Variable(unit="rad", doc="angle of the line n1 -> n2")
    r13 = Variable(unit="m", doc="signed distance n1 -> n3")
    w13 = Variable(unit="rad", doc="angle of the line n1 -> n3")
    mu2 = Variable(unit="N", doc="normal force on node 2")
    mu3 = Variable(unit="N", doc="normal force on node 3")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.a = NodePort(doc="node 1 (vertex)")
        self.b = NodePort(doc="node 2")
        self.c = NodePort(doc="node 3")

    def guesses(self, context):
        """Start values from the node assembly (talk eq. 3-16)."""
        return _assembly_guesses(self, context)

    def equations(self):
        a, b, c = self.a, self.b, self.c
        n12 = (-ca.sin(self.w12), ca.cos(self.w12))
        n13 = (-ca.sin(self.w13), ca.cos(self.w13))
        return [b.x - a.x == self.r12 * ca.cos(self.w12), b.y - a.y == self.r12 * ca.sin(self.w12),
                c.x - a.x == self.r13 * ca.cos(self.w13), c.y - a.y == self.r13 * ca.sin(self.w13),
                b.fx == self.mu2 * n12[0], b.fy == self.mu2 * n12[1],
                c.fx == self.mu3 * n13[0], c.fy == self.mu3 * n13[1],
                a.fx + b.fx + c.fx == 0, a.fy + b.fy + c.fy == 0,
                self.r12 * self.mu2 + self.r13 * self.mu3 == 0,
                self.w13 - self.w12 == self.value]


# ------------------------------------------------------------ values
class AngleHold(Component):
    """Holds a constraint's angle at ``value`` (cstr.js ``ang: 'const'`` or
    a number; mec2 ``ori: {type: 'const'}``); its flange torque is the
    constraint moment."""
    value = Parameter(0.0, "rad", "held angle")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.flange.phi == self.value]


class LengthHold(Component):
    """Holds a constraint's length at ``value`` (cstr.js ``len: 'const'`` or
    a number; mec2 ``len: {type: 'const'}``); its flange force is the
    constraint force."""
    value = Parameter(1.0, "m", "held length")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = TranslationalFlange()

    def equations(self):
        return [self.flange.s == self.value]


class _Drive(Component):
    """Prescribed value z(t) of a constraint's angle or length (a drive of
    Schnabel and Gössner's talk or of mec2), optionally clamped into [lo, hi] (a range of
    cstr.js with a source), optionally stopped by ranges of other values
    (see :meth:`set_stops`).  ``law(t, get)`` returns z(t) from the time
    symbol and a parameter getter."""
    t0 = Parameter(0.0, "s", "drive start time (mec2 t0)")
    Dt = Parameter(1.0, "s", "drive duration (mec2 Dt)", positive=True)
    _flange_class: Optional[type] = None      # RotationalFlange or TranslationalFlange
    _potential_name: Optional[str] = None    # its potential, "phi" or "s"

    def __init__(self, law, clamp=(False, False), **kw):
        super().__init__(**kw)
        self.law = law
        self.clamp = tuple(bool(c) for c in clamp)
        self.stops = []
        self.flange = self._flange_class()

    def set_stops(self, stops):
        """Pure ranges that stop this drive: a list of ``(quantity, lo, hi)``
        where ``quantity()`` returns the ranged value's symbol and lo/hi are
        numbers or None.  While a ranged value is at its limit (it reached
        it moving outwards) the drive is replaced by holding that value at
        the limit: the mechanism rests there, as cstr.js's correction fails
        and undoes beyond it."""
        self.stops = list(stops)

    def numeric_law(self):
        """z(t) without limits as a Python function of time (parameter
        values as they are now), for the position correction."""
        t = ca.SX.sym("t")
        f = ca.Function("z", [t], [ca.SX(self.law(t, self.parameter_value))])
        return lambda tt: float(f(tt))

    def value(self, t):
        """z(t), clamped where the element has limits."""
        z = self.law(t, lambda name: getattr(self, name))
        if self.clamp[1]:
            z = ca.if_else(z > self.hi, self.hi, z)
        if self.clamp[0]:
            z = ca.if_else(z < self.lo, self.lo, z)
        return z

    def equations(self):
        res = getattr(self.flange, self._potential_name) - self.value(time)
        for quantity, lo, hi in reversed(self.stops):
            q = quantity()
            if hi is not None:
                res = ca.if_else(q >= hi, q - hi, res)
            if lo is not None:
                res = ca.if_else(q <= lo, q - lo, res)
        return [res]


def _drive_parameters(unit, z0, Dz, mec2_name):
    """Class decorator: the parameters of a drive law in ``unit`` (start
    value ``z0``, range ``Dz``, speed, limits)."""
    def declare(cls):
        return add_declarations(cls, {
            "z0": Parameter(z0, unit, "value at the start of the drive"),
            "Dz": Parameter(Dz, unit, "drive range (mec2 %s)" % mec2_name),
            "om": Parameter(0.0, unit + "/s", "constant speed (law 'speed')"),
            "lo": Parameter(0.0, unit, "lower limit (range)"),
            "hi": Parameter(0.0, unit, "upper limit (range)")})
    return declare


@_drive_parameters("rad", 0.0, 6.283185307179586, "Dw")
class AngleDrive(_Drive):
    """Prescribed angle of a constraint (see :class:`_Drive`): Schnabel and Gössner's
    driven crank (``ang`` incremented each tick: law ``z0 + om t``) or a
    mec2 ``ori`` drive; its flange torque is the drive torque."""
    _flange_class = RotationalFlange
    _potential_name = "phi"


@_drive_parameters("m", 1.0, 1.0, "Dr")
class LengthDrive(_Drive):
    """Prescribed length of a constraint (see :class:`_Drive`), e.g. a
    hydraulic cylinder or a mec2 ``len`` drive; its flange force is the
    drive force."""
    _flange_class = TranslationalFlange
    _potential_name = "s"


class Coupling(Component):
    """A value coupled to other constraint values (cstr.js ``ang.from``,
    ``len.from``, ``ang.delta``; mec2 ``ref`` with ``ratio``,
    ``reftype``): ``g(q) = own - source(refs) = 0``, an ideal (lossless)
    coupling whose flange forces are ``lambda dg/dq`` (virtual work); with
    ``passive=True`` (mec2) the referenced values get no force back (the
    reaction goes to ground, one-way).

    ``source(q_refs, get)`` builds the source from the reference
    potentials and a parameter getter; ``kinds`` are 'ang' or 'len' for
    [own, ref1, ...].  ``aux`` (mec2 cross types) names one further flange
    whose potential the source uses as its last argument.  The range of
    cstr.js with a source clamps it into [lo, hi]; outside, the coupling
    holds the limit and passes no force to the references.  ``drive`` (a
    law ``z(t, get)`` of the parameters z0, Dz, t0, Dt) is added to the
    source (mec2's drive with ``ref``)."""
    ratio = Parameter(1.0, "", "coupling ratio")
    offset = Parameter(0.0, "", "constant term (rad or m)")
    base = Parameter(0.0, "", "value of the own quantity the coupling starts from (mec2)")
    ref0 = Parameter(0.0, "", "start value of the reference (mec2)")
    lo = Parameter(0.0, "", "lower limit (range)")
    hi = Parameter(0.0, "", "upper limit (range)")
    z0 = Parameter(0.0, "", "start value of an added drive (0: mec2's drive with ref)")
    Dz = Parameter(0.0, "", "range of an added drive (mec2 Dw, Dr)")
    t0 = Parameter(0.0, "s", "start time of an added drive")
    Dt = Parameter(1.0, "s", "duration of an added drive", positive=True)
    lam = Variable(doc="coupling force or torque (Lagrange multiplier)")

    def __init__(self, kinds, source, passive=False, clamp=(False, False), drive=None, **kw):
        super().__init__(**kw)
        self.kinds, self.source = list(kinds), source
        self.passive, self.clamp, self.drive = bool(passive), tuple(clamp), drive
        for k, kind in enumerate(self.kinds):
            setattr(self, "q%d" % k, RotationalFlange() if kind == "ang" else TranslationalFlange())

    def _ports(self):
        return [getattr(self, "q%d" % k) for k in range(len(self.kinds))]

    def numeric_drive(self):
        """The added drive z(t) as a Python function of time (parameter
        values as they are now), or None."""
        if self.drive is None:
            return None
        t = ca.SX.sym("t")
        f = ca.Function("z", [t], [ca.SX(self.drive(t, self.parameter_value))])
        return lambda tt: float(f(tt))

    @staticmethod
    def _pot(port):
        return port.phi if isinstance(port, RotationalFlange) else port.s

    @staticmethod
    def _flow(port):
        return port.tau if isinstance(port, RotationalFlange) else port.f

    def equations(self):
        ports = self._ports()
        q = [self._pot(p) for p in ports]
        src = self.source(q[1:], lambda name: getattr(self, name))
        if self.drive is not None:
            src = src + self.drive(time, lambda name: getattr(self, name))
        if self.clamp[1]:
            src = ca.if_else(src > self.hi, self.hi, src)
        if self.clamp[0]:
            src = ca.if_else(src < self.lo, self.lo, src)
        g = q[0] - src
        eqs = [g == 0]
        for k, port in enumerate(ports):
            if k > 0 and self.passive:
                eqs.append(self._flow(port) == 0)
            else:
                eqs.append(self._flow(port) == self.lam * ca.jacobian(g, q[k]))
        return eqs


class NodeForce(Component):
    """Force load on a node (mec2 ``force``): magnitude ``value`` [N] in the
    direction ``w0`` (rad), or ``w0`` against the angle of a constraint when
    the flange ``ang`` is connected to that constraint's angle (mec2
    ``wref``); the flange passes no torque."""
    value = Parameter(1.0, "N", "magnitude of the force")
    w0 = Parameter(0.0, "rad", "direction (absolute, or relative to wref)")

    def __init__(self, relative=False, **kw):
        super().__init__(**kw)
        self.relative = bool(relative)
        self.port = NodePort(doc="the loaded node")
        if self.relative:
            self.ang = RotationalFlange(doc="angle of the reference constraint")

    def equations(self):
        w = self.w0 + (self.ang.phi if self.relative else 0)
        eqs = [self.port.fx == -self.value * ca.cos(w), self.port.fy == -self.value * ca.sin(w)]
        if self.relative:
            eqs.append(self.ang.tau == 0)
        return eqs


class NodeSpring(Component):
    """Linear spring between two nodes (mec2 ``spring``): force
    ``k (L - len0)`` along p1 -> p2 (pulling the nodes together when
    stretched), energy ``k (L - len0)^2 / 2``; ``len0 = 0`` (a zero-free-
    length spring, Ebert (2015), eq. 3.11/3.12) is written without the length so
    that coincident nodes are no singularity."""
    k = Parameter(1.0, "N/m", "spring rate", min=0.0)
    len0 = Parameter(0.0, "m", "unloaded length", min=0.0)
    L = Variable(unit="m", doc="length |p2 - p1|")
    f = Variable(unit="N", doc="spring force k (L - len0), positive when stretched")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.a = NodePort(doc="node 1")
        self.b = NodePort(doc="node 2")

    def equations(self):
        a, b = self.a, self.b
        dx, dy = b.x - a.x, b.y - a.y
        eqs = [self.L == ca.sqrt(dx * dx + dy * dy), self.f == self.k * (self.L - self.len0),
               a.fx + b.fx == 0, a.fy + b.fy == 0]
        if float(self.parameter_value("len0")) == 0.0:
            return eqs + [b.fx == self.k * dx, b.fy == self.k * dy]
        return eqs + [b.fx * self.L == self.f * dx, b.fy * self.L == self.f * dy]

    def shapes(self):
        return [{"type": "spring", "a": ["a.x", "a.y"], "b": ["b.x", "b.y"]}]
