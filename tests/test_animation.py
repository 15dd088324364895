"""Tests of acausal2d.visual.animation: scene validation, the self-contained HTML
page, and the page running in a real (headless) Chromium.

The browser tests need Debian's chromium at /usr/bin/chromium
(``apt-get install -y chromium``); without it they FAIL, they do not skip.
Screenshots are written to tests/artifacts/ (ignored by git).
"""
import base64
import fcntl
import html as html_module
import json
import os
import pathlib
import queue
import re
import signal
import subprocess
import threading
import time

import numpy as np
import pytest
from matplotlib import image as mpimg

from acausal2d.visual.animation import MAX_FRAMES, render_html, validate_scene, write_html
from acausal2d.errors import Acausal2dError
from conftest import same_time, assert_copied

CHROMIUM = "/usr/bin/chromium"
ARTIFACTS = pathlib.Path(__file__).parent / "artifacts"
# Flags of every browser run: headless, no sandbox (we run as root in CI
# containers), and nothing that talks to the network.
CHROMIUM_FLAGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--window-size=800,600",
]
CANVAS_ROWS = 540  # the control bar is the bottom ~40 px of the 600 px window


# --------------------------------------------------------------------------
# a synthetic scene: slider-crank with a belt drive, a spring and a trace

def slider_crank_scene(n=401, t_end=2.0):
    """Kinematics of a slider-crank (crank r = 0.1, rod l = 0.3) computed
    with numpy, with a crank disc driving a small pulley by a belt, a return
    spring to a wall and the trace of the rod midpoint."""
    t = np.linspace(0.0, t_end, n)
    r, l = 0.1, 0.3
    th = 2 * np.pi * 0.75 * t + 0.3
    ax, ay = r * np.cos(th), r * np.sin(th)
    bx = ax + np.sqrt(l ** 2 - ay ** 2)
    signals = {
        "theta": th, "A.x": ax, "A.y": ay, "B.x": bx,
        "M.x": (ax + bx) / 2, "M.y": ay / 2,
        "cw.x": -0.04 * np.cos(th), "cw.y": -0.04 * np.sin(th),
        "pulley.phi": 2 * th, "spring.a": bx + 0.04,
        "unused": np.zeros(n),
    }
    shapes = [
        {"type": "ground", "x": 0, "y": 0},
        {"type": "ground", "x": 0.62, "y": 0, "phi": np.pi / 2},
        {"type": "pulley", "x": 0, "y": 0, "r": 0.1, "phi": "theta"},
        {"type": "pulley", "x": -0.3, "y": 0.0, "r": 0.05, "phi": "pulley.phi"},
        {"type": "belt", "points": [[-0.3, 0.05], [0.0, 0.1]]},
        {"type": "belt", "points": [[-0.3, -0.05], [0.0, -0.1]]},
        {"type": "slider", "x": "B.x", "y": 0, "phi": 0, "length": 0.08,
         "guide": [[0.1, 0], [0.6, 0]]},
        {"type": "spring", "a": ["spring.a", 0], "b": [0.62, 0]},
        {"type": "link", "points": [[0, 0], ["A.x", "A.y"]]},
        {"type": "link", "points": [["A.x", "A.y"], ["B.x", 0]], "width": 0.02},
        {"type": "body", "x": "cw.x", "y": "cw.y", "r": 0.025},
        {"type": "joint", "x": 0, "y": 0},
        {"type": "joint", "x": "A.x", "y": "A.y"},
        {"type": "joint", "x": "B.x", "y": 0},
        {"type": "trace", "x": "M.x", "y": "M.y"},
        {"type": "label", "x": "A.x", "y": "A.y", "text": "A <crank> & pin"},
    ]
    return {"title": "Slider-crank", "time": t.tolist(),
            "signals": {k: v.tolist() for k, v in signals.items()}, "shapes": shapes}


def embedded_data(page):
    m = re.search(r'<script id="acausal2d-data" type="application/json">(.*?)</script>',
                  page, re.S)
    assert m, "data script element not found"
    return json.loads(m.group(1))


# --------------------------------------------------------------------------
# validation

def test_valid_scene_passes():
    assert validate_scene(slider_crank_scene(n=11)) is None


