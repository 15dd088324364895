"""Singular positions: a double rocker whose input link is driven past the
end of its range stops at the limit position with a report naming the
elements, not with a raw solver failure; a parallelogram four-bar whose
crank turns through the change points (the dyad's two branches meet) is
followed on its branch and the positions passed are reported."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Fixed, FixedTranslation, Revolute
from acausal2d.library.rotational import Inertia, Position
from vdi2729_reference import vdi_dan, vdi_ddd
from acausal2d.library.signals import TimeFunction
from conftest import assert_copied

A, B, C, D = 0.6, 1.4, 0.9, 1.0        # input, coupler, output rocker, ground (non-Grashof)
PHI0, RATE = math.radians(60.0), -0.5


def _assembly(phi):
    """Closed-form position of the four-bar for input angle phi (one branch)."""
    b = np.array([A * math.cos(phi), A * math.sin(phi)])
    dvec = np.array([D, 0.0]) - b
    L = np.linalg.norm(dvec)
    e = dvec / L
    x = (B * B - C * C + L * L) / (2 * L)
    c = b + x * e + math.sqrt(B * B - x * x) * np.array([-e[1], e[0]])
    return b, c


class DrivenDoubleRocker(Component):
    """Four revolute joints; the input joint follows phi0 + rate*t."""

    def __init__(self, **kw):
        super().__init__(**kw)
        pb, pc = _assembly(PHI0)
        th_b = math.atan2(pc[1] - pb[1], pc[0] - pb[0])
        th_c = math.atan2(-pc[1], D - pc[0])      # rocker frame points from C to D
        self.ground_a = Fixed()
        self.ground_d = Fixed(r=(D, 0.0))
        self.ja = Revolute(use_flange=True, phi=start(PHI0))
        self.crank = FixedTranslation(r=(A, 0.0))
        self.jb = Revolute(phi=start(th_b - PHI0))
        self.coupler = FixedTranslation(r=(B, 0.0))
        self.jc = Revolute(phi=start(th_c - th_b))
        self.rocker = FixedTranslation(r=(C, 0.0))
        self.jd = Revolute()
        self.drive = Position()
        self.angle = TimeFunction(lambda t: PHI0 + RATE * t)
        self.connect(self.angle.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.ja.flange_a)
        self.connect(self.ground_a.frame, self.ja.frame_a)
        self.connect(self.ja.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.jb.frame_a)
        self.connect(self.jb.frame_b, self.coupler.frame_a)
        self.connect(self.coupler.frame_b, self.jc.frame_a)
        self.connect(self.jc.frame_b, self.rocker.frame_a)
        self.connect(self.rocker.frame_b, self.jd.frame_b)
        self.connect(self.ground_d.frame, self.jd.frame_a)


def test_double_rocker_stops_at_limit_position():
    res = acausal2d.simulate(DrivenDoubleRocker(), stop_time=4.0, rtol=1e-8, intervals=400)
    # limit: coupler folded onto the output rocker, |BD| = B - C
    phi_lim = math.acos((A * A + D * D - (B - C) ** 2) / (2 * A * D))
    t_lim = (phi_lim - PHI0) / RATE
    assert res.stopped is not None and "limit position" in res.stopped
    assert res.time[-1] == pytest.approx(t_lim, abs=1e-4)
    assert res.time[-1] < 4.0
    sing = res.singularities[-1]
    assert sing["kind"] == "limit position"
    assert sing["time"] == pytest.approx(t_lim, abs=1e-4)
    assert "FixedTranslation 'coupler'" in sing["elements"]
    assert "FixedTranslation 'rocker'" in sing["elements"]
    # up to the limit the motion is the closed-form one
    for k in range(0, len(res.time), 20):
        phi = res["ja.phi"][k]
        _, pc = _assembly(phi)
        assert res["rocker.frame_a.x"][k] == pytest.approx(pc[0], abs=1e-7)
        assert res["rocker.frame_a.y"][k] == pytest.approx(pc[1], abs=1e-7)


class Parallelogram(Component):
    """Crank 0.1 m about the origin, coupler 0.4 m, rocker 0.1 m about
    (0.4, 0): at crank angles 0 and pi all four links are collinear and the
    parallelogram and the antiparallelogram branch of the dyad meet."""

    def __init__(self, K=1, **kw):
        super().__init__(**kw)
        self.preset = Preset(om=2 * math.pi, phi0=0.3)
        self.crank = DAN(lL=0.1)
        self.dyad = DDD(lL1=0.4, lL2=0.1, x20=0.4, y20=0.0, K=K)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


def _branches(phi):
    """Closed form: the dyad's point P on the parallelogram branch
    (P = B0 + crank vector) and on the antiparallelogram branch (the other
    intersection of the two circles)."""
    B0 = np.array([0.4, 0.0])
    P1 = vdi_dan(np.zeros(2), 0.1, phi)
    par = B0 + (P1 - np.zeros(2))
    both = [vdi_ddd(P1, B0, 0.4, 0.1, K) for K in (1, -1)]
    anti = max(both, key=lambda q: np.linalg.norm(q - par))
    return par, anti


@pytest.mark.parametrize("K", [1, -1])
def test_change_point_four_bar_is_followed_through_branch_points(K):
    """Two crank revolutions: the branch K picked at t = 0 is kept through
    the four change points (crank angle pi, 2 pi, 3 pi, 4 pi) - not flipped
    to the other branch, which re-applying K at every instant would do - and
    each passage is reported with its time and the dyad."""
    res = acausal2d.simulate(Parallelogram(K), stop_time=2.0, rtol=1e-8, intervals=400)
    assert res.stopped is None and res.time[-1] == pytest.approx(2.0, abs=1e-12)
    phi = res["crank.phiL"]
    P = np.column_stack([res["dyad.xP"], res["dyad.yP"]])
    par0, anti0 = _branches(phi[0])
    on_par = np.linalg.norm(P[0] - par0) < 1e-9
    assert on_par or np.linalg.norm(P[0] - anti0) < 1e-9
    assert on_par == (K == 1)       # K = 1: P left of P1 -> P2, here the parallelogram
    err = [np.linalg.norm(P[k] - _branches(p)[0 if on_par else 1]) for k, p in enumerate(phi)]
    assert max(err) < 1e-8
    # the output link: parallel to the crank, or turning the other way round
    turn = res["dyad.phiL2"][-1] - res["dyad.phiL2"][0]
    assert turn == pytest.approx(4 * math.pi if on_par else -4 * math.pi, abs=1e-8)
    passed = [s for s in res.singularities if s["kind"] == "singular position passed"]
    expected = [(k * math.pi - 0.3) / (2 * math.pi) for k in (1, 2, 3, 4)]
    assert [s["time"] for s in passed] == pytest.approx(expected, abs=1e-6)
    assert all("DDD 'dyad'" in s["elements"] for s in passed)


class SwingingParallelogram(Component):
    """The parallelogram force-driven: massive links under gravity and a
    flywheel on the crank, started at 0.3 rad with 2 pi rad/s.  Too little
    energy to turn over: the crank swings about its lowest position through
    both change points (crank angle 0 and -pi) again and again."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flywheel = Inertia(J=0.01, phi=start(0.3, fixed=True),
                                w=start(2 * math.pi, fixed=True))
        self.crank = DAN(lL=0.1, mL=1.0, JL=0.001)
        self.dyad = DDD(lL1=0.4, lL2=0.1, x20=0.4, y20=0.0, K=1,
                        mL1=1.0, JL1=0.02, mL2=1.0, JL2=0.001)
        self.connect(self.flywheel.flange_a, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


def test_force_driven_change_point_four_bar_keeps_its_branch():
    """Dynamic analysis: the swinging parallelogram passes the change points
    on the parallelogram branch (rocker parallel to the crank), and every
    passage is reported at crank angle 0 or -pi."""
    res = acausal2d.simulate(SwingingParallelogram(), stop_time=1.0, rtol=1e-8, intervals=400)
    assert res.stopped is None and res.time[-1] == pytest.approx(1.0, abs=1e-12)
    phi = res["crank.phiL"]
    rocker = np.unwrap(res["dyad.phiL2"])
    assert np.max(np.abs(rocker - phi - (rocker[0] - phi[0]))) < 1e-8
    # it swings: both change points are passed, back and forth
    assert np.min(phi) < -math.pi + 0.1 and np.max(phi) > 0.1
    passed = [s for s in res.singularities if s["kind"] == "singular position passed"]
    assert len(passed) >= 3
    for s in passed:
        angle = res.at("crank.phiL", s["time"])
        assert abs(angle - math.pi * round(angle / math.pi)) < 1e-3
        assert "DDD 'dyad'" in s["elements"]


def test_buffered_determinant_scan_equals_plain_evaluation():
    """The scan for passed singular positions evaluates the watched block
    determinants in chunks through a buffer; across chunk boundaries
    (600 points, chunks of 256) it gives the values of a plain call."""
    from conftest import load_model_class
    from acausal2d.runtime.singularities import DeterminantScan as _DeterminantScan
    cm = acausal2d.compile_model(load_model_class("piston_engine_dynamic.py",
                                                  "PistonEngineDynamic")())
    p = cm.parameter_values()
    point = cm.initial_point()
    d = point.d
    form = cm.system.formulation(point.selection)
    assert form.det_fn is not None
    n = 600
    rng = np.random.default_rng(1)
    T, Y, YP = rng.random(n), rng.random((n, form.n)), rng.random((n, form.n))
    d = np.asarray(d, float)
    scanned = _DeterminantScan(form)(T, Y, YP, p, d)
    plain = np.column_stack([form.det_fn(T[k], Y[k], YP[k], p, d).full().ravel()
                             for k in range(n)]).T
    assert scanned.shape == plain.shape
    assert_copied(scanned, plain)          # one CasADi function, in chunks or one by one
