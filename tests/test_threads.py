"""Thread limits scoped to our calls (issue 34): ``import acausal2d`` and a
run leave the user's environment alone (no OMP_NUM_THREADS appears), and
the native thread pools are limited to one thread during a run only, the
user's own limits back afterwards (threadpoolctl)."""
import json
import os
import subprocess
import sys
import textwrap

import pytest
from threadpoolctl import threadpool_info, threadpool_limits

import acausal2d
from acausal2d import threads
from conftest import MODELS

PENDULUM = os.path.join(MODELS, "pendulum.py")

SCRIPT = textwrap.dedent("""
    import json, os, sys
    before = os.environ.get("OMP_NUM_THREADS")
    import acausal2d
    after_import = os.environ.get("OMP_NUM_THREADS")
    acausal2d.simulate(sys.argv[1], stop_time=0.2, intervals=4)
    print(json.dumps([before, after_import, os.environ.get("OMP_NUM_THREADS")]))
""")


@pytest.mark.parametrize("user_value", [None, "3"])
def test_import_and_a_run_leave_omp_num_threads_as_the_user_set_it(user_value, tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "OMP_NUM_THREADS"}
    if user_value is not None:
        env["OMP_NUM_THREADS"] = user_value
    env.update(ACAUSAL2D_NATIVE="off", ACAUSAL2D_CACHE_DIR=str(tmp_path))
    proc = subprocess.run([sys.executable, "-c", SCRIPT, PENDULUM], env=env, cwd=str(tmp_path),
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr[-3000:]
    assert json.loads(proc.stdout.strip().splitlines()[-1]) == [user_value] * 3


def _threads():
    return {info["filepath"]: info["num_threads"] for info in threadpool_info()}


def test_limits_hold_inside_the_run_only_and_the_users_come_back():
    cm = acausal2d.compile_model(PENDULUM)
    if not threadpool_info():
        pytest.skip("no native thread pool (BLAS, OpenMP) loaded in this process")
    inside = []
    with threadpool_limits(limits=2):                   # the user's own limit
        users = _threads()
        cm.simulate(stop_time=0.2, intervals=4, progress=lambda t, t_end: inside.append(_threads()))
        after = _threads()
        assert {k: after[k] for k in users} == users    # given back after the run
    assert inside and all(set(seen.values()) == {threads.LIMIT} for seen in inside)


def test_a_failed_run_gives_the_limits_back_too():
    cm = acausal2d.compile_model(PENDULUM)
    if not threadpool_info():
        pytest.skip("no native thread pool (BLAS, OpenMP) loaded in this process")
    before = _threads()

    def stop(t, t_end):
        raise KeyboardInterrupt

    with pytest.raises((KeyboardInterrupt, acausal2d.Acausal2dError)):
        cm.simulate(stop_time=0.2, intervals=4, progress=stop)
    after = _threads()
    assert {k: after[k] for k in before} == before


def test_the_controller_is_made_once_per_process():
    assert threads.controller() is threads.controller()


def test_bench_threads_small_prints_its_table():
    """The benchmark of the scoping's cost runs (small mode) and prints its
    rows with positive, finite numbers (no speed is asserted here)."""
    import math
    root = os.path.dirname(MODELS)
    proc = subprocess.run([sys.executable, os.path.join(root, "benchmarks", "bench_threads.py"),
                           "--small"], capture_output=True, text=True, cwd=root, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    rows = proc.stdout.strip().splitlines()
    assert [r.split("[ms]")[0].strip() for r in rows] == [
        "ThreadpoolController made (once per process)", "limit entered and left (every run)",
        "warm run of the pendulum, 0.1 s (for scale)"]
    assert all(0 < float(r.split()[-1]) < math.inf for r in rows)
