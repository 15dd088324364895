"""Straight-line bodies of CasADi's generated C (acausal2d.runtime.cstraight):
the same values as CasADi's own evaluation, a null input read as zeros and
a null output skipped as CasADi's guards do, no guard left in the rewritten
bodies, and the text split into units still links."""
import ctypes

import casadi as ca
import numpy as np
import pytest

from acausal2d.runtime import cbuild, csplit, cstraight

pytestmark = pytest.mark.skipif(cbuild.find_compiler() is None, reason="no C compiler")
EPS = np.finfo(float).eps
_P = ctypes.POINTER(ctypes.c_double)


def _function():
    """Two inputs, two outputs (one sparse), enough work to matter."""
    x, y = ca.SX.sym("x", 6), ca.SX.sym("y", 3)
    f = ca.vertcat(*[ca.sin(x[i]) * y[i % 3] + ca.exp(0.1 * x[(i + 1) % 6]) for i in range(6)])
    g = ca.jacobian(f, x)
    return ca.Function("fg", [x, y], [f, g], ["x", "y"], ["f", "g"])


def _text(fn):
    cg = ca.CodeGenerator("fg.c", {"with_header": False})
    cg.add(fn)
    return cg.dump()


def _library(tmp_path, monkeypatch, text, k):
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    units = csplit.split(text, k)
    sources = {"u%d.c" % j: u for j, u in enumerate(units)}
    return ctypes.CDLL(cbuild.build(sources, flags=["-O1"], name="fg")), len(units)


def _call(lib, fn, x, y, out):
    """Call the exported ``fg`` through CasADi's C signature; ``x``, ``y``
    None are null inputs, ``out[j]`` False a null output."""
    bufs = [np.full(fn.nnz_out(j), np.nan) for j in range(2)]
    arg = (_P * 2)(*[a.ctypes.data_as(_P) if a is not None else None for a in (x, y)])
    res = (_P * 2)(*[b.ctypes.data_as(_P) if want else None for b, want in zip(bufs, out)])
    iw = (ctypes.c_longlong * 16)()
    w = (ctypes.c_double * 16)()
    assert lib.fg(arg, res, iw, w, 0) == 0
    return bufs


def test_a_straight_body_gives_casadis_values_and_keeps_the_null_rules(tmp_path, monkeypatch):
    fn = _function()
    text = cstraight.straighten(_text(fn))
    body = text[text.index("casadi_f0_s("):]
    assert "arg[" not in body.split("\n}\n")[0] and "res[0]!=0" not in text
    monkeypatch.setattr(csplit, "SPLIT_FROM", 0)          # cut even this small file
    lib, n_units = _library(tmp_path, monkeypatch, text, 2)
    assert n_units == 2
    rng = np.random.default_rng(3)
    x, y = rng.normal(size=6), rng.normal(size=3)
    want = [np.asarray(v.nonzeros()) for v in fn(x, y)]
    got = _call(lib, fn, x, y, (True, True))
    for a, b in zip(got, want):        # the same operations in the same order: a few ulp
        assert np.max(np.abs(a - b)) <= 8 * EPS * (1.0 + np.max(np.abs(b)))
    got = _call(lib, fn, x, None, (True, False))          # null y reads zeros, null g skipped
    ref = np.asarray(fn(x, np.zeros(3))[0].nonzeros())
    assert np.max(np.abs(got[0] - ref)) <= 8 * EPS * (1.0 + np.max(np.abs(ref)))
    assert np.all(np.isnan(got[1]))                        # nothing written where asked nothing
    got = _call(lib, fn, x, y, (False, True))
    ref = np.asarray(fn(x, y)[1].nonzeros())
    assert np.max(np.abs(got[1] - ref)) <= 8 * EPS * (1.0 + np.max(np.abs(ref)))


def test_a_body_that_calls_another_is_kept_and_the_callee_straightened(tmp_path,
                                                                       monkeypatch):
    assert cstraight.straighten("int f(void) { return 0; }\n") == "int f(void) { return 0; }\n"
    s, x = ca.SX.sym("s", 3), ca.MX.sym("x", 3)
    inner = ca.Function("inner", [s], [ca.sin(s)])
    fn = ca.Function("fg", [x], [2 * inner(x)])            # an MX body calling an SX one
    text = _text(fn)
    caller = text[text.index("static int casadi_f0("):]
    caller = caller[:caller.index("\n}\n") + 3]
    out = cstraight.straighten(text)
    assert caller in out and "casadi_f1_s(" in out
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path))
    lib = ctypes.CDLL(cbuild.build({"m.c": out}, flags=["-O1"], name="m"))
    xv, got = np.array([0.3, -1.2, 2.0]), np.full(3, np.nan)
    arg, res = (_P * 1)(xv.ctypes.data_as(_P)), (_P * 1)(got.ctypes.data_as(_P))
    sz = (ctypes.c_longlong * 4)()
    assert lib.fg_work(ctypes.byref(sz, 0), ctypes.byref(sz, 8), ctypes.byref(sz, 16),
                       ctypes.byref(sz, 24)) == 0
    iw, w = (ctypes.c_longlong * (sz[2] + 1))(), (ctypes.c_double * (sz[3] + 1))()
    arg = (_P * (sz[0] + 1))(xv.ctypes.data_as(_P))
    res = (_P * (sz[1] + 1))(got.ctypes.data_as(_P))
    assert lib.fg(arg, res, iw, w, 0) == 0
    ref = 2 * np.sin(xv)
    assert np.max(np.abs(got - ref)) <= 8 * EPS * (1.0 + np.max(np.abs(ref)))
