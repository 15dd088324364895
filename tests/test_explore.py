"""``acausal2d explore`` (issue 33): the server started as a user starts it
(``acausal2d explore models/piston_engine.py --port 0``), its JSON API, and
its page driven in Debian's headless Chromium (as tests/test_animation.py
drives the animation page; without /usr/bin/chromium the browser test
fails, it does not skip).

The numbers checked are the piston engine's energy (no gravity work, no
friction: E = 0.5 I w^2 + 0.5 m v^2 is constant, 0.3125 J with the model's
values), its dead centres (the piston's x runs between l - r and l + r) and
the run's own error messages."""
import json
import os
import signal
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request

import matplotlib.image as mpimg
import numpy as np
import pytest

from test_animation import ARTIFACTS, DevTools, Page, console_errors, require_chromium
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTOL = 1e-8          # the piston engine's experiment rtol
ENERGY_TOL = 1e-4    # relative: IDA's local rtol 1e-8, global drift over 2 s with room


@pytest.fixture(scope="module")
def server():
    """The explore server on a free port: (url, process); stopped with
    SIGINT (Ctrl-C) at the end, which must end it with exit code 0."""
    proc = subprocess.Popen([sys.executable, "-m", "acausal2d", "explore",
                             "models/piston_engine.py", "--port", "0"], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    page = proc.stdout.readline().strip()
    assert page.startswith("http://127.0.0.1:"), (page, proc.stderr.read() if proc.poll() else "")
    url, _, token = page.partition("?token=")
    assert len(token) >= 32, page                   # the API's token is in the page's URL
    TOKENS[url] = token
    yield url, proc, page
    proc.send_signal(signal.SIGINT)
    try:
        code = proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert code == 0, proc.stderr.read()[-2000:]


TOKENS: dict = {}      # server URL -> its API token (from the printed page URL)


def call(url, path, body=None, raw=None, headers=None):
    """(status, decoded JSON or text) of GET (body None) or POST, sent as
    the page sends it (its token, JSON) unless ``headers`` replace that."""
    data = raw if raw is not None else (None if body is None else json.dumps(body).encode())
    sent = {"X-Acausal2d-Token": TOKENS.get(url, ""), "Content-Type": "application/json"}
    sent.update(headers or {})
    req = urllib.request.Request(url + path, data=data, method="GET" if data is None else "POST",
                                 headers={k: v for k, v in sent.items() if v is not None})
    try:
        with urllib.request.urlopen(req, timeout=120) as r:
            status, text, kind = r.status, r.read().decode(), r.headers.get_content_type()
    except urllib.error.HTTPError as exc:
        status, text, kind = exc.code, exc.read().decode(), exc.headers.get_content_type()
    return status, json.loads(text) if kind == "application/json" else text


def energy(answer, inertia=0.1, mass=3.0):
    s = answer["signals"]
    w, vx, vy = (np.array(s[n], dtype=float) for n in
                 ("revoluteDrive.w", "bodyPiston.vx", "bodyPiston.vy"))
    return 0.5 * inertia * w ** 2 + 0.5 * mass * (vx ** 2 + vy ** 2)


def test_params_list_units_rules_and_ranges(server):
    status, d = call(server[0], "api/params")
    assert status == 200 and d["model"] == "PistonEngine"
    params = {p["name"]: p for p in d["parameters"]}
    m = params["bodyDrive.m"]
    assert m["unit"] == "kg" and m["rule"] == ">= 0"
    assert_copied(m["value"], [1.0])                  # the declared value, passed through
    assert m["range"][0][0] >= 0 and m["range"][0][0] < 1.0 < m["range"][0][1]
    assert params["crank.r"]["unit"] == "m" and len(params["crank.r"]["range"]) == 2
    assert {"name": "prismatic.s", "unit": "m"} in d["signals"]
    assert d["figures"] and 0 < d["stop_time"] <= d["max_stop_time"]


def test_run_conserves_energy_with_changed_parameters(server):
    names = ["revoluteDrive.w", "bodyPiston.vx", "bodyPiston.vy", "bodyPiston.x"]
    status, d = call(server[0], "api/run", {"set": {"bodyDrive.I": 0.2, "bodyPiston.m": 2.0,
                                                     "crank.r": [0.35, 0]},
                                             "stop_time": 2, "signals": names})
    assert status == 200, d
    assert abs(d["time"][-1] - 2.0) < 1e-9 and d["elapsed_s"] > 0 and d["stopped"] is None
    e = energy(d, 0.2, 2.0)
    # at the dead centre (t = 0) the piston stands: E = 0.5 * 0.2 * 2.5^2
    assert np.max(np.abs(e - 0.625)) < ENERGY_TOL * 0.625
    x = np.array(d["signals"]["bodyPiston.x"])       # between l - r and l + r
    assert abs(x.min() - 0.45) < 1e-3 and abs(x.max() - 1.15) < 1e-3
    assert d["set"] == {"bodyDrive.I": 0.2, "bodyPiston.m": 2.0, "crank.r": [0.35, 0]}


def test_csv_export_holds_every_column(server):
    status, text = call(server[0], "api/csv", {"stop_time": 0.5, "intervals": 10})
    assert status == 200
    rows = text.strip().splitlines()
    header = rows[0].split(",")
    assert header[0] == "time" and "revoluteDrive.phi" in header and len(rows) == 12
    assert abs(float(rows[-1].split(",")[0]) - 0.5) < 1e-12


@pytest.mark.parametrize("raw,field,words", [
    (b'{"set": {"crank.len": 1}}', "set.crank.len", ["unknown parameter 'crank.len'"]),
    (b'{"set": {"crank.r": [NaN, 0]}}', "set.crank.r", ["not finite"]),
    (b'{"set": {"bodyPiston.m": -2}}', "set.bodyPiston.m", ["breaks its rule >= 0"]),
    (b'{"set": {"prismatic.r": [0, 0]}}', "set.prismatic.r", ["nonzero length"]),
    (b'{"set": {"crank.r": 0.3}}', "set.crank.r", ["takes 2 values"]),
    (b'{"set": [1]}', "set", ["must be an object"]),
    (b'{"stop_time": 1e9}', "stop_time", ["at most 100 s", "--max-stop-time"]),
    (b'{"stop_time": -1}', "stop_time", ["above 0 s"]),
    (b'{"stop_time": Infinity}', "stop_time", ["finite"]),
    (b'{"stop_time": "2"}', "stop_time", ["must be a number"]),
    (b'{"intervals": 2.5}', "intervals", ["whole number"]),
    (b'{"signals": ["prismatic.q"]}', "signals", ["no signal 'prismatic.q'", "prismatic.s"]),
    (b'{"stop_tim": 2}', "stop_tim", ["unknown field", "stop_time"]),
    (b'{"scene": "yes"}', "scene", ["true or false"]),
    (b'{"session": 5}', "session", ["string"]),
    (b'{"set": {"crank.r": [0.3, 0]}', "body", ["malformed JSON"]),
    (b'[1, 2]', "body", ["JSON object"]),
])
def test_bad_input_answers_400_naming_the_field(server, raw, field, words):
    status, d = call(server[0], "api/run", raw=raw)
    assert status == 400, d
    assert d["field"] == field and d["error"].startswith(field + ":")
    for w in words:
        assert w in d["error"], d["error"]
    assert call(server[0], "api/params")[0] == 200           # still serving


def test_failed_run_answers_its_own_message(server):
    # the crank points up 1 m: the 0.8 m rod cannot reach the piston's guide at y = 0
    status, d = call(server[0], "api/run", {"set": {"crank.r": [0, 1.0]}})
    assert status == 422
    assert "No consistent initial values" in d["error"] and "rod" in d["error"]
    assert call(server[0], "api/run", {"stop_time": 0.1})[0] == 200


def test_newer_run_of_a_session_stops_the_running_one(server):
    """A long run (100 s at rtol 1e-8, seconds of work) is stopped when the
    same session asks for another: the earlier (by the server's run
    numbers) answers 409, the later 200.  Under a heavy load the long
    request may reach the server after the short one, and on a fast machine
    it may be done before the short one arrives: the experiment is repeated
    with other delays (at most six times)."""
    for delay in (0.05, 0.2, 0.5, 0.05, 0.2, 0.5):   # the long request must reach the server
        answers = {}                                 # first and still be running: try delays

        def long_run():
            answers["long"] = call(server[0], "api/run", {"stop_time": 100, "intervals": 20000,
                                                          "session": "a"})
        t = threading.Thread(target=long_run)
        t.start()
        time.sleep(delay)
        answers["short"] = call(server[0], "api/run", {"stop_time": 0.2, "session": "a"})
        t.join(timeout=300)
        if answers["long"][1]["run"] < answers["short"][1]["run"] and answers["long"][0] == 409:
            break
    assert answers["long"][1]["run"] < answers["short"][1]["run"], "the long run never came first"
    assert answers["short"][0] == 200
    assert answers["long"][0] == 409 and answers["long"][1]["superseded"] is True


PIN_XY = ["revoluteDisc.frame_a.x", "revoluteDisc.frame_a.y"]     # the crank pin


def test_drag_moves_the_start_position_on_the_dae(server):
    """Dragging the crank pin (0.3 m from the origin) towards (0, 0.5): the
    nearest assembled position has the crank at 90 degrees, the pin at
    (0, 0.3); the run from there starts there and keeps its energy."""
    status, d = call(server[0], "api/start", {"drag": {"x": PIN_XY[0], "y": PIN_XY[1],
                                                       "to": [0.0, 0.5]}})
    assert status == 200, d
    phi = d["start"]["revoluteDrive.phi"]
    assert abs(phi - np.pi / 2) < 1e-2      # the least-squares target is off the circle
    status, run = call(server[0], "api/run", {"start": d["start"], "stop_time": 1,
                                              "signals": PIN_XY + ["revoluteDrive.w",
                                                                   "bodyPiston.vx", "bodyPiston.vy"]})
    assert status == 200, run
    x0, y0 = run["signals"][PIN_XY[0]][0], run["signals"][PIN_XY[1]][0]
    assert abs(np.hypot(x0, y0) - 0.3) < 1e-9 and abs(np.arctan2(y0, x0) - phi) < 1e-9
    e = energy(run)
    assert np.max(np.abs(e - e[0])) < ENERGY_TOL * e[0]
    assert e[0] > 0.3125 * (1 + 1e-3)            # the piston moves at this start


def test_drag_reaches_a_reachable_point(server):
    status, d = call(server[0], "api/start", {"drag": {"x": "bodyPiston.x", "y": "bodyPiston.y",
                                                       "to": [0.9, 0.0]}})
    assert status == 200, d
    # the piston at x = 0.9: s = -0.9 and cos(phi) from the triangle 0.3, 0.8, 0.9
    assert abs(d["start"]["prismatic.s"] + 0.9) < 1e-6
    c = (0.3 ** 2 + 0.9 ** 2 - 0.8 ** 2) / (2 * 0.3 * 0.9)
    assert abs(np.cos(d["start"]["revoluteDrive.phi"]) - c) < 1e-6


@pytest.mark.parametrize("body,field", [
    ({"drag": {"x": "nope.x", "y": PIN_XY[1], "to": [0, 0]}}, "drag.x"),
    ({"drag": {"x": PIN_XY[0], "y": PIN_XY[1], "to": [0, None]}}, "drag.to"),
    ({"drag": {"x": PIN_XY[0], "y": PIN_XY[1]}}, "drag"),
    ({"start": {"revoluteDrive.w2": 1.0}, "drag": {"x": PIN_XY[0], "y": PIN_XY[1],
                                                   "to": [0, 0]}}, "start.revoluteDrive.w2"),
])
def test_bad_drag_answers_400(server, body, field):
    status, d = call(server[0], "api/start", body)
    assert status == 400 and d["field"] == field, d


def test_run_refuses_a_drag_and_bad_start_values(server):
    status, d = call(server[0], "api/run", {"drag": {"x": "a", "y": "b", "to": [0, 0]}})
    assert status == 400 and d["field"] == "drag" and "/api/start" in d["error"]
    status, d = call(server[0], "api/run", {"start": {"revoluteDrive.phi": "up"}})
    assert status == 400 and d["field"] == "start.revoluteDrive.phi"


# --------------------------------------------------------------------------
# the page in a headless Chromium

def wait_for(page, expr, timeout=60):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if page.js(expr):
            return
        time.sleep(0.05)
    raise AssertionError("timed out waiting for %s; error: %s" % (expr, page.js("explore.error")))


def shot(page, name):
    data = page.cdp.call("Page.captureScreenshot", {"format": "png"}, session=page.session)
    path = ARTIFACTS / name
    import base64
    path.write_bytes(base64.b64decode(data["data"]))
    return mpimg.imread(str(path))[:, :, :3].astype(float)


def assert_not_blank(img):
    """More than 3 % of the pixels differ clearly from the most common
    (background) colour, and the steel-blue links of the animation are there."""
    colours, counts = np.unique(img.reshape(-1, 3), axis=0, return_counts=True)
    ink = np.max(np.abs(img - colours[np.argmax(counts)]), axis=2) > 0.15
    assert ink.mean() > 0.03, "the page looks blank (%d drawn pixels)" % ink.sum()
    steel = np.all(np.abs(img - np.array([70, 130, 180]) / 255) < 0.06, axis=2)
    assert steel.sum() > 200, "no steel-blue link or curve pixels"


def move_slider(page, label, fraction):
    """Click the range input ``label`` at ``fraction`` of its width (a real
    mouse press and release, as a user moves a slider)."""
    r = page.js("(function(){var b=document.querySelector('input[data-param=\"%s\"]')"
                ".getBoundingClientRect();return [b.left,b.top,b.width,b.height];})()" % label)
    x, y = r[0] + 8 + fraction * (r[2] - 16), r[1] + r[3] / 2
    page.mouse("mousePressed", x, y)
    page.mouse("mouseReleased", x, y, buttons=0)


def scene_signal(page, name):
    return page.js("Array.from(document.getElementById('anim').contentWindow"
                   ".acausal2d.scene.signals[%s])" % json.dumps(name))


def drag_crank_pin(page, r):
    """At the first frame, press the mouse on the crank pin (r, 0) and let
    go at (0, r): the crank turned by 90 degrees."""
    page.js("(function(){var a=document.getElementById('anim').contentWindow.acausal2d;"
            "a.pause();a.setFrame(0);})()")
    box = page.js("(function(){var f=document.getElementById('anim'),b=f.getBoundingClientRect(),"
                  "c=f.contentWindow.document.getElementById('view').getBoundingClientRect();"
                  "return [b.left+c.left,b.top+c.top];})()")
    a, b = (page.js("document.getElementById('anim').contentWindow.acausal2d.toScreen(%r,%r)"
                    % xy) for xy in ((r, 0.0), (0.0, r)))
    page.mouse("mousePressed", box[0] + a[0], box[1] + a[1])
    page.mouse("mouseMoved", (box[0] + a[0] + box[0] + b[0]) / 2, (box[1] + a[1] + box[1] + b[1]) / 2)
    page.mouse("mouseReleased", box[0] + b[0], box[1] + b[1], buttons=0)


def test_page_slider_changes_curve_and_animation_pin_and_error(server, tmp_path):
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "explore_cdp.log")
    try:
        page = Page(cdp)
        page.resize(1200, 800)
        page.open(server[2])
        wait_for(page, "window.explore && explore.runs >= 1 && explore.sceneLoads >= 1")
        first = shot(page, "explore_first.png")
        assert_not_blank(first)
        s0 = np.array(page.js("explore.current.data.signals['prismatic.s']"), dtype=float)
        anim0 = scene_signal(page, "revoluteDisc.frame_a.x")
        assert abs(s0.min() + 1.1) < 1e-3 and abs(s0.max() + 0.5) < 1e-3      # -(l +- r)

        move_slider(page, "crank.r[0]", 0.85)
        wait_for(page, "explore.runs >= 2 && explore.sceneLoads >= 2 && !explore.busy")
        r = page.js("explore.values['crank.r'][0]")
        assert r > 0.5, r
        s1 = np.array(page.js("explore.current.data.signals['prismatic.s']"), dtype=float)
        assert abs(s1.min() + (0.8 + r)) < 1e-3 and abs(s1.max() + (0.8 - r)) < 1e-3
        assert page.js("explore.previous.data.signals['prismatic.s'].length") == len(s0)
        anim1 = scene_signal(page, "revoluteDisc.frame_a.x")
        assert abs(max(anim1) - r) < 1e-3 and abs(max(anim0) - 0.3) < 1e-3   # the crank pin
        assert "--set crank.r=%s,0" % page.js("(+explore.values['crank.r'][0].toPrecision(6))") \
            in page.js("explore.setOptions()")

        page.js("document.getElementById('export-set').click()")
        assert page.js("document.getElementById('export').value").startswith(
            "acausal2d simulate models/piston_engine.py --set crank.r=")
        page.js("document.getElementById('export-csv').click()")
        wait_for(page, "explore.csvBytes > 0")
        # time + every column but derivatives, 501 rows of 17 digits each: far above 100 kB
        assert page.js("explore.csvBytes") > 100000

        page.js("document.getElementById('pin').click()")
        assert page.js("explore.pins.length") == 1
        pinned = shot(page, "explore_pinned.png")
        assert_not_blank(pinned)
        assert (np.max(np.abs(pinned - first), axis=2) > 0.15).sum() > 2000

        drag_crank_pin(page, r)
        wait_for(page, "explore.drags >= 1 && explore.runs >= 3 && !explore.busy")
        phi = page.js("explore.starts['revoluteDrive.phi']")
        assert abs(phi - np.pi / 2) < 0.05, phi        # a few pixels of the drop point
        assert abs(page.js("explore.current.data.signals['revoluteDrive.phi'][0]") - phi) < 1e-9

        page.js("(function(){var n=document.querySelector('input[aria-label=\"rod.r[0] value\"]');"
                "n.value='0.1';n.dispatchEvent(new Event('change'));})()")
        wait_for(page, "explore.error !== null")
        text = page.js("document.getElementById('error').textContent")
        assert "No consistent initial values" in text and page.js(
            "!document.getElementById('error').hidden")
        errors = console_errors(cdp.events)      # the browser logs the refused run itself
        assert [e for e in errors if "status of 422" not in e] == [] and len(errors) == 1
    finally:
        cdp.close()


