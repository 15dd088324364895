"""The model diagram drawn from the code (acausal2d.visual.diagram): every
model of models/ drawn with one box per top-level component, one line per
connect, no two boxes overlapping, every unconnected connector marked with
what the flattener does with it; a model that does not compile drawn with
its loose connector and the component its error names; ``diagram``,
``check --diagram`` and ``simulate`` writing it.

The expected counts and fates are read from the model instance by this
test's own walk (children, ``_connections``, each connector's ``ground=`` /
``required``); for two models the fates are checked against the flattened
equations of the compiler (the ports it fixes to ground or closes)."""
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import pytest

from acausal2d import Component, compile_model, start
from acausal2d.compiler.flatten import grounded_ports
from acausal2d.errors import Acausal2dError
from acausal2d.io.loader import load_model, model_names
from acausal2d.library import rotational
from acausal2d.visual.diagram import diagram_html, diagram_svg, structure

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SVG = "{http://www.w3.org/2000/svg}"
KINDS = {"Frame": "frame", "RotationalFlange": "rotational", "TranslationalFlange":
         "translational", "BandPort": "band", "HydraulicPort": "hydraulic", "Real": "signal",
         "NodePort": "frame"}


def all_models():
    jobs = []
    for path in sorted(glob.glob(os.path.join(ROOT, "models", "*.py"))):
        jobs += [(path, name) for name in model_names(path)]
    jobs += [(p, None) for p in sorted(glob.glob(os.path.join(ROOT, "models", "mec2", "*.json")))]
    return jobs


def parse(svg):
    return ET.fromstring(svg)


def classes(el):
    return (el.get("class") or "").split()


def boxes(root):
    return [g for g in root.iter(SVG + "g") if "box" in classes(g)]


def expected_fate(conn):
    """What flatten does with an unconnected connector (its
    _unconnected_equations): ground= fixes it, required= is an error,
    else its flows are zero: a closed hydraulic port, a free one else."""
    if conn.ground is not None:
        return "grounded"
    if conn.required:
        return "error"
    return "closed" if type(conn).kind == "HydraulicPort" else "free"


def loose_connectors(model):
    """{path: connector} of the top-level components' connectors that no
    connect of the model (at any level) joins from outside."""
    joined = {id(c) for scope in model.components() for pair in scope._connections
              for c in pair if c.owner is not scope}
    return {c.path: c for child in model._children.values()
            for c in child._connectors.values() if id(c) not in joined}


def overlap(a, b):
    return a[0] < b[0] + b[2] and b[0] < a[0] + a[2] and a[1] < b[1] + b[3] and \
        b[1] < a[1] + a[3]


def check_drawing(model, svg):
    """The counts, the overlaps, the line colours and the marks."""
    root = parse(svg)
    comps = [g for g in boxes(root) if "external" not in classes(g)]
    assert sorted(g.get("data-path") for g in comps) == sorted(model._children)
    lines = [p for p in root.iter(SVG + "path") if "line" in classes(p)]
    assert len(lines) == len(model._connections)
    for line, (a, b) in zip(lines, model._connections):
        assert {line.get("data-a"), line.get("data-b")} == {a.path, b.path}
        assert line.get("data-domain") == KINDS[type(a).kind]
    rects = [tuple(float(g.get("data-" + k)) for k in "xywh") for g in boxes(root)]
    for i, r in enumerate(rects):
        for s in rects[i + 1:]:
            assert not overlap(r, s), (r, s)
    marks = {g.get("data-path"): g.get("data-fate") for g in root.iter(SVG + "g")
             if "open-port" in classes(g)}
    assert marks == {p: expected_fate(c) for p, c in loose_connectors(model).items()}
    return root


def _proper_cross(p, q, r, s):
    """Straight segments pq and rs cross at a point inside both."""
    def side(a, b, c):
        v = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        return (v > 1e-9) - (v < -1e-9)
    return side(p, q, r) * side(p, q, s) < 0 and side(r, s, p) * side(r, s, q) < 0


def route_crossings(routes):
    """Crossings of the lines' routes (as straight segments between their
    points) with each other."""
    segs = [(i, a, b) for i, r in enumerate(routes) for a, b in zip(r, r[1:])]
    return sum(1 for x in range(len(segs)) for y in range(x + 1, len(segs))
               if segs[x][0] != segs[y][0] and _proper_cross(*segs[x][1:], *segs[y][1:]))


