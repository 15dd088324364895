"""Hydrostatic elements (acausal2d.library.hydraulics) against closed forms:

* pump and motor flow and torque with the volumetric and mechanical-
  hydraulic efficiencies in the quadrant of their power flow (Murrenhoff),
  fixed and variable displacement, and a motor overrun as a pump;
* a volume charged by a constant flow: p(t) linear with slope K q / V0;
* a relief valve limiting the pressure to p_crack + q / G;
* laminar throttle and turbulent orifice (regRoot) flows;
* a pump driving a motor through a volume: steady speed ratio =
  displacement ratio times both volumetric efficiencies, and the energy
  balance integrated over the run.

Tolerances: IDA runs at RTOL with atol = RTOL * nominal.  Algebraic closed
forms hold to the Newton tolerance of the equations (RTOL relative, times
ten for room); integrated quantities carry the global error, a few RTOL of
their scale per unit of time-constant-free growth (given 100 RTOL).  The
smooth power direction s = tanh(P_g / P_band) is within 4e-9 of +-1 for
|P_g| >= 10 P_band, which every operating point below exceeds by orders of
magnitude (P_g >= 1e3 W, P_band = 1 W)."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, der, start, Variable
from acausal2d.errors import ModelDefinitionError
from acausal2d.library import hydraulics as hy
from acausal2d.library import rotational as rot
from acausal2d.library import signals

RTOL = 1e-8
VG_P, VG_M = 1e-4, 2.5e-4            # m3/rev
EV_P, EH_P, EV_M, EH_M = 0.95, 0.9, 0.97, 0.92
K, V0 = 1.4e9, 2e-3


def _d(vg):
    return vg / (2 * math.pi)


class SpeedRig(Component):
    """A machine at the shaft speed ``w`` between two pressure sources
    (p_a at port_a, p_b at port_b); ``alpha`` given: variable displacement."""

    def __init__(self, machine, w=150.0, p_a=0.0, p_b=2e7, alpha=None, **kw):
        super().__init__(**kw)
        self.src_a = hy.PressureSource(p0=p_a)
        self.src_b = hy.PressureSource(p0=p_b)
        self.m = machine
        self.ws = signals.Constant(k=w)
        self.drive = rot.Speed(phi=start(0.0, fixed=True))
        self.connect(self.ws.y, self.drive.w_in)
        self.connect(self.drive.flange, self.m.flange)
        self.connect(self.src_a.port, self.m.port_a)
        self.connect(self.m.port_b, self.src_b.port)
        if alpha is not None:
            self.al = signals.Constant(k=alpha)
            self.connect(self.al.y, self.m.alpha)


def _final(rig, names):
    res = acausal2d.simulate(rig, stop_time=0.1, rtol=RTOL)
    return [res.final(n) for n in names]


def test_pump_flow_and_torque_with_efficiencies():
    """Pumping (P_g > 0): q = eta_v D w, tau = D dp / eta_hm; loss >= 0."""
    w, dp = 150.0, 2e7
    q, tau, s, loss = _final(SpeedRig(hy.Pump(Vg=VG_P, eta_v=EV_P, eta_hm=EH_P), w=w, p_b=dp),
                             ["m.q", "m.tau", "m.s", "m.loss_power"])
    D = _d(VG_P)
    assert q == pytest.approx(EV_P * D * w, rel=10 * RTOL)
    assert tau == pytest.approx(D * dp / EH_P, rel=10 * RTOL)
    assert s == pytest.approx(1.0, abs=1e-8)
    assert loss == pytest.approx(D * w * dp * (1 / EH_P - EV_P), rel=10 * RTOL)


def test_motor_flow_and_torque_with_efficiencies():
    """Motoring (supply at port_a, P_g < 0): q = D w / eta_v, the motor
    gives -tau = eta_hm D (p_a - p_b)."""
    w, pa, pb = 80.0, 2.2e7, 2e6
    q, tau, s, loss = _final(SpeedRig(hy.Motor(Vg=VG_M, eta_v=EV_M, eta_hm=EH_M), w=w,
                                      p_a=pa, p_b=pb), ["m.q", "m.tau", "m.s", "m.loss_power"])
    D = _d(VG_M)
    assert q == pytest.approx(D * w / EV_M, rel=10 * RTOL)
    assert -tau == pytest.approx(EH_M * D * (pa - pb), rel=10 * RTOL)
    assert s == pytest.approx(-1.0, abs=1e-8)
    assert loss == pytest.approx(D * w * (pa - pb) * (1 / EV_M - EH_M), rel=10 * RTOL)


def test_motor_overrun_acts_as_pump_and_still_loses_power():
    """A motor driven backwards against its supply pressure pumps (P_g > 0):
    the pump law applies and the loss stays positive."""
    w, pa = -60.0, 1.5e7
    q, tau, loss = _final(SpeedRig(hy.Motor(Vg=VG_M, eta_v=EV_M, eta_hm=EH_M), w=w, p_a=pa,
                                   p_b=0.0), ["m.q", "m.tau", "m.loss_power"])
    D = _d(VG_M)
    assert q == pytest.approx(EV_M * D * w, rel=10 * RTOL)
    assert tau == pytest.approx(-D * pa / EH_M, rel=10 * RTOL)
    assert loss > 0 and loss == pytest.approx(-D * w * pa * (1 / EH_M - EV_M), rel=10 * RTOL)


@pytest.mark.parametrize("alpha", [0.4, -0.7])
def test_variable_pump_scales_with_alpha(alpha):
    """Displacement alpha Vg; over centre (alpha < 0) the flow reverses and,
    against the higher pressure at port_b, the machine motors."""
    w, dp = 150.0, 1e7
    q, tau = _final(SpeedRig(hy.Pump(Vg=VG_P, eta_v=EV_P, eta_hm=EH_P, variable=True), w=w,
                             p_b=dp, alpha=alpha), ["m.q", "m.tau"])
    D = alpha * _d(VG_P)
    if alpha > 0:
        assert q == pytest.approx(EV_P * D * w, rel=10 * RTOL)
        assert tau == pytest.approx(D * dp / EH_P, rel=10 * RTOL)
    else:
        assert q == pytest.approx(D * w / EV_P, rel=10 * RTOL)
        assert tau == pytest.approx(EH_P * D * dp, rel=10 * RTOL)


class SweepRig(Component):
    """A motor between a pressure source swept through zero (p_a = -p_amp
    cos(2 pi t / T)) and the tank, its shaft driven by a speed swept
    through zero (w = w_amp sin(2 pi t / T')): all four quadrants."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.m = hy.Motor(Vg=VG_M, eta_v=EV_M, eta_hm=EH_M)
        self.src = hy.PressureSource(use_p_in=True)
        self.tank = hy.PressureSource()
        self.pa = signals.Sine(amplitude=2e7, f=1.0, phase=-math.pi / 2)
        self.ws = signals.Sine(amplitude=50.0, f=0.7)
        self.drive = rot.Speed(phi=start(0.0, fixed=True))
        self.connect(self.ws.y, self.drive.w_in)
        self.connect(self.drive.flange, self.m.flange)
        self.connect(self.m.port_b, self.tank.port)
        self.connect(self.src.port, self.m.port_a)
        self.connect(self.pa.y, self.src.p_in)


def test_machine_is_dissipative_and_continuous_in_all_four_quadrants():
    """Speed and pressure swept through zero: the loss P_g (eta_hm^-s -
    eta_v^s) never becomes negative (down to the rounding of its terms), and
    where |P_g| >= 10 P_band the textbook law of the quadrant holds."""
    res = acausal2d.simulate(SweepRig(), stop_time=3.0, rtol=RTOL,
                             output_times=np.linspace(0, 3.0, 3001))
    P_g = res["m.dp"] * res["m.q_g"]
    scale = 1e-12 * np.maximum(np.abs(res["m.P_mech"]), 1.0)
    assert np.min(res["m.loss_power"] + scale) >= 0
    assert np.max(P_g) > 3e4 and np.min(P_g) < -3e4         # D w_amp p_amp = 4e4 W
    D, w, dp = _d(VG_M), res["m.w"], res["m.dp"]
    pumping, motoring = P_g >= 10.0, P_g <= -10.0
    q = np.where(pumping, EV_M * D * w, D * w / EV_M)
    tau = np.where(pumping, D * dp / EH_M, EH_M * D * dp)
    both = pumping | motoring
    assert np.allclose(res["m.q"][both], q[both], rtol=1e-8, atol=0)
    assert np.allclose(res["m.tau"][both], tau[both], rtol=1e-8, atol=0)


class ChargeRig(Component):
    """Pump at constant speed from the tank into a volume (start 1 MPa),
    optionally protected by a relief valve to the tank."""

    def __init__(self, w=100.0, relief=None, **kw):
        super().__init__(**kw)
        self.tank = hy.PressureSource()
        self.pump = hy.Pump(Vg=VG_P, eta_v=EV_P, eta_hm=EH_P)
        self.vol = hy.Volume(V0=V0, K=K, p=start(1e6, fixed=True))
        self.ws = signals.Constant(k=w)
        self.drive = rot.Speed(phi=start(0.0, fixed=True))
        self.connect(self.ws.y, self.drive.w_in)
        self.connect(self.drive.flange, self.pump.flange)
        self.connect(self.tank.port, self.pump.port_a)
        self.connect(self.pump.port_b, self.vol.port)
        if relief is not None:
            self.valve = hy.ReliefValve(p_crack=relief[0], G=relief[1])
            self.connect(self.vol.port, self.valve.port_a)
            self.connect(self.valve.port_b, self.tank.port)


def test_volume_charged_by_constant_flow_rises_linearly():
    """p(t) = p0 + K q t / V0 with q = eta_v D w (BDF integrates a linear
    function exactly: the error is the step's Newton tolerance)."""
    w = 100.0
    res = acausal2d.simulate(ChargeRig(w=w), stop_time=0.5, rtol=RTOL,
                             output_times=np.linspace(0, 0.5, 51))
    q = EV_P * _d(VG_P) * w
    expect = 1e6 + K * q * res["time"] / V0
    assert np.max(np.abs(res["vol.p"] - expect)) <= 100 * RTOL * expect[-1]
    E = res["vol.E"]
    assert E[-1] == pytest.approx(V0 * expect[-1] ** 2 / (2 * K), rel=100 * RTOL)


def test_relief_valve_limits_the_pressure():
    """The pump's whole flow leaves over the valve: p -> p_crack + q / G,
    approached with the time constant V0 / (K G); the valve is closed
    (q = 0) until the pressure reaches p_crack."""
    w, p_crack, G = 100.0, 1.5e7, 2e-10
    res = acausal2d.simulate(ChargeRig(w=w, relief=(p_crack, G)), stop_time=1.0, rtol=RTOL,
                             output_times=np.linspace(0, 1.0, 201))
    q = EV_P * _d(VG_P) * w
    p_lim = p_crack + q / G
    assert V0 / (K * G) * 20 < 1.0          # the run lasts 20 time constants
    assert res.final("vol.p") == pytest.approx(p_lim, rel=100 * RTOL)
    assert res.final("valve.q") == pytest.approx(q, rel=100 * RTOL)
    closed = res["vol.p"] < p_crack
    assert np.max(np.abs(res["valve.q"][closed])) <= 10 * RTOL * q
    assert np.max(res["vol.p"]) <= p_lim * (1 + 100 * RTOL)


class FlowRig(Component):
    """Pressure source -> element -> tank."""

    def __init__(self, element, p=1e6, **kw):
        super().__init__(**kw)
        self.src = hy.PressureSource(p0=p)
        self.tank = hy.PressureSource()
        self.el = element
        self.connect(self.src.port, self.el.port_a)
        self.connect(self.el.port_b, self.tank.port)


def test_throttle_and_orifice_flows():
    """Laminar q = G dp; turbulent q = Cd A sqrt(2 dp / rho), regRoot's
    deviation (dp_small / dp)^2 / 4 = 2.5e-9 at dp = 1e7, dp_small = 1e3."""
    G, dp = 3e-11, 1e7
    res = acausal2d.simulate(FlowRig(hy.Throttle(G=G), p=dp), stop_time=0.01, rtol=RTOL)
    assert res.final("el.q") == pytest.approx(G * dp, rel=10 * RTOL)
    assert res.final("el.loss_power") == pytest.approx(G * dp ** 2, rel=10 * RTOL)
    A, Cd, rho = 2e-6, 0.65, 860.0
    res = acausal2d.simulate(FlowRig(hy.Orifice(A=A, Cd=Cd, rho=rho), p=dp), stop_time=0.01,
                             rtol=RTOL)
    assert res.final("el.q") == pytest.approx(Cd * A * math.sqrt(2 * dp / rho), rel=1e-8)


class Transmission(Component):
    """Diesel-like speed source -> pump -> volume (+ relief) -> motor ->
    inertia with a viscous load; the energy flows integrated as states."""
    E_in = Variable(start=0.0, fixed=True, unit="J", nominal=1e4, doc="shaft work into the pump")
    E_load = Variable(start=0.0, fixed=True, unit="J", nominal=1e4, doc="work into the load")
    E_loss = Variable(start=0.0, fixed=True, unit="J", nominal=1e3,
                      doc="machine losses from the closed forms")

    def __init__(self, w=100.0, d=20.0, **kw):
        super().__init__(**kw)
        self.tank = hy.PressureSource()
        self.pump = hy.Pump(Vg=VG_P, eta_v=EV_P, eta_hm=EH_P)
        self.motor = hy.Motor(Vg=VG_M, eta_v=EV_M, eta_hm=EH_M)
        self.vol = hy.Volume(V0=V0, K=K, p=start(1e6, fixed=True))
        self.valve = hy.ReliefValve(p_crack=3.5e7, G=1e-9)
        self.ws = signals.Constant(k=w)
        self.drive = rot.Speed(phi=start(0.0, fixed=True))
        self.J = rot.Inertia(J=0.5, phi=start(0.0, fixed=True), w=start(0.0, fixed=True))
        self.load = rot.Damper(d=d)
        self.ground = rot.Fixed()
        self.connect(self.ws.y, self.drive.w_in)
        self.connect(self.drive.flange, self.pump.flange)
        for a, b in [(self.tank.port, self.pump.port_a), (self.pump.port_b, self.vol.port),
                     (self.vol.port, self.motor.port_a), (self.motor.port_b, self.tank.port),
                     (self.vol.port, self.valve.port_a), (self.valve.port_b, self.tank.port),
                     (self.motor.flange, self.J.flange_a), (self.J.flange_b, self.load.flange_a),
                     (self.load.flange_b, self.ground.flange)]:
            self.connect(a, b)

    def equations(self):
        p, wp, wm = self.vol.p, self.pump.w, self.motor.w
        loss = (_d(VG_P) * wp * p * (1 / EH_P - EV_P) + _d(VG_M) * wm * p * (1 / EV_M - EH_M))
        return [der(self.E_in) == self.pump.tau * wp, der(self.E_load) == -self.load.tau * wm,
                der(self.E_loss) == loss]


def test_pump_drives_motor_speed_ratio_and_energy_balance():
    """Steady: q_pump = eta_vp D_p w_p = D_m w_m / eta_vm, so w_m / w_p =
    (Vg_p / Vg_m) eta_vp eta_vm; the motor pressure carries the load:
    eta_hm D_m p = d w_m.  Over the run (start-up from rest included):
    shaft work = load work + kinetic energy + oil elastic energy + machine
    losses (the relief valve stays closed).  The oil spring K D_m^2 / V0 =
    1.1e3 N m/rad against J = 0.5 kg m2 with d = 20 N m s/rad decays at
    about d / (2 J) = 20 /s, so 3 s are 60 time constants."""
    w, d = 100.0, 20.0
    res = acausal2d.simulate(Transmission(w=w, d=d), stop_time=3.0, rtol=RTOL,
                             output_times=np.linspace(0, 3.0, 301))
    ratio = VG_P / VG_M * EV_P * EV_M
    wm = res.final("motor.w")
    assert wm / w == pytest.approx(ratio, rel=100 * RTOL)
    assert res.final("vol.p") == pytest.approx(d * wm / (EH_M * _d(VG_M)), rel=100 * RTOL)
    assert np.max(res["valve.q"]) <= 0.0 + 1e-30
    E_kin = 0.5 * 0.5 * wm ** 2
    E_oil = res.final("vol.E") - res["vol.E"][0]
    E_in = res.final("E_in")
    balance = res.final("E_load") + E_kin + E_oil + res.final("E_loss")
    assert balance == pytest.approx(E_in, rel=100 * RTOL)


@pytest.mark.parametrize("cls, kw", [(hy.Pump, {"eta_v": 1.2}), (hy.Motor, {"eta_hm": 0.0}),
                                     (hy.Volume, {"K": -1.0}), (hy.ReliefValve, {"G": 0.0}),
                                     (hy.Orifice, {"A": float("nan")})])
def test_bad_parameters_are_named(cls, kw):
    """Efficiencies outside (0, 1], non-positive moduli and gradients are
    refused, naming the parameter and its rule."""
    name = next(iter(kw))
    with pytest.raises(ModelDefinitionError, match=name):
        cls(**kw)