@pytest.mark.parametrize("key", ["title", "time", "signals", "shapes"])
def test_missing_key(key):
    scene = slider_crank_scene(n=11)
    del scene[key]
    with pytest.raises(Acausal2dError, match=f"missing the key.*'{key}'"):
        validate_scene(scene)


def test_unknown_signal_names_signal_and_shape_index():
    scene = slider_crank_scene(n=11)
    scene["shapes"][9]["points"][1][0] = "C.x"
    with pytest.raises(Acausal2dError) as err:
        validate_scene(scene)
    msg = str(err.value)
    assert "'C.x'" in msg and "shape 9" in msg and "link" in msg and "'points'" in msg
    assert "'B.x'" in msg  # lists the available signals


def test_length_mismatch():
    scene = slider_crank_scene(n=11)
    scene["signals"]["theta"] = scene["signals"]["theta"][:-1]
    with pytest.raises(Acausal2dError, match=r"signal 'theta' has 10 values but scene\['time'\] has 11"):
        validate_scene(scene)


def test_unknown_shape_type():
    scene = slider_crank_scene(n=11)
    scene["shapes"].append({"type": "gear", "x": 0, "y": 0})
    with pytest.raises(Acausal2dError, match=r"shape 16 has unknown type 'gear'.*known types: ground"):
        validate_scene(scene)


@pytest.mark.parametrize("shape, pattern", [
    ({"type": "pulley", "x": 0, "y": 0, "r": 1}, r"shape 0 \(pulley\) is missing the required field 'phi'"),
    ({"type": "link", "points": [[0, 0]]}, r"shape 0 \(link\) field 'points' needs at least 2 points"),
    ({"type": "spring", "a": [0, 0], "b": [0]}, r"'b' must be a point"),
    ({"type": "joint", "x": [1], "y": 0}, r"'x' must be a number or a signal name"),
    ({"type": "label", "x": 0, "y": 0, "text": 3}, r"'text' must be a string"),
    ({"type": "pulley", "x": 0, "y": 0, "r": 1, "phi": 0, "contour": [[0, 1], [1, 0], ["s", 0]]},
     r"contour.*refers to signal 's'"),
    ("joint", r"shape 0 must be a dict"),
])
def test_bad_shapes(shape, pattern):
    scene = {"title": "", "time": [0, 1], "signals": {"s": [0, 1]}, "shapes": [shape]}
    with pytest.raises(Acausal2dError, match=pattern):
        validate_scene(scene)


def test_bad_time():
    with pytest.raises(Acausal2dError, match="non-decreasing"):
        validate_scene({"title": "", "time": [0, 2, 1], "signals": {}, "shapes": []})
    with pytest.raises(Acausal2dError, match="empty"):
        validate_scene({"title": "", "time": [], "signals": {}, "shapes": []})


def test_render_validates():
    with pytest.raises(Acausal2dError, match="unknown type"):
        render_html({"title": "", "time": [0], "signals": {}, "shapes": [{"type": "x"}]})


# --------------------------------------------------------------------------
# the HTML

def test_html_is_self_contained():
    page = render_html(slider_crank_scene())
    assert page.startswith("<!DOCTYPE html>")
    assert not re.search(r"<script[^>]*\bsrc\s*=", page, re.I)
    assert not re.search(r"""(src|href)\s*=\s*["']?\s*(https?:)?//""", page, re.I)
    assert not re.search(r"@import|url\(\s*['\"]?(https?:)?//", page, re.I)
    assert "http://" not in page and "https://" not in page
    assert '<canvas id="view"' in page
    for ident in ("play", "scrub", "speed", "time"):
        assert f'id="{ident}"' in page
    for speed in ("0.25", "0.5", "1", "2", "4"):
        assert f'<option value="{speed}"' in page
    assert '<title>Slider-crank</title>' in page


