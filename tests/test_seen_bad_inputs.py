"""Each input listed under "Seen" in the bad-input report, by name: it now
ends in a right answer or in the project's error naming the culprit, with
the documented exit code and without tracebacks or LAPACK chatter.  (The
fuzz suite, test_fuzz.py, varies these inputs by the hundred; the tests here
pin the report's own cases.)"""
import csv
import os
import textwrap

import numpy as np
import pytest

import acausal2d
from acausal2d import (Component, InitializationError, ModelDefinitionError, Parameter,
                       SimulationError, StructuralError, Variable, der, start)
from acausal2d.library import rotational, translational
from acausal2d.library.belt import Belt, Pulley, connect_band
from acausal2d.library.linkage import DAN, DDD, DSD, SDS, SSD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Prismatic, Revolute
from acausal2d.cli import main

NOISE = ("Traceback", "DLASCL", "** On entry", "[IDA")
HERE = os.path.dirname(os.path.abspath(__file__))
PENDULUM = os.path.join(HERE, os.pardir, "models", "pendulum.py")


class Pendulum(Component):
    """The PlanarMechanics pendulum; parameters of the body from the caller."""
    experiment = {"stop_time": 0.5, "intervals": 10}

    def __init__(self, m=1.0, I=0.1, r=(1.0, 0.0), **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.rod = FixedTranslation(r=r)
        self.bob = Body(m=m, I=I)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.bob.frame_a)


def error_of(build, capfd=None, **simulate):
    """The project's error raised by building/simulating; no noise printed."""
    with pytest.raises(acausal2d.Acausal2dError) as err:
        acausal2d.simulate(build(), stop_time=simulate.pop("stop_time", 0.2), **simulate)
    if capfd is not None:
        out, errs = capfd.readouterr()
        assert not any(n in out + errs for n in NOISE), out + errs
    return str(err.value)


def run_cli(argv, capfd):
    code = main([str(a) for a in argv])
    out, err = capfd.readouterr()
    assert not any(n in out + err for n in NOISE), out + err
    return code, out, err


def model_file(tmp_path, body, name="model.py"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(body), encoding="utf-8")
    return path


# ------------------------------------------------ NaN, inf or None in a parameter
@pytest.mark.parametrize("value", [float("nan"), float("inf"), None])
def test_seen_nan_inf_none_in_a_parameter_api(value, capfd):
    text = error_of(lambda: Pendulum(m=value), capfd)
    # built inside Pendulum.__init__, before it has a name: the line that made it is named
    assert "Body created at test_seen_bad_inputs.py:" in text and "parameter m = " in text


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_seen_nan_inf_in_a_parameter_cli_set(value, tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--set", "body.m=" + value,
                              "--out", tmp_path], capfd)
    assert code == 2 and "body" in err and "m" in err and "finite" in err


def test_seen_nan_in_params_of_the_api(capfd):
    cm = acausal2d.compile_model(Pendulum())
    with pytest.raises(ModelDefinitionError, match="bob: parameter m = nan is not finite"):
        cm.simulate(stop_time=0.1, params={"bob.m": float("nan")})


def test_seen_nan_in_a_model_file(tmp_path, capfd):
    path = model_file(tmp_path, """
        from acausal2d import Component
        from acausal2d.library.planar import Body, Fixed
        class M(Component):
            def __init__(self, **kw):
                super().__init__(**kw)
                self.b = Body(m=float('nan'))
        """)
    code, out, err = run_cli(["simulate", path, "--out", tmp_path / "out"], capfd)
    assert code == 2 and "Body created at model.py:7: parameter m = nan is not finite" in err


def test_seen_prismatic_with_zero_direction(capfd):
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed, self.p, self.b = Fixed(), Prismatic(r=(0.0, 0.0)), Body()
            self.connect(self.fixed.frame, self.p.frame_a)
            self.connect(self.p.frame_b, self.b.frame_a)
    text = error_of(M, capfd)
    assert "Prismatic created at" in text and "parameter r = (0, 0) breaks its rule nonzero" in text


def _on_crank(make_dyad, port):
    """A speed-driven crank (0.1 m) whose pin carries the dyad's ``port``."""
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.crank = DAN(lL=0.1)
            self.preset = Preset(kind="speed", om=1.0)
            self.dyad = make_dyad()
            self.connect(self.preset.flange, self.crank.ctrR2)
            self.connect(self.crank.ctr2D2, getattr(self.dyad, port))
    return M


