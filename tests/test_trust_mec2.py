"""Issue 18, Seen 9: every model in mec2's documentation pages (and mec2's
own old test pages) loads, checks and simulates; both spellings of every
view kind of mec.view.js are read; vel/acc/force vectors are arrows;
unknown view or shape fields warn once and the model loads; unknown
node/constraint/load fields stay errors."""
import json
import math
import os
import warnings

import numpy as np
import pytest

import acausal2d
from acausal2d import ModelDefinitionError
from acausal2d.cli import main
from acausal2d.library.nodes.mec2 import model_from_mec2
from acausal2d.library.nodes.mec2_views import Mec2Warning
from acausal2d.visual.animation import validate_scene
from acausal2d.visual.scene import build_scene
from conftest import same_time, assert_copied

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "data", "mec2")
FILES = sorted(n for n in os.listdir(DATA) if n.endswith(".json"))

CRANK = {"nodes": [{"id": "A0", "x": 0, "y": 0, "base": True}, {"id": "A", "x": 50, "y": 0},
                   {"id": "B0", "x": 200, "y": 0, "base": True}],
         "constraints": [{"id": "a", "p1": "A0", "p2": "A", "len": {"type": "const"},
                          "ori": {"type": "drive", "func": "linear", "Dt": 2}}]}


def crank(*views, **extra):
    return dict(json.loads(json.dumps(CRANK)), views=list(views), **extra)