def test_json_embedded_and_parseable():
    scene = slider_crank_scene(n=101)
    page = render_html(scene)
    data = embedded_data(page)
    assert data["title"] == "Slider-crank"
    assert data["nframes"] == 101 and data["source_samples"] == 101
    assert len(data["time"]) == 101
    np.testing.assert_allclose(data["time"], scene["time"], rtol=1e-6)
    # only signals used by shapes are embedded, each rounded to 6 digits
    assert "unused" not in data["signals"]
    assert set(data["signals"]) == set(scene["signals"]) - {"unused"}
    for name, values in data["signals"].items():
        np.testing.assert_allclose(values, scene["signals"][name], rtol=1e-5, atol=1e-12)
        assert_copied(values, [float(f"{v:.6g}") for v in values])    # written with 6 digits
    assert [s["type"] for s in data["shapes"]] == [s["type"] for s in scene["shapes"]]
    assert data["shapes"][1]["phi"] == pytest.approx(np.pi / 2, rel=1e-5)
    # the label text survives, and "<" in the data cannot close the <script>
    assert data["shapes"][-1]["text"] == "A <crank> & pin"
    assert "<crank>" not in page
    xmin, ymin, xmax, ymax = data["bbox"]
    assert xmin == pytest.approx(-0.35) and xmax == pytest.approx(0.62)
    # the crank pin A reaches y = +-0.1, and the rod through it is 0.02 wide
    assert ymin == pytest.approx(-0.11, abs=1e-4) and ymax == pytest.approx(0.11, abs=1e-4)


def test_nan_becomes_null():
    scene = {"title": "t", "time": [0, 1, 2], "signals": {"x": [0.0, float("nan"), 1.0]},
             "shapes": [{"type": "joint", "x": "x", "y": 0}]}
    data = embedded_data(render_html(scene))
    assert_copied(data["signals"]["x"], [0.0, None, 1.0])


def test_subsampling_keeps_first_and_last():
    n = 10001
    scene = slider_crank_scene(n=n, t_end=20.0)
    data = embedded_data(render_html(scene))
    assert data["source_samples"] == n
    assert 1900 <= data["nframes"] <= MAX_FRAMES
    t = np.array(data["time"])
    assert len(t) == data["nframes"]
    assert all(len(v) == len(t) for v in data["signals"].values())
    assert same_time(t[0], 0.0) and same_time(t[-1], 20.0)
    assert np.all(np.diff(t) > 0)
    assert np.max(np.diff(t)) < 2.5 * 20.0 / MAX_FRAMES  # evenly spread in time
    # the subsampled values are the original samples at those times
    src_t = np.array(scene["time"])
    idx = np.searchsorted(src_t, t - 1e-9)
    np.testing.assert_allclose(data["signals"]["B.x"],
                               np.array(scene["signals"]["B.x"])[idx], rtol=1e-5)
    small = embedded_data(render_html(scene, max_frames=50))
    assert small["nframes"] <= 50 and same_time(small["time"][0], 0.0) \
        and same_time(small["time"][-1], 20.0)
    assert '<input id="scrub" type="range" min="0" max="%d"' % (small["nframes"] - 1) in \
        render_html(scene, max_frames=50)


def test_subsampling_nonuniform_time_is_even_in_time():
    # dense samples clustered at the start must not eat the frame budget
    t = np.concatenate([np.linspace(0, 0.01, 5000, endpoint=False), np.linspace(0.01, 10, 5000)])
    scene = {"title": "", "time": t.tolist(), "signals": {"x": t.tolist()},
             "shapes": [{"type": "joint", "x": "x", "y": 0}]}
    tt = np.array(embedded_data(render_html(scene))["time"])
    assert same_time(tt[0], 0.0) and same_time(tt[-1], 10.0) and len(tt) <= MAX_FRAMES
    assert np.max(np.diff(tt)) < 0.02


def test_write_html(tmp_path):
    out = write_html(slider_crank_scene(n=21), tmp_path / "sub" / "anim.html")
    assert isinstance(out, pathlib.Path) and out.exists()
    assert embedded_data(out.read_text(encoding="utf-8"))["nframes"] == 21


def test_title_is_escaped():
    scene = slider_crank_scene(n=5)
    scene["title"] = "a <b> & c"
    page = render_html(scene)
    assert "<title>%s</title>" % html_module.escape("a <b> & c") in page


# --------------------------------------------------------------------------
# the page in a headless Chromium

def require_chromium():
    if not os.path.exists(CHROMIUM):
        pytest.fail(f"{CHROMIUM} not found: the browser tests need Debian's chromium; "
                    "install it with `apt-get update && apt-get install -y chromium`")