def test_bench_explore_small_prints_its_table():
    """benchmarks/bench_explore.py in its small mode: every row is there with
    positive finite numbers, the concurrent answers equal the runs made
    alone (within rtol) and the memory stays bounded (speed targets are the
    benchmark's, never checked here)."""
    out = subprocess.run([sys.executable, os.path.join(ROOT, "benchmarks", "bench_explore.py"),
                          "--small"], capture_output=True, text=True, cwd=ROOT, timeout=900)
    assert out.returncode == 0, out.stdout + out.stderr[-3000:]
    rows = out.stdout.splitlines()
    for label in ("round trip of a change", "of which the run itself", "with the animation page",
                  "worst diff", "answers compared", "server memory", "memory growth"):
        line = next((r for r in rows if label in r), None)
        assert line is not None, (label, out.stdout)
        numbers = [float(x) for x in line.split()[-2:]
                   if x.lstrip("-").replace(".", "", 1).isdigit()]
        # memory may also shrink between runs (the allocator gives pages back)
        floor = -np.inf if label == "memory growth" else 0.0
        assert numbers and all(np.isfinite(v) and v >= floor for v in numbers), line
    assert "memory bounded (last half adds < 20 MB): yes" in out.stdout
    assert "concurrent answers equal to the runs made alone: yes" in out.stdout


