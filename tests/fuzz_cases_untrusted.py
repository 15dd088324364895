"""Fuzz cases of what a slider, a ``--set`` or a name can do (the report
"Nothing a stranger can plant, no slider that does nothing"), in the format
of fuzz_cases.py (see its docstring):

* ``untrusted-structural``: a pulley's mass (read while compiling) changed
  through ``params=`` and ``--set``: the model is compiled again, the run
  ends with exit 0;
* ``untrusted-cross``: Limiter ``uMax``/``uMin``, LimPID ``yMax``/``yMin``
  and OneWayClutch ``cgeo`` through ``params=`` and ``--set``: refused
  (exit 2) exactly where the constructor refuses them, else exit 0;
* ``untrusted-names``: components named outside Latin-1 written as .mat;
* ``untrusted-guards``: ``--out ''`` and huge ``--intervals`` (exit 2), a
  start angle far outside one turn (a warning, exit 0).

The live page's requests and the cache folders are fuzzed in
tests/test_seen_untrusted.py (they need a server or folders of other
owners, not a model file).  Deterministic: fixed seeds."""
import random

from fuzz_cases import _case, pendulum

_HANGING = """
import math
from acausal2d import Component, start
from acausal2d.library import signals
from acausal2d.library.belt import Belt, Pulley, RopeDrive, connect_band
from acausal2d.library.planar import Body, Fixed


class Model(Component):
    experiment = {"stop_time": 0.02, "intervals": 4, "rtol": 1e-8}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.body = Body(m=4.0, I=0.05, x=start(0.0, fixed=True), y=start(-1.0, fixed=True),
                         phi=start(0.0, fixed=True))
        self.p = Pulley(r=0.05, w_i=-1, m=1.0, J=1e-4)
        self.connect(self.body.frame_a, self.p.ctr2D1)
        eps0 = 5.0 * 9.81 / 2 / 1e6
        self.span1 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.span2 = Belt(c=1e6, d=1e3, eps=start(eps0, fixed=True))
        self.anchor = Fixed(r=(-0.05, 0.0))
        self.pull = RopeDrive(x0=0.05, y0=0.0, angle=math.pi / 2)
        self.sig = signals.Constant(k=0.0)
        self.connect(self.sig.y, self.pull.s_in)
        self.connect(self.anchor.frame, self.span1.ctr2D1)
        connect_band(self, self.span1, 2, self.p, 1)
        connect_band(self, self.span2, 1, self.p, 2)
        self.connect(self.span2.ctr2D2, self.pull.frame)
"""

_BLOCKS = """
from acausal2d import Component, start
from acausal2d.library import rotational as rot, signals


class Model(Component):
    experiment = {"stop_time": 0.05, "intervals": 4}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.sp = signals.Step(height=5.0, startTime=0.0)
        self.lim = signals.Limiter(uMax=1.0, uMin=-1.0)
        self.pid = signals.LimPID(controllerType="P", k=1.0, yMax=1.0, yMin=-1.0)
        self.zero = signals.Constant(k=0.0)
        self.connect(self.sp.y, self.lim.u)
        self.connect(self.sp.y, self.pid.u_s)
        self.connect(self.zero.y, self.pid.u_m)
        self.a = rot.Inertia(J=1.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.b = rot.Inertia(J=3.0, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.owc = rot.OneWayClutch(mu_pos=[[0.0, 0.5]], cgeo=1.0, fn_max=100.0)
        self.eng = signals.Constant(k=1.0)
        self.tau = signals.Constant(k=4.0)
        self.src = rot.Torque()
        self.connect(self.eng.y, self.owc.f_normalized)
        self.connect(self.a.flange_b, self.owc.flange_a)
        self.connect(self.owc.flange_b, self.b.flange_a)
        self.connect(self.tau.y, self.src.tau_in)
        self.connect(self.src.flange, self.a.flange_a)
"""

_NAMED = """
from acausal2d import Component, start
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute


class Model(Component):
    experiment = {"stop_time": 0.05, "intervals": 4}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.%(joint)s = Revolute(phi=start(0.3, fixed=True), w=start(0.0, fixed=True))
        self.%(rod)s = FixedTranslation(r=(1.0, 0.0))
        self.bob = Body(m=1.0, I=0.1)
        self.connect(self.fixed.frame, self.%(joint)s.frame_a)
        self.connect(self.%(joint)s.frame_b, self.%(rod)s.frame_a)
        self.connect(self.%(rod)s.frame_b, self.bob.frame_a)
"""

