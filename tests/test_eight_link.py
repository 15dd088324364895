"""8-link mechanism after VDI 2729 example 2 (models/eight_link_vdi2729.py):
power balance of the drive torque, T w = d/dt (E_kin + E_pot), with the
energy rate computed here from the simulated centre-of-gravity motion and
the mass data; energy conservation of the force-driven variant."""
import math

import numpy as np
import pytest

import acausal2d


@pytest.fixture(scope="module")
def model_module(request):
    from conftest import load_model_class
    load_model_class("eight_link_vdi2729.py", "EightLinkVDI2729")
    import sys
    return sys.modules["models_eight_link_vdi2729"]


def series(res, cm, name, order=0):
    """Value (order 0) or time derivative (order 1, 2) of ``name``, resolving
    variables the compiler eliminated as aliases."""
    key = name
    for _ in range(order):
        key = "der(%s)" % key
    if key in res:
        return res[key]
    for a in cm.system.aliases:
        if a.var.name == name:
            if a.rep is None:
                return res[name] if order == 0 else np.zeros(len(res.time))
            return a.sign * series(res, cm, a.rep.name, order) + (
                res[name] - a.sign * res[a.rep.name] if order == 0 else 0.0)
    if order == 0:
        return res[name]
    raise KeyError(key)


def energy_terms(res, cm, bodies, g=(0.0, -9.81)):
    """(E_kin + E_pot, its time derivative) over res.time, from the centre
    of gravity positions/derivatives and the mass data of ``bodies``."""
    E = np.zeros(len(res.time))
    dE = np.zeros(len(res.time))
    for elem, mname, jname, xs, ys, ang in bodies:
        m = res.parameters["%s.%s" % (elem, mname)]
        J = res.parameters["%s.%s" % (elem, jname)]
        x, y = (series(res, cm, "%s.%s" % (elem, v)) for v in (xs, ys))
        vx, vy = (series(res, cm, "%s.%s" % (elem, v), 1) for v in (xs, ys))
        ax, ay = (series(res, cm, "%s.%s" % (elem, v), 2) for v in (xs, ys))
        w = series(res, cm, "%s.%s" % (elem, ang), 1)
        al = series(res, cm, "%s.%s" % (elem, ang), 2)
        E += 0.5 * m * (vx ** 2 + vy ** 2) + 0.5 * J * w ** 2 - m * (g[0] * x + g[1] * y)
        dE += m * (vx * ax + vy * ay) + J * w * al - m * (g[0] * vx + g[1] * vy)
    return E, dE


def test_power_balance_kinematic(model_module):
    cls = model_module.EightLinkVDI2729
    cm = acausal2d.compile_model(cls())
    T = model_module.PERIOD
    res = cm.simulate(stop_time=T, rtol=1e-10, output_times=np.linspace(0.0, T, 361))
    phi = res["dAN1.phiL"]
    assert abs(phi[-1] - 2 * math.pi) < 1e-9                  # one full revolution
    tau, w = res["preset1.tau"], res["preset1.w"]
    assert np.max(np.abs(w - 1.5)) < 1e-12
    _, dE = energy_terms(res, cm, model_module.BODIES)
    amplitude = np.max(np.abs(tau))
    assert amplitude > 1e-3
    # T w = dE/dt, as a torque: T = (dE/dt) / w to 1e-6 of the torque amplitude
    assert np.max(np.abs(tau - dE / w)) < 1e-6 * amplitude
    # the drive power integrates to the energy change over the revolution
    E, _ = energy_terms(res, cm, model_module.BODIES)
    work = np.trapezoid(tau * w, res.time) if hasattr(np, "trapezoid") else np.trapz(tau * w, res.time)
    assert abs(work - (E[-1] - E[0])) < 1e-4 * amplitude
    # outputs of the example: relative slider travels (C0-C, E-C) are periodic
    for out in ("relC0C.s_rel", "relEC.s_rel"):
        s = res[out]
        assert abs(s[-1] - s[0]) < 1e-9 and np.ptp(s) > 5e-3
    assert np.max(np.abs(res["relC0C.s_rel"] - res["sDS1.xG1"])) < 1e-12
    # all five sliders have a travel range (Ebert 2015, Bild 7.4), the DSD's
    # the range of its own travel xG (the guide runs from its pivot P1)
    from acausal2d.analysis.slider_ranges import slider_ranges
    ranges = {r.name: r for r in slider_ranges(res)}
    assert sorted(ranges) == ["dSD1", "sDS1[1]", "sDS1[2]", "sSD1[1]", "sSD1[2]"]
    xG = res["dSD1.xG"]
    assert abs(ranges["dSD1"].s_min - np.min(xG)) < 1e-9
    assert abs(ranges["dSD1"].s_max - np.max(xG)) < 1e-9 and ranges["dSD1"].stroke > 5e-3


