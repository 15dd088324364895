"""Shared test helpers: loading the example models from models/."""
import importlib.util
import os
import sys

import numpy as np
import pytest

# The suite compiles native code before a run (as before issue 30's tiers), so that a test
# sees the same path on a cold and a warm cache; tests/test_native_tiers.py sets "auto".
os.environ.setdefault("ACAUSAL2D_NATIVE", "now")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")


def load_model_class(filename, classname):
    """Import ``models/<filename>`` and return the class ``classname``."""
    if MODELS not in sys.path:
        sys.path.insert(0, MODELS)
    path = os.path.join(MODELS, filename)
    name = "models_" + os.path.splitext(filename)[0]
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
    return getattr(sys.modules[name], classname)


@pytest.fixture
def model_class():
    return load_model_class


# Rounding of a time placed by a few floating-point operations: an output
# point of numpy's linspace or t0 + k h, a time event's own instant (a few
# ulps of the time); 8 eps relative leaves room.
TIME_ROUNDING = 8 * np.finfo(float).eps


def same_time(times, t):
    """Where ``times`` equal ``t`` up to TIME_ROUNDING (relative to max(|t|,
    1)): output points and time events are exact in intent but placed by
    floating-point arithmetic, so they are not compared with ``==``."""
    return np.abs(np.asarray(times, dtype=float) - t) <= TIME_ROUNDING * max(abs(t), 1.0)


def assert_copied(actual, expected):
    """``actual`` holds the numbers of ``expected`` passed through code that
    does no arithmetic on them (a drawing scene, the disk cache, a CSV or
    JSON round trip written with 17 significant digits, a parameter read
    back, the same deterministic call repeated), or the constant a branch of
    the equations selects (a slack span's force, a closed valve's flow, a
    sign flag): exact equality is the claim and holds on any machine.  The only exact array comparison of the suite
    (tests/test_float_equality.py allows it here)."""
    np.testing.assert_array_equal(actual, expected)
