"""Linearisation and modes against closed forms (issue 21): a two-mass
spring chain, a physical pendulum, a damped oscillator, the double
pendulum's M and K, and A against a finite-difference linearisation of the
run's right-hand side (states perturbed, the nonlinear equations solved by
the runtime's Newton for every perturbation)."""
import math
import os

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.analysis.equilibrium import NoEquilibrium, find_equilibrium
from acausal2d.analysis.linearize import point_at
from acausal2d.analysis.modes import linearize, modes, modes_of
from acausal2d.errors import Acausal2dError
from acausal2d.library import rotational, translational
from acausal2d.library.planar import Body, Fixed, FixedTranslation, Revolute

G = 9.81


class TwoMassChain(Component):
    """wall -k1- m1 -k2- m2 (translational, no gravity)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.wall = translational.Fixed()
        self.k1 = translational.Spring(c=1000.0)
        self.m1 = translational.Mass(m=2.0, s=start(0.01, fixed=True), v=start(0.0, fixed=True))
        self.k2 = translational.Spring(c=400.0)
        self.m2 = translational.Mass(m=0.5, s=start(0.0, fixed=True), v=start(0.0, fixed=True))
        self.connect(self.wall.flange, self.k1.flange_a)
        self.connect(self.k1.flange_b, self.m1.flange_a)
        self.connect(self.m1.flange_b, self.k2.flange_a)
        self.connect(self.k2.flange_b, self.m2.flange_a)


class DampedOscillator(Component):
    """wall -(spring c, damper d)- mass m."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.wall = translational.Fixed()
        self.spring = translational.Spring(c=250.0)
        self.damper = translational.Damper(d=3.0)
        self.mass = translational.Mass(m=1.5, s=start(0.02, fixed=True), v=start(0.0, fixed=True))
        self.connect(self.wall.flange, self.spring.flange_a)
        self.connect(self.wall.flange, self.damper.flange_a)
        self.connect(self.spring.flange_b, self.mass.flange_a)
        self.connect(self.damper.flange_b, self.mass.flange_a)


class PhysicalPendulum(Component):
    """A body (m, I about its centre) at distance d from the pivot, started
    horizontal; ``torque``: a constant torque on the joint."""

    def __init__(self, torque=None, **kw):
        super().__init__(**kw)
        self.fixed = Fixed()
        self.revolute = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True),
                                 use_flange=torque is not None)
        self.rod = FixedTranslation(r=(0.7, 0.0))
        self.body = Body(m=2.0, I=0.05)
        self.connect(self.fixed.frame, self.revolute.frame_a)
        self.connect(self.revolute.frame_b, self.rod.frame_a)
        self.connect(self.rod.frame_b, self.body.frame_a)
        if torque is not None:
            self.drive = rotational.ConstantTorque(tau_constant=torque)
            self.connect(self.drive.flange, self.revolute.flange_a)


