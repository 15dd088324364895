"""The native cache verified (issue 35, Seen 3): a fuzz of damaged cache
files - truncated, a flipped byte in the code and in the data of a library,
permissions removed, digests and indexes damaged, an unwritable folder -
through whole ``acausal2d simulate`` processes (a library loaded without a
check would end them with SIGBUS or SIGILL, or with exit 0 and wrong
numbers).  Every run ends with exit 0, one line on stderr saying what was
found, no traceback, and the motion of the undamaged cache; ``export-fmu``
packs only a verified binary; a compiler that fails or writes nothing is
named with its command."""
import csv
import os
import random
import shutil
import stat
import struct
import subprocess
import sys

import numpy as np
import pytest

from acausal2d.runtime import cbuild, cstore, native

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
RTOL = 1e-6            # the pendulum's experiment tolerance
pytestmark = pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                                reason="no C compiler or another SUNDIALS")


def _simulate(cache, out, native_mode="now", env=None):
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=str(cache), **(env or {}))
    return subprocess.run([sys.executable, "-m", "acausal2d", "simulate", PENDULUM, "--out",
                           str(out), "--native", native_mode], env=env, capture_output=True,
                          text=True, timeout=600)


def _column(out, name="revolute.phi"):
    with open(os.path.join(out, "result.csv"), newline="") as fh:
        rows = list(csv.DictReader(fh))
    return np.array([float(r[name]) for r in rows])


@pytest.fixture(scope="module")
def filled(tmp_path_factory):
    """A cache filled by one run, and that run's motion."""
    cache, out = tmp_path_factory.mktemp("cache"), tmp_path_factory.mktemp("out")
    proc = _simulate(cache, out)
    assert proc.returncode == 0, proc.stderr
    return cache, _column(out)


def _section(path, wanted):
    """(offset, size) of an ELF64 section of a file (``.text``, ``.rodata``)."""
    with open(path, "rb") as fh:
        data = fh.read()
    shoff, = struct.unpack_from("<Q", data, 0x28)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x3A)
    names_off = struct.unpack_from("<Q", data, shoff + shstrndx * shentsize + 0x18)[0]
    for k in range(shnum):
        base = shoff + k * shentsize
        name_at, = struct.unpack_from("<I", data, base)
        end = data.index(b"\0", names_off + name_at)
        if data[names_off + name_at:end].decode() == wanted:
            off, size = struct.unpack_from("<QQ", data, base + 0x18)
            return off, size
    raise AssertionError("no %s in %s" % (wanted, path))


def _flip(path, section, rng):
    off, size = _section(path, section)
    at = off + rng.randrange(size)
    with open(path, "r+b") as fh:
        fh.seek(at)
        byte = fh.read(1)[0]
        fh.seek(at)
        fh.write(bytes([byte ^ (1 << rng.randrange(8))]))