def test_seen_ssd_with_parallel_guides(capfd):
    text = error_of(_on_crank(lambda: SSD(phiv=0.0), "ctr2D2"), capfd)
    assert "SSD 'dyad' cannot assemble at the start: guides 1 and 2 not parallel" in text
    assert "phiv" in text


def test_seen_sds_with_parallel_guides(capfd):
    # guide 1 on the crank (angle 0 at the start), guide 2 fixed at angle 0
    text = error_of(_on_crank(lambda: SDS(phi10=0.0, x20=0.1, y20=0.5, phi20=0.0), "ctr2D1"),
                    capfd)
    assert "SDS 'dyad' cannot assemble at the start: guides 1 and 2 not parallel" in text


def test_seen_dsd_pivot_on_the_crank_pin(capfd):
    text = error_of(_on_crank(lambda: DSD(v=0.0, x10=0.1, y10=0.0), "ctr2D2"), capfd)
    assert "DSD 'dyad' cannot assemble at the start: P1 != P2" in text


def test_seen_sqrt_of_a_negative_number_names_the_equation(capfd):
    class M(Component):
        x = Variable(start=1.0, fixed=True)
        y = Variable()

        def equations(self):
            return [der(self.x) == -1.0, self.y == (self.x - 2.0) ** 0.5]
    text = error_of(M, capfd)
    assert "evaluate to inf or NaN" in text
    assert "M '<model>' equation 2: y == sqrt((x-2))   (nan)" in text


def test_seen_exp_overflow_during_the_run_names_variable_and_time(capfd):
    class M(Component):
        x = Variable(start=0.0, fixed=True)
        y = Variable()

        def equations(self):
            return [der(self.x) == 1000.0, self.y == 2.0 ** self.x]
    with pytest.raises(SimulationError) as err:
        acausal2d.simulate(M(), stop_time=2.0)
    assert "y" in str(err.value) and 0.9 < err.value.time < 1.1
    out, errs = capfd.readouterr()
    assert not any(n in out + errs for n in NOISE)


# ------------------------------------------------ non-numeric values
def test_seen_string_mass_in_the_api():
    with pytest.raises(ModelDefinitionError, match="Body created at .*parameter m = 'abc' is not "
                                                   "a number"):
        Body(m="abc")


def test_seen_tuple_mass_on_the_command_line(tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--set", "body.m=1,2", "--out", tmp_path],
                             capfd)
    assert code == 2 and "body: parameter m takes 1 value, got (1.0, 2.0)" in err


@pytest.mark.parametrize("params", [{"bob.m": None}, {"bob.m": [1, 2]}, [("bob.m", 1.0)], "m"])
def test_seen_params_none_list_or_not_a_dict(params):
    cm = acausal2d.compile_model(Pendulum())
    with pytest.raises(ModelDefinitionError):
        cm.simulate(stop_time=0.1, params=params)


# ------------------------------------------------ nothing left to solve
def test_seen_body_welded_to_ground_is_evaluated():
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed(r=(0.3, 0.4))
            self.b = Body(m=2.0)
            self.connect(self.fixed.frame, self.b.frame_a)
    res = acausal2d.simulate(M(), stop_time=1.0)
    # the ground carries the weight: fy = m g at every output point
    np.testing.assert_allclose(res["b.frame_a.fy"], 2.0 * 9.81, rtol=1e-12)
    np.testing.assert_allclose(res["b.frame_a.x"], 0.3)


def test_seen_empty_model_is_an_error_naming_it():
    class Empty(Component):
        pass
    with pytest.raises(ModelDefinitionError, match="Empty"):
        acausal2d.simulate(Empty(), stop_time=1.0)


def test_seen_lone_fixed_is_evaluated():
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed(r=(1.0, 2.0), phi=0.5)
    res = acausal2d.simulate(M(), stop_time=1.0)
    np.testing.assert_allclose(res["fixed.frame.phi"], 0.5)


def test_seen_x_equals_one_over_p_is_evaluated():
    class M(Component):
        p = Parameter(4.0)
        x = Variable()

        def equations(self):
            return [self.x == 1 / self.p]
    res = acausal2d.simulate(M(), stop_time=1.0)
    np.testing.assert_allclose(res["x"], 0.25, rtol=1e-15)