class Parallelogram(Component):
    """A parallelogram four-bar (ground 1, crank and rocker 0.5, coupler 1)
    started at its change point: all pivots on one line."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.ground_a = Fixed()
        self.ground_d = Fixed(r=(1.0, 0.0))
        self.ja = Revolute(phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.crank = FixedTranslation(r=(0.5, 0.0))
        self.body = Body(m=1.0, I=0.01)
        self.jb = Revolute(phi=start(0.0))
        self.coupler = FixedTranslation(r=(1.0, 0.0))
        self.jc = Revolute(phi=start(0.0))
        self.rocker = FixedTranslation(r=(-0.5, 0.0))
        self.jd = Revolute()
        self.connect(self.ground_a.frame, self.ja.frame_a)
        self.connect(self.ja.frame_b, self.crank.frame_a)
        self.connect(self.crank.frame_b, self.body.frame_a)
        self.connect(self.crank.frame_b, self.jb.frame_a)
        self.connect(self.jb.frame_b, self.coupler.frame_a)
        self.connect(self.coupler.frame_b, self.jc.frame_a)
        self.connect(self.jc.frame_b, self.rocker.frame_a)
        self.connect(self.rocker.frame_b, self.jd.frame_a)
        self.connect(self.ground_d.frame, self.jd.frame_b)

def _compiled(cls, **kw):
    return acausal2d.compile_model(cls(**kw))


def test_two_mass_chain_eigenfrequencies():
    k1, k2, m1, m2 = 1000.0, 400.0, 2.0, 0.5
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    M = np.diag([m1, m2])
    # closed form of the 2x2 eigenproblem det(K - w^2 M) = 0
    a, b, c = m1 * m2, -(m1 * k2 + m2 * (k1 + k2)), k1 * k2
    w2 = sorted([(-b - math.sqrt(b * b - 4 * a * c)) / (2 * a),
                 (-b + math.sqrt(b * b - 4 * a * c)) / (2 * a)])
    result = modes(_compiled(TwoMassChain))
    f = result.frequencies()
    assert len(f) == 2 and result.rigid_body_modes == 0
    assert np.allclose(f, np.sqrt(w2) / (2 * math.pi), rtol=1e-9, atol=0)
    assert all(abs(m["damping_ratio"]) < 1e-12 for m in result.modes)
    # shapes: the amplitude ratio s2/s1 of each mode is (k1 + k2 - w^2 m1) / k2
    for m, w2k in zip(result.modes, w2):
        s1, s2 = (complex(*m["shape"][n]) for n in ("m1.s", "m2.s"))
        assert s2 / s1 == pytest.approx((k1 + k2 - w2k * m1) / k2, rel=1e-9)
    assert np.allclose(np.linalg.eigvals(np.linalg.solve(M, K)).real.min(), w2[0])


def test_damped_oscillator_damping_ratio():
    c, d, m = 250.0, 3.0, 1.5
    result = modes(_compiled(DampedOscillator))
    (mode,) = result.modes
    wn = math.sqrt(c / m)
    zeta = d / (2 * math.sqrt(c * m))
    assert mode["damping_ratio"] == pytest.approx(zeta, rel=1e-9)
    assert mode["frequency_hz"] == pytest.approx(wn / (2 * math.pi), rel=1e-9)
    assert mode["damped_frequency_hz"] == pytest.approx(
        wn * math.sqrt(1 - zeta ** 2) / (2 * math.pi), rel=1e-9)


def test_physical_pendulum_at_lower_equilibrium():
    m, I, d = 2.0, 0.05, 0.7
    cm = _compiled(PhysicalPendulum)
    eq = find_equilibrium(cm)          # from the horizontal start, where Newton is singular
    phi = eq.point.z[cm.system.node_names.index("revolute.phi")]
    assert eq.stable and eq.residual < 1e-8
    assert phi == pytest.approx(-math.pi / 2, abs=1e-10)
    result = modes(cm, equilibrium=True)
    (mode,) = result.modes
    assert mode["frequency_hz"] * 2 * math.pi == pytest.approx(
        math.sqrt(m * G * d / (I + m * d * d)), rel=1e-9)
    assert abs(mode["damping_ratio"]) < 1e-12
    # the body swings sideways at the bottom: x moves by d per rad of phi, y not
    shape = mode["shape"]
    assert complex(*shape["body.frame_a.x"]) / complex(*shape["revolute.phi"]) == \
        pytest.approx(d, rel=1e-9)
    assert abs(complex(*shape.get("body.frame_a.y", [0, 0]))) < 1e-9


def test_equilibrium_from_a_start_away_and_none_with_too_much_torque():
    m, d = 2.0, 0.7
    cm = _compiled(PhysicalPendulum, torque=0.5 * m * G * d)
    eq = find_equilibrium(cm, start={"revolute.phi": 1.0})
    phi = eq.point.z[cm.system.node_names.index("revolute.phi")]
    # m g d cos(phi) = tau: the stable solution below the pivot, phi = -60 deg
    assert eq.stable
    assert phi == pytest.approx(-math.acos(0.5), abs=1e-10)
    with pytest.raises(NoEquilibrium, match="no equilibrium"):
        find_equilibrium(_compiled(PhysicalPendulum, torque=1.5 * m * G * d))


def _double_pendulum():
    from acausal2d.io.loader import load_model
    return acausal2d.compile_model(load_model("models/double_pendulum.py"))


def test_double_pendulum_modes_match_its_m_and_k():
    m1, I1, l1, m2, I2, l2 = 1.0, 0.1, 1.0, 0.2, 0.01, 0.4
    # absolute link angles from the vertical, linearised about the hanging position
    M = np.array([[I1 + (m1 + m2) * l1 ** 2, m2 * l1 * l2], [m2 * l1 * l2, I2 + m2 * l2 ** 2]])
    K = G * np.diag([(m1 + m2) * l1, m2 * l2])
    w2, X = np.linalg.eig(np.linalg.solve(M, K))
    order = np.argsort(w2)
    w2, X = w2[order], X[:, order]
    result = modes(_double_pendulum(), equilibrium=True)
    assert np.allclose(result.frequencies() * 2 * math.pi, np.sqrt(w2), rtol=1e-9, atol=0)
    for mode, x in zip(result.modes, X.T):
        t1, t2 = (complex(*mode["shape"][n]) for n in ("body.phi", "body1.phi"))
        assert (t2 / t1).imag == pytest.approx(0, abs=1e-9)
        assert (t2 / t1).real == pytest.approx(x[1] / x[0], rel=1e-8)


def _fd_A(cm, point, lin, h=1e-6, tol=1e-14):
    """Central differences of der(x) over the states, each perturbed point
    made consistent by Newton on all equations with the states held."""
    from acausal2d.runtime.evaluator import Evaluator
    from acausal2d.runtime.newton import solve_consistent
    s = cm.system
    ev = Evaluator(s, point.p)
    idx = [s.node_names.index(n) for n in lin.states]
    der = [s.structure.var_to_diff[j] for j in idx]
    cols = []
    for k, j in enumerate(idx):
        f = []
        step = h * s.nominal[j]               # a strain of nominal 1e-5, a pressure of 1e5 Pa
        for sign in (1.0, -1.0):
            x = point.z[idx].copy()
            x[k] += sign * step
            z = solve_consistent(ev, point.t, point.z, point.d, idx, x, tol=tol)
            f.append(z[der])
        cols.append((f[0] - f[1]) / (2 * step))
    return np.array(cols).T


@pytest.mark.parametrize("path,t,h,tol", [("models/double_pendulum.py", 0.7, 1e-6, 1e-14),
                                           ("models/piston_engine.py", 1.3, 1e-6, 1e-14),
                                           ("models/crane_crab.py", 0.4, 1e-6, 1e-14),
                                           # belt, clutch, gas spring: forces of 1e3 N
                                           ("models/compressor.py", 8.0, 1e-4, 1e-12)])
def test_exact_A_agrees_with_finite_differences(path, t, h, tol):
    from acausal2d.io.loader import load_model
    cm = acausal2d.compile_model(load_model(path))
    point = point_at(cm, t)
    lin = linearize(cm, at=t)
    assert lin.point.t == t and lin.A.shape == (len(lin.states),) * 2
    fd = _fd_A(cm, point, lin, h, tol)
    scale = np.max(np.abs(lin.A))
    assert np.max(np.abs(lin.A - fd)) <= 1e-6 * scale, (lin.A, fd)


def test_crane_crab_hook_hangs_straight_down():
    from acausal2d.io.loader import load_model
    cm = acausal2d.compile_model(load_model("models/crane_crab.py"))    # started at 150 deg
    eq = find_equilibrium(cm)
    names = cm.system.node_names
    phi = eq.point.z[names.index("revolute.phi")]
    assert eq.stable and eq.residual < 1e-8
    # rod r = (0, -1) in the joint frame: hanging straight down at phi = 0 (mod 2 pi)
    assert math.remainder(phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-10)
    result = modes_of(linearize(cm, equilibrium=True))
    # the trolley may slide freely (damper only): one rigid-body mode
    assert result.rigid_body_modes == 1


def test_kinematically_driven_model_is_named():
    from acausal2d.io.loader import load_model
    cm = acausal2d.compile_model(load_model("models/four_link_mechanisms.py", "DDDD"))
    with pytest.raises(Acausal2dError, match="kinematically driven"):
        modes(cm, at=0.1)


def test_campbell_frequencies_over_a_swept_stiffness():
    from acausal2d.analysis.campbell import campbell
    cm = _compiled(TwoMassChain)
    table = campbell(cm, {"k2.c": [200.0, 400.0, 800.0]}, count=2, stop_time=0.01,
                     progress=False)
    k1, m1, m2 = 1000.0, 2.0, 0.5
    for row in table.rows:
        k2 = row["k2.c"]
        w2 = np.linalg.eigvals(np.linalg.solve(np.diag([m1, m2]),
                                               np.array([[k1 + k2, -k2], [-k2, k2]])))
        expected = np.sort(np.sqrt(w2.real)) / (2 * math.pi)
        assert [row["f1"], row["f2"]] == pytest.approx(list(expected), rel=1e-9)
    assert table.plot() is not None


def test_compiled_model_methods_give_a_b_c_d_of_the_damped_oscillator():
    cm = _compiled(DampedOscillator)
    lin = cm.linearize(inputs=["spring.s_rel0"], outputs=["mass.s", "spring.f"])
    c, d, m = 250.0, 3.0, 1.5
    # the damper's relative position is the preferred state (Modelica's
    # PartialCompliantWithRelativeStates), here equal to mass.s (wall at 0)
    assert set(lin.states) == {"damper.s_rel", "mass.v"}
    i, j = lin.states.index("damper.s_rel"), lin.states.index("mass.v")
    A = np.zeros((2, 2))
    A[i, j], A[j, i], A[j, j] = 1.0, -c / m, -d / m
    assert np.allclose(lin.A, A, rtol=1e-12, atol=1e-12)
    # u = unstretched length s_rel0: der(v) = -c (s - s_rel0)/m, f = c (s - s_rel0)
    assert lin.B[j, 0] == pytest.approx(c / m, rel=1e-12) and lin.B[i, 0] == 0
    assert abs(lin.D[1, 0]) == pytest.approx(c, rel=1e-12)
    assert cm.equilibrium().residual < 1e-8
    assert cm.modes().modes[0]["damping_ratio"] == pytest.approx(d / (2 * math.sqrt(c * m)))


def test_singular_point_is_refused_with_the_reason():
    with pytest.raises(acausal2d.SimulationError, match="cannot linearise Parallelogram") as info:
        modes(_compiled(Parallelogram))
    assert "'jb.phi'" in str(info.value) and "singular position" in str(info.value)


def _values(cm, point, names):
    """Values of nodes and eliminated aliases at an operating point."""
    s = cm.system
    aliases = s.alias_values(point.z[None, :], point.p)[0]
    table = dict(zip(s.node_names, point.z))
    table.update(zip(s.alias_names + s.alias_der_names, aliases))
    return {n: float(table[n]) for n in names}


def test_cable_crane_hook_returns_to_its_rest_position_and_swings_at_sqrt_g_over_l():
    from acausal2d.io.loader import load_model
    cm = acausal2d.compile_model(load_model("models/cable_crane.py"))
    names = cm.system.node_names
    rest = cm.initial_point().z        # the model starts in its static equilibrium (static_pose)
    hx, hy = names.index("hook.x"), names.index("hook.y")
    # swung aside by 1.5 m on its 6 m rope (rope length kept: the start keeps the
    # rope's material, an invariant the search holds)
    lift = 6.0 - math.sqrt(6.0 ** 2 - 1.5 ** 2)
    eq = find_equilibrium(cm, t=0.5, start={"hook.x": rest[hx] + 1.5, "hook.y": rest[hy] + lift})
    assert eq.stable and eq.residual < 1e-8
    res = _values(cm, eq.point, ["hook.x", "C.ctrK2.x", "load6.F"])
    # the hook hangs vertically below the point K2 where the rope leaves pulley C,
    # and the last load-rope section carries the hook's weight, 1000 kg * g
    assert res["hook.x"] == pytest.approx(res["C.ctrK2.x"], abs=1e-9)
    assert res["load6.F"] == pytest.approx(1000.0 * G, rel=1e-9)
    # back at the rest pose: the search keeps the rope material of the start, and
    # the start's swing about K2 ignores the rope wrapping on pulley C, which
    # leaves its material a fraction of a millimetre off the rest pose's
    assert eq.point.z[hx] == pytest.approx(rest[hx], abs=1e-3)
    assert eq.point.z[hy] == pytest.approx(rest[hy], abs=1e-3)
    l_u0 = [j for j, n in enumerate(names) if n.endswith(".l_u0")]
    assert len(l_u0) == 12
    moved = [names[j] for j in l_u0 if abs(eq.point.z[j] - rest[j]) > 1e-3]
    assert moved == []
    slowest = modes(cm, at=0.5, equilibrium=True).modes[0]
    # the hook hangs 6 m below pulley C: a pendulum of about that length (the
    # carriage and the elastic ropes move a little with it)
    assert slowest["dominant"] == "hook.x"
    assert slowest["frequency_hz"] == pytest.approx(math.sqrt(G / 6.0) / (2 * math.pi), rel=0.02)


@pytest.mark.parametrize("degrees", [30.0, 60.0, 135.0, 210.0, 300.0])
def test_four_bar_frequency_at_a_crank_angle_follows_its_reduced_inertia(degrees):
    import os
    import sys
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(
        __file__))), "models"))
    import four_bar_modes as fb
    cm = acausal2d.compile_model(fb.FourBarOnShaft())
    phi = math.radians(degrees)
    result = modes(cm, equilibrium=True, params={"hold.phi0": phi})
    crank = result.linearization.point.z[cm.system.node_names.index("ja.phi")]
    assert math.remainder(crank - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-10)
    (mode,) = result.modes
    assert mode["frequency_hz"] == pytest.approx(
        math.sqrt(fb.C_SHAFT / fb.reduced_inertia(phi)) / (2 * math.pi), rel=1e-9)


def test_top_level_input_becomes_a_parameter_input():
    from acausal2d.library.inputs import bind_inputs
    given = acausal2d.load_model(os.path.join(os.path.dirname(__file__), "data", "forced_mass.py"))
    model, names = bind_inputs(given, {"u": 20.0})
    assert names == {"u": "u_source.k"}
    assert "u" in given._connectors and not hasattr(given, "u_source")   # the user's model as it was
    cm = acausal2d.compile_model(model)
    lin = cm.linearize(equilibrium=True, inputs=["u"], outputs=["mass.s", "spring.f"])
    i, j = lin.states.index("mass.s"), lin.states.index("mass.v")
    assert lin.B[j, 0] == pytest.approx(1 / 4.0, rel=1e-12) and lin.B[i, 0] == 0
    assert lin.A[j, i] == pytest.approx(-100.0 / 4.0, rel=1e-12)
    # static: s = u / c = 0.2 m; C, D: s and the spring force follow u only through s
    assert lin.point.z[cm.system.node_names.index("mass.s")] == pytest.approx(0.2, rel=1e-12)
    assert lin.C[0, i] == 1 and lin.D[0, 0] == 0 and abs(lin.C[1, i]) == pytest.approx(100.0)
    assert lin.inputs == ["u"]
