"""The mode page (issue 21) in headless Chromium: it draws the first mode,
and its selector switches to the second mode, whose shape looks different.
Uses the DevTools helpers of test_animation.py; needs /usr/bin/chromium."""
import acausal2d
from acausal2d.io.loader import load_model
from acausal2d.visual.mode_page import render_mode_page, write_mode_page

from test_animation import (ARTIFACTS, DevTools, Page, assert_canvas_drawn, assert_differ,
                            console_errors, require_chromium)

WAIT_FRAME = """new Promise((resolve, reject) => {
  const t0 = Date.now();
  (function poll() {
    const w = document.getElementById('mode-view').contentWindow;
    if (w && w.acausal2d && w.acausal2d.scene && w.acausal2d.scene.title.includes(%r)) {
      w.acausal2d.pause(); w.acausal2d.setFrame(0);
      requestAnimationFrame(() => setTimeout(() => resolve(w.acausal2d.scene.title), 50));
    } else if (Date.now() - t0 > 10000) { reject(new Error('mode page did not load')); }
    else { setTimeout(poll, 20); }
  })();
})"""


def _double_pendulum_modes():
    cm = acausal2d.compile_model(load_model("models/double_pendulum.py"))
    return cm.modes(equilibrium=True)


def test_mode_page_holds_one_animation_per_mode():
    modes = _double_pendulum_modes()
    text = render_mode_page(modes)
    assert text.count('<option value=') == 2
    assert "mode 1: 0.458" in text and "mode 2: 0.7656" in text
    assert "http://" not in text and "https://" not in text


def test_mode_page_draws_and_switches_modes(tmp_path):
    require_chromium()
    ARTIFACTS.mkdir(exist_ok=True)
    path = write_mode_page(_double_pendulum_modes(), ARTIFACTS / "double_pendulum_modes.html")
    cdp = DevTools(tmp_path / "profile", ARTIFACTS / "chromium_modes.log")
    try:
        page = Page(cdp)
        page.open(path.resolve().as_uri())
        assert page.js("acausal2dModes.count") == 2
        title = page.js(WAIT_FRAME % "mode 1")
        assert "0.458 Hz" in title
        first = page.screenshot("modes_1.png")
        page.js("(() => { const s = document.getElementById('mode'); s.value = '1';"
                " s.dispatchEvent(new Event('change')); })()")
        title = page.js(WAIT_FRAME % "mode 2")
        assert "0.7656 Hz" in title and page.js("acausal2dModes.current") == 1
        second = page.screenshot("modes_2.png")
        assert_canvas_drawn(first, "mode 1")
        assert_canvas_drawn(second, "mode 2")
        assert_differ(first, second)
        assert page.js("document.getElementById('mode-view').contentWindow.acausal2d.errors") \
            == []
        assert console_errors(cdp.events) == []
    finally:
        cdp.close()
