"""Drawing a model diagram: SVG boxes with a symbol per kind of component,
lines coloured by domain (arrows on signals), the fate of every unconnected
connector, and the HTML page in which a sub-model's box opens its own
diagram.  The geometry comes from :mod:`acausal2d.visual.diagram_layout`.
"""
import html
import json
import textwrap

from .diagram_layout import HEAD, GLYPH, PARAM, end_points

HEADLINE = 3
"""Lines of an error message searched for component names and shown above
the diagram: its headline and the first culprits (a structural error goes
on to list every equation competing for the unknowns, which names every
component)."""

COLOURS = {"frame": "#4b5d6b", "rotational": "#1f6fb4", "translational": "#2e8b57",
           "band": "#d35400", "hydraulic": "#0097a7", "signal": "#8e44ad", "other": "#7f8c8d"}
"""The line colour of each domain."""

DOMAIN_NAMES = {"frame": "planar frame", "rotational": "rotational", "translational":
                "translational", "band": "band", "hydraulic": "hydraulic", "signal": "signal",
                "other": "other"}

FATE_TEXT = {"grounded": "grounded", "free": "free", "closed": "closed",
             "error": "not connected"}
"""The label of each fate of an unconnected connector."""

INK = "#37474f"
STYLE = """
.acausal2d-diagram text { font-family: system-ui, -apple-system, 'Segoe UI', Helvetica, Arial,
  sans-serif; fill: #263238; }
.acausal2d-diagram .name { font-size: 12px; font-weight: 600; }
.acausal2d-diagram .cls { font-size: 9px; fill: #78909c; }
.acausal2d-diagram .param { font-size: 10px; fill: #455a64; }
.acausal2d-diagram .pname { font-size: 9px; fill: #607d8b; }
.acausal2d-diagram .fate { font-size: 9px; fill: #546e7a; font-style: italic; }
.acausal2d-diagram .fate-error { fill: #c62828; font-weight: 600; font-style: normal; }
.acausal2d-diagram .flow { font-size: 10px; fill: #263238; paint-order: stroke;
  stroke: #fff; stroke-width: 3px; }
.acausal2d-diagram .line { fill: none; stroke-width: 2; }
.acausal2d-diagram .box rect.frame { fill: #fff; stroke: #90a4ae; stroke-width: 1.2; }
.acausal2d-diagram .box.named rect.frame { fill: #fdecea; stroke: #c62828; stroke-width: 2.5; }
.acausal2d-diagram .box.submodel rect.frame { stroke: #546e7a; stroke-width: 2; }
.acausal2d-diagram .box.selected rect.frame { stroke: #f39c12; stroke-width: 3; }
.acausal2d-diagram .glyph { fill: none; stroke: #37474f; stroke-width: 1.6;
  stroke-linejoin: round; stroke-linecap: round; }
.acausal2d-diagram .glyph .fill { fill: #b0bec5; }
.acausal2d-diagram .glyph text { stroke: none; font-size: 12px; font-weight: 700;
  fill: #37474f; }
"""


def _f(x):
    return ("%.1f" % x).rstrip("0").rstrip(".")


def _pts(points):
    return " ".join("%s,%s" % (_f(x), _f(y)) for x, y in points)


def _at(cx, cy, shape):
    """``shape`` (SVG in local coordinates about (0, 0)) moved to (cx, cy)."""
    return '<g class="glyph" transform="translate(%s,%s)">%s</g>' % (_f(cx), _f(cy), shape)


_ZIGZAG = _pts([(-26, 0), (-16, 0), (-12, -8), (-4, 8), (4, -8), (12, 8), (16, 0), (26, 0)])
_DASHPOT = ('<path d="M-26,0 H-6 M-6,-8 V8 M-12,-10 H14 M-12,10 H14 M14,-10 V10 '
            'M14,0 H26"/>')
