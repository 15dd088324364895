"""Cam contours for manufacturing (CSV, SVG, DXF) and for the analysis
elements, from a DB~SD synthesis (h = 0.05 + 0.02 sin(phi), K = -1)."""
import csv
import math
import os
import subprocess

import casadi as ca
import numpy as np
import pytest
from matplotlib import image as mpimg

from acausal2d import ModelDefinitionError
from acausal2d.library.synthesis.functional import BandStructure, synthesize
from acausal2d.library.synthesis.contour_export import (analysis_contour, cam_outline, export_contour,
                                              write_dxf)
from conftest import assert_copied

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--window-size=800,600"]


@pytest.fixture(scope="module")
def syn():
    s = BandStructure.dbsd((0, 0), (-0.296, 0), lambda p: 0.05 * p + 0.02 * (1 - ca.cos(p)),
                           -1, 0.25)
    return synthesize(s, np.linspace(0.0, 2.5, 251))


def _distance_to_polyline(px, py, x, y):
    """Distance of each point (px, py) to the closed polyline (x, y)."""
    ax, ay = x, y
    bx, by = np.roll(x, -1), np.roll(y, -1)
    dx, dy = bx - ax, by - ay
    t = np.clip(((px[:, None] - ax) * dx + (py[:, None] - ay) * dy) / (dx * dx + dy * dy), 0, 1)
    qx, qy = ax + t * dx, ay + t * dy
    return np.min(np.hypot(px[:, None] - qx, py[:, None] - qy), axis=1)


def test_outline_follows_the_contour(syn):
    """The arc vertices are exact contour points, every contour point
    (dense, between the vertices too) is within 1 micrometre of the outline,
    the outline is closed around the pivot and turns counter-clockwise."""
    out = cam_outline(syn, tol=1e-6)
    ax, ay = out.arc
    k = np.array([p == "arc" for p in out.part])
    v = syn.evaluate(out.phi[k])
    assert np.max(np.hypot(ax - v["x_u"], ay - v["y_u"])) < 1e-15
    dense = syn.evaluate(np.linspace(0.0, 2.5, 20001))
    assert np.max(_distance_to_polyline(dense["x_u"], dense["y_u"], out.x, out.y)) < 1e-6
    area = 0.5 * np.sum(out.x * np.roll(out.y, -1) - np.roll(out.x, -1) * out.y)
    assert area > 0
    # the pivot is inside: winding number 1
    ang = np.unwrap(np.arctan2(np.append(out.y, out.y[0]), np.append(out.x, out.x[0])))
    assert abs(ang[-1] - ang[0] - 2 * math.pi) < 1e-9
    # the hub (half the smallest lever arm) lies inside every band line
    assert out.hub_radius == pytest.approx(0.5 * syn.criteria["h"].min())
    with pytest.raises(ModelDefinitionError, match="hub_radius"):
        cam_outline(syn, hub_radius=0.2)


def test_dxf_round_trip(syn, tmp_path):
    """The DXF written with ezdxf and read back with ezdxf: a closed
    LWPOLYLINE in millimetres whose vertices are the outline's (to 1e-9 m),
    hence within 1e-6 m of the contour; the pivot marked on layer PIVOT."""
    import ezdxf
    out = cam_outline(syn)
    path = write_dxf(str(tmp_path / "cam.dxf"), out)
    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4
    polys = list(doc.modelspace().query("LWPOLYLINE"))
    assert len(polys) == 1 and polys[0].closed and polys[0].dxf.layer == "CONTOUR"
    pts = np.array([(p[0], p[1]) for p in polys[0].get_points("xy")]) * 1e-3
    assert pts.shape == (len(out.x), 2)
    assert np.max(np.hypot(pts[:, 0] - out.x, pts[:, 1] - out.y)) < 1e-9
    dense = syn.evaluate(np.linspace(0.0, 2.5, 5001))
    assert np.max(_distance_to_polyline(dense["x_u"], dense["y_u"], pts[:, 0], pts[:, 1])) < 1e-6
    pivot = list(doc.modelspace().query("POINT"))
    assert len(pivot) == 1
    assert_copied(tuple(pivot[0].dxf.location)[:2], (0.0, 0.0))
    assert pivot[0].dxf.layer == "PIVOT"
    circles = list(doc.modelspace().query("CIRCLE"))
    assert circles[0].dxf.radius == pytest.approx(out.hub_radius * 1e3)


