"""The talk's four-node constructions (parallel, parallel of equal length,
perpendicular, perpendicular bisector, angle bisector), each on its
defining property; the pole-triangle three-position synthesis against
closed-form circumcentres and poles; Kutzbach's speed diagram of a
planetary gear against Willis' equation."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")


def _run(file, name):
    model = acausal2d.load_model(os.path.join(MODELS, file), name)
    return acausal2d.compile_model(model).simulate(rtol=1e-10)


def _pt(res, nid):
    return np.column_stack([res[nid + ".x"], res[nid + ".y"]])


def _cross(u, v):
    return u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]


def _dot(u, v):
    return np.sum(u * v, axis=1)


@pytest.fixture(scope="module")
def cons():
    return _run("talk_constructions.py", "FourNodeConstructions")


def test_parallel_and_parallel_of_equal_length(cons):
    ab = _pt(cons, "B") - _pt(cons, "A")
    cdp = _pt(cons, "Dp") - _pt(cons, "C")
    assert np.abs(_cross(ab, cdp)).max() < 1e-12 and (_dot(ab, cdp) > 0).all()
    assert np.ptp(np.hypot(*cdp.T)) < 1e-12                        # its own length held
    assert np.abs(_pt(cons, "De") - _pt(cons, "C") - ab).max() < 1e-12
    turned = np.unwrap(cons["AB.w"])
    assert turned[-1] - turned[0] == pytest.approx(2 * math.pi, abs=1e-9)


def test_perpendicular_and_perpendicular_bisector(cons):
    a, b = _pt(cons, "A"), _pt(cons, "B")
    ab = b - a
    assert np.abs(_dot(ab, _pt(cons, "Do") - _pt(cons, "C"))).max() < 1e-12
    assert np.abs(_pt(cons, "Mb") - (a + b) / 2).max() < 1e-12
    db = _pt(cons, "Db")
    assert np.abs(np.hypot(*(db - a).T) - np.hypot(*(db - b).T)).max() < 1e-12  # |DA| = |DB|
    assert np.hypot(*(db - _pt(cons, "Mb")).T).min() > 0.03          # D is not the midpoint


def test_angle_bisector(cons):
    a = _pt(cons, "A")
    u, v, d = (_pt(cons, n) - a for n in ("B", "C", "Da"))
    first = np.arctan2(_cross(u, d), _dot(u, d))
    second = np.arctan2(_cross(d, v), _dot(d, v))
    assert np.abs(first - second).max() < 1e-12
    assert np.ptp(first) > 1.0                                     # the angle changes


def _circumcentre(p, q, r):
    """Closed form (rows)."""
    ax, ay, bx, by, cx, cy = p[:, 0], p[:, 1], q[:, 0], q[:, 1], r[:, 0], r[:, 1]
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    sa, sb, sc = ax ** 2 + ay ** 2, bx ** 2 + by ** 2, cx ** 2 + cy ** 2
    return np.column_stack([(sa * (by - cy) + sb * (cy - ay) + sc * (ay - by)) / d,
                            (sa * (cx - bx) + sb * (ax - cx) + sc * (bx - ax)) / d])


@pytest.fixture(scope="module")
def poles():
    return _run("talk_synthesis.py", "PoleTriangleSynthesis")


def test_pole_triangle_pivots_are_circumcentres(poles):
    A = [_pt(poles, "A%d" % i) for i in (1, 2, 3)]
    B = [_pt(poles, "B%d" % i) for i in (1, 2, 3)]
    assert np.abs(_pt(poles, "A0") - _circumcentre(*A)).max() < 1e-12
    assert np.abs(_pt(poles, "B0") - _circumcentre(*B)).max() < 1e-11
    assert np.ptp(poles["B0.x"]) > 0.01                            # B0 moves with position 3
    lengths = np.hypot(*(B[2] - A[2]).T)
    assert np.abs(lengths - 0.1).max() < 1e-12


def test_pole_triangle_poles_rotate_one_position_into_the_other(poles):
    """P_ij is the centre of the rotation taking A_iB_i to A_jB_j: turning
    A_i and B_i about P_ij by the coupler's change of angle gives A_j, B_j."""
    for i, j in ((1, 2), (1, 3), (2, 3)):
        ai, bi, aj, bj = (_pt(poles, "%s%d" % (p, k)) for p, k in (("A", i), ("B", i),
                                                                  ("A", j), ("B", j)))
        th = np.arctan2(*(bj - aj).T[::-1]) - np.arctan2(*(bi - ai).T[::-1])
        c, s = np.cos(th), np.sin(th)
        P = _pt(poles, "P%d%d" % (i, j))
        for x, y in ((ai, aj), (bi, bj)):
            d = x - P
            turned = P + np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]])
            assert np.abs(turned - y).max() < 1e-11


def test_speed_diagram_follows_willis():
    """Speeds read as lengths on y = h: the carrier's n_c and the planet's
    n_p against Willis' equation (n_s - n_c) / (n_r - n_c) = -r3 / r1 and
    the planet's omega_p = (r3 omega_r - r1 omega_s) / (r3 - r1)."""
    res = _run("talk_synthesis.py", "SpeedDiagram")
    r1, r3 = 0.030, 0.060
    ns, nr, nc, npl = (res[n + ".x"] for n in ("Ns", "Nr", "Nc", "Np"))
    assert np.ptp(ns) > 0.05 and np.abs(nr + 0.02).max() < 1e-12
    assert np.abs((ns - nc) + r3 / r1 * (nr - nc)).max() < 1e-12
    assert np.abs(nc - (r1 * ns + r3 * nr) / (r1 + r3)).max() < 1e-12
    assert np.abs(npl - (r3 * nr - r1 * ns) / (r3 - r1)).max() < 1e-12


@pytest.mark.parametrize("file,name,figures", [
    ("talk_constructions.py", "FourNodeConstructions", ["constructions.png"]),
    ("talk_synthesis.py", "PoleTriangleSynthesis", ["pivots.png", "pole_triangle.png",
                                                   "pole_triangle_synthesis.png"]),
    ("talk_synthesis.py", "SpeedDiagram", ["speeds.png"])])
def test_models_run_from_the_cli_with_figures(tmp_path, file, name, figures):
    proc = subprocess.run([sys.executable, "-m", "acausal2d", "simulate",
                           os.path.join(MODELS, file), "--model", name, "--out", str(tmp_path)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    for fig in figures + ["animation.html"]:
        assert (tmp_path / fig).stat().st_size > 5000
