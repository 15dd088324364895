(function () {
  "use strict";
  // The model's diagram on the explore page (see acausal2d/visual/diagram.py): shown beside the
  // animation, instead of it for a model without planar geometry.  A sub-model's box opens its
  // own diagram; a component's box shows its parameters (the sliders on the left) and its
  // signals; during playback each connection shows its flow at the animation's time.
  var levels = {}, level = null, selected = null, index = 0, playing = false, lastTick = 0;
  var SYMBOL = { tau: "\u03c4", f: "f", q: "q", u: "u", fx: "fx", fy: "fy", t: "t" };

  function $(id) { return document.getElementById(id); }
  function el(tag, attrs, text) {
    var e = document.createElement(tag);
    Object.keys(attrs || {}).forEach(function (k) { e.setAttribute(k, attrs[k]); });
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function fmt(x) { return String(+(+x).toPrecision(3)); }
  function full(path) { return level ? level + "." + path : path; }

  var css = el("style", {}, "#diagram-pane{border-bottom:1px solid #dde1e6;background:#fbfbfc;flex:none}" +
    "#diagram-bar{display:flex;gap:8px;align-items:center;padding:4px 8px;flex-wrap:wrap}" +
    "#diagram-bar a{color:#1f6fb4;cursor:pointer;text-decoration:underline}" +
    "#diagram{overflow:auto;max-height:460px}#diagram svg{display:block;height:auto}" +
    "#diagram .box{cursor:pointer}#diagram-time{width:160px}" +
    "#diagram-row{display:flex;flex:none;border-bottom:1px solid #dde1e6}" +
    "#diagram-row>#diagram-pane{flex:1 1 50%;min-width:0;border-bottom:0;border-right:1px solid #dde1e6}" +
    "#diagram-row>#diagram-pane #diagram{max-height:310px}" +
    "#diagram-row>#anim{flex:1 1 50%;min-width:0;border-bottom:0}" +
    "#selection{margin:0 0 8px;padding:6px;background:#fff7e6;border:1px solid #f5c26b}" +
    "#selection button{margin:2px 4px 0 0;font-size:11px}");
  document.head.appendChild(css);

  // ---- levels: the model, then a sub-model's diagram, one level at a time ----
  function crumbs() {
    var bar = $("diagram-bar"), parts = level ? level.split(".") : [];
    bar.textContent = "";
    bar.appendChild(el("strong", {}, "diagram"));
    [explore.meta.model].concat(parts).forEach(function (name, i) {
      var here = parts.slice(0, i).join(".");
      if (i) bar.appendChild(document.createTextNode("\u25b8"));
      var a = el(i < parts.length ? "a" : "span", {}, name);
      if (i < parts.length) a.addEventListener("click", function () { open(here); });
      bar.appendChild(a);
    });
    var time = el("input", { id: "diagram-time", type: "range", min: 0, max: 1000, value: 0,
                              "aria-label": "time of the flows shown" });
    time.addEventListener("input", function () { seek(+time.value / 1000); });
    var play = el("button", { id: "diagram-play", type: "button" }, "Play");
    play.addEventListener("click", function () { playing = !playing; play.textContent = playing ? "Pause" : "Play"; });
    bar.appendChild(play); bar.appendChild(time); bar.appendChild(el("span", { id: "diagram-t" }));
  }
  function open(path) {
    level = path;
    $("diagram").innerHTML = levels[path];
    Array.prototype.forEach.call($("diagram").querySelectorAll(".box"), function (b) {
      b.addEventListener("click", function (e) {
        e.stopPropagation();
        var p = full(b.getAttribute("data-path"));
        if (b.classList.contains("submodel") && levels[p] !== undefined) open(p);
        else if (!b.classList.contains("external")) select(p);
      });
    });
    crumbs();
    select(null);
    fit();
    showFlows();
  }

  // ---- a component chosen: its sliders on the left, its signals to plot ----
  function paramName(box) {
    var input = box.querySelector("input[data-param]");
    return input ? input.getAttribute("data-param").replace(/\[\d+\]$/, "") : "";
  }
  function select(path) {
    selected = path;
    Array.prototype.forEach.call($("diagram").querySelectorAll(".box"), function (b) {
      b.classList.toggle("selected", path !== null && full(b.getAttribute("data-path")) === path);
    });
    var shown = 0;
    Array.prototype.forEach.call($("controls").querySelectorAll(".param"), function (box) {
      var mine = path === null || paramName(box).indexOf(path + ".") === 0;
      box.hidden = !mine;
      shown += mine ? 1 : 0;
    });
    var info = $("selection");
    if (info) info.remove();
    if (path === null) return;
    info = el("div", { id: "selection" });
    info.appendChild(el("strong", {}, path));
    info.appendChild(document.createTextNode(": " + shown + " parameter" + (shown === 1 ? "" : "s") + " "));
    var all = el("a", { href: "#" }, "(show all)");
    all.addEventListener("click", function (e) { e.preventDefault(); select(null); });
    info.appendChild(all);
    info.appendChild(el("div", { "class": "rule" }, "signals (click to plot):"));
    explore.meta.signals.filter(function (s) { return s.name.indexOf(path + ".") === 0; })
      .slice(0, 40).forEach(function (s) {
        var b = el("button", { type: "button", "data-signal": s.name }, s.name.slice(path.length + 1));
        b.addEventListener("click", function () { $("pick").value = s.name; $("add").click(); });
        info.appendChild(b);
      });
    $("controls").insertBefore(info, $("controls").firstChild);
  }

  // ---- flows at the time shown: the animation's frame, else the time slider ----
  function anim() {
    var f = $("anim");
    return f && !f.hidden && f.contentWindow ? f.contentWindow.acausal2d : null;
  }
  function seek(frac) {
    var a = anim(), run = explore.current;
    if (a) { a.pause(); a.setFrame(Math.round(frac * (a.nframes - 1))); }
    if (run) index = Math.round(frac * (run.data.time.length - 1));
    showFlows();
  }
  function label(name, v) {
    var unit = (explore.meta.signals.filter(function (s) { return s.name === name; })[0] || {}).unit;
    var key = name.split(".").pop();
    return (SYMBOL[key] || key) + " = " + fmt(v) + (unit ? " " + unit : "");
  }
  function lineText(names, flows) {
    var v = {}, parts = [];
    names.forEach(function (n) {
      if (n && flows[n] && flows[n][index] !== null) v[n.split(".").pop()] = [n, flows[n][index]];
    });
    if (v.fx && v.fy) {                // a planar frame: the force's size
      var f = Math.sqrt(v.fx[1] * v.fx[1] + v.fy[1] * v.fy[1]);
      return "|f| = " + fmt(f) + " N";
    }
    Object.keys(v).forEach(function (k) { parts.push(label(v[k][0], v[k][1])); });
    return parts.join(", ");
  }
  function showFlows() {
    var run = explore.current, flows = run && run.data.flows;
    if (!flows) return;
    index = Math.max(0, Math.min(index, run.data.time.length - 1));
    Array.prototype.forEach.call($("diagram").querySelectorAll("path.line"), function (line) {
      var text = $("diagram").querySelector("#flow-" + line.id.slice(5));
      if (text) text.textContent = lineText((line.getAttribute("data-flows") || "").split(" "), flows);
    });
    var t = run.data.time[index];
    if ($("diagram-t")) $("diagram-t").textContent = "t = " + fmt(t) + " s";
    if ($("diagram-time")) $("diagram-time").value = Math.round(1000 * index / Math.max(1, run.data.time.length - 1));
  }
  function fit() {                     // fit the pane's width, but never below 60 % of full size
    var svg = $("diagram").querySelector("svg"), pane = $("diagram");
    if (!svg) return;
    var w = +svg.getAttribute("width"), pw = pane.clientWidth || w;
    svg.style.width = Math.max(Math.min(w, pw), 0.6 * w) + "px";
  }
  function tick() {
    var run = explore.current, a = anim(), now = performance.now();
    if (run && a && a.playing && a.nframes > 1) {
      index = Math.round(a.frame / (a.nframes - 1) * (run.data.time.length - 1));
      showFlows();
    } else if (run && playing && now - lastTick > 40) {
      lastTick = now;
      index = (index + Math.max(1, Math.round(run.data.time.length / 200))) % run.data.time.length;
      showFlows();
    } else if (run && run !== tick.last) {
      showFlows();
    }
    tick.last = run;
    requestAnimationFrame(tick);
  }

  function start() {
    var meta = window.explore && explore.meta;
    if (!meta || !$("controls").querySelector(".param") && meta.parameters.length) {
      setTimeout(start, 50);
      return;
    }
    (meta.diagrams || []).forEach(function (d) { levels[d.path] = d.svg; });
    if (levels[""] === undefined) return;
    $("diagram-pane").hidden = false;
    if (!meta.planar) {
      $("anim").hidden = true;
    } else {                              // side by side: the diagram beside the animation
      var row = el("div", { id: "diagram-row" });
      $("anim").parentNode.insertBefore(row, $("anim"));
      row.appendChild($("diagram-pane"));
      row.appendChild($("anim"));
    }
    open("");
    window.addEventListener("resize", fit);
    requestAnimationFrame(tick);
  }
  start();

  // for scripts and tests
  window.exploreDiagram = {
    get level() { return level; }, get selected() { return selected; },
    get index() { return index; }, open: open, select: select, seek: seek
  };
})();
