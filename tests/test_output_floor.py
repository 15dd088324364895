"""The output path at the floor: a run whose standard error is not a
terminal shows no bar, so it imports no tqdm and its IDA calls no
progress function (on the Python path: none per step; natively: none per
output row)."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = textwrap.dedent("""
    import json, sys
    import acausal2d
    from acausal2d.runtime import ida
    made = []
    real = ida.Problem.__init__
    def init(self, form, p, d, progress=None):
        made.append(progress is not None)
        real(self, form, p, d, progress)
    ida.Problem.__init__ = init
    acausal2d.simulate(sys.argv[1], stop_time=0.5, intervals=50)
    print(json.dumps({"tqdm": "tqdm" in sys.modules, "hooks": made}))
""")


@pytest.mark.parametrize("native", ["off", "now"])
def test_no_bar_no_tqdm_and_no_progress_function(tmp_path, native):
    env = dict(os.environ, ACAUSAL2D_CACHE_DIR=str(tmp_path), ACAUSAL2D_NATIVE=native,
               PYTHONPATH=os.pathsep.join([ROOT] + [p for p in [os.environ.get("PYTHONPATH")]
                                                     if p]))
    proc = subprocess.run([sys.executable, "-c", SCRIPT, os.path.join(ROOT, "models",
                                                                      "pendulum.py")],
                          env=env, capture_output=True, text=True, timeout=600, cwd=str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    assert out["tqdm"] is False
    assert out["hooks"] and not any(out["hooks"])
