"""Slider travel ranges (seed ch. 7.1, Bild 7.4): computed from a run by
:func:`acausal2d.analysis.slider_ranges.slider_ranges`, printed by
``acausal2d simulate`` and drawn in the animation over the whole range.

Reference: the slider crank DDDS of models/four_link_mechanisms.py (crank r
= 0.1, coupler l = 0.35, the pin on the line y = 0 through the crank pivot:
centric) has the stroke 2 r, between l - r and l + r from the guide point
P2 = (0, -0.02) (its x coordinate is 0).  The run samples one revolution at
200 intervals, so the dead centres (phi = 0, pi) are output points and the
range is exact up to the kinematic solution's error (rtol 1e-8 of lengths
below 1 m; the bound 1e-6 m leaves a factor 100)."""
import os
import sys

import numpy as np

import acausal2d
from acausal2d import cli
from acausal2d.analysis.slider_ranges import slider_ranges
from acausal2d.visual.animation import validate_scene
from acausal2d.visual.scene import build_scene

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import four_link_mechanisms as flm  # noqa: E402

R, L, TOL = 0.1, 0.35, 1e-6


def _run():
    return acausal2d.simulate(flm.DDDS(), stop_time=1.0, intervals=200, rtol=1e-8)


def test_slider_crank_stroke_is_twice_the_crank():
    res = _run()
    ranges = slider_ranges(res)
    assert [r.name for r in ranges] == ["dyad"]
    (rng,) = ranges
    assert abs(rng.stroke - 2 * R) < TOL
    assert abs(rng.s_min - (L - R)) < TOL and abs(rng.s_max - (L + R)) < TOL
    # the same range from the element's own travel variable
    assert abs(rng.s_max - np.max(res["dyad.xG"])) < TOL


def test_animation_draws_the_guide_over_the_whole_range():
    """The drawn guide runs from the guide point P2 (s = 0) to the far end
    of the range in every frame, and the travel marks sit at l -+ r: before,
    the guide ended at the slider's current position."""
    scene = build_scene(_run())
    validate_scene(scene)
    (sh,) = [s for s in scene["shapes"] if s["type"] == "slider"]
    sig = scene["signals"]
    gx = [np.asarray(sig[p[0]]) for p in sh["guide"]]
    tx = [np.asarray(sig[p[0]]) for p in sh["travel"]]
    gy = [np.asarray(sig[p[1]]) for p in sh["guide"] + sh["travel"]]
    assert np.max(np.abs(gx[0])) < TOL and np.max(np.abs(gx[1] - (L + R))) < TOL
    assert np.max(np.abs(tx[0] - (L - R))) < TOL and np.max(np.abs(tx[1] - (L + R))) < TOL
    assert np.max(np.abs(np.concatenate(gy) + 0.02)) < TOL     # on the guide line y = -0.02
    x_slider = np.asarray(sig[sh["x"]])
    assert np.all(x_slider >= tx[0] - TOL) and np.all(x_slider <= tx[1] + TOL)


def test_simulate_prints_the_ranges(tmp_path, capsys):
    code = cli.main(["simulate", os.path.join(ROOT, "models", "four_link_mechanisms.py"),
                     "--model", "DDDS", "--out", str(tmp_path / "out")])
    assert code == 0
    line = [s for s in capsys.readouterr().out.splitlines() if "slider dyad" in s]
    assert line and "stroke 0.2 m" in line[0], line


def test_dsd_slider_has_its_range():
    """The slider of a DSD (the swinging crank-slider DDSD of
    models/four_link_mechanisms.py: guide pivot B0 = (-0.25, 0), crank pin
    at radius 0.1 from the origin, offset v = 0.02) travels from P1 by
    xG = sqrt(|P2 - B0|^2 - v^2), |P2 - B0| between 0.15 and 0.35 m (pin at
    phi = pi and 0, both output points): the range follows this closed
    form; before, the DSD drew no guide and had no range."""
    res = acausal2d.simulate(flm.DDSD(), stop_time=1.0, intervals=200, rtol=1e-8)
    (rng,) = [r for r in slider_ranges(res) if r.name == "dyad"]
    v = 0.02
    assert abs(rng.s_min - np.sqrt(0.15 ** 2 - v ** 2)) < TOL
    assert abs(rng.s_max - np.sqrt(0.35 ** 2 - v ** 2)) < TOL


def test_slider_on_an_offset_guide_has_its_range():
    """A SAN whose guide sits on a turning crank with an offset (x10 = 0.05
    in the crank's frame: its start point is no result signal) travels
    xG = 0.1 + 0.2 t, driven against its guide: the range is 0.1 .. 0.3 m
    from the element's own travel, and the guide point PS - xG e it
    implies is the crank tip plus the offset (A.7, A.8) at every output
    point; the animation draws the guide over the range."""
    from acausal2d import Component
    from acausal2d.library.linkage import DAN, SAN
    from acausal2d.library.linkage.drives import Preset

    class CrankSlider(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.crank = DAN(lL=0.2, mL=0.1, JL=1e-3)
            self.turn = Preset(kind="speed", om=1.0, phi0=0.3)
            self.slider = SAN(x10=0.05, mS=0.2, JS=1e-3)
            self.push = Preset(kind="speed", om=0.2, phi0=0.1, translational=True,
                               use_support=True)
            self.connect(self.turn.flange, self.crank.ctrR2)
            self.connect(self.crank.ctr2D2, self.slider.ctr2D1)
            self.connect(self.push.flange, self.slider.ctrT2)
            self.connect(self.push.support, self.slider.ctrT1)

    res = acausal2d.simulate(CrankSlider(), stop_time=1.0, rtol=1e-8,
                             output_times=np.linspace(0.0, 1.0, 21))
    (rng,) = slider_ranges(res)
    assert rng.name == "slider"
    assert abs(rng.s_min - 0.1) < TOL and abs(rng.s_max - 0.3) < TOL
    phi = 0.3 + res.time
    G = (0.25 * np.cos(phi), 0.25 * np.sin(phi))
    e = (np.cos(res["slider.phiS"]), np.sin(res["slider.phiS"]))
    assert np.max(np.abs(res["slider.xPS"] - res["slider.xG"] * e[0] - G[0])) < TOL
    assert np.max(np.abs(res["slider.yPS"] - res["slider.xG"] * e[1] - G[1])) < TOL
    scene = build_scene(res)
    validate_scene(scene)
    (sh,) = [s for s in scene["shapes"] if s["type"] == "slider"]
    assert len(sh["guide"]) == 2 and len(sh["travel"]) == 2
