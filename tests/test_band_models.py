"""The band synthesis models: Hain's spring-lever balance, the cabinet door
(seed ch. 7.2.1) with the round trip synthesis -> CurvedDrum + SpringBelt
analysis, the DB~DS synthesis (seed ch. 7.2.2), and their CLI runs."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.belt import SpringBelt, connect_band
from acausal2d.library.belt.curved import CurvedDrum
from acausal2d.library.synthesis.contour_export import analysis_contour
from acausal2d.library.planar import Fixed
from conftest import ROOT, load_model_class, assert_copied

HainSpringLever = load_model_class("hain_spring_lever.py", "HainSpringLever")
load_model_class("cabinet_door.py", "door_design")
load_model_class("db_ds_synthesis.py", "design")
hain = sys.modules["models_hain_spring_lever"]
door = sys.modules["models_cabinet_door"]
dbds = sys.modules["models_db_ds_synthesis"]


# --------------------------------------------------------------------------
# Hain's spring-lever balance (eq. 3.10-3.12)
# --------------------------------------------------------------------------
def test_hain_lever_is_balanced():
    """c_S = m g k/(r b) (3.12): the lever, turned at constant speed, needs
    no drive torque anywhere in the range (<= 1e-9 N m; observed 1e-10)."""
    res = acausal2d.simulate(HainSpringLever())
    phi = math.pi / 2 - res["lever.phiL"]
    assert np.min(phi) < 0.4 and np.max(phi) > 2.7
    assert np.max(np.abs(res["drive.tau"])) <= 1e-9
    assert hain.C_BALANCE == pytest.approx(78.48)


@pytest.mark.parametrize("factor, a", [(0.8, 0.0), (1.0, 0.1)])
def test_hain_lever_torque_formula(factor, a):
    """Off balance (softer spring) and with a free spring length a: the
    drive torque is m g k sin(phi) - T(phi) with T the spring torque of eq.
    3.10 (the drive holds what weight and spring leave)."""
    res = acausal2d.simulate(HainSpringLever(c_S=factor * hain.C_BALANCE, a=a))
    phi = math.pi / 2 - res["lever.phiL"]
    weight = hain.MASS * hain.G * hain.K_COG * np.sin(phi)
    spring = hain.spring_torque(phi, factor * hain.C_BALANCE, a)
    assert np.max(np.abs(res["drive.tau"] - (weight - spring))) < 1e-8
    assert np.max(np.abs(res["drive.tau"])) > 1.0


# --------------------------------------------------------------------------
# cabinet door (seed ch. 7.2.1)
# --------------------------------------------------------------------------
@pytest.fixture(scope="module")
def design():
    return door.door_design()


def test_door_design(design):
    """Required torque from the door mechanism (2 kg on the coupler, the
    seed's test mass), the regression, the two ch. 6 runs and the
    assessment of the synthesised cam.  Run 1's spring is the closed form
    c_S = T(open)/(h_max x_S(open)) (the softest spring for h <= 80 mm; h
    is largest where the extension is least) to the bisection's 1e-12.
    That it lands within 3 % below the catalogue spring of Ebert (2015),
    938 N/m, is not a reproduction: the open extension X_OPEN = 36 mm is
    chosen to match it (the text does not give the pretension; c_S is 1670,
    928 and 668 N/m at 20, 36 and 50 mm); stiffer, run 2 keeps h <= h_max."""
    T = design.T
    assert np.all(T > 0)                              # the door rises over the whole range
    assert design.r2 > 0.99999
    assert np.max(np.abs(design.required_torque(design.phi) - T)) < 3e-3 * T.max()
    run1, fit = design.run1, design.fit
    T_open = design.required_torque(door.SPAN)
    assert run1.c_S == pytest.approx(T_open / (door.H_MAX * door.X_OPEN), rel=1e-9)
    assert 0.97 * 938.0 < run1.c_S <= 938.0
    assert np.max(run1.h) <= door.H_MAX + 1e-12
    assert_copied(fit.c_S, 938.0)                     # the given rate
    assert fit.x[0] == pytest.approx(door.X_OPEN, abs=1e-15)
    assert np.max(fit.h) <= door.H_MAX + 1e-12 and np.min(fit.h) > 0
    assert fit.max_abs < 0.01 * T.max()               # the balanced door's criterion
    assert np.all(np.abs(fit.x - fit.x_exact) <= fit.deviation_bound() + 1e-12)
    a = design.synthesis.assess(a_max=door.A_MAX)
    assert a.ok, a.report()
    assert a.values["S_Bf"] == "+1" and a.values["GF1 sign"] == "-1"
    assert a.values["l_Bf range"][0] > 0.05          # the spring eye stays off the cam


def test_door_synthesis_model_equals_functional(design):
    """The seed's synthesis model (presets A0, B0, DB_SD with h(phi) from the
    optimisation, Bandkurve) gives the functional contour."""
    model = door.BalancingSynthesis()
    res = acausal2d.simulate(model, output_times=np.linspace(0.0, door.SPAN, 61))
    v = design.synthesis.evaluate(res.time)
    assert np.max(np.hypot(res["bandkurve.xu"] - v["x_u"], res["bandkurve.yu"] - v["y_u"])) \
        < 1e-8
    assert np.max(np.abs(res["bandkurve.l_Bf"] - v["l_Bf"])) < 1e-8
    assert_copied(res["bandkurve.S_Bf"], 1.0)              # a sign flag
    # the DB~SD material point is the spring eye: l0 + x_S from B0
    d = np.hypot(res["dbsd.ctr2D3.x"] - door.B0[0], res["dbsd.ctr2D3.y"] - door.B0[1])
    xs = design.fit.x_at(door.SPAN - res.time)
    assert np.max(np.abs(d - (door.L0_SPRING + xs))) < 1e-8


class RoundTrip(Component):
    """The synthesised door cam as a CurvedDrum turned through the cam range
    by an angle drive, the band with the 938 N/m spring to B0."""

    def __init__(self, des, **kw):
        super().__init__(**kw)
        k0 = float(des.contour.kappa([0.0])[0])
        v = des.synthesis.evaluate([0.0])
        gamma = math.atan2(door.B0[1] - v["y_u"][0], door.B0[0] - v["x_u"][0])
        self.cam = CurvedDrum(des.contour.contour, w_i=1, x10=0.0, y10=0.0, kappa1=start(k0))
        self.spring = SpringBelt(k=door.C_SPRING, l0=door.L0_SPRING, gamma=start(gamma),
                                 l_dF=start(des.x_closed, fixed=True))
        self.B0 = Fixed(r=door.B0)
        connect_band(self, self.spring, 1, self.cam, 1)
        self.connect(self.spring.ctr2D2, self.B0.frame)
        self.drive = rotational.Position()
        self.angle = signals.TimeFunction(lambda t: t)
        self.connect(self.angle.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.cam.ctrR2)


def test_round_trip_reproduces_spring_travel(design):
    """Synthesised contour -> CurvedDrum + SpringBelt: the spring extension
    follows the prescribed x_S(phi) to 1e-5 relative (observed ~1e-6, the
    polar Fourier contour's radial error of 2e-7 m), and the torque the cam
    needs is c_S x_S h (6.3)."""
    assert design.contour.arc_error < 5e-7
    res = acausal2d.simulate(RoundTrip(design), stop_time=door.SPAN, rtol=1e-10,
                             output_times=np.linspace(0.0, door.SPAN, 51))
    psi = door.SPAN - res["cam.phi"]
    xs = design.fit.x_at(psi)
    assert np.max(np.abs(res["spring.l_dF"] / xs - 1.0)) < 1e-5
    torque = door.C_SPRING * xs * design.fit.h_at(psi)
    assert np.max(np.abs(np.abs(res["drive.flange.tau"]) / torque - 1.0)) < 1e-4


def test_balanced_door_needs_no_torque(design):
    """The door with the synthesised cam and the 938 N/m spring: the static
    drive torque stays below 1 % of the largest required torque at every
    angle of the range (the ch. 6 residual, 0.88 %)."""
    res = acausal2d.simulate(door.BalancedDoor())
    phi = res["cam.phi"]
    assert phi[0] == pytest.approx(0.0, abs=1e-9) and phi[-1] == pytest.approx(door.SPAN)
    assert np.max(np.abs(res["drive.tau"])) < 0.01 * np.max(design.T)
    # the cam holds the door: the moment about A0 it takes from the rocker it
    # sits on (the housing port's force and torque at the rocker's end C,
    # A.16-A.18) is what the door mechanism alone needs (same quasi-static
    # run, same angles)
    arm = (res["rocker.ctr2D2.x"] - door.A0[0], res["rocker.ctr2D2.y"] - door.A0[1])
    on_cam = (res["cam.ctr2D1.t"] + arm[0] * res["cam.ctr2D1.fy"]
              - arm[1] * res["cam.ctr2D1.fx"])
    held = res["drive.tau"] - on_cam
    assert np.max(np.abs(held - np.interp(phi, design.phi, design.T))) < 1e-6


# --------------------------------------------------------------------------
# DB~DS (seed ch. 7.2.2)
# --------------------------------------------------------------------------
def test_db_ds_synthesis():
    """The seed's results: free band length 100 .. 350 mm, largest cam
    radius about 120 mm, S_Bf constant; the model (SAN + Bandkurve) gives
    the functional contour."""
    syn = dbds.design()
    a = syn.assess()
    assert a.ok, a.report()
    lo, hi = a.values["l_Bf range"]
    assert 0.095 < lo < 0.105 and 0.34 < hi < 0.37
    assert 0.11 < a.values["max a"] < 0.125
    res = acausal2d.simulate(dbds.DBDSSynthesis(), output_times=np.linspace(0, dbds.PSI_END, 81))
    v = syn.evaluate(res.time)
    assert np.max(np.hypot(res["bandkurve.xu"] - v["x_u"], res["bandkurve.yu"] - v["y_u"])) \
        < 1e-7
    assert_copied(res["bandkurve.S_Bf"], -1.0)
    ac = analysis_contour(syn)
    assert ac.arc_error < 1e-7 and ac.kappa_range[1] - ac.kappa_range[0] > 3.5


@pytest.mark.parametrize("model, files", [
    (["db_ds_synthesis.py"], ["db_ds_cam.dxf", "db_ds_cam.svg", "db_ds_cam.csv",
                              "db_ds_involute_evolute.png", "db_ds_criteria.png", "db_ds_cam.png",
                              "db_ds_assessment.txt"]),
    (["cabinet_door.py", "--model", "BalancingSynthesis"],
     ["cabinet_door_cam.dxf", "cabinet_door_cam.svg", "cabinet_door_cam.csv",
      "cabinet_door_involute.png", "cabinet_door_transfer.png", "cabinet_door_criteria.png",
      "cabinet_door_assessment.txt"]),
    (["cabinet_door.py"], ["cabinet_door_balance.png"]),       # default: BalancedDoor
    (["hain_spring_lever.py"], ["hain_torques.png"])],
    ids=["db_ds_synthesis", "cabinet_door_synthesis", "cabinet_door", "hain_spring_lever"])
def test_models_run_from_the_cli(model, files, tmp_path):
    """The model's own files (write_outputs) are written, named in the
    summary and listed in the run's manifest, so the next run into the same
    folder removes them first; no temporary file is left."""
    import json
    from acausal2d.io.files import MANIFEST, _TEMPORARY
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    proc = subprocess.run([exe, "simulate", os.path.join(ROOT, "models", model[0]), *model[1:],
                           "--out", str(tmp_path)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    for name in files:
        assert (tmp_path / name).stat().st_size > 100, name
        assert name in proc.stdout
    listed = json.loads((tmp_path / MANIFEST).read_text())["files"]
    assert set(files) <= set(listed) and "result.csv" in listed
    assert not [p for p in os.listdir(tmp_path) if _TEMPORARY.match(p)]


def test_readme_band_synthesis_section(tmp_path, monkeypatch):
    """The user guide's "Band synthesis" page (the README's section until
    issue 31), up to its first subsection: its snippet runs as printed
    (report, criteria plot, cam files written into out/) and its picture is
    there, drawn by db_ds_synthesis.plot_cam."""
    import re
    page = os.path.join(ROOT, "docs", "user-guide", "band-synthesis.md")
    text = open(page, encoding="utf-8").read()
    section = text.split("\n## ", 1)[0]
    snippet = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(tmp_path)
    exec(compile(snippet, "docs/user-guide/band-synthesis.md", "exec"), {})
    assert sorted(os.listdir(tmp_path / "out")) == ["cam.csv", "cam.dxf", "cam.svg",
                                                    "criteria.png"]
    pictures = re.findall(r"!\[[^]]*\]\(([^)]+\.png)\)", section)
    assert len(pictures) == 1
    from matplotlib import image as mpimg
    img = mpimg.imread(os.path.join(os.path.dirname(page), pictures[0]))
    assert img.shape[0] > 400 and np.std(img[:, :, :3]) > 0.05
    again = mpimg.imread(dbds.plot_cam(dbds.design(), str(tmp_path / "cam.png")))
    assert again.shape == img.shape          # the same figure, drawn by today's code