_IDENTIFIERS = ["φ_gelenk", "関節", "Gelenk_ü", "шарнир", "κ2", "ρ_stab", "관절", "مفصل", "ǅoint"]


def _structural(rng, n):
    out = []
    for k in range(n):
        m = round(rng.uniform(0.0, 5.0), 3)
        out.append(_case("untrusted-structural-api-%d" % k, "untrusted", _HANGING,
                         params={"p.m": m}, codes=(0,)))
        out.append(_case("untrusted-structural-set-%d" % k, "untrusted", _HANGING,
                         args=["--set", "p.m=%r" % m], codes=(0,)))
    return out


def _cross(rng, n):
    """Pairs on both sides of each rule; the expected code from the rule
    itself (hi >= lo; cgeo > 0), not from the code under test."""
    out = []
    for k in range(n):
        comp, hi, lo = rng.choice([("lim", "uMax", "uMin"), ("pid", "yMax", "yMin")])
        a, b = (round(rng.uniform(-3.0, 3.0), 2) for _ in range(2))
        code = (0,) if a >= b else (2,)
        settings = {"%s.%s" % (comp, hi): a, "%s.%s" % (comp, lo): b}
        out.append(_case("untrusted-cross-%s-api-%d" % (comp, k), "untrusted", _BLOCKS,
                         params=settings, codes=code))
        out.append(_case("untrusted-cross-%s-set-%d" % (comp, k), "untrusted", _BLOCKS,
                         args=sum((["--set", "%s=%r" % kv] for kv in settings.items()), []),
                         codes=code))
        cgeo = rng.choice([0.0, 0.0, 0.1, 2.0])
        code = (0,) if cgeo > 0 else (2,)
        out.append(_case("untrusted-cross-owc-set-%d" % k, "untrusted", _BLOCKS,
                         args=["--set", "owc.cgeo=%r" % cgeo], codes=code))
    return out


def _mat_round_trip(paths, joint):
    """The API's side of a names case: the run written as .mat and read
    back has the joint's angle under its name, with the run's numbers."""
    import os
    import unicodedata
    import numpy as np
    import acausal2d
    from acausal2d.io.dymola_mat import read_mat, write_mat
    res = acausal2d.simulate(acausal2d.load_model(paths[0]))
    path = os.path.join(os.path.dirname(paths[0]), "result.mat")
    write_mat(path, res.time, {n: res[n] for n in res.names})
    time, columns = read_mat(path)
    name = unicodedata.normalize("NFKC", joint) + ".phi"     # Python's own identifier form
    assert name in columns, sorted(columns)[:10]
    assert np.max(np.abs(columns[name] - res[name])) <= 1e-12 * (1 + np.max(np.abs(res[name])))
    return res


def _names(rng, n):
    out = []
    for k in range(n):
        joint, rod = rng.sample(_IDENTIFIERS, 2)
        case = _case("untrusted-names-mat-%d" % k, "untrusted",
                     _NAMED % {"joint": joint, "rod": rod}, command="simulate-mat",
                     codes=(0,))
        case["argv"] = lambda paths, out_: ["simulate", paths[0], "--result-format", "mat",
                                            "--out", out_]
        case["api"] = lambda paths, joint=joint: _mat_round_trip(paths, joint)
        out.append(case)
    return out


def _guards(rng):
    out = [_case("untrusted-out-empty", "untrusted", pendulum(), args=["--out", ""],
                 codes=(2,))]
    out[-1]["argv"] = lambda paths, out_: ["simulate", paths[0], "--out", ""]
    for k, n in enumerate(rng.sample([10 ** 9, 2 * 10 ** 9, 10 ** 12, 2 ** 62], 3)):
        out.append(_case("untrusted-intervals-%d" % k, "untrusted", pendulum(),
                         args=["--intervals", str(n)], codes=(2,)))
    for k, phi in enumerate([1e17, -3e12, 1e300]):
        out.append(_case("untrusted-far-angle-%d" % k, "untrusted", pendulum(),
                         kwargs={"start": {"joint.phi": phi}, "stop_time": 0.02}, codes=(0, 3)))
    return out


def cases(seed=43, n=4):
    """Every case of this module, in a fixed order."""
    rng = random.Random(seed)
    return _structural(rng, n) + _cross(rng, n) + _names(rng, n) + _guards(rng)
