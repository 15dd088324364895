"""Issue 18, Seen 3 and 4: compare never passes what it did not compare, and
NaN/inf or wrong-shaped inputs are errors naming file, signal, row or
argument -- never a raw traceback."""
import os

import numpy as np
import pytest

import acausal2d
from acausal2d import Acausal2dError
from acausal2d.analysis.compare_inputs import modelica_counterpart
from acausal2d.cli import main
from acausal2d.io.tables import read_csv
from acausal2d.library.planar import modelica_names

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, os.pardir, "models", "planar_examples.py")
REF = os.path.join(HERE, "data", "references", "SpringDamperDemo.csv")
NOISE = ("Traceback", "ValueError", "TypeError")


@pytest.fixture(scope="module")
def spring_damper_result(tmp_path_factory):
    out = tmp_path_factory.mktemp("sdd")
    assert main(["simulate", MODELS, "--model", "SpringDamperDemo", "--out", str(out)]) == 0
    return str(out / "result.csv")


def test_seen_3_spring_damper_demo_compares_all_six_signals(spring_damper_result, capfd):
    """The PlanarMechanics reference (columns body.phi, body.r[1], body.r[2],
    body.v[1], body.v[2], body.w): all six compared through the Body's
    declared Modelica names, all within 2e-3."""
    capfd.readouterr()
    assert main(["compare", spring_damper_result, REF]) == 0
    out = capfd.readouterr().out
    assert "6 of 6 signals passed" in out
    for pair in ("body.r[1] -> body.x", "body.r[2] -> body.y", "body.v[1] -> body.vx",
                 "body.v[2] -> body.vy"):
        assert pair in out
    cmp = acausal2d.compare(spring_damper_result, REF)
    assert sorted(r.name for r in cmp.rows) == ["body.phi", "body.r[1]", "body.r[2]",
                                                "body.v[1]", "body.v[2]", "body.w"]
    assert cmp.passed and not cmp.unmatched
    # the closed form of the README (x = -1 + e^-t (2 cos 3t + 2/3 sin 3t)) at t = 5
    t, cols = read_csv(spring_damper_result)
    x5 = -1 + np.exp(-5.0) * (2 * np.cos(15.0) + 2 / 3 * np.sin(15.0))
    assert cols["body.x"][-1] == pytest.approx(x5, abs=1e-6)
    assert max(r.max_deviation for r in cmp.rows) < 2e-3


def test_seen_3_a_reference_signal_without_counterpart_fails_and_is_named(
        spring_damper_result, tmp_path, capfd):
    text = open(REF, encoding="utf-8").read().splitlines()
    rows = [text[0] + ',"body.n[1]"'] + [line + ",0" for line in text[1:]]
    extra = tmp_path / "extra.csv"
    extra.write_text("\n".join(rows) + "\n", encoding="utf-8")
    capfd.readouterr()
    assert main(["compare", spring_damper_result, str(extra)]) == 1
    out = capfd.readouterr().out
    assert "not compared (no counterpart in the result): body.n[1]" in out
    assert "--only-common" in out
    assert main(["compare", spring_damper_result, str(extra), "--only-common"]) == 0
    out = capfd.readouterr().out
    assert "body.n[1]" in out and "6 of 6 signals passed" in out
    cmp = acausal2d.compare(spring_damper_result, str(extra), only_common=True)
    assert cmp.passed and cmp.unmatched == ["body.n[1]"]
    assert not acausal2d.compare(spring_damper_result, str(extra)).passed


def test_seen_3_the_library_declares_the_modelica_names():
    table = modelica_names()
    assert {"r[1]": "x", "r[2]": "y", "v[1]": "vx", "v[2]": "vy"}.items() <= \
        {k: v[0] for k, v in table.items()}.items()
    ours = {"pos.r_x.u", "pos.r_y.u", "acc.a_x.u", "rel.v_rel_y.u", "b.x"}
    assert modelica_counterpart("pos.r[1]", ours) == "pos.r_x.u"
    assert modelica_counterpart("acc.a[1]", ours) == "acc.a_x.u"
    assert modelica_counterpart("rel.v_rel[2]", ours) == "rel.v_rel_y.u"
    assert modelica_counterpart("b.r[1]", ours) == "b.x"
    assert modelica_counterpart("b.r[2]", ours) is None


@pytest.mark.parametrize("where", ["result", "reference"])
@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_seen_4_nan_or_inf_names_file_signal_and_row(where, value, tmp_path, capfd):
    good = "time,a\n" + "".join("%g,%g\n" % (0.1 * k, np.sin(0.1 * k)) for k in range(11))
    bad = good.replace("0.3,%g" % np.sin(0.3), "0.3,%s" % value)
    files = {"result": tmp_path / "r.csv", "reference": tmp_path / "ref.csv"}
    for name, path in files.items():
        path.write_text(bad if name == where else good, encoding="utf-8")
    with pytest.raises(Acausal2dError) as exc:
        acausal2d.compare(str(files["result"]), str(files["reference"]))
    msg = str(exc.value)
    assert str(files[where]) in msg and "'a'" in msg and "line 5" in msg and "time 0.3" in msg
    capfd.readouterr()
    assert main(["compare", str(files["result"]), str(files["reference"])]) == 2
    err = "".join(capfd.readouterr())
    assert "line 5" in err and not any(n in err for n in NOISE)


@pytest.mark.parametrize("result, reference, argument", [
    ((np.arange(3.0),), "ref", "result"),
    ((np.arange(3.0), {"a": [1, 2]}), "ref", "'a'"),
    ((np.arange(3.0), [1, 2, 3]), "ref", "columns"),
    ((np.arange(3.0), {"a": [1, 2, float("nan")]}), "ref", "signal 'a'"),
    (("abc", {"a": [1]}), "ref", "time"),
    ((np.ones((2, 2)), {"a": [1, 2, 3, 4]}), "ref", "one-dimensional"),
    ("res", (np.arange(3.0), {"a": [1, 2, 3]}, None), "reference"),
    ("res", (np.arange(3.0), {"a": [[1, 2], [3, 4]]}), "'a'"),
    ("res", (np.arange(3.0), {"a": ["x", "y", "z"]}), "'a'"),
])
def test_seen_4_wrong_shaped_tuples_name_the_argument(result, reference, argument, tmp_path):
    ok = (np.arange(3.0), {"a": [0.0, 1.0, 2.0]})
    result = ok if result == "res" else result
    reference = ok if reference == "ref" else reference
    with pytest.raises(Acausal2dError, match=argument.replace("[", r"\[")):
        acausal2d.compare(result, reference)


@pytest.mark.parametrize("kw, name", [
    ({"abs_tol": "tight"}, "abs_tol"), ({"rel_tol": [1]}, "rel_tol"),
    ({"time_tol": -1.0}, "time_tol"), ({"until": "end"}, "until"),
    ({"event_tol": float("nan")}, "event_tol"), ({"signals": 5}, "signals"),
    ({"mapping": 5}, "mapping"), ({"mapping": {"a": 1}}, "mapping"),
    ({"plot_dir": 3}, "plot_dir"), ({"only_common": "yes"}, "only_common"),
    ({"abs_tol": True}, "abs_tol"),
])
def test_seen_5_compare_arguments_of_the_wrong_type_name_the_argument(kw, name):
    ok = (np.arange(3.0), {"a": [0.0, 1.0, 2.0]})
    with pytest.raises(Acausal2dError, match=name):
        acausal2d.compare(ok, ok, **kw)
