"""What another local user, a web page or a slider can do (the report
"Nothing a stranger can plant, no slider that does nothing"), each Seen
item by name: a library planted in a cache folder another user created is
refused and never loaded; cross-origin, simple-content-type, foreign-Host
and token-less requests to the live page are refused and start no run;
deep and huge JSON get 400 naming the field; a parameter read while
compiling is refused through every entry point, naming it; constructor
cross-checks hold on values given through ``--set`` and ``params=``; a
name outside Latin-1 round-trips through .mat; the guards before a run."""
import os
import stat
import subprocess
import sys

import numpy as np
import pytest

from acausal2d.runtime import private_dir
from acausal2d.runtime import cbuild, cstore, native, notices

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
OTHER_UID = 65534                      # "nobody": a user that is not the one running the tests
native_only = pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                                 reason="no C compiler or another SUNDIALS")

# ------------------------------------------------------------------ the cache


def _owned_by_another(path):
    """Give ``path`` to another user where the tests run as root (else the
    folder stays the runner's own, and only its mode makes it unsafe)."""
    if os.geteuid() == 0:
        os.chown(path, OTHER_UID, OTHER_UID)


def test_private_dir_is_created_0700(tmp_path):
    path = tmp_path / "a" / "cache"
    assert private_dir.problem(str(path)) is None
    assert stat.S_IMODE(os.lstat(path).st_mode) == 0o700


def test_private_dir_of_ones_own_readable_by_others_is_tightened(tmp_path):
    path = tmp_path / "cache"
    path.mkdir(mode=0o755)
    os.chmod(path, 0o755)
    assert private_dir.problem(str(path)) is None
    assert stat.S_IMODE(os.lstat(path).st_mode) == 0o700


@pytest.mark.parametrize("how", ["world-writable", "group-writable", "symlink", "other-owner"])
def test_private_dir_refuses_what_another_user_could_write(how, tmp_path):
    path = tmp_path / "cache"
    if how == "symlink":
        (tmp_path / "real").mkdir(mode=0o700)
        path.symlink_to(tmp_path / "real")
    else:
        path.mkdir()
        os.chmod(path, {"world-writable": 0o777, "group-writable": 0o770}.get(how, 0o700))
    if how == "other-owner":
        if os.geteuid() != 0:
            pytest.skip("giving a folder to another user needs root")
        _owned_by_another(path)
    why = private_dir.problem(str(path))
    assert why is not None and why.unsafe
    assert str(path) in why.message
    assert ("rm -r" in why.message or "Remove" in why.message or "remove" in why.message)
    if how != "symlink":
        assert stat.S_IMODE(os.lstat(path).st_mode) != 0o700 or how == "other-owner"


PLANT = r"""
#include <stdio.h>
#include <stdlib.h>
__attribute__((constructor)) static void planted(void) {
    FILE *f = fopen(getenv("A2D_PLANT_MARK"), "w");
    if (f) { fputs("planted code ran", f); fclose(f); }
}
"""


def _simulate(env, out):
    return subprocess.run([sys.executable, "-m", "acausal2d", "simulate", PENDULUM, "--out",
                           str(out), "--native", "now"], env=dict(os.environ, **env),
                          capture_output=True, text=True, timeout=600)


@native_only
@pytest.mark.parametrize("owner", ["other-user", "world-writable"])
def test_seen_planted_library_in_a_precreated_fallback_is_refused_and_never_loaded(
        owner, tmp_path):
    """Seen 1: another user creates ``acausal2d-cbuild-<uid>`` in the
    temporary directory first (mode 0777) and plants a library under the
    name the index names, with its digest beside it; the configured cache
    cannot be written, so the run falls back - and must refuse that folder."""
    if owner == "other-user" and os.geteuid() != 0:
        pytest.skip("giving a folder to another user needs root")
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    planted = tmp / ("acausal2d-cbuild-%d" % os.getuid())
    first = _simulate({"ACAUSAL2D_CACHE_DIR": str(planted), "TMPDIR": str(tmp)},
                      tmp_path / "first")
    assert first.returncode == 0, first.stderr
    libs = [n for n in os.listdir(planted) if n.startswith("a2d_model") and n.endswith(".so")]
    assert libs, os.listdir(planted)
    src = tmp_path / "plant.c"
    src.write_text(PLANT)
    for name in libs:          # the attacker's library under the indexed name, its digest beside
        lib = planted / name
        subprocess.run([cbuild.find_compiler(), "-shared", "-fPIC", "-o", str(lib), str(src)],
                       check=True)
        (planted / (name + cstore.DIGEST)).write_text(cstore.file_digest(str(lib)))
        os.chmod(lib, 0o777)
    os.chmod(planted, 0o777)
    if owner == "other-user":
        _owned_by_another(planted)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    mark = tmp_path / "mark"
    proc = _simulate({"ACAUSAL2D_CACHE_DIR": str(blocker / "cache"), "TMPDIR": str(tmp),
                      "XDG_RUNTIME_DIR": "", "A2D_PLANT_MARK": str(mark)}, tmp_path / "out")
    assert not mark.exists(), "the planted library was loaded"
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    assert str(planted) in proc.stderr and "not used" in proc.stderr, proc.stderr
    assert "undefined symbol" not in proc.stderr
    first_phi = np.loadtxt(tmp_path / "first" / "result.csv", delimiter=",", skiprows=1)
    again = np.loadtxt(tmp_path / "out" / "result.csv", delimiter=",", skiprows=1)
    scale = 1.0 + np.max(np.abs(first_phi))
    assert np.max(np.abs(again - first_phi)) <= 10 * 1e-6 * scale     # the experiment's rtol


