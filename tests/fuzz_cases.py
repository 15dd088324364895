"""Generators of malformed and borderline inputs for the fuzz suite
(test_fuzz.py): model files, parameter values, command lines and CSV files in
seven categories - structure, connections, parameters, impossible geometry,
numerics, files, compare inputs.  Deterministic: each category draws from a
``random.Random`` with a fixed seed, so CI sees the same cases every run.

A case is a dict: ``id``, ``category``, ``model`` (source text of a model
file, or None), ``filename``, ``args`` (extra command-line arguments of
``simulate``), ``params`` (the API's params=, or None), ``command``
('simulate', 'check' or 'compare') and for compare ``csv`` (the two files'
texts); ``codes`` the exit codes the case may end with when only some are
right (e.g. (1,) for a reference signal the result lacks: never 0 -- no
silent acceptance), ``kwargs`` further arguments of the API's simulate
(API-only cases).
"""
import math
import random
import textwrap

import fuzz_cases_friction
import fuzz_cases_geometry

HEADER = textwrap.dedent("""
    import math
    import acausal2d
    from acausal2d import Component, Parameter, Variable, der, start, time
    from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute
    from acausal2d.library import rotational, translational, signals
""")

VALUES = ["float('nan')", "float('inf')", "-float('inf')", "None", "'abc'", "[1, 2]", "(1,)",
          "-1.0", "0.0", "1e308", "-1e-300", "True", "{}", "(0.0, 0.0)", "1e-320", "3"]

PARAMS = [("Body", "m"), ("Body", "I"), ("FixedTranslation", "r"), ("Prismatic", "r"),
          ("Fixed", "r"), ("Fixed", "phi")]

SET_VALUES = ["nan", "inf", "-1", "0", "abc", "1,2", "1,2,3", "", "1e400", "0,0", "None", "-0"]


def _model(body, cls="Model", extra=""):
    return HEADER + extra + "\n\nclass %s(Component):\n    experiment = {'stop_time': 0.2, " \
        "'intervals': 20}\n\n    def __init__(self, **kw):\n        super().__init__(**kw)\n%s\n" \
        % (cls, textwrap.indent(textwrap.dedent(body).strip("\n"), " " * 8))


def _case(cid, category, model=None, args=(), params=None, command="simulate",
          filename="model.py", csv=None, codes=None, kwargs=None):
    return {"id": cid, "category": category, "model": model, "args": list(args),
            "params": params, "command": command, "filename": filename, "csv": csv,
            "codes": codes, "kwargs": kwargs}


# ------------------------------------------------------------------ structure
_PARTS = {"fixed": "Fixed()", "body": "Body(m=1.0, I=0.1)", "rod": "FixedTranslation(r=(0.5, 0.0))",
          "joint": "Revolute()", "slide": "Prismatic(r=(1.0, 0.0))"}
_FRAMES = {"fixed": ["frame"], "body": ["frame_a"], "rod": ["frame_a", "frame_b"],
           "joint": ["frame_a", "frame_b"], "slide": ["frame_a", "frame_b"]}


def structure_cases(n=60, seed=1):
    """Random planar models: 1-5 parts, random connections (missing,
    doubled, into loops)."""
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        names = ["%s%d" % (rng.choice(list(_PARTS)), i) for i in range(rng.randint(1, 5))]
        lines = ["self.%s = %s" % (nm, _PARTS[nm.rstrip("0123456789")]) for nm in names]
        ports = ["self.%s.%s" % (nm, f) for nm in names for f in _FRAMES[nm.rstrip("0123456789")]]
        for _ in range(rng.randint(0, len(ports))):
            a, b = rng.choice(ports), rng.choice(ports)
            lines.append("self.connect(%s, %s)" % (a, b))
        cases.append(_case("structure-%d" % k, "structure", _model("\n".join(lines))))
    return cases


