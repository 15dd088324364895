"""A run's side effects: first-run notices through the named logger
'acausal2d' (quiet in Python and a notebook unless asked, on stderr on the
command line), the process's temporary files in a folder of its own that
is removed at exit, on SIGINT and on SIGTERM, and no animation (said in one
line) for a model without planar geometry."""
import logging
import os
import signal
import subprocess
import sys
import time

import pytest

import acausal2d
from acausal2d import Acausal2dError
from acausal2d.io.output import OutputFolder
from acausal2d.runtime import notices as runtime_notices, rundir

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CLUTCH = os.path.join(HERE, "data", "user_models", "clutch_drive.py")
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")


@pytest.fixture
def fresh_notices(monkeypatch):
    monkeypatch.setattr(runtime_notices, "_said", set())
    log = runtime_notices.logger()
    level = log.level
    yield log
    log.setLevel(level)


def test_a_first_run_notice_is_quiet_in_python_unless_asked(fresh_notices, capfd):
    fresh_notices.setLevel(logging.WARNING)          # Python's and a notebook's default
    runtime_notices.notice("compiling native code for M in the background", first_run=True)
    assert capfd.readouterr().err == ""
    fresh_notices.setLevel(logging.INFO)             # asked for
    runtime_notices.notice("compiling native code for N in the background", first_run=True)
    assert capfd.readouterr().err == "acausal2d: compiling native code for N in the background\n"


def test_a_failure_notice_is_said_once_and_goes_through_the_named_logger(fresh_notices,
                                                                        capfd):
    assert fresh_notices is logging.getLogger("acausal2d")
    for _ in range(2):
        runtime_notices.notice("the cached library x is damaged; rebuilding it")
    assert capfd.readouterr().err == "acausal2d: the cached library x is damaged; rebuilding it\n"


def _folders(base):
    return [n for n in os.listdir(base) if n.startswith(rundir.PREFIX)]


def test_a_stale_run_folder_of_a_gone_process_is_swept(tmp_path):
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"],
                          capture_output=True, text=True).stdout.strip()
    (tmp_path / ("%s%s-abc" % (rundir.PREFIX, dead))).mkdir()
    (tmp_path / ("%s%d-def" % (rundir.PREFIX, os.getppid()))).mkdir()      # alive
    removed = rundir.sweep_stale(str(tmp_path))
    assert [os.path.basename(p) for p in removed] == ["%s%s-abc" % (rundir.PREFIX, dead)]
    assert _folders(tmp_path) == ["%s%d-def" % (rundir.PREFIX, os.getppid())]


