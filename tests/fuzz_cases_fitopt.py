"""Fuzz classes of issue 29 (Seen 6 and 7): degenerate fit data and
optimisation starts on either side of a constraint, through the API and
the command line (test_fuzz.py).  Deterministic (``random.Random`` with
fixed seeds).

Each case carries, besides the fields of :mod:`fuzz_cases`, ``csv`` (the
measured data written next to the model, its path the second of the
case's paths), ``api`` (a function of the paths that calls
``acausal2d.fit``/``optimize`` and asserts the right answer, so that a
plausible wrong one fails) and ``argv`` (a function of the paths and the
output folder giving the command line).  ``codes`` are the exit codes of
the right answer: 0 a regular optimum in the data's tube, 1 a fit outside
the tube of the measured noise, 2 an input error, 3 an estimate held by
its bound."""
import math
import random
import textwrap

DECAY = textwrap.dedent('''
    from acausal2d import Component, Parameter, Variable, der


    class Decay(Component):
        """x' = -a x + c, x(0) = 1: x = c/a + (1 - c/a) exp(-a t)."""
        a = Parameter(1.0, "1/s", "rate")
        c = Parameter(0.0, "m/s", "inflow")
        x = Variable(start=1.0, fixed=True, unit="m")

        def equations(self):
            return [der(self.x) == -self.a * self.x + self.c]
''')

MSD = textwrap.dedent('''
    from acausal2d import Component, start
    from acausal2d.library import signals, translational


    class MassSpringDamper(Component):
        """m 1 kg, c 450 N/m, a step of 45 N: s -> 0.1 m."""
        experiment = {"stop_time": 1.0, "intervals": 500}

        def __init__(self, **kw):
            super().__init__(**kw)
            self.wall = translational.Fixed()
            self.spring = translational.SpringDamper(c=450.0, d=10.0)
            self.mass = translational.Mass(m=1.0, s=start(0.0, fixed=True),
                                           v=start(0.0, fixed=True))
            self.force = translational.Force()
            self.load = signals.Constant(k=45.0)
            self.connect(self.wall.flange, self.spring.flange_a)
            self.connect(self.spring.flange_b, self.mass.flange_a)
            self.connect(self.force.flange, self.mass.flange_b)
            self.connect(self.load.y, self.force.f_in)
''')

OBJECTIVE = "integral((mass.s - 0.1) ** 2)"


def _csv(t, y, nan_at=None):
    rows = ["%.17g,%s" % (a, "nan" if k == nan_at else "%.17g" % b)
            for k, (a, b) in enumerate(zip(t, y))]
    return "time,x\n" + "\n".join(rows) + "\n"


def _case(cid, model, codes, api, args, csv=None):
    return {"id": cid, "category": "fitopt", "model": model, "args": list(args),
            "params": None, "command": cid.split("-")[0], "filename": "model.py",
            "csv": None if csv is None else (csv,), "codes": codes, "kwargs": None, "api": api,
            "argv": lambda paths, out, a=tuple(args): [cid.split("-")[0], paths[0]] +
            (["--data", paths[1]] if len(paths) > 1 else []) + ["--out", out] + list(a)}


def _raises(call):
    """The API call must end in the project's error (the test catches it)."""
    def run(paths):
        call(paths)
        raise AssertionError("accepted: no error raised")
    return run


def _fit(free, check, **kw):
    def run(paths):
        import acausal2d
        fr = acausal2d.fit(paths[0], paths[1], free=free, **kw)
        check(fr)
        return fr
    return run


def _series(rng, n, a, c=0.0, sigma=0.0, scale=1.0, offset=0.0):
    t = [0.05 + 2.95 * k / (n - 1) for k in range(n)] if n > 1 else [0.5]
    y = [scale * (c / a + (1.0 - c / a) * math.exp(-a * s)) + offset + rng.gauss(0.0, sigma)
         for s in t]
    return t, y


def _within(a, sigmas):
    def check(fr):
        assert fr.success, fr.message
        assert abs(fr.estimate[0] - a) <= sigmas * fr.std[0] + 1e-5 * a, (fr.estimate, a)
    return check


def _held(name, kind):
    def check(fr):
        assert fr.at_bound == {name: kind} and not fr.success, fr.message
    return check


def _outside_tube(fr):
    assert fr.success and not fr.compare().passed, fr.message


