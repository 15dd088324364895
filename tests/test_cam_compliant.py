"""Compliant (unilateral) cam contact: CamFollower(contact="compliant") on
the flat follower of models/cam_follower.py (CamFlatCompliant).

In contact the lift is s = L(t) - delta exactly (flat face on a support
function), so the penetration obeys the linear contact equation
M delta'' + d delta' + (k + K) delta = M (L'' + g) + F0 + K (L - R0), whose
periodic solution is the closed form below (its static limit is
delta = Fn/k).  Off the cam (Fn = 0) the follower swings on its spring under
gravity: s = s_eq + (s1 - s_eq) cos(w (t - t1)) + v1/w sin(w (t - t1)),
w = sqrt(K/M), s_eq = R0 - (M g + F0)/K."""
import math
import os
import sys

import numpy as np

import acausal2d

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import cam_follower as cf  # noqa: E402

G = 9.81
K_C, D_C = 1e7, 300.0            # CamFollower's defaults k_contact, d_contact


def _penetration(t, om):
    """Periodic solution delta(t), delta'(t) of the linear contact equation."""
    A = cf.M * G + cf.F0 + cf.K_SPRING * cf.H / 2
    B = cf.M * cf.H / 2 * om ** 2 - cf.K_SPRING * cf.H / 2
    Z = B / (K_C + cf.K_SPRING - cf.M * om ** 2 + 1j * D_C * om)
    e = np.exp(1j * om * t)
    return A / (K_C + cf.K_SPRING) + np.real(Z * e), np.real(1j * om * Z * e)


def test_defaults_are_the_documented_ones():
    cam = cf.CamFlatCompliant().cam
    assert (cam.k_contact, cam.d_contact) == (K_C, D_C)


def test_slow_cam_penetration_and_force_against_the_closed_form():
    """One turn per second: the follower stays on the cam; the penetration
    and the contact force match the closed form to 1e-6 relative (after the
    start transient, damped as exp(-d t/(2M)) = exp(-300 t)), the lift is
    the design law minus the penetration (1e-12 m), which is the static
    Fn/k to 1.2e-4 (the spring's, inertia's and damper's shares)."""
    res = acausal2d.simulate(cf.CamFlatCompliant(), stop_time=0.5, intervals=100, rtol=1e-10)
    t = res.time
    delta, rate = _penetration(t, cf.OM)
    law = np.array([cf.harmonic_lift(th) for th in res["drive.phi"]])
    late = t >= 0.05
    assert np.max(np.abs(res["cam.delta"] - delta)[late] / delta[late]) < 1e-6
    Fn = K_C * delta + D_C * rate
    assert np.max(np.abs(res["cam.Fn"] - Fn)[late] / Fn[late]) < 1e-6
    assert np.max(np.abs(law - res["guide.s"] - res["cam.delta"])) < 1e-12
    assert np.max(np.abs(law - res["guide.s"])) < 1.01 * np.max(Fn) / K_C
    F_static = cf.M * (cf.H / 2 * cf.OM ** 2 * np.cos(cf.OM * t) + G) + cf.F0 \
        + cf.K_SPRING * (law - cf.R0)
    static = np.abs(res["cam.delta"] - F_static / K_C)[late] / delta[late]
    assert 1e-5 < np.max(static) < 1.2e-4
    assert res.events == [] and np.all(res["cam.lifted"] == 0)


