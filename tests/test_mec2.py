"""mec2 JSON import (library/nodes/mec2.py): the verbatim examples of
goessner/mec2 (MIT, copied with their attribution into
tests/data/mec2, see SOURCE.md there), the project's own models in models/mec2/ covering every constraint kind,
and errors naming the JSON path."""
import json
import math
import os
import subprocess
import sys

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import acausal2d
from acausal2d import ModelDefinitionError
from acausal2d.cli import main
from acausal2d.library.nodes.mec2 import model_from_mec2
from acausal2d.visual.scene import build_scene
from conftest import ROOT, same_time
from vdi2729_reference import vdi_ddd

EXAMPLES = os.path.join(ROOT, "tests", "data", "mec2")
OWN = os.path.join(ROOT, "models", "mec2")
U = 0.01        # m per mec2 unit


def example(name):
    return acausal2d.load_model(os.path.join(EXAMPLES, name))


def own(name):
    return acausal2d.load_model(os.path.join(OWN, name))


def e(a):
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


# ------------------------------------------------------------ the mec2 examples
@pytest.mark.parametrize("name", sorted(n for n in os.listdir(EXAMPLES) if n.endswith(".json")))
def test_every_example_imports_and_runs(name):
    res = acausal2d.simulate(example(name))
    assert res.stopped is None and res.time[-1] > 0


def _views_1_coupler(w):
    """Closed form of views_1's coupler point C at crank angle w (m)."""
    A0, B0 = np.array([0.75, 0.5]), np.array([2.75, 0.5])
    A = A0 + 0.5 * np.array([math.cos(w), math.sin(w)])
    B = vdi_ddd(A, B0, math.hypot(2.0, 0.7), 1.2, 1)
    w_ab0 = math.atan2(0.7, 2.0)
    w_bc = math.atan2(0.05, -1.5) + (math.atan2(*(B - A)[::-1]) - w_ab0)
    return B + math.hypot(1.5, 0.05) * np.array([math.cos(w_bc), math.sin(w_bc)])


def test_views_1_coupler_trace_closes_after_one_drive_period():
    model = example("views_1.json")
    assert model.mec2_traces == ["C"] and len(model.mec2_views_not_drawn) == 1   # the chart
    assert [a["fx"] for a in model.mec2_arrows] == ["der(C.x)"]           # the vel vector
    cm = acausal2d.compile_model(model)
    res = cm.simulate(rtol=1e-10)
    assert same_time(res.time[-1], 2.0)                       # the drive's Dt
    C = np.stack([res["C.x"], res["C.y"]], axis=1)
    for k in (0, 37, len(res.time) - 1):             # the closed form along the run
        w = math.pi / 2 + 6.28 * min(res.time[k] / 2.0, 1.0)
        assert np.max(np.abs(C[k] - _views_1_coupler(w))) < 1e-9
    # the file's Dw = 6.28 stops 0.0032 rad short of a turn: the trace's gap
    gap = np.linalg.norm(C[-1] - C[0])
    assert gap == pytest.approx(np.linalg.norm(_views_1_coupler(math.pi / 2 + 6.28)
                                               - _views_1_coupler(math.pi / 2)), abs=1e-9)
    full = cm.simulate(rtol=1e-10, params={"a.ang_drive.Dz": 2 * math.pi})
    assert math.hypot(full["C.x"][-1] - full["C.x"][0], full["C.y"][-1] - full["C.y"][0]) < 1e-9
    traces = [s for s in build_scene(full)["shapes"] if s["type"] == "trace"]
    assert traces == [{"type": "trace", "x": "C.x", "y": "C.y"}]


def test_drive_3_couples_the_two_cranks_one_to_one():
    res = acausal2d.simulate(example("drive_3.json"), rtol=1e-10)
    t = res.time
    assert same_time(t[-1], 3.0)                              # repeat 3 of Dt = 1
    wb = math.pi + 2 * math.pi * t                    # three full turns, one angle
    A = np.array([2.5, 1.25]) + 0.75 * e(wb)
    B = np.array([1.0, 1.25]) + 0.75 * e(wb - math.pi)
    for node, ref in (("A", A), ("B", B)):
        assert np.max(np.abs(np.stack([res[node + ".x"], res[node + ".y"]], 1) - ref)) < 1e-9
    assert np.max(np.abs((res["c.w"] - res["c.w"][0]) - (res["b.w"] - res["b.w"][0]))) < 1e-9