GLYPHS = {
    "inertia": '<path d="M-28,0 H-9 M9,0 H28"/><rect class="fill" x="-9" y="-14" '
               'width="18" height="28" rx="2"/>',
    "mass": '<path d="M-28,0 H-14 M14,0 H28"/><rect class="fill" x="-14" y="-11" '
            'width="28" height="22" rx="2"/>',
    "spring": '<polyline points="%s"/>' % _ZIGZAG,
    "damper": _DASHPOT,
    "springdamper": '<g transform="translate(0,-8) scale(0.8,0.6)"><polyline points="%s"/>'
                    '</g><g transform="translate(0,9) scale(0.8,0.6)">%s</g>'
                    '<path d="M-26,-8 V9 M26,-8 V9 M-30,0 H-26 M26,0 H30"/>'
                    % (_ZIGZAG, _DASHPOT),
    "gear": '<circle cx="-7" cy="-3" r="11"/><circle cx="11" cy="7" r="7"/>'
            '<path d="M-28,-3 H-18 M18,7 H28"/>',
    "planetary": '<circle r="15"/><circle r="5" class="fill"/><circle cx="0" cy="-10" r="4"/>'
                 '<circle cx="8.7" cy="5" r="4"/><circle cx="-8.7" cy="5" r="4"/>',
    "clutch": '<path d="M-28,0 H-6 M6,0 H28"/><rect class="fill" x="-9" y="-14" width="4" '
              'height="28"/><rect class="fill" x="5" y="-14" width="4" height="28"/>'
              '<path d="M0,-18 V-10 M-3,-13 L0,-10 L3,-13"/>',
    "oneway": '<path d="M-28,0 H-6 M6,0 H28"/><rect class="fill" x="-9" y="-14" width="4" '
              'height="28"/><rect class="fill" x="5" y="-14" width="4" height="28"/>'
              '<path d="M-3,-6 L3,0 L-3,6"/>',
    "brake": '<path d="M-28,0 H28"/><rect class="fill" x="-3" y="-14" width="6" height="28"/>'
             '<rect x="-8" y="-18" width="16" height="5"/><rect x="-8" y="13" width="16" '
             'height="5"/><path d="M-12,18 H12 M-8,22 L-4,18 M0,22 L4,18 M8,22 L12,18"/>',
    "pulley": '<circle r="14"/><circle r="3" class="fill"/><path d="M-14,0 V16 M14,0 V16"/>',
    "drum": '<rect x="-16" y="-11" width="32" height="22" rx="4"/><path d="M-10,-11 V11 '
            'M-4,-11 V11 M2,-11 V11 M8,-11 V11 M14,11 V20"/>',
    "span": '<circle cx="-18" cy="0" r="6"/><circle cx="18" cy="0" r="6"/>'
            '<path d="M-18,-6 H18 M-18,6 H18" stroke-width="2.6"/>',
    "rope": '<path d="M-24,-10 Q0,-16 24,-10 M0,-13 V8" stroke-width="2"/>'
            '<path d="M0,8 a5,5 0 1 1 -5,5"/>',
    "body": '<rect class="fill" x="-24" y="-7" width="48" height="14" rx="7"/>'
            '<circle cx="-17" cy="0" r="3" fill="#fff"/><circle cx="17" cy="0" r="3" '
            'fill="#fff"/>',
    "joint": '<path d="M-28,6 L-6,0 M6,0 L28,-6"/><circle r="7" fill="#fff"/>'
             '<circle r="2" class="fill"/>',
    "vdi": '<polyline points="-22,10 -12,-12 14,-8 22,10"/><path d="M-27,10 H-17 M17,10 H27"/>'
           '<circle cx="-22" cy="10" r="2.6" fill="#fff"/><circle cx="-12" cy="-12" r="2.6" '
           'fill="#fff"/><circle cx="14" cy="-8" r="2.6" fill="#fff"/>'
           '<circle cx="22" cy="10" r="2.6" fill="#fff"/>',
    "pump": '<circle r="13"/><path class="fill" d="M0,-13 L-6,-3 L6,-3 Z"/>'
            '<path d="M-28,0 H-13 M13,0 H28"/>',
    "motor": '<circle r="13"/><text x="0" y="4.5" text-anchor="middle">M</text>'
             '<path d="M13,0 H28"/>',
    "valve": '<rect x="-16" y="-11" width="32" height="22"/><path d="M-12,8 L10,-8 '
             'M10,-8 L3,-7 M10,-8 L8,-1 M-28,0 H-16 M16,0 H28"/>',
    "volume": '<rect class="fill" x="-16" y="-12" width="32" height="24" rx="6"/>'
              '<path d="M-28,0 H-16"/>',
    "source": '<circle r="12"/><path d="M-7,0 H7 M3,-4 L7,0 L3,4"/><path d="M12,0 H28"/>',
    "sensor": '<circle r="12"/><path d="M0,0 L7,-7 M-8,5 H8"/><circle r="1.8" class="fill"/>',
    "block": '<rect x="-15" y="-12" width="30" height="24"/>'
             '<text x="0" y="4.5" text-anchor="middle" font-style="italic">f</text>',
    "fixed": '<path d="M-18,-6 H18 M-14,-6 L-19,2 M-6,-6 L-11,2 M2,-6 L-3,2 M10,-6 L5,2 '
             'M18,-6 L13,2 M0,-6 V-16"/>',
    "world": '<path d="M-14,12 H16 M-14,12 V-16 M12,9 L16,12 L12,15 M-17,-12 L-14,-16 '
             'L-11,-12"/><text x="18" y="8" style="font-size:9px">x</text>'
             '<text x="-10" y="-12" style="font-size:9px">y</text>',
    "submodel": '<rect x="-16" y="-12" width="26" height="18" fill="#fff"/>'
                '<rect x="-10" y="-6" width="26" height="18" fill="#fff"/>',
    "element": '<rect x="-14" y="-10" width="28" height="20" rx="3"/>',
}
"""The symbol of each kind, about (0, 0), at most 60 x 38 px."""


