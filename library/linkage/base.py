"""What the VDI 2729 linkage elements share (Ebert 2015, ch. 4.2, Anhang A): the
point-direction helpers, the d'Alembert forces of a body (A.27-A.29), the
sequential pre-assembly that evaluates the closed-form VDI positions with
the assembly parameter K (ch. 4.2.1, Bild 4.3) as start values, frame
placement (A.1-A.9), the mass data of the bodies, and drawing and topology
helpers.  The conventions are described in :mod:`acausal2d.library.linkage`.
"""
import casadi as ca

from acausal2d import (Component, der, Frame, Outer, Parameter, RotationalFlange,
                       TranslationalFlange, Variable)
from acausal2d.errors import InitializationError, ModelDefinitionError
from acausal2d.language.dsl import add_declarations
from acausal2d.language.unionfind import connector_sets
from acausal2d.library.planar import PlanarWorld, is_connected

__all__ = ["AssemblyError", "MassData", "element", "housing", "link_balance", "guide_balance", "axes"]


class AssemblyError(InitializationError, ModelDefinitionError):
    """A linkage element cannot assemble at the start (e.g. a DDD whose link
    lengths cannot reach between P1 and P2).  Raised when the model is
    compiled, with the element's name and the violated condition; it is an
    :class:`~acausal2d.errors.InitializationError`."""

_GROUND = {"x": 0.0, "y": 0.0, "phi": 0.0}


def _rot(phi, x, y):
    """Vector (x, y) given in a frame with angle phi, resolved in the world."""
    c, s = ca.cos(phi), ca.sin(phi)
    return c * x - s * y, s * x + c * y


def _cross(ax, ay, bx, by):
    return ax * by - ay * bx


def _sub(a, b):
    return a[0] - b[0], a[1] - b[1]


def _moment(point, ref, force):
    """z-moment about ``ref`` of ``force`` (2-tuple) acting at ``point``."""
    r = _sub(point, ref)
    return _cross(r[0], r[1], force[0], force[1])


class _Body:
    """Mass data of one body: centre of gravity S (variables), angle phi."""

    def __init__(self, m, J, xS, yS, phi, g):
        self.S = (xS, yS)
        self.m, self.J, self.phi = m, J, phi
        # d'Alembert force: gravity minus inertia force (A.27, A.28)
        self.F = (m * g[0] - m * der(der(xS)), m * g[1] - m * der(der(yS)))
        self.T = -J * der(der(phi))      # A.29

    def moment(self, ref):
        """Moment of gravity and inertia about ``ref`` (incl. -J phi'')."""
        return _moment(self.S, ref, self.F) + self.T

    def power(self, P_T, P_R):
        """Equations of the power of the inertia forces (A.30, A.31):
        ``P_T = Fax der(xS) + Fay der(yS)`` with ``Fa = m der(der(S))``
        (A.27, A.28) and ``P_R = Ta der(phi)`` with ``Ta = J der(der(phi))``
        (A.29): the rates of the translational and rotational kinetic
        energy of the body."""
        xS, yS = self.S
        return [P_T == self.m * (der(der(xS)) * der(xS) + der(der(yS)) * der(yS)),
                P_R == self.J * der(der(self.phi)) * der(self.phi)]