def test_loads_3_lever_balanced_by_the_zero_length_spring():
    """Lever A0-A-B (rigid: b's angle coupled to a's) under gravity 10 m/s^2,
    masses 1 kg at a = 0.5 m and b = 1.5 m, spring B0-A with len0 = 0 and
    B0 h = 0.5 m above A0: the torque about A0 is (k h a - g (a + b))
    cos(w) = (0.25 k - 20) cos(w), so k = 80 N/m balances the lever in
    every position.  The file's k = 78.695 N/m leaves 1.6 % of the weight's
    torque unbalanced: the lever falls, as w'' = (0.25 k - 20) cos(w) / J
    with J = 2.5 kg m^2 says."""
    cm = acausal2d.compile_model(example("loads_3.json"))
    res = cm.simulate(rtol=1e-10, params={"s.k": 80.0}, stop_time=2.0)
    for k in ("A.x", "A.y", "B.x", "B.y"):
        assert np.max(np.abs(res[k] - res[k][0])) < 1e-9
    res = cm.simulate(rtol=1e-10)                     # the file's 78.695 N/m
    assert (80.0 - 78.695) / 80.0 == pytest.approx(0.0163, abs=1e-4)
    sol = solve_ivp(lambda t, y: [y[1], (0.25 * 78.695 - 20.0) * math.cos(y[0]) / 2.5],
                    (0, 1), [0.0, 0.0], t_eval=res.time, rtol=1e-11, atol=1e-12)
    assert np.max(np.abs(res["a.w"] - sol.y[0])) < 1e-8
    assert res["a.w"][-1] < -0.05


# ------------------------------------------------------------ the project's models
def test_slider_crank_harmonic_bounce_repeat_and_rigid_coupler_point():
    model = own("slider_crank.json")
    assert model.mec2_views_not_drawn == [                 # trace and vel vector drawn
        "$.views[2] (chart of r): no counterpart in the animation"]
    assert [(a["x"], a["fx"], a["unit"]) for a in model.mec2_arrows] == [
        ("B.x", "der(B.x)", "m/s")]
    res = acausal2d.simulate(model, rtol=1e-10)
    t = res.time
    assert same_time(t[-1], 4.0)                              # Dt 1, bounce (x2), repeat 2
    q = (t % 2.0) / 2.0
    s = np.where(q < 0.5, 2 * q, 2 - 2 * q)
    w = math.pi / 2 + math.pi * (1 - np.cos(math.pi * s)) / 2
    assert np.max(np.abs(res["a.w"] - w)) < 1e-10
    Ax, Ay = 0.05 * np.cos(w), 0.05 * np.sin(w)
    Bx = Ax + np.sqrt(math.hypot(0.2, 0.05) ** 2 - Ay ** 2)
    assert np.max(np.abs(res["B.x"] - Bx)) < 1e-10 and np.max(np.abs(res["B.y"])) < 1e-10
    assert np.max(np.abs(res["C.x"] - (Ax + Bx) / 2)) < 1e-10          # C stays mid-rod
    assert np.max(np.abs(res["C.y"] - Ay / 2)) < 1e-10
    scene = build_scene(res)
    kinds = [sh["type"] for sh in scene["shapes"]]
    assert kinds.count("trace") == 1 and kinds.count("ground") == 2   # base nodes A0, G0


def test_gears_ratio_legacy_ref_and_drive_relative_to_a_reference():
    model = own("gears.json")
    res = acausal2d.simulate(model, rtol=1e-10)
    t = res.time
    wa = math.pi * t                                  # a full turn in Dt = 2 s
    assert np.max(np.abs(res["a.w"] - wa)) < 1e-12
    wb = -math.pi / 2 - 0.5 * wa                      # ratio -0.5
    wc = 2 * wa                                       # legacy "type": "ref", ratio 2
    wd = math.atan2(2, 1) + (wb + math.pi / 2) + 0.5 * t     # drive with ref b, Dw 1
    for n, c, r, w in (("B", (0.1, 0), 0.02, wb), ("C", (0.2, 0), 0.02, wc),
                       ("D", (0.3, 0), 0.03, wd)):      # D moved to r0 = 3 (mec2 initVector)
        P = np.array(c) + r * e(w)
        assert np.max(np.abs(np.stack([res[n + ".x"], res[n + ".y"]], 1) - P)) < 1e-10, n