# ------------------------------------------------------------------ connections
def connection_cases():
    """Connections that cannot be made, and odd but legal ones."""
    bodies = {
        "kinds": "self.b = Body()\nself.s = rotational.Inertia()\nself.connect(self.b.frame_a, "
                 "self.s.flange_a)",
        "self": "self.b = Body()\nself.connect(self.b.frame_a, self.b.frame_a)",
        "not-connector": "self.b = Body()\nself.connect(self.b, self.b.frame_a)",
        "number": "self.b = Body()\nself.connect(self.b.frame_a, 3)",
        "foreign": "self.b = Body()\nother = Body()\nself.connect(self.b.frame_a, other.frame_a)",
        "two-sources": "self.a = signals.Constant(k=1.0)\nself.b = signals.Constant(k=2.0)\n"
                       "self.p = rotational.Position()\nself.i = rotational.Inertia()\n"
                       "self.connect(self.a.y, self.p.phi_in)\nself.connect(self.b.y, self.p.phi_in)"
                       "\nself.connect(self.p.flange, self.i.flange_a)",
        "no-source": "self.p = rotational.Position()\nself.i = rotational.Inertia()\n"
                     "self.connect(self.p.flange, self.i.flange_a)",
        "reused": "b = Body()\nself.b1 = b\nself.b2 = b",
        "loop-potential": "self.f1 = Fixed()\nself.f2 = Fixed(r=(1.0, 0.0))\n"
                          "self.connect(self.f1.frame, self.f2.frame)",
        "triple-ground": "self.f1 = Fixed()\nself.f2 = Fixed()\nself.f3 = Fixed()\n"
                         "self.connect(self.f1.frame, self.f2.frame)\n"
                         "self.connect(self.f2.frame, self.f3.frame)",
        "param-assign": "self.b = Body()\nself.m = 3.0",
        "bad-start": "self.j = Revolute(phi='up')\nself.f = Fixed()\nself.connect(self.f.frame, "
                     "self.j.frame_a)",
        "state-select": "self.j = Revolute(state_select='sometimes')\nself.f = Fixed()\n"
                        "self.connect(self.f.frame, self.j.frame_a)",
        "nominal": "self.x = Variable(nominal=0.0)",
        "unknown-kw": "self.b = Body(mass=2.0)",
        "start-nan": "self.b = Body(x=start(float('nan')))",
    }
    cases = [_case("connection-%s" % name, "connections", _model(body))
             for name, body in bodies.items()]
    # the same through a sub-model
    for name, body in list(bodies.items())[:10]:
        sub = "class Sub(Component):\n    def __init__(self, **kw):\n        super().__init__(**kw)\n" \
              + textwrap.indent(body, " " * 8) + "\n"
        cases.append(_case("connection-sub-%s" % name, "connections",
                           _model("self.sub = Sub()", extra=sub)))
    return cases


# ------------------------------------------------------------------ parameters
_PENDULUM = """
self.fixed = Fixed(r=%(r)s)
self.joint = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
self.rod = FixedTranslation(r=%(rod)s)
self.bob = Body(m=%(m)s, I=%(I)s)
self.connect(self.fixed.frame, self.joint.frame_a)
self.connect(self.joint.frame_b, self.rod.frame_a)
self.connect(self.rod.frame_b, self.bob.frame_a)
"""


def pendulum(r="(0.0, 0.0)", rod="(1.0, 0.0)", m="1.0", I="0.1"):
    """Source of a pendulum model with the given parameter expressions."""
    return _model(_PENDULUM % {"r": r, "rod": rod, "m": m, "I": I})


def parameter_cases(seed=2):
    """Bad parameter values in the model file, through --set and params=."""
    rng = random.Random(seed)
    cases = []
    for k, value in enumerate(VALUES):
        for field in ("m", "I", "rod", "r"):
            cases.append(_case("param-file-%s-%d" % (field, k), "parameters",
                               pendulum(**{field: value})))
    good = pendulum()
    for k, value in enumerate(SET_VALUES):
        for name in ("bob.m", "rod.r", "fixed.phi", "bob.mass", "nothing"):
            cases.append(_case("param-set-%s-%d" % (name, k), "parameters", good,
                               args=["--set", "%s=%s" % (name, value)]))
    api_values = [float("nan"), None, "abc", [1.0, 2.0], -1.0, (1.0,), {"a": 1}, 1e400]
    for k, value in enumerate(api_values):
        for name in ("bob.m", "rod.r", "rod.r[0]", "joint.phi"):
            cases.append(_case("param-api-%s-%d" % (name, k), "parameters", good,
                               params={name: value}))
    for k in range(10):
        cases.append(_case("param-api-notdict-%d" % k, "parameters", good,
                           params=rng.choice([[("bob.m", 2.0)], "bob.m=2", 3, (1, 2)])))
    return cases


