"""Shared test helpers: loading the example models from models/."""
import importlib.util
import os
import sys

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
