"""The animation shape kinds of the force elements and sensors (damper,
box, sensor, arrow, torque): validation, bounding box, and the page
drawing them in headless Chromium without console errors."""
import numpy as np
import pytest

from acausal2d.errors import Acausal2dError
from acausal2d.visual.animation import _scene_data, validate_scene, write_html
from acausal2d.visual.scene import qualify_shape
from test_animation import ARTIFACTS, CANVAS_ROWS, assert_differ, screenshot_frames
from conftest import assert_copied


def element_scene(n=201):
    """A body on a spring and damper under a turning force and torque,
    with a box link and a sensor pair."""
    t = np.linspace(0.0, 2.0, n)
    y = -1.0 + 0.3 * np.cos(4 * t)
    signals = {"y": y, "fx": 3 * np.cos(2 * t), "fy": 3 * np.sin(2 * t), "tau": np.sin(3 * t),
               "phi": t, "zero": 0 * t}
    shapes = [
        {"type": "ground", "x": 0, "y": 0},
        {"type": "spring", "a": [0, 0], "b": [0, "y"]},
        {"type": "damper", "a": [0, 0], "b": [0, "y"], "offset": 14},
        {"type": "box", "a": [0, "y"], "b": [1.0, "y"], "width": 0.15},
        {"type": "body", "x": 0, "y": "y"},
        {"type": "sensor", "points": [[0, 0], [1.0, "y"]]},
        {"type": "arrow", "x": 1.0, "y": "y", "fx": "fx", "fy": "fy"},
        {"type": "arrow", "x": 0, "y": "y", "fx": 1.0, "fy": 0.0, "phi": "phi", "angle": 0.5,
         "scale": 0.2},
        {"type": "arrow", "x": 0, "y": 0, "fx": "zero", "fy": "zero"},
        {"type": "torque", "x": 1.0, "y": "y", "t": "tau"},
    ]
    return {"title": "Force elements", "time": t, "signals": signals, "shapes": shapes}


def test_element_kinds_validate_and_fit():
    scene = element_scene()
    validate_scene(scene)
    data = _scene_data(scene, 2000)
    xmin, ymin, xmax, ymax = data["bbox"]
    # the box's half width is added around its end points
    assert xmin == pytest.approx(-0.075) and xmax == pytest.approx(1.075)
    assert ymin == pytest.approx(-1.3 - 0.075, abs=1e-4) and ymax == pytest.approx(0.0)
    assert set(data["signals"]) == {"y", "fx", "fy", "tau", "phi", "zero"}


@pytest.mark.parametrize("shape,pattern", [
    ({"type": "arrow", "x": 0, "y": 0, "fx": 1.0}, "missing the required field 'fy'"),
    ({"type": "torque", "x": 0, "y": 0}, "missing the required field 't'"),
    ({"type": "damper", "a": [0, 0], "b": [0]}, r"must be a point \[X, Y\]"),
    ({"type": "sensor", "points": []}, "needs at least 1 points"),
    ({"type": "box", "a": [0, 0], "b": [1, 0], "width": "nope"}, "signal 'nope'"),
], ids=["arrow", "torque", "damper", "sensor", "box"])
def test_element_kinds_reject_bad_fields(shape, pattern):
    scene = element_scene(5)
    scene["shapes"] = [shape]
    with pytest.raises(Acausal2dError, match=pattern):
        validate_scene(scene)


def test_qualify_prefixes_force_fields():
    shape = {"type": "arrow", "x": "frame_b.x", "y": "frame_b.y", "fx": "fx", "fy": 0.0,
             "phi": "frame_a.phi", "angle": 0.3}
    out = qualify_shape(shape, "prismatic.")
    assert out["fx"] == "prismatic.fx"
    assert_copied(out["fy"], 0.0)
    assert out["phi"] == "prismatic.frame_a.phi"
    assert_copied(out["angle"], 0.3)
    torque = qualify_shape({"type": "torque", "x": "a.x", "y": "a.y", "t": "tau"}, "w.")
    assert torque["t"] == "w.tau"


def test_browser_draws_element_kinds(tmp_path):
    """Two frames of the page in headless Chromium: no console message,
    the red force arrow and the violet damper are drawn, and the frames
    differ."""
    ARTIFACTS.mkdir(exist_ok=True)
    page = write_html(element_scene(), ARTIFACTS / "force_elements.html")
    images = screenshot_frames(page, (0, 120), tmp_path, "elements")
    for img in images:
        area = img[:CANVAS_ROWS]
        red = np.all(np.abs(area - np.array([192, 57, 43]) / 255) < 0.08, axis=2)
        violet = np.all(np.abs(area - np.array([108, 92, 231]) / 255) < 0.08, axis=2)
        assert red.sum() > 50 and violet.sum() > 30, (red.sum(), violet.sum())
    assert_differ(images[0], images[1])
