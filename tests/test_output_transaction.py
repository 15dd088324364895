"""Issue 35, Seen 4, 5 and 6: an output folder is written as one transaction
(acausal2d.io.output.OutputFolder), sizes and inputs are bounded before
anything is allocated, and the forked figure process ends silently.

Each test names the Seen item it holds to.  No test depends on timing:
the concurrent run is a lock held by this process, interruptions are raised
at chosen points (the fuzz test test_fuzz_output.py sends real signals)."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

from acausal2d.cli import main
from acausal2d.io.files import MANIFEST, NAME_LIMIT, bounded_name, safe_filename
from acausal2d.io.output import LOCK_SUFFIX, PART_SUFFIX, OutputFolder

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir)
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")


def leftovers(out):
    """Temporary sibling folders and lock files of runs into ``out``."""
    parent, name = os.path.split(os.path.abspath(str(out)))
    return [n for n in os.listdir(parent) if n.startswith("." + name + ".")
            and (n.endswith(PART_SUFFIX) or n.endswith(LOCK_SUFFIX))]


def listed(out):
    with open(os.path.join(str(out), MANIFEST), encoding="utf-8") as fh:
        return json.load(fh)["files"]


def pendulum_copy(tmp_path, extra=""):
    """The pendulum model file with ``extra`` appended to its class body."""
    source = open(PENDULUM, encoding="utf-8").read()
    head, tail = source.split('\n\nif __name__ == "__main__":')
    path = tmp_path / "pendulum_x.py"
    path.write_text(head + textwrap.indent(textwrap.dedent(extra), "    ") + "\n",
                    encoding="utf-8")
    return str(path)


def simulate(model, out, *args):
    return main(["simulate", model, "--out", str(out), "--intervals", "20", *args])


@pytest.fixture
def first_run(tmp_path, capfd):
    """A successful run into tmp_path/out (its files listed); returns out."""
    out = tmp_path / "out"
    assert simulate(PENDULUM, out) == 0
    assert {"result.csv", "animation.html"} <= set(listed(out))
    capfd.readouterr()
    return out


# ------------------------------------------------------------------ Seen 4

def test_seen4_writer_failing_after_the_csv_leaves_neither_new_nor_old_files(
        first_run, tmp_path, capfd):
    """A model's output writer raises after result.csv was written: exit 2,
    its name in the message, no traceback, nothing of either run left."""
    model = pendulum_copy(tmp_path, """
        def write_outputs(self, result, folder):
            open(os.path.join(folder, "extra.txt"), "w").write("half")
            raise RuntimeError("disk on fire")
        """)
    text = open(model).read().replace('"""\nfrom acausal2d', '"""\nimport os\nfrom acausal2d', 1)
    open(model, "w").write(text)
    assert simulate(model, first_run) == 2
    err = capfd.readouterr().err
    assert "Pendulum.write_outputs failed: RuntimeError: disk on fire" in err
    assert "Traceback" not in err
    assert os.listdir(first_run) == []
    assert leftovers(first_run) == []


def test_seen4_interrupt_while_figures_are_drawn_leaves_nothing(first_run, monkeypatch, capfd):
    """Ctrl-C after result.csv was written (while the figures are collected):
    exit 130 and the folder holds nothing of the run or of the one before."""
    from acausal2d.visual import figure_process

    def interrupted(self):
        raise KeyboardInterrupt
    monkeypatch.setattr(figure_process.FigureProcess, "collect", interrupted)
    monkeypatch.setattr("acausal2d.visual.plotting.draw_jobs",
                        lambda jobs: (_ for _ in ()).throw(KeyboardInterrupt()))
    assert simulate(PENDULUM, first_run) == 130
    assert "interrupted" in capfd.readouterr().err
    assert os.listdir(first_run) == [] and leftovers(first_run) == []


def test_seen4_sigterm_after_the_csv_exits_143_and_leaves_nothing(first_run, tmp_path):
    """SIGTERM (a service stopping, a batch system's time limit) while the
    outputs are written is rolled back like Ctrl-C: exit 143, no traceback,
    nothing of this run or the one before."""
    model = pendulum_copy(tmp_path, """
        def write_outputs(self, result, folder):
            import os, signal, time
            os.kill(os.getpid(), signal.SIGTERM)
            time.sleep(5)
        """)
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    proc = subprocess.run([exe, "simulate", model, "--intervals", "20", "--out",
                           str(first_run)], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 143 and proc.stderr.strip() == "interrupted (SIGTERM)", proc.stderr
    assert os.listdir(first_run) == [] and leftovers(first_run) == []


def test_seen4_plot_of_many_joined_signals_gets_a_bounded_name(tmp_path, capfd):
    """A figure named after 40 joined signal names: written under a name of
    at most NAME_LIMIT bytes (shortened with a hash) and listed."""
    plot = ",".join(["body.phi", "revolute.w"] * 20)
    out = tmp_path / "out"
    assert simulate(PENDULUM, out, "--plot", plot) == 0, capfd.readouterr().err
    pngs = [n for n in listed(out) if n.endswith(".png")]
    assert len(pngs) == 1 and len(pngs[0].encode()) <= NAME_LIMIT
    assert (out / pngs[0]).stat().st_size > 1000


def test_bounded_name_keeps_short_names_and_separates_long_ones():
    assert bounded_name("result.csv") == "result.csv"
    a, b = "x" * 300 + "a.png", "x" * 300 + "b.png"
    assert bounded_name(a) != bounded_name(b)
    assert all(len(bounded_name(n).encode()) <= NAME_LIMIT and bounded_name(n).endswith(".png")
               for n in (a, b))
    assert len(safe_filename("ä" * 200).encode()) <= NAME_LIMIT


def test_seen4_unwritable_out_is_refused_before_the_model_is_compiled(monkeypatch, capfd):
    """An --out that cannot be created (under /proc, not writable even for
    root) fails before anything is compiled or simulated."""
    def never(*a, **k):
        raise AssertionError("compiled although --out cannot be written")
    monkeypatch.setattr("acausal2d.compiled.compile_model", never)
    assert simulate(PENDULUM, "/proc/acausal2d-out/x") == 2
    err = capfd.readouterr().err
    assert err.startswith("error: ") and "/proc/acausal2d-out" in err


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_seen4_read_only_out_is_refused_before_the_run(tmp_path, monkeypatch, capfd):
    out = tmp_path / "ro"
    out.mkdir()
    out.chmod(0o555)
    monkeypatch.setattr("acausal2d.compiled.compile_model",
                        lambda *a, **k: pytest.fail("compiled before the check"))
    try:
        assert simulate(PENDULUM, out) == 2
    finally:
        out.chmod(0o755)
    assert "not writable" in capfd.readouterr().err


def test_seen4_second_run_into_the_same_out_is_refused_naming_the_first(first_run, capfd):
    """While a run holds the folder, a second one stops at once with exit 2
    naming the first (its pid and command) and touches nothing; the first
    then completes."""
    with OutputFolder(first_run, "simulate") as tx:
        with open(tx.file("result.csv"), "w") as fh:
            fh.write("time\n0\n")
        assert simulate(PENDULUM, first_run) == 2
        err = capfd.readouterr().err
        assert "being written by process %d (acausal2d simulate" % os.getpid() in err
        assert os.path.exists(tx.file("result.csv"))
    assert listed(first_run) == ["result.csv"]
    assert leftovers(first_run) == []


def test_seen4_lock_of_a_killed_run_does_not_block(tmp_path):
    """A SIGKILLed run leaves its lock file and temporary folder: the kernel
    released the lock, so the next run proceeds and removes both."""
    out = tmp_path / "out"
    code = ("import os, sys\nfrom acausal2d.io.output import OutputFolder\n"
            "tx = OutputFolder(sys.argv[1], 'simulate').__enter__()\n"
            "open(tx.file('result.csv'), 'w').write('half')\nos._exit(9)\n")
    subprocess.run([sys.executable, "-c", code, str(out)], check=False, timeout=60)
    assert len(leftovers(out)) == 2
    with OutputFolder(out, "simulate"):
        pass
    assert leftovers(out) == [] and listed(out) == []


def test_seen4_kill_during_the_final_moves_is_cleaned_by_the_next_run(tmp_path):
    """A run killed after moving some entries in (its manifest still in the
    temporary folder): the next run removes those entries."""
    out = tmp_path / "out"
    code = ("import os, sys\nfrom acausal2d.io import output\n"
            "real = os.replace\n"
            "def replace(a, b):\n"
            "    real(a, b)\n"
            "    if b.endswith('a.csv'): os._exit(9)\n"
            "output.os.replace = replace\n"
            "with output.OutputFolder(sys.argv[1], 'simulate') as tx:\n"
            "    for n in ('a.csv', 'b.csv'): open(tx.file(n), 'w').write(n)\n")
    subprocess.run([sys.executable, "-c", code, str(out)], check=False, timeout=60)
    assert os.listdir(out) == ["a.csv"]              # moved in, not listed anywhere in out
    with OutputFolder(out, "simulate"):
        pass
    assert sorted(os.listdir(out)) == [MANIFEST] and leftovers(out) == []


def test_seen4_foreign_files_in_out_are_kept(first_run, tmp_path, capfd):
    (first_run / "notes.txt").write_text("mine")
    model = pendulum_copy(tmp_path, "experiment = {'stop_time': 1e-320}\n")
    assert simulate(model, first_run) == 2
    assert os.listdir(first_run) == ["notes.txt"]


def test_seen4_sweep_keeps_a_manifest_and_a_failing_sweep_leaves_no_old_file(tmp_path, capfd):
    out = tmp_path / "out"
    base = ["sweep", PENDULUM, "--vary", "body.m=1:2:2", "--scheduler", "serial",
            "--stop-time", "0.2", "--out", str(out)]
    assert main(base) == 0, capfd.readouterr().err
    assert sorted(listed(out)) == ["sweep.csv", "sweep.png"]
    assert main(base + ["--outputs", "no.such"]) == 2
    assert "no signal 'no.such'" in capfd.readouterr().err
    assert os.listdir(out) == [] and leftovers(out) == []


def test_seen4_export_fmu_into_an_existing_folder_is_refused_before_the_build(
        tmp_path, monkeypatch, capfd):
    monkeypatch.setattr("acausal2d.fmu.export.export_data",
                        lambda *a, **k: pytest.fail("built before the check"))
    assert main(["export-fmu", PENDULUM, "--out", str(tmp_path)]) == 2
    err = capfd.readouterr().err
    assert "is a folder" in err and str(tmp_path) in err
    assert os.listdir(tmp_path) == []


# ------------------------------------------------------------------ Seen 5

@pytest.mark.parametrize("vary, count", [(["body.m=0:1:100000000000"], "100000000000"),
                                         (["body.m=0:1:1000", "body.I=0:1:1000"], "1000000")])
@pytest.mark.parametrize("command", ["sweep", "modes"])
def test_seen5_grid_over_the_budget_is_refused_with_its_count(command, vary, count, tmp_path,
                                                              monkeypatch, capfd):
    monkeypatch.setattr("acausal2d.compiled.compile_model",
                        lambda *a, **k: pytest.fail("compiled before the size check"))
    monkeypatch.setattr("acausal2d.analysis.sweep.compiled_model",
                        lambda *a, **k: pytest.fail("compiled before the size check"))
    argv = [command, PENDULUM, "--out", str(tmp_path / "o")]
    for v in vary:
        argv += ["--vary", v]
    assert main(argv) == 2
    err = capfd.readouterr().err
    assert "has %s points" % count in err and "budget is 100000 points" in err


def test_seen5_study_that_raises_is_reported_with_its_name(tmp_path, capfd):
    model = pendulum_copy(tmp_path, """
        @acausal2d.study
        def broken(ctx):
            '''A study with a bug.'''
            return 1 / 0
        """)
    text = open(model).read().replace('"""\nfrom acausal2d', '"""\nimport acausal2d\n'
                                      'from acausal2d', 1)
    open(model, "w").write(text)
    out = tmp_path / "out"
    assert main(["study", model, "--out", str(out)]) == 2
    err = capfd.readouterr().err
    assert "study Pendulum.broken failed: ZeroDivisionError" in err
    assert "Traceback" not in err
    assert os.listdir(out) == [] and leftovers(out) == []


STUDIES = '''
@acausal2d.study
def table(ctx):
    """A table."""
    ctx.save(ctx.simulate(stop_time=0.1), "short")

@acausal2d.study
def broken(ctx):
    """A study with a bug."""
    raise KeyError("no such thing")
'''


def test_study_adds_its_files_to_the_simulation_s_and_a_failing_one_keeps_them(
        first_run, tmp_path, capfd):
    """``python model.py`` runs simulate, then study into one folder: the
    study's transaction keeps and lists simulate's files (merge); a study
    that fails leaves them as they were and adds nothing."""
    model = pendulum_copy(tmp_path, STUDIES)
    text = open(model).read().replace('"""\nfrom acausal2d', '"""\nimport acausal2d\n'
                                      'from acausal2d', 1)
    open(model, "w").write(text)
    before = set(listed(first_run))
    assert main(["study", model, "table", "--out", str(first_run)]) == 0
    assert set(listed(first_run)) == before | {"short.csv"}
    assert main(["study", model, "broken", "--out", str(first_run)]) == 2
    assert "study Pendulum.broken failed: KeyError" in capfd.readouterr().err
    assert set(listed(first_run)) == before | {"short.csv"}
    assert set(os.listdir(first_run)) == before | {"short.csv", MANIFEST}
    assert leftovers(first_run) == []


@pytest.mark.parametrize("content, expected", [
    (b'{"id": "x",\n "nodes": [\xff]}', "not UTF-8 text: byte 0xff at line 2, column 12"),
    (b"\n" + b"[" * 100000 + b"]" * 100000, "deeper than 64 levels (line 2, column 65)"),
    (b'{"a": "' + b"[" * 1000 + b'", "b": [[[]]]}', "no valid JSON"),
], ids=["invalid-utf8", "deep", "brackets-in-a-string"])
def test_seen5_mec2_file_parsed_with_limits_naming_file_and_position(content, expected,
                                                                     tmp_path, capfd):
    path = tmp_path / "model.json"
    path.write_bytes(content)
    assert main(["check", str(path)]) == 2
    err = capfd.readouterr().err
    assert str(path) in err and "Traceback" not in err
    if expected != "no valid JSON":
        assert expected in err
    else:                      # the brackets in a string do not count: the file is just no model
        assert "deeper" not in err


def test_seen5_deeply_nested_manifest_is_an_error_naming_it(tmp_path, capfd):
    out = tmp_path / "out"
    out.mkdir()
    (out / MANIFEST).write_text("[" * 100000)
    assert simulate(PENDULUM, out) == 2
    err = capfd.readouterr().err
    assert str(out / MANIFEST) in err and "line 1, column 65" in err
    assert "Traceback" not in err and leftovers(out) == []


# ------------------------------------------------------------------ Seen 6

CHILD = r"""
import os, signal, sys, time, weakref
from acausal2d.visual import figure_process

class Module: pass

def drawing():
    # importlib's module-lock callback interrupted: the SIGINT lands inside
    # a weakref callback, where Python can only report it as unraisable
    obj = Module()
    def cb(ref):
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(100000):
            pass
    keep = weakref.ref(obj, cb)
    del obj
    open(sys.argv[1], "w").close()
    time.sleep(0.2)
    return lambda jobs: []

figure_process._drawing = drawing
proc = figure_process.FigureProcess.start()
assert proc is not None
deadline = time.monotonic() + 30
while not os.path.exists(sys.argv[1]) and time.monotonic() < deadline:
    time.sleep(0.01)
proc.close()
print("closed")
"""


def test_seen6_figure_process_interrupted_early_ends_silently(tmp_path):
    """The child is interrupted inside a callback (as importing matplotlib
    was, once in 257 runs): nothing on stderr, the parent goes on."""
    marker = str(tmp_path / "interrupted")
    proc = subprocess.run([sys.executable, "-c", CHILD, marker], capture_output=True,
                          text=True, timeout=60)
    assert os.path.exists(marker)
    assert proc.returncode == 0 and proc.stdout == "closed\n"
    assert proc.stderr == ""


def test_seen6_early_failure_prints_only_its_error(tmp_path):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    for _ in range(3):
        proc = subprocess.run([exe, "simulate", PENDULUM, "--stop-time", "1e-320", "--out",
                               str(tmp_path / "o")], capture_output=True, text=True, timeout=120)
        assert proc.returncode == 2
        assert proc.stderr.startswith("error: ") and proc.stderr.count("\n") == 1, proc.stderr