def quiet(data):
    """The model, with every warning an error (a clean file warns nothing)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return model_from_mec2(data)


@pytest.mark.parametrize("name", FILES)
def test_seen_9_every_example_loads_checks_and_simulates(name):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        model = acausal2d.load_model(os.path.join(DATA, name))
    assert acausal2d.check(model) is not None
    res = acausal2d.simulate(model)
    assert res.stopped is None and res.time[-1] > 0
    validate_scene(build_scene(res))


def test_seen_9_the_docs_models_are_all_here():
    """SOURCE.md names a file for every complete model of docs/ (the
    fourteen distinct ones, two of them repeated in other pages)."""
    text = open(os.path.join(DATA, "SOURCE.md"), encoding="utf-8").read()
    for name in FILES:
        assert name in text
    docs = [n for n in FILES if not n.startswith("test2_")]
    assert len(docs) == 14


# ------------------------------------------------ both spellings of each view kind
# (mec.view.js: older spelling 8545ba3..0790336 and the test2 pages; newer from 222aacd)
SPELLINGS = [
    ("vector", "older", {"type": "vector", "p": "A", "value": "vel"}),
    ("vector", "newer", {"as": "vector", "show": "vel", "of": "A"}),
    ("trace", "older", {"type": "trace", "p": "A", "Dt": 1, "fill": "orange"}),
    ("trace", "newer", {"as": "trace", "show": "pos", "of": "A", "mode": "preview", "Dt": 2}),
    ("info", "older", {"type": "info", "elem": "a", "value": "w", "name": "w"}),
    ("info", "newer", {"as": "info", "show": "w", "of": "a"}),
    ("chart", "older", {"type": "chart", "xval": {"of": "a", "prop": "w"},
                        "yval": [{"of": "a", "prop": "wt"}]}),
    ("chart", "xaxis", {"as": "chart", "x": 10, "y": 20, "xaxis": {"show": "w", "of": "a"},
                        "yaxis": [{"show": "wt", "of": "a"}]}),
    ("chart", "newer", {"as": "chart", "x": 10, "y": 20, "b": 150, "h": 100, "t0": 0,
                        "Dt": 2, "show": "wt", "of": "a", "against": {"show": "t",
                                                                      "of": "timer"}}),
    ("point", "newer", {"as": "point", "show": "pos", "of": "A"}),
]


@pytest.mark.parametrize("kind, spelling, view", SPELLINGS,
                         ids=["%s-%s" % (k, s) for k, s, _ in SPELLINGS])
def test_seen_9_each_view_kind_in_each_spelling(kind, spelling, view):
    model = quiet(crank(view))
    if kind == "trace":
        assert model.mec2_traces == ["A"] and not model.mec2_views_not_drawn
    elif kind == "vector":
        assert [(a["fx"], a["fy"], a["unit"]) for a in model.mec2_arrows] == [
            ("der(A.x)", "der(A.y)", "m/s")]
    else:
        assert model.mec2_views_not_drawn == [
            "$.views[0] (%s of %s): no counterpart in the animation"
            % (kind, view.get("show") or view.get("value") or "?")]
    res = acausal2d.simulate(model)
    validate_scene(build_scene(res))


def test_seen_9_vel_arrow_is_the_crank_velocity():
    """The older-spelling vector of mec2's test page 1: crank radius 0.5 m,
    one turn in Dt = 5 s (linear drive): |v| = 0.5 * 2 pi / 5 m/s."""
    model = quiet(json.load(open(os.path.join(DATA, "test2_01.json"))))
    res = acausal2d.simulate(model, rtol=1e-10)
    arrow = [s for s in build_scene(res)["shapes"] if s["type"] == "arrow"][0]
    assert arrow["anchor"] == "tail" and arrow["color"] == "steelblue"
    mid = len(res.time) // 2
    v = math.hypot(res[arrow["fx"]][mid], res[arrow["fy"]][mid])
    assert v == pytest.approx(0.5 * 2 * math.pi / 5, rel=1e-8)


def test_seen_9_acc_arrow_and_anchor_at():
    model = quiet(crank({"as": "vector", "show": "acc", "of": "A", "at": "B0"}))
    res = acausal2d.simulate(model, rtol=1e-10)
    arrows = [s for s in build_scene(res)["shapes"] if s["type"] == "arrow"]
    assert [(a["x"], a["fx"], a["unit"]) for a in arrows] == [("B0.x", "der(der(A.x))", "m/s2")]
    mid = len(res.time) // 2                 # uniform rotation: |a| = r w^2 = 0.5 pi^2
    a = math.hypot(res["der(der(A.x))"][mid], res["der(der(A.y))"][mid])
    assert a == pytest.approx(0.5 * math.pi ** 2, rel=1e-6)


def test_seen_9_force_arrows_are_the_loads_on_the_node():
    """mec2's loads_1 pendulum (force 30 N at w0 = 1.5708, gravity) with a
    force vector view of A: one arrow per load -- the force load, drawn as
    minus its port flow (turned by pi), and the weight m g."""
    data = json.load(open(os.path.join(DATA, "loads_1.json")))
    data["views"] = [{"as": "vector", "show": "force", "of": "A"}]
    model = quiet(data)
    res = acausal2d.simulate(model)
    arrows = [s for s in build_scene(res)["shapes"] if s["type"] == "arrow"]
    assert [a["label"] for a in arrows] == ["F F1", "G A"]
    f = arrows[0]
    assert f["angle"] == pytest.approx(math.pi)
    fx, fy = -res[f["fx"]][0], -res[f["fy"]][0]
    assert fx == pytest.approx(30 * math.cos(1.5708), abs=1e-9)
    assert fy == pytest.approx(30 * math.sin(1.5708), abs=1e-9)
    assert_copied((arrows[1]["fx"], arrows[1]["fy"]), (0.0, -10.0))   # m g = 1 x 10: exact product


# ------------------------------------------------ unknown fields
def test_seen_9_unknown_view_and_shape_fields_warn_once_and_load():
    data = crank({"as": "trace", "show": "pos", "of": "A", "glow": 3},
                 {"type": "vector", "p": "A", "value": "vel"},
                 {"as": "hologram", "of": "A"},
                 shapes=[{"type": "fix", "p": "A0", "shadow": True}, {"type": "cloud"}])
    with pytest.warns(Mec2Warning) as record:
        model = model_from_mec2(data)
    assert len(record) == 1
    text = str(record[0].message)
    for path in ("$.views[0].glow", "$.views[2].as = 'hologram'", "$.shapes[0].shadow",
                 "$.shapes[1].type = 'cloud'"):
        assert path in text
    assert [a["fx"] for a in model.mec2_arrows] == ["der(A.x)"]     # the good view is kept
    assert same_time(acausal2d.simulate(model).time[-1], 2.0)


@pytest.mark.parametrize("where, change", [
    ("$.nodes[1].glow", lambda d: d["nodes"][1].update(glow=1)),
    ("$.constraints[0].glow", lambda d: d["constraints"][0].update(glow=1)),
    ("$.constraints[0].ori.glow", lambda d: d["constraints"][0]["ori"].update(glow=1)),
    ("$.loads[0].glow", lambda d: d.update(loads=[{"id": "F", "type": "force", "p": "A",
                                                    "glow": 1}])),
])
def test_seen_9_unknown_fields_that_change_the_motion_stay_errors(where, change):
    data = crank()
    change(data)
    with pytest.raises(ModelDefinitionError, match=where.replace("[", r"\[").replace("$", r"\$")):
        model_from_mec2(data)


def test_seen_9_cli_prints_one_warning_and_draws_the_arrow(tmp_path, capfd):
    path = tmp_path / "m.json"
    path.write_text(json.dumps(crank({"type": "vector", "p": "A", "value": "vel", "glow": 1},
                                     {"as": "vector", "show": "vel", "of": "A"})))
    assert main(["simulate", str(path), "--out", str(tmp_path / "out")]) == 0
    err = capfd.readouterr().err
    assert err.count("warning:") == 1 and "$.views[0].glow" in err and "Traceback" not in err
    page = (tmp_path / "out" / "animation.html").read_text()
    assert '"fx":"der(A.x)"' in page and '"unit":"m/s"' in page
