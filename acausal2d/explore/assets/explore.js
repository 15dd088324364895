(function () {
  "use strict";
  // acausal2d explore: the page of `acausal2d explore` (see acausal2d/explore/server.py).
  var session = "tab-" + Math.random().toString(36).slice(2, 12);
  var meta = null, values = {}, defaults = {}, units = {}, starts = {};
  var current = null, previous = null, pins = [], figures = [];
  var inflight = null, pending = false, sent = 0, shown = 0, runs = 0, lastError = null;
  var sceneLoads = 0, dragStart = null, drags = 0, csvBytes = 0;
  var LINE = ["#4682b4", "#e07b00", "#2e9e4f", "#8e44ad", "#c0392b", "#16a085"];
  var PIN = ["#d35400", "#27ae60", "#7f8c8d", "#9b59b6", "#2c3e50"];
  var TOKEN = new URLSearchParams(location.search).get("token") || "";  // the API's token
  var WAIT_MS = 400;  // a run still going after this is overtaken by the next change

  function $(id) { return document.getElementById(id); }
  function fmt(x) { return String(+(+x).toPrecision(6)); }
  function el(tag, attrs, text) {
    var e = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) { e.setAttribute(k, attrs[k]); });
    if (text !== undefined) e.textContent = text;
    return e;
  }

  // ---- the request of the current controls ----
  function changed(name) {
    return values[name].some(function (v, i) { return v !== defaults[name][i]; });
  }
  function changedSet() {
    var set = {};
    Object.keys(values).forEach(function (n) {
      if (changed(n)) set[n] = values[n].length === 1 ? values[n][0] : values[n].slice();
    });
    return set;
  }
  function wanted() {
    var names = {};
    figures.forEach(function (f) {
      f.groups.forEach(function (g) { g.forEach(function (n) { names[n] = 1; }); });
      if (f.x && f.x !== "time") names[f.x] = 1;
    });
    return Object.keys(names);
  }
  function request(scene) {
    return { set: changedSet(), stop_time: +$("stop").value, signals: wanted(), scene: scene,
             session: session, start: starts };
  }

  // ---- runs: one in flight, the newest change waits for it (or overtakes it after WAIT_MS) ----
  function schedule() {
    if (inflight && performance.now() - inflight.started < WAIT_MS) {
      pending = true;
      setTimeout(function () { if (pending) schedule(); }, WAIT_MS);
      return;
    }
    send();
  }
  function post(url, body) {
    return fetch(url, { method: "POST", headers: { "Content-Type": "application/json",
                                                   "X-Acausal2d-Token": TOKEN },
                        body: JSON.stringify(body) });
  }
  function send() {
    pending = false;
    var body = request(true), mine = { started: performance.now(), n: ++sent };
    inflight = mine;
    status("running ...");
    post("/api/run", body).then(function (r) {
      return r.json().then(function (d) { return { status: r.status, data: d }; });
    }).then(function (a) {
      if (inflight === mine) inflight = null;
      if (a.status === 200 && mine.n > shown) {
        shown = mine.n;
        show(a.data, body, performance.now() - mine.started);
      } else if (a.status !== 200 && a.status !== 409) {
        fail(a.data.error || "HTTP " + a.status);
      }
      if (pending && !inflight) send();
    }, function (e) {
      if (inflight === mine) inflight = null;
      fail("no answer from the server: " + e);
    });
  }
  function status(text) { $("status").textContent = text; }
  function fail(message) {
    lastError = message;
    $("error").textContent = message;
    $("error").hidden = false;
    status("run failed");
  }
  function show(data, body, roundTrip) {
    previous = current;
    current = { data: data, set: body.set, stop_time: body.stop_time, start: body.start };
    runs += 1;
    lastError = null;
    $("error").hidden = true;
    status("run " + runs + ": " + fmt(data.elapsed_s.toFixed(3)) + " s simulating, " +
           fmt((roundTrip / 1000).toFixed(3)) + " s round trip" +
           (data.stopped ? "; stopped early: " + data.stopped : ""));
    if (data.scene) showScene(data.scene);
    drawFigures();
  }

  // ---- the animation: the scene page of `simulate`, kept at its frame across runs ----
  function showScene(html) {
    var f = $("anim"), old = f.contentWindow && f.contentWindow.acausal2d;
    var keep = old ? { frac: old.nframes > 1 ? old.frame / (old.nframes - 1) : 0,
                       playing: old.playing } : { frac: 0, playing: true };
    f.onload = function () {
      var a = f.contentWindow.acausal2d;
      if (a) {
        a.setFrame(Math.round(keep.frac * (a.nframes - 1)));
        if (keep.playing) a.play();
        attachDrag(f.contentWindow);
      }
      sceneLoads += 1;
    };
    f.srcdoc = html;
  }

  // ---- dragging a joint of the mechanism: its start position, re-assembled and re-run ----
  function nearestPoint(w, px, py) {
    var a = w.acausal2d, best = null;
    a.scene.shapes.forEach(function (sh) {
      if ((sh.type !== "joint" && sh.type !== "body") || typeof sh.x !== "string") return;
      var x = a.signal(sh.x, 0), y = a.signal(sh.y, 0);
      if (x === undefined || x === null || y === null) return;
      var p = a.toScreen(x, y), d = Math.hypot(p[0] - px, p[1] - py);
      if (d < 14 && (!best || d < best.d)) best = { d: d, x: sh.x, y: sh.y };
    });
    return best;
  }
  function attachDrag(w) {
    var canvas = w.document.getElementById("view");
    canvas.addEventListener("mousedown", function (e) {
      if (!w.acausal2d || w.acausal2d.frame !== 0) return;   // start positions: frame 0
      dragStart = nearestPoint(w, e.offsetX, e.offsetY);
      if (dragStart) { w.acausal2d.pause(); e.preventDefault(); }
    });
    canvas.addEventListener("mouseup", function (e) {
      if (!dragStart) return;
      var to = w.acausal2d.toWorld(e.offsetX, e.offsetY), grab = dragStart;
      dragStart = null;
      moveStart(grab, to);
    });
  }
  function moveStart(grab, to) {
    var body = request(false);
    body.drag = { x: grab.x, y: grab.y, to: to };
    status("assembling ...");
    post("/api/start", body).then(function (r) {
      return r.json().then(function (d) { return { status: r.status, data: d }; });
    }).then(function (a) {
      if (a.status !== 200) { fail(a.data.error || "HTTP " + a.status); return; }
      starts = a.data.start;
      drags += 1;
      send();
    }, function (e) { fail("no answer from the server: " + e); });
  }

  // ---- figures: current run, the previous one faint, pinned runs dashed ----
  function xValues(run, f) {
    if (!f.x || f.x === "time") return run.time;
    var v = run.signals[f.x];
    if (units[f.x] !== "rad") return v;
    var out = [], off = 0;
    for (var i = 0; i < v.length; i++) {
      if (i > 0 && v[i] !== null && v[i - 1] !== null) {
        var d = v[i] - v[i - 1];
        if (d > Math.PI) off -= 2 * Math.PI; else if (d < -Math.PI) off += 2 * Math.PI;
      }
      out.push(v[i] === null ? null : (v[i] + off) * 180 / Math.PI);
    }
    return out;
  }
  function niceStep(span) {
    var raw = span / 5, p = Math.pow(10, Math.floor(Math.log10(raw))), m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }
  function extent(runs, f) {
    var box = { x0: Infinity, x1: -Infinity, y0: Infinity, y1: -Infinity };
    runs.forEach(function (run) {
      var xs = xValues(run, f);
      f.groups[f.group].forEach(function (n) {
        (run.signals[n] || []).forEach(function (y, i) {
          if (y === null || xs[i] === null) return;
          box.x0 = Math.min(box.x0, xs[i]); box.x1 = Math.max(box.x1, xs[i]);
          box.y0 = Math.min(box.y0, y); box.y1 = Math.max(box.y1, y);
        });
      });
    });
    if (!(box.x1 > box.x0)) { box.x0 -= 1; box.x1 += 1; }
    if (!(box.y1 > box.y0)) { var c = isFinite(box.y0) ? box.y0 : 0; box.y0 = c - 1; box.y1 = c + 1; }
    var pad = 0.05 * (box.y1 - box.y0);
    box.y0 -= pad; box.y1 += pad;
    return box;
  }
  function axes(ctx, box, v, f) {
    ctx.strokeStyle = "#dde1e6"; ctx.fillStyle = "#6b6f75"; ctx.lineWidth = 1;
    ctx.strokeRect(v.l, v.t, v.r - v.l, v.b - v.t);
    ctx.font = "11px sans-serif"; ctx.textAlign = "center";
    var s = niceStep(box.x1 - box.x0), x;
    for (x = Math.ceil(box.x0 / s) * s; x <= box.x1; x += s) ctx.fillText(fmt(x), v.X(x), v.b + 13);
    ctx.textAlign = "right";
    s = niceStep(box.y1 - box.y0);
    for (var y = Math.ceil(box.y0 / s) * s; y <= box.y1; y += s) ctx.fillText(fmt(y), v.l - 4, v.Y(y) + 4);
    ctx.textAlign = "left";
    var xl = !f.x || f.x === "time" ? "time [s]" : f.x + " [" + (units[f.x] === "rad" ? "deg" : units[f.x] || "-") + "]";
    ctx.fillText(xl, v.r - ctx.measureText(xl).width, v.b + 26);
  }
  function curve(ctx, v, xs, ys, style) {
    ctx.strokeStyle = style.color; ctx.globalAlpha = style.alpha; ctx.lineWidth = style.width;
    ctx.setLineDash(style.dash || []);
    ctx.beginPath();
    var up = true;
    for (var i = 0; i < ys.length; i++) {
      if (ys[i] === null || xs[i] === null) { up = true; continue; }
      if (up) ctx.moveTo(v.X(xs[i]), v.Y(ys[i])); else ctx.lineTo(v.X(xs[i]), v.Y(ys[i]));
      up = false;
    }
    ctx.stroke();
    ctx.globalAlpha = 1; ctx.setLineDash([]);
  }
  function drawFigure(f) {
    var c = f.canvas, w = c.clientWidth, h = c.clientHeight, dpr = window.devicePixelRatio || 1;
    c.width = w * dpr; c.height = h * dpr;
    var ctx = c.getContext("2d");
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.clearRect(0, 0, w, h);
    var shownRuns = [current, previous].concat(pins).filter(Boolean).map(function (r) { return r.data; });
    if (!current) return;
    var box = extent(shownRuns, f);
    var v = { l: 60, r: w - 12, t: 20, b: h - 30 };
    v.X = function (x) { return v.l + (v.r - v.l) * (x - box.x0) / (box.x1 - box.x0); };
    v.Y = function (y) { return v.b - (v.b - v.t) * (y - box.y0) / (box.y1 - box.y0); };
    axes(ctx, box, v, f);
    var names = f.groups[f.group];
    pins.forEach(function (p, k) {
      names.forEach(function (n) {
        if (p.data.signals[n]) curve(ctx, v, xValues(p.data, f), p.data.signals[n], { color: PIN[k % PIN.length], alpha: 0.9, width: 1.5, dash: [6, 4] });
      });
    });
    names.forEach(function (n, k) {
      if (previous && previous.data.signals[n]) curve(ctx, v, xValues(previous.data, f), previous.data.signals[n], { color: LINE[k % LINE.length], alpha: 0.25, width: 2 });
      if (current.data.signals[n]) curve(ctx, v, xValues(current.data, f), current.data.signals[n], { color: LINE[k % LINE.length], alpha: 1, width: 2 });
      ctx.fillStyle = LINE[k % LINE.length];
      ctx.fillText(n + " [" + (units[n] || "-") + "]", v.l + 6 + 170 * k, v.t - 6);
    });
  }
  function drawFigures() { figures.forEach(drawFigure); }
  function addFigure(spec) {
    spec.groups.forEach(function (g, k) {
      var f = { groups: spec.groups, group: k, x: spec.x, title: spec.title,
                canvas: el("canvas", { "aria-label": g.join(", ") }) };
      $("figures").appendChild(f.canvas);
      figures.push(f);
    });
  }

  // ---- pins and export ----
  function showPins() {
    var box = $("pins");
    box.textContent = "";
    pins.forEach(function (p, k) {
      var b = el("button", { type: "button", title: "remove this pinned run" }, "\u00d7 " + p.label);
      b.style.color = PIN[k % PIN.length];
      b.addEventListener("click", function () { pins.splice(k, 1); showPins(); drawFigures(); });
      box.appendChild(b);
    });
  }
  function pin() {
    if (!current) return;
    pins.push({ data: current.data, set: current.set, label: "pin " + (pins.length + 1) });
    showPins(); drawFigures();
  }
  function setOptions() {
    var parts = ["acausal2d simulate " + meta.file];
    Object.keys(current ? current.set : {}).forEach(function (n) {
      parts.push("--set " + n + "=" + [].concat(current.set[n]).map(fmt).join(","));
    });
    parts.push("--stop-time " + fmt(current ? current.stop_time : +$("stop").value));
    var st = Object.keys(current ? current.start : {}).map(function (n) { return n + "=" + fmt(current.start[n]); });
    return parts.join(" ") + (st.length ? "\n# start values (dragged): " + st.join(", ") : "");
  }
  function exportSet() {
    var box = $("export");
    box.value = setOptions();
    box.hidden = false;
    box.select();
  }
  function exportCsv() {
    var body = request(false);
    delete body.session;          // the export must not stop the page's own run
    post("/api/csv", body).then(function (r) {
      if (!r.ok) return r.json().then(function (d) { fail(d.error); });
      return r.blob().then(function (b) {
        csvBytes = b.size;
        var a = el("a", { href: URL.createObjectURL(b), download: meta.model + ".csv" });
        document.body.appendChild(a); a.click(); a.remove();
      });
    });
  }

  // ---- a control per parameter: a slider and a number field per component ----
  function setValue(name, vals) {
    values[name] = vals.slice();
    (controls[name] || []).forEach(function (c, i) {
      c.range.value = vals[i]; c.number.value = fmt(vals[i]); c.number.classList.remove("bad");
    });
  }
  var controls = {};
  function control(p) {
    var box = el("div", { "class": "param", title: p.doc });
    box.appendChild(el("div", { "class": "name" }, p.name + " [" + (p.unit || "-") + "]"));
    if (p.rule) box.appendChild(el("div", { "class": "rule" }, "rule: " + p.rule));
    controls[p.name] = p.value.map(function (v, i) {
      var row = el("div", { "class": "row" });
      var r = p.range[i], label = p.name + (p.value.length > 1 ? "[" + i + "]" : "");
      var range = el("input", { type: "range", min: r[0], max: r[1], step: (r[1] - r[0]) / 400 || "any", value: v, "aria-label": label, "data-param": label });
      var number = el("input", { type: "number", step: "any", value: fmt(v), "aria-label": label + " value" });
      range.addEventListener("input", function () {
        values[p.name][i] = +range.value; number.value = fmt(range.value); schedule();
      });
      number.addEventListener("change", function () {
        var x = parseFloat(number.value);
        number.classList.toggle("bad", !isFinite(x));
        if (!isFinite(x)) return;
        values[p.name][i] = x; range.value = x; schedule();
      });
      row.appendChild(range); row.appendChild(number); box.appendChild(row);
      return { range: range, number: number };
    });
    return box;
  }

  function start(m) {
    meta = m;
    $("model").textContent = m.model;
    document.title = m.model + " - acausal2d explore";
    $("stop").value = m.stop_time; $("stop").max = m.max_stop_time;
    m.signals.forEach(function (s) {
      units[s.name] = s.unit;
      $("pick").appendChild(el("option", { value: s.name }, s.name + " [" + (s.unit || "-") + "]"));
    });
    m.parameters.forEach(function (p) {
      values[p.name] = p.value.slice(); defaults[p.name] = p.value.slice();
      $("controls").appendChild(control(p));
    });
    m.figures.forEach(addFigure);
    send();
  }

  $("pin").addEventListener("click", pin);
  $("export-set").addEventListener("click", exportSet);
  $("export-csv").addEventListener("click", exportCsv);
  $("reset").addEventListener("click", function () {
    Object.keys(defaults).forEach(function (n) { setValue(n, defaults[n]); });
    starts = {};
    schedule();
  });
  $("stop").addEventListener("change", schedule);
  $("add").addEventListener("click", function () {
    addFigure({ groups: [[$("pick").value]], x: null, title: null }); send();
  });
  window.addEventListener("resize", drawFigures);
  fetch("/api/params", { headers: { "X-Acausal2d-Token": TOKEN } }).then(function (r) { return r.json(); }).then(start, function (e) {
    fail("cannot read the model from the server: " + e);
  });

  // for scripts and tests
  window.explore = {
    get runs() { return runs; }, get current() { return current; },
    get previous() { return previous; }, get pins() { return pins; },
    get error() { return lastError; }, get sceneLoads() { return sceneLoads; },
    get busy() { return !!inflight || pending; }, get drags() { return drags; },
    get starts() { return starts; }, get csvBytes() { return csvBytes; },
    get meta() { return meta; },
    session: session, values: values, figures: figures, setOptions: setOptions,
    send: send, moveStart: moveStart
  };
})();
