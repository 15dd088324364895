"""The model diagram on the explore page, driven in Debian's headless
Chromium as tests/test_explore.py drives the page (without
/usr/bin/chromium the test fails, it does not skip): the clutch motor
(a drive train, no planar geometry) shows its diagram instead of the
animation; its sub-model ``drive`` opens on a click, a click on the clutch
shows the clutch's parameters only, and each connection shows its flow at
the time shown."""
import base64
import json
import os
import signal
import subprocess
import sys
import time

import matplotlib.image as mpimg
import numpy as np
import pytest

from test_animation import ARTIFACTS, DevTools, Page, console_errors, require_chromium

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


@pytest.fixture(scope="module")
def server():
    proc = subprocess.Popen([sys.executable, "-m", "acausal2d", "explore",
                             "models/clutch_motor.py", "--model", "ClutchMotorConstantLoad",
                             "--port", "0"], cwd=ROOT, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True,
                            env=dict(os.environ, PYTHONPATH=ROOT))
    url = proc.stdout.readline().strip()
    assert url.startswith("http://127.0.0.1:"), (url, proc.stderr.read() if proc.poll() else "")
    yield url
    proc.send_signal(signal.SIGINT)
    try:
        assert proc.wait(timeout=30) == 0, proc.stderr.read()[-2000:]
    finally:
        if proc.poll() is None:
            proc.kill()


def wait_for(page, expr, timeout=60):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if page.js(expr):
            return
        time.sleep(0.05)
    raise AssertionError("timed out waiting for %s; error: %s" % (expr, page.js("explore.error")))


def click_box(page, path):
    """A real mouse click on the middle of the diagram's box ``path``."""
    r = page.js("(function(){var b=document.querySelector('#diagram .box[data-path=\"%s\"]')"
                ".getBoundingClientRect();return [b.left,b.top,b.width,b.height];})()" % path)
    x, y = r[0] + r[2] / 2, r[1] + r[3] / 2
    page.mouse("mousePressed", x, y)
    page.mouse("mouseReleased", x, y, buttons=0)


def shot(page, name):
    data = page.cdp.call("Page.captureScreenshot", {"format": "png"}, session=page.session)
    path = ARTIFACTS / name
    path.write_bytes(base64.b64decode(data["data"]))
    return mpimg.imread(str(path))[:, :, :3].astype(float)


def test_diagram_opens_the_clutch_and_shows_its_parameters_and_flows(server, tmp_path):
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "explore_diagram_cdp.log")
    try:
        page = Page(cdp)
        page.resize(1300, 900)
        page.open(server)
        wait_for(page, "window.exploreDiagram && exploreDiagram.level === '' && explore.runs >= 1")
        assert page.js("document.getElementById('anim').hidden")     # no planar geometry
        top = page.js("Array.from(document.querySelectorAll('#diagram .box'))"
                      ".map(function(b){return b.getAttribute('data-path')})")
        assert sorted(top) == ["drive", "torque"]

        click_box(page, "drive")
        wait_for(page, "exploreDiagram.level === 'drive'")
        inner = page.js("Array.from(document.querySelectorAll('#diagram .box:not(.external)'))"
                        ".map(function(b){return b.getAttribute('data-path')})")
        assert sorted(inner) == ["brake", "clutch", "engage", "load_inertia", "motor"]

        click_box(page, "clutch")
        wait_for(page, "exploreDiagram.selected === 'drive.clutch'")
        shown = page.js("Array.from(document.querySelectorAll('#controls .param'))"
                        ".filter(function(b){return !b.hidden})"
                        ".map(function(b){return b.querySelector('.name').textContent})")
        clutch = [p["name"] for p in page.js("explore.meta.parameters")
                  if p["name"].startswith("drive.clutch.")]
        assert len(clutch) >= 4 and [s.split(" [")[0] for s in shown] == clutch
        assert "fn_max" in " ".join(shown)
        assert "drive.clutch" in page.js("document.getElementById('selection').textContent")

        # the torque through the brake's flange at the end of the run, as the page writes it:
        # the constant load of 10 N m (Torque: flange.tau = -tau_in.u, an exact relation)
        page.js("exploreDiagram.seek(1)")
        line = page.js("(function(){var l=document.querySelector('#diagram path.line"
                       "[data-b=\"drive.brake.flange\"]');"
                       "return [l.id, l.getAttribute('data-flows')];})()")
        text = page.js("document.getElementById('flow-%s').textContent" % line[0][5:])
        name = line[1].split()[0]
        value = page.js("explore.current.data.flows[%s].slice(-1)[0]" % json.dumps(name))
        assert text.startswith("\u03c4 = ") and text.endswith(" N.m"), text
        assert abs(float(text.split()[2]) - value) <= 5e-3 * abs(value) + 1e-12, (text, value)
        assert abs(abs(value) - 10.0) < 1e-9, value

        img = shot(page, "explore_diagram.png")
        colours, counts = np.unique(img.reshape(-1, 3), axis=0, return_counts=True)
        ink = np.max(np.abs(img - colours[np.argmax(counts)]), axis=2) > 0.15
        assert ink.mean() > 0.03, "the page looks blank (%d drawn pixels)" % ink.sum()
        blue = np.all(np.abs(img - np.array([0x1f, 0x6f, 0xb4]) / 255) < 0.08, axis=2)
        assert blue.sum() > 100, "no rotational (blue) connection lines drawn"
        selected = np.all(np.abs(img - np.array([0xf3, 0x9c, 0x12]) / 255) < 0.08, axis=2)
        assert selected.sum() > 100, "the chosen clutch is not outlined"
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()


def test_html_diagram_opens_a_submodel_and_leads_back(tmp_path):
    """``acausal2d diagram --out NAME.html``: a click on the sub-model's box
    shows its own diagram, the path at the top leads back."""
    require_chromium()
    out = tmp_path / "d.html"
    r = subprocess.run([sys.executable, "-m", "acausal2d", "diagram", "models/clutch_motor.py",
                        "--model", "ClutchMotorConstantLoad", "--out", str(out)], cwd=ROOT,
                       capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=ROOT))
    assert r.returncode == 0, r.stderr
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "diagram_html_cdp.log")
    try:
        page = Page(cdp)
        page.resize(1300, 700)
        page.open(out.as_uri())
        visible = ("Array.from(document.querySelectorAll('.level')).filter(function(s)"
                   "{return !s.hidden}).map(function(s){return s.getAttribute('data-level')})")
        assert page.js(visible) == [""]
        r = page.js("(function(){var b=document.querySelector('.level:not([hidden]) "
                    ".box[data-path=\"drive\"]').getBoundingClientRect();"
                    "return [b.left,b.top,b.width,b.height];})()")
        page.mouse("mousePressed", r[0] + r[2] / 2, r[1] + r[3] / 2)
        page.mouse("mouseReleased", r[0] + r[2] / 2, r[1] + r[3] / 2, buttons=0)
        assert page.js(visible) == ["drive"]
        assert page.js("document.querySelectorAll('.level:not([hidden]) .box:not(.external)')"
                       ".length") == 5
        page.js("document.querySelector('#crumbs a').click()")
        assert page.js(visible) == [""]
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()
