"""Fuzz cases of issue 35 (output transactions, bounded inputs), in the
format of fuzz_cases.py (see its docstring), plus the plans of the signal
fuzz test (test_fuzz_output.py).

Deterministic: every choice is drawn from a ``random.Random`` with a fixed
seed."""
import json
import random

from fuzz_cases import _MEC2, _case, pendulum


def _nested(rng, depth):
    """A mec2 document whose ``nodes`` hold ``depth`` nested arrays or
    objects, some of them inside strings (which do not count)."""
    inner = "1"
    for _ in range(depth):
        inner = rng.choice(["[%s]", '{"k": %s}', '["[{", %s]']) % inner
    data = dict(_MEC2)
    text = json.dumps(data)
    return text[:-1] + ', "extra": %s}' % inner


def cases(seed=35, n=12):
    """mec2 files nested around the depth limit (64: deeper is refused with
    the position, shallower is an unknown field: both exit 2 without a
    traceback), plots named after many joined signals (file names bounded:
    exit 0) and --out values that are no folder."""
    rng = random.Random(seed)
    out = []
    for k in range(n):
        depth = rng.choice([10, 63, 64, 65, 200, 5000])
        out.append(_case("tx-mec2-depth-%d-%d" % (k, depth), "files", _nested(rng, depth),
                         filename="model.json", codes=(2,)))
    for k in range(4):
        names = ",".join(rng.choice(["joint.phi", "joint.w", "bob.frame_a.phi", "rod.frame_b.x"])
                         for _ in range(rng.randint(20, 60)))
        out.append(_case("tx-long-plot-%d" % k, "files", pendulum(), args=["--plot", names],
                         codes=(0,)))
    return out


def signal_plans(seed=35, n=5):
    """Plans of the signal fuzz test: (when SIGINT comes, as a fraction of
    the output phase's length, 0 to 1.2; whether a second run into the same
    --out starts; its delay in s)."""
    rng = random.Random(seed)
    return [(round(rng.uniform(0.0, 1.2), 3), rng.random() < 0.5, round(rng.uniform(0.0, 0.5), 3))
            for _ in range(n)]
