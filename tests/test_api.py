"""The Python API as a notebook uses it: the README's snippet, with the
functions called repeatedly and output folders that do not exist yet."""
import csv

import pytest

import acausal2d
from conftest import load_model_class


def test_check_and_compare_can_be_called_again(tmp_path):
    """``acausal2d.check`` / ``acausal2d.compare`` stay functions after the
    submodules of the same names have been imported."""
    import acausal2d.analysis.check  # noqa: F401
    import acausal2d.analysis.compare  # noqa: F401
    pendulum = load_model_class("pendulum.py", "Pendulum")
    for _ in range(2):
        report = acausal2d.check(pendulum())
        assert report.structural_dof == 1 and report.grubler == 1
    res = acausal2d.simulate(pendulum(), stop_time=0.5, intervals=50)
    path = res.to_csv(str(tmp_path / "new" / "folder" / "result.csv"))
    with open(path) as fh:
        header = next(csv.reader(fh))
    assert header[0] == "time" and "body.phi" in header
    for _ in range(2):
        cmp = acausal2d.compare(path, path)
        assert cmp.passed
        # a file against itself: each sample is interpolated at its own time,
        # exact up to a rounding of the value, far below a millionth of the tube
        assert len(cmp.rows) >= 2 and all(r.max_deviation <= 1e-6 * r.tolerance for r in cmp.rows)


def test_simulate_rejects_bad_settings(compiled_model):
    cm = compiled_model("pendulum.py", "Pendulum")
    with pytest.raises(acausal2d.Acausal2dError, match="must be larger than start_time"):
        cm.simulate(stop_time=0.0)
    with pytest.raises(acausal2d.Acausal2dError, match="output_times must be at least two"):
        cm.simulate(output_times=[0.0, 0.2, 0.1])
    with pytest.raises(acausal2d.Acausal2dError, match="atol must be a positive number"):
        cm.simulate(atol=-1.0)
