"""The symbolic Fourier series of the belt contours (built by a cached
CasADi Function per number of harmonics) against the direct sum of cosines
and sines, for several harmonic counts, bases and zero coefficients."""
import casadi as ca
import numpy as np

from acausal2d.library.belt.contour import _fourier_sx


def test_symbolic_series_equals_direct_sum():
    rng = np.random.default_rng(4)
    x = ca.SX.sym("x")
    for n, base in ((1, 1.0), (5, 2.0), (24, 2.0), (24, 1.0), (40, 3.0)):
        a, b = rng.normal(size=n), rng.normal(size=n)
        a[rng.integers(0, n)] = 0.0
        b[rng.integers(0, n)] = 0.0
        f = ca.Function("f", [x], [_fourier_sx(x, base, 0.7, a, b)])
        xs = rng.uniform(-7.0, 7.0, 25)
        k = base * np.arange(1, n + 1)
        direct = 0.7 + np.cos(np.outer(xs, k)) @ a + np.sin(np.outer(xs, k)) @ b
        got = np.array([float(f(v)) for v in xs])
        assert np.max(np.abs(got - direct)) < 1e-11 * max(1.0, np.sum(np.abs(a) + np.abs(b)))
        # numbers in, a number out (no CasADi object)
        assert abs(float(_fourier_sx(0.3, base, 0.7, a, b)) - float(f(0.3))) < 1e-12
