"""Fuzz suite: several hundred malformed or borderline inputs
(tests/fuzz_cases.py: structure, connections, parameters, impossible
geometry, numerics, files, compare inputs, and issue 18's trust classes) through the Python API and the
command-line entry point.  A run takes a quarter of each class's cases,
drawn with a fixed seed (``ACAUSAL2D_FUZZ=all``: every case); the first
of each class is in the fast tier.  Every input ends within its time limit in a
correct result or in the project's error: exit code 2 (input/model error),
3 (run stopped early) or, for compare, 1 (outside the tube) - never a
traceback, LAPACK chatter, a hang, or exit 0 with NaN in the result."""
import csv
import math
import signal

import numpy as np
import pytest

import acausal2d
from acausal2d import Acausal2dError
from acausal2d.cli import main
import fuzz_cases
from conftest import fuzz_sample

CASES = fuzz_cases.all_cases()
LIMIT = 30.0          # seconds per input (the slowest correct runs take well under 2 s)
NOISE = ("Traceback", "DLASCL", "** On entry", "[WARNING]", "[IDASolve, Error")


class Hang(Exception):
    pass


class time_limit:
    """Raise Hang in the main thread after ``seconds``."""

    def __init__(self, seconds):
        self.seconds = seconds

    def __enter__(self):
        def alarm(signum, frame):
            raise Hang("no answer within %g s" % self.seconds)
        self.previous = signal.signal(signal.SIGALRM, alarm)
        signal.setitimer(signal.ITIMER_REAL, self.seconds)

    def __exit__(self, *exc):
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, self.previous)
        return False


def _files(case, tmp_path):
    """Write the case's model file or CSV files; return their paths."""
    if case["command"] == "compare":
        paths = [tmp_path / "result.csv", tmp_path / "reference.csv"]
        for p, text in zip(paths, case["csv"]):
            p.write_text(text, encoding="utf-8", errors="surrogateescape")
        return [str(p) for p in paths]
    path = tmp_path / case["filename"]
    if case["model"] is not None:
        path.write_text(case["model"], encoding="utf-8")
    data = [tmp_path / ("data%d.csv" % k) for k in range(len(case.get("csv") or ()))]
    for p, text in zip(data, case.get("csv") or ()):       # e.g. a fit's measured data
        p.write_text(text, encoding="utf-8")
    return [str(path)] + [str(p) for p in data]


def _finite_result(res):
    for name in res.names:
        values = res[name]
        assert np.all(np.isfinite(values)), "%s has non-finite values" % name


def _fourbar_closes(res):
    x, y = res["rocker.frame_b.x"], res["rocker.frame_b.y"]
    gd = res["gd.frame.x"]
    assert np.max(np.hypot(x - gd, y)) < 1e-8, "the loop does not close"


def _api(case, paths):
    if case.get("api") is not None:       # its own call and checks (fuzz_cases_fitopt)
        return case["api"](paths)
    if case["command"] == "compare":
        return acausal2d.compare(paths[0], paths[1])
    model_name = case["args"][case["args"].index("--model") + 1] \
        if "--model" in case["args"] else None
    model = acausal2d.load_model(paths[0], model_name)
    if case["command"] == "check":
        return acausal2d.check(model)
    res = acausal2d.simulate(model, params=case["params"], max_steps=50000,
                             **(case["kwargs"] or {}))
    if res.stopped is None:
        _finite_result(res)
        if case["category"] == "geometry":
            _fourbar_closes(res)
    return res


@pytest.mark.parametrize("case", fuzz_sample(CASES))
def test_api_gives_a_result_or_the_projects_error(case, tmp_path, capfd):
    paths = _files(case, tmp_path)
    refused = False
    with time_limit(LIMIT):
        try:
            got = _api(case, paths)
        except Acausal2dError as exc:
            refused = True
            assert str(exc).strip(), "an error without a message"
            assert "Traceback" not in str(exc)
    if case["codes"] is not None and 0 not in case["codes"] and not case["args"]:
        # no silent acceptance (command-line arguments are the CLI test's)
        assert refused or (case["command"] == "compare" and not got.passed), "accepted"
    if case["codes"] == (0,):
        assert not refused, "refused a good input"
    out = capfd.readouterr()
    for noise in NOISE:
        assert noise not in out.out + out.err


def _argv(case, paths, out):
    if case.get("argv") is not None:
        return case["argv"](paths, str(out))
    if case["command"] == "compare":
        return ["compare"] + paths + ["--out", str(out)]
    if case["command"] == "check":
        return ["check"] + paths + case["args"]
    argv = ["simulate"] + paths + ["--out", str(out)] + case["args"]
    if "--max-steps" not in argv:
        argv += ["--max-steps", "50000"]
    return argv


def _check_written_result(out):
    path = out / "result.csv"
    assert path.exists(), "exit 0 without result.csv"
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    assert len(rows) >= 2 and rows[0][0] == "time"
    for row in rows[1:]:
        assert len(row) == len(rows[0]) and all(math.isfinite(float(v)) for v in row)


CLI_CASES = [c for c in CASES if c["params"] is None and c["kwargs"] is None]


@pytest.mark.parametrize("case", fuzz_sample(CLI_CASES))
def test_cli_exits_with_a_documented_code_and_no_traceback(case, tmp_path, capfd):
    paths = _files(case, tmp_path)
    out = tmp_path / "out"
    with time_limit(LIMIT):
        code = main(_argv(case, paths, out))
    text = "".join(capfd.readouterr())
    for noise in NOISE:
        assert noise not in text
    allowed = case["codes"] or ((0, 1, 2) if case["command"] == "compare" else (0, 2, 3))
    assert code in allowed, "exit %r: %s" % (code, text[-400:])
    if code != 0:
        assert "error" in text.lower() or "stopped" in text.lower() or "FAIL" in text
    elif case["command"] == "simulate":
        _check_written_result(out)
