"""Cable crane of seed ch. 8.1 (models/cable_crane.py, library/crane.py)."""
import math

import numpy as np
import pytest

from acausal2d import compile_model
from conftest import load_model_class

CableCrane = load_model_class("cable_crane.py", "CableCrane")
static_pose = load_model_class("cable_crane.py", "static_pose")
rope_geometry = load_model_class("cable_crane.py", "rope_geometry")
plot_cycle = load_model_class("cable_crane.py", "plot_cycle")
SECTIONS = load_model_class("cable_crane.py", "SECTIONS")
ROPES = load_model_class("cable_crane.py", "ROPES")

G = 9.81
M_HOOK = load_model_class("cable_crane.py", "M_HOOK")
M_CARRIAGE = load_model_class("cable_crane.py", "M_CARRIAGE")
F_SKY0 = load_model_class("cable_crane.py", "F_SKY0")
X_END = load_model_class("cable_crane.py", "X_END")
DROP_LOW = load_model_class("cable_crane.py", "DROP_LOW")
R_PULLEY = load_model_class("cable_crane.py", "R_PULLEY")
T_STOP = load_model_class("cable_crane.py", "T_STOP")
T_LIFT = load_model_class("cable_crane.py", "T_LIFT")
D_LIFT = load_model_class("cable_crane.py", "D_LIFT")


def trolley_haul_force(gam_sky_left, gam_sky_right, gam_load, gam_haul, F_load,
                       m_total=M_CARRIAGE + M_HOOK):
    """Closed form of the haul-back force of a frictionless carriage at rest.

    The two skyline spans at the carriage carry the same force F_s, so their
    resultant F_s (e_R - e_L) is perpendicular to the bisector
    u = e_L + e_R of the span directions (e_L: W1 -> S reversed, i.e. the
    direction S -> W1; e_R: W2 -> T).  Projecting the force balance of
    carriage and hook on u eliminates the skyline:

        F_haul (e_H . u) + F_load (e_A . u) - m g (j . u) = 0

    with e_H, e_A the directions in which haul-back and load rope pull the
    carriage (towards MH and MR) and j the upward unit vector."""
    eL = np.array([np.cos(gam_sky_left), np.sin(gam_sky_left)])
    eR = np.array([np.cos(gam_sky_right), np.sin(gam_sky_right)])
    u = eL + eR
    eH = -np.array([np.cos(gam_haul), np.sin(gam_haul)])
    eA = -np.array([np.cos(gam_load), np.sin(gam_load)])
    dot = lambda a, b: a[0] * b[0] + a[1] * b[1]  # noqa: E731 (works on arrays of angles)
    return (m_total * G * u[1] - F_load * dot(eA, u)) / dot(eH, u)


def test_static_pose_matches_trolley_closed_form():
    for x in (13.0, 25.0, 38.0):
        st = static_pose(x, 4.0, F_sky=F_SKY0)
        sky, _ = rope_geometry("sky", st["pose"])
        load, _ = rope_geometry("load", st["pose"])
        haul, _ = rope_geometry("haul", st["pose"])
        ref = trolley_haul_force(sky[1]["gamma"], sky[3]["gamma"], load[2]["gamma"],
                                 haul[1]["gamma"], M_HOOK * G)
        assert st["F_haul"] == pytest.approx(ref, rel=1e-9)
        assert st["F_load"] == pytest.approx(M_HOOK * G, rel=1e-15)
        assert 0 < st["F_haul"] < M_HOOK * G


@pytest.fixture(scope="module")
def cycle():
    cm = compile_model(CableCrane())
    res = cm.simulate(stop_time=T_STOP, rtol=1e-9, output_times=np.linspace(0.0, T_STOP, 301))
    return cm, res


