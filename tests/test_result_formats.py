"""Issue 31: results in Dymola's result format (read back by DyMat, an
independent reader of Dymola/OpenModelica files), ``compare`` of ``.mat``
files, ``Result.to_pandas``, what a notebook shows (``repr``,
``_repr_html_``, ``animation()``) and units on compare's plot axes."""
import base64
import csv
import html
import json
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.io.dymola_mat import read_mat, write_mat
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")
REFERENCE = os.path.join(ROOT, "tests", "data", "references", "PistonEngine.csv")


def cli(*args, cwd=None):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    return subprocess.run([exe] + list(args), capture_output=True, text=True, timeout=600,
                          cwd=cwd)


def read_our_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    data = np.array(rows[1:], dtype=float)
    return {name: data[:, k] for k, name in enumerate(rows[0])}


@pytest.fixture(scope="module")
def engine_run(tmp_path_factory):
    """The piston engine's default run written as result.mat and
    result.csv by ``acausal2d simulate`` (two runs of the command)."""
    out = tmp_path_factory.mktemp("engine")
    for fmt in ("csv", "mat"):
        proc = cli("simulate", os.path.join(MODELS, "piston_engine.py"), "--result-format", fmt,
                   "--out", str(out / fmt))
        assert proc.returncode == 0, proc.stderr
        assert "(result.%s, " % fmt in proc.stdout
    return out


def test_piston_engine_mat_read_by_dymat_equals_the_csv(engine_run):
    """Every signal of result.csv, read from result.mat by DyMat, to 1e-12
    relative (of the signal's largest magnitude); the time is the abscissa
    of the trajectory block; parameters are constants of data_1."""
    DyMat = pytest.importorskip("DyMat")
    ours = read_our_csv(engine_run / "csv" / "result.csv")
    mat = DyMat.DyMatFile(str(engine_run / "mat" / "result.mat"))
    t = ours.pop("time")
    assert len(t) == 5001
    block = mat.block("revoluteDrive.w")
    assert block == 2
    np.testing.assert_allclose(mat.abscissa(block, valuesOnly=True), t, rtol=1e-12, atol=0)
    for name, values in ours.items():
        got = mat.data(name)
        scale = max(np.max(np.abs(values)), 1e-300)
        assert np.max(np.abs(got - values)) <= 1e-12 * scale, name
    assert mat.block("bodyPiston.m") == 1
    np.testing.assert_allclose(mat.data("bodyPiston.m"), [3.0, 3.0], rtol=1e-15)   # Body(m=3.0)
    assert "rad/s" in mat.description("revoluteDrive.w")
    listing = json.loads((engine_run / "mat" / "acausal2d-run.json").read_text())
    assert "result.mat" in listing["files"] and "result.csv" not in listing["files"]


def test_piston_engine_mat_read_by_buildingspy_equals_the_csv(engine_run):
    """The issue's reader: buildingspy's Reader (Dymola format) gives every
    signal of result.csv, at the same times, to 1e-12 relative of the
    signal's largest magnitude (the file holds the doubles themselves)."""
    from buildingspy.io.outputfile import Reader
    ours = read_our_csv(engine_run / "csv" / "result.csv")
    reader = Reader(str(engine_run / "mat" / "result.mat"), "dymola")
    t = ours.pop("time")
    assert set(ours) <= set(reader.varNames())
    for name, values in ours.items():
        when, got = reader.values(name)
        np.testing.assert_allclose(when, t, rtol=1e-12, atol=0)
        scale = max(np.max(np.abs(values)), 1e-300)
        assert np.max(np.abs(got - values)) <= 1e-12 * scale, name


def test_mat_aliases_share_their_column(engine_run):
    """Dymola's layout: trajectories equal to another (or to its negation)
    point at one column of data_2, with the sign in dataInfo."""
    import scipy.io
    mat = scipy.io.loadmat(str(engine_run / "mat" / "result.mat"))
    info, data_2 = mat["dataInfo"], mat["data_2"]
    assert info.shape[0] == 4 and data_2.shape[1] == 5001
    trajectories = info[1][info[0] == 2]
    assert len(set(np.abs(trajectories))) == data_2.shape[0] - 1 < len(trajectories)
    assert [s.strip() for s in mat["Aclass"]] == ["Atrajectory", "1.1", "", "binTrans"]