# ------------------------------------------------------------------ geometry
_FOURBAR = """
self.ga = Fixed()
self.gd = Fixed(r=(%(d)r, 0.0))
self.ja = Revolute(phi=start(%(phi)r, fixed=True), w=start(%(w)r, fixed=True))
self.crank = FixedTranslation(r=(%(a)r, 0.0))
self.jb = Revolute()
self.coupler = FixedTranslation(r=(%(b)r, 0.0))
self.jc = Revolute()
self.rocker = FixedTranslation(r=(%(c)r, 0.0))
self.jd = Revolute()
self.mass = Body(m=1.0, I=0.01)
self.connect(self.ga.frame, self.ja.frame_a)
self.connect(self.ja.frame_b, self.crank.frame_a)
self.connect(self.crank.frame_b, self.jb.frame_a)
self.connect(self.jb.frame_b, self.coupler.frame_a)
self.connect(self.coupler.frame_b, self.jc.frame_a)
self.connect(self.jc.frame_b, self.rocker.frame_a)
self.connect(self.rocker.frame_b, self.jd.frame_b)
self.connect(self.gd.frame, self.jd.frame_a)
self.connect(self.crank.frame_b, self.mass.frame_a)
"""


def fourbar(a, b, c, d, phi=1.0, w=0.0):
    """Source of a four-bar of revolute joints (crank a, coupler b, rocker
    c, ground d) started at crank angle phi."""
    return _model(_FOURBAR % dict(a=a, b=b, c=c, d=d, phi=phi, w=w), cls="FourBar")


def geometry_cases(n=50, seed=3):
    """Four-bars with random (often impossible) link lengths; a slider on a
    zero guide; a Prismatic driven past its guide."""
    rng = random.Random(seed)
    cases = []
    for k in range(n):
        dims = [round(rng.choice([rng.uniform(0.05, 2.0), rng.uniform(0.0, 0.01)]), 4)
                for _ in range(4)]
        phi = round(rng.uniform(-math.pi, math.pi), 3)
        cases.append(_case("geometry-%d" % k, "geometry",
                           fourbar(*dims, phi=phi, w=round(rng.uniform(-5, 5), 2)),
                           args=["--model", "FourBar"]))
    return cases


# ------------------------------------------------------------------ numerics
_EXPRS = ["acausal2d.sqrt(self.x - %s)", "acausal2d.log(self.x - %s)", "1 / (self.x - %s)",
          "acausal2d.exp(%s * self.x)", "acausal2d.sign(self.x - %s)",
          "acausal2d.if_else(self.x < %s, 1.0, -1.0)", "self.x ** %s", "acausal2d.tan(%s * self.x)",
          "acausal2d.asin(self.x * %s)", "acausal2d.fmax(self.x, %s) - self.x"]


def numeric_cases(seed=4):
    """x' = f(x) with f running into NaN, inf, sliding modes, stiffness."""
    rng = random.Random(seed)
    cases = []
    for k, expr in enumerate(_EXPRS):
        for j in range(5):
            c = rng.choice(["0.0", "0.5", "1.0", "2.0", "1000.0", "-1.0"])
            x0 = rng.choice([0.0, 0.5, 1.0, 3.0])
            body = "self.add_variable('x', start=%r, fixed=True)" % x0
            eqs = "\n    def equations(self):\n        return [der(self.x) == %s]\n" % (expr % c)
            src = _model(body) + eqs
            cases.append(_case("numeric-%d-%d" % (k, j), "numerics", src))
    return cases


# ------------------------------------------------------------------ files
def file_cases():
    """Model files that are not what they should be, and bad command lines."""
    good = pendulum()
    texts = {
        "empty": "", "binary": "\x00\x01\x02garbage", "syntax": "def f(:\n",
        "exit3": "import sys\nsys.exit(3)\n", "exit0": "import sys\nsys.exit(0)\n",
        "raise": "raise ValueError('model file broke')\n", "nomodel": "x = 1\n",
        "import-missing": "import not_a_module_at_all\n",
        "two-models": good + "\nclass Other(Model):\n    experiment = {'stop_time': 0.1}\n",
        "init-raises": HEADER + "\nclass Model(Component):\n    def __init__(self, **kw):\n"
                                "        raise RuntimeError('boom')\n",
        "init-exit": HEADER + "\nclass Model(Component):\n    def __init__(self, **kw):\n"
                              "        import sys; sys.exit(4)\n",
        "equations-raise": HEADER + "\nclass Model(Component):\n    x = Variable()\n"
                                    "    def equations(self):\n        return [1 / 0]\n",
        "equations-bool": HEADER + "\nclass Model(Component):\n    x = Variable()\n"
                                   "    def equations(self):\n        return [True]\n",
        "experiment-str": good.replace("'stop_time': 0.2", "'stop_time': 'long'"),
        "experiment-list": good.replace("experiment = {'stop_time': 0.2, 'intervals': 20}",
                                        "experiment = [1, 2]"),
        "outputs-none": good.replace("experiment =", "outputs = None\n    experiment ="),
        "outputs-bad": good.replace("experiment =", "outputs = ['nothing.here']\n    experiment ="),
        "base-only": HEADER + "\nclass Model(Component):\n    pass\n",
    }
    cases = [_case("file-%s" % name, "files", text) for name, text in texts.items()]
    for name in ("model.txt", "model", "my model.py", "model.PY", "m.odel.py"):
        cases.append(_case("file-name-%s" % name, "files", good, filename=name))
    cases.append(_case("file-missing", "files", None, filename="does_not_exist.py"))
    bad_args = [["--stop-time", "inf"], ["--stop-time", "-1"], ["--stop-time", "nan"],
                ["--stop-time", "abc"], ["--intervals", "0"], ["--intervals", "1e8"],
                ["--intervals", "2.5"], ["--rtol", "10"], ["--rtol", "0"], ["--rtol", "-1e-6"],
                ["--model", "Nothing"], ["--model", "Component"], ["--plot", "no.such"],
                ["--trace", "no.frame"], ["--set", "noequals"], ["--stop-time", "1e300",
                                                                "--max-steps", "2000"]]
    for k, args in enumerate(bad_args):
        cases.append(_case("file-args-%d" % k, "files", good, args=args))
    for k in range(4):
        cases.append(_case("file-check-%d" % k, "files", list(texts.values())[k], command="check"))
    return cases