# --------------------------------------------------------------- assembly
class _Assembly:
    """Numeric-symbolic pre-assembly of all linkage elements of one model:
    node potentials (x, y, phi or s) as CasADi expressions of parameters."""

    def __init__(self, context, known=(), fallback=True):
        """``known``: further known poses [(connector, {potential:
        value})] (the start poses of planar frames, see
        :class:`~acausal2d.library.belt.placement.StartPoses`);
        ``fallback``: assemble elements whose inputs stay unknown as if
        those inputs sat at the origin (start guesses only; off where only
        poses that follow from the parameters are wanted)."""
        root = context.model
        self.root, self.context = root, context
        comps = list(root.components())
        sets, connected = connector_sets(root)
        self._find = sets.find
        self.connected = connected
        self.values = {}
        self.checks = []
        self.guesses = {}       # id(element) -> {variable: expression}
        for comp in comps:
            self._seed(comp)
        for conn, vals in known:
            self.put(conn, vals)
        pending = self._assemble_all([c for c in comps if isinstance(c, _Linkage)])
        for e in pending if fallback else ():
            e._assemble_alone(self)
        self.unresolved = pending
        self._run_checks(comps)

    def _seed(self, comp):
        """Known poses of ``comp``: its unconnected ground ports, its
        ``_linkage_seed()`` or, for library parts, :meth:`_seed_library`."""
        for conn in comp._connectors.values():
            if conn.ground is not None and id(conn) not in self.connected:
                g = conn.ground(comp) if callable(conn.ground) else conn.ground
                self.put(conn, dict(g))
        seed = getattr(comp, "_linkage_seed", None)
        if seed is not None:
            for conn, vals in seed():
                self.put(conn, vals)
        else:
            self._seed_library(comp)

    def _assemble_all(self, elems):
        """Assemble the elements in turn until none can; the ones left."""
        pending = list(elems)
        while pending:
            progress = False
            for e in list(pending):
                if e._assemble(self):
                    pending.remove(e)
                    progress = True
            if not progress:
                break
        return pending

    def check(self, elem, value, condition, hint):
        """Register an assembly condition ``value >= 0`` of ``elem``."""
        self.checks.append((elem, value, condition, hint))

    def _run_checks(self, comps):
        if not self.checks:
            return
        values = self.context.evaluate([c[1] for c in self.checks])
        for (elem, _, condition, hint), value in zip(self.checks, values):
            if not value >= -1e-12:
                raise AssemblyError(
                    "%s cannot assemble at the start: %s is violated (value %.6g). %s"
                    % (elem.describe(), condition, value, hint))

    def start(self, elem, values):
        """Record start guesses {local variable name: expression} of ``elem``."""
        self.guesses.setdefault(id(elem), {}).update(values)

    def _seed_library(self, comp):
        from acausal2d.library import planar, rotational, translational
        if isinstance(comp, planar.Fixed):
            self.put(comp.frame, {"x": comp.r[0], "y": comp.r[1], "phi": comp.phi})
        elif isinstance(comp, rotational.Fixed):
            self.put(comp.flange, {"phi": comp.phi0})
        elif isinstance(comp, translational.Fixed):
            self.put(comp.flange, {"s": comp.s0})

    def is_connected(self, conn):
        return id(conn) in self.connected

    def get(self, conn):
        """Known potentials of the node of ``conn`` (dict) or None."""
        return self.values.get(self._find(id(conn)))

    def put(self, conn, vals):
        k = self._find(id(conn))
        cur = self.values.setdefault(k, {})
        for name, v in vals.items():
            cur.setdefault(name, v)


