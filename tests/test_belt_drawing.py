"""The belt-drive elements draw themselves in the animation scene: pulleys
and drums at their axes (turned by their angle), belt spans between their
contact points, curved pulleys with their contour, ground symbols at fixed
pulleys (library/belt.py, library/belt_curved.py, library/crane.py)."""
import importlib.util
import math
import pathlib

import numpy as np
import pytest

from acausal2d import compile_model
from acausal2d.visual.animation import render_html, validate_scene
from acausal2d.library.belt import Drum, Pulley
from acausal2d.library.belt.curved import CurvedPulley
from acausal2d.visual.scene import build_scene
from conftest import assert_copied

MODELS = pathlib.Path(__file__).resolve().parent.parent / "models"


def _load(name):
    spec = importlib.util.spec_from_file_location("belt_drawing_" + name, MODELS / (name + ".py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _run(model, stop_time, intervals=20, **kw):
    res = compile_model(model).simulate(stop_time=stop_time,
                                        output_times=np.linspace(0.0, stop_time, intervals + 1),
                                        **kw)
    scene = build_scene(res)
    validate_scene(scene)
    html = render_html(scene)          # the page builds from the scene
    assert "acausal2d-data" in html
    return model, res, scene


def _by_type(scene, kind):
    return [s for s in scene["shapes"] if s["type"] == kind]


def _sig(scene, value):
    """Values of a shape field over the frames (constant or signal)."""
    if isinstance(value, str):
        return np.asarray(scene["signals"][value], dtype=float)
    return np.full(len(scene["time"]), float(value))


def _check_pulleys(model, res, scene, classes=(Pulley, Drum, CurvedPulley)):
    """Every wheel of the model is drawn once at its axis with its radius and
    absolute angle; returns {path: shape}."""
    wheels = {c.path: c for c in model.components() if isinstance(c, classes)}
    shapes = {}
    for sh in _by_type(scene, "pulley"):
        path = sh["x"].rsplit(".ctr2D1.x", 1)[0]
        assert path in wheels and path not in shapes
        shapes[path] = sh
    assert set(shapes) == set(wheels)
    for path, sh in shapes.items():
        assert sh["y"] == path + ".ctr2D1.y" and sh["phi"] == path + ".phi"
        assert_copied(_sig(scene, sh["x"]), res[path + ".ctr2D1.x"])
        assert_copied(_sig(scene, sh["y"]), res[path + ".ctr2D1.y"])
        assert_copied(_sig(scene, sh["phi"]), res[path + ".phi"])
        comp = wheels[path]
        if "contour" not in sh:
            assert_copied(_sig(scene, sh["r"]), float(comp.parameter_value("r")))
    return shapes


def _check_belts(scene, spans, contacts):
    """``spans``: {span path: (end 1, end 2)} of the expected belt shapes;
    the end points are the span's frames and coincide with ``contacts``
    (world points named by result signals) at every frame."""
    belts = _by_type(scene, "belt")
    assert len(belts) == len(spans)
    for sh in belts:
        span = sh["points"][0][0].rsplit(".ctr2D1.x", 1)[0]
        assert span in spans
        assert sh["points"] == [[span + ".ctr2D1.x", span + ".ctr2D1.y"],
                                [span + ".ctr2D2.x", span + ".ctr2D2.y"]]
        for (px, py), other in zip(sh["points"], spans[span]):
            if other is None:
                continue
            np.testing.assert_allclose(_sig(scene, px), contacts[other + ".x"], atol=1e-9)
            np.testing.assert_allclose(_sig(scene, py), contacts[other + ".y"], atol=1e-9)


def _grounds_at(scene, names):
    pts = {(s["x"], s["y"]) for s in _by_type(scene, "ground")}
    return {n for n in names if (n + ".ctr2D1.x", n + ".ctr2D1.y") in pts}


def test_pulley_block_drawing():
    mod = _load("pulley_block")
    model, res, scene = _run(mod.PulleyBlock(), 1.0)
    shapes = _check_pulleys(model, res, scene)
    assert len(shapes) == 4
    # fixed upper block at y = 0, lower block moves with the load
    assert np.allclose(res["U1.ctr2D1.y"], 0.0) and np.allclose(res["U3.ctr2D1.y"], 0.0)
    assert res["L2.ctr2D1.y"][-1] > res["L2.ctr2D1.y"][0]          # lifted
    for name, r in mod.RADII.items():
        assert np.allclose(_sig(scene, shapes[name]["r"]), r)
    # ground symbols only at the pulleys fixed in the ground
    assert _grounds_at(scene, mod.PULLEYS) == {"U1", "U3"}
    contacts = {n: res[n] for n in res.names}
    spans = {"rope1": ("pull.frame", "U1.ctrK1"), "rope2": ("U1.ctrK2", "L2.ctrK1"),
             "rope3": ("L2.ctrK2", "U3.ctrK1"), "rope4": ("U3.ctrK2", "L4.ctrK1"),
             "rope5": ("L4.ctrK2", "anchor.frame")}
    _check_belts(scene, spans, contacts)
    # the spans are tangent: contact point at distance r from the axis,
    # span direction perpendicular to the radius
    for span, (a, b) in spans.items():
        for end, (node, sign) in enumerate(((a, 1), (b, -1))):
            wheel = node.split(".")[0]
            if wheel not in mod.RADII:
                continue
            dx = res[node + ".x"] - res[wheel + ".ctr2D1.x"]
            dy = res[node + ".y"] - res[wheel + ".ctr2D1.y"]
            np.testing.assert_allclose(np.hypot(dx, dy), mod.RADII[wheel], rtol=1e-9)
            g = res[span + ".gamma"]
            np.testing.assert_allclose(dx * np.cos(g) + dy * np.sin(g), 0.0, atol=1e-9)
    # the rope end is drawn
    assert {"type": "joint", "x": "pull.frame.x", "y": "pull.frame.y"} in scene["shapes"]


def test_noncircular_belt_drive_drawing():
    mod = _load("noncircular_belt_drive")
    model, res, scene = _run(mod.NonCircularBeltDrive(), 0.1)
    shapes = _check_pulleys(model, res, scene)
    assert set(shapes) == {"small", "large"}
    assert _grounds_at(scene, shapes) == {"small", "large"}
    for name, contour in (("small", model.des.contour1), ("large", model.des.contour2)):
        sh = shapes[name]
        pts = np.asarray(sh["contour"], dtype=float)
        assert pts.shape[0] >= 100 and pts.shape[1] == 2
        rad = np.hypot(pts[:, 0], pts[:, 1])
        assert sh["r"] == pytest.approx(rad.max())
        # the sampled outline is the contour: its perimeter
        closed = np.vstack([pts, pts[:1]])
        per = np.sum(np.hypot(*np.diff(closed, axis=0).T))
        assert per == pytest.approx(contour.perimeter, rel=1e-3)
    np.testing.assert_allclose(_sig(scene, shapes["large"]["x"]), 0.8)
    # the belt ends are the contact points on the contours: in the pulley
    # frame, the contact point lies on the sampled outline
    contacts = {n: res[n] for n in res.names}
    _check_belts(scene, {"upper": ("large.ctrK2", "small.ctrK1"),
                         "lower": ("small.ctrK2", "large.ctrK1")}, contacts)
    for name in ("small", "large"):
        pts = np.asarray(shapes[name]["contour"], dtype=float)
        for k in ("ctrK1", "ctrK2"):
            phi = res[name + ".phi"]
            dx = res["%s.%s.x" % (name, k)] - res[name + ".ctr2D1.x"]
            dy = res["%s.%s.y" % (name, k)] - res[name + ".ctr2D1.y"]
            lx = np.cos(phi) * dx + np.sin(phi) * dy
            ly = -np.sin(phi) * dx + np.cos(phi) * dy
            d = np.min(np.hypot(pts[:, 0][None, :] - lx[:, None],
                                pts[:, 1][None, :] - ly[:, None]), axis=1)
            assert np.max(d) < 0.01          # within the sampling spacing


def test_cable_crane_drawing():
    mod = _load("cable_crane")
    model, res, scene = _run(mod.CableCrane(), 0.5, intervals=5)
    shapes = _check_pulleys(model, res, scene)
    pulleys = set(mod.MAST_PULLEYS) | set(mod.CARRIAGE_PULLEYS)
    assert set(shapes) == pulleys | set(mod.DRUMS)
    assert len(_by_type(scene, "pulley")) == 9 + 2
    for name in mod.DRUMS:
        assert np.allclose(_sig(scene, shapes[name]["r"]), mod.R_DRUM)
    # mast pulleys and drums are fixed in the ground, carriage pulleys not
    assert _grounds_at(scene, shapes) == set(mod.MAST_PULLEYS) | set(mod.DRUMS)
    for name in mod.CARRIAGE_PULLEYS:
        np.testing.assert_allclose(res[name + ".ctr2D1.x"], res["carriage.%s.x" % name])
    n_spans = sum(len(nodes) - 1 for nodes in mod.ROPES.values())
    assert n_spans == 12
    belts = _by_type(scene, "belt")
    assert len(belts) == n_spans
    # hook (load) and carriage are drawn
    assert any(s["type"] == "body" and s["x"] == "hook.x" for s in scene["shapes"])
    assert any(s["type"] == "link" and s["points"][0][0].startswith("carriage.")
               for s in scene["shapes"])


def test_compressor_drawing():
    mod = _load("compressor")
    model, res, scene = _run(mod.Compressor(), 0.2)
    shapes = _check_pulleys(model, res, scene)
    assert set(shapes) == {"drive", "driven", "tens"}
    assert _grounds_at(scene, shapes) == {"drive", "driven"}
    np.testing.assert_allclose(_sig(scene, shapes["drive"]["x"]), mod.P1[0])
    np.testing.assert_allclose(_sig(scene, shapes["driven"]["y"]), mod.P2[1])
    contacts = {n: res[n] for n in res.names}
    _check_belts(scene, {"span1": ("driven.ctrK2", "drive.ctrK1"),
                         "span2": ("drive.ctrK2", "tens.ctrK1"),
                         "span3": ("tens.ctrK2", "driven.ctrK1")}, contacts)
    # the gas cylinder has no planar positions and draws nothing
    assert model.cyl.shapes() == []
    assert not any(isinstance(v, str) and v.startswith("cyl.")
                   for s in scene["shapes"] for v in (s.get("x"), s.get("y")))


def test_compressor_tensioner_spring_drawing():
    # the "Belt Tensor" spring-damper is drawn as a spring from the end B of
    # the lever's second arm to the fixed anchor C
    mod = _load("compressor")
    model, res, scene = _run(mod.Compressor(), 0.05, intervals=5)
    springs = _by_type(scene, "spring")
    assert len(springs) == 1
    sh = springs[0]
    assert sh["a"] == ["spring.frame_a.x", "spring.frame_a.y"]
    assert sh["b"] == ["spring.frame_b.x", "spring.frame_b.y"]
    assert_copied(_sig(scene, sh["a"][0]), res["arm2.frame_b.x"])
    assert_copied(_sig(scene, sh["a"][1]), res["arm2.frame_b.y"])
    _, B, C = mod.tensioner_geometry()
    np.testing.assert_allclose(_sig(scene, sh["a"][0])[0], B[0], atol=1e-9)
    np.testing.assert_allclose(_sig(scene, sh["a"][1])[0], B[1], atol=1e-9)
    np.testing.assert_allclose(_sig(scene, sh["b"][0]), C[0], atol=1e-12)
    np.testing.assert_allclose(_sig(scene, sh["b"][1]), C[1], atol=1e-12)


def test_pulley_block_topology():
    """Seed eq. 2.1, F = 3 (n - 1) - sum (3 - f), for the pulley block.

    Links (n = 6): the ground (with the upper block: U1 and U3 have
    unconnected housings, the rope anchor is a Fixed), the lower block (the
    load body rigid with the arms and the housings of L2 and L4), and the
    four pulley wheels U1, L2, U3, L4.  Joints (g = 4): each wheel turns in
    its housing, a revolute joint with f = 1.  The five rope sections are
    elastic force elements (no links, no joints); the rope ends -- fastened
    to the anchor or moved by the RopeDrive, a motion source like the
    presets -- add no link.  F = 3 (6 - 1) - 4 (3 - 1) = 15 - 8 = 7: the
    four pulley angles and x, y, phi of the lower block, the same as the
    seven position states of the structural count; no closed loop."""
    from acausal2d.analysis.check import check
    model = _load("pulley_block").PulleyBlock()
    report = check(model)
    assert (report.links, report.joints, report.grubler) == (6, 4, 7)
    assert report.loops == 0
    assert report.structural_dof == 7
    # housings: ground items only for the unconnected ones
    for name, grounded in (("U1", True), ("U3", True), ("L2", False), ("L4", False)):
        wheel = getattr(model, name)
        items = wheel.topology()
        assert (("ground", [wheel.ctr2D1]) in items) == grounded
        assert ("rigid", [wheel.ctrK1, wheel.ctrK2]) in items
        assert ("joint", wheel.ctr2D1, wheel.ctrK1, 1) in items


@pytest.mark.parametrize("name, cls, expected", [
    # ground, 3 pulleys, lever, crank, rod, piston; 8 joints with f = 1
    # plus the coupling of the driven pulley with the crank (f = 2, see
    # Compressor.topology()): F = 3 * 7 - 8 * 2 - 1 = 4 = drive pulley,
    # tensioner lever, tensioner pulley, crank shaft
    # the clutch's relative angle is a preferred state (as in Modelica's Clutch): a fifth
    # position state beside the four of the linkage and belt drive
    ("compressor", "Compressor", (8, 9, 4, 5)),
    # ground, carriage, 9 pulleys, 2 drums; 11 revolute joints:
    # F = 3 * 12 - 11 * 2 = 14 = carriage 3 + 9 pulleys + 2 drums (the
    # drums' angles are prescribed by their drives, which eq. 2.1 counts,
    # while the structural 14 are carriage 3 + 9 pulleys + hook x, y: the
    # Hook declares no topology)
    ("cable_crane", "CableCrane", (13, 11, 14, 14)),
])
def test_belt_model_topology(name, cls, expected):
    from acausal2d.analysis.check import check
    report = check(getattr(_load(name), cls)())
    assert (report.links, report.joints, report.grubler, report.structural_dof) == expected