# ------------------------------------------------------------------ compare
def _csv(names, rows):
    return ",".join(names) + "\n" + "\n".join(",".join(str(v) for v in r) for r in rows) + "\n"


def compare_cases(seed=5):
    """Result/reference CSV pairs that are broken in many ways."""
    rng = random.Random(seed)
    t = [i * 0.1 for i in range(11)]
    good = _csv(["time", "a"], [[x, math.sin(x)] for x in t])
    refs = {
        "empty": "", "header-only": "time,a\n", "no-time": _csv(["x", "a"], [[1, 2]]),
        "text": "time,a\n0,abc\n0.1,def\n", "nan": _csv(["time", "a"], [[0, "nan"], [1, "nan"]]),
        "decreasing": _csv(["time", "a"], [[1, 0], [0, 1]]),
        "one-row": _csv(["time", "a"], [[0, 0]]),
        "no-common": _csv(["time", "b"], [[x, 0] for x in t]),
        "huge-header": "time," + "x" * 200000 + "\n0,1\n",
        "semicolon": "time;a\n0;0\n0.1;0.1\n", "quoted": '"Time","a"\n0,0\n1,0.8414\n',
        "ragged": "time,a\n0,1,2\n0.1\n", "binary": "\x00\x01\x02",
        "dup-rows": _csv(["time", "a"], [[0, 0], [0.5, 0.4], [0.5, 0.6], [1, 0.84]]),
        "outside": _csv(["time", "a"], [[5, 0], [6, 1]]),
        "inf": _csv(["time", "a"], [[0, "inf"], [1, 0]]),
    }
    cases = []
    for name, ref in refs.items():
        cases.append(_case("compare-ref-%s" % name, "compare", command="compare", csv=(good, ref)))
        cases.append(_case("compare-res-%s" % name, "compare", command="compare", csv=(ref, good)))
    for k in range(10):
        shift = rng.choice([0.0, 1e-4, 3e-3, 0.5])
        ref = _csv(["time", "a"], [[x, math.sin(x) + shift] for x in t])
        cases.append(_case("compare-shift-%d" % k, "compare", command="compare", csv=(good, ref)))
    return cases


# ------------------------------------------------------------------ trust (issue 18)
_FIXED = HEADER + """
class Model(Component):
    experiment = {'stop_time': 0.2, 'intervals': 20}
    x = Variable()
    y = Variable()

    def __init__(self, **kw):
        super().__init__(x=start(%r, fixed=True), **kw)

    def equations(self):
        return [self.x == %s, der(self.y) == self.x - self.y]
"""
_MEC2 = {"nodes": [{"id": "A0", "x": 0, "y": 0, "base": True}, {"id": "A", "x": 50, "y": 0}],
         "constraints": [{"id": "a", "p1": "A0", "p2": "A", "len": {"type": "const"},
                          "ori": {"type": "drive", "Dt": 0.2}}]}