# --------------------------------------------------------------- base class
class _Linkage(Component):
    """Common machinery: port placement (Anhang A.1), gravity, start values
    from the VDI pre-assembly."""
    world = Outer(PlanarWorld)
    _placed_ports = ()     # port numbers n with parameters xn0, yn0, phin0
    _output_ports = ()     # output port numbers n with xn0, yn0, phin0 (relative only)
    _bodies = ()           # MassData of the element's bodies
    _connector_spec = ()   # (name, factory) of the element's ports, in order

    def __init__(self, **kw):
        refs = {}
        for n in self._placed_ports:
            ref = kw.pop("frameRef%d" % n, "relative")
            if ref not in ("relative", "global"):
                raise ModelDefinitionError(
                    "%s: frameRef%d must be 'relative' (connection frame) or 'global', not %r"
                    % (type(self).__name__, n, ref))
            refs[n] = ref
        for n in self._output_ports:
            ref = kw.pop("frameRef%d" % n, "relative")
            if ref != "relative":
                raise ModelDefinitionError(
                    "%s: frameRef%d of the output port ctr2D%d must be 'relative' (x%d0, y%d0, "
                    "phi%d0 in the port's connection frame, Anhang A.1), not %r"
                    % (type(self).__name__, n, n, n, n, n, ref))
        super().__init__(**kw)
        self.__dict__["_frame_ref"] = refs
        self.__dict__["_rel"] = {}
        for name, make in self._connector_spec:
            setattr(self, name, make())

    def derived_parameters(self, context):
        """Centres of gravity at half the link length unless given ("l/2" in
        Tabellen B.2, B.8, B.11, B.14)."""
        return {"xS%srel" % b.key: 0.5 * float(self.parameter_value(b.half_of))
                for b in self._bodies
                if b.half_of is not None and not self.is_given("xS%srel" % b.key)}

    # ------------------------------------------------ mass data (A.2, A.3)
    def _mass(self, key, origin, phi, body_phi=None):
        """The body ``key`` whose frame has the origin ``origin`` and the
        angle ``phi``: its d'Alembert forces (:class:`_Body`, turning with
        ``body_phi``, the variable equal to ``phi`` where the element has
        one) and the two equations placing its centre of gravity (A.21,
        A.22)."""
        d = _rot(phi, getattr(self, "xS%srel" % key), getattr(self, "yS%srel" % key))
        xS, yS = getattr(self, "xS" + key), getattr(self, "yS" + key)
        body = _Body(getattr(self, "m" + key), getattr(self, "J" + key), xS, yS,
                     phi if body_phi is None else body_phi, self._g())
        return body, [xS == origin[0] + d[0], yS == origin[1] + d[1],
                      *body.power(getattr(self, "P_T" + key), getattr(self, "P_R" + key))]

    def _mass_start(self, key, origin, phi):
        """Start guesses {xS<key>: ..., yS<key>: ...} of the centre of
        gravity of body ``key`` (A.21, A.22 with the assembled pose)."""
        d = _rot(phi, getattr(self, "xS%srel" % key), getattr(self, "yS%srel" % key))
        return {"xS" + key: origin[0] + d[0], "yS" + key: origin[1] + d[1]}

    def guesses(self, context):
        """Start guesses from the pre-assembly of all linkage elements of the
        model (computed once per flattening)."""
        self._rel.clear()
        self.__dict__["_asm"] = context.shared("linkage assembly", lambda: _Assembly(context))
        return {k: v for k, v in self._asm.guesses.get(id(self), {}).items()
                if self.has_variable(k)}

    def _g(self):
        return self.world.g

    def _start(self, variable, parameter):
        """The start value given for ``variable`` (``phiL=start(0.3)`` or a
        number), else the start parameter ``parameter`` (``phiL0``; also
        for ``start(fixed=True)`` without a value): where the element's
        pre-assembly puts it at t0."""
        ov = self._overrides.get(variable)
        given = ov is not None and getattr(ov, "value", ov) is not None
        return self.start_value(variable) if given else parameter

    def _conn(self, n):
        return getattr(self, "ctr2D%d" % n)

    def _relative(self, n, asm):
        """Constant coordinates of Pn in its connection frame (A.1-A.6)."""
        if n in self._rel:
            return self._rel[n]
        xr, yr, pr = (getattr(self, "x%d0" % n), getattr(self, "y%d0" % n),
                      getattr(self, "phi%d0" % n))
        conn = self._conn(n)
        if self._frame_ref[n] == "global" and asm.is_connected(conn):
            c = asm.get(conn)
            if c is None or not all(k in c for k in ("x", "y", "phi")):
                raise ModelDefinitionError(
                    "%s: frameRef%d='global' needs the start pose of the connection at %s, "
                    "which the sequential assembly could not determine; use "
                    "frameRef%d='relative'" % (self.describe(), n, conn.path, n))
            c0, s0 = ca.cos(c["phi"]), ca.sin(c["phi"])
            dx, dy = xr - c["x"], yr - c["y"]
            xr, yr, pr = (dx * c0 + dy * s0,          # A.4
                          -dx * s0 + dy * c0,         # A.5
                          pr - c["phi"])              # A.6
        self._rel[n] = (xr, yr, pr)
        return self._rel[n]

    def _place(self, n):
        """(x, y, phi) of Pn and of its connection C (A.7-A.9), symbolic."""
        asm = self._asm
        f = self._conn(n)
        xr, yr, pr = self._relative(n, asm)
        dx, dy = _rot(f.phi, xr, yr)
        return (f.x + dx, f.y + dy, f.phi + pr), (f.x, f.y)

    def _place_value(self, n, asm):
        """(x, y, phi) of Pn at the start, from the assembly, or None."""
        c = asm.get(self._conn(n))
        if c is None or not all(k in c for k in ("x", "y", "phi")):
            return None
        xr, yr, pr = self._relative(n, asm)
        dx, dy = _rot(c["phi"], xr, yr)
        return c["x"] + dx, c["y"] + dy, c["phi"] + pr

    def _output_offset(self, n):
        """Offset (x, y, phi) of the output port n's point Pn in its
        connection frame, or None when it is zero (then Cn = Pn)."""
        names = ("x%d0" % n, "y%d0" % n, "phi%d0" % n)
        if n not in self._output_ports or all(float(self.parameter_value(k)) == 0.0
                                               for k in names):
            return None
        return tuple(getattr(self, k) for k in names)

    def _output(self, n, pose):
        """Equations of the output port n for the element's point pose
        ``pose`` = (x, y, phi) of Pn, and the connection point Cn where the
        port's force acts (for the moment balances, A.16-A.18): A.7-A.9
        with the connection frame as the unknown, phi_Cn = phi_Pn - phi_n0,
        Cn = Pn - R(phi_Cn) (x_n0, y_n0)."""
        f, rel = self._conn(n), self._output_offset(n)
        if rel is None:
            return [f.x == pose[0], f.y == pose[1], f.phi == pose[2]], (pose[0], pose[1])
        phi = pose[2] - rel[2]
        dx, dy = _rot(phi, rel[0], rel[1])
        C = (pose[0] - dx, pose[1] - dy)
        return [f.x == C[0], f.y == C[1], f.phi == phi], C

    def _set_port(self, asm, conn, vals):
        n = int(conn._name[-1]) if conn._name.startswith("ctr2D") else None
        if n in self._output_ports and "phi" in vals and self._output_offset(n) is not None:
            phi = vals["phi"] - self._output_offset(n)[2]
            dx, dy = _rot(phi, *self._output_offset(n)[:2])
            vals = {"x": vals["x"] - dx, "y": vals["y"] - dy, "phi": phi}
        asm.put(conn, vals)
        if conn._owner is self:
            asm.start(self, {"%s.%s" % (conn._name, k): v for k, v in vals.items()})

    def _assemble(self, asm):
        """Start values from the assembled poses of the input ports (False
        while one of them is not known yet)."""
        vals = self._input_values(asm, self._placed_ports)
        if vals is None:
            return False
        self._assemble_at(asm, *vals)
        return True

    def _assemble_at(self, asm, *poses):       # pragma: no cover - overridden
        """Record start guesses and output poses from the input poses (x, y,
        phi) of the placed points, one per input port."""

    def _assemble_alone(self, asm):
        """Fallback when inputs are unknown: assemble from the element's own
        parameters as if its input ports were unconnected."""
        saved = {}
        for n in self._placed_ports:
            conn = self._conn(n)
            if asm.get(conn) is None or not all(k in asm.get(conn) for k in ("x", "y", "phi")):
                saved[n] = conn
        fake = _FakeAssembly(asm, saved)
        try:
            self._assemble(fake)
        except Exception:       # a guess only
            pass

    def _input_values(self, asm, ports):
        vals = [self._place_value(n, asm) for n in ports]
        return None if any(v is None for v in vals) else vals

    # ------------------------------------------------ drawing and topology
    def _grounded(self, conn):
        """True if ``conn`` is a triangle port fixed to ground (unconnected)."""
        return conn.ground is not None and not is_connected(conn)

    def _port_point(self, n):
        """[X, Y] signal references (relative to the element) of the placed
        point Pn of input port n, for ports that have no output frame at Pn.
        Unconnected: the parameters ``(xn0, yn0)`` (results contain
        parameters).  Connected with zero offset (``frameRef='relative'``,
        ``xn0 = yn0 = 0``): the connection point ``ctr2Dn``.  Otherwise Pn is
        not a result signal and the connection point is returned as an
        approximation (second value False)."""
        if not is_connected(self._conn(n)):
            return ["x%d0" % n, "y%d0" % n], True
        return ["ctr2D%d.x" % n, "ctr2D%d.y" % n], self._at_connection(n)

    def _at_connection(self, n):
        """True if the placed point Pn of port n is the connection point
        itself (``frameRef='relative'`` with ``xn0 = yn0 = 0``)."""
        return (self._frame_ref.get(n) == "relative"
                and float(self.parameter_value("x%d0" % n)) == 0.0
                and float(self.parameter_value("y%d0" % n)) == 0.0)

    def _housing_shapes(self, n, point, phi=0.0):
        """Ground symbol at ``point`` when port n is fixed to ground, or the
        rigid arm from the connection point to ``point`` when the port is
        connected with an offset (``point`` must be the exact Pn)."""
        conn = self._conn(n)
        if self._grounded(conn):
            return [{"type": "ground", "x": point[0], "y": point[1], "phi": phi}]
        c = ["ctr2D%d.x" % n, "ctr2D%d.y" % n]
        if is_connected(conn) and list(point) != c and not self._at_connection(n):
            return [{"type": "link", "points": [c, list(point)]}]
        return []

    def _slider_shape(self, PS, phi, guide_port=None, travel=None):
        """Slider block at the foot point ``PS`` with angle ``phi``; its
        guide is drawn from the placed point of ``guide_port`` when that
        point is a result signal (see :meth:`_port_point`); otherwise the
        slider's own ``travel`` variable (measured from that point) gives
        its travel range (``"s"``, see
        :mod:`acausal2d.analysis.slider_ranges`)."""
        shape = {"type": "slider", "x": PS[0], "y": PS[1], "phi": phi}
        if guide_port is not None:
            start, exact = self._port_point(guide_port)
            if exact:
                shape["guide"] = [start, PS]
            elif travel is not None:
                shape["s"] = travel
        return shape

    def _body_shape(self, key):
        """Small disc at the centre of gravity of body ``key`` when it is off
        the pins (massive bodies only)."""
        pv = self.parameter_value
        if float(pv("m" + key)) > 0.0 and (float(pv("xS%srel" % key)) != 0.0
                                           or float(pv("yS%srel" % key)) != 0.0):
            return [{"type": "body", "x": "xS" + key, "y": "yS" + key}]
        return []

    def _ground_ports(self, *ports):
        """("ground", [...]) item for the given triangle ports that are
        unconnected (fixed to ground by the flattener), or nothing."""
        frames = [self._conn(n) for n in ports if self._grounded(self._conn(n))]
        return [("ground", frames)] if frames else []


