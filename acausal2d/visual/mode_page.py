"""The mode page: each mode shape animated around the operating point.

Every mode becomes a result of one oscillation cycle, z(theta) = z0 +
a Re(dz/dx v e^(i theta)) for theta over one turn (all node values move
along their sensitivities, eliminated aliases with them), drawn by the
animation page's own scene code (:func:`acausal2d.visual.scene.build_scene`,
:func:`acausal2d.visual.animation.render_html`).  The page holds one
animation page per mode and a mode selector (``id="mode"``) that shows the
chosen one in the frame ``id="mode-view"``; ``window.acausal2dModes``
exposes ``count``, ``current`` and ``select(k)`` for scripting and tests.
The amplitude ``a`` moves the point that moves most by
:data:`LENGTH_FRACTION` of the mechanism's size (a small pulley may turn
far then), or, where no point moves, turns the largest angle by
:data:`MAX_ANGLE`.
"""
import html
import json

import numpy as np

from ..analysis.linearize import signal_rows
from ..io.files import write_text
from ..result import Result
from .animation import render_html
from .scene import build_scene

FRAMES = 48
"""Frames of one animated oscillation cycle."""
CYCLE_TIME = 2.0
"""Seconds one cycle takes on the page at 1x speed."""
LENGTH_FRACTION = 0.06
MAX_ANGLE = 0.35


def _amplitude(compiled, z0, dz):
    """Scale of a mode's motion (see the module docstring)."""
    s = compiled.system
    names = s.node_names
    xy = [j for j, n in enumerate(names) if n.endswith((".x", ".y")) and
          s.structure.var_level[j] == 0]
    ang = [j for j, n in enumerate(names) if n.endswith(".phi") and s.structure.var_level[j] == 0]
    size = float(np.ptp(z0[xy])) if xy else 0.0
    if xy and np.max(np.abs(dz[xy])) > 1e-12:
        return LENGTH_FRACTION * (size if size > 0 else 1.0) / np.max(np.abs(dz[xy]))
    if ang and np.max(np.abs(dz[ang])) > 1e-12:
        return MAX_ANGLE / np.max(np.abs(dz[ang]))
    return 1.0


def mode_result(modes, k, frames=FRAMES):
    """A :class:`~acausal2d.result.Result` of one cycle of mode ``k``
    (its ``time`` runs over :data:`CYCLE_TIME`)."""
    lin = modes.linearization
    cm = lin.compiled
    s = cm.system
    dz = lin.dzdx @ modes.vectors[:, k]
    dominant = modes.modes[k]["dominant"]
    ref = (signal_rows(s, [dominant], lin.dzdx)[0] @ modes.vectors[:, k]) if dominant else 0.0
    dz = dz / ref if abs(ref) > 0 else dz        # the dominant motion real, as in the shape
    a = _amplitude(cm, lin.point.z, dz)
    theta = np.linspace(0.0, 2 * np.pi, frames + 1)
    Z = lin.point.z[None, :] + a * np.real(np.exp(1j * theta)[:, None] * dz[None, :])
    p = lin.point.p
    return Result(theta / (2 * np.pi) * CYCLE_TIME, s.node_names, Z,
                  s.alias_names + s.alias_der_names, s.alias_values(Z, p),
                  [name for name, *_ in s.parameters], p, model=cm)


def mode_title(modes, k):
    """'Model - mode k: f Hz, damping z' of mode k."""
    m = modes.modes[k]
    zeta = m["damping_ratio"] if abs(m["damping_ratio"]) > 1e-9 else 0.0
    return "%s - mode %d: %.4g Hz, damping ratio %.3g" % (
        type(modes.linearization.compiled.model).__name__, k + 1, m["frequency_hz"], zeta)


_PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><meta name="generator" content="acausal2d">
<title>%(title)s</title><link rel="icon" href="data:,">
<style>html,body{margin:0;height:100%%;font:14px sans-serif}
#top{padding:4px 8px;height:28px;box-sizing:border-box}
#mode-view{border:0;width:100%%;height:calc(100%% - 28px);display:block}</style></head>
<body><div id="top"><label>mode <select id="mode">%(options)s</select></label>
<span id="info">%(info)s</span></div>
<iframe id="mode-view" title="mode shape"></iframe>
<script id="acausal2d-modes" type="application/json">%(data)s</script>
<script>
(function () {
  var pages = JSON.parse(document.getElementById("acausal2d-modes").textContent);
  var select = document.getElementById("mode"), view = document.getElementById("mode-view");
  var api = {count: pages.length, current: -1, select: function (k) {
    k = Math.max(0, Math.min(pages.length - 1, k | 0));
    api.current = k; select.value = String(k);
    document.getElementById("info").textContent = pages[k].title;
    view.srcdoc = pages[k].html;
  }};
  select.addEventListener("change", function () { api.select(+select.value); });
  window.acausal2dModes = api;
  if (pages.length) api.select(0);
})();
</script></body></html>
"""


def render_mode_page(modes, autoplay=True):
    """The HTML text of the mode page (see the module docstring)."""
    pages, options = [], []
    for k in range(len(modes.modes)):
        title = mode_title(modes, k)
        scene = build_scene(mode_result(modes, k), title=title, autoplay=autoplay)
        pages.append({"title": title, "html": render_html(scene)})
        options.append('<option value="%d">%d: %.4g Hz</option>' % (
            k, k + 1, modes.modes[k]["frequency_hz"]))
    name = type(modes.linearization.compiled.model).__name__
    data = json.dumps(pages).replace("<", "\\u003c").replace(">", "\\u003e") \
        .replace("&", "\\u0026")
    info = "" if pages else "no oscillating modes"
    return _PAGE % {"title": html.escape(name + " modes"), "options": "".join(options),
                    "info": html.escape(info), "data": data}


def write_mode_page(modes, path, autoplay=True):
    """Write :func:`render_mode_page` to ``path``; returns the path."""
    write_text(path, render_mode_page(modes, autoplay))
    return path