def read_png(path):
    img = mpimg.imread(str(path))
    assert img.ndim == 3 and img.shape[:2] == (600, 800), img.shape
    return img[:, :, :3].astype(float)


def assert_canvas_drawn(img, name):
    """The canvas area is not just background: count pixels that differ
    clearly from the most common (background) colour; the faint grid lines
    stay below the threshold, the mechanism does not."""
    area = img[:CANVAS_ROWS]
    colours, counts = np.unique(area.reshape(-1, 3), axis=0, return_counts=True)
    background = colours[np.argmax(counts)]
    ink = np.max(np.abs(area - background), axis=2) > 0.15
    assert ink.mean() > 0.01, f"{name}: canvas looks blank ({ink.sum()} drawn pixels)"
    # steel-blue links are there
    steel = np.all(np.abs(area - np.array([70, 130, 180]) / 255) < 0.06, axis=2)
    assert steel.sum() > 200, f"{name}: no steel-blue link pixels"


def assert_differ(a, b):
    diff = np.max(np.abs(a[:CANVAS_ROWS] - b[:CANVAS_ROWS]), axis=2) > 0.15
    assert diff.sum() > 500, f"frames look the same ({diff.sum()} pixels differ)"


@pytest.fixture(scope="module")
def page_path():
    ARTIFACTS.mkdir(exist_ok=True)
    return write_html(slider_crank_scene(), ARTIFACTS / "slider_crank.html")


class DevTools:
    """Minimal Chrome DevTools Protocol client over --remote-debugging-pipe.

    Chromium reads NUL-terminated JSON commands from fd 3 and writes
    responses and events to fd 4; no port, no websocket library needed.
    """

    def __init__(self, user_data_dir, log_path):
        to_chrome_r, self._to_chrome = os.pipe()
        self._from_chrome, from_chrome_w = os.pipe()
        # move the child's ends above fd 10 so that dup2 onto 3/4 cannot clobber them
        child_r = fcntl.fcntl(to_chrome_r, fcntl.F_DUPFD_CLOEXEC, 10)
        child_w = fcntl.fcntl(from_chrome_w, fcntl.F_DUPFD_CLOEXEC, 10)
        os.close(to_chrome_r)
        os.close(from_chrome_w)

        def child_fds():  # runs in the child between fork and exec
            os.dup2(child_r, 3)
            os.dup2(child_w, 4)

        self.log = open(log_path, "wb")
        self.proc = subprocess.Popen(
            [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={user_data_dir}",
             "--remote-debugging-pipe", "about:blank"],
            stdin=subprocess.DEVNULL, stdout=self.log, stderr=subprocess.STDOUT,
            close_fds=False, preexec_fn=child_fds, start_new_session=True)
        os.close(child_r)
        os.close(child_w)
        self._next_id = 0
        self._messages = queue.Queue()
        self.events = []
        self._thread = threading.Thread(target=self._reader, daemon=True)
        self._thread.start()

    def _reader(self):
        buf = b""
        while True:
            try:
                chunk = os.read(self._from_chrome, 1 << 16)
            except OSError:
                chunk = b""
            if not chunk:
                self._messages.put(None)
                return
            buf += chunk
            *complete, buf = buf.split(b"\0")
            for raw in complete:
                self._messages.put(json.loads(raw))

    def _pull(self, deadline):
        try:
            msg = self._messages.get(timeout=max(0.01, deadline - time.monotonic()))
        except queue.Empty:
            raise TimeoutError("no message from chromium") from None
        if msg is None:
            raise RuntimeError("chromium closed the DevTools pipe")
        return msg

    def call(self, method, params=None, session=None, timeout=15):
        self._next_id += 1
        msg = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_chrome, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._pull(deadline)
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    def wait_event(self, method, timeout=15):
        deadline = time.monotonic() + timeout
        seen = len(self.events)
        while True:
            for ev in self.events[seen:]:
                if ev.get("method") == method:
                    return ev
            seen = len(self.events)
            self.events.append(self._pull(deadline))

    def close(self):
        try:
            self.call("Browser.close", timeout=5)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            os.killpg(self.proc.pid, signal.SIGKILL)  # our own process group only
            self.proc.wait(timeout=5)
        os.close(self._to_chrome)
        self._thread.join(timeout=5)  # the reader ends at EOF, once chromium has exited
        if not self._thread.is_alive():
            os.close(self._from_chrome)
        self.log.close()


