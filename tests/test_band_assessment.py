"""Assessment of band curves (seed ch. 5): numbers of the spec's DB~SD
check, findings for a material point on the contour (too small x0), a
broken transfer function, a dwell, space and stress limits, and the report
and plot."""
import casadi as ca
import numpy as np
import pytest
from matplotlib import image as mpimg

from acausal2d.library.synthesis.assessment import BandMaterial, jumps, sign_changes
from acausal2d.library.synthesis.functional import BandStructure, synthesize

B0 = (-0.296, 0.0)


def dbsd(K, x0, phi=None):
    """h = 0.05 + 0.02 sin(phi) through B0 (spec_synthesis.md section 2,
    checks/dbsd_check.py), on the grid of that check without 20 points at
    each end (the check differentiates numerically there)."""
    if phi is None:
        phi = np.linspace(0.0, 3.0, 8001)[20:-20]
    s = BandStructure.dbsd((0, 0), B0, lambda p: 0.05 * p + 0.02 * (1 - ca.cos(p)), K, x0)
    return synthesize(s, phi)


@pytest.mark.parametrize("K, x0, lo, hi", [(-1, 0.25, 0.5636, 0.7121), (1, 0.40, 0.1274, 0.2770)])
def test_dbsd_free_band_length_and_space(K, x0, lo, hi):
    """The spec's numbers (4 digits, finite differences on 8001 points
    there, exact derivatives here): free band length range, largest cam
    radius 0.0700 m, no finding."""
    syn = dbsd(K, x0)
    a = syn.assess()
    lbf = a.values["l_Bf range"]
    assert lbf[0] == pytest.approx(lo, abs=6e-5) and lbf[1] == pytest.approx(hi, abs=6e-5)
    assert a.values["max a"] == pytest.approx(0.0700, abs=5e-5)
    assert a.ok, a.report()
    assert "none -- the band curve can be built" in a.report()


def test_too_small_x0_raises_the_finding():
    """K = +1 with x0 = 0.25 m: the material point (the band fixing point)
    reaches the contour at phi = 0.4256 rad -- the free band length goes to
    zero, the involute has a cusp there, GF1 touches zero and S_Bf changes
    sign: the assessment reports it (with x0 = 0.40 m it does not, see
    above)."""
    syn = dbsd(1, 0.25)
    a = syn.assess()
    assert not a.ok and a.has("S_Bf")
    f = [f for f in a.findings if f.criterion == "S_Bf"][0]
    assert len(f.phi) == 1 and f.phi[0] == pytest.approx(0.4256, abs=1e-3)
    assert a.values["l_Bf range"][0] < 1e-4
    assert "VIOLATED" in a.report() and "check x0" in a.report()
    # GF1 touches zero there: its smallest magnitude is 1e-6 of its range
    Z = np.abs(syn.criteria["Z"])
    assert Z.min() < 1e-6 * Z.max()


def test_gf1_sign_change_is_a_c0_break():
    """A too sudden speed change of a DB~DS slider (0.02 -> 0.12 m/rad within
    1 rad): GF1 changes sign, the free band length runs to infinity and
    back (C0 break of the contour)."""
    def travel(p):
        s = (p - 1.0)
        mid = 0.12 + 0.02 * s + 0.1 * s ** 4 * (2.5 - 3 * s + s * s)
        return ca.if_else(p < 1.0, 0.1 + 0.02 * p, ca.if_else(p < 2.0, mid, 0.19 + 0.12 * (p - 2)))
    syn = synthesize(BandStructure.slider((0, 0), (0, 0), 0.0, travel, cam_angle=lambda p: -p),
                     np.linspace(0.0, 2.5, 401))
    a = syn.assess()
    assert a.has("GF1") and a.has("free band length jumps")
    assert not a.has("transfer function not C2")      # the speed step is C2 (degree 5)
    gf1 = [f for f in a.findings if f.criterion == "GF1"][0]
    assert all(1.0 < p < 2.0 for p in gf1.phi)


