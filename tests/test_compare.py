"""Tests of acausal2d.analysis.compare: reading result/reference CSV files and
comparing signals inside a tolerance tube."""
import io

import numpy as np
import pytest

from acausal2d.analysis.compare import Comparison, compare, read_csv
from acausal2d.cli.compare import run_compare_cli
from acausal2d.errors import Acausal2dError
from conftest import same_time, assert_copied

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def write_csv(path, names, rows, quoted=False):
    """Write a CSV file; ``rows`` is a 2-D array-like (one row per line)."""
    q = '"%s"' if quoted else "%s"
    lines = [",".join(q % n for n in names)]
    for row in rows:
        lines.append(",".join(repr(float(v)) for v in row))
    path.write_text("\n".join(lines) + "\n")
    return path


def ours_csv(path, t, **cols):
    names = ["time"] + [n.replace("__", ".") for n in cols]
    return write_csv(path, names, np.column_stack([t] + list(cols.values())))


def dymola_csv(path, t, cols):
    """Dymola-style file: quoted names, 'Time', last row repeated."""
    data = np.column_stack([t] + list(cols.values()))
    data = np.vstack([data, data[-1]])
    return write_csv(path, ["Time"] + list(cols), data, quoted=True)


@pytest.fixture
def sine_files(tmp_path):
    """Our result on a fine grid, a Dymola-style reference on a coarser grid."""
    t = np.linspace(0.0, 2.0, 2001)
    ours = ours_csv(tmp_path / "ours.csv", t, body__phi=np.sin(3 * t), body__w=3 * np.cos(3 * t))
    tr = np.linspace(0.0, 2.0, 201)
    ref = dymola_csv(tmp_path / "ref.csv", tr,
                     {"body.phi": np.sin(3 * tr) + 1e-3, "body.w": 3 * np.cos(3 * tr)})
    return ours, ref


# ---------------------------------------------------------------------------
# read_csv
# ---------------------------------------------------------------------------

def test_read_our_csv(tmp_path):
    p = tmp_path / "r.csv"
    p.write_text("time,body.phi,body.w\n0,1.5,-2\n0.1,1.25,3e-3\n0.2,1,4\n")
    t, cols = read_csv(p)
    assert_copied(t, [0.0, 0.1, 0.2])
    assert list(cols) == ["body.phi", "body.w"]
    assert_copied(cols["body.phi"], [1.5, 1.25, 1.0])
    assert_copied(cols["body.w"], [-2.0, 3e-3, 4.0])


def test_read_dymola_csv_with_events_and_repeated_end(tmp_path):
    p = tmp_path / "d.csv"
    p.write_text('"Time","body.phi","sw.y"\n'
                 '0,0,1\n0.5,0.25,1\n0.5,0.25,-1\n1,0.5,-1\n1,0.5,-1\n')
    t, cols = read_csv(p)
    assert_copied(t, [0.0, 0.5, 0.5, 1.0, 1.0])
    assert sorted(cols) == ["body.phi", "sw.y"]
    assert_copied(cols["sw.y"], [1, 1, -1, -1, -1])


def test_read_csv_errors(tmp_path):
    with pytest.raises(Acausal2dError, match="not found"):
        read_csv(tmp_path / "nope.csv")

    p = tmp_path / "notime.csv"
    p.write_text("t,x\n0,1\n1,2\n")
    with pytest.raises(Acausal2dError, match="no time column") as e:
        read_csv(p)
    assert "x" in str(e.value)

    p = tmp_path / "bad.csv"
    p.write_text("time,x\n0,1\n0.5,abc\n1,2\n")
    with pytest.raises(Acausal2dError, match="line 3") as e:
        read_csv(p)
    assert "abc" in str(e.value) and "'x'" in str(e.value)

    p = tmp_path / "back.csv"
    p.write_text("time,x\n0,1\n0.5,2\n0.4,3\n")
    with pytest.raises(Acausal2dError, match="not monotonic") as e:
        read_csv(p)
    assert "line 4" in str(e.value)


# ---------------------------------------------------------------------------
# compare
# ---------------------------------------------------------------------------

def test_pass_within_tolerance(sine_files):
    ours, ref = sine_files
    cmp = compare(ours, ref)
    assert isinstance(cmp, Comparison)
    assert cmp.passed
    assert [r.name for r in cmp.rows] == ["body.phi", "body.w"]
    phi, w = cmp.rows
    assert_copied(phi.tolerance, 2e-3)
    assert phi.max_deviation == pytest.approx(1e-3, abs=2e-6)   # the offset + interp. error
    assert w.max_deviation < 1e-5
    assert phi.passed and w.passed
    table = cmp.table()
    assert "PASS" in table and "FAIL" not in table
    assert "2 of 2 signals passed" in table


