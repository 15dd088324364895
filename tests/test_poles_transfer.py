"""Instantaneous poles, ratio, Drehschubstrecke (seed ch. 2.6, eq. 2.5-2.10)
and transfer functions of order 0..2 (eq. 2.2-2.4) against closed forms of
the four-bar, the eccentric slider-crank and the slotted crank
(Kurbelschleife)."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.analysis.poles import (cartesian, directed_ratio, kennedy, pole_homogeneous, poles,
                                      ratio, transfer, turn_slide)
from acausal2d.library.nodes import NodeModel, speed
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TURN = 2 * math.pi
TIMES = np.linspace(0.0, 1.0, 73)
A, E = 0.06, 0.06                      # crank length, guide offset [m]


class FourBar(NodeModel):
    """Crank A0A (0.06 m) at 1 turn/s, coupler AB, rocker B0B."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B0", 0.18, -0.06, base=True)
        self.node("A", 0, A, m=10)
        self.node("B", 0.12, 0.06)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("AB", "A", "B", len="const")
        self.n2("B0B", "B0", "B", len="const")


class SliderCrank(NodeModel):
    """Eccentric slider-crank: B slides on y = -E (guide from the fixed
    node G), crank 0.06 m at 1 turn/s, rod AB."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("G", -0.1, -E, base=True)
        self.node("A", 0, A, m=1)
        self.node("B", 0.18, -E, m=1)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("AB", "A", "B", len="const")
        self.n2("GB", "G", "B", ang="const")


class SlottedCrank(NodeModel):
    """Kurbelschleife: crank A0A (0.06 m) at 1 turn/s, A slides in the slot
    of the rocker B0A (B0 = (0.15, 0)), both its length and angle free."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.node("A0", 0, 0, base=True)
        self.node("B0", 0.15, 0, base=True)
        self.node("A", 0, A, m=1)
        self.n2("A0A", "A0", "A", len="const", ang=speed(TURN))
        self.n2("B0A", "B0", "A")


def run(model):
    return acausal2d.compile_model(model).simulate(output_times=TIMES, rtol=1e-10)


@pytest.fixture(scope="module")
def fourbar():
    return run(FourBar())


@pytest.fixture(scope="module")
def slider():
    return run(SliderCrank())


def _circle_intersection(p, rp, q, rq, near):
    """Intersection of two circles nearest to ``near`` (rows)."""
    d = q - p
    dist = np.hypot(d[:, 0], d[:, 1])
    a = (rp ** 2 - rq ** 2 + dist ** 2) / (2 * dist)
    h = np.sqrt(rp ** 2 - a ** 2)
    m = p + d * (a / dist)[:, None]
    off = np.column_stack([-d[:, 1], d[:, 0]]) * (h / dist)[:, None]
    c1, c2 = m + off, m - off
    pick = np.linalg.norm(c1 - near, axis=1) < np.linalg.norm(c2 - near, axis=1)
    return np.where(pick[:, None], c1, c2)


def _fourbar_closed(res):
    """Closed-form A, B and i_41-21 = a sin(th3 - th2) / (c sin(th3 - th4))."""
    phi = np.pi / 2 + TURN * res.time
    a_pt = A * np.column_stack([np.cos(phi), np.sin(phi)])
    b0 = np.tile([0.18, -0.06], (len(phi), 1))
    b, c = math.hypot(0.12, 0.0), math.hypot(0.06, 0.12)
    near = np.column_stack([res["B.x"], res["B.y"]])
    b_pt = _circle_intersection(a_pt, b, b0, c, near)
    th3 = np.arctan2(*(b_pt - a_pt).T[::-1])
    th4 = np.arctan2(*(b_pt - b0).T[::-1])
    i41 = A * np.sin(th3 - phi) / (c * np.sin(th3 - th4))
    return a_pt, b_pt, i41


LINKS = {"1": "ground", "2": "A0A", "3": "AB", "4": "B0B"}


def test_fourbar_poles_at_joints_are_the_joints(fourbar):
    a_pt, b_pt, _ = _fourbar_closed(fourbar)
    P = poles(fourbar, LINKS)
    assert np.abs(P[("1", "2")]).max() < 1e-12                     # A0 = origin
    assert np.abs(P[("2", "3")] - a_pt).max() < 1e-9
    assert np.abs(P[("3", "4")] - b_pt).max() < 1e-9
    assert np.abs(P[("1", "4")] - [0.18, -0.06]).max() < 1e-9