class _FakeAssembly:
    """Assembly view in which the given unknown ports sit at the origin."""

    def __init__(self, asm, ports):
        self.asm, self.ports = asm, {id(c) for c in ports.values()}

    def is_connected(self, conn):
        return self.asm.is_connected(conn) and id(conn) not in self.ports

    def get(self, conn):
        if id(conn) in self.ports:
            return dict(_GROUND)
        return self.asm.get(conn)

    def put(self, conn, vals):
        self.asm.put(conn, vals)

    def check(self, *args):
        pass            # fallback guesses are not checked

    def start(self, elem, values):
        self.asm.start(elem, values)


def _placement_declarations(n):
    """Parameters xn0, yn0, phin0 of input port n (Tabelle A.1)."""
    return {"x%d0" % n: Parameter(0.0, "m", "x of P%d in the reference frame (Tabelle A.1)" % n),
            "y%d0" % n: Parameter(0.0, "m", "y of P%d in the reference frame (Tabelle A.1)" % n),
            "phi%d0" % n: Parameter(0.0, "rad", "angle of the point frame PKS%d against the "
                                    "reference frame (Tabelle A.1)" % n)}


class MassData:
    """Mass data of one body of a VDI element (Anhang A.2/A.3; Tabellen B.2,
    B.5, B.8, B.11, B.14, B.17, B.20, B.23): the parameters ``xS<key>rel``,
    ``yS<key>rel`` (centre of gravity in the body frame ``frame``),
    ``m<key>`` and ``J<key>`` (about the centre of gravity) and the
    variables ``xS<key>``, ``yS<key>`` (the centre of gravity in the world)
    and ``P_T<key>``, ``P_R<key>`` (power of the inertia forces, A.30, A.31).
    ``half_of`` names the length whose half is the default of
    ``xS<key>rel`` ("l/2" in the tables)."""

    def __init__(self, key, what, frame, half_of=None):
        self.key, self.what, self.frame, self.half_of = key, what, frame, half_of

    def declarations(self):
        """{name: Parameter or Variable} of this body."""
        k, w = self.key, self.what
        cg = "centre of gravity of %s in %s" % (w, self.frame)
        half = " (default %s/2)" % self.half_of if self.half_of else ""
        return {"xS%srel" % k: Parameter(0.5 if self.half_of else 0.0, "m", cg + ", x" + half),
                "yS%srel" % k: Parameter(0.0, "m", cg + ", y"),
                "m" + k: Parameter(1.0, "kg", "mass of " + w, min=0.0),
                "J" + k: Parameter(0.1, "kg.m2", "moment of inertia of %s about its centre of "
                                   "gravity" % w, min=0.0),
                "xS" + k: Variable(unit="m", doc="centre of gravity of %s, x" % w),
                "yS" + k: Variable(unit="m", doc="centre of gravity of %s, y" % w),
                "P_T" + k: Variable(unit="W", doc="power of the inertia force of %s, rate of "
                                    "its translational kinetic energy (A.30)" % w),
                "P_R" + k: Variable(unit="W", doc="power of the inertia torque of %s, rate of "
                                    "its rotational kinetic energy (A.31)" % w)}


