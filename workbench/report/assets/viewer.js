/* trunk-workbench 3-D backbone viewer: a small dependency-free canvas viewer (orthographic view).
 * Data: the JSON block #wb-scenes ({frame, cases: [{id, title, gravity, L, disks, tendons, main,
 * models: {name: {label, color, reference, stations, frames: [[t, [[x, y, z], ...]], ...]}},
 * optional markers: [{label, color, size, points}] (measured points, drawn as crosses), note}]}),
 * points already in the report's frame (world by default, z up).  Drag: rotate; wheel: zoom;
 * double click: reset.  Disks and tendons are drawn on the main model's backbone with a
 * rotation-minimising frame (the backbone twist is not stored).  Checked by tests/report/.
 */
(function () {
  "use strict";
  var root = document.getElementById("wb-viewer");
  var dataEl = document.getElementById("wb-scenes");
  if (!root || !dataEl) { return; }
  var data = JSON.parse(dataEl.textContent);
  var canvas = root.querySelector("canvas");
  var ctx = canvas.getContext("2d");
  var sel = root.querySelector("select.wb-case");
  var slider = root.querySelector("input.wb-time");
  var play = root.querySelector("button.wb-play");
  var tlabel = root.querySelector("span.wb-tlabel");
  var info = root.querySelector("div.wb-info");
  var showDisks = root.querySelector("input.wb-disks");
  var showTendons = root.querySelector("input.wb-tendons");
  var view = { yaw: -0.6, pitch: 0.35, zoom: 1.0 };
  var state = { c: 0, t: 0, timer: null, times: [0] };

  function rot(p) {  // world -> view: yaw about z, then pitch about the view x axis
    var cy = Math.cos(view.yaw), sy = Math.sin(view.yaw), cp = Math.cos(view.pitch), sp = Math.sin(view.pitch);
    var x = cy * p[0] - sy * p[1], y = sy * p[0] + cy * p[1], z = p[2];
    return [x, cp * y - sp * z, sp * y + cp * z];
  }
  function frameAt(model, t) {  // the stored frame nearest to t
    var fr = model.frames, best = 0;
    for (var i = 0; i < fr.length; i++) { if (Math.abs(fr[i][0] - t) < Math.abs(fr[best][0] - t)) { best = i; } }
    return fr[best][1];
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function unit(a) { var n = Math.sqrt(dot(a, a)) || 1; return [a[0] / n, a[1] / n, a[2] / n]; }
  function lerp(a, b, f) { return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])]; }
  function localFrames(P, e0) {  // tangent and a rotation-minimising normal pair at every point
    var out = [], e = e0.slice();
    for (var i = 0; i < P.length; i++) {
      var d = sub(P[Math.min(i + 1, P.length - 1)], P[Math.max(i - 1, 0)]);
      var t = unit(d);
      var k = dot(e, t);
      e = unit([e[0] - k * t[0], e[1] - k * t[1], e[2] - k * t[2]]);
      out.push([P[i], e, cross(t, e)]);
    }
    return out;
  }
  function at(F, stations, s) {  // interpolated (centre, e1, e2) at arc length s
    var j = 0;
    while (j < stations.length - 2 && stations[j + 1] < s) { j++; }
    var f = (s - stations[j]) / ((stations[j + 1] - stations[j]) || 1);
    f = Math.max(0, Math.min(1, f));
    return [lerp(F[j][0], F[j + 1][0], f), unit(lerp(F[j][1], F[j + 1][1], f)), unit(lerp(F[j][2], F[j + 1][2], f))];
  }
  function ringPoint(c, r, u) {
    return [c[0][0] + r * (Math.cos(u) * c[1][0] + Math.sin(u) * c[2][0]),
            c[0][1] + r * (Math.cos(u) * c[1][1] + Math.sin(u) * c[2][1]),
            c[0][2] + r * (Math.cos(u) * c[1][2] + Math.sin(u) * c[2][2])];
  }

  function draw() {
    var cs = data.cases[state.c];
    var W = canvas.width, H = canvas.height;
    ctx.fillStyle = "#ffffff";
    ctx.fillRect(0, 0, W, H);
    var t = state.times[state.t] || 0;
    var names = Object.keys(cs.models), lines = [];
    names.forEach(function (m) { lines.push([m, frameAt(cs.models[m], t)]); });
    var L = cs.L || 1, scale = 0.8 * Math.min(W, H) / (cs.extent || L) * view.zoom;
    var c0 = rot(cs.center);
    function scr(p) { var q = rot(p); return [W / 2 + scale * (q[0] - c0[0]), H / 2 - scale * (q[2] - c0[2])]; }
    function poly(P, color, width, dash) {
      ctx.beginPath(); ctx.strokeStyle = color; ctx.lineWidth = width; ctx.setLineDash(dash || []);
      P.forEach(function (p, i) { var s = scr(p); if (i) { ctx.lineTo(s[0], s[1]); } else { ctx.moveTo(s[0], s[1]); } });
      ctx.stroke(); ctx.setLineDash([]);
    }
    // frame triad at the base (x red, y green, z blue), 0.2 L long
    var o = cs.base, a = 0.2 * L;
    [[1, 0, 0, "#c03030", "x"], [0, 1, 0, "#30a030", "y"], [0, 0, 1, "#3050c0", "z"]].forEach(function (ax) {
      var e = [o[0] + a * ax[0], o[1] + a * ax[1], o[2] + a * ax[2]];
      poly([o, e], ax[3], 1.2);
      var s = scr(e); ctx.fillStyle = ax[3]; ctx.font = "12px sans-serif"; ctx.fillText(data.frame + " " + ax[4], s[0] + 3, s[1] - 3);
    });
    // gravity: an arrow in the upper right corner, its projected direction in this view
    var g = cs.gravity, gn = Math.sqrt(dot(g, g));
    ctx.font = "12px sans-serif"; ctx.fillStyle = "#3060c0";
    if (gn > 0) {
      var q = rot([g[0] / gn, g[1] / gn, g[2] / gn]), cx = W - 70, cy = 60, len = 40;
      var ex = cx + len * q[0], ey = cy - len * q[2], ang = Math.atan2(ey - cy, ex - cx);
      ctx.beginPath(); ctx.strokeStyle = "#3060c0"; ctx.lineWidth = 2.5; ctx.moveTo(cx, cy); ctx.lineTo(ex, ey); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(ex, ey);
      ctx.lineTo(ex - 10 * Math.cos(ang - 0.4), ey - 10 * Math.sin(ang - 0.4));
      ctx.lineTo(ex - 10 * Math.cos(ang + 0.4), ey - 10 * Math.sin(ang + 0.4)); ctx.fill();
      ctx.fillText("gravity " + gn.toPrecision(3) + " m/s\u00b2", W - 150, 20);
    } else {
      ctx.textAlign = "right"; ctx.fillText(cs.note || "no gravity", W - 10, 20); ctx.textAlign = "left";
    }
    // disks and tendons on the main model's backbone
    var main = cs.models[cs.main];
    if (main && (cs.disks.length || cs.tendons.length)) {
      var P = frameAt(main, t), F = localFrames(P, cs.e0), st = main.stations;
      if (showDisks.checked) {
        cs.disks.forEach(function (d) {
          if (d[0] > st[st.length - 1] + 1e-9) { return; }
          var c = at(F, st, d[0]), R = [];
          for (var k = 0; k <= 24; k++) { R.push(ringPoint(c, d[1], 2 * Math.PI * k / 24)); }
          poly(R, "#888888", 1.0);
        });
      }
      if (showTendons.checked) {
        cs.tendons.forEach(function (td) {
          var T = [];
          [0].concat(cs.disks.map(function (d) { return d[0]; })).forEach(function (s) {
            if (s <= td[3] + 1e-12 && s <= st[st.length - 1] + 1e-9) { T.push(ringPoint(at(F, st, s), td[1] + (td[2] - td[1]) * s / td[3], td[0])); }
          });
          if (T.length > 1) { poly(T, "#b07020", 1.0); }
        });
      }
    }
    lines.forEach(function (ml) {
      var m = cs.models[ml[0]];
      poly(ml[1], m.color, m.reference ? 2.0 : 3.5, m.reference ? [6, 4] : []);
      var e = scr(ml[1][ml[1].length - 1]); ctx.fillStyle = m.color; ctx.beginPath(); ctx.arc(e[0], e[1], 3.5, 0, 2 * Math.PI); ctx.fill();
    });
    // measured points (calibration studies): a cross per point
    var markers = cs.markers || [];
    function markCross(s, r) { ctx.beginPath(); ctx.moveTo(s[0] - r, s[1] - r); ctx.lineTo(s[0] + r, s[1] + r); ctx.moveTo(s[0] - r, s[1] + r); ctx.lineTo(s[0] + r, s[1] - r); ctx.stroke(); }
    markers.forEach(function (mk) {
      ctx.strokeStyle = mk.color; ctx.lineWidth = 2;
      mk.points.forEach(function (p) { markCross(scr(p), mk.size || 5); });
    });
    var b = scr(o); ctx.fillStyle = "#555"; ctx.fillRect(b[0] - 4, b[1] - 4, 8, 8);
    // legend
    ctx.font = "12px sans-serif";
    lines.forEach(function (ml, i) {
      var m = cs.models[ml[0]];
      ctx.fillStyle = m.color; ctx.fillRect(10, 12 + 16 * i, 18, 3);
      ctx.fillStyle = "#222"; ctx.fillText(m.label, 34, 17 + 16 * i);
    });
    markers.forEach(function (mk, j) {
      var y = 17 + 16 * (lines.length + j);
      ctx.strokeStyle = mk.color; ctx.lineWidth = 2; markCross([19, y - 4], 4);
      ctx.fillStyle = "#222"; ctx.fillText(mk.label, 34, y);
    });
    var px = ctx.getImageData(0, 0, W, H).data, n = 0;
    for (var q = 0; q < px.length; q += 16) { if (px[q] < 200 || px[q + 1] < 200 || px[q + 2] < 200) { n++; } }
    canvas.setAttribute("data-drawn-pixels", String(n * 4));
  }

  function setCase(i) {
    state.c = i;
    var cs = data.cases[i], ts = {};
    Object.keys(cs.models).forEach(function (m) { cs.models[m].frames.forEach(function (f) { ts[f[0]] = 1; }); });
    state.times = Object.keys(ts).map(Number).sort(function (a, b) { return a - b; });
    state.t = state.times.length - 1;
    slider.max = String(state.times.length - 1); slider.value = String(state.t);
    var dyn = state.times.length > 1;
    slider.disabled = play.disabled = !dyn;
    root.querySelector(".wb-timebar").style.opacity = dyn ? "1" : "0.4";
    tlabel.textContent = dyn ? "t = " + state.times[state.t].toFixed(3) + " s" : "static case";
    sel.value = String(i);
    info.textContent = cs.title;
    draw();
  }

  data.cases.forEach(function (cs, i) {
    var opt = document.createElement("option"); opt.value = String(i); opt.textContent = cs.title; sel.appendChild(opt);
  });
  sel.addEventListener("change", function () { setCase(Number(sel.value)); });
  slider.addEventListener("input", function () {
    state.t = Number(slider.value); tlabel.textContent = "t = " + state.times[state.t].toFixed(3) + " s"; draw();
  });
  play.addEventListener("click", function () {
    if (state.timer) { clearInterval(state.timer); state.timer = null; play.textContent = "\u25b6 play"; return; }
    play.textContent = "\u275a\u275a pause";
    if (state.t >= state.times.length - 1) { state.t = 0; }
    state.timer = setInterval(function () {
      state.t += 1;
      if (state.t >= state.times.length) { clearInterval(state.timer); state.timer = null; play.textContent = "\u25b6 play"; state.t = state.times.length - 1; }
      slider.value = String(state.t); tlabel.textContent = "t = " + state.times[state.t].toFixed(3) + " s"; draw();
    }, 80);
  });
  [showDisks, showTendons].forEach(function (el) { el.addEventListener("change", draw); });
  root.querySelectorAll("button[data-view]").forEach(function (btn) {
    btn.addEventListener("click", function () {
      var v = btn.getAttribute("data-view");
      view.yaw = v === "xz" ? 0 : v === "yz" ? -Math.PI / 2 : -0.6;
      view.pitch = v === "xy" ? Math.PI / 2 : v === "iso" ? 0.35 : 0;
      view.zoom = 1; draw();
    });
  });
  var drag = null;
  canvas.addEventListener("pointerdown", function (e) { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) { return; }
    view.yaw += 0.01 * (e.clientX - drag[0]);
    view.pitch = Math.max(-1.55, Math.min(1.55, view.pitch + 0.01 * (e.clientY - drag[1])));
    drag = [e.clientX, e.clientY]; draw();
  });
  canvas.addEventListener("pointerup", function () { drag = null; });
  canvas.addEventListener("wheel", function (e) { e.preventDefault(); view.zoom *= e.deltaY < 0 ? 1.1 : 1 / 1.1; draw(); }, { passive: false });
  canvas.addEventListener("dblclick", function () { view.yaw = -0.6; view.pitch = 0.35; view.zoom = 1; draw(); });
  window.wbShowCase = function (id) {
    for (var i = 0; i < data.cases.length; i++) {
      if (data.cases[i].id === id) { setCase(i); root.scrollIntoView({ behavior: "smooth", block: "start" }); return true; }
    }
    return false;
  };
  setCase(0);
})();
