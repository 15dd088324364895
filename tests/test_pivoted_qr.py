"""compiler.pivoted_qr gives what scipy.linalg.qr(pivoting=True,
mode="economic") gives, bit for bit: full, rank-deficient, integer-valued
(ties), wide, tall, non-contiguous and empty matrices."""
import numpy as np
import scipy.linalg as sla

from acausal2d.compiler import pivoted_qr
from acausal2d.compiler.pivoted_qr import qr_pivoted
from conftest import assert_copied


def _cases():
    rng = np.random.default_rng(7)
    for k in range(600):
        m, n = (int(v) for v in rng.integers(1, 14, 2))
        A = rng.standard_normal((m, n))
        if k % 3 == 0 and n > 2:
            A[:, 1] = 2.0 * A[:, 0]
        if k % 5 == 0:
            A = np.round(A)
        if k % 7 == 0:
            A = A[:, ::-1]
        yield A
    yield np.zeros((3, 4))
    yield np.zeros((0, 3))
    yield np.zeros((2, 0))


def test_same_as_scipy_bit_for_bit():
    for A in _cases():
        r2, piv2 = qr_pivoted(A)
        if A.size == 0:            # scipy >= 1.11's answer; 1.10's qr fails on it
            assert r2.shape == (min(A.shape), A.shape[1]) and piv2.dtype == np.int32
            assert (piv2 == np.arange(A.shape[1])).all()
            continue
        _, r, piv = sla.qr(A, pivoting=True, mode="economic")
        assert r.shape == r2.shape
        assert_copied(r, r2)                   # the same LAPACK routine
        assert piv.dtype == piv2.dtype and (piv == piv2).all()


def test_without_the_wheels_lapack_scipy_is_called(monkeypatch):
    monkeypatch.setattr(pivoted_qr, "_lapack", False)
    A = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]])
    _, r, piv = sla.qr(A, pivoting=True, mode="economic")
    r2, piv2 = qr_pivoted(A)
    assert_copied(r, r2)
    assert (piv == piv2).all()