def _crank_pair(passive):
    """Two cranks, c coupled to a with ratio 2, a weight-less pull of 1 N up
    at C; the drive of a must supply c's torque unless passive."""
    return {"nodes": [{"id": "A0", "x": 0, "y": 0, "base": True}, {"id": "A", "x": 4, "y": 0},
                      {"id": "C0", "x": 20, "y": 0, "base": True}, {"id": "C", "x": 22, "y": 0}],
            "constraints": [
                {"id": "a", "p1": "A0", "p2": "A", "len": {"type": "const"},
                 "ori": {"type": "drive", "Dt": 2}},
                {"id": "c", "p1": "C0", "p2": "C", "len": {"type": "const"},
                 "ori": {"type": "const", "ref": "a", "ratio": 2, "passive": passive}}],
            "loads": [{"id": "F", "p": "C", "value": 1, "w0": math.pi / 2}]}


@pytest.mark.parametrize("passive", [False, True])
def test_passive_coupling_sends_no_torque_back(passive):
    res = acausal2d.simulate(model_from_mec2(_crank_pair(passive)), rtol=1e-10)
    wc = 2 * math.pi * res.time                       # c turns twice as fast as a
    load = 0.02 * np.cos(wc) * 1.0                    # the pull's moment about C0 [N m]
    # constant speeds: the nodes' inertia forces are radial and pass no torque
    # (the drive's flange torque is the torque the crank a exerts on the drive)
    drive = res["a.ang_drive.flange.tau"]
    assert np.max(np.abs(load)) == pytest.approx(0.02, rel=1e-3)
    if passive:
        assert np.max(np.abs(drive)) < 1e-9
    else:                                             # virtual work: twice c's torque
        assert np.max(np.abs(drive - 2.0 * load)) < 1e-9


def test_rack_and_pinion_cross_references_and_r0():
    res = acausal2d.simulate(own("rack_and_pinion.json"), rtol=1e-10)
    t = np.minimum(res.time, 1.0)
    dr = 0.1 * (10 - 15 * t + 6 * t * t) * t ** 3     # poly5 drive of the rack, Dr 10 u
    assert np.max(np.abs(res["R.x"] - dr)) < 1e-10
    wp = math.pi / 2 - dr / 0.05                      # w = w0 + ratio (r_ref - r_ref0) / r
    assert np.max(np.abs(res["p.w"] - wp)) < 1e-10
    assert np.max(np.abs(res["p.r"] - 0.05)) < 1e-12  # r0 = 5 u moved P from 6 u
    rq = 0.1 - 0.05 * (wp - math.pi / 2)              # r = r0 + ratio r_ref (w_ref - w_ref0)
    assert np.max(np.abs(res["Q.y"] + rq)) < 1e-10
    assert res["Q.y"][-1] == pytest.approx(-0.2)      # the rope unwound by the rack's travel
    # the telescope T0-T: r = r0 + 0.5 (r_ref - r_ref0), along x from T0 = (-0.1, -0.15)
    assert np.max(np.abs(res["T.x"] - 0.5 * dr)) < 1e-10
    assert np.max(np.abs(res["T.y"] + 0.15)) < 1e-12


def _kinds_of(sub, which):
    """The kinds of one mec2 ``ori``/``len`` object, written from the format
    description (mec2_format.md), not from the importer."""
    t = sub.get("type", "free")
    kinds = {(which, "legacy ref")} if t == "ref" else set()
    t = "const" if t == "ref" else t
    kinds.add((which, t))
    if "ref" in sub:
        other = sub.get("reftype", which)
        kinds.add((which, t, "ref", "same" if other == which else "cross"))
    kinds |= {(which, key) for key in ("passive", "r0", "w0", "ratio") if key in sub}
    return kinds