def _e(text):
    return html.escape(str(text), quote=True)


def _port_mark(port, x, y, side, external=False):
    """The small mark of a connector on the box edge: a square for power,
    a triangle for a signal (pointing the way it flows)."""
    colour = COLOURS.get(port.domain, COLOURS["other"])
    if port.domain == "signal":
        out = (port.signal == "output") != external
        dx = 1 if out == (side == "right") else -1
        pts = [(x - 4 * dx, y - 5), (x + 5 * dx, y), (x - 4 * dx, y + 5)]
        return '<polygon class="port" points="%s" fill="%s" data-path="%s"/>' % (
            _pts(pts), colour, _e(port.path))
    return '<rect class="port" x="%s" y="%s" width="7" height="7" fill="%s" data-path="%s"/>' % (
        _f(x - 3.5), _f(y - 3.5), colour, _e(port.path))


def _fate_mark(port, x, y, side):
    """What happens to an unconnected connector, drawn outside the box:
    a ground symbol, an open circle (free), a bar (closed) or a red cross
    (an error: it must be connected)."""
    s = 1 if side == "right" else -1
    x1 = x + 12 * s
    if port.fate == "grounded":
        mark = '<path d="M%s,%s H%s M%s,%s V%s M%s,%s V%s M%s,%s V%s"/>' % (
            _f(x), _f(y), _f(x1), _f(x1), _f(y - 7), _f(y + 7), _f(x1 + 3 * s), _f(y - 4.5),
            _f(y + 4.5), _f(x1 + 6 * s), _f(y - 2), _f(y + 2))
        end = x1 + 9 * s
    elif port.fate == "closed":
        mark = '<path d="M%s,%s H%s" /><path d="M%s,%s V%s" stroke-width="3.5"/>' % (
            _f(x), _f(y), _f(x1), _f(x1), _f(y - 6), _f(y + 6))
        end = x1 + 5 * s
    elif port.fate == "error":
        mark = ('<path d="M%s,%s H%s"/><circle cx="%s" cy="%s" r="5.5" fill="#fff" '
                'stroke="#c62828"/><path d="M%s,%s l6,6 m0,-6 l-6,6" stroke="#c62828"/>') % (
            _f(x), _f(y), _f(x1 - 5.5 * s), _f(x1), _f(y), _f(x1 - 3), _f(y - 3))
        end = x1 + 8 * s
    else:
        mark = '<path d="M%s,%s H%s"/><circle cx="%s" cy="%s" r="3.5" fill="#fff"/>' % (
            _f(x), _f(y), _f(x1 - 3.5 * s), _f(x1), _f(y))
        end = x1 + 6 * s
    label = '<text class="fate%s" stroke="none" x="%s" y="%s" text-anchor="%s">%s</text>' % (
        " fate-error" if port.fate == "error" else "", _f(end), _f(y + 3),
        "start" if s > 0 else "end", FATE_TEXT[port.fate])
    return ('<g class="open-port" data-path="%s" data-fate="%s" fill="none" stroke="%s" '
            'stroke-width="1.4">%s%s</g>') % (_e(port.path), port.fate,
                                              "#c62828" if port.fate == "error" else INK,
                                              mark, label)


