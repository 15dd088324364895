"""FMI 2.0 export (acausal2d/fmu): the exported Model Exchange and
Co-Simulation FMUs pass FMPy's validation and FMPy's simulation of them
(ME: CVode at rtol 1e-8; CS: 1 ms communication step) matches acausal2d's
own run (IDA, an independent integrator) within 1e-4 of each output's
range; clutch lock/unlock within 1 ms; a parameter set with fmi2SetReal
before initialization acts as ``params``/``--set``; the ME binary runs
from a C driver with an empty environment; dynamic state selection is
refused with the documented error."""
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

import acausal2d
from acausal2d.cli import main
import acausal2d.fmu  # noqa: E402,F401
from acausal2d.fmu import DynamicStateSelectionError, export_fmu

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "benchmarks"))
import bench_fmu  # noqa: E402
from bench_fmu import (CASES, STEP, export, fmu_run, load, max_relative_errors,  # noqa: E402
                       reference)


@pytest.fixture(scope="module")
def fmus(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fmu")
    cache = {}

    def get(case, kind):
        if (case, kind) not in cache:
            cache[case, kind] = export(case, kind, str(folder / ("%s_%s.fmu" % (case, kind))))
        return cache[case, kind]
    return get


@pytest.mark.parametrize("kind", ["me", "cs"])
@pytest.mark.parametrize("case", list(CASES))
def test_fmu_validates_and_matches_acausal2d(fmus, case, kind):
    fmu = fmus(case, kind)
    assert validate_fmu(fmu) == []
    with zipfile.ZipFile(fmu) as z:
        names = z.namelist()
    assert any(n.startswith("binaries/linux64/") and n.endswith(".so") for n in names)
    assert "sources/a2d_casadi.c" in names and "sources/a2d_core.c" in names
    res, grid, outputs = reference(case)
    r = fmu_run(fmu, kind, case)
    errs = max_relative_errors(res, grid, outputs, r)
    assert max(errs.values()) < 1e-4, errs


def _clutch_switches(times, w_rel, w_s=0.01):
    """(lock, unlock): the first time after 0.35 s that |w_rel| <= w_s and
    the first after 1 s that it exceeds w_s again."""
    slip = np.abs(w_rel) > w_s * (1 + 1e-9)
    lock = times[(times > 0.35) & ~slip][0]
    unlock = times[(times > 1.0) & slip][0]
    return lock, unlock


@pytest.mark.parametrize("kind", ["me", "cs"])
def test_clutch_lock_and_unlock_times(fmus, kind):
    res, grid, _ = reference("clutch")
    ev = [t for t, text in res.events if "clutch.w_rel" in text]
    lock_ref = min(t for t in ev if t > 0.35)
    unlock_ref = min(t for t in ev if t > 1.0)
    assert 0.4 < lock_ref < 0.45 and 1.0 < unlock_ref < 1.05
    r = fmu_run(fmus("clutch", kind), kind, "clutch")
    lock, unlock = _clutch_switches(r["time"], r["clutch.w_rel"])
    assert abs(lock - lock_ref) <= STEP
    assert abs(unlock - unlock_ref) <= STEP
    if kind == "me":   # FMPy records the FMU's events (two rows at one time)
        t = r["time"]
        events = t[1:][np.diff(t) == 0]
        for ref in (lock_ref, unlock_ref):
            assert np.min(np.abs(events - ref)) < 1e-4


def test_parameter_set_before_initialization_acts_as_set(fmus):
    fmu = fmus("pendulum", "me")
    base, grid, outputs = reference("pendulum")
    res, _, _ = reference("pendulum", {"rod.r": (0.5, 0.0)})
    r = fmu_run(fmu, "me", "pendulum", {"rod.r[0]": 0.5})
    assert np.max(np.abs(res["revolute.w"] - base["revolute.w"])) > 1.0   # really changed
    errs = max_relative_errors(res, grid, outputs, r)
    assert max(errs.values()) < 1e-4, errs


def test_model_exchange_binary_runs_without_python(fmus, tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        pytest.skip("no C compiler")
    fmu = fmus("pendulum", "me")
    with zipfile.ZipFile(fmu) as z:
        z.extractall(tmp_path)
    md = ET.parse(tmp_path / "modelDescription.xml").getroot()
    vr = {v.get("name"): v.get("valueReference") for v in md.iter("ScalarVariable")}
    nx = len(md.find("ModelStructure").find("Derivatives"))
    driver = str(tmp_path / "driver")
    subprocess.run([cc, "-O2", "-o", driver, os.path.join(ROOT, "tests/data/fmu/me_driver.c"),
                    "-I", str(tmp_path / "sources"), "-ldl"], check=True)
    # the shipped binary, and one rebuilt from sources/ alone (another platform's way)
    rebuilt = str(tmp_path / "rebuilt.so")
    src = tmp_path / "sources"
    subprocess.run([cc, "-shared", "-fPIC", "-O2", "-o", rebuilt]
                   + sorted(str(f) for f in src.glob("*.c")) + ["-lm"], check=True)
    res, _, _ = reference("pendulum")
    for so in (str(tmp_path / "binaries/linux64/Pendulum.so"), rebuilt):
        out = subprocess.run([driver, so, md.get("guid"), "1.0", "1e-4", vr["body.phi"],
                              str(nx)], env={}, capture_output=True, text=True, timeout=120)
        assert out.returncode == 0, out.stderr
        t, phi = map(float, out.stdout.split())
        assert t == pytest.approx(1.0)
        assert phi == pytest.approx(res.at("body.phi", 1.0), abs=1e-7)


def test_dynamic_state_selection_is_refused(tmp_path, capsys):
    model = acausal2d.load_model(os.path.join(ROOT, "models/piston_engine_dynamic.py"))
    with pytest.raises(DynamicStateSelectionError, match="state_select='always'"):
        export_fmu(model, "me", str(tmp_path / "x.fmu"))
    code = main(["export-fmu", os.path.join(ROOT, "models/piston_engine_dynamic.py"),
                 "--out", str(tmp_path / "y.fmu")])
    assert code == 2
    err = capsys.readouterr().err
    assert "dynamic state selection" in err and "--fixed-states" in err
    assert not os.path.exists(tmp_path / "y.fmu")


def test_two_fmus_in_one_process_keep_their_own_code(fmus, tmp_path):
    """Only the fmi2 functions are exported, so two acausal2d FMUs loaded
    with RTLD_GLOBAL do not resolve each other's generated functions."""
    import ctypes
    libs = []
    for case in ("pendulum", "fourbar"):
        with zipfile.ZipFile(fmus(case, "me")) as z:
            z.extractall(tmp_path / case)
        so = next((tmp_path / case / "binaries/linux64").glob("*.so"))
        libs.append(ctypes.CDLL(str(so), mode=ctypes.RTLD_GLOBAL))
    for lib in libs:
        assert hasattr(lib, "fmi2Instantiate")
        assert not hasattr(lib, "a2d_fE") and not hasattr(lib, "a2d_newton")
    res, grid, outputs = reference("pendulum")
    errs = max_relative_errors(res, grid, outputs, fmu_run(fmus("pendulum", "me"), "me",
                                                            "pendulum"))
    assert max(errs.values()) < 1e-4


def test_cli_export(tmp_path, capsys):
    out = str(tmp_path / "p.fmu")
    assert main(["export-fmu", os.path.join(ROOT, "models/pendulum.py"), "--kind", "cs",
                 "--out", out]) == 0
    assert "Co-Simulation FMU" in capsys.readouterr().out
    assert validate_fmu(out) == []


def test_missing_compiler_is_named(tmp_path, monkeypatch, capsys):
    from acausal2d.runtime import cbuild
    monkeypatch.setattr(cbuild, "find_compiler", lambda: None)
    monkeypatch.setenv("ACAUSAL2D_CACHE_DIR", str(tmp_path / "cache"))
    code = main(["export-fmu", os.path.join(ROOT, "models/pendulum.py"),
                 "--out", str(tmp_path / "p.fmu")])
    assert code == 2
    assert "No C compiler found" in capsys.readouterr().err
    assert not os.path.exists(tmp_path / "p.fmu")


def test_benchmark_small_mode_prints_its_table(capsys):
    bench_fmu.main(small=True)
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].split() == ["model", "kind", "export", "s", "fmpy", "s", "acausal2d", "s",
                                "max", "rel", "dev"]
    rows = [line.split() for line in lines[1:]]
    assert [r[:2] for r in rows] == [["pendulum", "me"], ["pendulum", "cs"]]
    assert all(float(r[-1]) < 1e-4 for r in rows)


class _SineDrivenFourBar(acausal2d.Component):
    """The four-bar with tau(t) = 0.2 + 0.1 sin(2 pi t) from a Sine source."""
    outputs = ["bar.crank.phiL", "bar.dyad.phiL2"]

    def __init__(self, **kw):
        from acausal2d.library.signals import Sine
        super().__init__(**kw)
        self.bar = load("fourbar")
        self.sine = Sine(amplitude=0.1, f=1.0, offset=0.2)
        self.connect(self.sine.y, self.bar.tau)


def _run_with_input(fmu, tmp_path, name, tau, stop, grid):
    """Integrate the ME FMU through FMPy's low-level API with SciPy (Radau,
    rtol 1e-10), the input set at every right-hand-side evaluation (FMPy's
    simulate_fmu holds inputs over an output interval)."""
    from ctypes import POINTER, c_double
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Model
    from scipy.integrate import solve_ivp
    folder = extract(fmu, str(tmp_path / "x"))
    md = read_model_description(folder)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    m = FMU2Model(guid=md.guid, unzipDirectory=folder,
                  modelIdentifier=md.modelExchange.modelIdentifier, instanceName="t")
    m.instantiate()
    m.setupExperiment(startTime=0.0)
    m.setReal([vr["tau"]], [tau(0.0)])
    m.enterInitializationMode()
    m.exitInitializationMode()
    m.newDiscreteStates()
    m.enterContinuousTimeMode()
    nx = len(md.derivatives)
    x0, xs, dx = np.zeros(nx), np.zeros(nx), np.zeros(nx)
    m.getContinuousStates(x0.ctypes.data_as(POINTER(c_double)), nx)

    def rhs(t, x):
        m.setTime(t)
        m.setReal([vr["tau"]], [tau(t)])
        xs[:] = x
        m.setContinuousStates(xs.ctypes.data_as(POINTER(c_double)), nx)
        m.getDerivatives(dx.ctypes.data_as(POINTER(c_double)), nx)
        return dx.copy()
    sol = solve_ivp(rhs, (0.0, stop), x0, method="Radau", rtol=1e-10, atol=1e-12, t_eval=grid)
    out = []
    for t, x in zip(sol.t, sol.y.T):
        rhs(t, x)
        out.append(m.getReal([vr[name]])[0])
    m.terminate()
    m.freeInstance()
    return np.array(out)


def test_time_varying_input_drives_the_model_exchange_fmu(fmus, tmp_path):
    stop = CASES["fourbar"][2]
    grid = np.linspace(0.0, stop, 201)
    res = acausal2d.compile_model(_SineDrivenFourBar()).simulate(rtol=1e-10, output_times=grid)
    const, _, _ = reference("fourbar")
    for name in ("crank.phiL", "dyad.phiL2"):
        got = _run_with_input(fmus("fourbar", "me"), tmp_path / name, name,
                              lambda t: 0.2 + 0.1 * np.sin(2 * np.pi * t), stop, grid)
        ref = res["bar." + name]
        assert np.max(np.abs(got - ref)) < 1e-6 * np.ptp(ref)
        assert np.max(np.abs(const[name][::10] - ref)) > 1e-2 * np.ptp(ref)   # input mattered


@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("kind", ["me", "cs"])
def test_singular_position_stops_the_fmu_with_a_named_element(tmp_path, kind):
    """A coupler of 0.05 m lets the four-bar assemble at the start but not
    turn through: acausal2d passes the singular position (the crank turns
    back); the FMU (Model Exchange and Co-Simulation) stops there with an
    error naming the elements, whether its Newton iteration fails there or
    an integrator step reaches it: the determinant of the equations with the
    states held changes sign between two accepted steps, has a deep minimum
    (below 1e-3 of its largest, the runtime's criterion) or is zero within
    rounding.
    The coupler's length is read while compiling (its centre of gravity is
    derived from it), so it is a constant of the FMU: the FMU is exported
    with it (``params``), as the run compared is compiled with it."""
    model = load("fourbar")
    model, names = acausal2d.fmu.bind_inputs(model, {"tau": 0.2})
    cm = acausal2d.compile_model(model)
    assert cm.is_structural("dyad.lL1")
    short = {"dyad.lL1": 0.05}
    res = cm.simulate(params=short, stop_time=0.6)
    t_sing = res.singularities[0]["time"]
    fmu = export_fmu(load("fourbar"), kind, str(tmp_path / "short.fmu"), inputs={"tau": 0.2},
                     params=short)
    messages = []
    try:   # FMPy raises, or (inside its CVode callback) only prints the error
        fmpy.simulate_fmu(fmu, stop_time=0.6, start_values={"tau": 0.2},
                          logger=lambda *a: messages.append(a[-1].decode()))
    except Exception as exc:    # FMPy's own wording; the FMU's message is in the log
        # where CVode meets the singular position first: the right-hand side,
        # a Jacobian evaluation (setup) or a Newton iteration (corrector)
        assert any(w in str(exc) for w in ("fmi2GetDerivatives", "right-hand side",
                                           "setup routine failed", "corrector convergence",
                                           "fmi2CompletedIntegratorStep", "fmi2DoStep"))
    assert names == {"tau": "tau_source.k"}
    text = " ".join(messages)
    assert "DDD 'dyad'" in text and "singular position" in text
    t_fail = float(text.split("t = ")[1].split()[0])
    assert abs(t_fail - t_sing) < 1e-3


def test_fmpy_rebuilds_the_binary_from_the_listed_sources(fmus, tmp_path):
    """modelDescription.xml lists sources/*.c; FMPy's CMake build of them
    alone gives a binary that runs the clutch model as the shipped one."""
    if shutil.which("cmake") is None:
        pytest.skip("no cmake")
    # fmpy.build exists from FMPy 0.3.26 on, which needs numpy >= 2.1.3: at
    # the floors (fmpy 0.3.0 with numpy 1.24, tests/data/floors.txt) it is absent
    build_platform_binary = pytest.importorskip(
        "fmpy.build", reason="FMPy < 0.3.26 has no fmpy.build").build_platform_binary
    with zipfile.ZipFile(fmus("clutch", "me")) as z:
        z.extractall(tmp_path)
    md = ET.parse(tmp_path / "modelDescription.xml").getroot()
    listed = sorted(f.get("name") for f in md.iter("File"))
    assert listed == sorted(f.name for f in (tmp_path / "sources").glob("*.c"))
    shutil.rmtree(tmp_path / "binaries")
    build = tmp_path.parent / (tmp_path.name + "-cmake")
    build.mkdir()
    build_platform_binary(str(tmp_path), build_dir=str(build))
    res, grid, outputs = reference("clutch")
    errs = max_relative_errors(res, grid, outputs, fmu_run(str(tmp_path), "me", "clutch"))
    assert max(errs.values()) < 1e-4, errs


@pytest.mark.slow
@pytest.mark.filterwarnings("ignore::pytest.PytestUnraisableExceptionWarning")
@pytest.mark.parametrize("ulps", [-3, 3])
def test_singular_position_decision_does_not_move_with_a_few_ulps(tmp_path, ulps):
    """The FMU's singular-position check decides on the sign and size of a
    determinant; the coupler's length moved by a few ulps stops the FMU at
    the same time (to the 1 ms of its steps) with an error naming the dyad
    (tests/test_decision_robustness.py for the runtime's own decisions; the
    four-bars of test_fmu_validates_and_matches_acausal2d run through their
    2 s without the check firing)."""
    length = float(np.nextafter(0.05, 1.0 if ulps > 0 else 0.0))
    for _ in range(abs(ulps) - 1):
        length = float(np.nextafter(length, 1.0 if ulps > 0 else 0.0))
    assert 0 < abs(length - 0.05) <= 3 * np.spacing(0.05)
    fmu = export_fmu(load("fourbar"), "me", str(tmp_path / "short.fmu"), inputs={"tau": 0.2},
                     params={"dyad.lL1": length})
    messages = []
    with pytest.raises(Exception):
        fmpy.simulate_fmu(fmu, stop_time=0.6, start_values={"tau": 0.2},
                          logger=lambda *a: messages.append(a[-1].decode()))
    text = " ".join(messages)
    # the same outcome, whichever check meets it first (Newton at a right-hand
    # side, or the determinant after a step): an error at the position naming the dyad
    assert "singular position" in text and "DDD 'dyad'" in text
    assert abs(float(text.split("t = ")[1].split()[0]) - 0.4058329) < 1e-3
