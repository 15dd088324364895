"""Fuzz: one ``connect`` of a model file of models/ left out at random
(fixed seed; one model per file, sampled so the test stays fast).  Either
the answer of ``check`` is unchanged (a redundant connect), or ``check``
names a connector of the connect that was left out: in its report (the
connector report lists every unconnected connector) or in the error it
raises (a failed initialization or state selection names the loose
connectors first)."""
import functools
import glob
import os
import random
import zlib

import pytest

from acausal2d.io.loader import model_names
from forgotten_connect import ROOT, answer, build_without, count_connects
from acausal2d.io.loader import load_model

SEED = 44
FILES = sorted(glob.glob(os.path.join(ROOT, "models", "*.py")))


@functools.lru_cache(maxsize=None)
def _case(path):
    """(model, k): the model of ``path`` and the connect left out, drawn
    with a generator seeded by SEED and the file's name; None when no
    model of the file makes a connect of its own."""
    rng = random.Random(SEED + zlib.crc32(os.path.basename(path).encode()))
    names = model_names(path)
    rng.shuffle(names)
    for name in names:
        n = count_connects(path, name)
        if n:
            return name, rng.randrange(n)
    return None


SLOW = {"cabinet_door.py"}          # its model's check takes seconds (the fast tier leaves it)


@pytest.mark.parametrize("path", [pytest.param(f, marks=pytest.mark.slow)
                                  if os.path.basename(f) in SLOW else f for f in FILES],
                         ids=[os.path.basename(f) for f in FILES])
def test_a_forgotten_connect_is_named_or_changes_nothing(path):
    case = _case(path)
    if case is None:
        pytest.skip("the file's models make no connect of their own (node models, builders)")
    name, k = case
    model, (a, b) = build_without(path, name, k)
    kind, text, _ = answer(model)
    if a.path in text or b.path in text:
        return
    base = answer(load_model(path, name))
    assert (kind, text) == base[:2], (
        "%s without connect(%s, %s): check names neither and answers otherwise:\n%s"
        % (name, a.path, b.path, text))


def test_the_sample_covers_most_model_files():
    cases = [_case(f) for f in FILES]
    assert sum(c is not None for c in cases) >= len(FILES) * 2 // 3