def _outside_mark(port, x, y, side):
    """A connector connected by the level above: a dashed stub so marked."""
    s = 1 if side == "right" else -1
    return ('<g class="outside-port" data-path="%s"><path d="M%s,%s h%s" stroke="%s" '
            'stroke-dasharray="3 2" stroke-width="1.6"/><text class="fate" x="%s" y="%s" '
            'text-anchor="%s">connected above</text></g>') % (
        _e(port.path), _f(x), _f(y), _f(14 * s), COLOURS.get(port.domain, COLOURS["other"]),
        _f(x + 17 * s), _f(y + 3), "start" if s > 0 else "end")


def _box_svg(box, geom, ports):
    """One component: frame, name, class, symbol, parameters, ports and
    the marks of its unconnected connectors."""
    x, y, w, h = geom
    cls = "box" + (" submodel" if box.submodel else "") + (" named" if box.named else "") + \
        (" external" if box.external else "")
    out = ['<g class="%s" data-path="%s" data-kind="%s" data-class="%s" data-x="%s" '
           'data-y="%s" data-w="%s" data-h="%s">' % (cls, _e(box.path), box.kind, _e(box.cls),
                                                    _f(x), _f(y), _f(w), _f(h)),
           '<title>%s (%s)%s</title>' % (_e(box.path), _e(box.cls), "; click to open"
                                         if box.submodel else "")]
    if box.external:
        out += ['<rect class="frame" x="%s" y="%s" width="%s" height="%s" rx="15"/>' % (
            _f(x), _f(y), _f(w), _f(h)),
            '<text class="name" x="%s" y="%s" text-anchor="middle">%s</text>' % (
            _f(x + w / 2), _f(y + h / 2 + 4), _e(box.name))]
    else:
        out += _component_svg(box, x, y, w, h)
    out += _ports_svg(box, ports)
    out.append("</g>")
    return out


def _ports_svg(box, ports):
    """The marks and names of a box's ports (twice for a mirrored one) and
    what happens to those left unconnected."""
    out = []
    for port in box.ports.values():
        px, py, side = ports[(box.path, port.name)]
        places = [(px, py, side)] + ([ports[(box.path, port.name, "mirror")]] if port.mirror
                                     else [])
        for qx, qy, qside in places:
            out.append(_port_mark(port, qx, qy, qside, box.external))
            if not box.external:
                inset = 7 if qside == "left" else -7
                out.append('<text class="pname" x="%s" y="%s" text-anchor="%s">%s</text>' % (
                    _f(qx + inset), _f(qy - 4), "start" if qside == "left" else "end",
                    _e(port.name)))
        outward = px + (3.5 if side == "right" else -3.5)
        if port.fate:
            out.append(_fate_mark(port, outward, py, side))
        elif port.outside:
            out.append(_outside_mark(port, outward, py, side))
    return out


