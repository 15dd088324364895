"""The five PlanarMechanics references of issue 14 (SpringDemo,
SpringDamperDemo, PendulumExcited, InvertedCraneCrab, MeasureDemo) through
the command line: ``acausal2d simulate`` at the model's default settings
(its experiment has the reference's output grid), then ``acausal2d
compare`` against the embedded reference points in the absolute 2e-3 tube
(the Modelica Standard Library's regression tube, references README).

MeasureDemo's rates are compared up to 9.3 s: near 9.5 s the reference
itself is off by more than the tube, which
test_measure_demo_reference_rates_are_marginal_late shows against an
independent solution (minimal coordinates, DOP853)."""
import csv
import os

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import acausal2d
from acausal2d import cli
from conftest import load_model_class, ROOT, same_time
from reference_data_planar import REFERENCES

TUBE = 2e-3
MODELS = os.path.join(ROOT, "models", "planar_examples.py")
BODY_MAP = {"body.r[1]": "body.x", "body.r[2]": "body.y", "body.v[1]": "body.vx",
            "body.v[2]": "body.vy"}
MEASURE_RATES_UNTIL = 9.3

# (model, reference column -> our name, [(columns, last time compared)])
CASES = [
    ("SpringDemo", {}, None),
    ("SpringDamperDemo", BODY_MAP, None),
    ("PendulumExcited", {}, None),
    ("InvertedCraneCrab", {}, None),
    ("MeasureDemo", {}, [(("body1.phi", "revolute2.phi"), 10.0),
                         (("body1.w", "revolute2.w"), MEASURE_RATES_UNTIL)]),
]


def _write_reference(path, name, columns, t_max):
    """The embedded reference points of ``columns`` up to ``t_max`` as a
    Dymola-style CSV (quoted header, event rows kept)."""
    ref = REFERENCES[name]
    idx = [ref["columns"].index(c) for c in columns]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh, quoting=csv.QUOTE_NONNUMERIC)
        w.writerow(["Time"] + list(columns))
        rows = [r for r in ref["rows"] if r[0] <= t_max]
        for r in rows:
            w.writerow([r[0]] + [r[i] for i in idx])
    return len(rows)


@pytest.mark.parametrize("name,mapping,parts", CASES, ids=[c[0] for c in CASES])
def test_cli_reproduces_reference(tmp_path, capfd, name, mapping, parts):
    out = tmp_path / "out"
    assert cli.main(["simulate", MODELS, "--model", name, "--out", str(out)]) == 0
    if parts is None:
        parts = [(tuple(REFERENCES[name]["columns"][1:]), np.inf)]
    for k, (columns, t_max) in enumerate(parts):
        ref_csv = tmp_path / ("reference%d.csv" % k)
        assert _write_reference(ref_csv, name, columns, t_max) >= 90
        args = ["compare", str(out / "result.csv"), str(ref_csv), "--abs-tol", str(TUBE)]
        for ref_name, ours in mapping.items():
            args += ["--map", "%s=%s" % (ref_name, ours)]
        code = cli.main(args)
        report = capfd.readouterr().out
        assert code == 0, report
        cmp = acausal2d.compare(str(out / "result.csv"), str(ref_csv), mapping=mapping or None,
                                abs_tol=TUBE)
        assert len(cmp.rows) == len(columns)
        for row in cmp.rows:
            assert row.max_deviation < TUBE, row


def test_inverted_crane_crab_reference_event_rows():
    """The reference holds t = 0.5 s twice (the ramp's time event); our
    result has the event there too, and the left and right rows agree with
    both reference rows (positions and velocities are continuous)."""
    cls = load_model_class("planar_examples.py", "InvertedCraneCrab")
    res = acausal2d.simulate(cls())
    assert [t for t, _ in res.events] == [pytest.approx(0.5, abs=1e-12)]
    k = np.nonzero(same_time(res.time, 0.5))[0]
    assert len(k) == 2
    ref = [r for r in REFERENCES["InvertedCraneCrab"]["rows"] if same_time(r[0], 0.5)]
    assert len(ref) == 2
    for j, col in enumerate(("body.phi", "prismatic.s", "prismatic.v"), start=1):
        for i, r in zip(k, ref):
            assert abs(res[col][i] - r[j]) < 1e-5


# --------------------------------------------------------------------------
# MeasureDemo: an independent solution in minimal coordinates

M1, I1, M2, I2, L2, G = 1.0, 0.1, 0.4, 0.02, 0.4, 9.81