def test_seen_model_component_on_the_command_line(tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--model", "Component", "--out", tmp_path],
                             capfd)
    assert code == 2 and "Component" in err and "Pendulum" in err


# ------------------------------------------------ physically invalid values
@pytest.mark.parametrize("make, name", [
    (lambda: Body(m=-1.0), "m"), (lambda: Body(I=-0.1), "I"),
    (lambda: DAN(mL=-1.0), "mL"), (lambda: DDD(mL2=-1.0), "mL2"),
    (lambda: rotational.Spring(c=-1.0), "c"), (lambda: rotational.Spring(c=0.0), "c"),
    (lambda: translational.Spring(c=0.0), "c"), (lambda: Belt(c=0.0), "c"),
    (lambda: Belt(c=-5.0), "c"), (lambda: DAN(lL=-0.1), "lL"),
    (lambda: DDD(lL1=0.0), "lL1"), (lambda: Pulley(r=-0.05), "r"),
])
def test_seen_physically_invalid_values_are_refused(make, name):
    with pytest.raises(ModelDefinitionError, match="parameter %s = .* breaks its rule" % name):
        make()


class Overlap(Component):
    """Open belt over two pulleys whose discs overlap (0.12 m < 0.1 + 0.05 m);
    ``crossed`` winds p2 the other way (then no tangent exists either)."""

    def __init__(self, crossed=False, **kw):
        super().__init__(**kw)
        self.p1 = Pulley(r=0.1, x10=0.0, y10=0.0, J=1e-3)
        self.p2 = Pulley(r=0.05, x10=0.12, y10=0.0, J=1e-4, w_i=1 if crossed else -1)
        self.span_a, self.span_b = Belt(c=1e6), Belt(c=1e6)
        connect_band(self, self.span_a, 1, self.p1, 2)
        connect_band(self, self.span_a, 2, self.p2, 1)
        connect_band(self, self.span_b, 1, self.p2, 2)
        connect_band(self, self.span_b, 2, self.p1, 1)


@pytest.mark.parametrize("crossed", [False, True])
def test_seen_overlapping_pulleys_are_named(crossed, capfd):
    text = error_of(lambda: Overlap(crossed=crossed), capfd)
    assert "Belt 'span_a' runs from Pulley 'p1' to Pulley 'p2', which overlap" in text
    assert "0.12 m < sum of the radii 0.15 m" in text


def test_seen_nominal_zero_is_refused():
    with pytest.raises(ModelDefinitionError, match="nominal"):
        Variable(nominal=0.0)


def test_seen_rtol_ten_is_refused(tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--rtol", "10", "--out", tmp_path], capfd)
    assert code == 2 and "rtol" in err


def test_seen_output_times_with_nan_are_refused():
    with pytest.raises(acausal2d.Acausal2dError, match="output_times must be .* finite"):
        acausal2d.simulate(Pendulum(), stop_time=1.0, output_times=[0.0, float("nan")])


# ------------------------------------------------ resource hangs
@pytest.mark.parametrize("stop", ["1e7", "1e30", "1e300"])
def test_seen_huge_stop_times_are_bounded(stop, tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--stop-time", stop, "--max-steps", "2000",
                              "--out", tmp_path], capfd)
    # refused up front (the output grid would not fit) or stopped by the step budget
    assert code in (2, 3)
    assert "GB of memory" in err if code == 2 else "2000 steps" in err


@pytest.mark.parametrize("intervals", ["100000000", "2000000000"])
def test_seen_huge_interval_counts_are_refused_with_their_size(intervals, tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--intervals", intervals, "--out", tmp_path],
                             capfd)
    assert code == 2 and "GB of memory" in err and "fewer intervals" in err


def test_seen_stop_time_inf_is_refused_and_keeps_nothing_stale(tmp_path, capfd):
    out = tmp_path / "out"
    assert run_cli(["simulate", PENDULUM, "--out", out], capfd)[0] == 0
    assert (out / "result.csv").exists()
    code, _, err = run_cli(["simulate", PENDULUM, "--stop-time", "inf", "--out", out], capfd)
    assert code == 2 and "stop" in err and "finite" in err
    assert not (out / "result.csv").exists()