def test_broken_transfer_function_and_dwell():
    """DB~DS with the slider speed stepping from -0.05 to -0.02 m/rad (not
    C1; spec_assessment_ch5.md test design) and with a dwell: the pre-check
    reports them, and the contour breaks (free band length jumps) at the
    step -- as an S_Bf jump in the seed's words."""
    step = synthesize(BandStructure.slider((0, 0), (0, 0), 0.0, lambda p: ca.if_else(
        p < 1.0, 0.3 - 0.05 * p, 0.25 - 0.02 * (p - 1.0))), np.linspace(0.0, 2.0, 201))
    a = step.assess()
    f = [f for f in a.findings if f.criterion == "transfer function not C2"]
    assert len(f) == 1 and "first derivative" in f[0].message
    assert f[0].phi[0] == pytest.approx(1.0, abs=0.01)
    assert a.has("free band length jumps")
    dwell = synthesize(BandStructure.slider((0, 0), (0, 0), 0.0, lambda p: ca.if_else(
        p < 1.0, 0.3 - 0.05 * p + 0.025 * p ** 2, 0.275)), np.linspace(0.0, 2.0, 201))
    b = dwell.assess()
    assert b.has("dwell")
    assert "1 .. 2" in [f for f in b.findings if f.criterion == "dwell"][0].message
    # a smooth transfer function raises nothing
    smooth = synthesize(BandStructure.slider((0, 0), (0, 0), 0.0, lambda p: 0.3 - 0.05 * p
                                             + 0.01 * ca.sin(p)), np.linspace(0.0, 2.0, 201))
    assert smooth.assess().ok


def test_jump_detection_tells_jumps_from_kinks():
    """jumps(): a jump of v is confirmed by bisection, a kink of v' (a jump of
    v'', i.e. v is C1) is not."""
    def kink(x):
        return np.where(x < 0.5, x ** 2, 0.25 + (x - 0.5) + 3 * (x - 0.5) ** 2), \
            np.where(x < 0.5, 2 * x, 1 + 6 * (x - 0.5))

    def jump(x):
        return np.where(x < 0.5, x, x + 1e-3), np.ones_like(x)
    x = np.linspace(0.0, 1.0, 51)
    for f, n in ((kink, 0), (jump, 1)):
        v, dv = f(x)
        assert len(jumps(x, v, dv, refine=f)) == n
    assert sign_changes([1.0, 0.0, 1.0, -1.0], [0, 1, 2, 3]) == pytest.approx([2.5], abs=4 * np.spacing(2.5))


def test_band_stresses_on_the_circle():
    """Circle case (spec test values): lever arm and contour radius R, so
    sigma_z = T/(R h_B br_B) and sigma_b = E h_B/(2 R) (5.16-5.18)."""
    R, L0 = 0.05, 0.30

    def cam(d):
        return (L0 - ca.sqrt(d * d - R * R) + R * ca.acos(R / d)) / R
    syn = synthesize(BandStructure.slider((0, 0), (0, 0), 0.0, lambda p: p, cam_angle=cam),
                     np.linspace(0.274, 0.375, 101))
    band = BandMaterial(h_B=0.2e-3, br_B=10e-3, E=200e9, sigma_allow=500e6)
    a = syn.assess(band=band, torque=2.0)
    s = a.series
    assert np.max(np.abs(s["sigma_b"] / (band.E * band.h_B / (2 * R)) - 1)) < 1e-8
    assert np.max(np.abs(s["sigma_z"] / (2.0 / R / (band.h_B * band.br_B)) - 1)) < 1e-10
    util = (2.0 / R / 2e-6 + 200e9 * 0.2e-3 / 0.1) / 500e6
    assert a.values["max utilisation"] == pytest.approx(util, rel=1e-8)
    assert a.ok                                   # util = 0.84
    assert syn.assess(band=band, torque=20.0).has("stress")   # util = 1.2
    assert syn.assess(a_max=0.049).has("space")
    assert syn.assess(rho_min=0.06).has("curvature")


def test_report_and_plot(tmp_path):
    syn = dbsd(-1, 0.25, np.linspace(0.0, 3.0, 301))
    a = syn.assess(a_max=0.08)
    text = a.report()
    for item in ("GF1 = Z (5.7)", "GF2 (5.9)", "S_Bf", "free band length", "(allowed 0.08 m)",
                 "lever arm"):
        assert item in text
    path = a.plot(str(tmp_path / "criteria.png"))
    img = mpimg.imread(path)
    assert img.shape[0] > 500 and img.shape[1] > 800
    assert np.std(img[:, :, :3]) > 0.05          # not blank
    assert [p.name for p in tmp_path.iterdir()] == ["criteria.png"]   # no temporary left
