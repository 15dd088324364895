"""How the background worker and the foreground build native code (issue
30, a cheaper compile): the drivers' constant C is compiled once per
machine into cached, verified object files that every structure's library
links; the row maps are not compiled where the C projector serves; and the
worker compiles two libraries at once, their C generated in its main
thread."""
import os
import sys
import threading
import types

import pytest

import acausal2d
from acausal2d.runtime import (background, cbuild, cstore, projection,
                               tiers)
from tiers_support import NEEDS_NATIVE, WAIT, fresh_cache
from tiers_support import agree as _agree

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "models"))
from piston_engine import PistonEngine  # noqa: E402
from pendulum import Pendulum  # noqa: E402
from double_pendulum import DoublePendulum  # noqa: E402

pytestmark = NEEDS_NATIVE


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty cache of its own and this process's queue; mode auto."""
    folder = fresh_cache(tmp_path, monkeypatch)
    yield folder
    assert not background._queue                           # every library asked for is built
    assert background.wait(WAIT)


def _run(model, stop_time=0.5, rtol=1e-8, intervals=200):
    cm = acausal2d.compile_model(model)
    return cm.simulate(stop_time=stop_time, rtol=rtol, intervals=intervals)


def _objects(folder):
    return sorted(f for f in os.listdir(folder) if f.endswith(".o"))


def test_the_drivers_are_compiled_once_and_verified(cache, monkeypatch, capfd):
    monkeypatch.setenv(tiers.ENV, "now")
    first = _run(Pendulum())
    objects = _objects(cache)
    assert any(f.startswith("a2d_driver") for f in objects), objects
    assert any(f.startswith("a2d_project") for f in objects), objects
    assert all(os.path.exists(os.path.join(cache, f + cstore.DIGEST)) for f in objects)
    stamps = {f: os.path.getmtime(os.path.join(cache, f)) for f in objects}
    second = _run(DoublePendulum(phi0=0.3))                 # another structure, same drivers
    libraries = [f for f in os.listdir(cache) if f.startswith("a2d_model") and f.endswith(".so")]
    assert len(libraries) == 2, libraries
    for f in objects:
        if f in _objects(cache):
            assert os.path.getmtime(os.path.join(cache, f)) == stamps[f]   # not rebuilt
    project = os.path.join(cache, next(f for f in objects if f.startswith("a2d_project")))
    with open(project, "r+b") as fh:                        # damage a byte of the object
        fh.seek(100)
        byte = fh.read(1)
        fh.seek(100)
        fh.write(bytes([byte[0] ^ 0xFF]))
    capfd.readouterr()
    third = _run(PistonEngine())                            # a new structure links it again
    err = capfd.readouterr().err
    assert "damaged" in err and os.path.basename(project) in err, err
    assert cstore.verified(project)                         # rebuilt
    monkeypatch.setenv(tiers.ENV, "off")
    _agree(first, _run(Pendulum()), ("revolute.phi", "revolute.w"), 1e-8)
    _agree(second, _run(DoublePendulum(phi0=0.3)), ("revolute.phi", "revolute1.phi"), 1e-8)
    _agree(third, _run(PistonEngine()), ("revoluteDrive.phi", "prismatic.s"), 1e-8)


def test_the_row_maps_are_compiled_only_where_the_c_projector_cannot_serve(cache,
                                                                          monkeypatch):
    monkeypatch.setenv(tiers.ENV, "now")
    asked = []
    real = projection.compiled

    def compiled(functions, chosen=None):
        asked.extend(functions)
        return real(functions, chosen)
    monkeypatch.setattr(projection, "compiled", compiled)
    res = _run(Pendulum())
    assert not [name for name in asked if name.startswith(("E_rows", "J_rows"))], asked
    monkeypatch.setenv(tiers.ENV, "off")
    _agree(res, _run(Pendulum()), ("revolute.phi", "revolute.w"), 1e-8)


class _Slow:
    """A recipe whose compile runs until another one runs beside it (at
    most ``WAIT`` s), or whose C cannot be generated; ``running`` counts the
    compiles running at once (shared by the recipes of one test)."""

    def __init__(self, name, running, fails=False):
        self.name, self.fails, self.events, self.running = name, fails, [], running

    def code(self):                        # made once, as Recipe.code
        if getattr(self, "_code", None) is None:
            self.events.append(("generate", threading.current_thread().name))
            if self.fails:
                raise RuntimeError("CasADi refused %s" % self.name)
            self._code = "/* %s */" % self.name
        return self._code

    def make(self):
        self.code()
        with self.running["lock"]:
            self.running["now"] += 1
            self.running["most"] = max(self.running["most"], self.running["now"])
            self.running["lock"].notify_all()
            # the first two wait until both run: one at a time would end here after WAIT s
            together = self.running["lock"].wait_for(lambda: self.running["most"] >= 2, WAIT)
            self.running["now"] -= 1
        self.events.append(("together", together))
        return "/nonexistent/%s.so" % self.name


def test_the_worker_compiles_two_libraries_at_once_and_generates_in_one_thread(
        cache, monkeypatch):
    published = []
    monkeypatch.setattr(cbuild, "publish_index", lambda key, name, lib: published.append(name))
    monkeypatch.setattr(os, "nice", lambda inc: 0)         # the worker's, not this process's
    monkeypatch.setattr(background, "BUILDS_AT_ONCE", 2)
    running = {"lock": threading.Condition(), "now": 0, "most": 0}
    jobs = [("k%d" % i, _Slow("lib%d" % i, running, fails=(i == 3))) for i in range(4)]
    os.makedirs(cache, exist_ok=True)
    path = str(cache / ".tmp-job-test")
    with open(path, "wb") as fh:
        fh.write(b"")
    monkeypatch.setattr(background, "pickle", types.SimpleNamespace(load=lambda fh: jobs))
    background._work(path)
    main = threading.current_thread().name
    for _, recipe in jobs:                 # CasADi (the C's generation): this thread only
        assert {who for what, who in recipe.events if what == "generate"} == {main}
    assert running["most"] == 2                              # two at once, BUILDS_AT_ONCE at most
    assert all(dict(r.events).get("together") for _, r in jobs[:2])
    assert sorted(published) == ["lib0", "lib1", "lib2"]
    marker = background.failure_path("k3", "lib3")          # the failure recorded
    with open(marker, encoding="utf-8") as fh:
        assert "CasADi refused lib3" in fh.read()
    os.remove(marker)
