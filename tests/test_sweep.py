"""Parameter studies on Dask (acausal2d.sweep, ``acausal2d sweep``):
a sweep on a LocalCluster of two worker processes equals the same runs done
serially, each worker compiles the model once, failed points are rows of
the table, and the command line writes the table and the plot."""
import csv
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis import sweep as sweep_module
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
OUTPUTS = ["body.phi", "revolute.w", "body.x"]


def run(*args):
    # the entry point installed with this interpreter (a virtualenv's bin/),
    # not another installation that happens to come first on PATH
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300)


@pytest.fixture(scope="module")
def client():
    with sweep_module.cluster(workers=2) as c:
        yield c


def test_forty_points_on_two_workers_equal_serial_runs(client):
    vary = {"body.m": "0.5:2.5:8", "rod.r[0]": [0.6, 0.8, 1.0, 1.2, 1.4]}
    study = acausal2d.sweep(PENDULUM, vary=vary, outputs=OUTPUTS, stop_time=1.0,
                            intervals=50, client=client, progress=False)
    assert len(study.rows) == 40 and not study.failed
    assert study.workers == 2
    cm = acausal2d.compile_model(acausal2d.load_model(PENDULUM))
    times = np.linspace(0.0, 1.0, 51)
    for row in study.rows:
        res = cm.simulate(params={"body.m": row["body.m"], "rod.r[0]": row["rod.r[0]"]},
                          output_times=times)
        for name in OUTPUTS:
            assert abs(row[name] - res.final(name)) <= 1e-12, (row, name)
    # the grid: every combination once, the last column varying fastest
    # grid points of a linspace: a few roundings each (8 eps relative)
    assert [r["rod.r[0]"] for r in study.rows[:5]] == pytest.approx([0.6, 0.8, 1.0, 1.2, 1.4],
                                                                  rel=8 * np.finfo(float).eps)
    assert sorted({r["body.m"] for r in study.rows}) == pytest.approx(np.linspace(0.5, 2.5, 8))
    # a longer rod swings slower: revolute.w at 1 s differs between points
    assert np.ptp(study.column("revolute.w")) > 0.1
    # each worker compiled the model once, for its first point only
    counts = client.run(lambda: sweep_module.COMPILATIONS["count"])
    assert sorted(counts.values()) == [1, 1]
    assert sum(r["status"] == "ok" for r in study.rows) == 40


def test_failed_point_is_a_row_with_its_error(client, tmp_path):
    points = [{"body.m": 1.0}, {"body.m": -1.0}, {"body.m": 2.0}]
    study = acausal2d.sweep(PENDULUM, points=points, outputs=["body.phi"], stop_time=0.5,
                            client=client, progress=False)
    assert [r["status"] for r in study.rows] == ["ok", "failed", "ok"]
    bad = study.rows[1]
    assert "parameter m = -1 breaks its rule >= 0" in bad["error"]
    assert "body.phi" not in bad
    assert np.isnan(study.column("body.phi")[1]) and np.isfinite(study.column("body.phi")[0])
    path = study.to_csv(tmp_path / "sweep.csv")
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    assert rows[1]["status"] == "failed" and "breaks its rule" in rows[1]["error"]
    assert "failed" in study.table().splitlines()[2]


def test_tied_parameters_share_one_column_and_value():
    cm = acausal2d.compile_model(acausal2d.load_model(PENDULUM))
    study = acausal2d.sweep(cm, vary={"body.m,body.I": [0.2, 0.4]}, outputs=["revolute.w"],
                            stop_time=0.5, progress=False)
    assert study.parameters == ["body.m,body.I"] and study.workers == 0
    for row in study.rows:
        v = row["body.m,body.I"]
        res = cm.simulate(stop_time=0.5, params={"body.m": v, "body.I": v},
                          output_times=np.linspace(0, 0.5, 501))
        assert_copied(row["revolute.w"], res.final("revolute.w"))        # the same run


def test_cli_sweep_on_an_existing_scheduler(client, tmp_path):
    address = client.scheduler.address
    proc = run("sweep", PENDULUM, "--vary", "body.m=0.5:2:4", "--vary", "body.I=-1,0.1",
               "--outputs", "revolute.w", "--stop-time", "0.5", "--scheduler", address,
               "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert "8 points (4 failed)" in proc.stdout and "on 2 workers" in proc.stdout
    assert proc.stdout.count("failed: ModelDefinitionError") == 4
    with open(tmp_path / "sweep.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["status"] for r in rows] == ["failed", "ok"] * 4
    assert (tmp_path / "sweep.png").read_bytes()[:4] == b"\x89PNG"
    assert "points" not in proc.stderr      # no bar into a pipe (test_progress: on a terminal)


@pytest.mark.parametrize("args,message", [
    (["--vary", "body.m=1:2"], "is not START:STOP:COUNT"),
    (["--vary", "body.q=1:2:3"], "unknown parameter 'body.q'"),
    (["--vary", "body.m=1,2", "--outputs", "body.nope"], "--outputs: no signal 'body.nope'"),
    (["--vary", "body.m=1,2", "--workers", "0"], "must be at least 1"),
    (["--vary", "body.m=1,2", "--x", "body.I"], "--x 'body.I' is not a varied parameter"),
    (["--vary", "body.m=1,2", "--set", "body.I=-3"], "breaks its rule"),
    (["--vary", "body.m=1,2", "--stop-time", "-1"], "stop_time (-1 s) must be larger than"),
    (["--vary", "body.m=1,2", "--stop-time", "1", "--at", "2"], "--at 2 lies after the end"),
    (["--vary", "body.m=1,2", "--scheduler", "tcp://127.0.0.1:1"], "cannot reach the Dask"),
], ids=["bad-range", "unknown-param", "unknown-output", "no-workers", "bad-x", "bad-set",
        "bad-stop", "bad-at", "no-scheduler"])
def test_cli_sweep_bad_options_exit_2(tmp_path, args, message):
    proc = run("sweep", PENDULUM, "--out", str(tmp_path), *args)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert message in proc.stderr and "Traceback" not in proc.stderr


def test_a_refused_scheduler_address_is_refused_before_dask_tries_again():
    """Nothing listens at the port: refused at once (Dask's Client would try
    again for its 10 s); a listening port, another scheme or a malformed
    port are left to the Client."""
    import socket
    from acausal2d.analysis.sweep import _refuse_unreachable
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        port = sock.getsockname()[1]
        sock.listen()
        assert _refuse_unreachable("tcp://127.0.0.1:%d" % port) is None
        assert _refuse_unreachable("127.0.0.1:%d" % port) is None
    for address in ("tcp://127.0.0.1:%d" % port, "127.0.0.1:%d" % port):
        with pytest.raises(ConnectionRefusedError):
            _refuse_unreachable(address)
    assert _refuse_unreachable("tls://127.0.0.1:%d" % port) is None
    assert _refuse_unreachable("tcp://127.0.0.1:notaport") is None
