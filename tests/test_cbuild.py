"""Run-time C builds (acausal2d.runtime.cbuild): a compiled function gives
the numbers its C source says, the cache is keyed by the sources, a missing
compiler is an error that names what to install."""
import ctypes
import os

import numpy as np
import pytest

from acausal2d.runtime import cbuild, cunits

SOURCE = """
double poly(double x) { return 3.0 * x * x - 2.0 * x + 0.5; }
"""

needs_cc = pytest.mark.skipif(cbuild.find_compiler() is None, reason="no C compiler")


@needs_cc
def test_build_compiles_caches_and_runs(tmp_path, monkeypatch):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    path = cbuild.build({"poly.c": SOURCE}, name="poly")
    assert os.path.dirname(path) == str(tmp_path)
    lib = ctypes.CDLL(path)
    lib.poly.restype = ctypes.c_double
    lib.poly.argtypes = [ctypes.c_double]
    # 3 x^2 - 2 x + 0.5 at 2: a few operations, each exact here; a contracted
    # multiply-add may still round differently: 4 ulps of the value
    assert abs(lib.poly(2.0) - 8.5) <= 4 * np.spacing(8.5)
    mtime = os.path.getmtime(path)
    assert cbuild.build({"poly.c": SOURCE}, name="poly") == path        # cached
    assert os.path.getmtime(path) == mtime
    other = cbuild.build({"poly.c": SOURCE.replace("0.5", "1.5")}, name="poly")
    assert other != path
    assert [f for f in os.listdir(tmp_path) if f.startswith(".build-")] == []


@needs_cc
def test_a_refused_source_is_a_build_error(tmp_path, monkeypatch):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    with pytest.raises(cbuild.BuildFailed, match="failed"):
        cbuild.build({"bad.c": "double f( { return }"}, name="bad")


def test_missing_compiler_names_what_to_install(monkeypatch):
    monkeypatch.setenv("CC", "no-such-compiler-xyz")
    monkeypatch.setattr(cunits, "COMPILERS", ())
    assert cbuild.find_compiler() is None
    with pytest.raises(cbuild.CompilerMissing, match="apt-get install gcc"):
        cbuild.build({"poly.c": SOURCE})


def test_key_depends_on_sources_flags_and_compiler():
    k = cbuild.build_key({"a.c": "x"}, ["-O2"], "cc")
    assert k == cbuild.build_key({"a.c": "x"}, ["-O2"], "cc")
    assert len({k, cbuild.build_key({"a.c": "y"}, ["-O2"], "cc"),
                cbuild.build_key({"a.c": "x"}, ["-O3"], "cc"),
                cbuild.build_key({"a.c": "x"}, ["-O2"], "gcc")}) == 4


def test_sundials_libraries_of_scikit_sundae():
    folder, libs = cbuild.sundials_libraries()
    assert {"ida", "core", "nvecserial", "sunmatrixdense", "sunlinsoldense"} <= set(libs)
    assert all(os.path.dirname(p) == folder for p in libs.values())


@needs_cc
def test_indexed_build_is_found_without_generating_the_code(tmp_path, monkeypatch):
    import casadi as ca
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    x = ca.SX.sym("x")
    f, g = ca.Function("f", [x], [x * x]), ca.Function("f", [x], [x * x + 1])
    assert cbuild.fingerprint([f]) == cbuild.fingerprint([ca.Function("f", [x], [x * x])])
    assert cbuild.fingerprint([f]) != cbuild.fingerprint([g])
    assert cbuild.fingerprint([f]) != cbuild.fingerprint([f], "driver text")
    calls = []

    def make():
        calls.append(1)
        return cbuild.build({"poly.c": SOURCE}, name="poly")
    key = cbuild.fingerprint([f])
    path = cbuild.build_indexed(key, make, "poly")
    assert cbuild.build_indexed(key, make, "poly") == path and len(calls) == 1
    os.remove(path)                                  # a library gone: built again
    assert cbuild.build_indexed(key, make, "poly") == path and len(calls) == 2
    with open(os.path.join(str(tmp_path), "poly-%s.idx" % key[:32]), "w") as fh:
        fh.write("garbage")                          # a broken index only costs a build
    assert cbuild.build_indexed(key, make, "poly") == path and len(calls) == 3
