"""Linkage elements after VDI 2729 with masses (seed ch. 4.2, Anhang A, B).

Elements: :class:`DAN` (rotary drive), :class:`SAN` (linear drive),
:class:`FGP` (guided link point), and the Assur dyads :class:`DDD`,
:class:`DDS`, :class:`DSD`, :class:`SSD`, :class:`SDS`.

Conventions (common to all elements)
------------------------------------
* Ports carry the seed's names: ``ctr2D1`` .. ``ctr2D4`` are planar frames
  (:class:`~acausal2d.language.connectors.Frame`: x, y, phi; fx, fy, t = force and
  torque acting *on the element* from the connected part, world frame);
  ``ctrR1``/``ctrR2`` are 1D rotational and ``ctrT1``/``ctrT2`` 1D
  translational flanges.
* Ports drawn with a triangle in the seed (bearing housings and guides,
  Tabelle 4.1) are fixed to ground while unconnected; ports drawn with a
  plug (the moving planes of links and sliders) are free (zero force) while
  unconnected.
* Frame placement (Anhang A.1, eqs. A.1-A.9): the point ``Pn`` of an input
  port n is placed against the frame of its connection (CKS) by the
  parameters ``xn0, yn0, phin0`` (Anhang C names, e.g. ``x10, y10, phi10``).
  ``frameRefn="relative"`` (default, SimulationX ``EnumType.relativ``) takes
  them as constant coordinates in the connection frame (A.1-A.3, A.7-A.9);
  ``frameRefn="global"`` takes them as global start coordinates and converts
  them to constant relative coordinates with the connection's pose at t0
  (A.4-A.6).  An unconnected port's CKS is the global frame, so both choices
  then give the global point ``(xn0, yn0)`` with angle ``phin0``.
* Each element states the position-level kinematics in point-direction form
  (Bild 4.3: ``x_P = x_P1 + l cos(phi)``), the force and moment balances of
  its bodies and their mass data (Anhang A.2/A.3), nothing else: velocities
  and accelerations are produced by the compiler's index reduction.  Angles
  are unwrapped unknowns; no atan2 appears in any residual.
* Centre-of-gravity coordinates (``xS..``, ``yS..``) and body angles are
  variables of every element, so results contain them (e.g. for energy
  checks).  Inertia terms are ``m der(der(xS))`` and ``J der(der(phi))`` with
  J about the centre of gravity (A.27-A.29); gravity comes from the model's
  :class:`~acausal2d.library.planar.PlanarWorld` (default {0, -9.81} m/s²,
  the seed's g_x, g_y defaults).
* Massless bearing housings and guides (Anhang B intro) pass forces from the
  joint to their port; their moment balance about the connection point
  includes the offset of the placed point (A.16-A.18).

Assembly and the parameter K (ch. 4.2.1, Bild 4.3)
-------------------------------------------------
Before the first simulation the elements are assembled once, in the
sequential order of VDI 2729, from the ground-fixed ports and the drives'
start angles (parameters ``phiL0``/``xS0`` or a connected motion preset):
each element evaluates the VDI closed-form position formulas (DDD: B.42-B.52,
DDS: B.71-B.86, DSD: B.119-B.125; with the assembly parameter ``K``) as
CasADi expressions of the parameters and uses them as START values of its
angle/travel unknowns and port coordinates.  The initialization then solves
the point-direction equations from these guesses, so K picks the branch;
afterwards the motion is continuous (a dead centre is passed through, not
flipped).  Start values follow parameter changes made with
``simulate(params=...)`` without recompiling.  A user start value
(``DDD(phiL1=start(...))``) overrides the assembled guess.

Drawing and topology
--------------------
``shapes()`` draws what the VDI symbol shows, with result signals only:
links between the element's points, revolute joints (white circles) at its
pins, sliders on dashed guides for prismatic pairs, a ground symbol at each
triangle port that is unconnected (fixed to ground), the rigid arm from the
connection point to the placed point when a connected port has an offset,
and a small disc at each centre of gravity of a massive link that lies off
the pins.  Unconnected placed points are the parameters ``(xn0, yn0)``.  A
point that is no result signal -- the placed point Pn of DAN/SAN/FGP/SSD/SDS
and the DDS guide origin when that port is connected with an offset -- is
drawn at the connection point (guides are then left out).  The slider foot
points ``xPS, yPS`` (SAN, DSD), ``xPS1, yPS1`` (SSD, SDS) and ``xPS2, yPS2``
(SSD) are variables for this purpose.

``topology()`` (seed eq. 2.1) uses the element's *output* frames as its
links: every moving body of an element has exactly one plug port (DAN crank
``ctr2D2``; SAN slider ``ctr2D2``; DDD links ``ctr2D3``/``ctr2D4``; DDS link
``ctr2D3``, slider ``ctr2D4``; DSD guide ``ctr2D3``, slider ``ctr2D4``;
SSD/SDS sliders ``ctr2D3``/``ctr2D4``), and the triangle ports (housings,
guides) are the plane of the predecessor they are mounted on.  So the inner
pin P of a dyad needs no frame of its own: it is the joint between the two
output frames, and a dyad adds 2 links and 3 joints (f = 1 each) between its
input ports.  Unconnected triangle ports are declared ``("ground", ...)``.
FGP is rigid with its predecessor (``("rigid", [ctr2D1, ctr2D2])``).  The
motion presets declare nothing: eq. 2.1 counts the mechanism's DOF, which
a drive uses up but does not remove from the chain.

Sign conventions differing from the extracted seed text (typos there):
slider foot points are ``PS = P_guide + x_G (cos phi_U, sin phi_U)`` in all
elements (the seed's B.10/B.99 print ``x_P1 - x_G cos``, contradicting B.126,
B.158, B.197); the DSD start direction uses ``H6 = (H2 H4 - v H1)/H3`` so that
it is consistent with B.132/B.133.
"""
import math

import casadi as ca
import numpy as np

from acausal2d import (Component, der, Frame, Outer, Parameter, RotationalFlange, TranslationalFlange,
                       Variable)
from acausal2d.errors import InitializationError, ModelDefinitionError
from acausal2d.library.planar import PlanarWorld, is_connected
from acausal2d.language.unionfind import connector_sets

__all__ = ["DAN", "SAN", "FGP", "DDD", "DDS", "DSD", "SSD", "SDS", "AssemblyError"]


class AssemblyError(InitializationError, ModelDefinitionError):
    """A linkage element cannot assemble at the start (e.g. a DDD whose link
    lengths cannot reach between P1 and P2).  Raised when the model is
    compiled, with the element's name and the violated condition; it is an
    :class:`~acausal2d.errors.InitializationError`."""

_GROUND = {"x": 0.0, "y": 0.0, "phi": 0.0}


# --------------------------------------------------------------- helpers
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


# --------------------------------------------------------------- assembly
class _Assembly:
    """Numeric-symbolic pre-assembly of all linkage elements of one model:
    node potentials (x, y, phi or s) as CasADi expressions of parameters."""

    def __init__(self, context):
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
            for conn in comp._connectors.values():
                if conn.ground is not None and id(conn) not in connected:
                    g = conn.ground(comp) if callable(conn.ground) else conn.ground
                    self.put(conn, dict(g))
            seed = getattr(comp, "_linkage_seed", None)
            if seed is not None:
                for conn, vals in seed():
                    self.put(conn, vals)
            else:
                self._seed_library(comp)
        elems = [c for c in comps if isinstance(c, _Linkage)]
        pending = list(elems)
        while pending:
            progress = False
            for e in list(pending):
                if e._assemble(self):
                    pending.remove(e)
                    progress = True
            if not progress:
                break
        for e in pending:
            e._assemble_alone(self)
        self.unresolved = pending
        self._run_checks(comps)

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

    def __init__(self, **kw):
        refs = {}
        for n in self._placed_ports:
            ref = kw.pop("frameRef%d" % n, "relative")
            if ref not in ("relative", "global"):
                raise ModelDefinitionError(
                    "%s: frameRef%d must be 'relative' (connection frame) or 'global', not %r"
                    % (type(self).__name__, n, ref))
            refs[n] = ref
        super().__init__(**kw)
        self.__dict__["_frame_ref"] = refs
        self.__dict__["_rel"] = {}
        self.__dict__["_halves"] = []

    # centre-of-gravity defaults "l/2" (Tabellen B.2, B.8, B.11, B.14)
    def _default_half(self, kw, name, length):
        """The parameter ``name`` is half of ``length`` unless the model
        gives it (see :meth:`derived_parameters`)."""
        self._halves.append((name, length))

    def derived_parameters(self, context):
        """Centres of gravity at half the link length unless given ("l/2" in
        Tabellen B.2, B.8, B.11, B.14)."""
        return {name: 0.5 * float(self.parameter_value(length))
                for name, length in self._halves if not self.is_given(name)}

    def guesses(self, context):
        """Start guesses from the pre-assembly of all linkage elements of the
        model (computed once per flattening)."""
        self._rel.clear()
        self.__dict__["_asm"] = context.shared("linkage assembly", lambda: _Assembly(context))
        return {k: v for k, v in self._asm.guesses.get(id(self), {}).items()
                if self.has_variable(k)}

    def _g(self):
        return self.world.g

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

    def _set_port(self, asm, conn, vals):
        asm.put(conn, vals)
        if conn._owner is self:
            asm.start(self, {"%s.%s" % (conn._name, k): v for k, v in vals.items()})

    def _assemble(self, asm):       # pragma: no cover - overridden
        return True

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

    def _body_shape(self, mass, xrel, yrel, xS, yS):
        """Small disc at a centre of gravity that is off the pins (massive
        bodies only)."""
        pv = self.parameter_value
        if float(pv(mass)) > 0.0 and (float(pv(xrel)) != 0.0 or float(pv(yrel)) != 0.0):
            return [{"type": "body", "x": xS, "y": yS}]
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


