"""The structure of a model as a diagram: what is drawn, taken from the
model instance without compiling it.

:func:`structure` reads one level of a model: a :class:`Box` per
sub-component (its kind, name, main parameters with units and its
connectors), a :class:`Line` per ``connect`` of that level, the model's own
connectors as boundary ports, and for every connector left unconnected what
the flattener does with it (:func:`fate`): ``grounded`` (declared with
``ground=``: fixed to ground, Ebert (2015), Tabelle 4.1), ``closed`` (a
hydraulic port: no flow), ``free`` (a mechanical connector: no force or
torque; a band port or a signal output: nothing to close) or ``error`` (a
connector that must be connected, e.g. a signal input).  A model that does
not compile is drawn the same way; the components an error message names
are marked (:func:`named_in`).

:mod:`acausal2d.visual.diagram_layout` places the boxes and
:mod:`acausal2d.visual.diagram_svg` draws them; :func:`diagram_svg` and
:func:`diagram_html` are the entry points (``acausal2d diagram``,
``CompiledModel.diagram()``, ``check --diagram``, ``simulate``'s
``diagram.svg`` and the explore page).
"""
import os
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ..errors import Acausal2dError, ModelDefinitionError
from ..io.files import write_text
from .diagram_layout import layout
from .diagram_svg import HEADLINE, render_html, render_svg

if TYPE_CHECKING:
    from ..language.dsl import Component

DOMAINS = {"Frame": "frame", "RotationalFlange": "rotational",
           "TranslationalFlange": "translational", "BandPort": "band",
           "HydraulicPort": "hydraulic", "Real": "signal", "NodePort": "frame"}
"""The domain of each connector kind (the colour of its lines)."""

FLOWS = {"frame": ("fx", "fy", "t"), "rotational": ("tau",), "translational": ("f",),
         "hydraulic": ("q",), "signal": ("u",), "band": ()}
"""The variables a line shows during playback (the flow through it; a
signal's value)."""

MAX_PARAMETERS = 3
"""Parameters written in a box (those the model set first)."""


@dataclass
class Port:
    """A connector of a box: ``name`` relative to the box (``flange_a``, or
    ``motor.flange`` for a deeper connector connected at this level),
    ``path`` in the model, ``domain``, ``signal`` (``input``/``output`` or
    None), ``fate`` when unconnected (see the module docstring; None when
    connected), ``side`` (``left``/``right``, set by the layout) and
    ``mirror`` (its lines leave to both sides: it is drawn on both) and
    ``outside`` (connected by a level above the one drawn)."""
    name: str
    path: str
    domain: str
    signal: str | None = None
    fate: str | None = None
    side: str = "right"
    mirror: bool = False
    outside: bool = False


@dataclass
class Box:
    """A component drawn as one box: ``path`` (its instance name in the
    model), ``cls`` (class name), ``kind`` (the symbol), ``params`` (lines
    ``name = value unit``), ``ports`` by name, ``submodel`` (it holds
    components of its own: its diagram opens from it), ``named`` (an error
    message names it) and ``external`` (a boundary port of the model
    itself, not a component)."""
    path: str
    name: str
    cls: str
    kind: str
    params: list = field(default_factory=list)
    ports: dict = field(default_factory=dict)
    submodel: bool = False
    named: bool = False
    external: bool = False


@dataclass
class Line:
    """One ``connect(a, b)``: the connector paths, the boxes they belong
    to, their port names, the domain, and for a signal the direction
    (``a`` is the source)."""
    a: str
    b: str
    box_a: str
    box_b: str
    port_a: str
    port_b: str
    domain: str

    @property
    def flows(self):
        """The full names of the variables shown on the line (of connector
        ``a``)."""
        return [self.a + "." + v for v in FLOWS.get(self.domain, ())]


@dataclass
class Structure:
    """One level of a model: its ``name`` and class, ``path`` ('' for the
    model itself), boxes (components first, then the model's own
    connectors as external boxes), lines and the error it failed with."""
    name: str
    path: str
    boxes: list
    lines: list
    error: str | None = None

    def box(self, path):
        """The box of ``path``."""
        for b in self.boxes:
            if b.path == path:
                return b
        raise KeyError(path)

    @property
    def components(self):
        """The boxes of components (not the model's own connectors)."""
        return [b for b in self.boxes if not b.external]