def test_random_bodies_are_accepted_or_refused_naming_a_field():
    """300 random request bodies (fixed seed) through the request checks of
    the server: each is a run spec or a BadRequest naming a field that is
    in the body (or "body"); no other exception escapes."""
    import random
    from acausal2d.compiled import compile_model
    from acausal2d.explore.requests import BadRequest, parse_run
    from acausal2d.io.loader import load_model
    cm = compile_model(load_model(os.path.join(ROOT, "models", "piston_engine.py")))
    defaults = {"stop_time": 10.0, "max_stop_time": 100.0, "intervals": 500, "signals": []}
    rng = random.Random(33)
    values = [None, True, 0, -1, 2.5, 1e308, float("nan"), float("inf"), "x", [], [1], [0.3, 0],
              [0.3, "a"], {}, {"a": 1}, 20001, 1e-300]
    keys = ["set", "stop_time", "intervals", "signals", "scene", "session", "start", "drag", "zz"]
    names = ["crank.r", "bodyPiston.m", "prismatic.r", "world.g", "nope", "revoluteDrive.phi"]
    refused = 0
    for _ in range(300):
        body = {k: rng.choice(values) for k in rng.sample(keys, rng.randint(0, 4))}
        if rng.random() < 0.5:
            body["set"] = {rng.choice(names): rng.choice(values) for _ in range(rng.randint(1, 3))}
        raw = json.dumps(body).encode() if rng.random() < 0.9 else json.dumps(body).encode()[:-1]
        try:
            spec = parse_run(raw, cm, defaults)
        except BadRequest as exc:
            refused += 1
            assert exc.field == "body" or exc.field.split(".")[0] in body, (body, exc.field)
            continue
        assert 0 < spec.stop_time <= 100.0 and 1 <= spec.intervals <= 20000
    assert 0 < refused < 300