def _placement_params(cls, ports):
    """Add xn0, yn0, phin0 parameters for the given ports to class ``cls``."""
    for n in ports:
        for name, unit, doc in (("x%d0", "m", "x of P%d in the reference frame (Tabelle A.1)"),
                                ("y%d0", "m", "y of P%d in the reference frame (Tabelle A.1)"),
                                ("phi%d0", "rad", "angle of the point frame PKS%d against the "
                                 "reference frame (Tabelle A.1)")):
            p = Parameter(0.0, unit, doc % n)
            p.__set_name__(cls, name % n)
            setattr(cls, name % n, p)
    cls._placed_ports = tuple(ports)
    return cls


# ================================================================ DAN
class DAN(_Linkage):
    """Rotary drive DAN (seed Anhang B.1, Tabellen B.1-B.3, eqs. B.1-B.9).

    A crank (Link) of length ``lL`` turns about the bearing point P1; its end
    point P moves on a circle.  Ports: ``ctr2D1`` bearing housing at P1
    (triangle: ground-fixed at ``(x10, y10)`` while unconnected),
    ``ctr2D2`` crank plane at P (angle phiL), ``ctrR1`` 1D rotational flange
    on the housing (support torque, angle = housing angle), ``ctrR2`` 1D
    rotational flange on the crank (angle = phiL, torque T_R2 on the crank).
    Drive the crank by connecting a motion preset or a torque to ``ctrR2``
    (see :mod:`acausal2d.library.linkage_drives`); with ``ctrR2`` unconnected
    the crank is free.

    Kinematics B.1/B.2: ``x_P = x_P1 + lL cos(phiL)``, ``y_P = y_P1 + lL
    sin(phiL)``.  Forces B.7-B.9 (balance of the crank, moment about P1).
    Parameters (Tabelle B.2 defaults): ``mL = 1 kg``, ``JL = 0.1 kg m²``
    about the centre of gravity, ``xSLrel = lL/2`` (when not given),
    ``ySLrel = 0``; ``phiL0``, ``omL0`` are the start angle/speed (guesses;
    fix them with ``DAN(phiL=start(fixed=True), omL=start(fixed=True))`` for
    a force-driven crank).
    """
    lL = Parameter(1.0, "m", "link (crank) length l_L", positive=True)
    phiL0 = Parameter(0.0, "rad", "start angle of the link")
    omL0 = Parameter(0.0, "rad/s", "start angular velocity of the link")
    xSLrel = Parameter(0.5, "m", "centre of gravity of the link in LKS, x (default lL/2)")
    ySLrel = Parameter(0.0, "m", "centre of gravity of the link in LKS, y")
    mL = Parameter(1.0, "kg", "mass of the link", min=0.0)
    JL = Parameter(0.1, "kg.m2", "moment of inertia of the link about its centre of gravity", min=0.0)

    phiL = Variable(unit="rad", doc="link angle (absolute)", state_select="prefer")
    omL = Variable(unit="rad/s", doc="link angular velocity", state_select="prefer")
    xSL = Variable(unit="m", doc="centre of gravity of the link, x")
    ySL = Variable(unit="m", doc="centre of gravity of the link, y")

    def __init__(self, **kw):
        super().__init__(**kw)
        self._default_half(kw, "xSLrel", "lL")
        self.ctr2D1 = Frame(ground=_GROUND, doc="housing at P1")
        self.ctr2D2 = Frame(doc="link plane at P")
        self.ctrR1 = RotationalFlange(doc="housing (support) flange")
        self.ctrR2 = RotationalFlange(doc="link flange")

    def _assemble(self, asm):
        p1 = self._input_values(asm, [1])
        if p1 is None:
            return False
        (x1, y1, a1), = p1
        r = asm.get(self.ctrR2)
        phi = r["phi"] if r and "phi" in r else self.phiL0
        om = r["w"] if r and "w" in r else self.omL0
        xP, yP = x1 + self.lL * ca.cos(phi), y1 + self.lL * ca.sin(phi)
        dx, dy = _rot(phi, self.xSLrel, self.ySLrel)
        asm.start(self, {"phiL": phi, "omL": om, "xSL": x1 + dx, "ySL": y1 + dy})
        self._set_port(asm, self.ctr2D2, {"x": xP, "y": yP, "phi": phi})
        self._set_port(asm, self.ctrR2, {"phi": phi})
        self._set_port(asm, self.ctrR1, {"phi": a1})
        return True

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        phi = self.phiL
        P1 = (x1, y1)
        P = (x1 + self.lL * ca.cos(phi), y1 + self.lL * ca.sin(phi))          # B.1, B.2
        dx, dy = _rot(phi, self.xSLrel, self.ySLrel)                          # A.21, A.22
        L = _Body(self.mL, self.JL, self.xSL, self.ySL, phi, self._g())
        F1 = (f1.fx, f1.fy)          # joint force housing -> link (massless housing)
        return [
            self.omL == der(phi),
            self.xSL == x1 + dx, self.ySL == y1 + dy,
            f2.x == P[0], f2.y == P[1], f2.phi == phi,                        # Tabelle B.3
            self.ctrR2.phi == phi, self.ctrR1.phi == a1,
            # B.7, B.8: forces on the link
            F1[0] + f2.fx + L.F[0] == 0,
            F1[1] + f2.fy + L.F[1] == 0,
            # B.9: moments about P1
            f2.t + self.ctrR2.tau + _moment(P, P1, (f2.fx, f2.fy)) + L.moment(P1) == 0,
            # massless housing, moments about the connection point (A.18)
            f1.t + self.ctrR1.tau + _moment(P1, C1, (-F1[0], -F1[1])) == 0,
        ]


    def shapes(self):
        P1, _ = self._port_point(1)
        P = ["ctr2D2.x", "ctr2D2.y"]
        return (self._housing_shapes(1, P1)
                + [{"type": "link", "points": [P1, P]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P[0], "y": P[1]}]
                + self._body_shape("mL", "xSLrel", "ySLrel", "xSL", "ySL"))

    def topology(self):
        # housing plane (ctr2D1) -- revolute at P1 -- crank (ctr2D2)
        return self._ground_ports(1) + [("joint", self.ctr2D1, self.ctr2D2, 1)]

_placement_params(DAN, (1,))


