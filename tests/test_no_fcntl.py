"""A simulation where ``fcntl`` is missing (Windows): the POSIX-only parts
(file locks of the native cache and of the background compile) are behind
:mod:`acausal2d.runtime.posix`, imported only where a lock is taken, so the
Python path runs with ``import fcntl`` failing.  The pendulum's motion is
checked against its energy, which the run conserves to its tolerance."""
import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PENDULUM = os.path.join(ROOT, "models", "pendulum.py")
RTOL = 1e-8
G, M, L, I_CM = 9.81, 1.0, 1.0, 0.1      # the model's gravity, mass, rod, inertia

SCRIPT = textwrap.dedent("""
    import json, sys

    class NoFcntl:                        # 'import fcntl' fails as where it does not exist
        def find_spec(self, name, path=None, target=None):
            if name == "fcntl":
                raise ImportError("No module named 'fcntl' (blocked by the test)")
            return None

    sys.meta_path.insert(0, NoFcntl())
    sys.modules.pop("fcntl", None)
    import acausal2d
    result = acausal2d.simulate(sys.argv[1], stop_time=2.0, intervals=200, rtol=%r,
                                progress=False)
    print(json.dumps({"loaded": "fcntl" in sys.modules, "phi": list(result["revolute.phi"]),
                      "w": list(result["revolute.w"])}))
""" % RTOL)


@pytest.mark.parametrize("native", ["off", "auto"])
def test_a_run_without_fcntl(tmp_path, native):
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=str(tmp_path / "cache"), ACAUSAL2D_NATIVE=native,
               PYTHONPATH=os.pathsep.join([ROOT] + [p for p in [os.environ.get("PYTHONPATH")]
                                                     if p]))
    proc = subprocess.run([sys.executable, "-c", SCRIPT, PENDULUM], env=env,
                          capture_output=True, text=True, timeout=600, cwd=str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert "Traceback" not in proc.stderr
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert not out["loaded"]
    phi, w = np.array(out["phi"]), np.array(out["w"])
    assert np.min(phi) < -1.0                      # it swung down (starts horizontal, at rest)
    # energy from rest at phi = 0: kinetic about the pivot plus potential of the body
    energy = 0.5 * (I_CM + M * L ** 2) * w ** 2 + M * G * L * np.sin(phi)
    assert np.max(np.abs(energy)) <= 1e3 * RTOL * M * G * L