def test_the_projects_models_cover_every_constraint_kind():
    """free/const/drive for ori and len, const with a reference of the same
    and of the other type, drives relative to a reference, the legacy
    "type": "ref", passive, ratio, initial r0/w0; force and spring loads,
    gravity, traces."""
    found = set()
    for name in sorted(os.listdir(OWN)):
        with open(os.path.join(OWN, name)) as f:
            data = json.load(f)
        for c in data["constraints"]:
            for which in ("ori", "len"):
                found |= _kinds_of(c.get(which, {}), which)
        found |= {("load", ld.get("type", "force")) for ld in data.get("loads", [])}
        found |= {("gravity",)} if data.get("gravity") else set()
        found |= {("view", v["as"]) for v in data.get("views", [])}
    wanted = {(w, t) for w in ("ori", "len") for t in ("free", "const", "drive")}
    wanted |= {(w, t, "ref", k) for w in ("ori", "len") for t in ("const",)
               for k in ("same", "cross")}
    wanted |= {("ori", "drive", "ref", "same"), ("ori", "legacy ref"), ("ori", "passive"),
               ("ori", "ratio"), ("len", "ratio"), ("ori", "w0"), ("len", "r0"),
               ("load", "force"), ("load", "spring"), ("gravity",), ("view", "trace")}
    assert wanted - found == set()


def test_spring_pendulum_against_an_independent_ode():
    res = acausal2d.simulate(own("spring_pendulum.json"), rtol=1e-10)
    L, m, k, len0, S0 = 0.3, 2.0, 100.0, 0.2, np.array([0.0, 0.3])

    def rhs(t, y):
        A = L * np.array([math.cos(y[0]), math.sin(y[0])])
        d = A - S0
        F = -k * (np.linalg.norm(d) - len0) * d / np.linalg.norm(d)
        torque = A[0] * F[1] - A[1] * F[0] - m * 10.0 * A[0] + L * 5.0
        return [y[1], torque / (m * L * L)]
    sol = solve_ivp(rhs, (0, 1), [0.0, 0.0], t_eval=res.time, rtol=1e-11, atol=1e-12)
    assert np.max(np.abs(res["a.w"] - sol.y[0])) < 1e-7
    assert np.ptp(res["a.w"]) > 0.2


def test_seq_drive_as_mec2_normalizes_it():
    data = {"nodes": [{"id": "O", "x": 0, "y": 0, "base": True}, {"id": "P", "x": 10, "y": 0}],
            "constraints": [{"id": "a", "p1": "O", "p2": "P", "len": {"type": "const"},
                             "ori": {"type": "drive", "func": "seq", "Dt": 7, "Dw": 1,
                                     "args": [{"func": "quadratic", "dt": 3, "dz": 1},
                                              {"func": "const", "dt": 1},
                                              {"func": "linear", "dt": 3, "dz": -1}]}}]}
    model = model_from_mec2(data)
    assert model.experiment["stop_time"] == 7
    res = acausal2d.simulate(model, output_times=[0, 1.5, 3, 3.5, 5.5, 7], rtol=1e-10)
    # quadratic 0 -> 1 in 3 s (1/2 at 1.5 s), rest, linear 1 -> 0 in 3 s
    for t, w in ((0, 0), (1.5, 0.5), (3, 1), (3.5, 1), (5.5, 0.5), (7, 0)):
        assert res.at("a.w", t) == pytest.approx(w, abs=1e-10)


def test_cli_runs_a_json_model(tmp_path, capsys):
    assert main(["check", os.path.join(OWN, "gears.json")]) == 0
    assert "N = 8, N_base = 4, C1 = 2, C2 = 2: F = 2 (eq. 1)" in capsys.readouterr().out
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate",
                           os.path.join(OWN, "slider_crank.json"), "--out", str(tmp_path)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("slider_crank: simulated 4 s")
    page = (tmp_path / "animation.html").read_text()
    assert '"type":"trace","x":"C.x","y":"C.y"' in page and '"nodes":{"nodes":' in page