def test_cli_refuses_a_busy_port_and_a_bad_host(capsys):
    """Checked before the model is compiled: exit code 2 naming the option."""
    import socket
    from acausal2d.cli import main
    with socket.socket() as busy:
        busy.bind(("127.0.0.1", 0))
        busy.listen()
        port = busy.getsockname()[1]
        assert main(["explore", "models/piston_engine.py", "--port", str(port)]) == 2
        assert "--port %d" % port in capsys.readouterr().err
    assert main(["explore", "models/piston_engine.py", "--host", "no.such.host.invalid"]) == 2
    assert "--host no.such.host.invalid" in capsys.readouterr().err
    assert main(["explore", "models/piston_engine.py", "--port", "70000"]) == 2
    assert "--port must be 0 ... 65535" in capsys.readouterr().err


def test_simulate_takes_start_values():
    """CompiledModel.simulate(start=...): a fixed start value replaced stays
    fixed (the crank starts at 0.5 rad), a replaced start speed changes the
    energy to 0.5 I w0^2 at the dead centre (the piston stands there); an
    unknown name is refused with the names that take start values."""
    from acausal2d import Acausal2dError
    from acausal2d.compiled import compile_model
    from acausal2d.io.loader import load_model
    cm = compile_model(load_model(os.path.join(ROOT, "models", "piston_engine.py")))
    assert "revoluteDrive.phi" in cm.start_names and "prismatic.s" in cm.start_names
    res = cm.simulate(stop_time=0.5, start={"revoluteDrive.phi": 0.5})
    assert abs(res["revoluteDrive.phi"][0] - 0.5) < 1e-12
    assert abs(res["prismatic.s"][0] + (0.3 * np.cos(0.5) + np.sqrt(0.64 - (0.3 * np.sin(0.5)) ** 2))) < 1e-8
    res = cm.simulate(stop_time=1.0, start={"revoluteDrive.w": -1.0})
    e = 0.5 * 0.1 * res["revoluteDrive.w"] ** 2 + 1.5 * (res["bodyPiston.vx"] ** 2
                                                         + res["bodyPiston.vy"] ** 2)
    assert np.max(np.abs(e - 0.05)) < ENERGY_TOL * 0.05
    with pytest.raises(Acausal2dError, match="start 'crank.q'.*revoluteDrive.phi"):
        cm.simulate(stop_time=0.1, start={"crank.q": 1.0})
    with pytest.raises(Acausal2dError, match="start revoluteDrive.phi must be finite"):
        cm.simulate(stop_time=0.1, start={"revoluteDrive.phi": float("nan")})
