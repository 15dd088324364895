"""The drivers' objects compiled at install time (issue 30: the first run
on a machine does not wait for them): ``setup.py`` compiles them and the
driver on CasADi's C API into the package, each with its SHA-256; a new structure links them and compiles
only its generated code (the C projector's library beside the model's);
a damaged one is left where it is and compiled into the cache instead;
``ACAUSAL2D_PREBUILT=0`` ignores them; an install without a compiler goes
on without them."""
import os
import subprocess
import sys

import pytest

import acausal2d
from acausal2d.runtime import background, cbuild, cstore, drivers, tiers
from tiers_support import NEEDS_NATIVE, WAIT, agree, fresh_cache

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "models"))
from piston_engine import PistonEngine  # noqa: E402

pytestmark = NEEDS_NATIVE


def _expected_names():
    cc = cbuild.find_compiler()
    return sorted([drivers.object_file(name, drivers.text(name), drivers.flags(cc), cc)[1]
                   for name in drivers.OBJECTS] + [drivers.capi_file()])


def _verified_objects(folder, suffixes=(".o", ".so")):
    names = sorted(f for f in os.listdir(folder) if f.endswith(suffixes))
    for f in names:
        path = os.path.join(folder, f)
        assert cstore.file_digest(path) == cstore.recorded(path), f
    return names


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The objects as ``drivers.install`` (what setup.py calls) builds them."""
    folder = str(tmp_path_factory.mktemp("prebuilt"))
    said = []
    built = drivers.install(folder, log=said.append)
    assert not said, said
    assert sorted(os.path.basename(p) for p in built) == _expected_names()
    return folder


@pytest.fixture
def cache(tmp_path, monkeypatch, installed):
    """An empty cache of its own, mode auto, the objects of ``installed``
    used as the package's."""
    folder = fresh_cache(tmp_path, monkeypatch)
    monkeypatch.setenv(drivers.ENV, "1")
    monkeypatch.setattr(drivers, "PREBUILT", installed)
    yield folder
    assert background.wait(WAIT)


def _run(model):
    return acausal2d.compile_model(model).simulate(stop_time=0.5, rtol=1e-8, intervals=200)


def _reference(monkeypatch):
    monkeypatch.setenv(tiers.ENV, "off")
    return _run(PistonEngine())


def test_install_compiles_every_object_with_its_digest(installed):
    assert _verified_objects(installed) == _expected_names()


def test_a_new_structure_links_the_installed_objects_and_compiles_only_its_code(
        cache, installed, monkeypatch):
    stamps = {f: os.path.getmtime(os.path.join(installed, f)) for f in os.listdir(installed)}
    monkeypatch.setenv(tiers.ENV, "now")            # in this process, which has them installed
    res = _run(PistonEngine())
    assert not [f for f in os.listdir(cache) if f.endswith(".o")]   # nothing compiled twice
    libraries = sorted(f.split("-")[0] for f in os.listdir(cache) if f.endswith(".so"))
    assert {"a2d_model", "a2d_rows"} <= set(libraries), libraries
    assert stamps == {f: os.path.getmtime(os.path.join(installed, f))
                      for f in os.listdir(installed)}
    agree(res, _reference(monkeypatch), ("revoluteDrive.phi", "prismatic.s"), 1e-8)


def test_a_damaged_installed_object_is_left_and_compiled_into_the_cache(
        cache, installed, tmp_path, monkeypatch, capfd):
    damaged = str(tmp_path / "damaged")
    os.makedirs(damaged)
    for f in os.listdir(installed):
        with open(os.path.join(installed, f), "rb") as src:
            data = bytearray(src.read())
        if f.startswith("a2d_project") and f.endswith(".o"):
            data[100] ^= 0xFF                              # a flipped byte
            victim = os.path.join(damaged, f)
        with open(os.path.join(damaged, f), "wb") as dst:
            dst.write(bytes(data))
    monkeypatch.setattr(drivers, "PREBUILT", damaged)
    monkeypatch.setenv(tiers.ENV, "now")
    res = _run(PistonEngine())
    err = capfd.readouterr().err
    assert "does not match its recorded SHA-256" in err and victim in err, err
    assert os.path.exists(victim)                          # not ours to remove
    assert [f.split("-")[0] for f in _verified_objects(cache, ".o")] == ["a2d_project"]
    agree(res, _reference(monkeypatch), ("revoluteDrive.phi", "prismatic.s"), 1e-8)


def test_prebuilt_0_ignores_the_installed_objects(cache, monkeypatch):
    monkeypatch.setenv(drivers.ENV, "0")
    monkeypatch.setenv(tiers.ENV, "now")
    res = _run(PistonEngine())
    assert sorted(f.split("-")[0] for f in _verified_objects(cache, ".o")) == \
        ["a2d_driver_events", "a2d_project"]
    agree(res, _reference(monkeypatch), ("revoluteDrive.phi", "prismatic.s"), 1e-8)


def _build_py(tmp_path, env):
    out = tmp_path / "build"
    proc = subprocess.run([sys.executable, "setup.py", "-q", "build_py", "-d", str(out)],
                          cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return out / "acausal2d" / "runtime" / "prebuilt", proc.stderr


def test_setup_py_compiles_the_objects_into_the_package(tmp_path):
    folder, _ = _build_py(tmp_path, dict(os.environ))
    assert _verified_objects(folder) == _expected_names()


def test_an_install_without_a_compiler_goes_on_without_them(tmp_path):
    env = dict(os.environ, PATH=str(tmp_path / "empty"))     # no cc, gcc or clang on it
    env.pop("CC", None)
    folder, err = _build_py(tmp_path, env)
    assert "no C compiler found" in err, err
    assert not folder.exists() or not os.listdir(folder)
