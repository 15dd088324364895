"""Seed eq. 2.1 in full on the three mechanisms of Bild 2.1 (ch. 2.2):
F = 1, 1, 2 from the check, the band length of (b)/(c) against the tangent
construction, the same start ratio in (a) and (b), and the identical freedom
of (c) (the slipping pulley keeps its speed, rocker 6 moves as in (b))."""
import math
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis.check import check, _terms
from acausal2d.library.belt import GuideContour

sys.path.insert(0, os.path.join(os.path.dirname(__file__), os.pardir, "models"))
import dof_bild_2_1 as b21  # noqa: E402


@pytest.mark.parametrize("cls, links, joints, F, terms", [
    (b21.Bild21a, 6, 7, 1, ""),                                    # 3(6-1) - 7(3-1)
    (b21.Bild21b, 5, 6, 1, ", 2 band joints, 1 coupling"),         # 3(5-1) - [4*2 + 2*1 + 1]
    (b21.Bild21c, 6, 7, 2, ", 2 band joints, 1 coupling"),         # 3(6-1) - [5*2 + 2*1 + 1]
])
def test_check_prints_the_seed_F(cls, links, joints, F, terms):
    report = check(cls())
    assert (report.links, report.joints, report.grubler) == (links, joints, F)
    assert "degree of freedom: %d by Ebert (2015) eq. 2.1 (n = %d links with ground, g = %d joints%s)" \
        % (F, links, joints, terms) in str(report)


def test_identical_freedom_and_passive_constraint_terms():
    """A door on two hinges (seed ch. 2.2): 3(2-1) - 2(3-1) = -1, with the
    passive constraint s = 2 of the second hinge F = 1; an identical
    freedom declared by the model is subtracted."""
    from acausal2d import Component, start
    from acausal2d.library.planar import Body, Fixed, Revolute

    class Door(Component):
        def __init__(self, s=2, f_id=0, **kw):
            super().__init__(**kw)
            self.s, self.f_id = s, f_id
            self.wall = Fixed()
            self.hinge1 = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
            self.door = Body(m=1.0, I=0.1)
            self.connect(self.wall.frame, self.hinge1.frame_a)
            self.connect(self.hinge1.frame_b, self.door.frame_a)

        def topology(self):     # the second hinge on the same axis
            return [("joint", self.wall.frame, self.door.frame_a, 1),
                    ("passive", self.s), ("identical", self.f_id)]

    from acausal2d.analysis.check import _planar_topology
    n, g, F, _, extra = _planar_topology(Door())
    assert (n, g, F) == (2, 2, 1)
    assert _planar_topology(Door(s=0))[2] == -1
    assert _planar_topology(Door(f_id=1))[2] == 0
    assert _terms(extra) == ", s = 2"


def _sim(cls):
    return acausal2d.simulate(cls(), stop_time=1.0, intervals=50, rtol=1e-10)


def _band_length(phi2, phi6):
    """|A K1| + r beta + |K2 B| by the tangent construction (closed form)."""
    C, r = b21.C0, b21.R_CONTOUR
    out = []
    for p2, p6 in zip(phi2, phi6):
        a = (b21.A0[0] + b21.R_ROCKER * math.cos(p2), b21.A0[1] + b21.R_ROCKER * math.sin(p2))
        b = (b21.B0[0] + b21.R_ROCKER6 * math.cos(p6), b21.B0[1] + b21.R_ROCKER6 * math.sin(p6))
        da, db = math.dist(a, C), math.dist(b, C)
        th1 = math.atan2(a[1] - C[1], a[0] - C[0]) - math.acos(r / da)
        th2 = math.atan2(b[1] - C[1], b[0] - C[0]) + math.acos(r / db)
        beta = (th1 - th2) % (2 * math.pi)         # clockwise wrap K1 -> K2
        out.append(math.sqrt(da * da - r * r) + r * beta + math.sqrt(db * db - r * r))
    return np.array(out)


def test_band_length_constant_and_taut():
    res = _sim(b21.Bild21b)
    length = _band_length(res["rocker2.phiL"], res["rocker6.phiL"])
    assert abs(res["rocker2.phiL"][-1] - res["rocker2.phiL"][0] - 0.4) < 1e-9
    assert abs(res["rocker6.phiL"][-1] - res["rocker6.phiL"][0]) > 0.1    # it moved
    assert np.max(np.abs(length - length[0])) < 1e-8
    assert np.min(res["band3.F"]) > 0 and np.min(res["band4.F"]) > 0
    # frictionless contour: both sections carry the same force
    assert np.max(np.abs(res["band3.F"] - res["band4.F"])) < 1e-8 * np.max(res["band3.F"])


def test_identical_freedom_of_the_slipping_pulley():
    """(c): the pulley's turn does not change the transfer (rocker 6 as in
    (b)) and no torque reaches it (its speed stays at the start value)."""
    rb, rc = _sim(b21.Bild21b), _sim(b21.Bild21c)
    assert np.max(np.abs(rb["rocker6.phiL"] - rc["rocker6.phiL"])) < 1e-8
    assert np.max(np.abs(rc["bearing.w"] - 1.0)) < 1e-8


def test_same_start_ratio_in_a_and_b():
    """Bild 2.1: momentarily the same transfer.  The pins of link 4 in (a)
    sit at the start contact points of (b): omega6/omega2 agree at t = 0
    (and differ later, when the band's contact points move)."""
    ra, rb = _sim(b21.Bild21a), _sim(b21.Bild21b)
    ia = ra["der(dyad2.phiL2)"][0] / ra["der(rocker2.phiL)"][0]
    ib = rb["der(rocker6.phiL)"][0] / rb["der(rocker2.phiL)"][0]
    assert abs(ia - ib) < 1e-7 * abs(ib)
    assert abs(ra["dyad2.phiL2"][-1] - rb["rocker6.phiL"][-1]) > 1e-4


def test_guide_contour_is_massless():
    with pytest.raises(acausal2d.errors.ModelDefinitionError, match="GuideContour.*massless"):
        GuideContour(m=1.0)


def test_check_and_simulate_from_the_cli(tmp_path, capsys):
    from acausal2d import cli
    path = os.path.join(os.path.dirname(__file__), os.pardir, "models", "dof_bild_2_1.py")
    assert cli.main(["check", path, "--model", "Bild21c"]) == 0
    assert "degree of freedom: 2 by Ebert (2015) eq. 2.1" in capsys.readouterr().out
    assert cli.main(["simulate", path, "--model", "Bild21b", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "transfer.png").exists()
