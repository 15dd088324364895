"""Drag mode of a node model's animation page in headless Chromium (the
browser is driven as in tests/test_animation.py: /usr/bin/chromium over the
DevTools pipe; without it the test fails).  A node of the talk's four-bar
is grabbed and moved with simulated mouse events; the page corrects the
positions by eq. 3-16 in its own script."""
import math
import os

import numpy as np
import pytest

import acausal2d
from acausal2d.library.nodes.correction import PositionCorrection
from conftest import load_model_class
from test_animation import (ARTIFACTS, DevTools, Page, assert_canvas_drawn, assert_differ,
                            console_errors, require_chromium)


@pytest.fixture(scope="module")
def four_bar_page():
    ARTIFACTS.mkdir(exist_ok=True)
    model = load_model_class("talk_mechanisms.py", "FourBar")()
    res = acausal2d.simulate(model, intervals=120)
    return res.animate(ARTIFACTS / "four_bar_drag.html"), model


def test_dragging_a_node_keeps_the_link_lengths(four_bar_page, tmp_path):
    page, model = four_bar_page
    system = model.node_system()
    lentol = system["lentol"]
    nominal = {c["id"]: c["len"]["value"] for c in system["constraints"]}
    require_chromium()
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_drag_cdp.log")
    try:
        page_tab = Page(cdp)
        js, screenshot, mouse = page_tab.js, page_tab.screenshot, page_tab.mouse
        page_tab.open(page.resolve().as_uri())
        before = screenshot("drag_before.png")
        assert_canvas_drawn(before, "before dragging")

        # switch the drag mode on with a real click on its check box
        box = js("(() => { const r = document.getElementById('drag').getBoundingClientRect();"
                 " return [r.left + r.width / 2, r.top + r.height / 2]; })()")
        mouse("mousePressed", *box)
        mouse("mouseReleased", *box, buttons=0)
        assert js("acausal2d.drag.active") is True
        start = js("acausal2d.drag.positions()")

        # grab B and pull it 60 px left and 50 px down in ten moves
        x, y = js("(() => { const p = acausal2d.drag.screenOf('B'),"
                  " r = acausal2d.canvas.getBoundingClientRect();"
                  " return [p[0] + r.left, p[1] + r.top]; })()")
        mouse("mouseMoved", x, y, buttons=0)
        mouse("mousePressed", x, y)
        for k in range(1, 11):
            mouse("mouseMoved", x - 6 * k, y + 5 * k)
            assert js("acausal2d.drag.last.converged") is True
        mouse("mouseReleased", x - 60, y + 50, buttons=0)
        after = screenshot("drag_after.png")

        pos = js("acausal2d.drag.positions()")
        moved = math.hypot(pos["B"][0] - start["B"][0], pos["B"][1] - start["B"][1])
        assert moved > 0.01                               # B followed the hand (m)
        assert math.hypot(pos["A"][0] - start["A"][0], pos["A"][1] - start["A"][1]) > 0.005
        assert pos["A0"] == start["A0"] and pos["B0"] == start["B0"]   # base nodes stay
        lengths = js("acausal2d.drag.lengths()")
        for cid, value in nominal.items():
            assert abs(lengths[cid] - value) <= lentol, (cid, lengths[cid], value)
        # the same lengths recomputed here from the returned positions
        for cid, (a, b) in {"A0A": ("A0", "A"), "AB": ("A", "B"), "B0B": ("B0", "B")}.items():
            length = math.dist(pos[a], pos[b])
            assert abs(length - nominal[cid]) <= lentol
        assert_canvas_drawn(after, "after dragging")
        assert_differ(before, after)

        # leaving the drag mode shows the simulation's frame again
        js("acausal2d.drag.disable()")
        again = screenshot("drag_off.png")
        assert np.count_nonzero(np.max(np.abs(again[:540] - before[:540]), axis=2) > 0.15) == 0
        assert js("acausal2d.errors") == []
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()


def _kinds_model():
    from test_nodes import Kinds
    return Kinds()


PAGES = {   # model, node moved, displacement (m)
    "bobillier": (lambda: load_model_class("talk_mechanisms.py", "Bobillier")(), "A",
                  (-0.004, -0.001)),
    "rack_and_pinion": (lambda: acausal2d.load_model(
        os.path.join(os.path.dirname(os.path.dirname(__file__)), "models", "mec2",
                     "rack_and_pinion.json")), "R", (0.02, 0.005)),
    "kinds": (_kinds_model, "P", (-0.1, 0.2)),
}


def test_the_page_corrects_exactly_as_the_python_solver(tmp_path):
    """The page's eq. 3-16 and library/node_correction.py are one algorithm:
    for models with three-node angles, references of free constraints,
    mec2's cross-type references, delta and ratio couplings, one drag step
    in the page gives the Python solver's sweep count and positions."""
    require_chromium()
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_drag2_cdp.log")
    try:
        tab = Page(cdp)
        js = tab.js
        for name, (build, node, (dx, dy)) in PAGES.items():
            model = build()
            page = acausal2d.simulate(model, intervals=20).animate(
                ARTIFACTS / ("drag_%s.html" % name))
            tab.open(page.resolve().as_uri())
            js("acausal2d.drag.enable()")
            start = js("acausal2d.drag.positions()")
            solver = PositionCorrection(model.node_system(drives=False))
            for nid, (x, y) in start.items():
                solver.set_position(nid, x, y)
            for c in solver.cstrs:
                if c["type"] == "n2":
                    c["wu"] = math.atan2(*reversed(solver.vector(c)))
            x, y = start[node][0] + dx, start[node][1] + dy
            report = js("acausal2d.drag.move(%r, %r, %r)" % (node, x, y))
            solver.set_position(node, x, y)
            expected = solver.correct()
            assert report["converged"] and expected.converged, name
            assert report["iterations"] == expected.iterations > 1, name
            pos = js("acausal2d.drag.positions()")
            for nid, (px, py) in solver.positions().items():
                assert abs(pos[nid][0] - px) < 1e-12 and abs(pos[nid][1] - py) < 1e-12, \
                    (name, nid)
            assert js("acausal2d.errors") == []
    finally:
        cdp.close()