# ================================================================ SAN
class SAN(_Linkage):
    """Linear drive SAN (seed Anhang B.2, Tabellen B.4-B.6, eqs. B.10-B.32).

    A slider with mass moves on a massless straight guide through P1 with
    direction phiU (angle of the placed frame at P1).  The slider travel
    ``xG`` is measured from P1 to the foot point PS; the driven point P lies
    at the constant offset ``v`` perpendicular to the guide (B.16, B.17):
    ``PS = P1 + xG (cos phiU, sin phiU)``, ``P = PS + v (-sin phiU, cos phiU)``.

    Ports: ``ctr2D1`` guide at P1 (triangle: ground-fixed while unconnected),
    ``ctr2D2`` slider plane at P, ``ctrT1`` guide support flange (s = 0,
    force on the guide), ``ctrT2`` slider flange (s = xG, tangential force on
    the slider Ft_S).  Connect a translational motion preset to ``ctrT2`` to
    drive the slider.  Parameters (Tabelle B.5): ``v = 0``, ``xS0`` start
    travel, ``xSrel = ySrel = 0``, ``mS`` (no seed default; 1 kg), ``JS``
    (0.1 kg m²).
    """
    v = Parameter(0.0, "m", "offset of P from the guide line")
    xS0 = Parameter(0.0, "m", "start travel of the slider (guess unless driven)")
    xSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, x")
    ySrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, y")
    mS = Parameter(1.0, "kg", "mass of the slider", min=0.0)
    JS = Parameter(0.1, "kg.m2", "moment of inertia of the slider about its centre of gravity", min=0.0)

    xG = Variable(unit="m", doc="slider travel P1 -> PS", state_select="prefer")
    phiS = Variable(unit="rad", doc="slider angle (= guide angle)")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")
    xSS = Variable(unit="m", doc="centre of gravity of the slider, x")
    ySS = Variable(unit="m", doc="centre of gravity of the slider, y")
    xPS = Variable(unit="m", doc="slider foot point PS on the guide, x (for drawing)")
    yPS = Variable(unit="m", doc="slider foot point PS on the guide, y (for drawing)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(ground=_GROUND, doc="guide at P1")
        self.ctr2D2 = Frame(doc="slider plane at P")
        self.ctrT1 = TranslationalFlange(doc="guide support flange")
        self.ctrT2 = TranslationalFlange(doc="slider flange")

    def _assemble(self, asm):
        p1 = self._input_values(asm, [1])
        if p1 is None:
            return False
        (x1, y1, a), = p1
        t = asm.get(self.ctrT2)
        xG = t["s"] if t and "s" in t else self.xS0
        c, s = ca.cos(a), ca.sin(a)
        xPS, yPS = x1 + xG * c, y1 + xG * s
        dx, dy = _rot(a, self.xSrel, self.ySrel)
        asm.start(self, {"xG": xG, "phiS": a, "xSS": xPS + dx, "ySS": yPS + dy,
                          "xPS": xPS, "yPS": yPS})
        self._set_port(asm, self.ctr2D2, {"x": xPS - self.v * s, "y": yPS + self.v * c, "phi": a})
        self._set_port(asm, self.ctrT2, {"s": xG})
        self._set_port(asm, self.ctrT1, {"s": 0.0})
        return True

    def equations(self):
        (x1, y1, a), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        PS = (x1 + self.xG * c, y1 + self.xG * s)          # B.10, B.11 (sign see module doc)
        P = (PS[0] - self.v * s, PS[1] + self.v * c)       # B.16, B.17
        dx, dy = _rot(a, self.xSrel, self.ySrel)
        S = _Body(self.mS, self.JS, self.xSS, self.ySS, self.phiS, self._g())
        Ft, Fu = self.ctrT2.f, self.ctrT1.f
        Fn = self.Fn
        return [
            self.phiS == a,                                 # B.22
            self.xSS == PS[0] + dx, self.ySS == PS[1] + dy,
            self.xPS == PS[0], self.yPS == PS[1],
            f2.x == P[0], f2.y == P[1], f2.phi == a,        # Tabelle B.6
            self.ctrT2.s == self.xG, self.ctrT1.s == 0,
            # slider B.28-B.30 (joint: normal force, moment; drive force Ft along e)
            Fn * n[0] + Ft * e[0] + f2.fx + S.F[0] == 0,
            Fn * n[1] + Ft * e[1] + f2.fy + S.F[1] == 0,
            self.TPS + f2.t + _moment(P, PS, (f2.fx, f2.fy)) + S.moment(PS) == 0,
            # massless guide B.25-B.27
            f1.fx - Fn * n[0] + Fu * e[0] == 0,
            f1.fy - Fn * n[1] + Fu * e[1] == 0,
            f1.t - self.TPS + _moment(PS, C1, (-Fn * n[0], -Fn * n[1]))
            + _moment((x1, y1), C1, (Fu * e[0], Fu * e[1])) == 0,
        ]


    def shapes(self):
        P1, exact1 = self._port_point(1)
        PS, P = ["xPS", "yPS"], ["ctr2D2.x", "ctr2D2.y"]
        slider = {"type": "slider", "x": PS[0], "y": PS[1], "phi": "phiS"}
        if exact1:
            slider["guide"] = [P1, PS]
        return (self._housing_shapes(1, P1, "phiS")
                + [slider,
                   {"type": "link", "points": [PS, P]},
                   {"type": "joint", "x": P[0], "y": P[1]}])

    def topology(self):
        # guide plane (ctr2D1) -- prismatic -- slider (ctr2D2)
        return self._ground_ports(1) + [("joint", self.ctr2D1, self.ctr2D2, 1)]

_placement_params(SAN, (1,))


# ================================================================ FGP
class FGP(_Linkage):
    """Guided link point FGP (seed Anhang B.3, Tabellen B.7-B.9, B.33-B.41).

    A rigid link with mass, fixed to the plane of its predecessor at
    ``ctr2D1``: its start point P1 and direction phiL are the placed frame
    (``x10, y10, phi10`` relative to the connection, Anhang A.1); the guided
    point P lies at ``lL`` along phiL (B.33, B.34).  Use it for coupler
    points and for the second arm of a bell crank.  Ports: ``ctr2D1``
    (triangle: ground-fixed while unconnected), ``ctr2D2`` plane at P (angle
    phiL).  Parameters (Tabelle B.8): ``lL``, ``xSLrel = lL/2``, ``ySLrel =
    0``, ``mL = 1 kg``, ``JL = 0.1 kg m²`` (set both to 0 for the seed's
    "masselos").
    """
    lL = Parameter(1.0, "m", "link length l_L (P1 -> P)", positive=True)
    xSLrel = Parameter(0.5, "m", "centre of gravity in LKS, x (default lL/2)")
    ySLrel = Parameter(0.0, "m", "centre of gravity in LKS, y")
    mL = Parameter(1.0, "kg", "mass of the link", min=0.0)
    JL = Parameter(0.1, "kg.m2", "moment of inertia about the centre of gravity", min=0.0)

    phiL = Variable(unit="rad", doc="link angle")
    xSL = Variable(unit="m", doc="centre of gravity, x")
    ySL = Variable(unit="m", doc="centre of gravity, y")

    def __init__(self, **kw):
        super().__init__(**kw)
        self._default_half(kw, "xSLrel", "lL")
        self.ctr2D1 = Frame(ground=_GROUND, doc="connection to the predecessor plane")
        self.ctr2D2 = Frame(doc="guided point P")

    def _assemble(self, asm):
        p1 = self._input_values(asm, [1])
        if p1 is None:
            return False
        (x1, y1, a), = p1
        dx, dy = _rot(a, self.xSLrel, self.ySLrel)
        asm.start(self, {"phiL": a, "xSL": x1 + dx, "ySL": y1 + dy})
        self._set_port(asm, self.ctr2D2, {"x": x1 + self.lL * ca.cos(a),
                                          "y": y1 + self.lL * ca.sin(a), "phi": a})
        return True

    def equations(self):
        (x1, y1, a), C1 = self._place(1)
        f1, f2 = self.ctr2D1, self.ctr2D2
        P = (x1 + self.lL * ca.cos(self.phiL), y1 + self.lL * ca.sin(self.phiL))   # B.33, B.34
        dx, dy = _rot(self.phiL, self.xSLrel, self.ySLrel)
        L = _Body(self.mL, self.JL, self.xSL, self.ySL, self.phiL, self._g())
        return [
            self.phiL == a,
            self.xSL == x1 + dx, self.ySL == y1 + dy,
            f2.x == P[0], f2.y == P[1], f2.phi == self.phiL,                         # Tab. B.9
            f1.fx + f2.fx + L.F[0] == 0,                                             # B.39
            f1.fy + f2.fy + L.F[1] == 0,                                             # B.40
            f1.t + f2.t + _moment(P, C1, (f2.fx, f2.fy)) + L.moment(C1) == 0,         # B.41
        ]


    def shapes(self):
        P1, _ = self._port_point(1)
        P = ["ctr2D2.x", "ctr2D2.y"]
        return (self._housing_shapes(1, P1, "phiL")
                + [{"type": "link", "points": [P1, P]}]
                + self._body_shape("mL", "xSLrel", "ySLrel", "xSL", "ySL"))

    def topology(self):
        # part of the predecessor's plane: no joint, one rigid link
        return self._ground_ports(1) + [("rigid", [self.ctr2D1, self.ctr2D2])]

_placement_params(FGP, (1,))


# ================================================================ DDD
def vdi_ddd(x1, y1, x2, y2, l1, l2, K, sqrt=ca.sqrt):
    """VDI 2729 DDD start solution (B.42-B.52): (xP, yP, phiL1, phiL2)."""
    H1 = x2 - x1                                    # B.42
    H2 = y2 - y1                                    # B.43
    H3 = H1 ** 2 + H2 ** 2                          # B.44
    H4 = l1 ** 2 - l2 ** 2 + H3                     # B.45
    H5 = K * sqrt(4 * H3 * l1 ** 2 - H4 ** 2)       # B.46
    H6 = (H1 * H4 - H2 * H5) / (2 * H3)             # B.47
    H7 = (H2 * H4 + H1 * H5) / (2 * H3)             # B.48
    return (x1 + H6, y1 + H7,                       # B.49, B.50
            ca.atan2(H7, H6), ca.atan2(H7 - H2, H6 - H1))   # B.51, B.52


class DDD(_Linkage):
    """Dyad with three revolute joints DDD (seed Anhang B.4, Tabellen
    B.10-B.12, eqs. B.42-B.70).

    Link 1 (length ``lL1``) turns about P1, link 2 (``lL2``) about P2; they
    are joined at P.  Position equations in point-direction form (B.53,
    B.54, B.59, B.60): ``P = P1 + lL1 e(phiL1) = P2 + lL2 e(phiL2)``.
    ``K = +1`` puts P on the left of the line P1 -> P2 at the start, ``K =
    -1`` on the right (VDI 2729, B.42-B.52 give the start angles).

    Ports: ``ctr2D1``/``ctr2D2`` bearing housings at P1/P2 (triangles:
    ground-fixed while unconnected), ``ctr2D3`` plane of link 1 at P1 (angle
    phiL1), ``ctr2D4`` plane of link 2 at P2 (angle phiL2), ``ctrR1`` flange
    on housing 2 (support), ``ctrR2`` flange on link 2 (angle phiL2).
    Outputs ``xP, yP``: the joint point P.  Parameters (Tabelle B.11):
    ``lL1 = lL2 = 1 m``, ``K``, ``xSL1rel = lL1/2``, ``xSL2rel = lL2/2``,
    ``ySL1rel = ySL2rel = 0``, ``mL1 = mL2 = 1 kg``, ``JL1 = JL2 = 0.1 kg m²``.
    """
    lL1 = Parameter(1.0, "m", "length of link 1 (P1 -> P)", positive=True)
    lL2 = Parameter(1.0, "m", "length of link 2 (P2 -> P)", positive=True)
    K = Parameter(1.0, "", "assembly parameter: +1 P left of P1->P2, -1 right (start only)")
    xSL1rel = Parameter(0.5, "m", "centre of gravity of link 1 in LKS1, x (default lL1/2)")
    ySL1rel = Parameter(0.0, "m", "centre of gravity of link 1 in LKS1, y")
    xSL2rel = Parameter(0.5, "m", "centre of gravity of link 2 in LKS2, x (default lL2/2)")
    ySL2rel = Parameter(0.0, "m", "centre of gravity of link 2 in LKS2, y")
    mL1 = Parameter(1.0, "kg", "mass of link 1", min=0.0)
    JL1 = Parameter(0.1, "kg.m2", "moment of inertia of link 1 about its centre of gravity", min=0.0)
    mL2 = Parameter(1.0, "kg", "mass of link 2", min=0.0)
    JL2 = Parameter(0.1, "kg.m2", "moment of inertia of link 2 about its centre of gravity", min=0.0)

    phiL1 = Variable(unit="rad", doc="angle of link 1 (P1 -> P)")
    phiL2 = Variable(unit="rad", doc="angle of link 2 (P2 -> P)")
    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force link 2 -> link 1 at P, x")
    FPy = Variable(unit="N", doc="joint force link 2 -> link 1 at P, y")
    xSL1 = Variable(unit="m", doc="centre of gravity of link 1, x")
    ySL1 = Variable(unit="m", doc="centre of gravity of link 1, y")
    xSL2 = Variable(unit="m", doc="centre of gravity of link 2, x")
    ySL2 = Variable(unit="m", doc="centre of gravity of link 2, y")

    def __init__(self, **kw):
        super().__init__(**kw)
        self._default_half(kw, "xSL1rel", "lL1")
        self._default_half(kw, "xSL2rel", "lL2")
        self.ctr2D1 = Frame(ground=_GROUND, doc="housing at P1")
        self.ctr2D2 = Frame(ground=_GROUND, doc="housing at P2")
        self.ctr2D3 = Frame(doc="link 1 plane at P1")
        self.ctr2D4 = Frame(doc="link 2 plane at P2")
        self.ctrR1 = RotationalFlange(doc="housing 2 (support) flange")
        self.ctrR2 = RotationalFlange(doc="link 2 flange")

    def _assemble(self, asm):
        vals = self._input_values(asm, [1, 2])
        if vals is None:
            return False
        (x1, y1, _), (x2, y2, a2) = vals
        l1, l2 = self.lL1, self.lL2
        d2 = (x2 - x1) ** 2 + (y2 - y1) ** 2
        asm.check(self, 4 * d2 * l1 ** 2 - (l1 ** 2 - l2 ** 2 + d2) ** 2,
                  "|lL1 - lL2| <= |P1 P2| <= lL1 + lL2 (B.46)",
                  "The links cannot reach between P1 and P2; change lL1, lL2 or the "
                  "positions of P1/P2 (or the start angle of the drive).")
        xP, yP, p1, p2 = vdi_ddd(x1, y1, x2, y2, l1, l2, self.K,
                                 sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        d1, d2 = _rot(p1, self.xSL1rel, self.ySL1rel), _rot(p2, self.xSL2rel, self.ySL2rel)
        asm.start(self, {"phiL1": p1, "phiL2": p2, "xP": xP, "yP": yP,
                          "xSL1": x1 + d1[0], "ySL1": y1 + d1[1],
                          "xSL2": x2 + d2[0], "ySL2": y2 + d2[1]})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": p1})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": p2})
        self._set_port(asm, self.ctrR2, {"phi": p2})
        self._set_port(asm, self.ctrR1, {"phi": a2})
        return True

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, a2), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        p1, p2 = self.phiL1, self.phiL2
        P1, P2, P = (x1, y1), (x2, y2), (self.xP, self.yP)
        d1, d2 = _rot(p1, self.xSL1rel, self.ySL1rel), _rot(p2, self.xSL2rel, self.ySL2rel)
        g = self._g()
        L1 = _Body(self.mL1, self.JL1, self.xSL1, self.ySL1, p1, g)
        L2 = _Body(self.mL2, self.JL2, self.xSL2, self.ySL2, p2, g)
        FP = (self.FPx, self.FPy)
        return [
            self.xP == x1 + self.lL1 * ca.cos(p1),             # B.53
            self.yP == y1 + self.lL1 * ca.sin(p1),             # B.54
            self.xP == x2 + self.lL2 * ca.cos(p2),             # B.59
            self.yP == y2 + self.lL2 * ca.sin(p2),             # B.60
            self.xSL1 == x1 + d1[0], self.ySL1 == y1 + d1[1],  # A.21, A.22
            self.xSL2 == x2 + d2[0], self.ySL2 == y2 + d2[1],
            f3.x == x1, f3.y == y1, f3.phi == p1,              # Tabelle B.12
            f4.x == x2, f4.y == y2, f4.phi == p2,
            self.ctrR2.phi == p2, self.ctrR1.phi == a2,
            # link 1, B.65-B.67 (moments about P1)
            f1.fx + FP[0] + f3.fx + L1.F[0] == 0,
            f1.fy + FP[1] + f3.fy + L1.F[1] == 0,
            f3.t + _moment(P, P1, FP) + L1.moment(P1) == 0,
            # link 2, B.68-B.70 (moments about P2)
            f2.fx - FP[0] + f4.fx + L2.F[0] == 0,
            f2.fy - FP[1] + f4.fy + L2.F[1] == 0,
            f4.t + self.ctrR2.tau + _moment(P, P2, (-FP[0], -FP[1])) + L2.moment(P2) == 0,
            # massless housings (A.18)
            f1.t + _moment(P1, C1, (-f1.fx, -f1.fy)) == 0,
            f2.t + self.ctrR1.tau + _moment(P2, C2, (-f2.fx, -f2.fy)) == 0,
        ]


    def shapes(self):
        P1, P2, P = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xP", "yP"]
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2)
                + [{"type": "link", "points": [P1, P]},
                   {"type": "link", "points": [P2, P]}]
                + [{"type": "joint", "x": q[0], "y": q[1]} for q in (P1, P2, P)]
                + self._body_shape("mL1", "xSL1rel", "ySL1rel", "xSL1", "ySL1")
                + self._body_shape("mL2", "xSL2rel", "ySL2rel", "xSL2", "ySL2"))

    def topology(self):
        # links: link 1 = ctr2D3, link 2 = ctr2D4; revolutes at P1, P2, P
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]