def test_fourbar_kennedy_poles_agree_with_velocity_poles(fourbar):
    """P13 and P24 constructed by Aronhold-Kennedy from the four joint
    poles equal the poles of the velocity fields; the three-pole lines hold."""
    joints = [("1", "2"), ("2", "3"), ("3", "4"), ("1", "4")]
    built = poles(fourbar, LINKS, joints=joints)
    direct = poles(fourbar, LINKS)
    for key in (("1", "3"), ("2", "4")):
        ok = np.isfinite(direct[key]).all(axis=1)
        assert ok.sum() > 60
        scale = 1 + np.linalg.norm(direct[key][ok], axis=1)
        assert (np.linalg.norm(built[key][ok] - direct[key][ok], axis=1) / scale).max() < 1e-8
    p12, p14, p24 = direct[("1", "2")], direct[("1", "4")], direct[("2", "4")]
    u, v = p14 - p12, p24 - p12
    cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    assert np.nanmax(np.abs(cross)) < 1e-10                        # collinear (Kennedy)


def test_fourbar_ratio_closed_form_and_pole_distances(fourbar):
    """i_41-21 = w4/w2 (eq. 2.5) against the closed form and against the
    directed pole distances 12-24 / 14-24."""
    _, _, i41 = _fourbar_closed(fourbar)
    i = ratio(fourbar, "B0B", "A0A")
    assert np.abs(i - i41).max() < 1e-9
    P = poles(fourbar, LINKS)
    from_poles = directed_ratio(P[("1", "2")], P[("1", "4")], P[("2", "4")])
    ok = np.isfinite(from_poles)
    assert np.abs(from_poles[ok] - i[ok]).max() < 1e-7
    assert (np.sign(i) > 0).any() and (np.sign(i) < 0).any()      # Gleichlauf and Gegenlauf


def _slider_closed(phi):
    """x_B and its derivatives by phi for B on y = -E (eccentric)."""
    l2 = 0.18 ** 2 + (A + E) ** 2
    h, h1, h2 = A * np.sin(phi) + E, A * np.cos(phi), -A * np.sin(phi)
    s = np.sqrt(l2 - h ** 2)
    s1 = -h * h1 / s
    s2 = -(h1 ** 2 + h * h2) / s - (h * h1) ** 2 / s ** 3
    return A * np.cos(phi) + s, -A * np.sin(phi) + s1, -A * np.cos(phi) + s2


def test_slider_crank_transfer_functions_to_1e9(slider):
    """q = x_B over the crank angle: q, q', q'' (eq. 2.2-2.4) from the run's
    derivatives against the closed forms, to 1e-9."""
    tf = transfer(slider, "B.x", "A0A.w")
    x, x1, x2 = _slider_closed(slider["A0A.w"])
    assert np.abs(tf[0] - x).max() < 1e-9
    assert np.abs(tf[1] - x1).max() < 1e-9
    assert np.abs(tf[2] - x2).max() < 1e-9
    assert np.abs(x2).max() > 0.05                               # not a trivial curve


def test_drehschubstrecke_slider_crank_is_pole_distance(slider):
    """r_41-21 = x_dot_41 / phi_dot_21 (eq. 2.8) = the closed-form q', and
    the directed pole distance 12-24 (pole 24 by Kennedy from 12, 23, 34 and
    14 at infinity)."""
    r = turn_slide(slider, "GB.r", "A0A")
    _, x1, _ = _slider_closed(slider["A0A.w"])
    assert np.abs(r - x1).max() < 1e-9
    links = {"1": "ground", "2": "A0A", "3": "AB", "4": ("B.x", "B.y", "GB.w")}
    P = poles(slider, links, joints=[("1", "2"), ("2", "3"), ("3", "4"), ("1", "4")])
    assert np.isnan(P[("1", "4")]).all()                            # prismatic: at infinity
    d = P[("2", "4")] - P[("1", "2")]
    along = -d[:, 1]                       # (k x d) . e with e = (1, 0), the guide
    ok = np.isfinite(along)
    assert ok.sum() > 60 and np.abs(along[ok] - r[ok]).max() < 1e-8


