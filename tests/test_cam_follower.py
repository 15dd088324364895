"""Cam joint K (seed Tab. 2.1): the follower's lift against the cam's design
law (knife edge on a polar Fourier contour, flat face on a support function,
roller on an eccentric circle, knife edge on a band-synthesised cam), the
contact force against m (y'' + g) + spring, the lift-off time against its
closed form, rolling (f = 1) against the epicycloid's ratio, and the joint
DOF in eq. 2.1."""
import math
import os
import sys

import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError, cli, start
from acausal2d.analysis.check import check
from acausal2d.library.belt import Contour, SupportContour
from acausal2d.library.planar import Body, Fixed
from acausal2d.library.planar.cam import CamFollower

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import cam_follower as cf  # noqa: E402

G = 9.81


@pytest.mark.parametrize("cls, law", [
    (cf.CamKnifeEdge, cf.harmonic_lift), (cf.CamFlatFollower, cf.harmonic_lift),
    (cf.CamRollerFollower, cf.eccentric_lift)], ids=lambda v: getattr(v, "__name__", None))
def test_follower_motion_matches_the_design_law(cls, law):
    res = acausal2d.simulate(cls(), stop_time=1.0, intervals=100, rtol=1e-10)
    theta = res["drive.phi"]
    lift = np.array([law(t) for t in theta])
    assert np.max(np.abs(res["guide.s"] - lift)) < 1e-8
    # vertical contact force = m (y'' + g) + spring preload and rate
    # (closed form for the harmonic law; the knife edge's normal is tilted)
    if law is cf.harmonic_lift:
        acc = cf.H / 2 * cf.OM ** 2 * np.cos(theta)
        F_y = cf.M * (acc + G) + cf.F0 + cf.K_SPRING * (lift - cf.R0)
        Fn_y = res["cam.Fn"] * np.sin(theta + res["cam.psi"])
        assert np.max(np.abs(Fn_y - F_y)) < 1e-6
    assert np.min(res["cam.Fn"]) > 0 and res.events == []
    assert np.all(res["cam.lifted"] == 0)


def _t_star(om):
    """Rigid flat follower: Fn = M (H/2 om^2 cos th + g) + F0 + K H/2 (1 - cos th)
    turns negative at cos th* = -(K H/2 + F0 + M g) / (M H/2 om^2 - K H/2)."""
    c = -(cf.K_SPRING * cf.H / 2 + cf.F0 + cf.M * G) / (cf.M * cf.H / 2 * om ** 2
                                                       - cf.K_SPRING * cf.H / 2)
    return math.acos(c) / om


def test_rigid_force_closure_ends_the_run_at_the_closed_form_lift_off():
    """The rigid contact cannot follow a lift-off: the run ends with an
    error naming the element, the time t* (closed form) and the way out;
    the motion up to t* comes with it and its force is >= 0."""
    compiled = acausal2d.compile_model(cf.CamFlatFollower())
    with pytest.raises(acausal2d.SimulationError) as info:
        compiled.simulate(stop_time=0.03, intervals=30, rtol=1e-10, params={"drive.om": 100.0})
    exc, t_star = info.value, _t_star(100.0)
    assert "CamFollower 'cam'" in str(exc) and "use contact='compliant'" in str(exc)
    assert "At t=0.0190839495" in str(exc) and abs(exc.time - t_star) < 1e-9
    part = exc.result
    assert abs(part.time[-1] - t_star) < 1e-9 and part.events[-1][1] == "cam.Fn < 0"
    before = part.time < part.time[-1]
    assert np.min(part["cam.Fn"][before]) > 0
    assert np.max(np.abs(part["cam.Fn"][~before])) < 1e-9


