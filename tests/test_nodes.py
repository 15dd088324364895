"""The node/constraint front end (library/nodes/model.py, library/nodes.py):
every constraint kind compiles into the DAE and meets a closed form or an
independent solution; eq. 1/2 counts; assembly from rough coordinates;
ranges with events; loads; frames joining library elements."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import ModelDefinitionError
from acausal2d.library.nodes import (NodeAssemblyError, NodeModel, at_least, at_most, between,
                                      delta, drive, mec2_drive, ref, speed)
from acausal2d.library.linkage import DAN, DDD, DDS
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import PlanarWorld
from vdi2729_reference import vdi_ddd

TURN = 2 * math.pi
TIMES = np.linspace(0.0, 1.0, 181)


def run(model, **kw):
    kw.setdefault("output_times", TIMES)
    return acausal2d.simulate(model, rtol=1e-10, **kw)


class FourBar(NodeModel):
    """Four-bar in metres: crank 0.06 turned at 1 turn/s."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B0", 0.18, -0.06, base=True)
        self.node("A", 0, 0.06, m=10)
        self.node("B", 0.12, 0.06)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("AB", "A", "B", len="const")
        self.n2("B0B", "B0", "B", len="const")


def test_four_bar_matches_the_closed_form_dyad():
    res = run(FourBar())
    phi = math.pi / 2 + TURN * res.time
    assert np.max(np.abs(res["A0A.w"] - phi)) < 1e-12
    A = np.stack([0.06 * np.cos(phi), 0.06 * np.sin(phi)], axis=1)
    B0, l1, l2 = np.array([0.18, -0.06]), 0.12, math.hypot(0.06, 0.12)
    B = np.array([vdi_ddd(a, B0, l1, l2, 1) for a in A])
    assert np.max(np.abs(res["B.x"] - B[:, 0])) < 1e-10
    assert np.max(np.abs(res["B.y"] - B[:, 1])) < 1e-10
    # held lengths and the unwrapped angle of the rocker stay continuous
    assert np.max(np.abs(res["AB.r"] - l1)) < 1e-12
    assert np.max(np.abs(np.diff(res["B0B.w"]))) < 0.1


def test_counts_of_eq_1_and_2_and_check_output():
    counts = FourBar().node_counts()
    assert {k: counts[k] for k in ("N", "N_base", "C1", "C2", "F", "m")} == \
        {"N": 4, "N_base": 2, "C1": 3, "C2": 0, "F": 1, "m": 1}
    assert counts["driven"] == ["A0A.ang"]
    text = str(acausal2d.check(FourBar()))
    assert "N = 4, N_base = 2, C1 = 3, C2 = 0: F = 1 (eq. 1), m = 1 loops (eq. 2)" in text
    assert "driven (inputs, not counted): A0A.ang" in text


U0 = (0.5, -1.0)
T0 = (math.cos(math.atan2(-3.0, 0.5)), math.sin(math.atan2(-3.0, 0.5)))


class Kinds(NodeModel):
    """One model with every constraint value kind of the front end: held
    numbers and 'const', a function drive, a mec2 drive, references (cstr.js
    from with offset and with scale, mec2 relative with ratio), delta, the
    three-node angle and a free constraint used as a reference."""

    def __init__(self, **kw):
        super().__init__(**kw)
        for nid, x, y, base in (("O", 0, 0, True), ("P", 1, 0, False), ("Q", 0, 2, False),
                                ("R", 1, 1, False), ("S", -1, 0, False), ("U", *U0, False),
                                ("V", 3, 0, True), ("W", 3, 1, False), ("T", *T0, False)):
            self.node(nid, x, y, base=base)
        self.n2("OP", "O", "P", len=1.0, ang=drive(lambda t: 0.3 * acausal2d.sin(TURN * t)))
        self.n2("OQ", "O", "Q", len="const", ang=ref("OP", offset=math.pi / 2))
        self.n2("OR", "O", "R", len=ref("OP", ratio=math.sqrt(2)),
                ang=delta("OP", "OQ", 0.5))
        self.n2("OS", "O", "S", len=ref("OQ", ratio=0.5),
                ang=ref("OP", ratio=2.0, relative=True))
        self.n2("VW", "V", "W", len="const", ang=mec2_drive("harmonic", Dz=1.0, Dt=1.0))
        self.n3("OPU", "O", "P", "U", "const")          # U rigid with OP ...
        self.n2("OU", "O", "U", len="const")
        self.n2("QU", "Q", "U")                          # free: a measurement
        self.n2("OT", "O", "T", len="const", ang=ref("QU"))   # OT parallel to QU