def triangle(doc):
    """A frame port drawn with a triangle (housing, guide): fixed to ground
    while unconnected (Tabelle 4.1)."""
    return lambda: Frame(ground=_GROUND, doc=doc)


def plug(doc):
    """A frame port drawn with a plug (a moving plane): free while unconnected."""
    return lambda: Frame(doc=doc)


def rotational(doc):
    """A 1D rotational flange."""
    return lambda: RotationalFlange(doc=doc)


def translational(doc):
    """A 1D translational flange."""
    return lambda: TranslationalFlange(doc=doc)


def element(ports, *bodies, connectors=None, outputs=()):
    """Class decorator of a VDI element: the placement parameters ``xn0,
    yn0, phin0`` of its input ``ports`` and of its ``outputs`` (the point
    frames PCSn of Anhang C; Anhang A.1, Tabelle A.1), the mass data of its
    ``bodies`` (:class:`MassData`) and its ``connectors`` ({name:
    :func:`triangle`, :func:`plug`, :func:`rotational` or
    :func:`translational` port}, created in this order)."""
    def declare(cls):
        if connectors is not None:
            cls._connector_spec = tuple(connectors.items())
        decls = {}
        for body in bodies:
            decls.update(body.declarations())
        for n in tuple(ports) + tuple(outputs):
            decls.update(_placement_declarations(n))
        cls._bodies = tuple(bodies)
        cls._placed_ports = tuple(ports)
        cls._output_ports = tuple(outputs)
        return add_declarations(cls, decls)
    return declare