def test_knife_edge_on_a_band_synthesised_cam():
    """The analysis contour of a DB~SD synthesis (contour_export) as a cam:
    the knife edge on the y axis rises to r(pi/2 - theta) of that contour."""
    from acausal2d.library.synthesis.functional import BandStructure, synthesize
    from acausal2d.library.synthesis.contour_export import analysis_contour
    s = BandStructure.dbsd((0, 0), (-0.296, 0), lambda p: 0.05 * p + 0.02 * (1 - ca.cos(p)),
                           -1, 0.25)
    contour = analysis_contour(synthesize(s, np.linspace(0.0, 2.5, 251)), n_harm=200).contour

    class SynthCam(cf._Cam):
        y0 = float(contour.r(math.pi / 2))

        def __init__(self, **kw):
            super().__init__(**kw)
            self._build(CamFollower(contour, r_roller=0.0, q=start(math.pi / 2)))

    res = acausal2d.simulate(SynthCam(), stop_time=0.25, intervals=25, rtol=1e-10)
    expect = contour.r(math.pi / 2 - res["drive.phi"])
    assert np.ptp(expect) > 1e-3                           # the follower moves
    assert np.max(np.abs(res["guide.s"] - expect)) < 1e-8


class RollingRoller(Component):
    """A free roller (radius rr) rolling without slip on a fixed circular
    cam (radius R) under gravity, held on it by a groove (form closure)."""
    R, rr, alpha0 = 0.05, 0.02, math.pi / 2 - 0.1

    def __init__(self, **kw):
        super().__init__(**kw)
        self.base = Fixed()
        self.roller = Body(m=0.1, I=1e-4, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.cam = CamFollower(SupportContour(self.R), rolling=True, r_roller=self.rr,
                               closure="form", q=start(self.alpha0, fixed=True))
        self.connect(self.base.frame, self.cam.frame_a)
        self.connect(self.roller.frame_a, self.cam.frame_b)


def test_rolling_roller_turns_as_the_epicycloid():
    """Rolling without slip on a circle: the roller's absolute angle grows by
    (R + rr)/rr times the polar angle of its centre (epicycloid); eq. 2.1
    counts the joint with f = 1: F = 3(2-1) - (3-1) = 1."""
    res = acausal2d.simulate(RollingRoller(), stop_time=0.5, intervals=50, rtol=1e-10)
    ratio = (RollingRoller.R + RollingRoller.rr) / RollingRoller.rr
    alpha = np.unwrap(np.arctan2(res["roller.y"], res["roller.x"]))
    assert alpha[0] - alpha[-1] > 0.5                       # it rolled off the top
    assert np.max(np.abs(res["roller.phi"] - ratio * (alpha - alpha[0]))) < 1e-8
    assert np.max(np.abs(np.hypot(res["roller.x"], res["roller.y"])
                         - RollingRoller.R - RollingRoller.rr)) < 1e-10
    report = check(RollingRoller())
    assert (report.links, report.joints, report.grubler) == (2, 1, 1)


def test_cam_joint_dof_in_eq_2_1():
    """Cam, follower and ground: revolute (f = 1), prismatic (f = 1), cam
    joint (f = 2): F = 3(3-1) - 2 - 2 - 1 = 1."""
    report = check(cf.CamRollerFollower())
    assert (report.links, report.joints, report.grubler) == (3, 3, 1)


def test_bad_arguments_name_the_element():
    with pytest.raises(ModelDefinitionError, match="follower must be one of"):
        CamFollower(Contour.circle(0.05), follower="needle")
    with pytest.raises(ModelDefinitionError, match="contour must be a Contour"):
        CamFollower(0.05)
    with pytest.raises(ModelDefinitionError, match="closure must be"):
        CamFollower(Contour.circle(0.05), closure="glue")
    with pytest.raises(ModelDefinitionError, match="contact must be one of rigid, compliant"):
        CamFollower(Contour.circle(0.05), contact="soft")
    for bad in ({"closure": "form"}, {"rolling": True}):
        with pytest.raises(ModelDefinitionError, match="contact='compliant' is the force-closed"):
            CamFollower(Contour.circle(0.05), contact="compliant", **bad)
    with pytest.raises(ModelDefinitionError, match="compliant knife edge"):
        CamFollower(Contour.circle(0.05), contact="compliant")
    with pytest.raises(ModelDefinitionError, match="k_contact"):
        CamFollower(Contour.circle(0.05), contact="compliant", follower="flat", k_contact=0.0)
    with pytest.raises(ModelDefinitionError, match="d_contact"):
        CamFollower(Contour.circle(0.05), contact="compliant", follower="flat", d_contact=-1.0)


def test_cam_model_from_the_cli_writes_figures(tmp_path):
    code = cli.main(["simulate", os.path.join(ROOT, "models", "cam_follower.py"),
                     "--model", "CamRollerFollower", "--out", str(tmp_path)])
    assert code == 0
    assert (tmp_path / "lift.png").exists() and (tmp_path / "contact_force.png").exists()


def test_cam_is_drawn_with_its_contour():
    from acausal2d.visual.animation import validate_scene
    from acausal2d.visual.scene import build_scene
    res = acausal2d.simulate(cf.CamFlatFollower(), stop_time=0.1, intervals=5)
    scene = build_scene(res)
    validate_scene(scene)
    cams = [s for s in scene["shapes"] if s["type"] == "pulley" and "contour" in s]
    assert len(cams) == 1 and len(cams[0]["contour"]) == 240
    # the outline is the support function's contour: radius between R0 and R0 + H
    r = np.hypot(*np.array(cams[0]["contour"]).T)
    assert cf.R0 - 1e-12 <= r.min() and r.max() <= cf.R0 + cf.H + 1e-12


def test_rigid_lift_off_from_the_cli_exits_2_and_leaves_no_results(tmp_path, capsys):
    model = os.path.join(ROOT, "models", "cam_follower.py")
    args = ["simulate", model, "--model", "CamFlatFollower", "--intervals", "10",
            "--out", str(tmp_path)]
    assert cli.main(args + ["--stop-time", "0.03"]) == 0
    assert (tmp_path / "result.csv").exists()
    code = cli.main(args + ["--set", "drive.om=100", "--stop-time", "0.03"])
    err = capsys.readouterr().err
    assert code == 2
    assert "At t=0.0190839495 in CamFollower 'cam'" in err and "contact='compliant'" in err
    assert "Traceback" not in err
    assert not (tmp_path / "result.csv").exists() and not (tmp_path / "lift.png").exists()


class WheelOnIncline(Component):
    """A disc (a circular cam of radius R, the moving part) rolling without
    slip on a flat face inclined by alpha (the ground as a flat follower)."""
    R, alpha, m, I = 0.1, 0.3, 2.0, 0.004

    def __init__(self, **kw):
        super().__init__(**kw)
        a, R = self.alpha, self.R
        self.slope = Fixed(phi=-a)
        self.wheel = Body(m=self.m, I=self.I, x=start(R * math.sin(a), fixed=True),
                          y=start(R * math.cos(a)), phi=start(0.0, fixed=True),
                          w=start(0.0, fixed=True))
        self.contact = CamFollower(SupportContour(R), follower="flat", rolling=True,
                                   q=start(-math.pi / 2 - a))
        self.connect(self.wheel.frame_a, self.contact.frame_a)
        self.connect(self.slope.frame, self.contact.frame_b)


def test_disc_rolls_down_a_flat_face_with_the_closed_form_acceleration():
    """Flat face, rolling (f = 1): the centre runs down the slope by
    s = a t^2/2 with a = g sin(alpha) / (1 + I/(m R^2)), and the disc turns
    by -s/R; the normal force is m g cos(alpha)."""
    W = WheelOnIncline
    res = acausal2d.simulate(W(), stop_time=1.0, intervals=20, rtol=1e-10)
    t = res.time
    acc = G * math.sin(W.alpha) / (1 + W.I / (W.m * W.R ** 2))
    s = (res["wheel.x"] - res["wheel.x"][0]) * math.cos(W.alpha) \
        - (res["wheel.y"] - res["wheel.y"][0]) * math.sin(W.alpha)
    assert np.max(np.abs(s - acc * t ** 2 / 2)) < 1e-8
    assert np.max(np.abs(res["wheel.phi"] + s / W.R)) < 1e-8
    assert np.max(np.abs(res["contact.Fn"] - W.m * G * math.cos(W.alpha))) < 1e-7
    assert check(W()).grubler == 1