_VIEWS = [{"type": "vector", "p": "A", "value": "vel"}, {"as": "vector", "show": "acc", "of": "A"},
          {"type": "trace", "p": "A"}, {"as": "trace", "show": "pos", "of": "A"},
          {"type": "info", "elem": "a", "value": "w"}, {"as": "chart", "show": "wt", "of": "a"},
          {"as": "point", "show": "pos", "of": "A"}, {"as": "vector", "show": "force", "of": "A"}]
_JUNK = [("glow", 1), ("as", "hologram"), ("Dt", "long"), ("of", 3), ("type", "movie"),
         ("p", None), ("extra", {"a": [1]})]


def _mec2(data):
    import json
    return json.dumps(data)


def trust_cases(seed=6):
    """Issue 18's classes: stop times that cannot advance the clock, fixed
    starts against equations, compare with signals the result lacks or
    Modelica names, API arguments of the wrong type, mec2 views and shapes
    in both spellings and with unknown fields (load with one warning) and
    unknown fields where the motion depends on them (errors)."""
    import copy
    rng = random.Random(seed)
    good = pendulum()
    stops = ("1e-300", "1e-320", "5e-324", "1e-13", "1e-11")
    cases = [_case("trust-stop-%s" % st, "trust", good, args=["--stop-time", st], codes=(2,))
             for st in stops]
    cases += [_case("trust-stop-api-%s" % st, "trust", good, codes=(2,),
                    kwargs={"stop_time": float(st)}) for st in stops]
    for k in range(8):
        given, eq = rng.choice([1.0, 2.0, -3.5, 0.0]), rng.choice(["2.0", "2.0 + 0 * time"])
        cases.append(_case("trust-fixed-%d" % k, "trust", _FIXED % (given, eq),
                           codes=(0,) if given == 2.0 else (2,)))
    t = [i * 0.1 for i in range(11)]
    res = _csv(["time", "a", "body.x"], [[x, math.sin(x), math.cos(x)] for x in t])
    refs = {"extra-column": (_csv(["time", "a", "b"], [[x, math.sin(x), 0] for x in t]), (1,)),
            "modelica-ok": (_csv(["time", "body.r[1]"], [[x, math.cos(x)] for x in t]), (0,)),
            "modelica-off": (_csv(["time", "body.r[1]"], [[x, math.cos(x) + .5] for x in t]), (1,)),
            "modelica-unknown": (_csv(["time", "body.a[1]", "a"], [[x, 0, math.sin(x)]
                                                                    for x in t]), (1,)),
            "nan-middle": (_csv(["time", "a"], [[x, "nan" if x == 0.5 else 0] for x in t]), (2,))}
    for name, (ref, codes) in refs.items():
        cases.append(_case("trust-compare-%s" % name, "trust", command="compare", csv=(res, ref),
                           codes=codes))
    for k, kw in enumerate([{"rtol": "tight"}, {"atol": [1e-6, 1e-6]}, {"output_times": "0,1"},
                            {"progress": 3}, {"atol": "x"}, {"output_times": [[0, 1]]},
                            {"stop_time": 1e-300}, {"bogus": 1}]):
        cases.append(_case("trust-api-%d" % k, "trust", good, codes=(2,), kwargs=kw))
    for k in range(24):
        data = copy.deepcopy(_MEC2)
        data["views"] = [dict(v) for v in rng.sample(_VIEWS, rng.randint(1, 4))]
        codes = (0,)
        if k % 3 == 1:
            key, value = rng.choice(_JUNK)
            rng.choice(data["views"])[key] = value
        elif k % 3 == 2:
            target = rng.choice([data["nodes"][1], data["constraints"][0],
                                 data["constraints"][0]["ori"]])
            target["glow"] = 1
            codes = (2,)
        cases.append(_case("trust-mec2-%d" % k, "trust", _mec2(data), filename="model.json",
                           codes=codes))
    return cases


def all_cases():
    """Every fuzz case, in a fixed order."""
    import fuzz_cases_drivetrain
    import fuzz_cases_fitopt
    import fuzz_cases_hydraulics
    import fuzz_cases_pulley
    import fuzz_cases_seednums
    import fuzz_cases_tx
    import fuzz_cases_untrusted
    return (structure_cases() + connection_cases() + parameter_cases() + geometry_cases()
            + numeric_cases() + file_cases() + compare_cases() + trust_cases()
            + fuzz_cases_geometry.cases() + fuzz_cases_fitopt.cases()
            + fuzz_cases_friction.cases() + fuzz_cases_tx.cases()
            + fuzz_cases_drivetrain.cases() + fuzz_cases_hydraulics.cases()
            + fuzz_cases_pulley.cases() + fuzz_cases_seednums.cases()
            + fuzz_cases_untrusted.cases())
