(function () {
  "use strict";
  var errors = [];
  window.addEventListener("error", function (e) {
    errors.push(String(e && e.message ? e.message : e));
  });

  var D = JSON.parse(document.getElementById("acausal2d-data").textContent);
  var T = D.time, N = T.length, S = D.signals, shapes = D.shapes;
  var canvas = document.getElementById("view");
  var ctx = canvas.getContext("2d");
  var playBtn = document.getElementById("play");
  var scrub = document.getElementById("scrub");
  var speedSel = document.getElementById("speed");
  var timeOut = document.getElementById("time");
  var loopBox = document.getElementById("loop");

  var COLORS = {
    background: "#fbfbfc", grid: "#eceef1", axis: "#dde1e6", text: "#2d3436",
    ground: "#6b6f75", groundFill: "#d5d8dc", link: "#4682b4", linkEdge: "#2b4f6e",
    joint: "#ffffff", jointEdge: "#1f2933", body: "#2d3436", slider: "#a9c3db",
    sliderEdge: "#2b4f6e", guide: "#8a9099", pulley: "#e9edf1", pulleyEdge: "#555d66",
    spoke: "#7b858f", belt: "#e07b00", spring: "#2e9e4f", trace: "rgba(240,128,128,0.8)",
    tracePoint: "#e74c3c", label: "#1f2933", force: "#c0392b", torque: "#8e44ad",
    plotLine: "#4682b4", cursor: "#e74c3c"
  };

  var frame = 0, playing = false, rafId = null, anchorWall = 0, anchorSim = 0;
  var override = null;  // function (signal name) -> value or undefined (drag mode)
  var view = { s: 1, ox: 0, oy: 0, w: 1, h: 1 };

  // Playback clock: the time vector, or 30 frames/s if it does not advance.
  var duration = N > 1 ? T[N - 1] - T[0] : 0;
  var clock = new Array(N);
  for (var q = 0; q < N; q++) clock[q] = duration > 0 ? T[q] : q / 30;

  function val(x, k) {
    if (override !== null && typeof x === "string") {
      var o = override(x);
      if (o !== undefined) return o;
    }
    var y = x;
    if (typeof x === "string") { var a = S[x]; y = a ? a[k] : null; }
    return (y === null || y === undefined) ? NaN : +y;
  }
  function finite() {
    for (var i = 0; i < arguments.length; i++) if (!isFinite(arguments[i])) return false;
    return true;
  }
  function P(x, y) { return [view.ox + view.s * x, view.oy - view.s * y]; }
  function pt(p, k) {
    var x = val(p[0], k), y = val(p[1], k);
    return finite(x, y) ? P(x, y) : null;
  }
  function pts(list, k) {
    var out = [];
    for (var i = 0; i < list.length; i++) { var p = pt(list[i], k); if (!p) return null; out.push(p); }
    return out;
  }
  function polyline(ps) {
    ctx.beginPath(); ctx.moveTo(ps[0][0], ps[0][1]);
    for (var i = 1; i < ps.length; i++) ctx.lineTo(ps[i][0], ps[i][1]);
  }
  function worldLen(v, k, dflt, minimum) {
    if (v === undefined || v === null) return dflt;
    var L = Math.abs(val(v, k)) * view.s;
    return isFinite(L) ? Math.max(minimum, L) : NaN;
  }
  function circle(x, y, r) { ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI); }

  // ---- shape drawers: function (shape, frameIndex) ----
  function drawGround(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), phi = sh.phi === undefined ? 0 : val(sh.phi, k);
    if (!finite(x, y, phi)) return;
    var p = P(x, y), c = sh.color || COLORS.ground;
    ctx.save(); ctx.translate(p[0], p[1]); ctx.rotate(-phi);
    ctx.beginPath(); ctx.moveTo(0, 0); ctx.lineTo(-9, 13); ctx.lineTo(9, 13); ctx.closePath();
    ctx.fillStyle = COLORS.groundFill; ctx.fill();
    ctx.strokeStyle = c; ctx.lineWidth = 1.5; ctx.lineJoin = "round"; ctx.stroke();
    ctx.beginPath(); ctx.moveTo(-17, 13); ctx.lineTo(17, 13); ctx.lineWidth = 2; ctx.stroke();
    ctx.beginPath();
    for (var hx = -13; hx <= 19; hx += 5) { ctx.moveTo(hx, 13); ctx.lineTo(hx - 6, 20); }
    ctx.lineWidth = 1.2; ctx.stroke();
    ctx.restore();
  }
  function drawJoint(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    circle(p[0], p[1], 4.5);
    ctx.fillStyle = COLORS.joint; ctx.fill();
    ctx.strokeStyle = sh.color || COLORS.jointEdge; ctx.lineWidth = 1.6; ctx.stroke();
  }
  function drawLink(sh, k) {
    var ps = pts(sh.points, k), w = worldLen(sh.width, k, 7, 1.5);
    if (!ps || !isFinite(w)) return;
    ctx.lineCap = "round"; ctx.lineJoin = "round";
    polyline(ps); ctx.strokeStyle = COLORS.linkEdge; ctx.lineWidth = w + 2.5; ctx.stroke();
    polyline(ps); ctx.strokeStyle = sh.color || COLORS.link; ctx.lineWidth = w; ctx.stroke();
  }
  function drawBody(sh, k) {
    var p = pt([sh.x, sh.y], k), r = worldLen(sh.r, k, 9, 2);
    if (!p || !isFinite(r)) return;
    circle(p[0], p[1], r); ctx.fillStyle = sh.color || COLORS.body; ctx.fill();
    circle(p[0] - 0.3 * r, p[1] - 0.3 * r, 0.35 * r);
    ctx.fillStyle = "rgba(255,255,255,0.22)"; ctx.fill();
  }
  function drawGuide(sh, k) {
    if (!sh.guide) return;
    var ps = pts(sh.guide, k); if (!ps) return;
    ctx.save(); ctx.setLineDash([7, 5]); ctx.lineCap = "butt";
    polyline(ps); ctx.strokeStyle = COLORS.guide; ctx.lineWidth = 1.5; ctx.stroke();
    ctx.restore();
    drawTravel(sh, k);
  }
  function drawTravel(sh, k) {       // the slider's travel range over the run (seed Bild 7.4)
    var ps = sh.travel && pts(sh.travel, k); if (!ps) return;
    var dx = ps[1][0] - ps[0][0], dy = ps[1][1] - ps[0][1], d = Math.hypot(dx, dy);
    var nx = d > 0 ? -dy / d * 7 : 0, ny = d > 0 ? dx / d * 7 : 7;
    ctx.save(); ctx.lineCap = "butt"; ctx.strokeStyle = COLORS.guide; ctx.lineWidth = 2.5;
    polyline(ps); ctx.stroke();
    ps.forEach(function (p) {
      ctx.beginPath(); ctx.moveTo(p[0] - nx, p[1] - ny); ctx.lineTo(p[0] + nx, p[1] + ny); ctx.stroke();
    });
    ctx.restore();
  }
  function drawSlider(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), phi = val(sh.phi, k);
    var L = worldLen(sh.length, k, 38, 4);
    if (!finite(x, y, phi, L)) return;
    var H = 0.6 * L, p = P(x, y);
    ctx.save(); ctx.translate(p[0], p[1]); ctx.rotate(-phi);
    ctx.beginPath(); ctx.rect(-L / 2, -H / 2, L, H);
    ctx.fillStyle = sh.color || COLORS.slider; ctx.fill();
    ctx.strokeStyle = COLORS.sliderEdge; ctx.lineWidth = 1.6; ctx.lineJoin = "round"; ctx.stroke();
    ctx.restore();
  }
  function drawPulley(sh, k) {
    var x = val(sh.x, k), y = val(sh.y, k), r = val(sh.r, k), phi = val(sh.phi, k);
    if (!finite(x, y, r, phi)) return;
    var p = P(x, y), R = Math.max(3, Math.abs(r) * view.s), rin = R;
    var c = Math.cos(phi), s = Math.sin(phi);
    ctx.lineJoin = "round";
    if (sh.contour && sh.contour.length >= 3) {
      ctx.beginPath();
      rin = Infinity;
      for (var i = 0; i < sh.contour.length; i++) {
        var cx = +sh.contour[i][0], cy = +sh.contour[i][1];
        rin = Math.min(rin, Math.sqrt(cx * cx + cy * cy) * view.s);
        var q = P(x + c * cx - s * cy, y + s * cx + c * cy);
        if (i === 0) ctx.moveTo(q[0], q[1]); else ctx.lineTo(q[0], q[1]);
      }
      ctx.closePath();
      rin = Math.max(3, Math.min(rin, R));
    } else {
      circle(p[0], p[1], R);
    }
    ctx.fillStyle = COLORS.pulley; ctx.fill();
    ctx.strokeStyle = sh.color || COLORS.pulleyEdge; ctx.lineWidth = 2; ctx.stroke();
    if (!(sh.contour && sh.contour.length >= 3)) {
      circle(p[0], p[1], 0.84 * R); ctx.lineWidth = 1; ctx.strokeStyle = COLORS.spoke; ctx.stroke();
    }
    var hub = Math.max(2.5, 0.15 * rin), spoke = 0.84 * rin;
    for (var j = 0; j < 5; j++) {
      var a = -phi - j * 2 * Math.PI / 5, ca = Math.cos(a), sa = Math.sin(a);
      ctx.beginPath();
      ctx.moveTo(p[0] + hub * ca, p[1] + hub * sa);
      ctx.lineTo(p[0] + spoke * ca, p[1] + spoke * sa);
      ctx.lineCap = "round";
      ctx.strokeStyle = j === 0 ? (sh.color || COLORS.pulleyEdge) : COLORS.spoke;
      ctx.lineWidth = j === 0 ? 3 : 1.8; ctx.stroke();
    }
    circle(p[0], p[1], hub); ctx.fillStyle = sh.color || COLORS.pulleyEdge; ctx.fill();
  }
  function drawBelt(sh, k) {
    var ps = pts(sh.points, k); if (!ps) return;
    ctx.lineCap = "round"; ctx.lineJoin = "round";
    polyline(ps); ctx.strokeStyle = sh.color || COLORS.belt; ctx.lineWidth = 3; ctx.stroke();
  }
  function drawSpring(sh, k) {
    var a = pt(sh.a, k), b = pt(sh.b, k); if (!a || !b) return;
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.sqrt(dx * dx + dy * dy);
    if (L < 1) return;
    var ux = dx / L, uy = dy / L, nx = -uy, ny = ux, lead = 0.15 * L, m = 12, amp = 6;
    ctx.beginPath(); ctx.moveTo(a[0], a[1]);
    for (var j = 0; j <= m; j++) {
      var d = lead + (L - 2 * lead) * j / m, o = (j === 0 || j === m) ? 0 : (j % 2 ? amp : -amp);
      ctx.lineTo(a[0] + ux * d + nx * o, a[1] + uy * d + ny * o);
    }
    ctx.lineTo(b[0], b[1]);
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    ctx.strokeStyle = sh.color || COLORS.spring; ctx.lineWidth = 2; ctx.stroke();
  }
  function drawTracePath(sh) {
    ctx.beginPath();
    var pen = false;
    for (var k = 0; k < N; k++) {
      var p = pt([sh.x, sh.y], k);
      if (!p) { pen = false; continue; }
      if (pen) ctx.lineTo(p[0], p[1]); else ctx.moveTo(p[0], p[1]);
      pen = true;
    }
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    ctx.strokeStyle = sh.color || COLORS.trace; ctx.lineWidth = 1.5;
    ctx.save(); if (sh.color) ctx.globalAlpha = 0.5; ctx.stroke(); ctx.restore();
  }
  function drawTracePoint(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    circle(p[0], p[1], 4); ctx.fillStyle = sh.color || COLORS.tracePoint; ctx.fill();
    ctx.strokeStyle = "#ffffff"; ctx.lineWidth = 1.2; ctx.stroke();
  }
  // ---- force and torque arrows: one scale per kind over the whole run ----
  function maxOver(kind, fn) {
    var m = 0;
    shapes.forEach(function (sh) {
      if (!sh || sh.type !== kind) return;
      for (var k = 0; k < N; k++) { var v = fn(sh, k); if (isFinite(v) && v > m) m = v; }
    });
    return m;
  }
  function arrowHead(x, y, ang, size) {
    ctx.beginPath(); ctx.moveTo(x, y);
    ctx.lineTo(x - size * Math.cos(ang - 0.4), y - size * Math.sin(ang - 0.4));
    ctx.lineTo(x - size * Math.cos(ang + 0.4), y - size * Math.sin(ang + 0.4));
    ctx.closePath(); ctx.fill();
  }
  function arrowText(text, x, y) {
    ctx.font = "11px system-ui, sans-serif"; ctx.textAlign = "left"; ctx.textBaseline = "middle";
    ctx.lineWidth = 3; ctx.strokeStyle = "rgba(251,251,252,0.9)"; ctx.strokeText(text, x, y);
    ctx.fillText(text, x, y);
  }
  function drawLabel(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    ctx.font = "13px system-ui, -apple-system, 'Segoe UI', Roboto, Helvetica, Arial, sans-serif";
    ctx.textBaseline = "bottom"; ctx.textAlign = "left"; ctx.lineJoin = "round";
    ctx.strokeStyle = "rgba(251,251,252,0.9)"; ctx.lineWidth = 3;
    ctx.strokeText(String(sh.text), p[0] + 7, p[1] - 5);
    ctx.fillStyle = sh.color || COLORS.label; ctx.fillText(String(sh.text), p[0] + 7, p[1] - 5);
  }

  function drawPole(sh, k) {
    var p = pt([sh.x, sh.y], k); if (!p) return;
    var c = sh.color || "#16a085";
    circle(p[0], p[1], 5); ctx.strokeStyle = c; ctx.lineWidth = 2; ctx.stroke();
    circle(p[0], p[1], 1.5); ctx.fillStyle = c; ctx.fill();
    if (sh.text === undefined) return;
    ctx.font = "12px system-ui, sans-serif"; ctx.textBaseline = "top"; ctx.textAlign = "left";
    ctx.fillText(String(sh.text), p[0] + 6, p[1] + 4);
  }
  // ---- layers: one check box per "layer" name of the shapes ----
  var hiddenLayers = {};
  shapes.forEach(function (sh) {
    if (!sh || !sh.layer || hiddenLayers.hasOwnProperty(sh.layer)) return;
    hiddenLayers[sh.layer] = false;
    var lab = document.createElement("label"), box = document.createElement("input");
    box.type = "checkbox"; box.checked = true; box.id = "layer-" + sh.layer;
    box.addEventListener("change", function () { hiddenLayers[sh.layer] = !box.checked; draw(); });
    lab.appendChild(box); lab.appendChild(document.createTextNode(" " + sh.layer));
    document.getElementById("bar").appendChild(lab);
  });

  // ---- force elements and sensors (damper, box, sensor, arrow, torque) ----
  var ELEMENT_COLORS = {
    damper: "#6c5ce7", box: "#4682b4", boxEdge: "#2b4f6e", sensor: "#d35400",
    arrow: "#c0392b", torque: "#8e44ad"
  };
  function drawDamper(sh, k) {
    var a = pt(sh.a, k), b = pt(sh.b, k); if (!a || !b) return;
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.sqrt(dx * dx + dy * dy);
    if (L < 1) return;
    var ux = dx / L, uy = dy / L, nx = -uy, ny = ux, off = sh.offset === undefined ? 0 : val(sh.offset, k);
    if (!isFinite(off)) return;
    var potLen = Math.min(30, 0.6 * L), half = 6;
    var ox = nx * off, oy = ny * off, pot0 = 0.5 * (L - potLen), pot1 = pot0 + potLen, pist = pot0 + 0.6 * potLen;
    function q(d, o) { return [a[0] + ox + ux * d + nx * o, a[1] + oy + uy * d + ny * o]; }
    ctx.strokeStyle = sh.color || ELEMENT_COLORS.damper; ctx.lineWidth = 2;
    ctx.lineCap = "round"; ctx.lineJoin = "miter";
    var s0 = q(0, 0), s1 = q(pot0, 0), p1 = q(pot0, -half), p2 = q(pot1, -half);
    var p3 = q(pot0, half), p4 = q(pot1, half);
    polyline([s0, s1]); ctx.stroke();                         // rod of the pot
    polyline([p2, p1, p3, p4]); ctx.stroke();                 // the pot, open towards b
    var r0 = q(pist, -half + 2), r1 = q(pist, half - 2), e0 = q(pist, 0), e1 = q(L, 0);
    polyline([r0, r1]); ctx.lineWidth = 3; ctx.stroke();      // piston
    polyline([e0, e1]); ctx.lineWidth = 2; ctx.stroke();      // piston rod
  }
  function drawBox(sh, k) {
    var a = pt(sh.a, k), b = pt(sh.b, k), w = worldLen(sh.width, k, 12, 2);
    if (!a || !b || !isFinite(w)) return;
    var dx = b[0] - a[0], dy = b[1] - a[1], L = Math.sqrt(dx * dx + dy * dy);
    ctx.save(); ctx.translate(a[0], a[1]); ctx.rotate(Math.atan2(dy, dx));
    ctx.beginPath(); ctx.rect(0, -w / 2, L, w);
    ctx.fillStyle = sh.color || ELEMENT_COLORS.box; ctx.fill();
    ctx.strokeStyle = ELEMENT_COLORS.boxEdge; ctx.lineWidth = 1.6; ctx.lineJoin = "miter"; ctx.stroke();
    ctx.restore();
  }
  function drawSensor(sh, k) {
    var ps = pts(sh.points, k); if (!ps) return;
    var c = sh.color || ELEMENT_COLORS.sensor;
    if (ps.length > 1) {
      ctx.save(); ctx.setLineDash([2, 3]); polyline(ps);
      ctx.strokeStyle = c; ctx.lineWidth = 1.2; ctx.stroke(); ctx.restore();
    }
    for (var i = 0; i < ps.length; i++) {
      ctx.beginPath(); ctx.rect(ps[i][0] - 3.5, ps[i][1] - 3.5, 7, 7);
      ctx.fillStyle = "#ffffff"; ctx.fill(); ctx.strokeStyle = c; ctx.lineWidth = 1.5; ctx.stroke();
    }
  }
  function largest(sh, key, fn) {  // largest value of fn(frame) over the run, cached per shape
    if (sh[key] === undefined) {
      var m = 0;
      for (var j = 0; j < N; j++) { var v = fn(j); if (isFinite(v) && v > m) m = v; }
      sh[key] = m;
    }
    return sh[key];
  }
  function arrowVector(sh, k) {
    var fx = val(sh.fx, k), fy = val(sh.fy, k);
    var a = (sh.phi === undefined ? 0 : val(sh.phi, k)) + (sh.angle === undefined ? 0 : val(sh.angle, k));
    return [Math.cos(a) * fx - Math.sin(a) * fy, Math.sin(a) * fx + Math.cos(a) * fy];
  }
  function drawArrow(sh, k) {
    var p = pt([sh.x, sh.y], k), f = arrowVector(sh, k); if (!p || !finite(f[0], f[1])) return;
    var mag = Math.sqrt(f[0] * f[0] + f[1] * f[1]), len;
    if (sh.scale !== undefined) { len = Math.abs(val(sh.scale, k)) * mag * view.s; }
    else {
      var top = largest(sh, "_largest", function (j) { var g = arrowVector(sh, j); return Math.sqrt(g[0] * g[0] + g[1] * g[1]); });
      len = top > 0 ? 60 * mag / top : 0;
    }
    if (!(len > 0.5)) return;
    var ux = f[0] / mag, uy = -f[1] / mag, head = Math.min(10, 0.5 * len + 3);
    if (sh.anchor === "tail") p = [p[0] + ux * len, p[1] + uy * len];   // vectors: from the point
    var tail = [p[0] - ux * len, p[1] - uy * len], base = [p[0] - ux * head, p[1] - uy * head];
    var c = sh.color || ELEMENT_COLORS.arrow;
    polyline([tail, base]); ctx.strokeStyle = c; ctx.lineWidth = 2.5; ctx.lineCap = "round"; ctx.stroke();
    ctx.beginPath(); ctx.moveTo(p[0], p[1]);
    ctx.lineTo(base[0] + uy * 0.45 * head, base[1] - ux * 0.45 * head);
    ctx.lineTo(base[0] - uy * 0.45 * head, base[1] + ux * 0.45 * head);
    ctx.closePath(); ctx.fillStyle = c; ctx.fill();
    if (sh.label !== undefined) arrowText(sh.label + " " + (+mag.toPrecision(3)) + " " + (sh.unit || "N"),
                                          tail[0] + 6, tail[1]);
  }
  function drawTorque(sh, k) {
    var p = pt([sh.x, sh.y], k), t = val(sh.t, k); if (!p || !isFinite(t) || t === 0) return;
    var top = sh.scale !== undefined ? 1 / Math.abs(val(sh.scale, k))
      : largest(sh, "_largest", function (j) { return Math.abs(val(sh.t, j)); });
    if (!(top > 0)) return;
    var sweep = Math.min(1, Math.abs(t) / top) * 300 * Math.PI / 180, R = 17, dir = t > 0 ? -1 : 1;
    if (sweep < 0.05) return;
    var a0 = Math.PI / 2, a1 = a0 + dir * sweep, c = sh.color || ELEMENT_COLORS.torque;
    ctx.beginPath(); ctx.arc(p[0], p[1], R, a0, a1, dir < 0);
    ctx.strokeStyle = c; ctx.lineWidth = 2; ctx.lineCap = "round"; ctx.stroke();
    var ex = p[0] + R * Math.cos(a1), ey = p[1] + R * Math.sin(a1);
    var tx = -Math.sin(a1) * dir, ty = Math.cos(a1) * dir;        // direction of travel
    ctx.beginPath(); ctx.moveTo(ex + tx * 7, ey + ty * 7);
    ctx.lineTo(ex - ty * 4, ey + tx * 4); ctx.lineTo(ex + ty * 4, ey - tx * 4);
    ctx.closePath(); ctx.fillStyle = c; ctx.fill();
    if (sh.label !== undefined) arrowText(sh.label + " " + (+Math.abs(t).toPrecision(3)) +
                                          " N\u00b7m", p[0] + R + 6, p[1] - R);
  }

  // Layers, drawn bottom to top; unknown shape types are ignored.
  var LAYERS = {
    trace: [[0, drawTracePath], [90, drawTracePoint]], pulley: [[10, drawPulley]],
    slider: [[15, drawGuide], [60, drawSlider]], ground: [[20, drawGround]],
    belt: [[30, drawBelt]], spring: [[40, drawSpring]], link: [[50, drawLink]],
    body: [[70, drawBody]], joint: [[80, drawJoint]], label: [[100, drawLabel]],
    damper: [[42, drawDamper]], box: [[52, drawBox]], sensor: [[85, drawSensor]],
    arrow: [[95, drawArrow]], torque: [[95, drawTorque]], pole: [[98, drawPole]]
  };
  var ops = [];
  shapes.forEach(function (sh, i) {
    (LAYERS[sh && sh.type] || []).forEach(function (l) { ops.push({ z: l[0], i: i, sh: sh, fn: l[1] }); });
  });
  ops.sort(function (a, b) { return a.z - b.z || a.i - b.i; });

  function niceStep(raw) {
    var p = Math.pow(10, Math.floor(Math.log10(raw))), m = [1, 2, 5, 10];
    for (var i = 0; i < m.length; i++) if (m[i] * p >= raw) return m[i] * p;
    return 10 * p;
  }
  function fmt(x) { return Math.abs(x) >= 1e4 || (Math.abs(x) < 1e-3 && x !== 0) ? x.toExponential(0) : String(+x.toPrecision(6)); }

  function drawGrid() {
    var step = niceStep(70 / view.s);
    var x0 = -view.ox / view.s, x1 = (view.w - view.ox) / view.s;
    var y0 = (view.oy - view.h) / view.s, y1 = view.oy / view.s;
    ctx.lineWidth = 1;
    ctx.beginPath();
    for (var gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
      var sx = Math.round(view.ox + view.s * gx) + 0.5; ctx.moveTo(sx, 0); ctx.lineTo(sx, view.h);
    }
    for (var gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
      var sy = Math.round(view.oy - view.s * gy) + 0.5; ctx.moveTo(0, sy); ctx.lineTo(view.w, sy);
    }
    ctx.strokeStyle = COLORS.grid; ctx.stroke();
    ctx.beginPath();
    if (x0 <= 0 && 0 <= x1) { var ax = Math.round(view.ox) + 0.5; ctx.moveTo(ax, 0); ctx.lineTo(ax, view.h); }
    if (y0 <= 0 && 0 <= y1) { var ay = Math.round(view.oy) + 0.5; ctx.moveTo(0, ay); ctx.lineTo(view.w, ay); }
    ctx.strokeStyle = COLORS.axis; ctx.stroke();
    ctx.font = "11px system-ui, sans-serif"; ctx.fillStyle = "#8a9099";
    ctx.textAlign = "left"; ctx.textBaseline = "bottom";
    gridLabel = "grid " + fmt(step) + " " + (D.unit || "m");
    ctx.fillText(gridLabel, 10, view.h - 8);
  }

  // ---- the signal strip under the mechanism, its cursor synced to the frame ----
  var plotCanvas = document.getElementById("plot"), plotCtx = null, plotView = null;
  var gridLabel = "";
  function fitPlot() {
    if (!D.plot || !plotCanvas) return;
    plotCanvas.hidden = false;
    plotCtx = plotCtx || plotCanvas.getContext("2d");
    var dpr = window.devicePixelRatio || 1;
    var w = Math.max(1, plotCanvas.clientWidth), h = Math.max(1, plotCanvas.clientHeight);
    plotCanvas.width = Math.round(w * dpr); plotCanvas.height = Math.round(h * dpr);
    plotCtx.setTransform(dpr, 0, 0, dpr, 0, 0);
    var y = S[D.plot.signal], lo = Infinity, hi = -Infinity;
    for (var k = 0; k < N; k++) if (y[k] !== null) { lo = Math.min(lo, y[k]); hi = Math.max(hi, y[k]); }
    if (!(hi > lo)) { lo = (isFinite(lo) ? lo : 0) - 1; hi = lo + 2; }
    var t0 = T[0], t1 = N > 1 && T[N - 1] > T[0] ? T[N - 1] : T[0] + 1;
    plotView = { w: w, h: h, left: 64, right: w - 14, top: 18, bottom: h - 18, lo: lo, hi: hi, t0: t0, t1: t1 };
  }
  function plotX(t) { var v = plotView; return v.left + (v.right - v.left) * (t - v.t0) / (v.t1 - v.t0); }
  function plotY(y) { var v = plotView; return v.bottom - (v.bottom - v.top) * (y - v.lo) / (v.hi - v.lo); }
  function drawPlot() {
    if (!plotView) return;
    var c = plotCtx, v = plotView, y = S[D.plot.signal];
    c.fillStyle = "#ffffff"; c.fillRect(0, 0, v.w, v.h);
    c.strokeStyle = COLORS.axis; c.lineWidth = 1; c.strokeRect(v.left, v.top, v.right - v.left, v.bottom - v.top);
    c.beginPath();
    var pen = false;
    for (var k = 0; k < N; k++) {
      if (y[k] === null) { pen = false; continue; }
      if (pen) c.lineTo(plotX(T[k]), plotY(y[k])); else c.moveTo(plotX(T[k]), plotY(y[k]));
      pen = true;
    }
    c.strokeStyle = COLORS.plotLine; c.lineWidth = 1.5; c.stroke();
    var cx = Math.round(plotX(T[frame])) + 0.5;
    c.beginPath(); c.moveTo(cx, v.top); c.lineTo(cx, v.bottom);
    c.strokeStyle = COLORS.cursor; c.lineWidth = 2; c.stroke();
    c.font = "11px system-ui, sans-serif"; c.fillStyle = COLORS.text;
    c.textAlign = "left"; c.textBaseline = "top";
    var cur = y[frame] === null ? "" : " = " + fmt(y[frame]);
    c.fillText(D.plot.label + cur, v.left + 4, 3);
    c.textAlign = "right"; c.textBaseline = "middle";
    c.fillText(fmt(v.hi), v.left - 4, v.top); c.fillText(fmt(v.lo), v.left - 4, v.bottom);
  }
  function plotCursor() {
    return plotView ? { x: plotX(T[frame]), t: T[frame] } : null;
  }

  function fit() {
    var dpr = window.devicePixelRatio || 1;
    var w = Math.max(1, canvas.clientWidth), h = Math.max(1, canvas.clientHeight);
    canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    var b = D.bbox, pad = 34, top = D.title ? 44 : pad;
    var bw = b[2] - b[0], bh = b[3] - b[1], size = Math.max(bw, bh) || 1;
    if (!(bw > 0)) { bw = size * 1e-3; }
    if (!(bh > 0)) { bh = size * 1e-3; }
    var aw = Math.max(10, w - 2 * pad), ah = Math.max(10, h - pad - top);
    var s = Math.min(aw / bw, ah / bh);
    view = { s: s, w: w, h: h,
             ox: pad + (aw - s * bw) / 2 - s * b[0],
             oy: top + (ah - s * bh) / 2 + s * b[3] };
  }

  function draw() {
    ctx.fillStyle = COLORS.background; ctx.fillRect(0, 0, view.w, view.h);
    drawGrid();
    for (var i = 0; i < ops.length; i++) {
      if (ops[i].sh.layer && hiddenLayers[ops[i].sh.layer]) continue;
      ctx.save();
      try { ops[i].fn(ops[i].sh, frame); } finally { ctx.restore(); }
    }
    if (D.title) {
      ctx.font = "600 15px system-ui, -apple-system, 'Segoe UI', Roboto, Helvetica, Arial, sans-serif";
      ctx.fillStyle = COLORS.text; ctx.textAlign = "left"; ctx.textBaseline = "top";
      ctx.fillText(D.title, 12, 12);
    }
    timeOut.textContent = "t = " + (N ? T[frame].toFixed(3) : "0") + " s  (" + (frame + 1) + "/" + N + ")";
    scrub.value = String(frame);
    drawPlot();
  }

  function findFrame(simT) {  // last frame with clock <= simT
    var lo = 0, hi = N - 1;
    if (simT <= clock[0]) return 0;
    if (simT >= clock[hi]) return hi;
    while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (clock[mid] <= simT) lo = mid; else hi = mid; }
    return lo;
  }
  function speed() { var v = parseFloat(speedSel.value); return v > 0 ? v : 1; }
  function anchor() { anchorWall = performance.now(); anchorSim = clock[frame]; }

  function setFrame(i) {
    i = Math.round(+i);
    if (!isFinite(i)) i = 0;
    frame = Math.max(0, Math.min(N - 1, i));
    if (playing) anchor();
    draw();
    return frame;
  }
  function tick(now) {
    rafId = null;
    if (!playing) return;
    var simT = anchorSim + (now - anchorWall) / 1000 * speed();
    if (simT >= clock[N - 1]) {
      if (loopBox.checked && N > 1) {
        frame = 0; anchorWall = now; anchorSim = clock[0];
      } else {
        frame = N - 1; draw(); pause(); return;
      }
    } else {
      frame = findFrame(simT);
    }
    draw();
    rafId = window.requestAnimationFrame(tick);
  }
  function play() {
    if (playing || N < 2) return;
    if (frame >= N - 1) frame = 0;
    playing = true; playBtn.textContent = "Pause";
    anchor();
    rafId = window.requestAnimationFrame(tick);
  }
  function pause() {
    playing = false; playBtn.textContent = "Play";
    if (rafId !== null) { window.cancelAnimationFrame(rafId); rafId = null; }
  }

  function frameFromHash() {
    var m = /(?:^#|&)frame=(-?\d+)/.exec(window.location.hash || "");
    return m ? parseInt(m[1], 10) : null;
  }

  playBtn.addEventListener("click", function () { if (playing) pause(); else play(); });
  scrub.addEventListener("input", function () { setFrame(parseInt(scrub.value, 10)); });
  speedSel.addEventListener("change", function () {
    if (playing) { anchorSim = anchorSim + (performance.now() - anchorWall) / 1000 * speed(); anchor(); }
  });
  window.addEventListener("resize", function () { fitPlot(); fit(); draw(); });
  window.addEventListener("hashchange", function () {
    var h = frameFromHash(); if (h !== null) setFrame(h);
  });
  document.addEventListener("keydown", function (e) {
    var tag = e.target && e.target.tagName;
    if (tag === "INPUT" || tag === "SELECT" || tag === "BUTTON" || tag === "TEXTAREA") return;
    if (e.key === " ") { e.preventDefault(); if (playing) pause(); else play(); }
    else if (e.key === "ArrowRight") { setFrame(frame + 1); }
    else if (e.key === "ArrowLeft") { setFrame(frame - 1); }
    else if (e.key === "Home") { setFrame(0); }
    else if (e.key === "End") { setFrame(N - 1); }
  });

  scrub.max = String(Math.max(0, N - 1));
  var h0 = frameFromHash();
  frame = h0 === null ? 0 : Math.max(0, Math.min(N - 1, h0));
  fitPlot();
  fit();
  draw();
  if (D.autoplay || /(?:^[?#]|[?&#])autoplay(?:[=&#]|$)/.test(window.location.search + window.location.hash)) play();

  window.acausal2d = {
    get frame() { return frame; },
    nframes: N,
    get playing() { return playing; },
    setFrame: setFrame,
    play: play,
    pause: pause,
    errors: errors,
    scene: D,
    get gridLabel() { return gridLabel; },
    plotCursor: plotCursor,
    canvas: canvas,
    setOverride: function (f) { override = f || null; draw(); },
    redraw: function () { draw(); },
    toWorld: function (px, py) { return [(px - view.ox) / view.s, (view.oy - py) / view.s]; },
    toScreen: function (x, y) { return P(x, y); },
    signal: function (name, k) { var a = S[name]; return a ? a[k] : undefined; }
  };
})();