def test_fast_cam_lifts_off_and_flies_free():
    """100 rad/s: lift-off within the contact time scale sqrt(M/k) of the
    rigid model's t* (closed form), free flight on the spring to 1e-6 of
    the closed form (measured 4e-11 m), re-contact, Fn >= 0 throughout."""
    om = 100.0
    compiled = acausal2d.compile_model(cf.CamFlatCompliant())
    res = compiled.simulate(stop_time=0.08, intervals=400, rtol=1e-10, params={"drive.om": om})
    changes = compiled.model.cam.contact_changes(res)
    assert [c[1] for c in changes[:2]] == ["lift-off", "re-contact"]
    (t1, _), (t2, _) = changes[:2]
    c = -(cf.K_SPRING * cf.H / 2 + cf.F0 + cf.M * G) / (cf.M * cf.H / 2 * om ** 2
                                                       - cf.K_SPRING * cf.H / 2)
    t_star = math.acos(c) / om
    assert 0 < t1 - t_star < math.sqrt(cf.M / K_C)
    texts = [text for t, text in res.events if t in (t1, t2)]
    assert texts == ["cam.delta <= 0", "cam.delta <= 0"]
    t = res.time
    k1 = np.nonzero(t == t1)[0][-1]
    s1, v1 = res["guide.s"][k1], res["guide.v"][k1]
    w, s_eq = math.sqrt(cf.K_SPRING / cf.M), cf.R0 - (cf.M * G + cf.F0) / cf.K_SPRING
    flight = (t >= t1) & (t <= t2)
    tau = t[flight] - t1
    free = s_eq + (s1 - s_eq) * np.cos(w * tau) + v1 / w * np.sin(w * tau)
    assert np.sum(flight) > 100 and np.ptp(free) > 0.01
    assert np.max(np.abs(res["guide.s"][flight] - free)) < 1e-6 * np.ptp(free)
    inner = flight & (t > t1) & (t < t2)
    assert np.all(res["cam.Fn"][inner] == 0) and np.max(res["cam.delta"][inner]) < 1e-15
    Fn = res["cam.Fn"]
    assert np.min(Fn) >= -1e-12 * np.max(Fn)


def test_compliant_contact_is_a_force_element_in_eq_2_1():
    """The follower keeps its freedom: F = 3(3-1) - 2 - 2 = 2."""
    from acausal2d.analysis.check import check
    assert check(cf.CamFlatCompliant()).grubler == 2


def test_lift_off_and_re_contact_from_the_cli(tmp_path, capsys):
    from acausal2d import cli
    code = cli.main(["simulate", os.path.join(ROOT, "models", "cam_follower.py"), "--model",
                     "CamFlatCompliant", "--set", "drive.om=100", "--stop-time", "0.08",
                     "--out", str(tmp_path)])
    out = capsys.readouterr().out
    assert code == 0
    assert "CamFollower 'cam': touching without force -> lifted off at t = 0.01914452 s" \
        in out                                                        # lift-off
    assert "CamFollower 'cam': lifted off -> in contact at t = 0.07329789 s" in out   # re-contact
    assert (tmp_path / "penetration.png").exists() and (tmp_path / "lift.png").exists()


def test_compliant_roller_penetration_is_the_distance_to_the_eccentric_circle():
    """Roller (radius RR) on the eccentric circle (radius RC, centre C at E
    on the cam's x axis), started pressed in and moving with the cam (no
    impact): delta = RC + RR - |B - C| from the positions alone (1e-12 m);
    it stays on the cam (0 < delta < 2e-6 m)."""
    from acausal2d import start
    from acausal2d.library.belt import SupportContour
    from acausal2d.library.planar.cam import CamFollower

    class RollerCompliant(cf._Cam):
        y0 = cf.eccentric_lift(0.0)

        def __init__(self, **kw):
            super().__init__(**kw)
            self._build(CamFollower(SupportContour(cf.RC, a=(cf.E,), b=(0.0,)), r_roller=cf.RR,
                                    contact="compliant", q=start(math.pi / 2)),
                        s_start=self.y0 - 1e-6, v_start=cf.E * cf.OM)

    res = acausal2d.simulate(RollerCompliant(), stop_time=0.5, intervals=50, rtol=1e-10)
    th = res["drive.phi"]
    gap = np.hypot(0.0 - cf.E * np.cos(th), res["guide.s"] - cf.E * np.sin(th))
    assert np.max(np.abs(res["cam.delta"] - (cf.RC + cf.RR - gap))) < 1e-12
    assert 0 < np.min(res["cam.delta"]) and np.max(res["cam.delta"]) < 2e-6
    law = np.array([cf.eccentric_lift(x) for x in th])
    assert np.max(np.abs(res["guide.s"] - law)) < 2e-6