def test_diagonal_drehschubstrecke_slotted_crank():
    """Kurbelschleife: r_34-21 = x_dot_34 / phi_dot_21 (eq. 2.9) with x_34 the
    slide of A in the turning slot: d|B0A|/dphi = a d sin(phi) / |B0A|; the
    diagonal ratio i_41-21 of the rocker (eq. 2.5) against its closed form."""
    res = run(SlottedCrank())
    phi = res["A0A.w"]
    rho = np.sqrt(A ** 2 + 0.15 ** 2 - 2 * A * 0.15 * np.cos(phi))
    assert np.abs(turn_slide(res, "B0A.r", "A0A") - A * 0.15 * np.sin(phi) / rho).max() < 1e-9
    i41 = A * (A - 0.15 * np.cos(phi)) / rho ** 2                  # d(psi)/d(phi)
    assert np.abs(ratio(res, "B0A", "A0A") - i41).max() < 1e-9
    ad = A * 0.15
    rho1 = ad * np.sin(phi) / rho
    tf_r, tf_w = transfer(res, "B0A.r", "A0A.w"), transfer(res, "B0A.w", "A0A.w")
    assert np.abs(tf_r[2] - (ad * np.cos(phi) / rho - rho1 ** 2 / rho)).max() < 1e-9
    psi2 = ad * np.sin(phi) / rho ** 2 - 2 * A * (A - 0.15 * np.cos(phi)) * ad * np.sin(phi) \
        / rho ** 4
    assert np.abs(tf_w[1] - i41).max() < 1e-9 and np.abs(tf_w[2] - psi2).max() < 1e-9


def test_kennedy_line_intersection_closed_form():
    """Intersection of the line (0,0)-(1,1) with the line through (2,0) in
    direction (0,1) (a pole at infinity): (2, 2)."""
    h = lambda *v: np.array([v], dtype=float)
    p = kennedy(h(0, 0, 1), h(1, 1, 1), h(2, 0, 1), h(0, 1, 0))
    assert np.allclose(cartesian(p), [[2.0, 2.0]], atol=1e-14)


def test_absolute_pole_of_ground_and_missing_link(fourbar):
    assert np.isnan(cartesian(pole_homogeneous(fourbar, "ground", "ground"))).all()
    with pytest.raises(acausal2d.Acausal2dError, match="no link"):
        poles(fourbar, {"1": "ground", "2": "nothing"})
    with pytest.raises(acausal2d.Acausal2dError, match="orders are 0, 1 and 2"):
        transfer(fourbar, "B.x", "A0A.w", orders=(3,))


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "acausal2d"] + list(args), capture_output=True,
                          text=True, timeout=300, cwd=ROOT)