# ------------------------------------------------------------ errors
def _write(tmp_path, text):
    path = tmp_path / "model.json"
    path.write_text(text)
    return str(path)


GOOD = {"nodes": [{"id": "A0", "x": 0, "y": 0, "base": True}, {"id": "A", "x": 1, "y": 0}],
        "constraints": [{"id": "a", "p1": "A0", "p2": "A", "len": {"type": "const"},
                         "ori": {"type": "drive"}}]}


def _broken(change):
    data = json.loads(json.dumps(GOOD))
    change(data)
    return data


@pytest.mark.parametrize("change, pattern", [
    (lambda d: d["constraints"][0]["ori"].update(type="spin"),
     r"\$\.constraints\[0\]\.ori\.type: unknown constraint type 'spin'"),
    (lambda d: d["nodes"][1].update(z=3), r"\$\.nodes\[1\]\.z: unknown field"),
    (lambda d: d["nodes"][1].update(x="1"), r"\$\.nodes\[1\]\.x: must be a number"),
    (lambda d: d["nodes"][1].pop("id"), r"\$\.nodes\[1\]: the required field 'id' is missing"),
    (lambda d: d["nodes"][1].update(m=0), r"\$\.nodes\[1\]\.m: the mass must be > 0"),
    (lambda d: d["constraints"][0].update(p2="Z"), r"\$\.constraints\[0\]\.p2: 'Z' is no node"),
    (lambda d: d["constraints"][0]["len"].update(ref="x"),
     r"\$\.constraints\[0\]\.len\.ref: 'x' is no constraint"),
    (lambda d: d["constraints"][0]["ori"].update(func="spin"),
     r"a\.ang: unknown drive function 'spin'"),
    (lambda d: d["constraints"][0]["ori"].update(Dt=0), r"\.ori\.Dt: the drive duration"),
    (lambda d: d["constraints"][0]["ori"].update(repeat=1.5), r"\.ori\.repeat: must be a whole"),
    (lambda d: d.update(loads=[{"id": "L", "type": "torque"}]),
     r"\$\.loads\[0\]\.type: unknown load type 'torque'"),
    (lambda d: d.update(tolerance="tight"), r"\$\.tolerance: must be one of low, medium, high"),
    (lambda d: d.update(gravity={"x": 0, "y": -10, "on": True}), r"\$\.gravity\.on: unknown"),
    (lambda d: d.update(speed=3), r"\$\.speed: unknown field"),
    (lambda d: d["nodes"].append({"id": "A", "x": 0, "y": 1}), r"\$\.nodes\[2\]\.id: 'A' is used"),
    (lambda d: d["nodes"][1].update(id="1A"), r"\$\.nodes\[1\]\.id: '1A' is no usable id"),
    (lambda d: d["constraints"].extend([
        {"id": "b", "p1": "A0", "p2": "A", "ori": {"type": "const", "ref": "c"}},
        {"id": "c", "p1": "A0", "p2": "A", "ori": {"type": "const", "ref": "b"}}]),
     r"\$\.constraints\[\d\]: the references of constraint '[bc]' form a cycle"),
])
def test_malformed_models_name_the_json_path(tmp_path, change, pattern):
    path = _write(tmp_path, json.dumps(_broken(change)))
    with pytest.raises(ModelDefinitionError, match=pattern):
        acausal2d.load_model(path)


def test_json_syntax_error_names_line_and_column(tmp_path, capsys):
    path = _write(tmp_path, '{"nodes": [\n  {"id": "A0", "x": 0 "y": 0}\n]}')
    with pytest.raises(ModelDefinitionError, match=r"is no valid JSON: Expecting ',' delimiter "
                       r"\(line 2, column 23\)"):
        acausal2d.load_model(path)
    assert main(["check", path]) == 2
    assert "line 2, column 23" in capsys.readouterr().err


def test_cli_reports_an_unknown_constraint_type_with_its_path(tmp_path, capsys):
    path = _write(tmp_path, json.dumps(_broken(
        lambda d: d["constraints"][0]["len"].update(type="elastic"))))
    assert main(["simulate", path, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "$.constraints[0].len.type: unknown constraint type 'elastic'" in err
    assert "Traceback" not in err
