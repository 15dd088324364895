"""A parameter the compiler reads (the hanging pulley's mass ``p.m`` decides
whether the pulley has mass) cannot change in an exported FMU: the model's
structure was decided with its value.  The FMU lists it as a local
constant with its value and says why in its description; ``fmi2SetReal``
refuses it with an error naming it (a run never goes on with a value that
changes nothing), while an ordinary parameter of the same FMU is still set
before initialization and acts as ``params``."""
import xml.etree.ElementTree as ET
import zipfile

import numpy as np
import pytest

from acausal2d.compiled import compile_model
from acausal2d.fmu import export_fmu
from acausal2d.fmu.description import STRUCTURAL
from acausal2d.io.loader import load_model
from test_seen_untrusted import HANGING

fmpy = pytest.importorskip("fmpy")
from fmpy.validation import validate_fmu  # noqa: E402

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def hanging(tmp_path_factory):
    """(the compiled hanging pulley with m = 1 kg, its Model Exchange FMU)."""
    folder = tmp_path_factory.mktemp("structural")
    source = folder / "hanging.py"
    source.write_text(HANGING % 1.0)
    model = load_model(str(source))
    cm = compile_model(model)
    fmu = str(folder / "Hanging.fmu")
    export_fmu(model, "me", fmu, fixed_states=True)    # its 0.05 s keep the states chosen
    return cm, fmu


def _variables(fmu):
    with zipfile.ZipFile(fmu) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    return {v.get("name"): v for v in root.iter("ScalarVariable")}


def test_a_structural_parameter_is_a_constant_of_the_fmu(hanging):
    cm, fmu = hanging
    assert cm.is_structural("p.m") and not cm.is_structural("body.m")
    assert validate_fmu(fmu) == []
    variables = _variables(fmu)
    m = variables["p.m"]
    assert (m.get("causality"), m.get("variability"), m.get("initial")) == \
        ("local", "constant", "exact")
    assert m.get("description").startswith(STRUCTURAL)
    assert float(m.find("Real").get("start")) == pytest.approx(1.0, rel=1e-15)
    body = variables["body.m"]
    assert (body.get("causality"), body.get("variability")) == ("parameter", "fixed")


def _instance(fmu, tmp_path, said):
    """(an instantiated FMU2Model of ``fmu`` whose log messages are appended
    to ``said``, {name: value reference}); the callbacks as fmpy's
    simulate_fmu builds them for its ``logger``."""
    from ctypes import byref
    from fmpy import calloc, extract, free, read_model_description
    from fmpy import fmi2
    from fmpy.logging import addLoggerProxy
    md = read_model_description(fmu)
    unzipped = extract(fmu, unzipdir=str(tmp_path / "unzipped"))
    inst = fmi2.FMU2Model(guid=md.guid, unzipDirectory=unzipped,
                          modelIdentifier=md.modelExchange.modelIdentifier, instanceName="h")
    callbacks = fmi2.fmi2CallbackFunctions()
    callbacks.logger = fmi2.fmi2CallbackLoggerTYPE(lambda *a: said.append(a[-1].decode()))
    callbacks.allocateMemory = fmi2.fmi2CallbackAllocateMemoryTYPE(calloc)
    callbacks.freeMemory = fmi2.fmi2CallbackFreeMemoryTYPE(free)
    addLoggerProxy(byref(callbacks))
    inst.instantiate(callbacks=callbacks, loggingOn=True)
    return inst, {v.name: v.valueReference for v in md.modelVariables}


def test_setting_it_is_an_error_naming_it(hanging, tmp_path):
    cm, fmu = hanging
    said = []
    inst, vr = _instance(fmu, tmp_path, said)
    try:
        inst.setupExperiment(startTime=0.0)
        with pytest.raises(Exception) as err:            # fmpy's FMICallException: fmi2Error
            inst.setReal([vr["p.m"]], [3.0])
        assert "fmi2SetReal" in str(err.value) or "Error" in str(err.value)
        assert any("p.m was read when the model was compiled" in m for m in said), said
        inst.setReal([vr["body.m"]], [5.0])            # an ordinary parameter: accepted
        inst.enterInitializationMode()
        inst.exitInitializationMode()
        assert inst.getReal([vr["p.m"]])[0] == pytest.approx(1.0, rel=1e-15)   # unchanged
    finally:
        inst.terminate()
        inst.freeInstance()


def test_a_run_that_asks_for_another_value_stops_instead_of_ignoring_it(hanging):
    cm, fmu = hanging
    with pytest.raises(Exception) as err:
        fmpy.simulate_fmu(fmu, stop_time=0.05, start_values={"p.m": 3.0})
    assert "p.m" in str(err.value) or "constant" in str(err.value).lower()
    # the FMU's own value runs as acausal2d does
    ref = cm.simulate()
    r = fmpy.simulate_fmu(fmu, stop_time=0.05, output=["span1.F"], output_interval=0.005,
                          relative_tolerance=1e-8)
    want = np.interp(r["time"], np.asarray(ref.time), np.asarray(ref["span1.F"]))
    scale = 1.0 + float(np.max(np.abs(want)))
    assert float(np.max(np.abs(r["span1.F"] - want))) <= 1e-4 * scale


def test_export_fmu_set_exports_another_value_compiled_again(hanging, tmp_path, capsys):
    """``export-fmu --set p.m=3``: the model compiled again with it (as a
    run with ``params`` is); the FMU's constant is 3 and its run is the
    3 kg pulley's, 2 kg x g more rope force than the exported 1 kg one."""
    from acausal2d.cli import main
    cm, fmu1 = hanging
    source = tmp_path / "hanging.py"
    source.write_text(HANGING % 1.0)
    out = str(tmp_path / "Heavy.fmu")
    code = main(["export-fmu", str(source), "--fixed-states", "--set", "p.m=3", "--out", out])
    assert code == 0, capsys.readouterr().err
    assert float(_variables(out)["p.m"].find("Real").get("start")) == pytest.approx(3.0)
    ref = cm.simulate(params={"p.m": 3.0})
    runs = {}
    for name, f in (("heavy", out), ("light", fmu1)):
        runs[name] = fmpy.simulate_fmu(f, stop_time=0.05, output=["span1.F"],
                                       output_interval=0.005, relative_tolerance=1e-8)
    r = runs["heavy"]
    want = np.interp(r["time"], np.asarray(ref.time), np.asarray(ref["span1.F"]))
    scale = 1.0 + float(np.max(np.abs(want)))
    assert float(np.max(np.abs(r["span1.F"] - want))) <= 1e-4 * scale
    assert r["span1.F"][-1] - runs["light"]["span1.F"][-1] > 1.0       # 2 kg x 9.81 / 2
