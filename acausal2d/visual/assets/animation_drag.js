// Drag mode of node models: grab a node with the mouse, and the page keeps
// the constraints by the position correction of the talk's eq. 3-16 (the
// algorithm of cstr.js: per sweep every constraint corrects its nodes,
// angle first (eq. 16), then length (eq. 14), weighted by inverse masses
// that grow by one per correction in the sweep; sweeps until no correction
// exceeds lentol, at most itrmax; on failure the last sweep is undone).
// The same algorithm as acausal2d/library/node_correction.py.
(function () {
  "use strict";
  var A = window.acausal2d, D = A && A.scene, SYS = D && D.nodes;
  if (!SYS) return;
  var TWO_PI = 2 * Math.PI, EPS = 2.220446049250313e-16;
  var nodes = {}, cstrs = [], byId = {};
  var lentol = +SYS.lentol, itrmax = SYS.itrmax | 0;
  var active = false, grabbed = null, last = null, box = null;

  // ---- model
  function setup() {
    SYS.nodes.forEach(function (n) {
      nodes[n.id] = { id: n.id, x: +n.x, y: +n.y, m: (+n.m) || 1, base: !!n.base, dym: 0 };
    });
    SYS.constraints.forEach(function (c) {
      var k = { src: c, id: c.id, type: c.type, ns: [] };
      ["n1", "n2", "n3"].forEach(function (e) { if (c[e] !== undefined) k.ns.push(nodes[c[e]]); });
      cstrs.push(k); byId[c.id] = k;
    });
    cstrs.forEach(function (c) { if (c.type === "n2") c.wu = rawAngle(c); });
  }
  function vec(c, i, j) { return [c.ns[j].x - c.ns[i].x, c.ns[j].y - c.ns[i].y]; }
  function rawAngle(c) { var d = vec(c, 0, 1); return Math.atan2(d[1], d[0]); }
  function length(id) { var d = vec(byId[id], 0, 1); return Math.sqrt(d[0] * d[0] + d[1] * d[1]); }
  function angle(id) {  // unwrapped, continuous with its previous value
    var c = byId[id], a = rawAngle(c);
    c.wu = a + TWO_PI * Math.round((c.wu - a) / TWO_PI);
    return c.wu;
  }
  function value(id, kind) { return kind === "len" ? length(id) : angle(id); }
  function invMass(n) { return n.base ? 0 : 1 / (n.m + n.dym); }
  function shares(n1, n2) {
    var i1 = invMass(n1), i2 = invMass(n2), s = i1 + i2;
    return s ? [i1 / s, i2 / s] : [i1, i2];
  }

  // ---- targets of a constraint's length or angle (drives are left to the hand)
  function coupled(c, s) {
    if (s.kind === "ref") return s.ratio * value(s.ref, s.of) + s.offset;
    if (s.kind === "delta") {
      var w1 = angle(s.from), w2 = angle(s.to);
      return w1 + s.scl * (w2 - w1) + (s.offset || 0);
    }
    if (s.kind === "ang_from_len") return s.base + s.ratio * (length(s.ref) - s.ref0) / (length(c.id) || 1);
    if (s.kind === "len_from_ang") return s.base + s.ratio * length(s.ref) * (angle(s.ref) - s.ref0);
    return null;
  }
  function target(c, kind) {
    var s = c.src[kind], z;
    if (!s || s.kind === "free" || s.kind === "drive") return null;
    if (s.kind === "value") return s.value;
    z = s.kind === "range" ? value(c.id, kind) : coupled(c, s);
    if (z === null) return null;
    if (s.hi !== undefined && z > s.hi) z = s.hi;
    if (s.lo !== undefined && z < s.lo) z = s.lo;
    return z;
  }

  // ---- corrections (eq. 14, 16 and cstr.js's n3)
  function correctLen(c, r) {
    var n1 = c.ns[0], n2 = c.ns[1], x = n2.x - n1.x, y = n2.y - n1.y;
    var cur = Math.sqrt(x * x + y * y), dr = r - cur;
    if (Math.abs(dr) <= lentol) return 0;
    var ex = cur > EPS ? x / cur : 1, ey = cur > EPS ? y / cur : 0, w = shares(n1, n2);
    n1.x -= w[0] * dr * ex; n1.y -= w[0] * dr * ey;
    n2.x += w[1] * dr * ex; n2.y += w[1] * dr * ey;
    n1.dym++; n2.dym++;
    return Math.abs(dr);
  }
  function correctAng(c, a) {
    var n1 = c.ns[0], n2 = c.ns[1], x = n2.x - n1.x, y = n2.y - n1.y;
    var ca = Math.cos(a), sa = Math.sin(a), de = -x * sa + y * ca, dx = -de * sa, dy = de * ca;
    if (c.src.dir) {
      var re = (c.src.dir > 0 ? 1 : -1) * (x * ca + y * sa);
      if (re <= 0) { dx = 2 * re * ca - de * sa; dy = 2 * re * sa + de * ca; }
    }
    var w = shares(n1, n2);
    n1.x += w[0] * dx; n1.y += w[0] * dy;
    n2.x -= w[1] * dx; n2.y -= w[1] * dy;
    n1.dym++; n2.dym++;
    return Math.max(Math.abs(dx), Math.abs(dy));
  }
  function correctN3(c) {
    var n1 = c.ns[0], n3 = c.ns[2], d12 = vec(c, 0, 1), r12 = Math.sqrt(d12[0] * d12[0] + d12[1] * d12[1]);
    if (r12 <= Math.sqrt(EPS)) return 0;
    var c12 = d12[0] / r12, s12 = d12[1] / r12, ca = Math.cos(c.src.value), sa = Math.sin(c.src.value);
    var c12a = c12 * ca - s12 * sa, s12a = s12 * ca + c12 * sa;
    var o13 = -(n3.x - n1.x) * s12a + (n3.y - n1.y) * c12a, dx = -o13 * s12a, dy = o13 * c12a;
    var share = shares(n1, n3)[1];
    n3.x -= share * dx; n3.y -= share * dy; n3.dym++;
    return Math.max(Math.abs(dx), Math.abs(dy));
  }
  function correctOne(c) {
    if (c.type === "n3") return correctN3(c);
    var move = 0, w = target(c, "ang"), r;
    if (w !== null) move = correctAng(c, w);
    r = target(c, "len");
    if (r !== null) move = Math.max(move, correctLen(c, r));
    return move;
  }
  function correct() {
    var itr, saved, largest = 0, id;
    for (itr = 1; itr <= itrmax; itr++) {
      saved = {};
      for (id in nodes) { saved[id] = [nodes[id].x, nodes[id].y]; if (!nodes[id].base) nodes[id].dym = 0; }
      largest = 0;
      for (var i = 0; i < cstrs.length; i++) largest = Math.max(largest, correctOne(cstrs[i]));
      if (largest < lentol) { track(); return (last = { iterations: itr, converged: true }); }
    }
    for (id in saved) { nodes[id].x = saved[id][0]; nodes[id].y = saved[id][1]; }
    track();
    return (last = { iterations: itrmax, converged: false, undone: true });
  }
  function track() { cstrs.forEach(function (c) { if (c.type === "n2") angle(c.id); }); }

  // ---- page integration
  function signalValue(name) {
    var m = SYS.signals[name];
    if (!m) return undefined;
    if (m[0] === "length" || m[0] === "angle") {
      var a = nodes[m[1]], b = nodes[m[2]], dx = b.x - a.x, dy = b.y - a.y;
      return m[0] === "length" ? Math.sqrt(dx * dx + dy * dy) : Math.atan2(dy, dx);
    }
    return nodes[m[0]][m[1]];
  }
  function fromFrame() {
    var k = A.frame;
    for (var name in SYS.signals) {
      var m = SYS.signals[name], v = A.signal(name, k);
      if (m.length === 2 && v !== undefined && v !== null) nodes[m[0]][m[1]] = +v;
    }
    cstrs.forEach(function (c) { if (c.type === "n2") c.wu = rawAngle(c); });
  }
  function eventPoint(e) {
    var r = A.canvas.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  }
  function nearest(px, py) {
    var best = null, bestD = 14;
    for (var id in nodes) {
      if (nodes[id].base) continue;
      var p = A.toScreen(nodes[id].x, nodes[id].y), d = Math.hypot(p[0] - px, p[1] - py);
      if (d <= bestD) { best = id; bestD = d; }
    }
    return best;
  }
  function moveTo(e) {
    var p = eventPoint(e), w = A.toWorld(p[0], p[1]);
    nodes[grabbed].x = w[0]; nodes[grabbed].y = w[1];
    correct(); A.redraw();
  }
  function enable() {
    if (active) return;
    A.pause(); fromFrame(); active = true;
    if (box) box.checked = true;
    A.canvas.style.cursor = "grab";
    A.setOverride(signalValue);
  }
  function disable() {
    active = false; grabbed = null;
    if (box) box.checked = false;
    A.canvas.style.cursor = "";
    A.setOverride(null);
  }
  function addControl() {
    var bar = document.getElementById("bar");
    if (!bar) return;
    var label = document.createElement("label");
    label.title = "Drag the nodes with the mouse; the constraints are kept (talk eq. 3-16)";
    box = document.createElement("input");
    box.type = "checkbox"; box.id = "drag";
    label.appendChild(box); label.appendChild(document.createTextNode(" drag"));
    bar.appendChild(label);
    box.addEventListener("change", function () { if (box.checked) enable(); else disable(); });
  }
  function listen() {
    A.canvas.addEventListener("mousedown", function (e) {
      if (!active) return;
      var p = eventPoint(e);
      grabbed = nearest(p[0], p[1]);
      if (grabbed !== null) { A.canvas.style.cursor = "grabbing"; e.preventDefault(); }
    });
    window.addEventListener("mousemove", function (e) { if (active && grabbed !== null) moveTo(e); });
    window.addEventListener("mouseup", function (e) {
      if (!active || grabbed === null) return;
      moveTo(e); grabbed = null; A.canvas.style.cursor = "grab";
    });
  }

  setup(); addControl(); listen();
  A.drag = {
    get active() { return active; },
    get last() { return last; },
    enable: enable,
    disable: disable,
    correct: function () { var r = correct(); A.redraw(); return r; },
    move: function (id, x, y) {  // what a drag step does: place the node, correct
      nodes[id].x = +x; nodes[id].y = +y;
      var r = correct(); A.redraw(); return r;
    },
    positions: function () {
      var out = {};
      for (var id in nodes) out[id] = [nodes[id].x, nodes[id].y];
      return out;
    },
    screenOf: function (id) { return A.toScreen(nodes[id].x, nodes[id].y); },
    lengths: function () {
      var out = {};
      cstrs.forEach(function (c) { if (c.type === "n2") out[c.id] = length(c.id); });
      return out;
    }
  };
})();