def test_rest_state_is_static_equilibrium(cycle):
    cm, res = cycle
    rest = res.time <= T_LIFT
    assert rest.sum() >= 10
    # nothing moves before the drums start
    for name in ("carriage.x", "carriage.y", "carriage.phi", "hook.x", "hook.y"):
        assert np.max(np.abs(res[name][rest] - res[name][0])) < 1e-9, name
    # rope forces: the hook load in every load-rope section, the pretension in
    # every skyline section, the trolley closed form in the haul-back rope
    for s in SECTIONS["load"]:
        assert np.max(np.abs(res[s + ".F"][rest] / (M_HOOK * G) - 1)) < 1e-9, s
    for s in SECTIONS["sky"]:
        assert np.max(np.abs(res[s + ".F"][rest] / F_SKY0 - 1)) < 1e-9, s
    ref = trolley_haul_force(res["sky2.gamma"][rest], res["sky4.gamma"][rest],
                             res["load3.gamma"][rest], res["haul2.gamma"][rest],
                             res["load3.F"][rest])
    for s in SECTIONS["haul"]:
        assert np.max(np.abs(res[s + ".F"][rest] / ref - 1)) < 1e-8, s
    # the hook hangs vertically below pulley C
    assert np.max(np.abs(np.cos(res["load6.gamma"][rest]))) < 1e-9


def _material(res, rope):
    """Unstretched rope material between the drum contact (or anchor) and
    the rope end: geometric span lengths l/(1 + eps) plus wrapped arcs."""
    nodes = ROPES[rope]
    m = sum(res[s + ".l"] / (1 + res[s + ".eps"]) for s in SECTIONS[rope])
    for node in nodes:
        if node[0] == "pulley":
            m = m + R_PULLEY * res[node[1] + ".beta"]
    return m


def test_rope_bookkeeping(cycle):
    cm, res = cycle
    # drum payout = change of the geometric (unstretched) rope length
    for rope, drum in (("load", "D1"), ("haul", "D2")):
        payout = -(res[drum + ".l_wound"] - res[drum + ".l_wound"][0])
        dm = _material(res, rope) - _material(res, rope)[0]
        assert np.max(np.abs(payout - dm)) < 1e-7, rope
        assert np.max(np.abs(payout)) > 20.0          # the transport moved rope
    # the skyline keeps its material
    m = _material(res, "sky")
    assert np.max(np.abs(m - m[0])) < 1e-7
    # lifting with the carriage held: D1 winds up exactly 4 m
    k = np.argmin(np.abs(res.time - (T_LIFT + D_LIFT)))
    assert res["D1.l_wound"][k] - res["D1.l_wound"][0] == pytest.approx(4.0, abs=1e-9)
    assert np.all(res["D1.l_wound"] > 0) and np.all(res["D2.l_wound"] > 0)


def test_cycle_completes_with_taut_ropes(cycle, tmp_path):
    cm, res = cycle
    assert res.time[-1] == pytest.approx(T_STOP)
    # only the time events of the drive functions: no rope went slack
    assert all(txt.startswith("time") for _, txt in res.events), res.events
    for rope in SECTIONS.values():
        for s in rope:
            assert np.min(res[s + ".F"]) > 1000.0, s
            assert np.min(res[s + ".eps"]) > 0.0, s
    # the carriage stays on the skyline: both running wheels stay wrapped
    for w in ("W1", "W2"):
        assert np.min(res[w + ".beta"]) > math.radians(0.5)
    # the carriage arrives where the drive design put it; the hook is lowered
    end = static_pose(X_END, DROP_LOW, sky_material=cm.model.design["start"]["sky_material"],
                      guess=(12.0, 0.2, 6000.0, F_SKY0))
    assert res["carriage.x"][-1] == pytest.approx(end["pose"][0], abs=0.02)
    assert res["carriage.y"][-1] == pytest.approx(end["pose"][1], abs=0.05)
    assert res["hook.y"][-1] == pytest.approx(end["hook"][1], abs=0.1)
    # the transport loads the ropes dynamically, but moderately
    F = res["load1.F"]
    assert 0.8 * M_HOOK * G < F.min() < M_HOOK * G < F.max() < 1.2 * M_HOOK * G
    paths = plot_cycle(res, str(tmp_path))
    assert all((tmp_path / p.split("/")[-1]).stat().st_size > 1000 for p in paths)