def _plus(a, b):
    return a if b is None else a + b


def housing(frame, point, connection, tau=None):
    """Moment balance of a massless bearing housing or guide plate (Anhang B
    intro, A.16-A.18): the joint force at ``point`` passes to the port
    ``frame`` at ``connection``; ``tau`` is a 1D flange torque on it."""
    return _plus(frame.t, tau) + _moment(point, connection, (-frame.fx, -frame.fy)) == 0


def off_point(C, P):
    """``C`` unless it is the point ``P`` itself (an output port placed
    without offset, :meth:`_Linkage._output`), else None."""
    return None if C[0] is P[0] and C[1] is P[1] else C


def port_moment(C, pivot, f):
    """Moment about ``pivot`` of the force of port ``f`` acting at its
    connection point ``C`` (A.16-A.18); 0 where C is the pivot itself."""
    return 0 if off_point(C, pivot) is None else _moment(C, pivot, (f.fx, f.fy))


def link_balance(f_in, f_plane, joint_force, joint, pivot, body, tau=None, plane_at=None):
    """Force and moment balance (about ``pivot``) of a link turning about the
    housing port ``f_in`` and carrying its plane port ``f_plane``, with the
    force ``joint_force`` acting on it at ``joint`` (DDD B.65-B.70, DDS
    B.108-B.110); ``tau`` is a 1D flange torque on the link; ``plane_at``
    the connection point of the plane port when it is placed off the
    pivot (A.18)."""
    mom = _plus(f_plane.t, tau) + _moment(joint, pivot, joint_force) + body.moment(pivot)
    if plane_at is not None:
        mom = mom + _moment(plane_at, pivot, (f_plane.fx, f_plane.fy))
    return [f_in.fx + joint_force[0] + f_plane.fx + body.F[0] == 0,
            f_in.fy + joint_force[1] + f_plane.fy + body.F[1] == 0,
            mom == 0]


def guide_balance(frame, Fn, Fu, TPS, e, n, PS, origin, connection):
    """Balance of a massless straight guide through ``origin`` with direction
    ``e`` and normal ``n`` carrying a slider at its foot point ``PS`` (SAN
    B.25-B.27, DDS B.114-B.116): normal force ``Fn``, moment ``TPS`` and
    the force ``Fu`` of the guide's 1D support flange along ``e``."""
    return [frame.fx - Fn * n[0] + Fu * e[0] == 0,
            frame.fy - Fn * n[1] + Fu * e[1] == 0,
            frame.t - TPS + _moment(PS, connection, (-Fn * n[0], -Fn * n[1]))
            + _moment(origin, connection, (Fu * e[0], Fu * e[1])) == 0]


def axes(phi):
    """Unit vectors e (along) and n (normal, turned by +90°) of a guide with
    angle ``phi`` (Bild 4.3 point-direction form)."""
    c, s = ca.cos(phi), ca.sin(phi)
    return (c, s), (-s, c)