def _measure_demo_rhs(t, x):
    """Double pendulum of MeasureDemo in the absolute angles a (inner arm,
    = revolute1.phi) and b (outer arm, = body1.phi), Lagrange's equations."""
    a, b, wa, wb = x
    c, s = np.cos(b - a), np.sin(b - a)
    M = np.array([[M1 + I1 + M2, L2 * M2 * c], [L2 * M2 * c, L2 ** 2 * M2 + I2]])
    rhs = np.array([L2 * M2 * s * wb ** 2 - G * (M1 + M2) * np.cos(a),
                    -L2 * M2 * s * wa ** 2 - G * M2 * L2 * np.cos(b)])
    return [wa, wb, *np.linalg.solve(M, rhs)]


def _measure_demo_exact(times):
    sol = solve_ivp(_measure_demo_rhs, (0.0, times[-1]), [0.0, 0.0, 0.0, 0.0], method="DOP853",
                    rtol=1e-13, atol=1e-13, t_eval=times)
    a, b, wa, wb = sol.y
    return {"body1.phi": b, "body1.w": wb, "revolute2.phi": b - a, "revolute2.w": wb - wa}


def _measure_demo_energy(a, b, wa, wb):
    vq2 = wa ** 2 + L2 ** 2 * wb ** 2 + 2 * L2 * wa * wb * np.cos(b - a)
    return (0.5 * (M1 + I1) * wa ** 2 + 0.5 * M2 * vq2 + 0.5 * I2 * wb ** 2
            + G * (M1 * np.sin(a) + M2 * (np.sin(a) + L2 * np.sin(b))))


def test_measure_demo_reference_rates_are_marginal_late():
    """Why MeasureDemo's rates are compared up to 9.3 s only: our solution
    agrees with an independent one (minimal coordinates, DOP853 at rtol
    1e-13) over the whole run, and both keep the energy 0; the reference
    loses 2e-4 J, and in this chaotic motion its rates drift from the exact
    solution by more than the 2e-3 tube near t = 9.5 s, while its angles
    stay within 4e-4 rad and its rates within 1.1e-3 up to 9.3 s."""
    data = np.array(REFERENCES["MeasureDemo"]["rows"])
    cols = REFERENCES["MeasureDemo"]["columns"]
    times = np.unique(data[:, 0])
    exact = _measure_demo_exact(times)
    cls = load_model_class("planar_examples.py", "MeasureDemo")
    ours = acausal2d.simulate(cls(), output_times=times, rtol=1e-10)
    for name in exact:
        assert np.max(np.abs(ours[name] - exact[name])) < 2e-5, name
    a = ours["body1.phi"] - ours["revolute2.phi"]
    e_ours = _measure_demo_energy(a, ours["body1.phi"], ours["body1.w"] - ours["revolute2.w"],
                                  ours["body1.w"])
    assert np.max(np.abs(e_ours)) < 1e-6
    ref = {c: data[:, k] for k, c in enumerate(cols)}
    e_ref = _measure_demo_energy(ref["body1.phi"] - ref["revolute2.phi"], ref["body1.phi"],
                                 ref["body1.w"] - ref["revolute2.w"], ref["body1.w"])
    assert np.max(np.abs(e_ref)) > 1e-4
    dev = {c: np.abs(np.interp(data[:, 0], times, exact[c]) - ref[c]) for c in exact}
    early = data[:, 0] <= MEASURE_RATES_UNTIL
    for c in ("body1.phi", "revolute2.phi"):
        assert dev[c].max() < 4e-4, c
    for c in ("body1.w", "revolute2.w"):
        assert dev[c][early].max() < 1.1e-3, c
    assert dev["revolute2.w"][~early].max() > TUBE


def test_measure_demo_sensors_match_definitions():
    """The sensor outputs of MeasureDemo against the README's expected
    values from the joint motion (to 1e-9)."""
    cls = load_model_class("planar_examples.py", "MeasureDemo")
    res = acausal2d.simulate(cls(), stop_time=3.0, rtol=1e-9)
    phi, w2 = res["body1.phi"], res["revolute2.w"]
    expected = {"relativePosition.r_rel_x.u": 0.4 * np.cos(phi),
                "relativePosition.r_rel_y.u": 0.4 * np.sin(phi),
                "relativeVelocity.v_rel_x.u": 0.0 * phi,
                "relativeVelocity.v_rel_y.u": 0.4 * w2,
                "relativeVelocity.w_rel.u": w2,
                "absolutePosition.phi.u": phi,
                "absoluteVelocity.w.u": res["body1.w"]}
    for name, value in expected.items():
        assert np.max(np.abs(res[name] - value)) < 1e-9, name