def fit_cases(seed=29):
    """Degenerate fit data: too few points, exact data, data in the wrong
    unit (an estimate held by its bound), a NaN, a parameter given twice,
    noisy data, a time range without data, a model error beyond the noise."""
    rng = random.Random(seed)
    free = ["--free", "a=1:0.1:5", "--set", "c=0"]
    cases = []
    for k, n in enumerate((1, 2)):
        t, y = _series(rng, n, 1.5)
        extra = [] if n == 1 else ["--free", "c=0:-1:1"]
        cases.append(_case("fit-few-%d" % k, DECAY, (2,), _raises(
            lambda p, e=extra: __import__("acausal2d").fit(
                p[0], p[1], free=["a=1:0.1:5"] + e[1:], fixed={} if e else {"c": 0.0})),
            ["--free", "a=1:0.1:5"] + (extra or ["--set", "c=0"]), _csv(t, y)))
    a = rng.uniform(0.5, 3.0)
    t, y = _series(rng, 30, a)
    cases.append(_case("fit-exact-0", DECAY, (0,), _fit(["a=1:0.1:5"], _within(a, 0.0),
                                                         fixed={"c": 0.0}), free, _csv(t, y)))
    t, y = _series(rng, 30, 1.5, sigma=0.005, scale=1000.0)
    cases.append(_case("fit-units-0", DECAY, (3,), _fit(["a=1:0:5"], _held("a", "lower"),
                                                        fixed={"c": 0.0}),
                       ["--free", "a=1:0:5", "--set", "c=0"], _csv(t, y)))
    t, y = _series(rng, 30, 1.5, sigma=0.005)
    cases.append(_case("fit-nan-0", DECAY, (2,), _raises(
        lambda p: __import__("acausal2d").fit(p[0], p[1], free=["a=1:0.1:5"])), free,
        _csv(t, y, nan_at=rng.randrange(30))))
    cases.append(_case("fit-twice-0", DECAY, (2,), _raises(
        lambda p: __import__("acausal2d").fit(p[0], p[1], free=["a=1:0.1:5", "a=2:0.1:5"])),
        free + ["--free", "a=2:0.1:5"], _csv(t, y)))
    cases.append(_case("fit-range-0", DECAY, (2,), _raises(
        lambda p: __import__("acausal2d").fit(p[0], p[1], free=["a=1:0.1:5"],
                                              t_range=(7, 8))),
        free + ["--t-range", "7:8"], _csv(t, y)))
    for k in range(2):
        a = rng.uniform(0.5, 3.0)
        t, y = _series(rng, 40, a, sigma=0.005)
        cases.append(_case("fit-noisy-%d" % k, DECAY, (0,), _fit(["a=1:0.1:5"], _within(a, 4.0),
                                                                 fixed={"c": 0.0}),
                           free, _csv(t, y)))
    t, y = _series(rng, 40, 1.5, sigma=0.005, offset=0.05)
    cases.append(_case("fit-offset-0", DECAY, (1,), _fit(["a=1:0.1:5"], _outside_tube,
                                                         fixed={"c": 0.0}), free, _csv(t, y)))
    return cases


def d_star(v):
    """The damping whose step response peaks at v (0.1 < v < 0.2): zeta = b / sqrt(1 + b^2)
    with b = -ln(v / 0.1 - 1) / pi, d = 2 zeta sqrt(c m)."""
    b = -math.log(v / 0.1 - 1.0) / math.pi
    return 2.0 * math.sqrt(450.0) * b / math.sqrt(1.0 + b * b)


D_FREE = math.sqrt(450.0)
"""The unconstrained minimum of the ISE 0.01 (1 + 4 zeta^2) / (4 zeta omega_n): zeta = 1/2,
d = sqrt(c m); its peak 0.1 (1 + exp(-pi / sqrt(3))) = 0.1163: a larger v is inactive."""


def _optimum(v, d0):
    """The optimum must be the closed form's max(d*(v), D_FREE).  Constraint active: the
    sampled peak (h = 2 ms) lies up to 0.1 * 450 * overshoot * h^2 / 8 below the continuous
    one, the runs (rtol 1e-8) add 100 rtol of the peak; divided by |d peak / d d| >= 1e-4
    m s/N over 0.1005 < v < 0.125.  Inactive: a relative error e = (omega_n h)^2 / 12 of
    the trapezoidal ISE moves its flat minimum by at most sqrt(e) relative."""
    def run(paths):
        import acausal2d
        opt = acausal2d.optimize(paths[0], {"spring.d": (d0, 1.0, 100.0)},
                                 OBJECTIVE, constraints=["max(mass.s) <= %r" % v], rtol=1e-8)
        assert opt.success and opt.kkt.ok, opt.message
        if d_star(v) > D_FREE:
            tol = (45.0 * (v - 0.1) / 0.1 * 4e-6 / 8.0 + 100 * 1e-8 * v) / 1e-4
            assert opt.constraints[0]["active"]
        else:
            tol = D_FREE * math.sqrt((D_FREE * 2e-3) ** 2 / 12.0)
            assert not opt.constraints[0]["active"]
        want = max(d_star(v), D_FREE)
        assert abs(opt.optimum[0] - want) <= tol, (opt.optimum, want, tol)
        return opt
    return run


def optimize_cases(seed=7):
    """Starts on either side of the peak constraint max(mass.s) <= v of the
    mass-spring-damper (below d*: infeasible, above: feasible), a design
    parameter without bounds, an objective that is not a number."""
    rng = random.Random(seed)
    cases = []
    for k in range(4):
        v = rng.uniform(0.1005, 0.125)
        d0 = max(d_star(v), D_FREE) * (rng.uniform(0.3, 0.9) if k % 2 == 0 else
                                       rng.uniform(1.1, 2.0))
        cases.append(_case("optimize-side-%d" % k, MSD, (0,), _optimum(v, d0),
                           ["--vary", "spring.d=%r:1:100" % d0, "--objective", OBJECTIVE,
                            "--constraint", "max(mass.s) <= %r" % v, "--rtol", "1e-8"]))
    cases.append(_case("optimize-nobounds-0", MSD, (2,), _raises(
        lambda p: __import__("acausal2d").optimize(p[0], {"spring.d": 25.0}, OBJECTIVE)),
        ["--vary", "spring.d=25", "--objective", OBJECTIVE]))
    nan = "mean(mass.s) / (final(mass.v) * 0)"
    cases.append(_case("optimize-nan-0", MSD, (2,), _raises(
        lambda p: __import__("acausal2d").optimize(p[0], {"spring.d": (25.0, 1.0, 100.0)},
                                                   nan, intervals=50)),
        ["--vary", "spring.d=25:1:100", "--objective", nan, "--intervals", "50"]))
    return cases


def cases():
    """Every fit/optimize fuzz case, in a fixed order."""
    return fit_cases() + optimize_cases()