def test_fail_with_perturbed_point(tmp_path):
    t = np.linspace(0.0, 2.0, 2001)
    y = np.sin(3 * t)
    y_pert = y.copy()
    k = 1300                                     # t = 1.3
    y_pert[k] += 5e-3
    ours = ours_csv(tmp_path / "ours.csv", t, body__phi=y_pert, body__w=3 * np.cos(3 * t))
    tr = np.linspace(0.0, 2.0, 201)
    ref = dymola_csv(tmp_path / "ref.csv", tr,
                     {"body.phi": np.sin(3 * tr), "body.w": 3 * np.cos(3 * tr)})
    cmp = compare(ours, ref)
    assert not cmp.passed
    phi = next(r for r in cmp.rows if r.name == "body.phi")
    assert not phi.passed
    assert phi.max_deviation == pytest.approx(5e-3, abs=1e-5)
    assert phi.time == pytest.approx(1.3, abs=1e-12)
    assert [r.name for r in cmp.failed] == ["body.phi"]

    lines = cmp.table().splitlines()
    assert lines[0].split()[:2] == ["signal", "max"]
    phi_line = next(ln for ln in lines if ln.startswith("body.phi "))
    assert phi_line.split()[-1] == "FAIL"
    assert float(phi_line.split()[1]) == pytest.approx(5e-3, abs=1e-5)
    assert float(phi_line.split()[2]) == pytest.approx(1.3)
    w_line = next(ln for ln in lines if ln.startswith("body.w "))
    assert w_line.split()[-1] == "PASS"

    # a tolerance larger than the perturbation passes
    assert compare(ours, ref, abs_tol=6e-3).passed


def step_signal(t, t_event=0.5):
    return np.where(t < t_event, np.sin(t), np.sin(t) - 2.0)


def with_event(t, t_event):
    """Insert a duplicated time at t_event into the (event-free) grid t."""
    t = t[np.abs(t - t_event) > 1e-12]
    i = np.searchsorted(t, t_event)
    return np.concatenate([t[:i], [t_event, t_event], t[i:]])


def event_values(t, t_event):
    """step_signal with left limit at the first and right limit at the second
    row of the event."""
    y = step_signal(t, t_event)
    i = np.flatnonzero(t == t_event)
    y[i[0]] = np.sin(t_event)
    return y


def test_step_at_event_is_not_a_false_failure(tmp_path):
    tr = with_event(np.linspace(0.0, 1.0, 101), 0.5)
    ref = dymola_csv(tmp_path / "ref.csv", tr, {"sw.y": event_values(tr, 0.5)})
    t_ref, cols = read_csv(ref)
    assert np.count_nonzero(same_time(t_ref, 0.5)) == 2 \
        and np.count_nonzero(same_time(t_ref, 1.0)) == 2

    # ours: different grid, same event time
    t = with_event(np.linspace(0.0, 1.0, 733), 0.5)
    cmp = compare(ours_csv(tmp_path / "a.csv", t, sw__y=event_values(t, 0.5)), ref)
    assert cmp.passed
    assert cmp.rows[0].max_deviation < 1e-5

    # ours: event located slightly later (solver event-location accuracy)
    te = 0.5 + 3e-8
    t = with_event(np.linspace(0.0, 1.0, 733), te)
    cmp = compare(ours_csv(tmp_path / "b.csv", t, sw__y=event_values(t, te)), ref)
    assert cmp.passed
    assert cmp.rows[0].max_deviation < 1e-5

    # ours: no step at all -> fails with the step height at the event
    t = np.linspace(0.0, 1.0, 733)
    cmp = compare(ours_csv(tmp_path / "c.csv", t, sw__y=np.sin(t)), ref)
    assert not cmp.passed
    assert cmp.rows[0].max_deviation == pytest.approx(2.0, abs=1e-6)
    assert cmp.rows[0].time == pytest.approx(0.5)

    # ours: step at the wrong time (0.6) -> fails
    t = with_event(np.linspace(0.0, 1.0, 733), 0.6)
    cmp = compare(ours_csv(tmp_path / "d.csv", t, sw__y=event_values(t, 0.6)), ref)
    assert not cmp.passed
    assert cmp.rows[0].max_deviation == pytest.approx(2.0, abs=1e-6)
    assert 0.5 <= cmp.rows[0].time < 0.6