@pytest.mark.parametrize("path,name", all_models(),
                         ids=lambda v: os.path.basename(v) if isinstance(v, str) else str(v))
def test_every_model_is_drawn_whole(path, name):
    model = load_model(path, name)
    check_drawing(model, diagram_svg(model))
    # a model whose connections form a tree (no loop, no double line) is drawn without
    # crossings: a layered drawing of a tree has none (35 of the models)
    import networkx as nx
    from acausal2d.visual.diagram_layout import layout
    st = structure(model)
    graph = nx.Graph()
    graph.add_nodes_from(b.path for b in st.boxes)
    graph.add_edges_from((ln.box_a, ln.box_b) for ln in st.lines)
    if nx.is_forest(graph) and graph.number_of_edges() == len(st.lines):
        assert route_crossings(layout(st).routes) == 0


def test_fates_agree_with_the_flattened_equations():
    """The compiler's own record: the ports it fixed to ground, and those it
    closed with zero flows ("(unconnected)" equations), are the ports
    drawn grounded, and free or closed."""
    kinds = set()
    for path, name in [("models/compressor.py", None), ("models/hydraulic_drum_drive.py", None)]:
        model = load_model(os.path.join(ROOT, path), name)
        cm = compile_model(model)
        root = parse(diagram_svg(model))
        marks = {g.get("data-path"): g.get("data-fate") for g in root.iter(SVG + "g")
                 if "open-port" in classes(g)}
        eqs = cm.system.flat_equations
        closed = {e.origin[:-len(" (unconnected)")] for e in eqs
                  if e.origin.endswith(" (unconnected)")}
        grounded = set(grounded_ports(eqs))
        top = set(model._children)
        def on_top(paths):
            return {p for p in paths if p.split(".")[0] in top and p.count(".") == 1}
        assert {p for p, f in marks.items() if f == "grounded"} == on_top(grounded)
        assert {p for p, f in marks.items() if f in ("free", "closed")} == on_top(closed)
        kinds |= {"grounded"} if on_top(grounded) else set()
        kinds |= {"closed"} if on_top(closed) else set()
    assert kinds == {"grounded", "closed"}      # both occur in these two models


