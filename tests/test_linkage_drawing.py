"""Drawing (shapes) and planar topology (eq. 2.1) of the VDI 2729 linkage
elements on the nine four-link mechanisms of Bild 2.2 and the 8-link
mechanism of VDI 2729 example 2."""
import os
import sys

import pytest

import acausal2d
from acausal2d.analysis.check import check
from acausal2d.visual.animation import validate_scene
from acausal2d.library.linkage.base import _Linkage
from acausal2d.visual.scene import build_scene

sys.path.insert(0, os.path.join(os.path.dirname(__file__), os.pardir, "models"))

import four_link_mechanisms as flm  # noqa: E402
import eight_link_vdi2729 as e8  # noqa: E402


def _element_shapes(scene, elem):
    prefix = elem.path + "."
    out = []
    for shape in scene["shapes"]:
        names = []
        for k in ("x", "y"):
            if isinstance(shape.get(k), str):
                names.append(shape[k])
        for pt in shape.get("points", ()):
            names += [v for v in pt if isinstance(v, str)]
        if any(n.startswith(prefix) for n in names):
            out.append(shape["type"])
    return out


@pytest.mark.parametrize("cls", flm.MECHANISMS, ids=lambda c: c.__name__)
def test_four_link_topology_and_scene(cls):
    model = cls()
    report = check(model)
    assert report.grubler == 1
    assert report.loops == 1
    assert (report.links, report.joints) == (4, 4)

    res = acausal2d.simulate(cls(), stop_time=0.2, intervals=20)
    scene = build_scene(res)
    validate_scene(scene)
    elems = [c for c in res.model.model.components() if isinstance(c, _Linkage)]
    assert len(elems) == 2
    for elem in elems:
        kinds = _element_shapes(scene, elem)
        assert "link" in kinds, (elem.path, kinds)
        assert "joint" in kinds, (elem.path, kinds)
    # the unconnected bearing housings / guides are drawn as ground
    assert any(s["type"] == "ground" for s in scene["shapes"])
    for name in scene["signals"]:          # the result's, or a slider's travel range drawn
        assert name in res or name.startswith("slider travel "), name


def test_ground_only_for_unconnected_ports():
    res = acausal2d.simulate(flm.DDDD(), stop_time=0.1, intervals=5)
    grounds = [s for s in build_scene(res)["shapes"] if s["type"] == "ground"]
    # crank bearing A0 and rocker bearing B0; the dyad's P1 sits on the crank pin
    assert sorted((s["x"], s["y"]) for s in grounds) == [
        ("crank.x10", "crank.y10"), ("dyad.ctr2D4.x", "dyad.ctr2D4.y")]


def test_eight_link_topology_and_scene():
    report = check(e8.EightLinkVDI2729())
    assert report.grubler == 1
    assert (report.links, report.joints, report.loops) == (8, 10, 3)
    res = acausal2d.simulate(e8.EightLinkVDI2729(), stop_time=0.5, intervals=10)
    scene = build_scene(res)
    validate_scene(scene)
    kinds = [s["type"] for s in scene["shapes"]]
    assert kinds.count("slider") == 5      # DSD 1, SDS 2, SSD 2
    assert kinds.count("ground") >= 4      # A0, B0, the ground guide (x2), C0