_placement_params(DDD, (1, 2))


# ================================================================ DDS
def vdi_dds(x1, y1, x2, y2, phiU, l, v, K, sqrt=ca.sqrt):
    """VDI 2729 DDS start solution (B.71-B.86): (xP0, yP0, phiL0)."""
    xPH, yPH = x2 + ca.cos(phiU), y2 + ca.sin(phiU)        # B.71, B.72
    H1 = xPH - x2                                          # B.73
    H2 = yPH - y2                                          # B.74
    H3 = H1 ** 2 + H2 ** 2                                 # B.75
    H4 = H1 / ca.sqrt(H3)                                  # B.76
    H5 = H2 / ca.sqrt(H3)                                  # B.77
    H6 = x2 - x1                                           # B.78
    H7 = y2 - y1                                           # B.79
    H8 = H4 * H7 - H5 * H6 + v                             # B.80
    H9 = H6 ** 2 + H7 ** 2 + v ** 2 - l ** 2 + 2 * v * (H8 - v)   # B.81
    H10 = H4 * H6 + H5 * H7                                # B.82
    H11 = K * sqrt(H10 ** 2 - H9) - H10                    # B.83
    xP0 = x2 + H4 * H11 - H5 * v                           # B.84
    yP0 = y2 + H5 * H11 + H4 * v                           # B.85
    return xP0, yP0, ca.atan2(y1 - yP0, x1 - xP0), H11     # B.86 (and x_G)