def _component_svg(box, x, y, w, h):
    cx = x + w / 2
    out = ['<rect class="frame" x="%s" y="%s" width="%s" height="%s" rx="6"/>' % (
        _f(x), _f(y), _f(w), _f(h))]
    if box.submodel:
        out.append('<rect x="%s" y="%s" width="%s" height="%s" rx="8" fill="none" '
                   'stroke="#b0bec5" stroke-dasharray="3 2"/>' % (
                       _f(x + 3), _f(y + 3), _f(w - 6), _f(h - 6)))
    out.append('<text class="name" x="%s" y="%s" text-anchor="middle">%s</text>' % (
        _f(cx), _f(y + 15), _e(box.name)))
    out.append(_at(cx, y + HEAD + GLYPH / 2 + 2, GLYPHS.get(box.kind, GLYPHS["element"])))
    top = y + HEAD + GLYPH + 8
    out.append('<text class="cls" x="%s" y="%s" text-anchor="middle">%s%s</text>' % (
        _f(cx), _f(top - 3), _e(box.cls), " \u25b8 open" if box.submodel else ""))
    for k, text in enumerate(box.params):
        out.append('<text class="param" x="%s" y="%s" text-anchor="middle">%s</text>' % (
            _f(cx), _f(top + 9 + PARAM * k), _e(text)))
    return out


def _path_d(points):
    """A smooth path through ``points``: horizontal tangents at each one."""
    (x0, y0), rest = points[0], points[1:]
    d = ["M%s,%s" % (_f(x0), _f(y0))]
    for x1, y1 in rest:
        if abs(y1 - y0) < 0.5 or abs(x1 - x0) < 0.5:       # straight along an axis
            d.append("L%s,%s" % (_f(x1), _f(y1)))
        else:
            dx = max(abs(x1 - x0) / 2, 30)
            sx = 1 if x1 >= x0 else -1
            d.append("C%s,%s %s,%s %s,%s" % (_f(x0 + sx * dx), _f(y0), _f(x1 - sx * dx), _f(y1),
                                             _f(x1), _f(y1)))
        x0, y0 = x1, y1
    return " ".join(d)