def test_every_value_kind_against_closed_forms():
    res = run(Kinds())
    t = res.time
    w = 0.3 * np.sin(TURN * t)

    def pos(n):
        return np.stack([res[n + ".x"], res[n + ".y"]], axis=1)

    def e(a):
        return np.stack([np.cos(a), np.sin(a)], axis=1)
    assert np.max(np.abs(pos("P") - e(w))) < 1e-10                     # number + drive
    assert np.max(np.abs(pos("Q") - 2 * e(w + math.pi / 2))) < 1e-10  # const + from(offset)
    assert np.max(np.abs(pos("R") - math.sqrt(2) * e(w + math.pi / 4))) < 1e-10   # scl, delta
    assert np.max(np.abs(pos("S") - e(math.pi + 2 * w))) < 1e-10      # mec2 ratio 2
    wv = math.pi / 2 + (1 - np.cos(math.pi * np.minimum(t, 1.0))) / 2  # harmonic, Dz = Dt = 1
    assert np.max(np.abs(pos("W") - (np.array([3.0, 0.0]) + e(wv)))) < 1e-10
    U = math.hypot(*U0) * e(w + math.atan2(U0[1], U0[0]))               # n3 + len
    assert np.max(np.abs(pos("U") - U)) < 1e-10
    QU = U - pos("Q")
    T = e(np.arctan2(QU[:, 1], QU[:, 0]))                               # ref of a free one
    assert np.max(np.abs(pos("T") - T)) < 1e-10


def test_kinds_count_every_held_value():
    c = Kinds().node_counts()
    # C1: OP (len; ang driven), VW (len; ang driven), OPU (n3), OU (len);
    # C2: OQ, OR, OS, OT; QU is free
    assert (c["N"], c["N_base"], c["C1"], c["C2"]) == (9, 2, 4, 4)
    assert (c["F"], c["m"]) == (2 * 7 - 4 - 8, 4 + 4 - 9 + 2)
    assert sorted(c["driven"]) == ["OP.ang", "VW.ang"]


def test_assembly_turns_rough_coordinates_into_the_closed_position():
    model = FourBar()
    exact = run(model, output_times=[0.0, 0.01])

    class Off(NodeModel):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("A0", 0, 0, base=True)
            self.node("B0", 0.18, -0.06, base=True)
            self.node("A", 0.004, 0.055, m=10)
            self.node("B", 0.126, 0.066)
            self.n2("A0A", "A0", "A", len=0.06, ang=speed(TURN, start=math.pi / 2))
            self.n2("AB", "A", "B", len=0.12)
            self.n2("B0B", "B0", "B", len=math.hypot(0.06, 0.12))
    solver, report = Off().assemble()
    assert report.converged and report.iterations > 1
    res = run(Off(), output_times=[0.0, 0.01])
    for k in ("A.x", "A.y", "B.x", "B.y"):
        assert abs(res[k][0] - exact[k][0]) < 1e-10