def domain(conn):
    """The domain of connector ``conn`` (``other`` for an unknown kind)."""
    return DOMAINS.get(type(conn).kind, "other")


def fate(conn):
    """What the flattener does with ``conn`` when nothing is connected to
    it: ``grounded``, ``error``, ``closed`` or ``free`` (module docstring)."""
    if conn.ground is not None:
        return "grounded"
    if conn.required:
        return "error"
    return "closed" if domain(conn) == "hydraulic" else "free"


_KINDS = [
    ("oneway", ("OneWayClutch",)), ("clutch", ("Clutch",)),
    ("brake", ("Brake", "BearingFriction", "SupportFriction")),
    ("planetary", ("IdealPlanetary",)), ("gear", ("IdealGear",)),
    ("drum", ("Drum", "CurvedDrum")),
    ("pulley", ("Pulley", "GuideContour", "CurvedPulley")),
    ("rope", ("RopeDrive",)), ("span", ("Belt", "SpringBelt", "Band", "NozzleBelt")),
    ("pump", ("Pump",)), ("motor", ("Motor", "AsyncMotor")),
    ("valve", ("ReliefValve", "Throttle", "Orifice")), ("volume", ("Volume", "GasCylinder")),
    ("springdamper", ("SpringDamper", "LineSpringDamper")),
    ("spring", ("Spring", "NodeSpring")), ("damper", ("Damper",)),
    ("inertia", ("Inertia",)), ("mass", ("Mass", "MassWithStopAndFriction")),
    ("world", ("PlanarWorld",)), ("fixed", ("Fixed",)),
    ("joint", ("Revolute", "Prismatic", "IdealRolling", "Node", "CamFollower")),
    ("body", ("Body", "BodyShape", "FixedTranslation", "FixedRotation", "Link", "Carriage",
              "Hook")),
    ("source", ("Torque", "ConstantTorque", "Speed", "Position", "Force", "PressureSource",
                "WorldForce", "WorldTorque", "RelativeForce", "TorqueSource", "ForceSource",
                "Preset", "AngleDrive", "LengthDrive", "TimeFunction", "Constant", "Sine",
                "Ramp", "Step", "Pulse", "NodeForce")),
]
_BY_NAME = {name: kind for kind, names in _KINDS for name in names}
_BY_MODULE = [("linkage", "vdi"), ("synthesis", "vdi"), ("sensors", "sensor"),
              ("blocks", "block"), ("controllers", "block"), ("signals", "block")]


def kind_of(comp):
    """The symbol of component ``comp``: one of :data:`KINDS`."""
    cls = type(comp)
    for klass in cls.__mro__:
        if klass.__name__ in _BY_NAME and klass.__module__.split(".")[0] in ("acausal2d",
                                                                              "library"):
            return _BY_NAME[klass.__name__]
    if "Sensor" in cls.__name__ or cls.__name__ in ("Power", "CutForce", "CutTorque",
                                                      "Distance"):
        return "sensor"
    for klass in cls.__mro__:
        for part, kind in _BY_MODULE:
            if klass.__module__.split(".")[0] in ("acausal2d", "library") and \
                    part in klass.__module__.split("."):
                return kind
    return "submodel" if comp._children else "element"


KINDS = sorted({k for k, _ in _KINDS} | {"vdi", "sensor", "block", "submodel", "element"})
"""The symbols a box may carry."""


def _value_text(value):
    if isinstance(value, (tuple, list)):
        return "(%s)" % ", ".join("%.4g" % v for v in value)
    try:
        return "%.4g" % value
    except TypeError:
        return str(value)