def test_compare_of_a_mat_reference_passes_where_its_csv_passes(engine_run, tmp_path):
    """The Dymola reference as a .mat file gives the same table as the CSV,
    and a reference moved out of the tube fails in both forms."""
    from acausal2d.io.tables import read_csv
    t, cols = read_csv(REFERENCE)
    write_mat(tmp_path / "PistonEngine.mat", t, cols)
    result = str(engine_run / "csv" / "result.csv")
    for reference in (REFERENCE, str(tmp_path / "PistonEngine.mat")):
        proc = cli("compare", result, reference)
        assert proc.returncode == 0 and "2 of 2 signals passed" in proc.stdout, proc.stdout
    by_csv = acausal2d.compare(result, REFERENCE)
    by_mat = acausal2d.compare(str(engine_run / "mat" / "result.mat"),
                               str(tmp_path / "PistonEngine.mat"))
    assert by_csv.table() == by_mat.table()
    moved = {k: v + (0.01 if k == "revoluteDrive.w" else 0.0) for k, v in cols.items()}
    write_mat(tmp_path / "moved.mat", t, moved)
    proc = cli("compare", result, str(tmp_path / "moved.mat"))
    assert proc.returncode == 1 and "1 of 2 signals passed" in proc.stdout, proc.stdout


def test_mat_round_trip_with_negated_alias_and_parameters(tmp_path):
    t = np.linspace(0.0, 1.0, 7)
    x = np.sin(t)
    path = write_mat(tmp_path / "r.mat", t, {"a.x": x, "b.x": -x, "c.x": x, "zero": 0 * t},
                     parameters={"a.m": 2.5}, descriptions={"a.x": "position [m]"})
    time, cols = read_mat(path)
    assert set(cols) == {"a.x", "b.x", "c.x", "zero"}
    assert_copied(time, t)                              # written and read back unchanged
    assert_copied(cols["b.x"], -x)
    assert_copied(cols["c.x"], x)
    from acausal2d.io.dymola_mat import mat_units
    assert mat_units(path) == {"Time": "s", "a.x": "m"}


def test_mat_errors_name_the_file(tmp_path):
    bad = tmp_path / "bad.mat"
    bad.write_text("time,x\n0,1\n")
    for args in ((str(bad), REFERENCE), (REFERENCE, str(tmp_path / "missing.mat"))):
        proc = cli("compare", *args)
        assert proc.returncode == 2 and "Traceback" not in proc.stderr, proc.stderr
        assert "mat" in proc.stderr
    import scipy.io
    scipy.io.savemat(str(tmp_path / "plain.mat"), {"x": np.ones(3)}, format="4")
    with pytest.raises(acausal2d.Acausal2dError, match="plain.mat is not a Dymola result "
                       "file: no Aclass"):
        read_mat(tmp_path / "plain.mat")


def test_to_pandas_and_notebook_display():
    pd = pytest.importorskip("pandas")
    from conftest import load_model_class
    res = acausal2d.simulate(load_model_class("pendulum.py", "Pendulum")(), stop_time=1.0,
                             intervals=100)
    frame = res.to_pandas()
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "time"
    assert list(frame.columns) == res.names and len(frame) == len(res.time)
    assert_copied(frame["revolute.w"].to_numpy(), res["revolute.w"])   # the same numbers
    assert frame.attrs["units"]["revolute.w"] == "rad/s"
    text = repr(res)
    assert text.startswith("<Result Pendulum: t 0..1 s, 101 points, ") and "0x" not in text
    page = res._repr_html_()
    assert "<table>" in page and "Pendulum" in page and "final body.phi" in page
    png = base64.b64decode(re.search(r"base64,([A-Za-z0-9+/=]+)", page).group(1))
    assert png.startswith(b"\x89PNG")
    anim = res.animation()
    shown = anim._repr_html_()
    assert shown.startswith("<iframe srcdoc=")
    srcdoc = html.unescape(re.search(r'srcdoc="([^"]*)"', shown).group(1))
    assert srcdoc == anim.html and "<script" in anim.html


def test_compare_plots_carry_units(engine_run, tmp_path):
    """The unit of each compared signal: from the model (a Result), from
    the manifest beside a result CSV, from a .mat file's descriptions; the
    plot's value axes are labelled with it."""
    from acausal2d.visual.plotting import axis_label
    for result in (str(engine_run / "csv" / "result.csv"), str(engine_run / "mat" / "result.mat")):
        cmp = acausal2d.compare(result, REFERENCE, plot_dir=str(tmp_path / "plots"))
        units = {r.name: r.unit for r in cmp.rows}
        assert units == {"revoluteDrive.phi": "rad", "revoluteDrive.w": "rad/s"}, result
    assert axis_label("revoluteDrive.w", "rad/s") == "revoluteDrive.w [rad/s]"
    from matplotlib.figure import Figure
    labels = []
    original = Figure.savefig

    def record(fig, *a, **k):
        labels.extend(ax.get_ylabel() for ax in fig.axes)
        labels.extend(ax.get_xlabel() for ax in fig.axes if ax.get_xlabel())
        return original(fig, *a, **k)

    Figure.savefig = record
    try:
        cmp.plots = acausal2d.analysis.compare.plot_comparison(cmp, str(tmp_path / "again"))
    finally:
        Figure.savefig = original
    assert "revoluteDrive.w [rad/s]" in labels and "result \u2212 ref [rad/s]" in labels
    assert "time [s]" in labels
