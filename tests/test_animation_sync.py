"""The animation page written by ``acausal2d simulate`` with ``--signal``,
``--arrows`` and ``--autoplay``, driven in headless Chromium through the
DevTools protocol (helpers of test_animation.py): autoplay starts playback,
the grid label carries its unit, the signal strip's cursor follows the time
slider, and force arrows are drawn.  Screenshots go to tests/artifacts/."""
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

from test_animation import ARTIFACTS, DevTools, Page, console_errors, require_chromium
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(*args):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def engine_page(tmp_path_factory):
    out = tmp_path_factory.mktemp("sync")
    proc = run("simulate", os.path.join(ROOT, "models", "piston_engine.py"), "--stop-time", "4",
               "--signal", "revoluteDrive.w", "--arrows", "fixed.frame", "--out", str(out))
    assert proc.returncode == 0, proc.stderr
    return out / "animation.html"


def cursor_column(img, top, bottom):
    """Pixel column of the red cursor line in the plot strip rows top..bottom."""
    strip = img[top:bottom]
    red = (strip[:, :, 0] > 0.8) & (strip[:, :, 1] < 0.45) & (strip[:, :, 2] < 0.4)
    cols = np.flatnonzero(red.sum(axis=0) > 0.6 * (bottom - top))
    assert cols.size, "no cursor line in the plot strip"
    return cols.mean()


def test_autoplay_grid_unit_and_synced_plot(engine_page, tmp_path):
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    data = json.loads(re.search(r'<script id="acausal2d-data" type="application/json">(.*?)'
                                r'</script>', engine_page.read_text(), re.S).group(1))
    assert data["plot"] == {"signal": "revoluteDrive.w", "label": "revoluteDrive.w [rad/s]"}
    assert data["autoplay"] is False
    assert [s["type"] for s in data["shapes"] if s["type"] in ("arrow", "torque")] == \
        ["arrow", "torque"]
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_sync.log")
    try:
        page = Page(cdp)
        url = engine_page.resolve().as_uri()
        # without the flag the page waits at frame 0
        page.open(url)
        assert page.js("acausal2d.playing") is False
        assert page.js("acausal2d.gridLabel").endswith(" m")
        assert re.fullmatch(r"grid [0-9.e+-]+ m", page.js("acausal2d.gridLabel"))
        strip = page.js("(() => { const r = document.getElementById('plot')"
                        ".getBoundingClientRect(); return [r.top, r.bottom, r.height]; })()")
        assert 120 <= strip[2] <= 121              # 120 px and its top border
        top, bottom = int(strip[0]) + 22, int(strip[1]) - 22
        # the cursor follows the range input (the time slider)
        positions = []
        for k in (0, 600, 1500):
            page.js("(() => { const s = document.getElementById('scrub'); s.value = '%d';"
                    " s.dispatchEvent(new Event('input')); })()" % k)
            cur = page.js("acausal2d.plotCursor()")
            assert cur["t"] == pytest.approx(data["time"][k])
            img = page.screenshot("sync_frame%d.png" % k)
            positions.append((cur["x"], cursor_column(img, top, bottom)))
        xs = [p[0] for p in positions]
        assert xs[0] < xs[1] < xs[2]
        for want, seen in positions:
            assert abs(want - seen) <= 2.5, positions        # drawn where it says
        # the cursor moves in proportion to time along the strip
        slope = (xs[2] - xs[0]) / (data["time"][1500] - data["time"][0])
        assert xs[1] - xs[0] == pytest.approx(slope * (data["time"][600] - data["time"][0]),
                                              abs=1.0)
        # autoplay from the URL flag: playing at once, frames advance
        page.open(url + "?autoplay=1")
        assert page.js("acausal2d.playing") is True
        assert page.js("document.getElementById('play').textContent") == "Pause"
        page.js("new Promise(r => setTimeout(r, 300))")
        f1, x1 = page.js("[acausal2d.frame, acausal2d.plotCursor().x]")
        page.js("new Promise(r => setTimeout(r, 300))")
        f2, x2 = page.js("[acausal2d.frame, acausal2d.plotCursor().x]")
        assert 0 < f1 < f2 and x1 < x2
        assert page.js("acausal2d.errors") == []
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()


def test_autoplay_option_is_embedded(tmp_path):
    proc = run("simulate", os.path.join(ROOT, "models", "pendulum.py"), "--stop-time", "0.5",
               "--autoplay", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    html = (tmp_path / "animation.html").read_text()
    assert '"autoplay":true' in html
    bad = run("simulate", os.path.join(ROOT, "models", "pendulum.py"), "--arrows", "body.nope",
              "--out", str(tmp_path))
    assert bad.returncode == 2 and "cannot draw arrows for 'body.nope'" in bad.stderr
    assert "body.frame_a" in bad.stderr


def test_cable_crane_masts_are_drawn():
    """Both masts stand on the terrain with a ground symbol at the foot and
    reach the skyline pulley S (left) and the fastening T (right)."""
    import acausal2d
    from acausal2d.visual.scene import build_scene
    from conftest import load_model_class
    h_mast, span, y_right = (load_model_class("cable_crane.py", n)
                             for n in ("H_MAST", "SPAN", "Y_RIGHT"))
    cm = acausal2d.compile_model(load_model_class("cable_crane.py", "CableCrane")())
    res = cm.simulate(stop_time=0.2, intervals=4)
    scene = build_scene(res)

    def point(p):
        return tuple(float(scene["signals"][v][-1]) if isinstance(v, str) else v for v in p)

    links = [[point(p) for p in s["points"]] for s in scene["shapes"]
             if s["type"] == "link" and s.get("color") == "#5d6d7e"]
    assert_copied(sorted(links), [[(0.0, h_mast), (0.0, 0.0)],      # parameters drawn
                                  [(span, y_right + h_mast), (span, y_right)]])
    grounds = [(s["x"], s["y"]) for s in scene["shapes"] if s["type"] == "ground"]
    assert (0.0, 0.0) in grounds and (span, y_right) in grounds
