"""The disk cache of slow deterministic results (acausal2d.io.cache) and the
pulley-pair synthesis it holds for the non-circular belt drive (issue 17,
item 4)."""
import math

import numpy as np
import pytest

from acausal2d.io import cache
from conftest import load_model_class, assert_copied

synthesise = load_model_class("noncircular_belt_drive.py", "synthesise")
design = load_model_class("noncircular_belt_drive.py", "design")
gauss_newton = load_model_class("noncircular_belt_drive.py", "gauss_newton")


@pytest.fixture
def cache_folder(tmp_path, monkeypatch):
    monkeypatch.setenv("ACAUSAL2D_CACHE_DIR", str(tmp_path))
    return tmp_path


def test_entry_computed_once_then_read(cache_folder):
    calls = []

    def compute():
        calls.append(1)
        return {"x": np.arange(3.0), "s": np.array(2.5)}

    a = cache.cached_arrays("t", ("k", 1.0), compute)
    b = cache.cached_arrays("t", ("k", 1.0), compute)
    assert len(calls) == 1
    assert_copied(a["x"], b["x"])
    assert_copied(float(b["s"]), 2.5)
    cache.cached_arrays("t", ("k", 2.0), compute)          # another key: computed
    assert len(calls) == 2
    assert len(list(cache_folder.glob("t-*.npz"))) == 2


def test_corrupt_entry_is_recomputed(cache_folder):
    path = cache.cache_path("t", 7)
    cache_folder.joinpath(path.split("/")[-1]).write_bytes(b"not a zip file")
    out = cache.cached_arrays("t", 7, lambda: {"x": np.ones(2)})
    assert_copied(out["x"], np.ones(2))
    assert_copied(cache.cached_arrays("t", 7, lambda: {"x": np.zeros(2)})["x"], np.ones(2))


def test_unwritable_folder_only_costs_the_computation(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("a file where the folder should be")
    monkeypatch.setenv("ACAUSAL2D_CACHE_DIR", str(blocker / "sub"))
    assert_copied(cache.cached_arrays("t", 1, lambda: {"x": np.ones(1)})["x"], [1.0])


def test_gauss_newton_matches_closed_forms():
    # zero residual: intersection of the circle x^2 + y^2 = 4 and the line y = x
    def fun(z):
        return np.array([z[0] ** 2 + z[1] ** 2 - 4.0, z[1] - z[0]])

    def jac(z):
        return np.array([[2 * z[0], 2 * z[1]], [-1.0, 1.0]])

    z = gauss_newton(fun, jac, np.array([3.0, 0.5]))
    assert np.allclose(z, [math.sqrt(2), math.sqrt(2)], atol=1e-14)
    # nonzero residual, linear: the least-squares line through noisy points
    rng = np.random.default_rng(3)
    x = np.linspace(0, 1, 40)
    y = 2.0 * x + 0.5 + 0.1 * rng.standard_normal(40)
    A = np.column_stack([x, np.ones_like(x)])
    z = gauss_newton(lambda z: A @ z - y, lambda z: A, np.zeros(2))
    assert np.allclose(z, np.polyfit(x, y, 1), atol=1e-12)


def test_design_from_cache_equals_synthesis(cache_folder):
    fresh = synthesise()
    assert float(fresh["residual"]) < 1e-10          # contact conditions hold to 1e-10 m
    des = design.__wrapped__()                      # computes and stores
    assert len(list(cache_folder.glob("noncircular-pulley-pair-*.npz"))) == 1
    again = design.__wrapped__()                    # reads
    K = des.K
    for d in (des, again):
        assert np.allclose(d.support1[1], fresh["p1c"][:K], rtol=0, atol=1e-14)
        assert np.allclose(d.support2[1], fresh["p2c"][:K], rtol=0, atol=1e-14)
        assert d.support2[0] == pytest.approx(float(fresh["p2m"]), abs=1e-15)
    assert again.contour2.perimeter == pytest.approx(1.28, abs=1e-9)
