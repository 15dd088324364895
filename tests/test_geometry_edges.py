"""Issue 29, Seen 3-5, by name: a pulley whose winding sign contradicts how
its bands are placed, a linkage with a forgotten connect(), and a cam
contour that does not close, each end in a right answer or in an error
naming the culprit (the fuzz classes are in fuzz_cases_geometry.py)."""
import csv
import math
import os
import sys
import textwrap

import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, InitializationError, ModelDefinitionError, start
from acausal2d.cli import main
from acausal2d.library.belt import Band, Belt, Contour, Pulley, connect_band
from acausal2d.library.linkage import DDD
from acausal2d.library.planar import Body, Fixed
from acausal2d.library.planar.cam import CamFollower

G = 9.81
RTOL = 1e-8


class Atwood(Component):
    """Atwood machine of issue 29: 3 kg and 2 kg hanging from the two
    sides of a pulley (r = 0.1 m, J = 0.02 kg m^2, axis fixed at the
    origin); the bands run over the top, K1 on the left, K2 on the right,
    which is w = -1 (a positive turn pays out at K1).  ``elastic`` uses
    stiff elastic belts (pretensioned by the static weights) instead of
    inextensible bands."""

    def __init__(self, w=-1, elastic=False, anchor=False, **kw):
        super().__init__(**kw)
        self.pulley = Pulley(r=0.1, x10=0.0, y10=0.0, w_i=-w, J=0.02)
        if elastic:
            self.band1 = Belt(c=1e7, d=1e3, eps=start(3 * G / 1e7, fixed=True))
            self.band2 = Belt(c=1e7, d=1e3, eps=start(2 * G / 1e7, fixed=True))
        else:
            self.band1, self.band2 = Band(), Band()
        if anchor:          # the left end fastened to the ground instead of the 3 kg
            self.m1 = Fixed(r=(-0.1, -1.0))
            self.connect(self.m1.frame, self.band1.ctr2D1)
        else:
            self.m1 = Body(m=3.0, I=0.01, x=start(-0.1), y=start(-1.0))
            self.connect(self.m1.frame_a, self.band1.ctr2D1)
        self.m2 = Body(m=2.0, I=0.01, x=start(0.1), y=start(-1.0))
        connect_band(self, self.band1, 2, self.pulley, 1)
        connect_band(self, self.band2, 1, self.pulley, 2)
        self.connect(self.band2.ctr2D2, self.m2.frame_a)


@pytest.mark.parametrize("elastic", [False, True])
def test_seen3_atwood_with_the_flipped_winding_sign_is_refused(elastic):
    with pytest.raises(InitializationError) as err:
        acausal2d.simulate(Atwood(w=1, elastic=elastic), stop_time=0.2)
    text = str(err.value)
    kind = "Belt" if elastic else "Band"
    assert text.startswith("Pulley 'pulley': its bands %s 'band1' (at K1) and %s 'band2' "
                           "(at K2) cross each other" % (kind, kind))
    assert "Use w_i=+1 (Pulley(w_i=1); w=-1 in the deprecated notation)" in text
    # the crossing point lies on the pulley's vertical, between pulley and masses
    x, y = [float(v) for v in text.split(" at (")[1].split(")")[0].split(",")]
    assert abs(x) < 1e-4 and -1.0 < y < -0.1
    # check() (and with it the CLI's check) refuses the model in the same words
    with pytest.raises(InitializationError, match=r"Use w_i=\+1"):
        acausal2d.check(Atwood(w=1, elastic=elastic))


def test_seen3_atwood_with_the_right_sign_has_the_closed_form_acceleration():
    """a = (m1 - m2) g / (m1 + m2 + J/r^2) = 1.40 m/s^2; with inextensible
    bands the accelerations are algebraic in the states, so they hold to
    the integration tolerance (rtol 1e-8, bound 1e-6 relative)."""
    res = acausal2d.simulate(Atwood(w=-1), stop_time=0.5, rtol=RTOL,
                             output_times=np.linspace(0.0, 0.5, 11))
    a = (3.0 - 2.0) * G / (3.0 + 2.0 + 0.02 / 0.1 ** 2)
    assert a == pytest.approx(1.40, abs=0.005)
    assert np.max(np.abs(res["m1.ay"] + a)) < 100 * RTOL * a
    assert np.max(np.abs(res["m2.ay"] - a)) < 100 * RTOL * a
    # the bands stay vertical: no swing, 180 degree wrap
    assert np.max(np.abs(res["m1.x"] + 0.1)) < 100 * RTOL
    assert np.max(np.abs(res["pulley.beta"] - math.pi)) < 100 * RTOL
    # the pulley turns with the bands: r der(phi) = speed of the masses
    assert np.max(np.abs(0.1 * res["pulley.w_rel"] - a * res.time)) < 100 * RTOL * a


