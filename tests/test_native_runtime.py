"""The native inner loop (acausal2d.runtime.native) against the Python path
through scikit-sundae: the same IDA steps and the same motion; without a C
compiler and the driver installed with the package (or with
ACAUSAL2D_NATIVE=0) the run takes the Python path."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import capi, cbuild, cunits, drivers, native

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "models"))
from piston_engine import PistonEngine  # noqa: E402
from conftest import assert_copied

needs_cc = pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                              reason="no C compiler or another SUNDIALS")


def _run():
    cm = acausal2d.compile_model(PistonEngine())
    res = cm.simulate(stop_time=2.0, rtol=1e-8, intervals=500)
    form = next(iter(cm.system._formulations.values()))
    return res, native.library(form) is not None


@needs_cc
def test_native_and_python_paths_take_the_same_steps(monkeypatch):
    fast, used = _run()
    assert used
    monkeypatch.setenv("ACAUSAL2D_NATIVE", "0")
    slow, used = _run()
    assert not used
    assert fast.stats["steps"] == slow.stats["steps"]
    assert fast.stats["nfev"] == slow.stats["nfev"]
    for name in ("revoluteDrive.phi", "revoluteDrive.w", "prismatic.s"):
        scale = 1.0 + np.max(np.abs(slow[name]))
        assert np.max(np.abs(fast[name] - slow[name])) <= 1e-9 * scale, name


def test_without_a_compiler_or_installed_driver_the_python_path_runs(monkeypatch):
    """No compiler and no driver on CasADi's C API installed with the
    package (an install that found no compiler; with it installed, the run
    is native on it: tests/test_native_capi.py)."""
    monkeypatch.setattr(cunits, "COMPILERS", ())
    monkeypatch.delenv("CC", raising=False)
    monkeypatch.setenv(cbuild.CACHE_ENV, "/nonexistent-acausal2d-cache")
    monkeypatch.setenv(drivers.ENV, "0")
    monkeypatch.setattr(capi, "_loaded", {})
    res, used = _run()
    assert not used
    monkeypatch.setenv("ACAUSAL2D_NATIVE", "0")      # the Python path on purpose
    ref, _ = _run()
    assert res.stats["steps"] == ref.stats["steps"] and len(res.time) == 501
    assert_copied(res["prismatic.s"], ref["prismatic.s"])    # both the Python path


def test_an_interrupt_in_the_progress_callback_stops_the_run():
    cm = acausal2d.compile_model(PistonEngine())
    calls = []

    def progress(t, t_end):
        calls.append(t)
        if len(calls) == 100:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        cm.simulate(stop_time=10.0, intervals=5000, progress=progress)
    assert len(calls) == 100 and calls[-1] < 10.0