def test_csv(syn, tmp_path):
    out = cam_outline(syn)
    paths = export_contour(syn, str(tmp_path), "cam")
    assert [os.path.basename(p) for p in paths] == ["cam.csv", "cam.svg", "cam.dxf"]
    assert sorted(os.listdir(tmp_path)) == ["cam.csv", "cam.dxf", "cam.svg"]   # no temporaries
    with open(paths[0]) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["part", "phi_rad", "x_m", "y_m"] and rows[1] == ["pivot", "", "0", "0"]
    xy = np.array([[float(r[2]), float(r[3])] for r in rows[2:]])
    assert_copied(xy, np.column_stack([out.x, out.y]))       # 17 digits
    arc = [r for r in rows[2:] if r[0] == "arc"]
    v = syn.evaluate([float(arc[7][1])])
    assert_copied([float(arc[7][2]), float(arc[7][3])], [v["x_u"][0], v["y_u"][0]])


def test_synthesis_table_csv(syn, tmp_path):
    """The functional synthesis as a table (involute, evolute, ch. 5
    quantities): the CSV reads back bit for bit, its evolute columns are
    the exact contour points at the grid's parameter values."""
    cols = syn.table()
    assert list(cols)[:8] == ["phi", "cam", "x_P3", "y_P3", "x_e", "y_e", "x_u", "y_u"]
    assert {"l_Bf", "S_Bf", "Z", "GF2", "a", "h", "rho_cam"} <= set(cols)
    path = syn.to_csv(str(tmp_path / "synthesis.csv"))
    with open(path) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == list(cols) and len(rows) == len(syn.phi) + 1
    data = np.array(rows[1:], dtype=float)
    for k, name in enumerate(cols):
        assert_copied(data[:, k], cols[name])
    v = syn.evaluate(data[[0, 100, -1], 0])
    assert_copied(v["x_u"], data[[0, 100, -1], 6])
    assert os.listdir(tmp_path) == ["synthesis.csv"]


def test_svg_draws_in_headless_chromium(syn, tmp_path):
    """The SVG opens in Chromium (headless screenshot, the suite's browser
    of tests/test_animation.py) and draws the filled contour, its outline
    and the red pivot cross."""
    if not os.path.exists(CHROMIUM):
        pytest.fail("%s not found: install Debian's chromium" % CHROMIUM)
    svg = export_contour(syn, str(tmp_path), "cam")[1]
    text = open(svg).read()
    assert 'width="' in text and 'mm"' in text and 'id="pivot"' in text
    png = tmp_path / "shot.png"
    proc = subprocess.run([CHROMIUM, *CHROMIUM_FLAGS, "--user-data-dir=%s" % (tmp_path / "u"),
                           "--screenshot=%s" % png, "file://" + svg],
                          stdin=subprocess.DEVNULL, capture_output=True, timeout=60)
    assert proc.returncode == 0 and png.exists(), proc.stderr.decode()[-2000:]
    img = mpimg.imread(str(png))[:, :, :3]

    def pixels(rgb, tol=0.08):
        return int(np.sum(np.all(np.abs(img - np.array(rgb) / 255.0) < tol, axis=2)))
    assert pixels((221, 230, 240), 0.02) > 5000        # fill
    assert pixels((31, 78, 121)) > 100                  # contour line
    assert pixels((192, 0, 0), 0.15) > 10               # pivot cross


def test_analysis_contour_is_the_arc(syn):
    """The closed polar contour for CurvedDrum/CurvedPulley equals the arc
    (radial error at and between the table points below 1e-7 m) and its
    polar angle range covers the arc."""
    ac = analysis_contour(syn, n_harm=200)
    assert ac.arc_error < 1e-7
    p = np.linspace(0.0, 2.5, 77)
    v = syn.evaluate(p)
    k = ac.kappa(p)
    assert np.min(k) >= ac.kappa_range[0] - 1e-12 and np.max(k) <= ac.kappa_range[1] + 1e-12
    x, y = ac.contour.point(k)
    assert np.max(np.hypot(x - v["x_u"], y - v["y_u"])) < 1e-7
    assert np.min(ac.contour.r(np.linspace(0, 2 * math.pi, 721))) > 0
