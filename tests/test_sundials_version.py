"""The native driver declares the SUNDIALS functions it calls for one
release (the A2D_SUNDIALS_* lines of native_driver.c) and checks it against
the release the shipped core library reports (SUNDIALSGetVersionNumber):
before it builds, and in the built library when it is loaded.  Another
release makes the process say so once on stderr and run IDA through
scikit-sundae, with the same motion."""
import glob
import os
import re

import numpy as np
import pytest

import acausal2d
from acausal2d.runtime import cbuild, native, notices
from conftest import load_model_class

RTOL = 1e-8


def _run():
    cm = acausal2d.compile_model(load_model_class("pendulum.py", "Pendulum")())
    res = cm.simulate(stop_time=1.0, intervals=100, rtol=RTOL)
    form = next(iter(cm.system._formulations.values()))
    return res, native.library(form) is not None


def test_the_declared_release_is_read_from_the_driver_source():
    with open(os.path.join(os.path.dirname(native.__file__), "native_driver.c"),
              encoding="utf-8") as fh:
        text = fh.read()
    parts = [re.search(r"#define A2D_SUNDIALS_%s (\d+)" % p, text).group(1)
             for p in ("MAJOR", "MINOR", "PATCH")]
    assert native.SUNDIALS_VERSION == ".".join(parts)


def test_the_loaded_release_is_the_one_the_core_library_is_named_for():
    found = cbuild.sundials_libraries()
    if found is None:
        pytest.skip("scikit-sundae ships no SUNDIALS libraries here")
    core = glob.glob(os.path.join(found[0], "libsundials_core*.so.*"))
    assert len(core) == 1
    named = re.search(r"\.so\.(\d+\.\d+\.\d+)$", core[0]).group(1)    # the soname's release
    assert native.loaded_sundials_version() == named


def test_another_release_falls_back_once_with_the_same_motion(monkeypatch, capsys):
    if cbuild.sundials_libraries() is None:
        pytest.skip("scikit-sundae ships no SUNDIALS libraries here")
    monkeypatch.setattr(notices, "_said", set())
    monkeypatch.setattr(native, "_loaded_version", ["7.8.0"])
    first, used = _run()
    second, used_again = _run()
    assert not used and not used_again
    said = [line for line in capsys.readouterr().err.splitlines() if "SUNDIALS" in line]
    assert said == ["acausal2d: SUNDIALS 7.8.0 is loaded, the native driver is declared for "
                    "SUNDIALS %s: IDA runs through scikit-sundae instead (the Python path: the "
                    "same results, slower; ACAUSAL2D_NATIVE=off chooses it without this "
                    "message)" % native.SUNDIALS_VERSION]
    # energy of the pendulum (1 kg at 1 m, I = 0.1 kg m^2, g = 9.81, released
    # horizontally): kept to the run's tolerance times the motion's scale, with room
    kinetic = 0.5 * 1.1 * first["revolute.w"] ** 2
    lost = 9.81 * np.abs(np.sin(first["revolute.phi"]))
    assert np.max(np.abs(kinetic - lost)) < 1e3 * RTOL * np.max(lost)
    monkeypatch.undo()
    if cbuild.find_compiler() is None or not native.enabled():
        return
    fast, used = _run()          # the native driver with the declared release
    assert used
    for name in ("revolute.phi", "revolute.w"):
        scale = 1.0 + np.max(np.abs(first[name]))
        assert np.max(np.abs(fast[name] - first[name])) <= 1e3 * RTOL * scale, name


@pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                    reason="no C compiler or another SUNDIALS")
def test_the_built_library_checks_the_release_at_load():
    cm = acausal2d.compile_model(load_model_class("pendulum.py", "Pendulum")())
    cm.simulate(stop_time=0.1, rtol=RTOL)
    lib = native.library(next(iter(cm.system._formulations.values())))
    assert lib is not None and lib.a2d_sundials_matches() == 1