def parameter_lines(comp, limit=MAX_PARAMETERS):
    """The main parameters of ``comp`` as ``name = value unit`` lines: those
    the model set first (in declaration order), then the declared defaults,
    at most ``limit``."""
    names = list(comp._param_values)
    ordered = [n for n in names if comp.is_given(n)] + \
        [n for n in names if not comp.is_given(n)]
    lines = []
    for name in ordered[:limit]:
        unit = comp.parameter_declaration(name).unit
        unit = "" if unit in ("1", "-") else unit
        try:
            value = comp.parameter_value(name)
        except Exception:        # noqa: BLE001 - a value the model cannot give: not drawn
            continue
        lines.append(("%s = %s %s" % (name, _value_text(value), unit)).rstrip())
    return lines


def _top(comp, scope):
    """The child of ``scope`` that holds ``comp`` (``scope`` itself for its
    own connectors)."""
    node = comp
    while node._parent is not None and node._parent is not scope:
        node = node._parent
    return node if node._parent is scope else scope


def _relative(path, base):
    return path[len(base) + 1:] if base and path.startswith(base + ".") else path


def connected_paths(model):
    """The paths of the connectors a ``connect`` of some level of ``model``
    joins from outside their component (those the flattener leaves
    alone)."""
    return {c.path for scope in model.components() for pair in scope._connections
            for c in pair if c.owner is not scope}


def _box(comp, scope, named, connected):
    ports = {}
    for name, conn in comp._connectors.items():
        ports[name] = Port(name, conn.path, domain(conn), conn.signal,
                           None if conn.path in connected else fate(conn))
    return Box(_relative(comp.path, scope.path), comp._name, type(comp).__name__,
               kind_of(comp), parameter_lines(comp), ports, bool(comp._children),
               comp.path in named)


def _external(conn, scope):
    return Box(conn._name, conn._name, type(conn).__name__, "port",
               ports={conn._name: Port(conn._name, conn.path, domain(conn), conn.signal)},
               external=True)


def _endpoint(conn, scope, boxes):
    """(box path, port name) of a connector connected in ``scope``; a
    deeper connector becomes a port of its top-level box."""
    if conn.owner is scope:
        return conn._name, conn._name
    top = _top(conn.owner, scope)
    box = boxes[_relative(top.path, scope.path)]
    name = _relative(conn.path, top.path)
    port = box.ports.get(name)
    if port is None:
        port = box.ports[name] = Port(name, conn.path, domain(conn), conn.signal)
    port.fate = None
    return box.path, name



def named_in(message, model):
    """The paths of the components of ``model`` that the headline of the
    error ``message`` (its first :data:`HEADLINE` lines) names, as
    ``'path'``, ``path.member`` or ``path (Class)``."""
    if not message:
        return set()
    message = "\n".join(message.splitlines()[:HEADLINE])
    found = set()
    for comp in model.components():
        path = comp.path
        if path and re.search(r"(?<![\w.])%s(?![\w\[])" % re.escape(path), message):
            found.add(path)
    return found


def _scope(model, path):
    """The sub-model at ``path`` ('' for the model itself)."""
    scope = model
    for part in [p for p in path.split(".") if p]:
        scope = scope._children[part] if part in scope._children else _child(scope, part)
    return scope


def _inside(conn, scope):
    """True if ``conn`` belongs to ``scope`` or to a component inside it."""
    node = conn.owner
    while node is not None and node is not scope:
        node = node._parent
    return node is scope


def _lines(scope, boxes):
    """A :class:`Line` per connect of ``scope``, a signal's from its source."""
    lines = []
    for a, b in scope._connections:
        if not (_inside(a, scope) and _inside(b, scope)):
            continue                    # connects what is not part of it: the error says so
        (ba, pa), (bb, pb) = _endpoint(a, scope, boxes), _endpoint(b, scope, boxes)
        if a.signal is not None and _is_sink(a, scope):
            (a, ba, pa), (b, bb, pb) = (b, bb, pb), (a, ba, pa)
        lines.append(Line(a.path, b.path, ba, bb, pa, pb, domain(a)))
    return lines