def test_assembly_failure_names_the_constraint_and_undoes():
    class Open(NodeModel):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("A0", 0, 0, base=True)
            self.node("B0", 1.0, 0, base=True)
            self.node("A", 0, 0.1)
            self.node("B", 0.5, 0.1)
            self.n2("A0A", "A0", "A", len=0.1, ang=speed(1.0))
            self.n2("AB", "A", "B", len=0.3)
            self.n2("B0B", "B0", "B", len=0.3)           # 0.1 + 0.3 + 0.3 < 1: cannot close
    model = Open()
    with pytest.raises(NodeAssemblyError) as err:
        acausal2d.compile_model(model)
    msg = str(err.value)
    assert "cannot close" in msg and "256 sweeps" in msg and "undone" in msg
    assert err.value.correction.iterations == 256 and err.value.correction.undone
    assert isinstance(err.value, acausal2d.InitializationError)


class Cylinder(NodeModel):
    """A hydraulic cylinder: node B on a horizontal guide from A0, its
    length driven out and back (mec2 linear bounce, 60 mm in 1 s) and
    limited to [30, 80] mm (a range with a source)."""
    length_unit = 1e-3

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B", 50, 0)
        self.n2("A0B", "A0", "B", ang="const",
                len=between(30, 80, source=mec2_drive("linear", Dz=60, Dt=1, bounce=True)))


def test_len_range_stops_the_motion_at_the_limit_with_events():
    res = run(Cylinder(), output_times=np.linspace(0.0, 2.5, 251))
    times = res.time
    drive = np.where(times < 1, 0.05 + 0.06 * times,
                     np.where(times < 2, 0.05 + 0.06 * (2 - times), 0.05))
    expected = np.minimum(drive, 0.08)
    assert np.max(np.abs(res["B.x"] - expected)) < 1e-12
    assert np.max(np.abs(res["B.y"])) < 1e-12
    # the stop at the limit and the return are events at the exact times
    times_of = [t for t, _ in res.events]
    assert 0.5 in times_of and 1.5 in times_of
    still = (res.time > 0.5) & (res.time < 1.5)
    assert np.max(np.abs(res["der(B.x)"][still])) < 1e-12
    assert np.all(res["A0B.r"] <= 0.08 + 1e-15)


def test_range_without_a_drive_to_stop_is_an_error():
    class Free(NodeModel):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("A0", 0, 0, base=True)
            self.node("A", 1, 0)
            self.n2("A0A", "A0", "A", len=at_most(2.0))
    with pytest.raises(ModelDefinitionError, match="has no source.*has none.*impact"):
        acausal2d.compile_model(Free())


def test_range_names_a_missing_drive():
    class Two(FourBar):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("C", 0.3, 0)
            self.n2("B0C", "B0", "C", len=at_least(0.1, stops="nope"), ang="const")
    with pytest.raises(ModelDefinitionError, match="stops 'nope', which is no driven"):
        acausal2d.compile_model(Two())


@pytest.mark.parametrize("build, pattern", [
    (lambda m: m.node("1A", 0, 0), "is not a name"),
    (lambda m: m.node("A0", 1, 1), "already used"),
    (lambda m: m.n2("X", "A0", "Z"), "'Z' is no node"),
    (lambda m: m.n2("X", "A0", "A", len=ref("later")), "no two-node constraint declared before"),
    (lambda m: m.n2("X", "A0", "A", len="long"), "is no constraint value"),
    (lambda m: m.n2("X", "A0", "B", ang=ref("AB", of="len")), "relative=True"),
    (lambda m: m.n2("X", "A0", "B", dir=1), "dir needs a held angle"),
    (lambda m: m.n2("X", "A0", "B", ang=mec2_drive("spin")), "unknown drive function 'spin'"),
    (lambda m: m.n3("X", "A0", "A", "B", ang="wide"), "takes ang='const' or a number"),
])
def test_definition_errors_name_what_to_change(build, pattern):
    model = FourBar()
    with pytest.raises(ModelDefinitionError, match=pattern):
        build(model)


