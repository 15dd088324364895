"""What a run imports (issue 17, item 3): compiling and simulating a model
and writing its CSV and animation page load neither ``scipy.optimize`` nor
matplotlib; scikit-sundae still finds scipy's ``group_columns`` when it is
asked for it, and ``scipy.optimize`` imported afterwards is the real one."""
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

_RUN = r"""
import sys, os, tempfile
import acausal2d
res = acausal2d.simulate(acausal2d.load_model(%r), stop_time=1.0)
with tempfile.TemporaryDirectory() as d:
    res.to_csv(os.path.join(d, "result.csv"))
    res.animate(os.path.join(d, "animation.html"), signal="revolute.w")
    print(os.path.getsize(os.path.join(d, "animation.html")) > 1000)
print(sorted(m for m in sys.modules if m.startswith(("scipy.optimize", "matplotlib"))))
print(len(res.time))
"""


def _run(code):
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout.strip().splitlines()


def test_run_and_animation_page_import_neither_scipy_optimize_nor_matplotlib():
    lines = _run(_RUN % os.path.join(ROOT, "models", "pendulum.py"))
    assert lines[0] == "True"
    assert lines[1] == "[]"
    assert int(lines[2]) > 10


def test_scipy_optimize_after_sksundae_is_the_real_module():
    lines = _run("from acausal2d.runtime.sundae import sksundae\n"
                 "import sys\n"
                 "print('scipy.optimize._numdiff' in sys.modules)\n"
                 "from scipy.optimize import least_squares\n"
                 "from scipy.optimize._numdiff import approx_derivative, group_columns\n"
                 "import sksundae._cy_ida as c\n"
                 "import numpy as np\n"
                 "print([int(k) for k in c.group_columns(np.eye(3))])\n"
                 "print(sorted(int(k) for k in c.group_columns(np.ones((3, 3)))))\n"
                 "print(least_squares(lambda x: x - 2.0, [0.0]).x[0])\n")
    assert lines[0] == "False"
    assert lines[1] == "[0, 0, 0]"       # independent columns share one group
    assert lines[2] == "[0, 1, 2]"       # a full matrix: one group per column
    assert abs(float(lines[3]) - 2.0) < 1e-8


_NATIVE_RUN = r"""
import sys
import acausal2d
from acausal2d.runtime import native
cm = acausal2d.compile_model(acausal2d.load_model(%r))
res = cm.simulate(stop_time=1.0, intervals=200)
forms = list(cm.system._formulations.values())
print(all(native.library(f) is not None for f in forms))
print(sorted(m for m in sys.modules if m.startswith(("scipy", "sksundae", "matplotlib"))))
print(len(res.time))
"""


def _native_available():
    from acausal2d.runtime import cbuild, native
    return cbuild.find_compiler() is not None and native.enabled()


def test_native_run_imports_no_scipy_no_scikit_sundae_no_matplotlib():
    """Where the native loop runs (a C compiler), compiling and simulating a
    small model (dense below SPARSE_FROM unknowns) loads neither scipy (so
    not scipy.optimize) nor scikit-sundae nor matplotlib: the Python path
    imports them when it is taken."""
    import pytest
    if not _native_available():
        pytest.skip("no C compiler or another SUNDIALS: the run takes the Python path")
    for model in ("pendulum.py", "piston_engine.py"):
        lines = _run(_NATIVE_RUN % os.path.join(ROOT, "models", model))
        assert lines[0] == "True", model
        assert lines[1] == "[]", (model, lines[1])
        assert int(lines[2]) == 201, model


def test_python_path_still_imports_scikit_sundae():
    """ACAUSAL2D_NATIVE=0: the same run goes through scikit-sundae (imported
    on that path), still without scipy.optimize."""
    code = _NATIVE_RUN % os.path.join(ROOT, "models", "piston_engine.py")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT,
                         timeout=300, env=dict(os.environ, ACAUSAL2D_NATIVE="0"))
    assert out.returncode == 0, out.stderr
    lines = out.stdout.strip().splitlines()
    assert lines[0] == "False"
    assert "sksundae" in lines[1] and "scipy.optimize" not in lines[1]
    assert int(lines[2]) == 201


_SPARSE_GRID = r"""
import sys
import numpy as np
import acausal2d
cm = acausal2d.compile_model(acausal2d.load_model(%r))
fine = cm.simulate(stop_time=10.0, rtol=1e-8, intervals=5000)
coarse = cm.simulate(output_times=[0.0, 10.0], rtol=1e-8)
print(sorted(m for m in sys.modules if m.startswith("sksundae")))
print(coarse.stats["steps"] > 500)
print(abs(coarse["revoluteDrive.phi"][-1] - fine["revoluteDrive.phi"][-1]))
"""


def test_a_used_up_step_budget_stays_on_the_native_path():
    """One output interval that takes more than MAX_STEPS (500) IDA steps
    (the piston engine's 10 s in one interval: about 1500 steps): the native
    loop reports the used-up budget as the Python path does and the run goes
    on natively (before, the whole segment was repeated through
    scikit-sundae); the end point agrees with a 5000-interval run."""
    import pytest
    if not _native_available():
        pytest.skip("no C compiler or another SUNDIALS: the run takes the Python path")
    lines = _run(_SPARSE_GRID % os.path.join(ROOT, "models", "piston_engine.py"))
    assert lines[0] == "[]"
    assert lines[1] == "True"
    assert float(lines[2]) < 1e-5