def test_a_cached_library_writable_by_others_is_not_loaded(tmp_path, monkeypatch):
    monkeypatch.setenv(cstore.CACHE_ENV, str(tmp_path / "cache"))
    folder = cstore.folder()
    lib = os.path.join(folder, "x.so")
    with open(lib, "wb") as fh:
        fh.write(b"\x7fELF planted")
    with open(lib + cstore.DIGEST, "w") as fh:
        fh.write(cstore.file_digest(lib))
    assert cstore.verified(lib)
    os.chmod(lib, 0o666)
    assert not cstore.verified(lib)
    assert not os.path.exists(lib)

# ------------------------------------------------------------ the live page


def _start_server():
    """(base URL, process, token) of an explore server of the piston
    engine on a free port, started as a user starts it."""
    proc = subprocess.Popen([sys.executable, "-m", "acausal2d", "explore",
                             "models/piston_engine.py", "--port", "0"], cwd=ROOT,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    page = proc.stdout.readline().strip()
    assert page.startswith("http://127.0.0.1:"), (page, proc.stderr.read() if proc.poll() else "")
    base, _, token = page.partition("?token=")
    return base, proc, token


def _stop_server(proc):
    """Ctrl-C, as a user stops it; its stderr."""
    proc.send_signal(2)
    try:
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
    return proc.stderr.read()


@pytest.fixture(scope="module")
def live():
    """The explore server of the piston engine (:func:`_start_server`)."""
    base, proc, token = _start_server()
    yield base, proc, token
    _stop_server(proc)


def _http(base, path, body=b"", method="POST", headers=()):
    """(status, JSON answer) of one raw HTTP request with exactly ``headers``."""
    import http.client
    import json
    host, port = base.split("//")[1].rstrip("/").split(":")
    conn = http.client.HTTPConnection(host, int(port), timeout=120)
    try:
        conn.putrequest(method, path, skip_host=True, skip_accept_encoding=True)
        for k, v in headers:
            conn.putheader(k, v)
        if method == "POST" and "Content-Length" not in dict(headers):
            conn.putheader("Content-Length", str(len(body)))
        conn.endheaders(body if method == "POST" else None)
        r = conn.getresponse()
        text = r.read().decode()
    finally:
        conn.close()
    return r.status, (json.loads(text) if r.getheader("content-type", "").startswith(
        "application/json") else text)


def _runs(live):
    """The server's run counter: the "run" number of a fresh good run."""
    base, _, token = live
    host = base.split("//")[1].rstrip("/")
    status, d = _http(base, "/api/run", b'{"stop_time": 0.05, "intervals": 2}', headers=[
        ("Host", host), ("Content-Type", "application/json"), ("X-Acausal2d-Token", token)])
    assert status == 200, d
    return d["run"]


@pytest.mark.parametrize("path", ["/api/run", "/api/csv", "/api/start"])
@pytest.mark.parametrize("attack,status", [
    ("evil-origin", 403), ("text-plain", 415), ("foreign-host", 403), ("no-token", 403),
    ("wrong-token", 403), ("cross-site", 403), ("form", 415)])
def test_seen_cross_origin_simple_and_foreign_host_requests_start_no_run(live, path, attack,
                                                                        status):
    """Seen 2: a page from another origin posting text/plain (no preflight),
    a DNS-rebinding page (foreign Host), a request without the token: each
    is refused and starts no run."""
    base, _, token = live
    host = base.split("//")[1].rstrip("/")
    body = b'{"stop_time": 0.05, "intervals": 2}'
    if path == "/api/start":
        body = b'{"drag": {"x": "bodyPiston.x", "y": "bodyPiston.y", "to": [0.8, 0]}}'
    headers = {"Host": host, "Content-Type": "application/json", "X-Acausal2d-Token": token}
    if attack == "evil-origin":
        headers["Origin"] = "http://evil.example"
    elif attack in ("text-plain", "form"):
        headers["Content-Type"] = "text/plain" if attack == "text-plain" else \
            "application/x-www-form-urlencoded"
    elif attack == "foreign-host":
        headers["Host"] = "rebind.attacker.example:%s" % host.split(":")[1]
    elif attack == "no-token":
        del headers["X-Acausal2d-Token"]
    elif attack == "wrong-token":
        headers["X-Acausal2d-Token"] = token[:-1] + ("A" if token[-1] != "A" else "B")
    elif attack == "cross-site":
        headers["Sec-Fetch-Site"] = "cross-site"
    before = _runs(live)
    got, d = _http(base, path, body, headers=list(headers.items()))
    assert got == status, d
    assert isinstance(d, dict) and d["error"] and "Traceback" not in d["error"]
    assert _runs(live) == before + 1            # only the counting run ran


def test_seen_foreign_host_cannot_read_the_model(live):
    base, _, token = live
    port = base.rstrip("/").split(":")[-1]
    status, d = _http(base, "/api/params", method="GET", headers=[
        ("Host", "rebind.attacker.example:" + port), ("X-Acausal2d-Token", token)])
    assert status == 403 and "piston" not in str(d).lower()
    status, d = _http(base, "/api/params", method="GET", headers=[("Host", "localhost:" + port)])
    assert status == 403 and "token" in d["error"]
    for host in ("localhost", "127.0.0.1"):
        status, d = _http(base, "/api/params", method="GET", headers=[
            ("Host", "%s:%s" % (host, port)), ("X-Acausal2d-Token", token)])
        assert status == 200 and d["model"] == "PistonEngine"
    status, d = _http(base, "/api/params?token=" + token, method="GET",
                      headers=[("Host", "127.0.0.1:" + port)])
    assert status == 200


@pytest.mark.parametrize("body,field,words", [
    (b'{"stop_time": ' + b"[" * 5000 + b"]" * 5000 + b"}", "body", ["nested too deeply"]),
    (b"[" * 100000 + b"]" * 100000, "body", ["nested too deeply"]),
    (b'{"set": {"crank.r": [[[[1]]]]}}', "set.crank.r[0][0][0]", ["nested too deeply"]),
    (b'{"stop_time": 1' + b"0" * 400 + b"}", "stop_time", ["finite"]),
    (b'{"set": {"bodyPiston.m": 1' + b"0" * 400 + b"}}", "set.bodyPiston.m", ["not finite"]),
    (b'{"start": {"revoluteDrive.phi": 1' + b"0" * 400 + b"}}", "start.revoluteDrive.phi",
     ["finite"]),
    (b'{"intervals": 1e400}', "intervals", ["finite"]),
])
def test_seen_deep_and_huge_json_get_400_naming_the_field(live, body, field, words):
    """Seen 5: 5,000-deep nesting, a 200 kB nested array, a 401-digit
    integer in stop_time, set and start: 400 naming the field."""
    base, proc, token = live
    host = base.split("//")[1].rstrip("/")
    status, d = _http(base, "/api/run", body, headers=[
        ("Host", host), ("Content-Type", "application/json"), ("X-Acausal2d-Token", token)])
    assert status == 400, d
    assert d["field"] == field, d
    assert all(w in d["error"] for w in words), d


def test_seen_a_huge_body_is_refused_before_it_is_read(live):
    """Seen 5: a 50 MiB body declared by Content-Length is refused (413)
    from its headers; one that streams past the limit is cut at it."""
    import socket
    base, proc, token = live
    host = base.split("//")[1].rstrip("/")
    status, d = _http(base, "/api/run", b"", headers=[
        ("Host", host), ("Content-Type", "application/json"), ("X-Acausal2d-Token", token),
        ("Content-Length", str(50 << 20))])
    assert status == 413 and "at most" in d["error"]
    h, port = host.split(":")
    with socket.create_connection((h, int(port)), timeout=30) as s:
        s.sendall(("POST /api/run HTTP/1.1\r\nHost: %s\r\nContent-Type: application/json\r\n"
                   "X-Acausal2d-Token: %s\r\nTransfer-Encoding: chunked\r\n\r\n"
                   % (host, token)).encode())
        chunk = b" " * (1 << 16)
        answer = b""
        try:
            for _ in range(40):          # 2.5 MiB offered, the limit is 1 MiB
                s.sendall(b"%x\r\n%s\r\n" % (len(chunk), chunk))
        except OSError:
            pass                         # the server answered and closed
        s.settimeout(30)
        try:
            answer = s.recv(4096)
        except OSError:
            pass
    assert answer.startswith(b"HTTP/1.1 413"), answer[:200]


def test_seen_a_client_leaving_mid_body_is_one_line():
    import socket
    import time
    base, proc, token = _start_server()
    live = (base, proc, token)
    host = base.split("//")[1].rstrip("/")
    h, port = host.split(":")
    with socket.create_connection((h, int(port)), timeout=30) as s:
        s.sendall(("POST /api/run HTTP/1.1\r\nHost: %s\r\nContent-Type: application/json\r\n"
                   "X-Acausal2d-Token: %s\r\nContent-Length: 1000\r\n\r\n{\"stop"
                   % (host, token)).encode())
        time.sleep(0.3)
    time.sleep(0.5)
    assert _runs(live) > 0                # still serving
    err = _stop_server(proc)
    assert "Traceback" not in err and "ClientDisconnect" not in err, err
    assert err.count("went away before its request") == 1, err


def test_seen_slow_headers_are_cut_off(live):
    """Seen 5: a client that never finishes its headers is disconnected
    after the header deadline (uvicorn alone waits for ever)."""
    import socket
    import time
    from acausal2d.explore.guard import HEADER_SECONDS
    base, proc, token = live
    h, port = base.split("//")[1].rstrip("/").split(":")
    with socket.create_connection((h, int(port)), timeout=HEADER_SECONDS + 20) as s:
        t0 = time.monotonic()
        s.sendall(b"GET /api/params HTTP/1.1\r\nHost: ")
        try:
            got = s.recv(100)
        except ConnectionResetError:
            got = b""
        assert got == b""                        # closed by the server
        assert time.monotonic() - t0 < HEADER_SECONDS + 15

# ------------------------------------------------ parameters: structural, cross-checks

CHECKED_MODELS = '''
from acausal2d import Component, start
from acausal2d.library import rotational as rot, signals


class Blocks(Component):
    """A step through a Limiter, and a P controller with its output limits."""
    experiment = {"stop_time": 0.1, "intervals": 4}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sp = signals.Step(height=5.0, startTime=0.0)
        self.lim = signals.Limiter(uMax=1.0, uMin=-1.0)
        self.pid = signals.LimPID(controllerType="P", k=1.0, yMax=1.0, yMin=-1.0)
        self.zero = signals.Constant(k=0.0)
        self.connect(self.sp.y, self.lim.u)
        self.connect(self.sp.y, self.pid.u_s)
        self.connect(self.zero.y, self.pid.u_m)


class Freewheel(Component):
    """Inertia a driven by +4 N m through a OneWayClutch to inertia b."""
    experiment = {"stop_time": 0.2, "intervals": 4}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.a = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.b = rot.Inertia(J=3.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.owc = rot.OneWayClutch(mu_pos=[[0.0, 0.5]], cgeo=1.0, fn_max=100.0)
        self.eng = signals.Constant(k=1.0)
        self.tau = signals.Constant(k=4.0)
        self.src = rot.Torque()
        self.connect(self.eng.y, self.owc.f_normalized)
        self.connect(self.a.flange_b, self.owc.flange_a)
        self.connect(self.owc.flange_b, self.b.flange_a)
        self.connect(self.tau.y, self.src.tau_in)
        self.connect(self.src.flange, self.a.flange_a)
'''


@pytest.fixture(scope="module")
def checked_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("models") / "checked.py"
    path.write_text(CHECKED_MODELS)
    return path


def _cli(argv, capfd):
    from acausal2d.cli import main
    code = main([str(a) for a in argv])
    out, err = capfd.readouterr()
    assert "Traceback" not in out + err
    return code, out, err


@pytest.mark.parametrize("model,setting,words", [
    ("Blocks", "lim.uMax=-2", ["Limiter", "uMax = -2", "below uMin"]),
    ("Blocks", "lim.uMin=3", ["Limiter", "uMin = 3"]),
    ("Blocks", "pid.yMax=-5", ["LimPID", "yMax = -5", "below yMin"]),
    ("Freewheel", "owc.cgeo=0", ["OneWayClutch", "cgeo = 0"]),
])
def test_seen_set_of_a_cross_check_is_refused_like_the_constructor(
        model, setting, words, checked_file, tmp_path, capfd):
    """Seen 4: ``--set`` of ``uMax < uMin``, ``yMax < yMin``, ``cgeo = 0``
    is refused (exit 2, the constructor's message), no result is written."""
    code, out, err = _cli(["simulate", checked_file, "--model", model, "--set", setting,
                           "--out", tmp_path / "out"], capfd)
    assert code == 2, err
    assert all(w in err for w in words), err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
    code, _, err = _cli(["simulate", checked_file, "--model", model, "--out",
                         tmp_path / "good"], capfd)
    assert code == 0, err


def test_seen_params_of_a_cross_check_is_refused_in_the_api(checked_file):
    import acausal2d
    from acausal2d.compiled import compile_model
    from acausal2d.io.loader import load_model
    cm = compile_model(load_model(str(checked_file), "Blocks"))
    for params, words in (({"pid.yMax": -5.0}, "yMax = -5"), ({"lim.uMin": 3.0}, "uMin = 3"),
                          ({"pid.yMin": 2.0}, "yMin = 2")):
        with pytest.raises(acausal2d.ModelDefinitionError) as err:
            cm.simulate(params=params)
        assert words in str(err.value)
    res = cm.simulate(params={"pid.yMax": 2.0, "lim.uMax": 3.0})
    assert abs(res["pid.y.u"][-1] - 2.0) <= 1e-9 and abs(res["lim.y.u"][-1] - 3.0) <= 1e-9


HANGING = '''
import math
from acausal2d import Component, start
from acausal2d.library import signals
from acausal2d.library.belt import Belt, Pulley, RopeDrive, connect_band
from acausal2d.library.planar import Body, Fixed

M_PULLEY = %r


class Hanging(Component):
    """A pulley (r 0.05 m) on a free 4 kg body hangs in a rope anchored at
    (-r, 0) and held at (+r, 0): both spans vertical; the spans start
    stretched for the default masses, so another pulley mass moves it."""
    experiment = {"stop_time": 0.05, "intervals": 10, "rtol": 1e-8}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.body = Body(m=4.0, I=0.05, x=start(0.0, fixed=True), y=start(-1.0, fixed=True),
                         phi=start(0.0, fixed=True))
        self.p = Pulley(r=0.05, w_i=-1, m=M_PULLEY, J=1e-4)
        self.connect(self.body.frame_a, self.p.ctr2D1)
        eps0 = (4.0 + 1.0) * 9.81 / 2 / 1e6
        self.span1 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.span2 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.anchor = Fixed(r=(-0.05, 0.0))
        self.pull = RopeDrive(x0=0.05, y0=0.0, angle=math.pi / 2)
        self.sig = signals.Constant(k=0.0)
        self.connect(self.sig.y, self.pull.s_in)
        self.connect(self.anchor.frame, self.span1.ctr2D1)
        connect_band(self, self.span1, 2, self.p, 1)
        connect_band(self, self.span2, 1, self.p, 2)
        self.connect(self.span2.ctr2D2, self.pull.frame)
'''


@pytest.fixture(scope="module")
def hanging(tmp_path_factory):
    """(model file with pulley mass 1 kg, the same with 3 kg, the compiled 1 kg one)."""
    from acausal2d.compiled import compile_model
    from acausal2d.io.loader import load_model
    folder = tmp_path_factory.mktemp("hanging")
    one, three = folder / "one.py", folder / "three.py"
    one.write_text(HANGING % 1.0)
    three.write_text(HANGING % 3.0)
    return one, three, compile_model(load_model(str(one)))


def _close(a, b, rtol=1e-8):
    scale = 1.0 + float(np.max(np.abs(b)))
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b)))) <= 100 * rtol * scale