class Page:
    """One tab of a DevTools-driven Chromium, 800 x 600 CSS pixels."""

    def __init__(self, cdp):
        self.cdp = cdp
        target = cdp.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = cdp.call("Target.attachToTarget",
                                {"targetId": target, "flatten": True})["sessionId"]
        for domain in ("Page", "Runtime", "Log"):
            cdp.call(f"{domain}.enable", session=self.session)
        self.resize(800, 600)

    def resize(self, width, height):
        self.cdp.call("Emulation.setDeviceMetricsOverride",
                      {"width": width, "height": height, "deviceScaleFactor": 1,
                       "mobile": False}, session=self.session)

    def open(self, url):
        self.cdp.call("Page.navigate", {"url": url}, session=self.session)
        self.cdp.wait_event("Page.loadEventFired")

    def js(self, expr):
        res = self.cdp.call("Runtime.evaluate", {"expression": expr, "returnByValue": True,
                                                 "awaitPromise": True}, session=self.session)
        assert "exceptionDetails" not in res, res
        return res["result"].get("value")

    def screenshot(self, name):
        data = self.cdp.call("Page.captureScreenshot", {"format": "png"},
                             session=self.session)["data"]
        path = ARTIFACTS / name
        path.write_bytes(base64.b64decode(data))
        return read_png(path)

    def mouse(self, kind, x, y, buttons=1):
        """A left-button mouse event at (x, y) CSS pixels."""
        self.cdp.call("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y,
                                                   "button": "left", "buttons": buttons,
                                                   "clickCount": 1}, session=self.session)


def console_errors(events):
    """Uncaught exceptions, console.error/assert calls and error log entries
    (e.g. failed resource loads) reported by the DevTools protocol."""
    out = []
    for ev in events:
        method, params = ev.get("method"), ev.get("params", {})
        if method == "Runtime.exceptionThrown":
            details = params["exceptionDetails"]
            out.append(details.get("exception", {}).get("description") or details.get("text"))
        elif method == "Runtime.consoleAPICalled" and params.get("type") in ("error", "assert"):
            out.append(" ".join(str(a.get("value", a.get("description"))) for a in params["args"]))
        elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
            out.append(params["entry"]["text"])
    return out


