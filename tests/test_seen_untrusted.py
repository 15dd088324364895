"""What another local user, a web page or a slider can do (the report
"Nothing a stranger can plant, no slider that does nothing"), each Seen
item by name: a library planted in a cache folder another user created is
refused and never loaded; cross-origin, simple-content-type, foreign-Host
and token-less requests to the live page are refused and start no run;
deep and huge JSON get 400 naming the field; a parameter read while
compiling is refused through every entry point, naming it; constructor
cross-checks hold on values given through ``--set`` and ``params=``; a
name outside Latin-1 round-trips through .mat; the guards before a run."""
import os
import stat
import subprocess
import sys

import numpy as np
import pytest

from acausal2d.io import private_dir
from acausal2d.runtime import cbuild, cstore, native

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
OTHER_UID = 65534                      # "nobody": a user that is not the one running the tests
native_only = pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                                 reason="no C compiler or another SUNDIALS")

# ------------------------------------------------------------------ the cache


def _owned_by_another(path):
    """Give ``path`` to another user where the tests run as root (else the
    folder stays the runner's own, and only its mode makes it unsafe)."""
    if os.geteuid() == 0:
        os.chown(path, OTHER_UID, OTHER_UID)


def test_private_dir_is_created_0700(tmp_path):
    path = tmp_path / "a" / "cache"
    assert private_dir.problem(str(path)) is None
    assert stat.S_IMODE(os.lstat(path).st_mode) == 0o700


def test_private_dir_of_ones_own_readable_by_others_is_tightened(tmp_path):
    path = tmp_path / "cache"
    path.mkdir(mode=0o755)
    os.chmod(path, 0o755)
    assert private_dir.problem(str(path)) is None
    assert stat.S_IMODE(os.lstat(path).st_mode) == 0o700


@pytest.mark.parametrize("how", ["world-writable", "group-writable", "symlink", "other-owner"])
def test_private_dir_refuses_what_another_user_could_write(how, tmp_path):
    path = tmp_path / "cache"
    if how == "symlink":
        (tmp_path / "real").mkdir(mode=0o700)
        path.symlink_to(tmp_path / "real")
    else:
        path.mkdir()
        os.chmod(path, {"world-writable": 0o777, "group-writable": 0o770}.get(how, 0o700))
    if how == "other-owner":
        if os.geteuid() != 0:
            pytest.skip("giving a folder to another user needs root")
        _owned_by_another(path)
    why = private_dir.problem(str(path))
    assert why is not None and why.unsafe
    assert str(path) in why.message
    assert ("rm -r" in why.message or "Remove" in why.message or "remove" in why.message)
    if how != "symlink":
        assert stat.S_IMODE(os.lstat(path).st_mode) != 0o700 or how == "other-owner"


PLANT = r"""
#include <stdio.h>
#include <stdlib.h>
__attribute__((constructor)) static void planted(void) {
    FILE *f = fopen(getenv("A2D_PLANT_MARK"), "w");
    if (f) { fputs("planted code ran", f); fclose(f); }
}
"""


def _simulate(env, out):
    return subprocess.run([sys.executable, "-m", "acausal2d", "simulate", PENDULUM, "--out",
                           str(out), "--native", "now"], env=dict(os.environ, **env),
                          capture_output=True, text=True, timeout=600)


@native_only
@pytest.mark.parametrize("owner", ["other-user", "world-writable"])
def test_seen_planted_library_in_a_precreated_fallback_is_refused_and_never_loaded(
        owner, tmp_path):
    """Seen 1: another user creates ``acausal2d-cbuild-<uid>`` in the
    temporary directory first (mode 0777) and plants a library under the
    name the index names, with its digest beside it; the configured cache
    cannot be written, so the run falls back - and must refuse that folder."""
    if owner == "other-user" and os.geteuid() != 0:
        pytest.skip("giving a folder to another user needs root")
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    planted = tmp / ("acausal2d-cbuild-%d" % os.getuid())
    first = _simulate({"ACAUSAL2D_CACHE_DIR": str(planted), "TMPDIR": str(tmp)},
                      tmp_path / "first")
    assert first.returncode == 0, first.stderr
    libs = [n for n in os.listdir(planted) if n.startswith("a2d_model") and n.endswith(".so")]
    assert libs, os.listdir(planted)
    src = tmp_path / "plant.c"
    src.write_text(PLANT)
    for name in libs:          # the attacker's library under the indexed name, its digest beside
        lib = planted / name
        subprocess.run([cbuild.find_compiler(), "-shared", "-fPIC", "-o", str(lib), str(src)],
                       check=True)
        (planted / (name + cstore.DIGEST)).write_text(cstore.file_digest(str(lib)))
        os.chmod(lib, 0o777)
    os.chmod(planted, 0o777)
    if owner == "other-user":
        _owned_by_another(planted)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    mark = tmp_path / "mark"
    proc = _simulate({"ACAUSAL2D_CACHE_DIR": str(blocker / "cache"), "TMPDIR": str(tmp),
                      "XDG_RUNTIME_DIR": "", "A2D_PLANT_MARK": str(mark)}, tmp_path / "out")
    assert not mark.exists(), "the planted library was loaded"
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    assert str(planted) in proc.stderr and "not used" in proc.stderr, proc.stderr
    assert "undefined symbol" not in proc.stderr
    first_phi = np.loadtxt(tmp_path / "first" / "result.csv", delimiter=",", skiprows=1)
    again = np.loadtxt(tmp_path / "out" / "result.csv", delimiter=",", skiprows=1)
    scale = 1.0 + np.max(np.abs(first_phi))
    assert np.max(np.abs(again - first_phi)) <= 10 * 1e-6 * scale     # the experiment's rtol


def test_a_cached_library_writable_by_others_is_not_loaded(tmp_path, monkeypatch):
    monkeypatch.setenv(cstore.CACHE_ENV, str(tmp_path / "cache"))
    folder = cstore.folder()
    lib = os.path.join(folder, "x.so")
    with open(lib, "wb") as fh:
        fh.write(b"\x7fELF planted")
    with open(lib + cstore.DIGEST, "w") as fh:
        fh.write(cstore.file_digest(lib))
    assert cstore.verified(lib)
    os.chmod(lib, 0o666)
    assert not cstore.verified(lib)
    assert not os.path.exists(lib)