def test_seen_pulley_mass_is_structural_and_params_recompile(hanging, capfd, monkeypatch):
    """Seen 3: the pulley's m decides whether it has mass (read while
    compiling): simulate(params=) compiles the model again and says so; its
    motion is that of the model written with m = 3, not the unchanged one."""
    monkeypatch.setattr(notices, "_said", set())       # the notice is said once per process
    one, three, cm = hanging
    assert {"p.m", "p.J"} <= cm.structural
    base = cm.simulate()
    capfd.readouterr()
    changed = cm.simulate(params={"p.m": 3.0})
    err = capfd.readouterr().err
    assert "p.m is read while Hanging is compiled; it is compiled again with p.m = 3" in err
    from acausal2d.compiled import compile_model
    from acausal2d.io.loader import load_model
    want = compile_model(load_model(str(three))).simulate()
    for name in ("span1.F", "body.y"):
        assert _close(changed[name], want[name]), name
    # the unchanged model's answer is far from it: the extra 2 kg pull 9.81 N more
    assert abs(changed["span1.F"][-1] - base["span1.F"][-1]) > 1.0
    with pytest.raises(Exception) as err:         # the vector of the compiled model: refused
        cm.parameter_values({"p.m": 3.0})
    assert "p.m" in str(err.value) and "compiled" in str(err.value)
    assert len(cm.parameter_values({"p.m": 1.0})) == len(cm.parameters)   # unchanged: fine