class DDS(_Linkage):
    """Dyad with a prismatic joint as outer joint DDS (seed Anhang B.5,
    Tabellen B.13-B.15, eqs. B.71-B.118).

    A link of length ``lL`` turns about P1; at its other end P it carries,
    by a revolute joint, a slider guided on a massless straight guide through
    P2 with direction phiU (the placed frame at P2).  P lies at the offset
    ``v`` from the guide line:
    ``P = P1 - lL e(phiL)`` (B.87, B.88; the link frame LKS sits in P and
    points to P1), ``PS = P2 + xG e(phiU)`` (B.99, B.100), ``P = PS + v
    n(phiU)`` (B.93, B.94).  ``K = +1`` puts P, at the start, on the side of
    the perpendicular from P1 onto the guide towards which the guide's
    x-axis points; ``K = -1`` on the other side (B.71-B.86).

    Ports: ``ctr2D1`` housing at P1 (triangle), ``ctr2D2`` guide at P2
    (triangle), ``ctr2D3`` link plane at P1 (angle phiL), ``ctr2D4`` slider
    plane at PS (angle phiU), ``ctrT1`` guide support flange (s = 0),
    ``ctrT2`` slider flange (s = xG, tangential force on the slider).
    Outputs ``xP, yP``.  Parameters (Tabelle B.14): ``lL = 1 m``, ``v = 0.1
    m``, ``K``, ``xSLrel = lL/2``, ``ySLrel = 0``, ``xSSrel = ySSrel = 0``,
    ``mL = mS = 1 kg``, ``JL = JS = 0.1 kg m²``.
    """
    lL = Parameter(1.0, "m", "link length (P1 - P)", positive=True)
    v = Parameter(0.1, "m", "offset of P from the guide line")
    K = Parameter(1.0, "", "assembly parameter (start only), see class doc")
    xSLrel = Parameter(0.5, "m", "centre of gravity of the link in LKS, x (default lL/2)")
    ySLrel = Parameter(0.0, "m", "centre of gravity of the link in LKS, y")
    xSSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, x")
    ySSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, y")
    mL = Parameter(1.0, "kg", "mass of the link", min=0.0)
    JL = Parameter(0.1, "kg.m2", "moment of inertia of the link about its centre of gravity", min=0.0)
    mS = Parameter(1.0, "kg", "mass of the slider", min=0.0)
    JS = Parameter(0.1, "kg.m2", "moment of inertia of the slider about its centre of gravity", min=0.0)

    phiL = Variable(unit="rad", doc="link angle (direction P -> P1)")
    xG = Variable(unit="m", doc="slider travel P2 -> PS")
    phiS = Variable(unit="rad", doc="slider angle (= guide angle)")
    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force slider -> link at P, x")
    FPy = Variable(unit="N", doc="joint force slider -> link at P, y")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")
    xSL = Variable(unit="m", doc="centre of gravity of the link, x")
    ySL = Variable(unit="m", doc="centre of gravity of the link, y")
    xSS = Variable(unit="m", doc="centre of gravity of the slider, x")
    ySS = Variable(unit="m", doc="centre of gravity of the slider, y")

    def __init__(self, **kw):
        super().__init__(**kw)
        self._default_half(kw, "xSLrel", "lL")
        self.ctr2D1 = Frame(ground=_GROUND, doc="housing at P1")
        self.ctr2D2 = Frame(ground=_GROUND, doc="guide at P2")
        self.ctr2D3 = Frame(doc="link plane at P1")
        self.ctr2D4 = Frame(doc="slider plane at PS")
        self.ctrT1 = TranslationalFlange(doc="guide support flange")
        self.ctrT2 = TranslationalFlange(doc="slider flange")

    def _assemble(self, asm):
        vals = self._input_values(asm, [1, 2])
        if vals is None:
            return False
        (x1, y1, _), (x2, y2, a) = vals
        dist = -ca.sin(a) * (x1 - x2) + ca.cos(a) * (y1 - y2) - self.v
        asm.check(self, self.lL ** 2 - dist ** 2,
                  "distance of P1 from the offset guide line <= lL (B.83)",
                  "The link cannot reach the guide; change lL, v or the positions.")
        xP, yP, phiL, xG = vdi_dds(x1, y1, x2, y2, a, self.lL, self.v, self.K,
                                   sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        xPS, yPS = x2 + xG * ca.cos(a), y2 + xG * ca.sin(a)
        dL, dS = _rot(phiL, self.xSLrel, self.ySLrel), _rot(a, self.xSSrel, self.ySSrel)
        asm.start(self, {"phiL": phiL, "xG": xG, "phiS": a, "xP": xP, "yP": yP,
                          "xSL": xP + dL[0], "ySL": yP + dL[1],
                          "xSS": xPS + dS[0], "ySS": yPS + dS[1]})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": phiL})
        self._set_port(asm, self.ctr2D4, {"x": xPS, "y": yPS, "phi": a})
        self._set_port(asm, self.ctrT2, {"s": xG})
        self._set_port(asm, self.ctrT1, {"s": 0.0})
        return True

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, a), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        phiL = self.phiL
        P1, P2, P = (x1, y1), (x2, y2), (self.xP, self.yP)
        PS = (x2 + self.xG * c, y2 + self.xG * s)                   # B.99, B.100
        dL, dS = _rot(phiL, self.xSLrel, self.ySLrel), _rot(a, self.xSSrel, self.ySSrel)
        g = self._g()
        L = _Body(self.mL, self.JL, self.xSL, self.ySL, phiL, g)
        S = _Body(self.mS, self.JS, self.xSS, self.ySS, self.phiS, g)
        FP = (self.FPx, self.FPy)
        Fn, Ft, Fu = self.Fn, self.ctrT2.f, self.ctrT1.f
        return [
            self.xP == x1 - self.lL * ca.cos(phiL),                # B.87
            self.yP == y1 - self.lL * ca.sin(phiL),                # B.88
            self.xP == PS[0] - self.v * s,                          # B.93
            self.yP == PS[1] + self.v * c,                          # B.94
            self.phiS == a,                                         # B.105
            self.xSL == P[0] + dL[0], self.ySL == P[1] + dL[1],
            self.xSS == PS[0] + dS[0], self.ySS == PS[1] + dS[1],
            f3.x == x1, f3.y == y1, f3.phi == phiL,                 # Tabelle B.15
            f4.x == PS[0], f4.y == PS[1], f4.phi == a,
            self.ctrT2.s == self.xG, self.ctrT1.s == 0,
            # link B.108-B.110 (moments about P1)
            f1.fx + FP[0] + f3.fx + L.F[0] == 0,
            f1.fy + FP[1] + f3.fy + L.F[1] == 0,
            f3.t + _moment(P, P1, FP) + L.moment(P1) == 0,
            # slider B.111-B.113 (moments about PS)
            -FP[0] + Fn * n[0] + Ft * e[0] + f4.fx + S.F[0] == 0,
            -FP[1] + Fn * n[1] + Ft * e[1] + f4.fy + S.F[1] == 0,
            self.TPS + f4.t + _moment(P, PS, (-FP[0], -FP[1])) + S.moment(PS) == 0,
            # massless guide B.114-B.116
            f2.fx - Fn * n[0] + Fu * e[0] == 0,
            f2.fy - Fn * n[1] + Fu * e[1] == 0,
            f2.t - self.TPS + _moment(PS, C2, (-Fn * n[0], -Fn * n[1]))
            + _moment(P2, C2, (Fu * e[0], Fu * e[1])) == 0,
            # massless housing at P1
            f1.t + _moment(P1, C1, (-f1.fx, -f1.fy)) == 0,
        ]


    def shapes(self):
        P1, PS, P = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xP", "yP"]
        P2, exact2 = self._port_point(2)
        slider = {"type": "slider", "x": PS[0], "y": PS[1], "phi": "phiS"}
        if exact2:
            slider["guide"] = [P2, PS]
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2, "phiS")
                + [{"type": "link", "points": [P1, P]}, slider,
                   {"type": "link", "points": [PS, P]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P[0], "y": P[1]}]
                + self._body_shape("mL", "xSLrel", "ySLrel", "xSL", "ySL"))

    def topology(self):
        # links: link = ctr2D3, slider = ctr2D4; revolutes at P1 and P,
        # prismatic between the guide plane (ctr2D2) and the slider
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1)]

_placement_params(DDS, (1, 2))


# ================================================================ DSD
def vdi_dsd(x1, y1, x2, y2, v, sqrt=ca.sqrt):
    """VDI 2729 DSD start solution (B.119-B.125): (phiU, xG)."""
    H1 = x2 - x1                                    # B.119
    H2 = y2 - y1                                    # B.120
    H3 = H1 ** 2 + H2 ** 2                          # B.121
    H4 = sqrt(H3 - v ** 2)                          # B.122
    H5 = (H1 * H4 + v * H2) / H3                    # B.123
    H6 = (H2 * H4 - v * H1) / H3                    # B.124 (sign, see module doc)
    return ca.atan2(H6, H5), H4                     # B.125