def _truncate(path, rng):
    with open(path, "r+b") as fh:
        fh.truncate(rng.randrange(64, os.path.getsize(path) // 2))


DAMAGE = {
    "truncated": lambda p, rng: _truncate(p, rng),
    "code-byte": lambda p, rng: _flip(p, ".text", rng),
    "data-byte": lambda p, rng: _flip(p, ".rodata", rng),
    "no-permissions": lambda p, rng: os.chmod(p, 0),
    "digest-missing": lambda p, rng: os.remove(p + cstore.DIGEST),
    "digest-garbage": lambda p, rng: open(p + cstore.DIGEST, "wb").write(os.urandom(64)),
    "emptied": lambda p, rng: open(p, "wb").close(),
}
"""How a library is damaged (issue 35: truncated, a flipped byte in its code
and in its data, permissions removed, and its digest lost or damaged)."""
CASES = [(kind, lib, seed) for kind in DAMAGE for lib in ("a2d_model", "a2d_rows")
         for seed in ((1, 2) if kind.endswith("byte") else (1,))]


@pytest.mark.parametrize("kind,lib,seed", CASES, ids=["%s-%s-%d" % c for c in CASES])
def test_a_damaged_library_is_found_and_rebuilt(filled, tmp_path, kind, lib, seed):
    cache, motion = filled
    mine = tmp_path / "cache"
    shutil.copytree(cache, mine)
    path = next(str(mine / f) for f in sorted(os.listdir(mine))
                if f.startswith(lib) and f.endswith(".so"))
    DAMAGE[kind](path, random.Random(seed))
    proc = _simulate(mine, tmp_path / "out")
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    readable = kind == "no-permissions" and os.access(path, os.R_OK)     # root reads it
    assert proc.stderr.count("is damaged") == (0 if readable else 1), proc.stderr
    scale = 1.0 + np.max(np.abs(motion))
    assert np.max(np.abs(_column(tmp_path / "out") - motion)) <= 10 * RTOL * scale
    os.chmod(path, stat.S_IRWXU)
    assert cstore.verified(path)            # the rebuilt library, with its digest


@pytest.mark.parametrize("kind", ["index-garbage", "index-elsewhere"])
def test_a_damaged_index_only_costs_a_lookup(filled, tmp_path, kind):
    cache, motion = filled
    mine = tmp_path / "cache"
    shutil.copytree(cache, mine)
    for f in os.listdir(mine):
        if f.endswith(".idx"):
            text = os.urandom(40) if kind == "index-garbage" else b"../../etc/passwd.so"
            (mine / f).write_bytes(text)
    proc = _simulate(mine, tmp_path / "out")
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    scale = 1.0 + np.max(np.abs(motion))
    assert np.max(np.abs(_column(tmp_path / "out") - motion)) <= 10 * RTOL * scale


def test_an_unwritable_cache_falls_back_with_a_notice(filled, tmp_path):
    motion = filled[1]
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    (tmp_path / "tmp").mkdir()
    proc = _simulate(blocker / "cache", tmp_path / "out", env={"TMPDIR": str(tmp_path / "tmp")})
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.count("cannot be written") == 1, proc.stderr
    assert proc.stderr.count("; using ") == 1, proc.stderr
    assert any(f.endswith(".so") for f in os.listdir(tmp_path / "tmp" / (
        "acausal2d-cbuild-%d" % os.getuid())))
    scale = 1.0 + np.max(np.abs(motion))
    assert np.max(np.abs(_column(tmp_path / "out") - motion)) <= 10 * RTOL * scale


def test_a_killed_build_leaves_nothing_behind(tmp_path, monkeypatch):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    stale = tmp_path / (cstore.BUILD_PREFIX + "poly-0123.so-abcd")
    stale.mkdir()
    (stale / "out.so").write_bytes(b"half")
    path = cbuild.build({"poly.c": "double poly(double x) { return x; }\n"}, name="poly")
    assert cstore.verified(path)
    assert not [f for f in os.listdir(tmp_path) if f.startswith(cstore.BUILD_PREFIX)]


@pytest.mark.parametrize("cc,why", [("/bin/false", "failed (exit 1)"),
                                    ("/bin/true", "exited 0 but wrote no")])
def test_a_compiler_that_fails_is_named_with_its_command(tmp_path, monkeypatch, cc, why):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    monkeypatch.setenv("CC", cc)
    with pytest.raises(cbuild.BuildFailed) as info:
        cbuild.build({"poly.c": "double poly(double x) { return x; }\n"}, name="poly")
    text = str(info.value)
    assert cc in text and why in text and "command: %s " % cc in text and "poly.c" in text
    assert not [f for f in os.listdir(tmp_path) if f.startswith(cstore.BUILD_PREFIX)]


def test_export_packs_only_a_verified_binary(tmp_path, monkeypatch):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    path = cbuild.build({"poly.c": "double poly(double x) { return 2.0 * x; }\n"}, name="poly")
    good = cbuild.copy_verified(path, str(tmp_path / "packed.so"))
    assert cstore.file_digest(good) == cstore.recorded(path)
    _flip(path, ".text", random.Random(3))            # changed after its build
    with pytest.raises(cbuild.BuildFailed, match="does not match"):
        cbuild.copy_verified(path, str(tmp_path / "packed2.so"))
    assert not os.path.exists(tmp_path / "packed2.so") and not os.path.exists(path)
    again = cbuild.build({"poly.c": "double poly(double x) { return 2.0 * x; }\n"}, name="poly")
    assert again == path and cstore.verified(again)


def test_cache_command_lists_sizes_and_clears(tmp_path, monkeypatch, capsys):
    from acausal2d.cli import main
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    path = cbuild.build({"poly.c": "double poly(double x) { return 3.0 * x; }\n"}, name="poly")
    (tmp_path / "pulley-0123.npz").write_bytes(b"another cache's entry")
    assert main(["cache", "path"]) == 0
    assert capsys.readouterr().out.strip() == str(tmp_path)
    assert main(["cache", "list"]) == 0
    out = capsys.readouterr().out
    assert os.path.basename(path) in out and "1 library" in out
    assert "compiled at install" in out                # the drivers' objects, or that there are none
    assert main(["cache", "size"]) == 0
    size = os.path.getsize(path) + os.path.getsize(path + cstore.DIGEST)
    kb = float(capsys.readouterr().out.split()[0])
    assert size / 1e3 <= kb <= size / 1e3 + 1.0          # digest, lock and library, in kB
    assert main(["cache", "clear"]) == 0
    assert "removed" in capsys.readouterr().out
    assert sorted(os.listdir(tmp_path)) == ["pulley-0123.npz"]    # only the native cache's files


def test_cache_list_names_the_installed_driver_objects_and_a_damaged_one(tmp_path, monkeypatch,
                                                                         capsys):
    from acausal2d.cli import main
    from acausal2d.runtime import drivers
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path / "cache"))
    folder = tmp_path / "prebuilt"
    monkeypatch.setattr(drivers, "PREBUILT", str(folder))
    assert main(["cache", "list"]) == 0
    assert "no driver objects were compiled at install" in capsys.readouterr().out
    folder.mkdir()
    for name, data in (("a2d_driver-0.o", b"object"), ("a2d_project-1.o", b"object")):
        (folder / name).write_bytes(data)
        (folder / (name + cstore.DIGEST)).write_text(cstore.file_digest(str(folder / name)))
    assert main(["cache", "list"]) == 0
    assert "2 driver objects compiled at install" in capsys.readouterr().out
    (folder / "a2d_project-1.o").write_bytes(b"changed")
    assert main(["cache", "list"]) == 0
    out = capsys.readouterr().out
    assert "not matching" in out and "a2d_project-1.o" in out and "a2d_driver-0.o" not in out