def _line_svg(k, line, route, ports, boxes):
    """A connection: its path (an arrow at the input for a signal) and the
    empty label the explore page writes the flow into."""
    colour = COLOURS.get(line.domain, COLOURS["other"])
    pts = list(route)
    side_a, side_b = (e[2] for e in end_points(ports, boxes, line))
    # leave and enter each port horizontally, outwards from its box
    pts.insert(1, (pts[0][0] + (14 if side_a == "right" else -14), pts[0][1]))
    pts.insert(-1, (pts[-1][0] + (14 if side_b == "right" else -14), pts[-1][1]))
    if line.domain == "signal":         # the arrow ends at the port's triangle
        pts[-1] = (pts[-1][0] + (6 if side_b == "right" else -6), pts[-1][1])
    mid = pts[len(pts) // 2 - 1], pts[len(pts) // 2]
    mx, my = (mid[0][0] + mid[1][0]) / 2, (mid[0][1] + mid[1][1]) / 2
    marker = ' marker-end="url(#arrow)"' if line.domain == "signal" else ""
    return ('<path class="line" id="line-%d" d="%s" stroke="%s" data-a="%s" data-b="%s" '
            'data-domain="%s" data-flows="%s"%s/>'
            '<text class="flow" id="flow-%d" x="%s" y="%s" text-anchor="middle"></text>') % (
        k, _path_d(pts), colour, _e(line.a), _e(line.b), line.domain,
        _e(" ".join(line.flows)), marker, k, _f(mx), _f(my - 5))


def _legend(st, y):
    used = [d for d in COLOURS if any(ln.domain == d for ln in st.lines) or
            any(p.domain == d for b in st.boxes for p in b.ports.values())]
    out, x = [], 20.0
    for d in used:
        out.append('<path d="M%s,%s h26" stroke="%s" stroke-width="2.5"/>'
                   '<text class="param" x="%s" y="%s">%s</text>' % (
                       _f(x), _f(y), COLOURS[d], _f(x + 32), _f(y + 4), DOMAIN_NAMES[d]))
        x += 48 + 6.2 * len(DOMAIN_NAMES[d])
    return out


def _error_lines(error, width, most=5):
    """The headline of the error the model failed to compile with, wrapped
    to the drawing's width (at most ``most`` lines)."""
    lines = []
    for k, text in enumerate(error.splitlines()[:HEADLINE]):
        lines += textwrap.wrap(("does not compile: " if k == 0 else "") + text.strip(),
                               max(40, int((width - 40) / 6.6)))
    if len(lines) > most or len(error.splitlines()) > HEADLINE:
        lines = lines[:most]
        lines[-1] += " ..."
    return ['<text class="fate fate-error" x="20" y="%s" style="font-size:11px">%s</text>' % (
        _f(50 + 14 * k), _e(t)) for k, t in enumerate(lines)], 14 * len(lines) + 10


def render_svg(st, lay):
    """The SVG text of a :class:`~acausal2d.visual.diagram.Structure` laid
    out as ``lay``."""
    shift, errs = 0.0, []
    if st.error:
        errs, shift = _error_lines(st.error, lay.width)
    width, height = lay.width, lay.height + shift + 36
    out = ['<svg xmlns="http://www.w3.org/2000/svg" class="acausal2d-diagram" width="%s" '
           'height="%s" viewBox="0 0 %s %s" data-model="%s" data-path="%s">' % (
               _f(width), _f(height), _f(width), _f(height), _e(st.name), _e(st.path)),
           "<style>%s</style>" % STYLE,
           '<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="4" '
           'markerHeight="4" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 Z" '
           'fill="%s"/></marker></defs>' % COLOURS["signal"],
           '<rect width="100%" height="100%" fill="#fbfbfc"/>',
           '<text class="name" x="20" y="28" style="font-size:15px">%s</text>' % _e(st.name)]
    out += errs
    out.append('<g transform="translate(0,%s)">' % _f(shift))
    for k, (line, route) in enumerate(zip(st.lines, lay.routes)):
        out.append(_line_svg(k, line, route, lay.ports, lay.boxes))
    for box in st.boxes:
        out += _box_svg(box, lay.boxes[box.path], lay.ports)
    out += _legend(st, lay.height + 14)
    out.append("</g></svg>")
    return "\n".join(out)


_PAGE = """<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>%(title)s - diagram</title>
<style>body{margin:0;font:13px system-ui,sans-serif;background:#fbfbfc}
nav{padding:6px 12px;border-bottom:1px solid #dde1e6;background:#fff}
nav a{cursor:pointer;color:#1f6fb4;text-decoration:underline}
.box.submodel{cursor:pointer}.level{overflow:auto}</style></head><body>
<nav id="crumbs"></nav>
%(levels)s
<script>
(function(){
  var levels = %(paths)s;
  function show(path){
    document.querySelectorAll(".level").forEach(function(s){
      s.hidden = s.getAttribute("data-level") !== path;});
    var nav = document.getElementById("crumbs"), parts = path ? path.split(".") : [];
    nav.textContent = "";
    var names = [%(name)s].concat(parts);
    names.forEach(function(n, i){
      if (i) nav.appendChild(document.createTextNode(" \\u25b8 "));
      var p = parts.slice(0, i).join("."), a = document.createElement(i < names.length - 1 ? "a" : "b");
      a.textContent = n;
      if (i < names.length - 1) a.addEventListener("click", function(){ show(p); });
      nav.appendChild(a);
    });
    location.hash = path;
  }
  document.querySelectorAll(".level").forEach(function(s){
    var base = s.getAttribute("data-level");
    s.querySelectorAll(".box.submodel").forEach(function(b){
      b.addEventListener("click", function(){
        var p = (base ? base + "." : "") + b.getAttribute("data-path");
        if (levels.indexOf(p) >= 0) show(p);
      });
    });
  });
  var start = decodeURIComponent(location.hash.slice(1));
  show(levels.indexOf(start) >= 0 ? start : "");
})();
</script></body></html>
"""


def render_html(title, levels):
    """The HTML page of a model's diagrams: ``levels`` is [(path, svg)],
    the model itself ('') first; a sub-model's box opens its level."""
    sections = "\n".join('<section class="level" data-level="%s"%s>%s</section>' % (
        _e(path), " hidden" if path else "", svg) for path, svg in levels)
    return _PAGE % {"title": _e(title), "levels": sections,
                    "paths": json.dumps([p for p, _ in levels]),
                    "name": json.dumps(title).replace("</", "<\\/")}