def test_seen_pulley_mass_through_set_recompiles(hanging, tmp_path, capfd, monkeypatch):
    import csv
    monkeypatch.setattr(notices, "_said", set())       # the notice is said once per process
    one, three, cm = hanging
    code, out, err = _cli(["simulate", one, "--set", "p.m=3", "--out", tmp_path / "a"], capfd)
    assert code == 0, err
    assert "compiled again with p.m = 3" in err
    code, out, err = _cli(["simulate", three, "--out", tmp_path / "b"], capfd)
    assert code == 0, err

    def col(folder):
        with open(folder / "result.csv", newline="") as fh:
            return np.array([float(r["span1.F"]) for r in csv.DictReader(fh)])
    assert _close(col(tmp_path / "a"), col(tmp_path / "b"))


def test_seen_pulley_mass_through_a_sweep_recompiles(hanging):
    import acausal2d
    one, three, cm = hanging
    from acausal2d.io.loader import load_model
    from acausal2d.compiled import compile_model
    table = acausal2d.sweep(load_model(str(one)), vary={"p.m": [1.0, 3.0]}, stop_time=0.05,
                            outputs=["span1.F"])
    assert not table.failed
    rows = sorted(table.rows, key=lambda r: r["p.m"])
    for row, path in zip(rows, (one, three)):        # each point as the model written so
        want = compile_model(load_model(str(path))).simulate()["span1.F"][-1]
        assert abs(row["span1.F"] - want) <= 100 * 1e-8 * (1 + abs(want)), (row, want)


