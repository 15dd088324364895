"""Velocity correction by impulses (the talk's eq. 6-10;
library/nodes/correction.py:PositionCorrection.correct_velocities): after
the correction the velocities satisfy J q' + C_t = 0 (eq. 4); the impulses
act along the constraints only (eq. 7), so the result is the projection
of the given velocities in the metric of the mass matrix, found here
independently by a linear solve, and the kinetic energy falls by exactly
the energy of the removed velocity part (no energy is added)."""
import numpy as np
import pytest

from acausal2d.errors import ModelDefinitionError
from acausal2d.library.nodes.correction import PositionCorrection
from conftest import load_model_class

TOL = 1e-12                     # m/s, the sweeps' stopping tolerance on |C'|


def _four_bar(ang_b0b="free"):
    """The talk's intro crank-rocker (A0, B0 base; A 2 kg, B 1 kg), the
    crank free: three length constraints, F = 1."""
    nodes = [{"id": "A0", "x": 0.0, "y": 0.0, "m": 1.0, "base": True},
             {"id": "A", "x": 0.0, "y": 0.05, "m": 2.0, "base": False},
             {"id": "B", "x": 0.18, "y": 0.11, "m": 1.0, "base": False},
             {"id": "B0", "x": 0.2, "y": 0.01, "m": 1.0, "base": True}]
    cstrs = []
    for cid, a, b in (("A0A", "A0", "A"), ("AB", "A", "B"), ("B0B", "B0", "B")):
        pa = next(n for n in nodes if n["id"] == a)
        pb = next(n for n in nodes if n["id"] == b)
        r = float(np.hypot(pb["x"] - pa["x"], pb["y"] - pa["y"]))
        cstrs.append({"id": cid, "type": "n2", "n1": a, "n2": b, "dir": 0,
                      "len": {"kind": "value", "value": r}, "ang": {"kind": "free"}})
    return {"nodes": nodes, "constraints": cstrs, "lentol": 1e-4, "itrmax": 256}


def _jacobian(system):
    """J (rows: the length constraints) and M over (A.x, A.y, B.x, B.y)."""
    pos = {n["id"]: np.array([n["x"], n["y"]]) for n in system["nodes"]}
    col = {"A": 0, "B": 2}
    J = np.zeros((3, 4))
    for i, c in enumerate(system["constraints"]):
        e = pos[c["n2"]] - pos[c["n1"]]
        e /= np.linalg.norm(e)
        for node, sign in ((c["n1"], -1.0), (c["n2"], 1.0)):
            if node in col:
                J[i, col[node]:col[node] + 2] += sign * e
    return J, np.diag([2.0, 2.0, 1.0, 1.0])


def _vector(v):
    return np.array([*v["A"], *v["B"]])


def test_velocities_after_correction_satisfy_the_constraints():
    """Arbitrary velocities of A and B: afterwards |J q'| <= TOL (eq. 4,
    C_t = 0), equal to the M-projection q' - W J^T (J W J^T)^-1 J q' (the
    sweeps converge to it; 1e-9 of the speeds covers the stopping
    tolerance amplified by the Jacobian's conditioning), and the kinetic
    energy falls by (dq')^T M dq'/2 (impulses along J^T: Pythagoras in the
    M metric)."""
    system = _four_bar()
    J, M = _jacobian(system)
    W = np.linalg.inv(M)
    given = {"A": (0.3, -0.1), "B": (-0.2, 0.4)}
    v, report = PositionCorrection(system).correct_velocities(given, tol=TOL)
    assert report.converged and report.largest <= TOL
    q0, q1 = _vector(given), _vector(v)
    assert np.max(np.abs(J @ q1)) <= 10 * TOL
    expected = q0 - W @ J.T @ np.linalg.solve(J @ W @ J.T, J @ q0)
    assert np.max(np.abs(q1 - expected)) <= 1e-9 * np.max(np.abs(q0))
    assert v["A0"] == pytest.approx((0.0, 0.0), abs=0.0)        # base nodes untouched
    kin = 0.5 * q0 @ M @ q0
    lost = 0.5 * (q0 - q1) @ M @ (q0 - q1)
    assert kin - 0.5 * q1 @ M @ q1 == pytest.approx(lost, rel=1e-9)
    assert 0.5 * q1 @ M @ q1 < kin


def test_consistent_velocities_are_kept():
    """Velocities already satisfying eq. 4 (a projection of arbitrary
    ones) pass unchanged, without energy loss, in one sweep."""
    system = _four_bar()
    J, M = _jacobian(system)
    W = np.linalg.inv(M)
    q = np.array([0.3, -0.1, -0.2, 0.4])
    q = q - W @ J.T @ np.linalg.solve(J @ W @ J.T, J @ q)
    given = {"A": tuple(q[:2]), "B": tuple(q[2:])}
    v, report = PositionCorrection(system).correct_velocities(given, tol=TOL)
    assert report.iterations == 1
    assert np.max(np.abs(_vector(v) - q)) <= 10 * TOL


def test_driven_constraint_rate_is_met():
    """The talk's crank-rocker with its crank angle driven: the angle row
    has C_t = -|A0A| w', so after the correction A moves with |A0A| w'
    normal to the crank (and not along it)."""
    model = load_model_class("talk_mechanisms.py", "IntroCrankRocker")()
    system = model.node_system()
    solver = PositionCorrection(system)
    w = 2.0
    v, report = solver.correct_velocities({"A": (0.0, 0.0), "B": (0.0, 0.0)},
                                          rates={("A0A", "ang"): w}, tol=TOL)
    assert report.converged
    r = 0.05                                                   # A0A along +y
    assert v["A"][0] == pytest.approx(-r * w, abs=10 * TOL)    # e~ = (-1, 0)
    assert v["A"][1] == pytest.approx(0.0, abs=10 * TOL)


def test_three_node_constraint_is_refused():
    system = _four_bar()
    system["constraints"].append({"id": "tri", "type": "n3", "n1": "A", "n2": "B", "n3": "B0",
                                  "value": 0.5})
    with pytest.raises(ModelDefinitionError, match="'tri'.*two-node"):
        PositionCorrection(system).correct_velocities({"A": (0.0, 0.0)})