class Lever(NodeModel):
    """Rigid lever A0-A-B (b's angle coupled 1:1 to a's) under gravity,
    held by a zero-free-length spring from B0 above A0 to A (seed eq.
    3.11/3.12: balanced for every angle when k h a = g (m_A a + m_B b))."""
    gravity = (0.0, -10.0)

    def __init__(self, k=80.0, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B0", 0, 0.5, base=True)
        self.node("A", 0.5, 0)
        self.node("B", 1.5, 0)
        self.n2("a", "A0", "A", len="const")
        self.n2("b", "A", "B", len="const", ang=ref("a", relative=True))
        self.spring("s", "B0", "A", k=k, len0=0.0)


def test_balanced_lever_rests_and_unbalanced_one_falls_as_the_ode_says():
    res = run(Lever(), stop_time=2.0, output_times=np.linspace(0, 2, 101))
    assert np.max(np.abs(res["a.w"] - res["a.w"][0])) < 1e-9
    # with k = 70 the torque is (k h a - g (m_A a + m_B b)) cos(w) = -2.5
    # cos(w) about A0 and J = m_A a^2 + m_B b^2 = 2.5: w'' = -cos(w)
    from scipy.integrate import solve_ivp
    res = run(Lever(k=70.0), output_times=np.linspace(0, 1, 51))
    sol = solve_ivp(lambda t, y: [y[1], -math.cos(y[0])], (0, 1), [0.0, 0.0],
                    t_eval=res.time, rtol=1e-11, atol=1e-12)
    assert np.max(np.abs(res["a.w"] - sol.y[0])) < 1e-7
    # the coupling keeps the lever straight
    assert np.max(np.abs(res["b.w"] - res["a.w"])) < 1e-12


def test_force_load_on_a_pendulum_balances_gravity():
    class Pendulum(NodeModel):
        gravity = (0.0, -10.0)

        def __init__(self, **kw):
            super().__init__(**kw)
            self.node("A0", 0, 0, base=True)
            self.node("A", 1, 0, m=3)
            self.n2("a", "A0", "A", len="const")
            self.force("F", "A", 30.0, w0=math.pi / 2)
    res = run(Pendulum())
    assert np.max(np.abs(res["A.y"])) < 1e-12
    # the constraint force is zero: the load carries the weight
    assert np.max(np.abs(res["a.len.f"])) < 1e-9


class NodeCrankVDICoupler(NodeModel):
    """A node four-bar whose coupler carries a VDI DDS: the DDS housing
    sits on the coupler plane (``AB.frame``, at A, angle of AB) 40 mm
    along and 20 mm across it; its slider runs on the ground guide y =
    -0.1 m."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B0", 0.18, -0.06, base=True)
        self.node("A", 0, 0.06, m=10)
        self.node("B", 0.12, 0.06)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("AB", "A", "B", len="const")
        self.n2("B0B", "B0", "B", len="const")
        self.dds = DDS(lL=0.25, v=0.0, x10=0.04, y10=0.02, x20=0.0, y20=-0.1, phi20=0.0, K=1)
        self.connect(self.AB.frame, self.dds.ctr2D1)


class VDICoupler(acausal2d.Component):
    """The same mechanism from VDI elements only (DAN + DDD + DDS)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.world = PlanarWorld(g=(0.0, 0.0))
        self.crank = DAN(lL=0.06, phiL0=math.pi / 2)
        self.preset = Preset(kind="speed", om=TURN, phi0=math.pi / 2)
        self.dyad = DDD(lL1=0.12, lL2=math.hypot(0.06, 0.12), x20=0.18, y20=-0.06, K=1)
        self.dds = DDS(lL=0.25, v=0.0, x10=0.04, y10=0.02, x20=0.0, y20=-0.1, phi20=0.0, K=1)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        self.connect(self.dyad.ctr2D3, self.dds.ctr2D1)


def test_a_node_model_carries_a_vdi_element_on_a_constraint_frame():
    a, b = run(NodeCrankVDICoupler()), run(VDICoupler())
    for k in ("dds.xP", "dds.yP", "dds.xG"):
        assert np.max(np.abs(a[k] - b[k])) < 1e-10
    assert np.ptp(a["dds.xG"]) > 0.05


class VDICrankNodeRest(NodeModel):
    """A VDI crank (DAN with a preset) whose end is node A's frame (a pin);
    the rest of the four-bar is made of node constraints."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("B0", 0.18, -0.06, base=True)
        self.node("A", 0, 0.06, m=10)
        self.node("B", 0.12, 0.06)
        self.n2("AB", "A", "B", len="const")
        self.n2("B0B", "B0", "B", len="const")
        self.crank = DAN(lL=0.06, phiL0=math.pi / 2)
        self.preset = Preset(kind="speed", om=TURN, phi0=math.pi / 2)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.connect(self.crank.ctr2D2, self.A.frame)


def test_a_library_frame_drives_a_node():
    a, b = run(VDICrankNodeRest()), run(FourBar())
    for k in ("A.x", "A.y", "B.x", "B.y"):
        assert np.max(np.abs(a[k] - b[k])) < 1e-10
    # eq. 1/2 count the node part only: 3 nodes (1 base), C1 = 2
    c = VDICrankNodeRest().node_counts()
    assert (c["N"], c["N_base"], c["C1"], c["F"]) == (3, 1, 2, 2)


class PulleysOnNodes(NodeModel):
    """tests/test_belt.py's two pulleys with an open belt, carried by a node
    model: the driving pulley on the plane of the bracket Z -> O (length and
    angle held, so rigid with the ground; the plane sits at Z), the driven
    one on the frame of the base node C."""

    def __init__(self, **kw):
        from acausal2d import start
        from acausal2d.library import rotational, signals
        from acausal2d.library.belt import Belt, Pulley, connect_band
        from test_belt import C2, R1, R2, smooth_angle
        super().__init__(**kw)
        self.node("O", -0.2, 0.0, base=True)
        self.node("Z", 0.0, 0.0)
        self.node("C", *C2, base=True)
        self.n2("ZO", "Z", "O", len="const", ang="const")
        self.p1 = Pulley(r=R1, w_i=-1)               # axes at the frames they ride on
        self.p2 = Pulley(r=R2, w_i=-1, J=1e-4)
        self.connect(self.ZO.frame, self.p1.ctr2D1)
        self.connect(self.C.frame, self.p2.ctr2D1)
        self.span_a = Belt(c=1e8, d=1e4, eps=start(1e-6, fixed=True))
        self.span_b = Belt(c=1e8, d=1e4, eps=start(1e-6, fixed=True))
        connect_band(self, self.span_a, 1, self.p1, 2)
        connect_band(self, self.span_a, 2, self.p2, 1)
        connect_band(self, self.span_b, 1, self.p2, 2)
        connect_band(self, self.span_b, 2, self.p1, 1)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(smooth_angle)
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.p1.ctrR2)


def test_a_node_model_carries_pulleys():
    from test_belt import TwoPulleys
    times = np.linspace(0.0, 2.0, 101)
    a = acausal2d.simulate(PulleysOnNodes(), rtol=1e-9, output_times=times)
    b = acausal2d.simulate(TwoPulleys(), rtol=1e-9, output_times=times)
    for k in ("p1.phi", "p2.phi", "p1.beta", "p2.beta", "span_a.F", "span_b.F"):
        assert np.max(np.abs(a[k] - b[k])) < 1e-8 * max(1.0, np.max(np.abs(b[k]))), k
    assert np.ptp(b["p2.phi"]) > 1.0
    # (the bracket points at pi: the drive on ctrR2 sets the absolute angle, phi_rel = phi - pi)
    tol = 1e-8 * max(1.0, np.max(np.abs(b["p1.phi"])))
    assert np.max(np.abs(a["p1.phi_rel"] - (b["p1.phi"] - math.pi))) < tol
    # the bracket carries the first pulley's bearing force through its held length
    assert np.max(np.abs(a["ZO.len.f"])) > 1.0
