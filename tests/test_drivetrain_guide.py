"""The example of docs/guide/drive-train.md runs as printed and reaches
the steady state the page states: the drum at its 10 rad/s set point, the
motor torque the brake's sliding torque 60 N m divided by the reductions
4 * (1 + 2).

The PI loop is linear while the limiter is off: J s^2 + R k s + R k / Ti
with the drum-side inertia J = 20 + 0.05 R^2 and R = 12; at t = 5 s the
deviation left from the brake's disturbance at 1.5 s is below its scale
(the set point) times exp(-p (5 - 1.5)), p the slower pole, given ten
times room."""
import os
import re

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def test_guide_example_runs_and_settles(capsys):
    with open(os.path.join(ROOT, "docs", "guide", "drive-train.md"), encoding="utf-8") as fh:
        code = re.findall(r"```python\n(.*?)```", fh.read(), re.S)[0]
    exec(compile(code, "drive-train.md", "exec"), {"__name__": "guide"})
    out = capsys.readouterr().out
    speed, torque = (float(x) for x in re.findall(r"([-\d.]+) (?:rad/s|N m)", out))
    R, k, Ti = 12.0, 20.0, 0.5
    J = 20.0 + 0.05 * R ** 2
    p = float(np.min(np.abs(np.roots([J, R * k, R * k / Ti]).real)))
    bound = 10 * 10.0 * np.exp(-p * (5.0 - 1.5))
    assert abs(speed - 10.0) <= bound + 5e-5                      # + the printed rounding
    assert abs(torque - 60.0 / R) <= k * (1 + 1 / (Ti * p)) * bound + 5e-4