def test_browser_scrub_play_and_console(page_path, tmp_path):
    """Drive the page with the DevTools protocol.

    Chromium is started as ``/usr/bin/chromium --headless --no-sandbox
    --disable-gpu --disable-quic --no-first-run --disable-background-networking
    --disable-component-update --disable-sync --window-size=800,600
    --user-data-dir=<tmp> --remote-debugging-pipe about:blank``.  The test opens
    the page at ``#frame=120``, checks the initial frame, takes a screenshot,
    scrubs with ``acausal2d.setFrame`` and with the range input, takes a second
    screenshot, plays for a moment at 4x and pauses, and resizes the window.  Console errors are collected
    from the protocol's Runtime.exceptionThrown, Runtime.consoleAPICalled
    (error/assert) and Log.entryAdded (level error) events; this does not
    depend on the format of Chromium's log output, and catches errors the page
    itself could not report (e.g. a syntax error in its script).
    """
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_cdp.log")
    try:
        page = Page(cdp)
        js, screenshot = page.js, page.screenshot
        page.open(page_path.resolve().as_uri() + "#frame=120")
        state = js("({frame: acausal2d.frame, n: acausal2d.nframes, playing: acausal2d.playing,"
                   " scrub: document.getElementById('scrub').value,"
                   " max: document.getElementById('scrub').max,"
                   " time: document.getElementById('time').textContent})")
        assert state == {"frame": 120, "n": 401, "playing": False, "scrub": "120", "max": "400",
                         "time": state["time"]}
        assert state["time"].startswith("t = 0.600 s")
        img_a = screenshot("browser_frame120.png")

        assert js("acausal2d.setFrame(250)") == 250
        assert js("acausal2d.frame") == 250
        # scrubbing with the range input
        js("(() => { const s = document.getElementById('scrub'); s.value = '40';"
           " s.dispatchEvent(new Event('input')); })()")
        assert js("acausal2d.frame") == 40
        assert js("acausal2d.setFrame(1e6)") == 400  # clamped
        js("acausal2d.setFrame(40)")
        img_b = screenshot("browser_frame40.png")
        assert_canvas_drawn(img_a, "frame 120")
        assert_canvas_drawn(img_b, "frame 40")
        assert_differ(img_a, img_b)

        # real-time playback at 4x: 0.4 s wall clock is about 1.6 s of the 2 s scene
        js("document.getElementById('speed').value = '4';"
           "document.getElementById('speed').dispatchEvent(new Event('change'));"
           "acausal2d.setFrame(0); acausal2d.play()")
        assert js("acausal2d.playing") is True
        assert js("document.getElementById('play').textContent") == "Pause"
        js("new Promise(r => setTimeout(r, 400))")
        js("acausal2d.pause()")
        frame = js("acausal2d.frame")
        assert 60 <= frame <= 400, frame
        time.sleep(0.1)
        assert js("acausal2d.frame") == frame and js("acausal2d.playing") is False

        # the canvas follows the window size
        page.resize(500, 700)
        js("new Promise(r => requestAnimationFrame(() => setTimeout(r, 50)))")
        size = js("[document.getElementById('view').width, document.getElementById('view').height,"
                  " window.innerHeight]")
        assert size[0] == 500 and 600 <= size[1] < size[2] == 700, size

        assert js("acausal2d.errors") == []
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()


def test_browser_screenshot_cli(page_path, tmp_path):
    """The plain command-line way: two ``--screenshot`` runs of the page at
    ``#frame=0`` and ``#frame=200`` (the page reads the initial frame from the
    URL fragment), run in parallel::

        /usr/bin/chromium --headless --no-sandbox --disable-gpu --disable-quic
            --no-first-run --disable-background-networking --disable-component-update
            --disable-sync --window-size=800,600 --user-data-dir=<tmp>
            --screenshot=<png> --enable-logging=stderr --v=0 file://...#frame=N

    Checks: both PNGs show a drawing, they differ, and Chromium logged no
    console message at all (``--enable-logging=stderr`` prints every console
    message and uncaught exception as a ``:CONSOLE`` line; the page itself
    never writes to the console, so any such line is an error).
    """
    images = screenshot_frames(page_path, (0, 200), tmp_path, "cli")
    assert_canvas_drawn(images[0], "frame 0")
    assert_canvas_drawn(images[1], "frame 200")
    assert_differ(images[0], images[1])


def screenshot_frames(page_path, frames, tmp_path, prefix):
    """Screenshots of ``page_path`` at the given frames (``#frame=N``), taken
    in parallel by headless Chromium and saved as artifacts
    ``tests/artifacts/<prefix>_frame<N>.png``; fails on any console message."""
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    runs = []
    for frame in frames:
        png = ARTIFACTS / f"{prefix}_frame{frame}.png"
        if png.exists():
            png.unlink()
        log = open(tmp_path / f"chromium_{prefix}_{frame}.log", "w+b")
        proc = subprocess.Popen(
            [CHROMIUM, *CHROMIUM_FLAGS, f"--user-data-dir={tmp_path / f'profile_{prefix}{frame}'}",
             f"--screenshot={png}", "--enable-logging=stderr", "--v=0",
             pathlib.Path(page_path).resolve().as_uri() + f"#frame={frame}"],
            stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
            start_new_session=True)
        runs.append((frame, png, log, proc))
    images = []
    for frame, png, log, proc in runs:
        try:
            proc.wait(timeout=60)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        log.seek(0)
        text = log.read().decode(errors="replace")
        log.close()
        assert png.exists(), f"no screenshot for frame {frame}; chromium said:\n{text[-3000:]}"
        console = [line for line in text.splitlines() if ":CONSOLE" in line or "Uncaught" in line]
        assert console == [], f"console output at frame {frame}: {console}"
        images.append(read_png(png))
    return images