class DSD(_Linkage):
    """Dyad with a prismatic joint as inner joint DSD (seed Anhang B.6,
    Tabellen B.16-B.18, eqs. B.119-B.148).

    A guide with mass turns about P1; a slider with mass slides on it and
    turns about P2.  ``PS = P1 + xG e(phiU)`` (B.126, B.127) and ``P2 = PS +
    v n(phiU)`` (B.132, B.133); the slider angle equals phiU (B.138).  The
    start direction follows B.119-B.125 with ``xG > 0``; VDI's K would only
    move an auxiliary point and is not needed (ch. 4.2.1).  The distance
    P1-P2 must exceed ``|v|``.

    Ports: ``ctr2D1``/``ctr2D2`` housings at P1/P2 (triangles), ``ctr2D3``
    guide plane at P1 (angle phiU), ``ctr2D4`` slider plane at P2 (angle
    phiU), ``ctrT1`` slider flange (s = xG, tangential force on the slider),
    ``ctrT2`` guide flange (s = 0, tangential force on the guide) as in
    Tabelle B.18.  Parameters (Tabelle B.17): ``v = 0.1 m``, ``xSUrel =
    ySUrel = xSSrel = ySSrel = 0`` (guide CoG in UKS at P1, slider CoG in SKS
    at PS), ``mU = mS = 1 kg``, ``JU = JS = 0.1 kg m²``.
    """
    v = Parameter(0.1, "m", "offset of P2 from the guide line")
    xSUrel = Parameter(0.0, "m", "centre of gravity of the guide in UKS, x")
    ySUrel = Parameter(0.0, "m", "centre of gravity of the guide in UKS, y")
    xSSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, x")
    ySSrel = Parameter(0.0, "m", "centre of gravity of the slider in SKS, y")
    mU = Parameter(1.0, "kg", "mass of the guide", min=0.0)
    JU = Parameter(0.1, "kg.m2", "moment of inertia of the guide about its centre of gravity", min=0.0)
    mS = Parameter(1.0, "kg", "mass of the slider", min=0.0)
    JS = Parameter(0.1, "kg.m2", "moment of inertia of the slider about its centre of gravity", min=0.0)

    phiU = Variable(unit="rad", doc="guide angle (= slider angle)")
    xG = Variable(unit="m", doc="slider travel P1 -> PS")
    Fn = Variable(unit="N", doc="normal force guide -> slider")
    TPS = Variable(unit="N.m", doc="moment guide -> slider")
    xSU = Variable(unit="m", doc="centre of gravity of the guide, x")
    ySU = Variable(unit="m", doc="centre of gravity of the guide, y")
    xSS = Variable(unit="m", doc="centre of gravity of the slider, x")
    ySS = Variable(unit="m", doc="centre of gravity of the slider, y")
    xPS = Variable(unit="m", doc="slider foot point PS on the guide, x (for drawing)")
    yPS = Variable(unit="m", doc="slider foot point PS on the guide, y (for drawing)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(ground=_GROUND, doc="housing at P1")
        self.ctr2D2 = Frame(ground=_GROUND, doc="housing at P2")
        self.ctr2D3 = Frame(doc="guide plane at P1")
        self.ctr2D4 = Frame(doc="slider plane at P2")
        self.ctrT1 = TranslationalFlange(doc="slider flange")
        self.ctrT2 = TranslationalFlange(doc="guide flange")

    def _assemble(self, asm):
        vals = self._input_values(asm, [1, 2])
        if vals is None:
            return False
        (x1, y1, _), (x2, y2, _) = vals
        asm.check(self, (x2 - x1) ** 2 + (y2 - y1) ** 2 - self.v ** 2,
                  "|P1 P2| >= |v| (B.122)", "Increase the distance P1-P2 or reduce v.")
        asm.check(self, ca.sqrt((x2 - x1) ** 2 + (y2 - y1) ** 2) - 1e-9,
                  "P1 != P2 (the guide's pivot P1 is not on the slider's pivot P2)",
                  "Move P1 (x10, y10) or P2 (x20, y20): the guide direction is undefined.")
        a, xG = vdi_dsd(x1, y1, x2, y2, self.v, sqrt=lambda z: ca.sqrt(ca.fmax(z, 0)))
        xPS, yPS = x1 + xG * ca.cos(a), y1 + xG * ca.sin(a)
        dU, dS = _rot(a, self.xSUrel, self.ySUrel), _rot(a, self.xSSrel, self.ySSrel)
        asm.start(self, {"phiU": a, "xG": xG, "xSU": x1 + dU[0], "ySU": y1 + dU[1],
                          "xSS": xPS + dS[0], "ySS": yPS + dS[1], "xPS": xPS, "yPS": yPS})
        self._set_port(asm, self.ctr2D3, {"x": x1, "y": y1, "phi": a})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": a})
        self._set_port(asm, self.ctrT1, {"s": xG})
        self._set_port(asm, self.ctrT2, {"s": 0.0})
        return True

    def equations(self):
        (x1, y1, _), C1 = self._place(1)
        (x2, y2, _), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        a = self.phiU
        c, s = ca.cos(a), ca.sin(a)
        e, n = (c, s), (-s, c)
        P1, P2 = (x1, y1), (x2, y2)
        PS = (x1 + self.xG * c, y1 + self.xG * s)                   # B.126, B.127
        dU, dS = _rot(a, self.xSUrel, self.ySUrel), _rot(a, self.xSSrel, self.ySSrel)
        g = self._g()
        U = _Body(self.mU, self.JU, self.xSU, self.ySU, a, g)
        S = _Body(self.mS, self.JS, self.xSS, self.ySS, a, g)
        Fn, Ft, Fu = self.Fn, self.ctrT1.f, self.ctrT2.f
        FS = (Fn * n[0] + Ft * e[0], Fn * n[1] + Ft * e[1])   # guide -> slider at PS
        return [
            x2 == PS[0] - self.v * s,                               # B.132
            y2 == PS[1] + self.v * c,                               # B.133
            self.xSU == x1 + dU[0], self.ySU == y1 + dU[1],
            self.xSS == PS[0] + dS[0], self.ySS == PS[1] + dS[1],
            self.xPS == PS[0], self.yPS == PS[1],
            f3.x == x1, f3.y == y1, f3.phi == a,                    # Tabelle B.18
            f4.x == x2, f4.y == y2, f4.phi == a,
            self.ctrT1.s == self.xG, self.ctrT2.s == 0,
            # guide B.141-B.143 (moments about P1)
            f1.fx + f3.fx - Fn * n[0] + Fu * e[0] + U.F[0] == 0,
            f1.fy + f3.fy - Fn * n[1] + Fu * e[1] + U.F[1] == 0,
            f3.t - self.TPS + _moment(PS, P1, (-Fn * n[0], -Fn * n[1])) + U.moment(P1) == 0,
            # slider B.144-B.146 (moments about P2)
            f2.fx + f4.fx + FS[0] + S.F[0] == 0,
            f2.fy + f4.fy + FS[1] + S.F[1] == 0,
            f4.t + self.TPS + _moment(PS, P2, FS) + S.moment(P2) == 0,
            # massless housings
            f1.t + _moment(P1, C1, (-f1.fx, -f1.fy)) == 0,
            f2.t + _moment(P2, C2, (-f2.fx, -f2.fy)) == 0,
        ]


    def shapes(self):
        P1, P2, PS = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"], ["xPS", "yPS"]
        return (self._housing_shapes(1, P1) + self._housing_shapes(2, P2)
                + [{"type": "link", "points": [P1, PS]},
                   {"type": "slider", "x": PS[0], "y": PS[1], "phi": "phiU"},
                   {"type": "link", "points": [PS, P2]},
                   {"type": "joint", "x": P1[0], "y": P1[1]},
                   {"type": "joint", "x": P2[0], "y": P2[1]}]
                + self._body_shape("mU", "xSUrel", "ySUrel", "xSU", "ySU"))

    def topology(self):
        # links: guide = ctr2D3, slider = ctr2D4; revolutes at P1 and P2,
        # prismatic between guide and slider
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]

_placement_params(DSD, (1, 2))


# ================================================================ SSD
def solve_ssd(x1, y1, a1, x2, y2, v1, v2, phiv):
    """Closed-form travels (xG1, xG2) of SSD (B.158-B.177 solved, linear)."""
    a2 = a1 + phiv
    e1, n1 = (ca.cos(a1), ca.sin(a1)), (-ca.sin(a1), ca.cos(a1))
    e2, n2 = (ca.cos(a2), ca.sin(a2)), (-ca.sin(a2), ca.cos(a2))
    rx = x2 - x1 - v1 * n1[0] - v2 * n2[0]
    ry = y2 - y1 - v1 * n1[1] - v2 * n2[1]
    det = _cross(e1[0], e1[1], e2[0], e2[1])
    return _cross(rx, ry, e2[0], e2[1]) / det, _cross(e1[0], e1[1], rx, ry) / det


