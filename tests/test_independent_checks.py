"""Checks against what the code under test does not compute:

* GF2 = Z' N - Z N' (Ebert (2015), eq. 5.9) and dl_Bf/dphi (5.10) of
  :func:`acausal2d.library.synthesis.bandkurve.band_criteria` against
  central differences of Z = x' y'' - y' x'' (5.7) and N = (x'^2 +
  y'^2)^(3/2), written here from the analytic first and second
  derivatives of a test involute (its third derivatives enter only
  band_criteria);
* the slotted slider of Schnabel and Gössner (models/talk_mechanisms.py:
  SlottedSlider) against its closed form: B lies on the slot through A0,
  turned by +90 deg from the crank, and on the horizontal line y = 1.5 e
  through B0, so B.x = 1.5 e cot(w + pi/2) = -1.5 e tan(w) for the crank
  angle w(t) = -45 deg + 40 deg sin(2 pi t)."""
import math

import numpy as np
import pytest
from conftest import load_model_class

import acausal2d
from acausal2d.library.synthesis.bandkurve import band_criteria

# test involute e(phi) = (a cos phi + b cos 2 phi, a sin phi + c sin 3 phi)
A, B, C = 0.1, 0.02, 0.01


def _derivs(phi, k):
    """k-th derivative (x, y) of the test involute, k = 0..3."""
    cx = [math.cos, lambda p: -math.sin(p), lambda p: -math.cos(p), math.sin][k]
    sx = [math.sin, math.cos, lambda p: -math.sin(p), lambda p: -math.cos(p)][k]
    x = A * cx(phi) + B * 2 ** k * cx(2 * phi)
    y = A * sx(phi) + C * 3 ** k * sx(3 * phi)
    return x, y


def _Z_N(phi):
    (x1, y1), (x2, y2) = _derivs(phi, 1), _derivs(phi, 2)
    return x1 * y2 - y1 * x2, (x1 * x1 + y1 * y1) ** 1.5


@pytest.mark.parametrize("phi", np.linspace(0.1, 6.0, 9))
def test_gf2_and_dl_bf_against_finite_differences(phi):
    """Central differences with h = 1e-4 rad: truncation h^2/6 Z''' ~ 1e-9
    of the scale Z N (derivatives of a trigonometric polynomial of degree
    3 grow by at most 3 per order), rounding eps Z N / h ~ 1e-12: bound
    1e-7 of the scale."""
    h = 1e-4
    e = [_derivs(phi, k) for k in range(4)]
    crit = band_criteria(e[0][0], e[0][1], e[1][0], e[1][1], e[2][0], e[2][1], e[3][0],
                         e[3][1], 0.0, 0.0, sqrt=np.sqrt, fabs=np.abs, sign=np.sign)
    Z, N = _Z_N(phi)
    (Zp, Np), (Zm, Nm) = _Z_N(phi + h), _Z_N(phi - h)
    dZ, dN = (Zp - Zm) / (2 * h), (Np - Nm) / (2 * h)
    scale = abs(Z * N) + abs(dZ * N) + abs(Z * dN)
    assert abs(float(crit["Z"]) - Z) < 1e-12 * abs(N)
    assert abs(float(crit["GF2"]) - (dZ * N - Z * dN)) < 1e-7 * scale
    # l_Bf = N/|Z| (5.3): its derivative by differences against dl_Bf (5.10)
    dl = (Np / abs(Zp) - Nm / abs(Zm)) / (2 * h)
    assert abs(float(crit["dl_Bf"]) - dl) < 1e-6 * (abs(dl) + N / abs(Z))


def test_slotted_slider_against_its_closed_form():
    """Run at rtol 1e-10; the crank swings w = -85 .. -5 deg, B.x = 1.03 ..
    0.0079 m (e = 60 mm: the node model's coordinates are millimetres, its
    results metres): bound 1e-7 relative (1000 rtol)."""
    model = load_model_class("talk_mechanisms.py", "SlottedSlider")()
    res = acausal2d.simulate(model, stop_time=1.0, rtol=1e-10,
                             output_times=np.linspace(0.0, 1.0, 91))
    e = 0.060
    w = math.atan2(-40.0, 40.0) + math.radians(40.0) * np.sin(2 * math.pi * res.time)
    closed = -1.5 * e * np.tan(w)
    assert np.max(np.abs(res["B.x"] - closed) / np.abs(closed)) < 1e-7
    assert np.max(np.abs(res["B.y"] - 1.5 * e)) < 1e-7 * 1.5 * e
    assert np.ptp(closed) > 1.0                        # the whole swing