# ------------------------------------------------ loader and attributes
@pytest.mark.parametrize("name", ["pendulum.txt", "pendulum"])
def test_seen_model_in_a_txt_or_extensionless_file(name, tmp_path, capfd):
    path = tmp_path / name
    path.write_text(open(PENDULUM).read())
    assert run_cli(["simulate", path, "--stop-time", "0.1", "--out", tmp_path / "o"],
                   capfd)[0] == 0


def test_seen_state_select_sometimes_is_refused():
    with pytest.raises(ModelDefinitionError, match="Revolute .*state_select must be one of "
                                                   "never, avoid, default, prefer, always, not "
                                                   "'sometimes'"):
        acausal2d.compile_model(Revolute(state_select="sometimes"))


@pytest.mark.parametrize("experiment, code, message", [
    ('{"stop_time": "long"}', 2, "stop_time"),
    ('{"stop_time": 1.0}\n            outputs = 3', 2, "outputs"),
    # None is "no outputs declared": the run plots nothing and says so
    ('{"stop_time": 1.0}\n            outputs = None', 0, "declares no outputs")])
def test_seen_bad_experiment_or_outputs(experiment, code, message, tmp_path, capfd):
    path = model_file(tmp_path, """
        from acausal2d import Component
        from acausal2d.library.planar import Fixed
        class M(Component):
            experiment = %s
            def __init__(self, **kw):
                super().__init__(**kw)
                self.f = Fixed()
        """ % experiment)
    got, out, err = run_cli(["simulate", path, "--out", tmp_path / "o"], capfd)
    assert got == code and message in (err if code else out)


def test_seen_user_file_calling_sys_exit(tmp_path, capfd):
    path = model_file(tmp_path, "import sys\nsys.exit(3)\n")
    code, out, err = run_cli(["simulate", path, "--out", tmp_path / "o"], capfd)
    assert code == 2 and "model.py: the file calls sys.exit(3)" in err


def test_seen_base_model_and_subclass_without_model_option(tmp_path, capfd):
    path = model_file(tmp_path, """
        from acausal2d import Component
        from acausal2d.library.planar import Fixed
        class Base(Component):
            def __init__(self, **kw):
                super().__init__(**kw)
                self.f = Fixed()
        class Derived(Base):
            pass
        """)
    code, out, err = run_cli(["simulate", path, "--out", tmp_path / "o"], capfd)
    assert code == 2 and "Base" in err and "Derived" in err and "--model" in err


# ------------------------------------------------ compare
def _write_csv(path, header, rows):
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        w.writerows(rows)


def test_seen_compare_header_cell_over_the_csv_field_limit(tmp_path, capfd):
    ours, ref = tmp_path / "ours.csv", tmp_path / "ref.csv"
    _write_csv(ours, ["time", "x"], [[0.0, 1.0], [1.0, 2.0]])
    _write_csv(ref, ["time", "x" * 200000], [[0.0, 1.0], [1.0, 2.0]])
    code, out, err = run_cli(["compare", ours, ref], capfd)
    assert code == 2 and "no column" in err.lower() or "common" in err.lower()


def test_seen_compare_without_common_columns_names_the_map_option(tmp_path, capfd):
    ours, ref = tmp_path / "ours.csv", tmp_path / "ref.csv"
    _write_csv(ours, ["time", "x"], [[0.0, 1.0], [1.0, 2.0]])
    _write_csv(ref, ["time", "y"], [[0.0, 1.0], [1.0, 2.0]])
    code, out, err = run_cli(["compare", ours, ref], capfd)
    assert code == 2 and "no signal in common" in err and "--map REF=OURS" in err


# ------------------------------------------------ misleading messages
def test_seen_unconnected_body_is_named():
    class M(Component):
        """The pendulum with its body left unconnected."""
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed = Fixed()
            self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
            self.rod, self.loose = FixedTranslation(), Body()
            self.connect(self.fixed.frame, self.revolute.frame_a)
            self.connect(self.revolute.frame_b, self.rod.frame_a)
    with pytest.raises(StructuralError) as err:
        acausal2d.compile_model(M())
    text = str(err.value)
    assert "separate groups" in text and "Body 'loose'" in text
    assert "Unconnected connectors (probably one of them should connect the groups): " \
        "loose.frame_a, rod.frame_b" in text
    assert "Remove it." not in text