def test_cli_transfer_figure_and_pole_layer(tmp_path):
    """``--x DRIVE --transfer 0,1,2`` writes the transfer-function figure;
    ``--poles`` puts the poles on the layer "poles" of the page, at the
    joints where the seed's Bild 2.12 has them (P12 at A0, P23 at A)."""
    import json
    import re
    proc = _cli("simulate", "models/talk_mechanisms.py", "--model", "EccentricSliderCrank",
                "--plot", "B.x", "--x", "A0A.w", "--transfer", "0,1,2", "--poles",
                "1=ground,2=A0A,3=AB,4=B.x:B.y:AB0B.w", "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "transfer_B.x_over_A0A.w.png").stat().st_size > 10000
    page = (tmp_path / "animation.html").read_text()
    data = json.loads(re.search(r'id="acausal2d-data" type="application/json">(.*?)</script>',
                                page, re.S).group(1))
    poles = {s["text"]: s for s in data["shapes"] if s["type"] == "pole"}
    assert set(poles) == {"P12", "P13", "P14", "P23", "P24", "P34"}
    assert all(s["layer"] == "poles" for s in poles.values())
    sig = data["signals"]
    assert np.allclose(sig["pole P12.x"], 0, atol=1e-9) and np.allclose(sig["pole P12.y"], 0,
                                                                         atol=1e-9)
    p23 = np.array([sig["pole P23.x"], sig["pole P23.y"]])
    a = np.array([sig["A.x"], sig["A.y"]])
    assert np.abs(p23 - a).max() < 1e-6
    assert all(v is None for v in sig["pole P14.x"])               # at infinity: hidden


def test_cli_transfer_needs_x_and_valid_orders(tmp_path):
    proc = _cli("simulate", "models/talk_mechanisms.py", "--model", "EccentricSliderCrank",
                "--plot", "B.x", "--transfer", "0,1", "--out", str(tmp_path))
    assert proc.returncode == 2 and "--transfer needs --x DRIVE" in proc.stderr
    proc = _cli("simulate", "models/talk_mechanisms.py", "--model", "EccentricSliderCrank",
                "--plot", "B.x", "--x", "A0A.w", "--transfer", "3", "--out", str(tmp_path))
    assert proc.returncode == 2 and "--transfer takes orders 0, 1, 2" in proc.stderr
    proc = _cli("simulate", "models/talk_mechanisms.py", "--model", "EccentricSliderCrank",
                "--poles", "1=ground,2=crank", "--out", str(tmp_path))
    assert proc.returncode == 2 and "'crank' is no link of the result" in proc.stderr
    assert "simulated" not in proc.stdout                          # refused before the run
    proc = _cli("simulate", "models/talk_mechanisms.py", "--model", "EccentricSliderCrank",
                "--poles", "1=ground,A0A", "--out", str(tmp_path))
    assert proc.returncode == 2 and "--poles takes label=link pairs" in proc.stderr


def test_browser_pole_layer_is_drawn_and_hidden_by_its_check_box(tmp_path):
    """The page draws the poles (teal rings) and its "poles" check box hides them."""
    from test_animation import ARTIFACTS, DevTools, Page, require_chromium
    require_chromium()
    res = run(FourBar())
    path = res.animate(tmp_path / "poles.html", poles=LINKS)
    ARTIFACTS.mkdir(exist_ok=True)
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_cdp_poles.log")
    try:
        page = Page(cdp)
        page.open(path.resolve().as_uri() + "#frame=10")
        assert page.js("document.getElementById('layer-poles').checked") is True
        teal = np.array([0x16, 0xa0, 0x85]) / 255

        def teal_pixels(name):
            img = page.screenshot(name)[:540]
            return int(np.all(np.abs(img - teal) < 0.08, axis=2).sum())
        shown = teal_pixels("poles_on.png")
        page.js("var b = document.getElementById('layer-poles'); b.click(); b.checked")
        hidden = teal_pixels("poles_off.png")
        assert shown > 50 and hidden == 0, (shown, hidden)
        assert page.js("window.acausal2d.errors.length") == 0
    finally:
        cdp.close()


def test_vdi_fourbar_frames_rates_and_joint_points():
    """The VDI 2729 four-bar DDDD (frames of DAN and DDD, whose output frames
    the index reduction does not differentiate: their rates come from the
    total derivative of the equations, analysis/rates.py): the rates agree
    with the der() columns of the same links, the velocity poles lie at the
    joints, and with the joint points given the Kennedy poles agree."""
    from acausal2d.analysis.poles import derivative
    model = acausal2d.load_model(os.path.join(ROOT, "models", "four_link_mechanisms.py"), "DDDD")
    res = acausal2d.compile_model(model).simulate(output_times=np.linspace(0.01, 0.99, 50),
                                                  rtol=1e-10)
    assert "der(dyad.ctr2D3.x)" not in res.names
    assert np.abs(derivative(res, "dyad.ctr2D3.x") - res["der(crank.ctr2D2.x)"]).max() < 1e-9
    assert np.abs(derivative(res, "dyad.ctr2D3.phi", 2) - res["der(der(dyad.phiL1))"]).max() \
        < 1e-8
    links = {"1": "ground", "2": "crank.ctr2D2", "3": "dyad.ctr2D3", "4": "dyad.ctr2D4"}
    P = poles(res, links)
    b = np.column_stack([res["dyad.xP"], res["dyad.yP"]])
    a = np.column_stack([res["crank.ctr2D2.x"], res["crank.ctr2D2.y"]])
    assert np.abs(P[("3", "4")] - b).max() < 1e-8 and np.abs(P[("2", "3")] - a).max() < 1e-9
    assert np.abs(P[("1", "4")] - [0.4, 0.0]).max() < 1e-9
    joints = {("1", "2"): "crank.ctr2D1", ("2", "3"): "crank.ctr2D2",
              ("3", "4"): ("dyad.xP", "dyad.yP"), ("1", "4"): "dyad.ctr2D4"}
    built = poles(res, links, joints=joints)
    assert np.abs(built[("3", "4")] - b).max() < 1e-12
    for key in (("1", "3"), ("2", "4")):
        ok = np.isfinite(P[key]).all(axis=1)
        scale = 1 + np.linalg.norm(P[key][ok], axis=1)
        assert ok.sum() > 40
        assert (np.linalg.norm(built[key][ok] - P[key][ok], axis=1) / scale).max() < 1e-7
    i = ratio(res, "dyad.ctr2D4", "crank.ctr2D2")
    assert np.abs(i - res["der(dyad.phiL2)"] / TURN).max() < 1e-9
    assert np.abs(directed_ratio(built[("1", "2")], built[("1", "4")], built[("2", "4")]) - i) \
        .max() < 1e-7


def test_diagonal_ratio_is_pole_distance_ratio_on_the_collineation_axis(fourbar):
    """Eq. 2.6: i_34-21 = w_34 / w_21 = 12R / 34R with R the intersection of
    the line P12-P34 with the collineation axis k_14-23 (through P14, P23)."""
    P = poles(fourbar, LINKS)
    h = lambda p: np.column_stack([p, np.ones(len(p))])
    R = cartesian(kennedy(h(P[("1", "2")]), h(P[("3", "4")]), h(P[("1", "4")]),
                          h(P[("2", "3")])))
    i = ratio(fourbar, "AB", "A0A", ref="B0B", in_ref="ground")
    w = fourbar
    expected = (w["der(AB.w)"] - w["der(B0B.w)"]) / w["der(A0A.w)"]
    assert np.abs(i - expected).max() < 1e-12
    lam = directed_ratio(P[("1", "2")], P[("3", "4")], R)
    ok = np.isfinite(lam)
    assert ok.sum() > 60 and np.abs(lam[ok] - i[ok]).max() < 1e-9


def test_mec2_pole_view_is_the_intersection_of_crank_and_rocker_lines():
    """mec2's view {"show": "pole", "of": "b", "as": "trace"} (views_2.json,
    a four-bar driven at its coupler b) becomes a pole and its path (the
    fixed centrode) on the poles layer; the pole of the coupler is where
    the lines A0A and B0B cross.  The moving centrode (``ref``) stays
    listed as not drawn."""
    from acausal2d.visual.scene import build_scene
    model = acausal2d.load_model(os.path.join(ROOT, "tests", "data", "mec2",
                                              "views_2.json"))
    assert [v["link"] for v in model.pole_views] == ["b"]
    assert model.mec2_views_not_drawn == ["$.views[1] (trace of pole): no counterpart in the "
                                          "animation"]
    res = acausal2d.compile_model(model).simulate(rtol=1e-10)
    scene = build_scene(res)
    kinds = [(s["type"], s.get("layer")) for s in scene["shapes"] if s.get("layer")]
    assert kinds == [("pole", "poles"), ("trace", "poles")]
    p = np.column_stack([scene["signals"]["pole P(b).x"], scene["signals"]["pole P(b).y"]])
    a0, b0 = np.array([1.0, 0.5]), np.array([2.0, 0.5])
    a, b = (np.column_stack([res[n + ".x"], res[n + ".y"]]) for n in ("A", "B"))
    u, v = a - a0, b - b0
    den = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    s = ((b0 - a0)[0] * v[:, 1] - (b0 - a0)[1] * v[:, 0]) / den
    crossing = a0 + s[:, None] * u
    ok = np.abs(den) > 1e-3
    assert ok.sum() > 500 and np.abs(p[ok] - crossing[ok]).max() < 1e-9
    path = np.array(scene["signals"]["pole P(b) path.x"], dtype=float)
    assert_copied(path, p[:, 0])               # this centrode stays near the mechanism


class _SliderCrankPoleView(SliderCrank):
    pole_views = [{"link": "AB", "text": "P13", "trace": True}]


def test_pole_path_is_hidden_where_the_pole_runs_off():
    """The slider-crank rod's pole (crank line x vertical through B) goes to
    infinity where the crank stands vertical: its path is cut there (NaN),
    and kept where it lies within three times the mechanism's extent."""
    from acausal2d.visual.scene import build_scene
    res = run(_SliderCrankPoleView())
    sig = build_scene(res)["signals"]
    pole = np.column_stack([sig["pole P13.x"], sig["pole P13.y"]])
    path = np.column_stack([sig["pole P13 path.x"], sig["pole P13 path.y"]])
    kept = np.isfinite(path).all(axis=1)
    assert 0 < kept.sum() < len(kept) - 4
    assert_copied(path[kept], pole[kept])
    assert np.nanmax(np.abs(pole[~kept])) > 0.5                  # the mechanism spans 0.3 m
    assert np.abs(path[kept]).max() < 0.3 * 1.5 + 0.2