def _mark_outside(boxes, lines):
    """Ports connected by a level above: no fate and no line here."""
    ends = {(ln.box_a, ln.port_a) for ln in lines} | {(ln.box_b, ln.port_b) for ln in lines}
    for b in boxes:
        for p in b.ports.values():
            p.outside = p.fate is None and not b.external and (b.path, p.name) not in ends


def structure(model, error=None, path=""):
    """The :class:`Structure` of one level of ``model`` (a Component
    instance): of the model itself, or with ``path`` of its sub-model there.
    ``error``: the message the model failed to compile with; the components
    it names are marked, and its loose connectors keep their fate."""
    scope = _scope(model, path)
    named = named_in(str(error) if error else "", model)
    connected = connected_paths(model)
    boxes = {}
    for child in scope._children.values():
        b = _box(child, scope, named, connected)
        boxes[b.path] = b
    for conn in scope._connectors.values():
        boxes.setdefault(conn._name, _external(conn, scope))
    lines = _lines(scope, boxes)
    _mark_outside(boxes.values(), lines)
    name = type(scope).__name__ if not path else "%s (%s)" % (path, type(scope).__name__)
    return Structure(name, path, list(boxes.values()), lines, str(error) if error else None)


def _child(scope, part):
    raise ModelDefinitionError("%s has no sub-model %r; its sub-models: %s" % (
        scope.describe(), part, ", ".join(n for n, c in scope._children.items()
                                           if c._children) or "none"))


def _is_sink(conn, scope):
    """True if a signal connector takes the value at this level: an input
    of a sub-component, or the model's own output."""
    inside = conn.owner is not scope
    return (conn.signal == "input") == inside


def submodel_paths(model, path=""):
    """The paths of the sub-models below ``path`` (each a diagram of its
    own), depth first."""
    scope = _scope(model, path)
    out = []
    for name, child in scope._children.items():
        if child._children:
            sub = name if not path else path + "." + name
            out.append(sub)
            out.extend(submodel_paths(model, sub))
    return out


def diagram_svg(model: "Component", error: object = None, path: str = "") -> str:
    """The diagram of ``model`` (a Component instance; with ``path`` of its
    sub-model there) as SVG text; ``error`` is the message it failed to
    compile with."""
    st = structure(model, error, path)
    return render_svg(st, layout(st))


def diagram_html(model, error=None):
    """The diagram of ``model`` and of each of its sub-models as one HTML
    page: a sub-model's box opens its own diagram, one level at a time, and
    a link leads back up."""
    levels = [("", diagram_svg(model, error))]
    levels += [(p, diagram_svg(model, error, p)) for p in submodel_paths(model)]
    return render_html(type(model).__name__, levels)


def check_diagram_path(path):
    """Raise an error naming ``path`` unless it ends in .svg or .html (a
    diagram never overwrites a model file or a result)."""
    if not str(path).lower().endswith((".svg", ".html", ".htm")):
        raise Acausal2dError("the diagram is written as .svg or .html, not to %s; name a file "
                             "ending in .svg or .html" % path)


def write_diagram(model, path, error=None):
    """Write the diagram of ``model`` to ``path``: an HTML page (sub-models
    open in it) if it ends in ``.html``, else SVG; written whole or not at
    all (a temporary file moved in).  Returns ``path``."""
    check_diagram_path(path)
    folder = os.path.dirname(os.fspath(path))
    if folder:
        os.makedirs(folder, exist_ok=True)
    text = diagram_html(model, error) if str(path).lower().endswith((".html", ".htm")) \
        else diagram_svg(model, error)
    return write_text(path, text)


class DiagramView:
    """A model's diagram as a notebook shows it (``_repr_svg_``); ``svg``
    is its text, ``save(path)`` writes it."""

    def __init__(self, model: "Component", error: object = None) -> None:
        self.model = model
        self.error = error
        self.svg: str = diagram_svg(model, error)

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, path):
        """Write the diagram to ``path`` (SVG, or HTML for ``*.html``)."""
        return write_diagram(self.model, path, self.error)

    def __repr__(self):
        return "<diagram of %s: %d boxes>" % (type(self.model).__name__,
                                              self.svg.count('class="box'))