def test_seen_the_live_page_offers_no_slider_for_a_structural_parameter(hanging):
    from acausal2d.explore.requests import BadRequest
    from acausal2d.explore.runner import Explorer
    one, three, cm = hanging
    explorer = Explorer(str(one))
    try:
        d = explorer.describe()
        sliders = {p["name"] for p in d["parameters"]}
        assert "p.m" not in sliders and "p.m" in d["structural"]
        assert "span1.c" in sliders
        with pytest.raises(BadRequest) as err:
            explorer.parse(b'{"set": {"p.m": 3}}')
        assert err.value.field == "set.p.m" and "compiled" in str(err.value)
    finally:
        explorer.close()

# ------------------------------------------------------------------ .mat names

NAMES_MODEL = '''
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class Gelenk(Component):
    """The pendulum with its joint and rod named outside Latin-1."""
    experiment = {"stop_time": 0.3, "intervals": 6}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.φ_gelenk = Revolute(phi=start(0.3, fixed=True), w=start(0.0, fixed=True))
        self.関節 = FixedTranslation(r=(1.0, 0.0))
        self.bob = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.φ_gelenk.frame_a)
        self.connect(self.φ_gelenk.frame_b, self.関節.frame_a)
        self.connect(self.関節.frame_b, self.bob.frame_a)
'''