class SSD(_Linkage):
    """Dyad with prismatic joints as outer and inner joint SSD (seed Anhang
    B.7, Tabellen B.19-B.21, eqs. B.149-B.194).

    Slider 1 slides on a massless guide 1 fixed to the plane at P1 (direction
    phiU1 = angle of the placed frame); it carries the point P at the offset
    ``v1`` and a second guide at the angle ``phiv`` against guide 1.  Slider 2
    slides on guide 2 and turns about P2 at the offset ``v2``:
    ``PS1 = P1 + xG1 e1`` (B.158), ``P = PS1 + v1 n1`` (B.164), ``PS2 = P +
    xG2 e2`` (B.170), ``P2 = PS2 + v2 n2`` (B.176), ``phiU2 = phiU1 + phiv``
    (B.152).  Linear in the travels: no assembly parameter.

    Ports: ``ctr2D1`` guide 1 at P1 (triangle, rigid), ``ctr2D2`` housing at
    P2 (triangle, revolute), ``ctr2D3`` slider 1 plane at P (angle phiU1),
    ``ctr2D4`` slider 2 plane at P2 (angle phiU2).  Parameters (Tabelle
    B.20): ``v1 = v2 = 0.1 m``, ``phiv = 15°``, CoG offsets 0 in SKS1 (at PS1)
    and SKS2 (at PS2), ``mS1 = mS2 = 1 kg``, ``JS1 = JS2 = 0.1 kg m²``.
    """
    v1 = Parameter(0.1, "m", "offset of P from guide 1")
    v2 = Parameter(0.1, "m", "offset of P2 from guide 2")
    phiv = Parameter(math.radians(15.0), "rad", "angle of guide 2 against guide 1")
    xSS1rel = Parameter(0.0, "m", "centre of gravity of slider 1 in SKS1, x")
    ySS1rel = Parameter(0.0, "m", "centre of gravity of slider 1 in SKS1, y")
    xSS2rel = Parameter(0.0, "m", "centre of gravity of slider 2 in SKS2, x")
    ySS2rel = Parameter(0.0, "m", "centre of gravity of slider 2 in SKS2, y")
    mS1 = Parameter(1.0, "kg", "mass of slider 1", min=0.0)
    JS1 = Parameter(0.1, "kg.m2", "moment of inertia of slider 1 about its centre of gravity", min=0.0)
    mS2 = Parameter(1.0, "kg", "mass of slider 2", min=0.0)
    JS2 = Parameter(0.1, "kg.m2", "moment of inertia of slider 2 about its centre of gravity", min=0.0)

    xG1 = Variable(unit="m", doc="travel of slider 1, P1 -> PS1")
    xG2 = Variable(unit="m", doc="travel of slider 2, P -> PS2")
    phiS1 = Variable(unit="rad", doc="angle of slider 1 (= guide 1)")
    phiS2 = Variable(unit="rad", doc="angle of slider 2 (= guide 2)")
    Fn1 = Variable(unit="N", doc="normal force guide 1 -> slider 1")
    T1 = Variable(unit="N.m", doc="moment guide 1 -> slider 1")
    Fn2 = Variable(unit="N", doc="normal force slider 1 -> slider 2")
    T2 = Variable(unit="N.m", doc="moment slider 1 -> slider 2")
    xSS1 = Variable(unit="m", doc="centre of gravity of slider 1, x")
    ySS1 = Variable(unit="m", doc="centre of gravity of slider 1, y")
    xSS2 = Variable(unit="m", doc="centre of gravity of slider 2, x")
    ySS2 = Variable(unit="m", doc="centre of gravity of slider 2, y")
    xPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, x (for drawing)")
    yPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, y (for drawing)")
    xPS2 = Variable(unit="m", doc="foot point PS2 of slider 2 on guide 2, x (for drawing)")
    yPS2 = Variable(unit="m", doc="foot point PS2 of slider 2 on guide 2, y (for drawing)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(ground=_GROUND, doc="guide 1 at P1")
        self.ctr2D2 = Frame(ground=_GROUND, doc="housing at P2")
        self.ctr2D3 = Frame(doc="slider 1 plane at P")
        self.ctr2D4 = Frame(doc="slider 2 plane at P2")

    def _assemble(self, asm):
        vals = self._input_values(asm, [1, 2])
        if vals is None:
            return False
        (x1, y1, a1), (x2, y2, _) = vals
        a2 = a1 + self.phiv
        asm.check(self, ca.fabs(ca.sin(self.phiv)) - 1e-9,
                  "guides 1 and 2 not parallel, sin(phiv) != 0 (B.158-B.177)",
                  "Give phiv a value other than 0 or 180 degrees.")
        xG1, xG2 = solve_ssd(x1, y1, a1, x2, y2, self.v1, self.v2, self.phiv)
        PS1 = (x1 + xG1 * ca.cos(a1), y1 + xG1 * ca.sin(a1))
        P = (PS1[0] - self.v1 * ca.sin(a1), PS1[1] + self.v1 * ca.cos(a1))
        PS2 = (P[0] + xG2 * ca.cos(a2), P[1] + xG2 * ca.sin(a2))
        d1, d2 = _rot(a1, self.xSS1rel, self.ySS1rel), _rot(a2, self.xSS2rel, self.ySS2rel)
        asm.start(self, {"xG1": xG1, "xG2": xG2, "phiS1": a1, "phiS2": a2,
                          "xSS1": PS1[0] + d1[0], "ySS1": PS1[1] + d1[1],
                          "xSS2": PS2[0] + d2[0], "ySS2": PS2[1] + d2[1],
                          "xPS1": PS1[0], "yPS1": PS1[1], "xPS2": PS2[0], "yPS2": PS2[1]})
        self._set_port(asm, self.ctr2D3, {"x": P[0], "y": P[1], "phi": a1})
        self._set_port(asm, self.ctr2D4, {"x": x2, "y": y2, "phi": a2})
        return True

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        (x2, y2, _), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        a2 = self.phiS2
        e1, n1 = (ca.cos(a1), ca.sin(a1)), (-ca.sin(a1), ca.cos(a1))
        e2, n2 = (ca.cos(a2), ca.sin(a2)), (-ca.sin(a2), ca.cos(a2))
        P2 = (x2, y2)
        PS1 = (x1 + self.xG1 * e1[0], y1 + self.xG1 * e1[1])               # B.158, B.159
        P = (PS1[0] + self.v1 * n1[0], PS1[1] + self.v1 * n1[1])           # B.164, B.165
        PS2 = (P[0] + self.xG2 * e2[0], P[1] + self.xG2 * e2[1])           # B.170, B.171
        d1, d2 = _rot(a1, self.xSS1rel, self.ySS1rel), _rot(a2, self.xSS2rel, self.ySS2rel)
        g = self._g()
        S1 = _Body(self.mS1, self.JS1, self.xSS1, self.ySS1, self.phiS1, g)
        S2 = _Body(self.mS2, self.JS2, self.xSS2, self.ySS2, a2, g)
        N1 = (self.Fn1 * n1[0], self.Fn1 * n1[1])
        N2 = (self.Fn2 * n2[0], self.Fn2 * n2[1])
        return [
            self.phiS1 == a1,                                             # B.149
            self.phiS2 == a1 + self.phiv,                                 # B.152, B.155
            x2 == PS2[0] + self.v2 * n2[0],                               # B.176
            y2 == PS2[1] + self.v2 * n2[1],                               # B.177
            self.xSS1 == PS1[0] + d1[0], self.ySS1 == PS1[1] + d1[1],
            self.xSS2 == PS2[0] + d2[0], self.ySS2 == PS2[1] + d2[1],
            self.xPS1 == PS1[0], self.yPS1 == PS1[1],
            self.xPS2 == PS2[0], self.yPS2 == PS2[1],
            f3.x == P[0], f3.y == P[1], f3.phi == a1,                     # Tabelle B.21
            f4.x == x2, f4.y == y2, f4.phi == a2,
            # massless guide 1 (B.182-B.184), moments about C1
            f1.fx - N1[0] == 0, f1.fy - N1[1] == 0,
            f1.t - self.T1 + _moment(PS1, C1, (-N1[0], -N1[1])) == 0,
            # slider 1 (B.185-B.187), moments about PS1
            N1[0] - N2[0] + f3.fx + S1.F[0] == 0,
            N1[1] - N2[1] + f3.fy + S1.F[1] == 0,
            self.T1 - self.T2 + f3.t + _moment(PS2, PS1, (-N2[0], -N2[1]))
            + _moment(P, PS1, (f3.fx, f3.fy)) + S1.moment(PS1) == 0,
            # slider 2 (B.188-B.190), moments about PS2
            N2[0] + f2.fx + f4.fx + S2.F[0] == 0,
            N2[1] + f2.fy + f4.fy + S2.F[1] == 0,
            self.T2 + f4.t + _moment(P2, PS2, (f2.fx + f4.fx, f2.fy + f4.fy))
            + S2.moment(PS2) == 0,
            # massless housing at P2
            f2.t + _moment(P2, C2, (-f2.fx, -f2.fy)) == 0,
        ]


    def shapes(self):
        P1, exact1 = self._port_point(1)
        P, P2 = ["ctr2D3.x", "ctr2D3.y"], ["ctr2D4.x", "ctr2D4.y"]
        PS1, PS2 = ["xPS1", "yPS1"], ["xPS2", "yPS2"]
        slider1 = {"type": "slider", "x": PS1[0], "y": PS1[1], "phi": "phiS1"}
        if exact1:
            slider1["guide"] = [P1, PS1]
        return (self._housing_shapes(1, P1, "phiS1") + self._housing_shapes(2, P2)
                + [slider1,
                   {"type": "link", "points": [PS1, P]},
                   {"type": "slider", "x": PS2[0], "y": PS2[1], "phi": "phiS2",
                    "guide": [P, PS2]},
                   {"type": "link", "points": [PS2, P2]},
                   {"type": "joint", "x": P2[0], "y": P2[1]}])

    def topology(self):
        # links: slider 1 = ctr2D3, slider 2 = ctr2D4; prismatic guide 1
        # (ctr2D1) - slider 1, prismatic slider 1 - slider 2, revolute at P2
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1)]

_placement_params(SSD, (1, 2))


# ================================================================ SDS
def solve_sds(x1, y1, a1, x2, y2, a2, v1, v2):
    """Closed-form travels (xG1, xG2) of SDS (B.197-B.216 solved, linear)."""
    e1, n1 = (ca.cos(a1), ca.sin(a1)), (-ca.sin(a1), ca.cos(a1))
    e2, n2 = (ca.cos(a2), ca.sin(a2)), (-ca.sin(a2), ca.cos(a2))
    # xG1 e1 - xG2 e2 = r
    rx = x2 + v2 * n2[0] - x1 - v1 * n1[0]
    ry = y2 + v2 * n2[1] - y1 - v1 * n1[1]
    det = _cross(e1[0], e1[1], -e2[0], -e2[1])
    return _cross(rx, ry, -e2[0], -e2[1]) / det, _cross(e1[0], e1[1], rx, ry) / det