class Drive(Component):
    """A motor on an inertia braked by a torque whose input is forgotten."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.motor = rotational.AsyncMotor(J=0.01, T_k=40.0, s_k=0.2)
        self.load = rotational.Inertia(J=0.05, phi=start(0.0, fixed=True))
        self.brake = rotational.Torque()
        self.connect(self.motor.flange, self.load.flange_a)
        self.connect(self.load.flange_b, self.brake.flange)


def test_a_model_that_fails_to_compile_shows_its_loose_connector():
    model = Drive()
    with pytest.raises(Acausal2dError) as info:
        compile_model(model)
    assert "brake.tau_in" in str(info.value)
    root = check_drawing(model, diagram_svg(model, info.value))
    loose = [g for g in root.iter(SVG + "g") if "open-port" in classes(g)
             and g.get("data-fate") == "error"]
    assert [g.get("data-path") for g in loose] == ["brake.tau_in"]
    named = [g.get("data-path") for g in boxes(root) if "named" in classes(g)]
    assert named == ["brake"]
    text = " ".join(t.text or "" for t in root.iter(SVG + "text"))
    assert "does not compile" in text and "not connected" in text


def test_free_ports_are_marked_and_the_flow_runs_left_to_right():
    """clutch_motor: motor left of the clutch, the clutch left of the load
    inertia (power from the source to the load); the signal line ends in
    an arrow."""
    model = load_model(os.path.join(ROOT, "models", "clutch_motor.py"), "ClutchMotor")
    root = parse(diagram_svg(model))
    x = {g.get("data-path"): float(g.get("data-x")) for g in boxes(root)}
    assert x["motor"] < x["clutch"] < x["load_inertia"] < x["brake"]
    assert x["engage"] < x["clutch"]
    signal = [p for p in root.iter(SVG + "path") if p.get("data-domain") == "signal"]
    assert len(signal) == 2 and all(p.get("marker-end") == "url(#arrow)" for p in signal)
    params = [t.text for t in root.iter(SVG + "text") if "param" in classes(t)]
    assert "fn_max = 1500 N" in params and "J = 0.05 kg.m2" in params


def test_submodel_opens_in_the_html_page():
    model = load_model(os.path.join(ROOT, "models", "clutch_motor.py"),
                       "ClutchMotorConstantLoad")
    root = parse(diagram_svg(model))
    assert [g.get("data-path") for g in boxes(root) if "submodel" in classes(g)] == ["drive"]
    page = diagram_html(model)
    levels = re.findall(r'<section class="level" data-level="([^"]*)"', page)
    assert levels == ["", "drive"]
    inner = structure(model, path="drive")
    assert sorted(b.path for b in inner.components) == sorted(model.drive._children)
    assert len(inner.lines) == len(model.drive._connections)


def test_notebook_and_compiled_model_show_it():
    model = load_model(os.path.join(ROOT, "models", "pendulum.py"))
    assert model._repr_svg_().startswith("<svg")
    cm = compile_model(model)
    view = cm.diagram()
    assert view._repr_svg_() == cm._repr_svg_()
    # the compiled copy holds the world the flattener added
    assert len(boxes(parse(view.svg))) >= len(model._children)


def run_cli(*args, cwd=ROOT):
    env = dict(os.environ, PYTHONPATH=ROOT)
    return subprocess.run([sys.executable, "-m", "acausal2d"] + list(args), cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=600)


def test_cli_diagram_and_check_write_it(tmp_path):
    out = tmp_path / "d.svg"
    r = run_cli("diagram", "models/clutch_motor.py", "--model", "ClutchMotor", "--out", str(out))
    assert r.returncode == 0, r.stderr
    model = load_model(os.path.join(ROOT, "models", "clutch_motor.py"), "ClutchMotor")
    check_drawing(model, out.read_text())
    out2 = tmp_path / "check" / "diagram.svg"
    out2.parent.mkdir()
    r = run_cli("check", os.path.join(ROOT, "models", "pendulum.py"), "--diagram",
                cwd=out2.parent)
    assert r.returncode == 0, r.stderr
    assert "structural index" in r.stdout
    r = run_cli("check", "models/pendulum.py", "--diagram", str(tmp_path / "d.py"))
    assert r.returncode == 2 and ".svg or .html" in r.stderr and not (tmp_path / "d.py").exists()
    assert "structural index" not in r.stdout           # refused before the model is compiled
    check_drawing(load_model(os.path.join(ROOT, "models", "pendulum.py")), out2.read_text())


def test_check_of_a_broken_model_still_writes_the_diagram(tmp_path):
    src = tmp_path / "broken.py"
    src.write_text("from acausal2d import Component, start\n"
                   "from acausal2d.library import rotational\n\n\n"
                   "class Broken(Component):\n"
                   "    def __init__(self, **kw):\n"
                   "        super().__init__(**kw)\n"
                   "        self.load = rotational.Inertia(J=0.05, phi=start(0.0, fixed=True))\n"
                   "        self.brake = rotational.Torque()\n"
                   "        self.connect(self.load.flange_b, self.brake.flange)\n")
    out = tmp_path / "diagram.svg"
    r = run_cli("check", str(src), "--diagram", str(out))
    assert r.returncode == 2 and "brake.tau_in" in r.stderr, r.stderr
    root = parse(out.read_text())
    marks = {g.get("data-path"): g.get("data-fate") for g in root.iter(SVG + "g")
             if "open-port" in classes(g)}
    assert marks["brake.tau_in"] == "error" and marks["load.flange_a"] == "free"
    assert [g.get("data-path") for g in boxes(root) if "named" in classes(g)] == ["brake"]


def test_simulate_writes_the_diagram_with_its_outputs(tmp_path):
    out = tmp_path / "out"
    r = run_cli("simulate", "models/pendulum.py", "--out", str(out), "--native", "off",
                "--intervals", "20")
    assert r.returncode == 0, r.stderr
    manifest = json.loads((out / "acausal2d-run.json").read_text())
    assert "diagram.svg" in manifest["files"]
    assert "diagram.svg" in r.stdout
    root = parse((out / "diagram.svg").read_text())
    model = load_model(os.path.join(ROOT, "models", "pendulum.py"))
    names = {g.get("data-path") for g in boxes(root)}
    assert set(model._children) <= names


def test_gallery_entry_shows_the_diagram(tmp_path):
    """The docs' gallery runner writes the model's diagram beside its
    figures and the entry's page embeds it (one entry, as the build makes
    each)."""
    sys.path.insert(0, os.path.join(ROOT, "docs", "_ext"))
    try:
        import gallery
        import gallery_run
    finally:
        sys.path.pop(0)
    path = os.path.join(ROOT, "models", "pendulum.py")
    entry = gallery_run.run_model(path, "Pendulum", str(tmp_path), str(tmp_path / "anim"))
    svg = (tmp_path / entry["diagram"]).read_text()
    check_drawing(load_model(path, "Pendulum"), svg)
    text = gallery._entry_text(path, "Pendulum", entry)
    assert "![diagram of Pendulum](%s)" % entry["diagram"] in text


class Inner(Component):
    """A sub-model with a connector of its own (connected inside)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        from acausal2d import RotationalFlange
        self.shaft = RotationalFlange()
        self.disc = rotational.Inertia(J=0.2)
        self.connect(self.shaft, self.disc.flange_a)