def test_seen3_rope_from_an_anchor_with_the_flipped_sign_is_refused():
    with pytest.raises(InitializationError, match=r"Pulley 'pulley': .* Use w_i=\+1"):
        acausal2d.simulate(Atwood(w=1, anchor=True), stop_time=0.2)


# ------------------------------------------------ Seen 4: a forgotten connect()
sys.path.insert(0, os.path.join(os.path.dirname(__file__), os.pardir, "models"))
import four_link_mechanisms as flm  # noqa: E402


class DDDDForgotten(flm._CrankDriven):
    """The DDDD four-bar of models/four_link_mechanisms.py without
    ``connect(crank.ctr2D2, dyad.ctr2D1)``: the dyad's triangle port
    ctr2D1 is then fixed to ground (Ebert 2015, Tabelle 4.1)."""
    outputs = ["crank.phiL", "dyad.phiL2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)


def test_seen4_check_lists_the_ports_grounded_because_unconnected():
    report = acausal2d.check(DDDDForgotten())
    assert report.grounded == {"crank.ctr2D1": ["x", "y", "phi"],
                               "dyad.ctr2D1": ["x", "y", "phi"],
                               "dyad.ctr2D2": ["x", "y", "phi"]}
    text = str(report)
    line = " ".join(text.split("grounded ports:")[1].split("free connectors:")[0].split())
    assert line == ("3 unconnected, so fixed to ground (Ebert 2015, Tabelle 4.1): "
                    "crank.ctr2D1 (x, y, phi), dyad.ctr2D1 (x, y, phi), dyad.ctr2D2 (x, y, phi)")
    # eq. 2.1 counts with them: crank, two dyad links and ground, 4 joints:
    # 3 (4 - 1) - 4 (3 - 1) = 1 (a rigid truss dyad and a free crank)
    assert (report.links, report.joints, report.grubler) == (4, 4, 1)
    assert "0 structural (position states); both with the 3 grounded ports fixed" in text
    connected = acausal2d.check(flm.DDDD())
    assert list(connected.grounded) == ["crank.ctr2D1", "dyad.ctr2D2"]


def test_seen4_simulate_lists_the_grounded_ports(tmp_path, capfd):
    path = tmp_path / "forgotten.py"
    path.write_text(textwrap.dedent('''
        import sys
        sys.path.insert(0, %r)
        from four_link_mechanisms import _CrankDriven
        from acausal2d.library.linkage import DDD

        class DDDDForgotten(_CrankDriven):
            outputs = ["crank.phiL", "dyad.phiL2"]

            def __init__(self, **kw):
                super().__init__(**kw)
                self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)
        ''' % os.path.dirname(flm.__file__)), encoding="utf-8")
    code = main(["simulate", str(path), "--stop-time", "0.25", "--intervals", "5",
                 "--out", str(tmp_path / "out")])
    out = capfd.readouterr().out
    assert code == 0
    assert "  grounded ports: 3 unconnected, so fixed to ground (Ebert 2015, Tabelle 4.1):" in out
    assert "dyad.ctr2D1 (x, y, phi)" in out
    # Tabelle 4.1 semantics: the crank turns, the grounded dyad stands still
    with open(tmp_path / "out" / "result.csv", newline="") as fh:
        rows = list(csv.reader(fh))
    col = rows[0].index("dyad.phiL2")
    phi = np.array([float(r[col]) for r in rows[1:]])
    assert np.ptp(phi) < 1e-9


def test_seen4_belt_library_ports_are_listed_too():
    report = acausal2d.check(Atwood(w=-1))
    assert report.grounded == {"pulley.ctr2D1": ["x", "y", "phi"], "band1.ctrB1": ["L"],
                               "band2.ctrB2": ["L"]}


# ------------------------------------------------ Seen 5: a cam contour that does not close
import cam_follower as cf  # noqa: E402

SPIRAL_RATE = 0.005      # m/rad: r = R0 + 0.005 kappa, a gap of 2 pi 0.005 m after one turn


class CamFromFunction(cf._Cam):
    """models/cam_follower.py's knife edge on a contour from a function:
    ``closed`` the harmonic cam r = R0 + H/2 - H/2 sin(kappa), else the
    spiral r = R0 + 0.005 kappa of issue 29."""

    def __init__(self, closed=True, **kw):
        super().__init__(**kw)
        if closed:
            contour = Contour.from_function(lambda k: cf.R0 + cf.H / 2 - cf.H / 2 * ca.sin(k))
        else:
            contour = Contour.from_function(lambda k: cf.R0 + SPIRAL_RATE * k)
        self._build(CamFollower(contour, follower="roller", r_roller=0.0, q=start(math.pi / 2)))


def test_seen5_spiral_contour_is_refused_naming_the_gap():
    with pytest.raises(ModelDefinitionError) as err:
        CamFromFunction(closed=False)
    text = str(err.value)
    assert text.startswith("Contour.from_function: the contour does not close: ")
    gap = float(text.split("a gap of ")[1].split(" m")[0])
    assert gap == pytest.approx(2 * math.pi * SPIRAL_RATE, rel=1e-5)     # printed to 6 digits
    assert "at kappa = 0," in text and "period 2 pi" in text


def test_seen5_closed_contour_from_a_function_runs_the_design_law():
    """The same follower on the closed harmonic contour: the lift is the
    design law at every cam angle (so equal after one turn), to the
    integration tolerance (rtol 1e-10, bound 1e-8 m as the model test)."""
    res = acausal2d.simulate(CamFromFunction(closed=True), stop_time=1.0, intervals=20,
                             rtol=1e-10)
    lift = np.array([cf.harmonic_lift(t) for t in res["drive.phi"]])
    assert np.max(np.abs(res["guide.s"] - lift)) < 1e-8
    assert abs(res["guide.s"][-1] - res["guide.s"][0]) < 1e-8


@pytest.mark.parametrize("func, symmetry, words", [
    (lambda k: 0.03 + 0.005 * ca.fabs(ca.sin(k)), 1, "closes with a kink: its tangent turns "
                                                     "by -9.46232 deg at kappa = 0 "),
    (lambda k: 0.05 / ca.sqrt(1 + 0.5 * ca.cos(k) ** 2), 4, "r(kappa + 2 pi/4) = "),
    (lambda k: 0.03 + 0.005 * ca.fabs(ca.sin(k - 1.0)), 1, "the contour is not smooth"),
])
def test_seen5_kinks_and_wrong_periods_are_refused(func, symmetry, words):
    with pytest.raises(ModelDefinitionError) as err:
        Contour.from_function(func, symmetry=symmetry)
    assert words in str(err.value)
    if "not smooth" in words:        # the kink at kappa = 1, found on a 4096-point grid
        near = float(str(err.value).split("near kappa = ")[1].split(" ")[0])
        assert abs(near - 1.0) < 2 * math.pi / 4096


def test_seen5_table_angles_must_increase_monotonically():
    k = np.linspace(0.0, 2 * math.pi, 12, endpoint=False)
    r = 0.04 + 0.005 * np.cos(k)
    bad = k.copy()
    bad[5] = bad[4]
    with pytest.raises(ModelDefinitionError, match=r"kappa\[4\] = 2.0943951 is followed by "
                                                   r"kappa\[5\] = 2.0943951"):
        Contour.from_table(bad, r)
    over = np.linspace(0.0, 2 * math.pi, 12)            # repeats the first point
    with pytest.raises(ModelDefinitionError, match="an overlap of 0 rad; drop the last point"):
        Contour.from_table(over, r)


# ------------------------------------------------ the fuzz classes' own expectations
import fuzz_cases_geometry  # noqa: E402


@pytest.mark.parametrize("case", fuzz_cases_geometry.unconnected_cases(),
                         ids=lambda c: c["id"])
def test_fuzz_unconnected_cases_list_exactly_their_grounded_ports(case, tmp_path):
    path = tmp_path / "model.py"
    path.write_text(case["model"], encoding="utf-8")
    report = acausal2d.check(acausal2d.load_model(str(path)))
    assert list(report.grounded) == case["grounded"]
    for name in case["grounded"]:
        assert name + " (x, y, phi)" in str(report).replace("\n" + " " * 21, " ")