def test_seen_closed_loop_without_guesses_names_the_joints():
    class FourBar(Component):
        """A four-bar from planar basics that cannot close (links too short)."""
        def __init__(self, **kw):
            super().__init__(**kw)
            self.fixed_a, self.fixed_b = Fixed(), Fixed(r=(1.0, 0.0))
            self.j1 = Revolute(phi=start(1.0, fixed=True))
            self.j2, self.j3, self.j4 = Revolute(), Revolute(), Revolute()
            self.crank, self.coupler = FixedTranslation(r=(0.1, 0.0)), FixedTranslation(r=(0.2, 0.0))
            self.rocker = FixedTranslation(r=(0.2, 0.0))
            self.connect(self.fixed_a.frame, self.j1.frame_a)
            self.connect(self.j1.frame_b, self.crank.frame_a)
            self.connect(self.crank.frame_b, self.j2.frame_a)
            self.connect(self.j2.frame_b, self.coupler.frame_a)
            self.connect(self.coupler.frame_b, self.j3.frame_a)
            self.connect(self.j3.frame_b, self.rocker.frame_a)
            self.connect(self.rocker.frame_b, self.j4.frame_a)
            self.connect(self.j4.frame_b, self.fixed_b.frame)
    with pytest.raises(InitializationError) as err:
        acausal2d.simulate(FourBar(), stop_time=0.1)
    text = str(err.value)
    assert "position" in text and "der(" not in text.split("position")[1][:200]
    assert any(j in text for j in ("j2.phi", "j3.phi", "j4.phi"))


def test_seen_nan_in_fixed_r_names_the_parameter():
    with pytest.raises(ModelDefinitionError, match="Fixed created at .*parameter r = "
                                                   r"\(nan, 0.0\) is not finite"):
        Fixed(r=(float("nan"), 0.0))


def test_seen_unknown_set_name_lists_the_valid_ones(tmp_path, capfd):
    code, out, err = run_cli(["simulate", PENDULUM, "--set", "body.mass=2", "--out", tmp_path],
                             capfd)
    assert code == 2 and "body.mass" in err and "body.m" in err and "body.I" in err


def test_seen_run_stopped_at_a_limit_position_exits_3(tmp_path, capfd):
    path = model_file(tmp_path, """
        import math
        from acausal2d import Component
        from acausal2d.library.linkage import DAN, DDD
        from acausal2d.library.linkage.drives import Preset
        class Rocker(Component):
            experiment = {"stop_time": 1.0, "intervals": 50}
            def __init__(self, **kw):
                super().__init__(**kw)
                self.preset = Preset(kind="speed", om=2 * math.pi)
                self.crank = DAN(lL=0.3)
                self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)
                self.connect(self.preset.flange, self.crank.ctrR2)
                self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        """)
    code, out, err = run_cli(["simulate", path, "--out", tmp_path / "o"], capfd)
    assert code == 3 and "stopped early" in err and "limit" in (out + err)
    assert (tmp_path / "o" / "result.csv").exists()       # the motion up to the limit


# ------------------------------------------------ data
def test_seen_failing_run_leaves_no_previous_results(tmp_path, capfd):
    out = tmp_path / "out"
    assert run_cli(["simulate", PENDULUM, "--out", out, "--plot", "body.phi"], capfd)[0] == 0
    before = set(os.listdir(out))
    assert "result.csv" in before and "animation.html" in before
    code, _, _ = run_cli(["simulate", PENDULUM, "--set", "body.m=-1", "--out", out], capfd)
    assert code == 2
    assert not ({"result.csv", "animation.html"} | {f for f in before if f.endswith(".png")}) \
        & set(os.listdir(out))


def test_seen_other_plot_signals_leave_no_old_pngs(tmp_path, capfd):
    out = tmp_path / "out"
    assert run_cli(["simulate", PENDULUM, "--out", out, "--plot", "body.phi"], capfd)[0] == 0
    first = {f for f in os.listdir(out) if f.endswith(".png")}
    assert run_cli(["simulate", PENDULUM, "--out", out, "--plot", "revolute.w"], capfd)[0] == 0
    second = {f for f in os.listdir(out) if f.endswith(".png")}
    assert first and second and not first & second