def test_seen_non_latin1_names_round_trip_through_mat(tmp_path, capfd):
    """Seen 6: components named φ_gelenk and 関節: the .mat result is
    written (exit 0) and read back with the same names and the numbers of
    the CSV result."""
    import csv
    from acausal2d.io.dymola_mat import mat_units, read_mat
    path = tmp_path / "gelenk.py"
    path.write_text(NAMES_MODEL, encoding="utf-8")
    code, _, err = _cli(["simulate", path, "--result-format", "mat", "--out", tmp_path / "m"],
                        capfd)
    assert code == 0, err
    code, _, err = _cli(["simulate", path, "--out", tmp_path / "c"], capfd)
    assert code == 0, err
    time, cols = read_mat(tmp_path / "m" / "result.mat")
    with open(tmp_path / "c" / "result.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    for name in ("φ_gelenk.phi", "関節.frame_b.x", "bob.x"):
        assert name in cols, sorted(cols)[:20]
        want = np.array([float(r[name]) for r in rows])
        assert np.max(np.abs(cols[name] - want)) <= 1e-9 * (1 + np.max(np.abs(want)))
    assert mat_units(tmp_path / "m" / "result.mat").get("φ_gelenk.phi") == "rad"

# ------------------------------------------------------------------ guards


def test_seen_out_empty_is_refused(tmp_path, capfd, monkeypatch):
    """Seen 7: ``--out ''`` named the current folder (exit 0, files in it)."""
    monkeypatch.chdir(tmp_path)
    code, out, err = _cli(["simulate", PENDULUM, "--out", ""], capfd)
    assert code == 2 and "--out ''" in err and "names no folder" in err
    assert os.listdir(tmp_path) == []


def test_seen_huge_intervals_are_refused_before_allocating(tmp_path, capfd):
    code, out, err = _cli(["simulate", PENDULUM, "--intervals", "2000000000", "--out",
                           tmp_path / "o"], capfd)
    assert code == 2 and "intervals" in err and "GB of memory" in err


def test_seen_unknown_native_mode_is_refused_naming_the_modes(tmp_path, capfd, monkeypatch):
    """Seen 7: ``ACAUSAL2D_NATIVE=fast`` was taken as auto without a word."""
    monkeypatch.setenv("ACAUSAL2D_NATIVE", "fast")
    code, out, err = _cli(["simulate", PENDULUM, "--out", tmp_path / "o"], capfd)
    assert code == 2 and "'fast'" in err and "auto, now, off" in err


def test_seen_far_start_angle_is_warned():
    """Seen 7: a start angle of 1e17 rad ran silently to a wrong motion."""
    import warnings
    from acausal2d.compiled import compile_model
    from acausal2d.io.loader import load_model
    cm = compile_model(load_model(PENDULUM))
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        cm.simulate(stop_time=0.01, start={"revolute.phi": 1e17})
    texts = [str(w.message) for w in seen]
    assert any("revolute.phi starts at 1e+17 rad" in t and "modulo 2 pi" in t for t in texts)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        cm.simulate(stop_time=0.01, start={"revolute.phi": 50.0})     # a few turns: fine
    assert not [w for w in seen if "far outside one turn" in str(w.message)]


@native_only
def test_seen_native_fallbacks_are_said_in_one_line(tmp_path):
    """Seen 7: a sticky failure marker, an index naming no library and a
    cache whose index cannot be written each say so in one line."""
    cache = tmp_path / "cache"
    env = {"ACAUSAL2D_CACHE_DIR": str(cache)}
    first = _simulate(env, tmp_path / "first")
    assert first.returncode == 0, first.stderr
    for name in os.listdir(cache):
        if name.startswith("a2d_model") and name.endswith(".idx"):
            (cache / name).write_text("elsewhere.so")           # an index naming no library
    proc = _simulate(env, tmp_path / "second")
    assert proc.returncode == 0 and proc.stderr.count("names no library of the cache") == 1, \
        proc.stderr
    for name in os.listdir(cache):                               # a compile killed before
        if name.endswith(".idx") or name.endswith(".so"):
            os.remove(cache / name)
            if name.endswith(".idx"):
                (cache / (name[:-4] + ".failed")).write_text("BuildFailed: cc killed (SIGKILL)")
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", PENDULUM, "--out",
                           str(tmp_path / "third")],
                          env=dict(os.environ, ACAUSAL2D_NATIVE="auto", **env),
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if "cc killed" in ln]
    assert len(lines) == 1 and "Python path" in lines[0] and "cache clear" in lines[0], \
        proc.stderr