def test_force_driven_conserves_energy(model_module):
    cls = model_module.EightLinkVDI2729
    cm = acausal2d.compile_model(cls(drive="force"))
    res = cm.simulate(stop_time=2.0, rtol=1e-10, output_times=np.linspace(0.0, 2.0, 201))
    E, _ = energy_terms(res, cm, model_module.BODIES)
    Jf = res.parameters["flywheel.J"]
    E = E + 0.5 * Jf * series(res, cm, "flywheel.w") ** 2
    assert res["dAN1.omL"][0] == pytest.approx(1.5, abs=1e-12)
    assert np.max(np.abs(E - E[0])) < 1e-6 * abs(E[0])
    assert res["dAN1.phiL"][-1] > 2.0                         # keeps turning


def test_power_of_inertia_forces_is_the_kinetic_energy_rate(model_module):
    """Seed A.30, A.31 as element outputs P_T<key>, P_R<key>: for every body
    of the mechanism they equal m (v . a) and J w alpha computed here from
    the centre-of-gravity motion and the mass data, and their sum the rate
    of the kinetic energy; with gravity's power, the drive power (as a
    torque, to 1e-6 of its amplitude, as the power balance above)."""
    cls = model_module.EightLinkVDI2729
    cm = acausal2d.compile_model(cls())
    T = model_module.PERIOD
    res = cm.simulate(stop_time=T, rtol=1e-10, output_times=np.linspace(0.0, T, 181))
    total = np.zeros(len(res.time))
    for elem, mname, jname, xs, ys, ang in model_module.BODIES:
        key = mname[1:]
        m = res.parameters["%s.%s" % (elem, mname)]
        J = res.parameters["%s.%s" % (elem, jname)]
        vx, vy = (series(res, cm, "%s.%s" % (elem, v), 1) for v in (xs, ys))
        ax, ay = (series(res, cm, "%s.%s" % (elem, v), 2) for v in (xs, ys))
        w, al = (series(res, cm, "%s.%s" % (elem, ang), k) for k in (1, 2))
        P_T, P_R = (series(res, cm, "%s.P_%s%s" % (elem, kind, key)) for kind in "TR")
        # P_T, P_R are evaluated from the same derivative nodes: rounding only
        scale = max(m * np.max(np.hypot(vx, vy) * np.hypot(ax, ay))
                    + J * np.max(np.abs(w * al)), 1e-12)
        assert np.max(np.abs(P_T - m * (vx * ax + vy * ay))) <= 1e-9 * scale
        assert np.max(np.abs(P_R - J * w * al)) <= 1e-9 * scale
        total += P_T + P_R
    _, dE = energy_terms(res, cm, model_module.BODIES)
    _, dE_kin = energy_terms(res, cm, model_module.BODIES, g=(0.0, 0.0))
    tau, w = res["preset1.tau"], res["preset1.w"]
    amplitude = np.max(np.abs(tau))
    assert np.max(np.abs(total - dE_kin)) <= 1e-9 * amplitude * 1.5
    # drive power = power of the inertia forces + power against gravity
    assert np.max(np.abs(tau - (total + dE - dE_kin) / w)) < 1e-6 * amplitude
