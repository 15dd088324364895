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
from threadpoolctl import ThreadpoolController as _CONTROLLER_CLASS
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


@pytest.fixture
def builds(monkeypatch):
    """The ThreadpoolControllers made while the test runs (threadpoolctl's
    constructor, counted)."""
    import threadpoolctl
    made = []
    real = threadpoolctl.ThreadpoolController

    def counted(*args, **kwargs):
        made.append(real(*args, **kwargs))
        return made[-1]
    monkeypatch.setattr(threadpoolctl, "ThreadpoolController", counted)
    return made


def test_a_second_run_of_the_same_model_makes_no_controller(builds):
    """Compiling and running the pendulum again loads its native library
    again (the same file): no library with a thread pool is new, so the
    controller of the first run is kept, also where a run reports loaded
    libraries (the native driver and scikit-sundae call libraries_loaded)."""
    acausal2d.compile_model(PENDULUM).simulate(stop_time=0.2, intervals=4, progress=False)
    first = len(builds)
    controller = threads.controller()
    acausal2d.compile_model(PENDULUM).simulate(stop_time=0.2, intervals=4, progress=False)
    with threads.our_threads():
        threads.libraries_loaded()
    assert len(builds) == first
    assert threads.controller() is controller


def test_a_newly_loaded_pool_library_makes_the_controller_anew(builds, tmp_path):
    """A library with a thread pool loaded inside a run (a copy of this
    process's OpenBLAS or OpenMP runtime under a new path) makes one new
    controller, and its pool is limited for the rest of the run and given
    back afterwards."""
    import ctypes
    import shutil
    pools = threads.pool_libraries()
    if not pools:
        pytest.skip("the loaded libraries cannot be listed here, or none carries a thread pool")
    source = min(pools, key=os.path.getsize)
    copy = tmp_path / os.path.basename(source)
    shutil.copyfile(source, copy)
    threads.controller()
    with threads.our_threads():
        ctypes.CDLL(str(copy))
        loaded = _uncounted()[str(copy)]             # its own default, before any limit
        threads.libraries_loaded()
        assert len(builds) == 1
        assert str(copy) in threads.pool_libraries()
        assert _uncounted()[str(copy)] == threads.LIMIT
        threads.libraries_loaded()                   # nothing new since: no further controller
        assert len(builds) == 1
    assert _uncounted()[str(copy)] == loaded


def _uncounted():
    """{library path: threads} read by a controller the builds fixture does not count."""
    return {i["filepath"]: i["num_threads"] for i in _CONTROLLER_CLASS().info()}


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
        "ThreadpoolController made (once per process)",
        "check for newly loaded pools (each native library load)",
        "limit entered and left (every run)",
        "warm run of the pendulum, 0.1 s (for scale)"]
    assert all(0 < float(r.split()[-1]) < math.inf for r in rows)