def test_seen_full_disk_index_is_said(tmp_path, monkeypatch, capsys):
    import errno
    monkeypatch.setenv(cstore.CACHE_ENV, str(tmp_path))

    def full(path, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    monkeypatch.setattr(cstore, "write_atomic", full)
    monkeypatch.setattr(notices, "_said", set())
    cbuild.publish_index("0" * 64, "lib", str(tmp_path / "lib-x.so"))
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No space left on device" in err and "compile it again" in err

# ------------------------------------------------------------------ fuzz


def _expected_status(host, path, method, headers, body, hosts, token):
    """The answer the gate's rules give (written from the rules, not from
    the gate): None where the request reaches the application."""
    h = {k.lower(): v for k, v in headers}
    if h.get("host", "").lower() not in hosts:
        return 403
    if path.startswith("/api/") and h.get("x-acausal2d-token") != token and \
            "token=" + token not in path:
        return 403
    if method != "POST":
        return None
    if "origin" in h and h["origin"].lower() not in {"http://" + x for x in hosts}:
        return 403
    if h.get("sec-fetch-site", "same-origin") not in ("same-origin", "none"):
        return 403
    if h.get("content-type", "").split(";")[0].strip().lower() != "application/json":
        return 415
    if len(body) > 1 << 20:
        return 413
    return None


def test_fuzz_the_gate_refuses_exactly_what_its_rules_refuse():
    """400 random requests (fixed seed: Host, Origin, Sec-Fetch-Site,
    Content-Type, token, method, path, body size) through the gate in front
    of an application that counts what reaches it: each answer is the one
    the rules give, and a refused request never reaches the application."""
    import asyncio
    import random
    from urllib.parse import urlsplit
    from acausal2d.explore.guard import Guard, allowed_hosts
    rng = random.Random(43)
    token = "t0k3n-" + "x" * 26
    hosts = allowed_hosts("127.0.0.1", 8765)
    reached = []

    async def app(scope, receive, send):
        message = await receive()
        reached.append(message["body"])
        await send({"type": "http.response.start", "status": 200, "headers": []})
        await send({"type": "http.response.body", "body": b"ok"})
    gate = Guard(app, token, hosts)
    host_values = ["127.0.0.1:8765", "localhost:8765", "[::1]:8765", "LOCALHOST:8765",
                   "127.0.0.1:8766", "rebind.attacker.example:8765", "", "127.0.0.1"]
    origins = [None, "http://127.0.0.1:8765", "http://localhost:8765", "http://evil.example",
               "null", "https://127.0.0.1:8765"]
    kinds = [None, "application/json", "application/json; charset=utf-8", "text/plain",
             "application/x-www-form-urlencoded", "multipart/form-data", "APPLICATION/JSON"]
    for k in range(400):
        method = rng.choice(["GET", "POST", "POST"])
        path = rng.choice(["/", "/api/params", "/api/run", "/api/csv", "/api/start",
                           "/api/run?token=" + token, "/api/new-route"])
        body = b"{}" if rng.random() < 0.9 else b" " * ((1 << 20) + rng.randint(1, 5000))
        headers = [("Host", rng.choice(host_values))]
        for name, choices in (("Origin", origins), ("Content-Type", kinds),
                              ("Sec-Fetch-Site", [None, "same-origin", "cross-site",
                                                  "same-site", "none"]),
                              ("X-Acausal2d-Token", [None, token, token[:-1], "", token + "x"])):
            value = rng.choice(choices)
            if value is not None:
                headers.append((name, value))
        want = _expected_status(headers[0][1], path, method, headers, body, hosts, token)
        split = urlsplit(path)
        scope = {"type": "http", "method": method, "path": split.path,
                 "query_string": split.query.encode(), "headers": [
                     (n.lower().encode(), v.encode()) for n, v in headers]}
        sent, chunks = [], [body[i:i + 65536] for i in range(0, len(body), 65536)] or [b""]

        async def receive():
            part = chunks.pop(0)
            return {"type": "http.request", "body": part, "more_body": bool(chunks)}

        async def send(message):
            sent.append(message)
        before = len(reached)
        asyncio.run(gate(scope, receive, send))
        status = sent[0]["status"]
        assert status == (want or 200), (k, method, path, headers, len(body), sent[:2])
        assert (len(reached) > before) == (want is None)


def test_fuzz_request_bodies_nested_and_huge_numbers_name_their_field():
    """300 random bodies (fixed seed) with deep nesting and numbers too
    large for a float in every field: each is a run spec or a BadRequest
    naming a field of the body; nothing else escapes."""
    import json
    import random
    from acausal2d.compiled import compile_model
    from acausal2d.explore.requests import BadRequest, parse_run
    from acausal2d.io.loader import load_model
    cm = compile_model(load_model(os.path.join(ROOT, "models", "piston_engine.py")))
    defaults = {"stop_time": 10.0, "max_stop_time": 100.0, "intervals": 500, "signals": []}
    rng = random.Random(431)
    big = ["1" + "0" * n for n in (300, 309, 400, 401, 5000)] + ["1e400", "-1e999", "2.5"]
    refused = 0
    for _ in range(300):
        field = rng.choice(["stop_time", "intervals", "set", "start", "drag", "session"])
        number = rng.choice(big)
        depth = rng.choice([0, 1, 3, 5, 50, 3000])
        value = "[" * depth + number + "]" * depth
        if field == "set":
            value = '{"%s": %s}' % (rng.choice(["crank.r", "bodyPiston.m"]), value)
        elif field == "start":
            value = '{"revoluteDrive.phi": %s}' % value
        elif field == "drag":
            value = '{"x": "bodyPiston.x", "y": "bodyPiston.y", "to": [%s, 0]}' % value
        raw = ('{"%s": %s}' % (field, value)).encode()
        try:
            spec = parse_run(raw, cm, defaults, drag=field == "drag")
        except BadRequest as exc:
            refused += 1
            assert exc.field == "body" or exc.field.split(".")[0].split("[")[0] == field, \
                (raw[:80], exc.field)
            continue
        assert 0 < spec.stop_time <= 100.0 and 1 <= spec.intervals <= 20000
        assert all(np.isfinite(np.atleast_1d(v)).all() for v in spec.params.values())
        json.dumps(spec.start, allow_nan=False)
    assert 0 < refused < 300


def test_fuzz_cache_folders_of_every_mode_and_owner(tmp_path):
    """Folders with random modes (and owners, as root), links and files in
    their place: private_dir uses exactly those its rules allow - a real
    folder of the user (or tightened from read bits) that no one else can
    write - and refuses the others as unsafe."""
    import random
    rng = random.Random(4343)
    for k in range(60):
        path = tmp_path / ("f%d" % k)
        kind = rng.choice(["dir", "dir", "dir", "link", "file", "missing"])
        mode = rng.choice([0o700, 0o755, 0o750, 0o770, 0o777, 0o1777, 0o711, 0o702, 0o720])
        owner = os.geteuid()
        if kind == "dir":
            path.mkdir()
            os.chmod(path, mode)
            if os.geteuid() == 0 and rng.random() < 0.3:
                owner = OTHER_UID
                os.chown(path, owner, owner)
        elif kind == "link":
            (tmp_path / ("t%d" % k)).mkdir(mode=0o700)
            path.symlink_to(tmp_path / ("t%d" % k))
        elif kind == "file":
            path.write_text("x")
        why = private_dir.problem(str(path))
        if kind == "missing" or (kind == "dir" and owner == os.geteuid()
                                 and not mode & 0o022):
            assert why is None, (kind, oct(mode), why)
            assert stat.S_IMODE(os.lstat(path).st_mode) == 0o700
        else:
            assert why is not None and str(path) in why.message, (kind, oct(mode))
            assert why.unsafe == (kind != "file"), (kind, oct(mode), why.message)


def test_seen_the_live_page_checks_limits_on_all_the_values_it_is_sent(checked_file):
    """Seen 4 on the live page: limits moved together past the old ones are
    accepted, a pair breaking uMax >= uMin is refused naming both."""
    from acausal2d.explore.requests import BadRequest
    from acausal2d.explore.runner import Explorer
    explorer = Explorer(str(checked_file), "Blocks")
    try:
        spec = explorer.parse(b'{"set": {"pid.yMax": -5, "pid.yMin": -6}}')
        assert spec.params == {"pid.yMax": -5.0, "pid.yMin": -6.0}
        with pytest.raises(BadRequest) as err:
            explorer.parse(b'{"set": {"lim.uMax": -2, "lim.uMin": -1}}')
        assert err.value.field == "set" and "uMax = -2" in str(err.value) \
            and "uMin = -1" in str(err.value)
    finally:
        explorer.close()


@pytest.mark.skipif(cbuild.find_compiler() is None, reason="no C compiler")
def test_seen_a_library_missing_its_symbol_is_rebuilt(tmp_path, monkeypatch, capsys):
    """Seen 1: a verified library under the indexed name that lacks the
    driver's symbol ("undefined symbol: a2d_create") was not rebuilt."""
    import ctypes
    monkeypatch.setenv(cstore.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setattr(notices, "_said", set())
    good = {"good.c": "int a2d_create(void) { return 42; }\n"}
    import shutil
    built = cbuild.build({"wrong.c": "int other(void) { return 1; }\n"}, name="wrong")
    wrong = os.path.join(os.path.dirname(built), "lib-" + "cd" * 16 + ".so")
    shutil.copy(built, wrong + ".new")
    cstore.publish(wrong + ".new", wrong)             # verified, under a name of "lib"
    key = "ab" * 32
    cbuild.publish_index(key, "lib", wrong)           # the index names a library without it
    made = []

    def make():
        made.append(1)
        return cbuild.build(good, name="lib")
    got = cbuild.load(key, make, "lib", lambda path: ctypes.CDLL(path).a2d_create())
    assert got == 42 and made == [1]
    err = capsys.readouterr().err
    assert "could not be loaded" in err and "rebuilding it" in err