def _default_sigint():
    """In the child before exec: SIGINT's default disposition, so that Python
    installs its handler even where this suite runs with SIGINT ignored (a
    background job of a shell without job control)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


@pytest.mark.slow           # a command-line process interrupted in its run
@pytest.mark.parametrize("signum,code", [(signal.SIGTERM, 143), (signal.SIGINT, 130)])
def test_the_run_folder_is_removed_on_a_signal(tmp_path, signum, code):
    """The command's SUNDIALS log lives in <tmp>/acausal2d-run-<pid>-*; the
    folder is gone after SIGTERM or SIGINT in the middle of the run."""
    base = tmp_path / "tmp"
    base.mkdir()
    env = dict(os.environ, TMPDIR=str(base))
    env.pop("SUNLOGGER_WARNING_FILENAME", None)
    proc = subprocess.Popen([sys.executable, "-m", "acausal2d", "simulate", CLUTCH, "--model",
                             "ClutchDrive", "--stop-time", "200", "--native", "off", "--out",
                             str(tmp_path / "o")], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_default_sigint)
    deadline = time.monotonic() + 120

    def started():       # the run folder and the output transaction's temporary folder
        return _folders(base) and any(n.startswith(".o.") for n in os.listdir(tmp_path))
    while not started() and time.monotonic() < deadline and proc.poll() is None:
        time.sleep(0.05)
    assert _folders(base) == ["%s%d-%s" % (rundir.PREFIX, proc.pid, _folders(base)[0].split(
        "-")[-1])]
    time.sleep(0.5)                                    # inside the command
    proc.send_signal(signum)
    out, err = proc.communicate(timeout=120)
    assert proc.returncode == code, err
    assert _folders(base) == []


def test_a_model_without_geometry_gets_no_animation_and_says_so(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", CLUTCH, "--model",
                           "ClutchDrive", "--stop-time", "0.05", "--native", "off", "--out",
                           str(tmp_path / "o")], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert not (tmp_path / "o" / "animation.html").exists()
    assert "animation.html" not in proc.stdout
    assert ("  no animation: ClutchDrive has no planar geometry to draw (its elements declare "
            "no shapes, as in a drive train or a hydraulic circuit)") in proc.stdout.splitlines()
    res = acausal2d.simulate(acausal2d.load_model(CLUTCH, "ClutchDrive"), stop_time=0.05)
    with pytest.raises(Acausal2dError, match="no animation: ClutchDrive has no planar"):
        res.animate(tmp_path / "a.html")
    with pytest.raises(Acausal2dError, match="no animation"):
        res.animation()


def test_a_planar_model_still_gets_its_animation(tmp_path):
    res = acausal2d.simulate(acausal2d.load_model(PENDULUM), stop_time=0.1)
    page = res.animate(tmp_path / "a.html")
    assert os.path.getsize(page) > 1000


@pytest.mark.slow           # a command-line process compiling native code
def test_a_first_run_says_one_notice_and_no_contradicting_notes(tmp_path):
    """A first run with an empty native cache: at most one notice on
    stderr, and the tier notes ("native: compile first ...") only with
    --verbose."""
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=str(tmp_path / "cache"), ACAUSAL2D_NATIVE="auto")
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", PENDULUM,
                           "--stop-time", "0.2", "--out", str(tmp_path / "o")], env=env,
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    notices = [line for line in proc.stderr.splitlines() if line.startswith("acausal2d: ")]
    assert len(notices) <= 1, notices
    assert not any(line.startswith("  native: ") for line in proc.stdout.splitlines())


def test_a_ctrl_c_swallowed_on_its_way_up_still_rolls_the_output_folder_back(tmp_path):
    """An interrupt that lands where it is only printed ("Exception ignored",
    a finaliser or weakref callback) must not let the run commit."""
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            with OutputFolder(tmp_path / "o", "simulate") as tx:
                with open(tx.file("result.csv"), "w", encoding="utf-8") as fh:
                    fh.write("time\n0\n")
                try:
                    signal.raise_signal(signal.SIGINT)
                except KeyboardInterrupt:
                    pass                 # swallowed, as a weakref callback does
    finally:
        signal.signal(signal.SIGINT, old)
    assert not (tmp_path / "o" / "result.csv").exists()
    assert [n for n in os.listdir(tmp_path) if n != "o"] == []


SWALLOWED = """

class Swallow(ClutchDrive):
    def write_outputs(self, result, folder):
        try:    # Ctrl-C inside code run by exec() of a string, caught there
            exec("import signal; signal.raise_signal(signal.SIGINT)")
        except KeyboardInterrupt:
            pass
        return []
"""


def test_python_m_exits_130_when_ctrl_c_ended_exec_code_and_was_caught(tmp_path):
    """CPython remembers a KeyboardInterrupt that ended exec() of a string
    even when it was caught, and under ``python -m`` kills the process with
    SIGINT after finalisation (exit -2); the command exits 130, with its
    output folder rolled back and its run folder removed."""
    model = tmp_path / "swallow.py"
    model.write_text(open(CLUTCH, encoding="utf-8").read() + SWALLOWED, encoding="utf-8")
    base = tmp_path / "tmp"
    base.mkdir()
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate", str(model), "--model",
                           "Swallow", "--stop-time", "0.05", "--native", "off", "--out",
                           str(tmp_path / "o")], env=dict(os.environ, TMPDIR=str(base)),
                          capture_output=True, text=True, timeout=600, preexec_fn=_default_sigint)
    assert proc.returncode == 130, proc.stderr
    assert proc.stderr.splitlines()[-1] == "interrupted"
    assert not os.path.exists(tmp_path / "o" / "result.csv")
    assert _folders(base) == []