def test_mapping_and_signal_selection(sine_files, tmp_path):
    ours, ref = sine_files
    t, cols = read_csv(ours)
    renamed = (t, {"mech.body.phi": cols["body.phi"], "other": cols["body.w"]})

    with pytest.raises(Acausal2dError, match="no signal in common"):
        compare(renamed, ref)

    cmp = compare(renamed, ref, mapping={"body.phi": "mech.body.phi"})
    assert [(r.name, r.our_name) for r in cmp.rows] == [("body.phi", "mech.body.phi")]
    # body.w has no counterpart: named, and the comparison fails (issue 18)
    assert cmp.unmatched == ["body.w"] and not cmp.passed and cmp.rows[0].passed
    assert "not compared (no counterpart in the result): body.w" in cmp.table()
    cmp = compare(renamed, ref, mapping={"body.phi": "mech.body.phi"}, only_common=True)
    assert cmp.passed and "body.w" in cmp.table()
    assert cmp.rows[0].max_deviation == pytest.approx(1e-3, abs=2e-6)
    assert "body.phi -> mech.body.phi" in cmp.table()

    cmp = compare(ours, ref, signals=["body.w"])
    assert [r.name for r in cmp.rows] == ["body.w"]


def test_rel_tol(tmp_path):
    t = np.linspace(0.0, 3.0, 301)
    ref = 10 * np.cos(t)                            # max |ref| = 10 at t = 0
    ours = (t, {"x": ref + 0.03})
    reference = (t, {"x": ref})
    assert not compare(ours, reference).passed          # default abs_tol 2e-3

    cmp = compare(ours, reference, rel_tol=0.005)       # tube half-width 0.05
    assert cmp.passed
    assert cmp.rows[0].tolerance == pytest.approx(0.05)
    assert cmp.rows[0].max_deviation == pytest.approx(0.03)

    cmp = compare(ours, reference, rel_tol=0.002)       # 0.02 < 0.03
    assert not cmp.passed
    assert cmp.rows[0].tolerance == pytest.approx(0.02)

    cmp = compare(ours, reference, abs_tol=0.04, rel_tol=0.002)   # the larger one
    assert cmp.passed
    assert cmp.rows[0].tolerance == pytest.approx(0.04)
    cmp = compare(ours, reference, abs_tol=0.001, rel_tol=0.005)
    assert cmp.rows[0].tolerance == pytest.approx(0.05)


def test_missing_signals(sine_files):
    ours, ref = sine_files
    with pytest.raises(Acausal2dError) as e:
        compare(ours, ref, signals=["body.phi", "body.phii", "nope.x"])
    msg = str(e.value)
    assert "body.phii" in msg and "nope.x" in msg and "reference" in msg
    assert "body.phi," in msg or "body.phi " in msg           # lists available names

    with pytest.raises(Acausal2dError) as e:
        compare(ours, ref, signals=["body.phi"], mapping={"body.phi": "mech.phi"})
    msg = str(e.value)
    assert "mech.phi" in msg and "result" in msg and "body.phi" in msg


def test_reference_longer_than_result_fails(tmp_path):
    t = np.linspace(0.0, 1.0, 101)
    tr = np.linspace(0.0, 2.0, 201)
    cmp = compare((t, {"x": t}), (tr, {"x": tr}))
    assert not cmp.passed
    row = cmp.rows[0]
    assert row.max_deviation < 1e-12                    # the covered part agrees
    assert "t=0 to 1" in row.message and "100 reference points outside" in row.message
    assert "t=0 to 1" in cmp.table()


def test_plots_written(sine_files, tmp_path):
    ours, ref = sine_files
    t, cols = read_csv(ours)
    ours_t = (t, {"der(body.phi)": cols["body.w"], "body.phi": cols["body.phi"]})
    t_ref, ref_cols = read_csv(ref)
    ref_t = (t_ref, {"der(body.phi)": ref_cols["body.w"], "body.phi": ref_cols["body.phi"]})
    out = tmp_path / "plots"
    cmp = compare(ours_t, ref_t, plot_dir=out)
    names = sorted(p.name for p in out.iterdir())
    assert names == ["body.phi.png", "der_body.phi_.png"]
    assert sorted(str(out / n) for n in names) == sorted(cmp.plots)
    for n in names:
        data = (out / n).read_bytes()
        assert len(data) > 1000
        assert data[:8] == PNG_MAGIC


def test_run_compare_cli(sine_files, tmp_path):
    ours, ref = sine_files
    buf = io.StringIO()
    assert run_compare_cli(ours, ref, stream=buf) == 0
    assert "body.phi" in buf.getvalue() and "PASS" in buf.getvalue()

    buf = io.StringIO()
    rc = run_compare_cli(ours, ref, signals=["body.phi"], abs_tol=5e-4,
                         out_dir=tmp_path / "out", stream=buf)
    assert rc == 1
    assert "FAIL" in buf.getvalue()
    assert (tmp_path / "out" / "body.phi.png").read_bytes()[:8] == PNG_MAGIC