class SDS(_Linkage):
    """Dyad with prismatic joints as outer joints SDS (seed Anhang B.8,
    Tabellen B.22-B.24, eqs. B.195-B.236).

    Slider 1 slides on the massless guide 1 at P1 (direction phiU1), slider 2
    on guide 2 at P2 (phiU2); they are joined by a revolute joint at P:
    ``PS1 = P1 + xG1 e1``, ``P = PS1 + v1 n1`` (B.197, B.209) and ``PS2 = P2 +
    xG2 e2``, ``P = PS2 + v2 n2`` (B.203, B.215).  Linear in the travels: no
    assembly parameter; the guides must not be parallel.

    Ports (Tabelle B.24): ``ctr2D1`` guide 1 at P1 and ``ctr2D2`` guide 2 at
    P2 (triangles, rigid), ``ctr2D3`` slider 1 plane at P (angle phiU1),
    ``ctr2D4`` slider 2 plane at PS2 (angle phiU2).  Outputs ``xP, yP``.
    Parameters (Tabelle B.23): ``v1 = v2 = 0.1 m``, CoG offsets 0 in SKS1 (at
    PS1) and SKS2 (at PS2), ``mS1 = mS2 = 1 kg``, ``JS1 = JS2 = 0.1 kg m²``.
    """
    v1 = Parameter(0.1, "m", "offset of P from guide 1")
    v2 = Parameter(0.1, "m", "offset of P from guide 2")
    xSS1rel = Parameter(0.0, "m", "centre of gravity of slider 1 in SKS1, x")
    ySS1rel = Parameter(0.0, "m", "centre of gravity of slider 1 in SKS1, y")
    xSS2rel = Parameter(0.0, "m", "centre of gravity of slider 2 in SKS2, x")
    ySS2rel = Parameter(0.0, "m", "centre of gravity of slider 2 in SKS2, y")
    mS1 = Parameter(1.0, "kg", "mass of slider 1", min=0.0)
    JS1 = Parameter(0.1, "kg.m2", "moment of inertia of slider 1 about its centre of gravity", min=0.0)
    mS2 = Parameter(1.0, "kg", "mass of slider 2", min=0.0)
    JS2 = Parameter(0.1, "kg.m2", "moment of inertia of slider 2 about its centre of gravity", min=0.0)

    xG1 = Variable(unit="m", doc="travel of slider 1, P1 -> PS1")
    xG2 = Variable(unit="m", doc="travel of slider 2, P2 -> PS2")
    phiS1 = Variable(unit="rad", doc="angle of slider 1 (= guide 1)")
    phiS2 = Variable(unit="rad", doc="angle of slider 2 (= guide 2)")
    xP = Variable(unit="m", doc="joint point P, x")
    yP = Variable(unit="m", doc="joint point P, y")
    FPx = Variable(unit="N", doc="joint force slider 2 -> slider 1 at P, x")
    FPy = Variable(unit="N", doc="joint force slider 2 -> slider 1 at P, y")
    Fn1 = Variable(unit="N", doc="normal force guide 1 -> slider 1")
    T1 = Variable(unit="N.m", doc="moment guide 1 -> slider 1")
    Fn2 = Variable(unit="N", doc="normal force guide 2 -> slider 2")
    T2 = Variable(unit="N.m", doc="moment guide 2 -> slider 2")
    xSS1 = Variable(unit="m", doc="centre of gravity of slider 1, x")
    ySS1 = Variable(unit="m", doc="centre of gravity of slider 1, y")
    xSS2 = Variable(unit="m", doc="centre of gravity of slider 2, x")
    ySS2 = Variable(unit="m", doc="centre of gravity of slider 2, y")
    xPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, x (for drawing)")
    yPS1 = Variable(unit="m", doc="foot point PS1 of slider 1 on guide 1, y (for drawing)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ctr2D1 = Frame(ground=_GROUND, doc="guide 1 at P1")
        self.ctr2D2 = Frame(ground=_GROUND, doc="guide 2 at P2")
        self.ctr2D3 = Frame(doc="slider 1 plane at P")
        self.ctr2D4 = Frame(doc="slider 2 plane at PS2")

    def _assemble(self, asm):
        vals = self._input_values(asm, [1, 2])
        if vals is None:
            return False
        (x1, y1, a1), (x2, y2, a2) = vals
        asm.check(self, ca.fabs(ca.sin(a2 - a1)) - 1e-9,
                  "guides 1 and 2 not parallel at the start (B.197-B.216)",
                  "Turn a guide (phi10, phi20) or start where the guides cross.")
        xG1, xG2 = solve_sds(x1, y1, a1, x2, y2, a2, self.v1, self.v2)
        PS1 = (x1 + xG1 * ca.cos(a1), y1 + xG1 * ca.sin(a1))
        PS2 = (x2 + xG2 * ca.cos(a2), y2 + xG2 * ca.sin(a2))
        P = (PS1[0] - self.v1 * ca.sin(a1), PS1[1] + self.v1 * ca.cos(a1))
        d1, d2 = _rot(a1, self.xSS1rel, self.ySS1rel), _rot(a2, self.xSS2rel, self.ySS2rel)
        asm.start(self, {"xG1": xG1, "xG2": xG2, "phiS1": a1, "phiS2": a2,
                          "xP": P[0], "yP": P[1],
                          "xSS1": PS1[0] + d1[0], "ySS1": PS1[1] + d1[1],
                          "xSS2": PS2[0] + d2[0], "ySS2": PS2[1] + d2[1],
                          "xPS1": PS1[0], "yPS1": PS1[1]})
        self._set_port(asm, self.ctr2D3, {"x": P[0], "y": P[1], "phi": a1})
        self._set_port(asm, self.ctr2D4, {"x": PS2[0], "y": PS2[1], "phi": a2})
        return True

    def equations(self):
        (x1, y1, a1), C1 = self._place(1)
        (x2, y2, a2), C2 = self._place(2)
        f1, f2, f3, f4 = self.ctr2D1, self.ctr2D2, self.ctr2D3, self.ctr2D4
        e1, n1 = (ca.cos(a1), ca.sin(a1)), (-ca.sin(a1), ca.cos(a1))
        e2, n2 = (ca.cos(a2), ca.sin(a2)), (-ca.sin(a2), ca.cos(a2))
        PS1 = (x1 + self.xG1 * e1[0], y1 + self.xG1 * e1[1])               # B.197, B.198
        PS2 = (x2 + self.xG2 * e2[0], y2 + self.xG2 * e2[1])               # B.203, B.204
        P = (self.xP, self.yP)
        d1, d2 = _rot(a1, self.xSS1rel, self.ySS1rel), _rot(a2, self.xSS2rel, self.ySS2rel)
        g = self._g()
        S1 = _Body(self.mS1, self.JS1, self.xSS1, self.ySS1, self.phiS1, g)
        S2 = _Body(self.mS2, self.JS2, self.xSS2, self.ySS2, self.phiS2, g)
        N1 = (self.Fn1 * n1[0], self.Fn1 * n1[1])
        N2 = (self.Fn2 * n2[0], self.Fn2 * n2[1])
        FP = (self.FPx, self.FPy)
        return [
            self.phiS1 == a1, self.phiS2 == a2,                            # B.195, B.196
            self.xP == PS1[0] + self.v1 * n1[0],                           # B.209
            self.yP == PS1[1] + self.v1 * n1[1],                           # B.210
            self.xP == PS2[0] + self.v2 * n2[0],                           # B.215
            self.yP == PS2[1] + self.v2 * n2[1],                           # B.216
            self.xSS1 == PS1[0] + d1[0], self.ySS1 == PS1[1] + d1[1],
            self.xSS2 == PS2[0] + d2[0], self.ySS2 == PS2[1] + d2[1],
            self.xPS1 == PS1[0], self.yPS1 == PS1[1],
            f3.x == P[0], f3.y == P[1], f3.phi == a1,                      # Tabelle B.24
            f4.x == PS2[0], f4.y == PS2[1], f4.phi == a2,
            # massless guides B.221-B.226
            f1.fx - N1[0] == 0, f1.fy - N1[1] == 0,
            f1.t - self.T1 + _moment(PS1, C1, (-N1[0], -N1[1])) == 0,
            f2.fx - N2[0] == 0, f2.fy - N2[1] == 0,
            f2.t - self.T2 + _moment(PS2, C2, (-N2[0], -N2[1])) == 0,
            # slider 1 B.227-B.229 (moments about PS1)
            N1[0] + FP[0] + f3.fx + S1.F[0] == 0,
            N1[1] + FP[1] + f3.fy + S1.F[1] == 0,
            self.T1 + f3.t + _moment(P, PS1, (FP[0] + f3.fx, FP[1] + f3.fy))
            + S1.moment(PS1) == 0,
            # slider 2 B.230-B.232 (moments about PS2)
            N2[0] - FP[0] + f4.fx + S2.F[0] == 0,
            N2[1] - FP[1] + f4.fy + S2.F[1] == 0,
            self.T2 + f4.t + _moment(P, PS2, (-FP[0], -FP[1])) + S2.moment(PS2) == 0,
        ]


    def shapes(self):
        P1, exact1 = self._port_point(1)
        P2, exact2 = self._port_point(2)
        P, PS1, PS2 = ["xP", "yP"], ["xPS1", "yPS1"], ["ctr2D4.x", "ctr2D4.y"]
        slider1 = {"type": "slider", "x": PS1[0], "y": PS1[1], "phi": "phiS1"}
        slider2 = {"type": "slider", "x": PS2[0], "y": PS2[1], "phi": "phiS2"}
        if exact1:
            slider1["guide"] = [P1, PS1]
        if exact2:
            slider2["guide"] = [P2, PS2]
        return (self._housing_shapes(1, P1, "phiS1") + self._housing_shapes(2, P2, "phiS2")
                + [slider1, slider2,
                   {"type": "link", "points": [PS1, P]},
                   {"type": "link", "points": [PS2, P]},
                   {"type": "joint", "x": P[0], "y": P[1]}])

    def topology(self):
        # links: slider 1 = ctr2D3, slider 2 = ctr2D4; prismatic guide 1
        # (ctr2D1) - slider 1 and guide 2 (ctr2D2) - slider 2, revolute at P
        return self._ground_ports(1, 2) + [
            ("joint", self.ctr2D1, self.ctr2D3, 1),
            ("joint", self.ctr2D2, self.ctr2D4, 1),
            ("joint", self.ctr2D3, self.ctr2D4, 1)]


_placement_params(SDS, (1, 2))
