"""Large straight-line bodies cut into parts (acausal2d.runtime.cparts):
CasADi's values from the parts, compiled as one unit or spread over two,
the null rules of the straight bodies kept, the parts not inlined back into
one function, and bodies whose outputs all need one long computation left
as they are."""
import ctypes
import re
import shutil
import subprocess

import casadi as ca
import numpy as np
import pytest

from acausal2d.runtime import cbuild, codegen, cparts, csplit, cstraight

pytestmark = pytest.mark.skipif(cbuild.find_compiler() is None, reason="no C compiler")
EPS = np.finfo(float).eps
_P = ctypes.POINTER(ctypes.c_double)
N = 40


def _chain():
    """A chain of ``N`` links as CasADi builds one: each output needs its
    link and its neighbours (values shared by two parts), all of them one
    common factor."""
    q, p = ca.SX.sym("q", N), ca.SX.sym("p", 2)
    common = ca.cos(p[0]) * p[1]
    x = [(ca.sin(q[i]) * common + q[i] ** 2) * ca.cos(q[i] - p[1]) for i in range(N)]
    r = [ca.exp(0.1 * x[i]) * (x[i - 1] if i else 1.0) - 0.5 * x[(i + 1) % N] for i in range(N)]
    return ca.Function("fg", [q, p], [ca.vertcat(*r)], ["q", "p"], ["r"])


def _deep():
    """Every output needs one long computation: nothing to cut."""
    q, p = ca.SX.sym("q", N), ca.SX.sym("p", 2)
    s = p[0]
    for _ in range(400):
        s = ca.sin(s) * p[1] + 0.5
    r = ca.vertcat(*[s * q[i] for i in range(N)])
    return ca.Function("fg", [q, p], [r], ["q", "p"], ["r"])


def _straight(fn):
    cg = ca.CodeGenerator("fg.c", {"with_header": False})
    cg.add(codegen.eliminated(fn))
    return cstraight.straighten(cg.dump())


@pytest.fixture
def small_parts(monkeypatch):
    """Parts of about 120 statements, so that a small function is cut."""
    monkeypatch.setattr(cparts, "PART", 120)
    monkeypatch.setattr(cparts, "PART_FROM", 240)


def _library(tmp_path, monkeypatch, text, k, name):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    units = csplit.split(text, k) if k > 1 else [text]
    sources = {"u%d.c" % j: u for j, u in enumerate(units)}
    path = cbuild.build(sources, flags=["-O1"], name=name)
    return ctypes.CDLL(path), path, len(units)


def _call(lib, fn, q, p, out):
    """The exported ``fg`` through CasADi's C signature; ``p`` None a null
    input, ``out[j]`` False a null output."""
    bufs = [np.full(fn.nnz_out(j), np.nan) for j in range(fn.n_out())]
    arg = (_P * 8)(*[a.ctypes.data_as(_P) if a is not None else None for a in (q, p)])
    res = (_P * 8)(*[b.ctypes.data_as(_P) if want else None for b, want in zip(bufs, out)])
    iw, w = (ctypes.c_longlong * 64)(), (ctypes.c_double * 4096)()
    assert lib.fg(arg, res, iw, w, 0) == 0
    return bufs


def _close(got, want):
    """The same operations in the same order: equal to a few ulp."""
    return np.max(np.abs(got - want)) <= 8 * EPS * (1.0 + np.max(np.abs(want)))


@pytest.mark.parametrize("units", [1, 2])
def test_the_parts_give_casadis_values_and_keep_the_null_rules(small_parts, tmp_path,
                                                               monkeypatch, units):
    fn = _chain()
    text = _straight(fn)
    out = cparts.partition(text)
    parts = re.findall(r"^static A2D_NOINLINE int (casadi_f\d+_s\d+)\(", out, re.M)
    assert "casadi_f0_s0" in parts and "casadi_f0_s2" in parts      # shared part, two or more
    assert cparts.longest(out) < cparts.longest(text) / 2
    monkeypatch.setattr(csplit, "SPLIT_FROM", 0)
    lib, path, n_units = _library(tmp_path, monkeypatch, out, units, "fg%d" % units)
    assert n_units == units
    rng = np.random.default_rng(5)
    q, p = rng.normal(size=N), rng.normal(size=2)
    want = [np.asarray(fn(q, p).nonzeros())]
    assert _close(_call(lib, fn, q, p, (True,))[0], want[0])
    ref = np.asarray(fn(q, np.zeros(2)).nonzeros())
    assert _close(_call(lib, fn, q, None, (True,))[0], ref)           # null p reads zeros
    assert np.all(np.isnan(_call(lib, fn, q, p, (False,))[0]))        # null r: nothing written
    nm = shutil.which("nm")
    if nm:                                   # the parts stayed functions of their own
        symbols = subprocess.run([nm, path], capture_output=True, text=True).stdout
        assert len(set(re.findall(r"\bfg_f0_s\d+\b", symbols))) == len(
            [s for s in parts if s.startswith("casadi_f0_")])


def test_a_part_holds_about_PART_statements(small_parts):
    out = cparts.partition(_straight(_chain()))
    bodies = re.findall(r"^static A2D_NOINLINE int casadi_f0_s(\d+)\([^)]*\) \{\n(.*?)^\}\n",
                        out, re.M | re.S)
    sizes = [sum(1 for line in b.split("\n") if "=" in line) for k, b in bodies if k != "0"]
    assert len(sizes) >= 2
    assert max(sizes) <= 3 * cparts.PART             # a run of outputs: about PART each


def test_a_body_whose_outputs_all_need_one_long_computation_is_left_as_it_is(small_parts):
    text = _straight(_deep())
    assert cparts.partition(text) == text


def test_text_of_another_shape_is_returned_as_it_is(small_parts):
    assert cparts.partition("int f(void) { return 0; }\n") == "int f(void) { return 0; }\n"
    text = _straight(_chain())
    odd = text.replace("  return 0;\n}\n", "  casadi_copy(A1, 3, w);\n  return 0;\n}\n", 1)
    assert cparts.partition(odd).count("A2D_NOINLINE int") < \
        cparts.partition(text).count("A2D_NOINLINE int")


def test_longest_counts_the_lines_of_the_longest_body():
    text = ("static int casadi_f0(int x) {\n  a;\n  b;\n}\n"
            "static A2D_NOINLINE int casadi_f1_s0(int x) {\n  a;\n}\n")
    assert cparts.longest(text) == 2 and cparts.longest("") == 0
