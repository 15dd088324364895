"""Drawing of the planar prismatic joint (library/planar.py): the slider
block sits at the frame that moves against the grounded side, on a guide of
constant length fixed in the world along the joint axis."""
import math

import numpy as np
import pytest

from acausal2d import Component, compile_model, start
from acausal2d.visual.animation import validate_scene
from acausal2d.library.planar import Body, Fixed, Prismatic, fixed_of, is_connected
from acausal2d.visual.scene import build_scene
from conftest import load_model_class, assert_copied


def _scene(model, stop_time, intervals=40):
    res = compile_model(model).simulate(stop_time=stop_time,
                                        output_times=np.linspace(0.0, stop_time, intervals + 1))
    scene = build_scene(res)
    validate_scene(scene)
    return res, scene


def _values(scene, value):
    """A shape field over the frames (a constant or a signal)."""
    if isinstance(value, str):
        return np.asarray(scene["signals"][value], dtype=float)
    return np.full(len(scene["time"]), float(value))


def _slider(scene, path):
    sliders = [s for s in scene["shapes"] if s["type"] == "slider"
               and s["x"].startswith(path + ".")]
    assert len(sliders) == 1
    return sliders[0]


def _check_guide(scene, sh, moving_x, moving_y):
    """The guide end points do not move, and the moving frame stays on the
    guide line within its ends over the whole run."""
    ends = []
    for pt in sh["guide"]:
        xs, ys = _values(scene, pt[0]), _values(scene, pt[1])
        # fixed points: constant up to rounding (4 ulps of the coordinate)
        assert np.ptp(xs) <= 4 * np.spacing(np.max(np.abs(xs)))
        assert np.ptp(ys) <= 4 * np.spacing(np.max(np.abs(ys)))
        ends.append(np.array([xs[0], ys[0]]))
    d = ends[1] - ends[0]
    L = np.hypot(*d)
    assert L > 0.0
    rel = np.stack([moving_x - ends[0][0], moving_y - ends[0][1]])
    along = (d @ rel) / L
    across = (d[0] * rel[1] - d[1] * rel[0]) / L
    assert np.max(np.abs(across)) < 1e-9
    assert np.min(along) >= 0.0 and np.max(along) <= L
    return ends


def test_piston_engine_slider_at_piston_on_fixed_guide():
    # frame_b of the prismatic joint is on the Fixed at the origin (the
    # cylinder), frame_a carries the piston: the block is drawn at frame_a
    model = load_model_class("piston_engine.py", "PistonEngine")()
    assert fixed_of(model.prismatic.frame_b) is model.fixed1
    assert fixed_of(model.prismatic.frame_a) is None
    res, scene = _scene(model, 2.0)
    sh = _slider(scene, "prismatic")
    assert (sh["x"], sh["y"], sh["phi"]) == ("prismatic.frame_a.x", "prismatic.frame_a.y",
                                             "prismatic.frame_a.phi")
    x, y = _values(scene, sh["x"]), _values(scene, sh["y"])
    assert_copied(x, res["bodyPiston.x"])
    assert np.ptp(x) > 0.5                     # the piston strokes 0.5 .. 1.1
    ends = _check_guide(scene, sh, x, y)
    # the model gives the guide range s = -0.4 ... -1.2: the cylinder over the
    # piston's travel along +x from the grounded frame at the origin
    np.testing.assert_allclose(ends, [[0.4, 0.0], [1.2, 0.0]], atol=1e-12)
    # no guide end follows a moving frame
    assert not any(isinstance(v, str) for pt in sh["guide"] for v in pt)


def test_crane_crab_slider_at_trolley():
    # frame_a on the Fixed, the trolley at frame_b (start s = 0): block at
    # frame_b, guide symmetric about the Fixed, |r|/2 to each side
    model = load_model_class("crane_crab.py", "CraneCrab")()
    res, scene = _scene(model, 3.0)
    sh = _slider(scene, "prismatic")
    assert (sh["x"], sh["y"]) == ("prismatic.frame_b.x", "prismatic.frame_b.y")
    x, y = _values(scene, sh["x"]), _values(scene, sh["y"])
    assert_copied(x, res["body1.x"])
    assert np.ptp(x) > 0.1
    ends = _check_guide(scene, sh, x, y)
    np.testing.assert_allclose(ends, [[-0.5, 0.0], [0.5, 0.0]], atol=1e-12)


class _TiltedSlider(Component):
    """Fixed at (1, 2) turned by 30 deg; the prismatic joint r = (0, 2) in
    its frame (axis at 120 deg in the world) carries a body at frame_b that
    slides down from s = 0.4 under gravity (s = 0.4 - 4.25 t^2)."""

    def __init__(self, guide=None, **kw):
        super().__init__(**kw)
        self.ground = Fixed(r=(1.0, 2.0), phi=math.radians(30.0))
        self.joint = Prismatic(r=(0.0, 2.0), guide=guide, s=start(0.4, fixed=True),
                               v=start(0.0, fixed=True))
        self.body = Body(m=1.0, I=0.1)
        self.connect(self.ground.frame, self.joint.frame_a)
        self.connect(self.joint.frame_b, self.body.frame_a)


@pytest.mark.parametrize("guide", [None, (-0.2, 1.5)])
def test_guide_along_turned_axis(guide):
    model = _TiltedSlider(guide=guide)
    res, scene = _scene(model, 0.25, intervals=10)
    sh = _slider(scene, "joint")
    assert sh["x"] == "joint.frame_b.x"
    ends = _check_guide(scene, sh, _values(scene, sh["x"]), _values(scene, sh["y"]))
    lo, hi = guide or (0.0, 0.8)               # default: s = 0 .. 2 s(0)
    e = np.array([math.cos(math.radians(120.0)), math.sin(math.radians(120.0))])
    np.testing.assert_allclose(ends, [[1.0, 2.0] + lo * e, [1.0, 2.0] + hi * e], atol=1e-12)


class _FloatingSlider(Component):
    """A prismatic joint between two free bodies: no side is grounded."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.a = Body(m=1.0, I=0.1)
        self.joint = Prismatic(r=(1.0, 0.0), s=start(0.5, fixed=True), v=start(0.0, fixed=True))
        self.b = Body(m=1.0, I=0.1)
        self.connect(self.a.frame_a, self.joint.frame_a)
        self.connect(self.joint.frame_b, self.b.frame_a)


def test_ungrounded_prismatic_keeps_block_at_frame_b():
    model = _FloatingSlider()
    assert not any(fixed_of(f) for f in (model.joint.frame_a, model.joint.frame_b))
    sh = model.joint.shapes()[0]
    assert (sh["x"], sh["y"]) == ("frame_b.x", "frame_b.y")
    assert sh["guide"] == [["frame_a.x", "frame_a.y"], ["frame_b.x", "frame_b.y"]]


def test_connection_helpers():
    model = load_model_class("piston_engine.py", "PistonEngine")()
    assert is_connected(model.prismatic.frame_b)
    assert not is_connected(Prismatic().frame_a)       # not part of a model
    # through a chain of connections: revolutePiston.frame_b -> prismatic.frame_a
    assert fixed_of(model.revoluteDrive.frame_a) is model.fixed
    assert fixed_of(model.bodyPiston.frame_a) is None
    assert_copied(model.prismatic.start_value("s"), -1.1)
    assert_copied(model.prismatic.start_value("v"), 0.0)
