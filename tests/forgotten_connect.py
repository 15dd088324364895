"""Helpers of tests/test_forgotten_connect.py: a model of models/ built with
one of its model file's own ``connect`` statements left out, and what
``check`` answers for it."""
import os
import sys

from acausal2d import Acausal2dError, check
from acausal2d.io.loader import load_model
from acausal2d.language.dsl import Component

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class _Skipping:
    """Patches Component.connect while a model file's model is built: the
    connects called from the model file itself are counted and the one
    numbered ``skip`` (if any) is left out (its connectors recorded)."""

    def __init__(self, path, skip=None):
        self.path, self.skip = os.path.abspath(path), skip
        self.count, self.skipped = 0, None

    def __enter__(self):
        original = self.original = Component.connect
        outer = self

        def connect(comp, a, b):
            if os.path.abspath(sys._getframe(1).f_code.co_filename) == outer.path:
                outer.count += 1
                if outer.count - 1 == outer.skip:
                    outer.skipped = (a, b)
                    return None
            return original(comp, a, b)
        Component.connect = connect
        return self

    def __exit__(self, *exc):
        Component.connect = self.original
        return False


def count_connects(path, name):
    """How many connects the model file's own code makes building ``name``."""
    with _Skipping(path) as s:
        load_model(path, name)
    return s.count


def build_without(path, name, k):
    """(model, (a, b)): ``name`` of the model file built without its k-th connect."""
    with _Skipping(path, k) as s:
        model = load_model(path, name)
    return model, s.skipped


def answer(model):
    """What check answers: ('report', text, report) or ('error', message, None)."""
    try:
        report = check(model)
    except Acausal2dError as exc:
        return "error", str(exc), None
    return "report", str(report), report