class Outer(Component):
    """A connect at the top that reaches into the sub-model's component."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.inner = Inner()
        self.spring = rotational.Spring(c=100.0)
        self.connect(self.spring.flange_b, self.inner.disc.flange_b)
        self.connect(self.spring.flange_a, self.inner.shaft)


def test_a_connect_into_a_submodel_ends_at_its_box():
    model = Outer()
    st = structure(model)
    assert [(ln.box_b, ln.port_b) for ln in st.lines] == [("inner", "disc.flange_b"),
                                                        ("inner", "shaft")]
    root = check_drawing(model, diagram_svg(model))
    inner = [g for g in boxes(root) if g.get("data-path") == "inner"][0]
    assert "submodel" in classes(inner)
    level = structure(model, path="inner")
    # the disc's flange_b is connected from the level above: no mark there
    assert level.box("disc").ports["flange_b"].fate is None
    assert level.box("disc").ports["flange_b"].outside
    svg = parse(diagram_svg(model, path="inner"))
    assert [g.get("data-path") for g in svg.iter(SVG + "g") if "outside-port" in classes(g)] \
        == ["inner.disc.flange_b"]
    assert level.box("shaft").external and len(level.lines) == 1


def test_drawing_leaves_the_model_as_it_was():
    """Drawing reads the model; every component's and connector's own
    attributes are the same afterwards (no world added, no side stored)."""
    model = load_model(os.path.join(ROOT, "models", "hydraulic_drum_drive.py"))
    def picture():
        return [(c.path, sorted(vars(c)), repr(c._param_values), repr(c._given),
                 repr(c._derived), len(c._connections), sorted(c._children),
                 [(n, repr(vars(k))) for n, k in c._connectors.items()])
                for c in model.components()]
    before = picture()
    diagram_html(model)
    assert picture() == before


def test_an_element_and_an_empty_model_are_drawn():
    """A notebook shows a single element (its connectors as the border's
    ports) and an empty model (its name only)."""
    root = parse(rotational.Inertia(J=1.0)._repr_svg_())
    assert sorted(g.get("data-path") for g in boxes(root)) == ["flange_a", "flange_b"]
    root = parse(Component()._repr_svg_())
    assert boxes(root) == [] and root.get("data-model") == "Component"


class Stray(Component):
    """Connects a flange of a component that is not part of it."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.disc = rotational.Inertia(J=1.0)
        other = rotational.Inertia(J=2.0)
        self.connect(self.disc.flange_a, other.flange_a)


def test_a_connect_to_a_stray_component_is_drawn_as_its_error():
    model = Stray()
    with pytest.raises(Acausal2dError) as info:
        compile_model(model)
    root = parse(diagram_svg(model, info.value))
    assert [g.get("data-path") for g in boxes(root)] == ["disc"]
    assert not [p for p in root.iter(SVG + "path") if "line" in classes(p)]
    text = " ".join(t.text or "" for t in root.iter(SVG + "text"))
    assert "not part of it" in text


def test_drawing_a_diagram_imports_no_graph_library():
    """simulate writes diagram.svg with every run: its layout is pure Python
    (networkx's import alone took longer than the drawing)."""
    code = ("import sys, acausal2d; from acausal2d.visual.diagram import write_diagram; "
            "write_diagram(acausal2d.load_model(sys.argv[1], 'ClutchMotor'), sys.argv[2]); "
            "print('networkx' in sys.modules)")
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "d.svg")
        proc = subprocess.run([sys.executable, "-c", code, os.path.join(ROOT, "models", "clutch_motor.py"),
                               out], capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.split() == ["False"]
        assert os.path.getsize(out) > 0
