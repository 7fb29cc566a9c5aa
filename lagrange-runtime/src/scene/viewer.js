// The scene viewer of lagrange: plays the sampled frames of one or more runs
// on a Canvas 2D, with an orbiting camera and a linked plot. No libraries and
// no network: the page is one file. Solids are flat-shaded polygons drawn far
// to near (the painter's algorithm) shape by shape: a convex solid's visible
// faces do not overlap, so ordering the shapes by their centres' depth (ties
// in the description's order, so a bar across a disc is drawn over it) is
// enough for a few bodies and needs no WebGL.
(function () {
  'use strict';
  var data = JSON.parse(document.getElementById('scene-data').textContent);
  var view = document.getElementById('view'), plot = document.getElementById('plot');
  var ctx = view.getContext('2d'), pctx = plot.getContext('2d');
  var NB = data.bodies.length, NP = data.points.length, NQ = data.plot.length;
  var runs = data.runs;
  var tMin = Math.min.apply(null, runs.map(function (r) { return r.t0; }));
  var tMax = Math.max.apply(null, runs.map(function (r) { return r.t0 + r.dt * (r.count - 1); }));
  var state = { t: tMin, playing: true, speed: 1, follow: false, last: null };

  // ---- vectors and rotations -------------------------------------------
  function add(a, b) { return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]; }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function scale(a, s) { return [a[0] * s, a[1] * s, a[2] * s]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function norm(a) { var n = Math.sqrt(dot(a, a)) || 1; return scale(a, 1 / n); }
  // Row-major 3x3 matrices as arrays of nine.
  function mulMV(m, v) {
    return [m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
      m[6] * v[0] + m[7] * v[1] + m[8] * v[2]];
  }
  function mulMM(a, b) {
    var c = [];
    for (var i = 0; i < 3; i++) for (var j = 0; j < 3; j++)
      c.push(a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j]);
    return c;
  }
  function column(m, j) { return [m[j], m[3 + j], m[6 + j]]; }
  function quatToMatrix(w, x, y, z) {
    var n = Math.sqrt(w * w + x * x + y * y + z * z) || 1;
    w /= n; x /= n; y /= n; z /= n;
    return [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)];
  }
  // A planar description lies in z = 0 with y up: turned to this viewer's z up.
  function lift(p) { return data.planar ? [p[0], -p[2], p[1]] : p; }
  var LIFT = data.planar ? [1, 0, 0, 0, 0, -1, 0, 1, 0] : [1, 0, 0, 0, 1, 0, 0, 0, 1];

  // ---- the state of each run at time t (frames interpolated) -----------
  function poseAt(run, t) {
    var f = run.dt > 0 ? (t - run.t0) / run.dt : 0;
    f = Math.max(0, Math.min(run.count - 1, f));
    var i = Math.floor(f), a = f - i, k = Math.min(i + 1, run.count - 1);
    var bodies = [], points = [];
    for (var b = 0; b < NB; b++) {
      var p = run.bodies, o0 = (i * NB + b) * 7, o1 = (k * NB + b) * 7, q = [];
      var sign = p[o0 + 3] * p[o1 + 3] + p[o0 + 4] * p[o1 + 4] + p[o0 + 5] * p[o1 + 5] + p[o0 + 6] * p[o1 + 6] < 0 ? -1 : 1;
      for (var c = 0; c < 7; c++) q.push(p[o0 + c] * (1 - a) + (c < 3 ? 1 : sign) * p[o1 + c] * a);
      bodies.push({ origin: lift([q[0], q[1], q[2]]), rotation: mulMM(LIFT, quatToMatrix(q[3], q[4], q[5], q[6])) });
    }
    for (var j = 0; j < NP; j++) {
      var s = run.points, u = (i * NP + j) * 3, v = (k * NP + j) * 3;
      points.push(lift([s[u] * (1 - a) + s[v] * a, s[u + 1] * (1 - a) + s[v + 1] * a, s[u + 2] * (1 - a) + s[v + 2] * a]));
    }
    return { bodies: bodies, points: points };
  }
  function anchorPosition(pose, anchor) {
    return anchor[0] === 'b' ? pose.bodies[anchor[1]].origin : pose.points[anchor[1]];
  }
  function centroid(pose) {
    var all = pose.bodies.map(function (b) { return b.origin; }).concat(pose.points), c = [0, 0, 0];
    all.forEach(function (p) { c = add(c, p); });
    return all.length ? scale(c, 1 / all.length) : c;
  }

  // ---- camera ----------------------------------------------------------
  // The camera: a system that travels (a bicycle, a rolling disk) is
  // followed at the size of one frame; one that stays (an arm, a top) is
  // framed whole, every sampled position of every run in view.
  function anchors(pose) { return pose.bodies.map(function (b) { return b.origin; }).concat(pose.points); }
  function spread(list, centre) {
    return list.reduce(function (m, p) { return Math.max(m, Math.sqrt(dot(sub(p, centre), sub(p, centre)))); }, 0);
  }
  var first = poseAt(runs[0], tMin), home = centroid(first), radius = spread(anchors(first), home);
  var shapeSize = data.shapes.reduce(function (m, s) {
    var size = s.size ? Math.max.apply(null, s.size) / 2 : (s.radius || 0) + (s.length || 0) / 2;
    return Math.max(m, size + Math.sqrt(dot(s.at, s.at)));
  }, 0);
  var everywhere = [];
  runs.forEach(function (run) {
    for (var k = 0; k <= 60; k++) everywhere = everywhere.concat(anchors(poseAt(run, tMin + (tMax - tMin) * k / 60)));
  });
  var lo = everywhere.reduce(function (m, p) { return [Math.min(m[0], p[0]), Math.min(m[1], p[1]), Math.min(m[2], p[2])]; }, home);
  var hi = everywhere.reduce(function (m, p) { return [Math.max(m[0], p[0]), Math.max(m[1], p[1]), Math.max(m[2], p[2])]; }, home);
  var whole = spread(everywhere, scale(add(lo, hi), 0.5));
  // A lone point has no size of its own: such a scene is always framed whole.
  var size = Math.max(radius, shapeSize);
  state.follow = size > 0 && whole > 4 * size;
  if (!state.follow) { home = scale(add(lo, hi), 0.5); radius = whole; }
  radius = Math.max(radius, shapeSize);
  if (!(radius > 0)) radius = 1;
  document.getElementById('follow').checked = state.follow;
  var cam = { az: data.planar ? -Math.PI / 2 : -1.0, el: data.planar ? 0.0 : 0.35, dist: 4.2 * radius, target: home };
  function camera() {
    var ce = Math.cos(cam.el), eye = add(cam.target, scale([ce * Math.cos(cam.az), ce * Math.sin(cam.az), Math.sin(cam.el)], cam.dist));
    var forward = norm(sub(cam.target, eye)), right = norm(cross(forward, [0, 0, 1])), up = cross(right, forward);
    var f = view.height / (2 * Math.tan(20 * Math.PI / 180));
    return { eye: eye, forward: forward, right: right, up: up, f: f };
  }
  function project(c, p) {
    var d = sub(p, c.eye), z = dot(d, c.forward);
    return [view.width / 2 + c.f * dot(d, c.right) / z, view.height / 2 - c.f * dot(d, c.up) / z, z];
  }

  // ---- primitives: polygons, discs, lines, dots --------------------------
  function shade(rgb, n, c, faint) {
    var light = norm(add(add(scale(c.forward, -1), scale(c.up, 0.6)), scale(c.right, -0.3)));
    var k = 0.4 + 0.6 * Math.abs(dot(n, light)), mix = faint ? 0.35 : 0;
    return 'rgb(' + rgb.map(function (x) { return Math.round((x * k) * (1 - mix) + 255 * mix); }).join(',') + ')';
  }
  function polygon(out, c, pts, n, style) {
    var centre = scale(pts.reduce(add, [0, 0, 0]), 1 / pts.length);
    if (style.closed && dot(n, sub(c.eye, centre)) <= 0) return;
    var screen = pts.map(function (p) { return project(c, p); });
    if (screen.some(function (s) { return s[2] <= 1e-6; })) return;
    var depth = screen.reduce(function (s, p) { return s + p[2]; }, 0) / screen.length;
    out.push({ depth: depth, kind: 'poly', pts: screen, fill: shade(style.rgb, n, c, style.faint), alpha: style.alpha });
  }
  function boxFaces(out, c, centre, axes, size, style) {
    var e = [0, 1, 2].map(function (j) { return scale(column(axes, j), size[j] / 2); });
    for (var j = 0; j < 3; j++) for (var s = -1; s <= 1; s += 2) {
      var u = e[(j + 1) % 3], v = e[(j + 2) % 3], m = add(centre, scale(e[j], s));
      var pts = [sub(sub(m, u), v), sub(add(m, u), v), add(add(m, u), v), add(sub(m, u), v)];
      polygon(out, c, pts, norm(scale(e[j], s)), style);
    }
  }
  function cylinder(out, c, centre, axes, r, len, axis, style, caps) {
    var a = norm(column(axes, axis)), u = column(axes, (axis + 1) % 3), v = column(axes, (axis + 2) % 3);
    var n = 24, ring = [];
    for (var i = 0; i < n; i++) {
      var th = 2 * Math.PI * i / n;
      ring.push(add(scale(u, r * Math.cos(th)), scale(v, r * Math.sin(th))));
    }
    var top = add(centre, scale(a, len / 2)), bottom = sub(centre, scale(a, len / 2));
    for (var k = 0; k < n; k++) {
      var p = ring[k], q = ring[(k + 1) % n];
      polygon(out, c, [add(bottom, p), add(bottom, q), add(top, q), add(top, p)], norm(add(p, q)), style);
    }
    if (caps) {
      polygon(out, c, ring.map(function (p) { return add(top, p); }), a, style);
      polygon(out, c, ring.map(function (p) { return add(bottom, p); }).reverse(), scale(a, -1), style);
    }
    return [top, bottom];
  }
  function disc(out, c, centre, r, style) {
    var s = project(c, centre);
    if (s[2] <= 1e-6) return;
    out.push({ depth: s[2], kind: 'disc', at: s, r: c.f * r / s[2], rgb: style.rgb, alpha: style.alpha, faint: style.faint });
  }
  function line(out, c, p, q, style) {
    var a = project(c, p), b = project(c, q);
    if (a[2] <= 1e-6 || b[2] <= 1e-6) return;
    out.push({ depth: (a[2] + b[2]) / 2 - 1e-3 * radius, kind: 'line', pts: [a, b], rgb: style.rgb, alpha: style.alpha, width: style.faint ? 1.5 : 3 });
  }
  function dotAt(out, c, p, style) {
    var s = project(c, p);
    if (s[2] > 1e-6) out.push({ depth: s[2] - 2e-3 * radius, kind: 'dot', at: s, rgb: style.rgb, alpha: style.alpha });
  }

  // Draws one shape into `out`; returns the depth of its centre.
  function shapePrimitives(out, c, pose, s, style) {
    var frame = s.on[0] === 'b' ? pose.bodies[s.on[1]] : { origin: pose.points[s.on[1]], rotation: LIFT };
    var centre = add(frame.origin, mulMV(frame.rotation, s.at)), axes = mulMM(frame.rotation, s.axes);
    var st = { rgb: style.rgb, alpha: style.alpha, faint: s.default, closed: true };
    if (s.kind === 'box') {
      if (Math.max.apply(null, s.size) > 0) boxFaces(out, c, centre, axes, s.size, st);
      else dotAt(out, c, centre, st);
    } else if (s.kind === 'sphere') disc(out, c, centre, s.radius, st);
    else if (s.kind === 'cylinder') cylinder(out, c, centre, axes, s.radius, s.length, s.axis, st, true);
    else if (s.kind === 'capsule') {
      cylinder(out, c, centre, axes, s.radius, s.length, s.axis, st, false).forEach(function (end) { disc(out, c, end, s.radius, st); });
    } else if (s.kind === 'line') {
      var to = anchorPosition(pose, s.to);
      line(out, c, frame.origin, to, st);
      return project(c, scale(add(frame.origin, to), 0.5))[2];
    }
    return project(c, centre)[2];
  }
  function hexToRgb(h) { return [1, 3, 5].map(function (i) { return parseInt(h.substr(i, 2), 16); }); }

  // ---- drawing -----------------------------------------------------------
  function grid(c) {
    if (data.planar) return;
    var step = Math.pow(10, Math.floor(Math.log10(radius))), n = 8;
    var cx = Math.round(cam.target[0] / step) * step, cy = Math.round(cam.target[1] / step) * step;
    ctx.strokeStyle = '#e2e2e2'; ctx.lineWidth = 1;
    for (var i = -n; i <= n; i++) for (var d = 0; d < 2; d++) {
      var a = d ? [cx + i * step, cy - n * step, 0] : [cx - n * step, cy + i * step, 0];
      var b = d ? [cx + i * step, cy + n * step, 0] : [cx + n * step, cy + i * step, 0];
      var p = project(c, a), q = project(c, b);
      if (p[2] <= 1e-6 || q[2] <= 1e-6) continue;
      ctx.beginPath(); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); ctx.stroke();
    }
  }
  function drawPrimitive(p) {
    ctx.globalAlpha = p.alpha;
    if (p.kind === 'poly') {
      ctx.fillStyle = p.fill; ctx.strokeStyle = p.fill; ctx.lineWidth = 0.5;
      ctx.beginPath(); ctx.moveTo(p.pts[0][0], p.pts[0][1]);
      for (var i = 1; i < p.pts.length; i++) ctx.lineTo(p.pts[i][0], p.pts[i][1]);
      ctx.closePath(); ctx.fill(); ctx.stroke();
    } else if (p.kind === 'disc') {
      var g = ctx.createRadialGradient(p.at[0] - p.r / 3, p.at[1] - p.r / 3, p.r / 10, p.at[0], p.at[1], p.r);
      var light = p.rgb.map(function (x) { return Math.round(x + (255 - x) * 0.6); });
      g.addColorStop(0, 'rgb(' + light.join(',') + ')'); g.addColorStop(1, 'rgb(' + p.rgb.join(',') + ')');
      ctx.fillStyle = g; ctx.beginPath(); ctx.arc(p.at[0], p.at[1], Math.max(p.r, 1), 0, 2 * Math.PI); ctx.fill();
    } else if (p.kind === 'line') {
      ctx.strokeStyle = 'rgb(' + p.rgb.map(function (x) { return Math.round(x * 0.6); }).join(',') + ')';
      ctx.lineWidth = p.width; ctx.lineCap = 'round';
      ctx.beginPath(); ctx.moveTo(p.pts[0][0], p.pts[0][1]); ctx.lineTo(p.pts[1][0], p.pts[1][1]); ctx.stroke();
    } else {
      ctx.fillStyle = '#333'; ctx.beginPath(); ctx.arc(p.at[0], p.at[1], 4, 0, 2 * Math.PI); ctx.fill();
    }
    ctx.globalAlpha = 1;
  }
  // Side by side: each run after the first moved, horizontally, under the
  // first one's centroid, one lane to the side per run (display only).
  function moved(pose, shift) {
    return {
      bodies: pose.bodies.map(function (b) { return { origin: add(b.origin, shift), rotation: b.rotation }; }),
      points: pose.points.map(function (p) { return add(p, shift); })
    };
  }
  function sideBySide(poses) {
    var lead = centroid(poses[0]);
    return poses.map(function (pose, r) {
      if (r === 0) return pose;
      var d = sub(lead, centroid(pose));
      return moved(pose, [d[0], d[1] + 2.2 * radius * r, 0]);
    });
  }
  function render() {
    var poses = runs.map(function (r) { return poseAt(r, state.t); });
    if (data.sideBySide) poses = sideBySide(poses);
    if (state.follow) cam.target = centroid(poses[0]);
    else cam.target = home;
    var c = camera(), prims = [];
    ctx.fillStyle = '#ffffff'; ctx.fillRect(0, 0, view.width, view.height);
    grid(c);
    var order = 0;
    function group(list, depth) {
      list.forEach(function (p) { p.group = depth; p.order = order; prims.push(p); });
      order++;
    }
    runs.forEach(function (run, r) {
      var style = { rgb: hexToRgb(run.color), alpha: run.opacity };
      data.shapes.forEach(function (s) {
        var own = [], depth = shapePrimitives(own, c, poses[r], s, style);
        group(own, depth);
      });
      poses[r].points.forEach(function (p, j) {
        var own = [];
        if (data.pointDots[j]) dotAt(own, c, p, style);
        if (own.length) group(own, own[0].depth);
      });
    });
    prims.sort(function (a, b) { return (b.group - a.group) || (a.order - b.order) || (b.depth - a.depth); });
    prims.forEach(drawPrimitive);
    document.getElementById('time').textContent = 't = ' + state.t.toFixed(3) + ' s';
    document.getElementById('slider').value = Math.round(1000 * (state.t - tMin) / ((tMax - tMin) || 1));
    drawPlot();
  }

  // ---- the linked plot ----------------------------------------------------
  var DASHES = [[], [7, 4], [2, 3], [10, 3, 2, 3], [4, 4]];
  var plotted = document.createElement('canvas');
  plotted.width = plot.width; plotted.height = plot.height;
  var PAD = { l: 50, r: 12, t: 10, b: 22 };
  function plotX(t) { return PAD.l + (plot.width - PAD.l - PAD.r) * (t - tMin) / ((tMax - tMin) || 1); }
  function drawStaticPlot() {
    var g = plotted.getContext('2d'), lo = Infinity, hi = -Infinity;
    runs.forEach(function (r) { r.plot.forEach(function (v) { lo = Math.min(lo, v); hi = Math.max(hi, v); }); });
    if (!(hi > lo)) { lo -= 1; hi += 1; }
    var y = function (v) { return plot.height - PAD.b - (plot.height - PAD.t - PAD.b) * (v - lo) / (hi - lo); };
    g.fillStyle = '#fff'; g.fillRect(0, 0, plot.width, plot.height);
    g.fillStyle = '#555'; g.font = '11px sans-serif';
    g.fillText(hi.toPrecision(3), 4, PAD.t + 8); g.fillText(lo.toPrecision(3), 4, plot.height - PAD.b);
    g.fillText(tMin.toFixed(2) + ' s', PAD.l, plot.height - 6); g.fillText(tMax.toFixed(2) + ' s', plot.width - PAD.r - 40, plot.height - 6);
    runs.forEach(function (run) {
      for (var j = 0; j < NQ; j++) {
        g.strokeStyle = run.color; g.globalAlpha = Math.max(run.opacity, 0.5); g.lineWidth = 1.5;
        g.setLineDash(DASHES[j % DASHES.length]); g.beginPath();
        for (var k = 0; k < run.count; k++) {
          var px = plotX(run.t0 + k * run.dt), py = y(run.plot[k * NQ + j]);
          if (k) g.lineTo(px, py); else g.moveTo(px, py);
        }
        g.stroke();
      }
    });
    g.setLineDash([]); g.globalAlpha = 1;
    data.plot.forEach(function (name, j) {
      var x = PAD.l + 10 + 110 * j;
      g.strokeStyle = '#333'; g.setLineDash(DASHES[j % DASHES.length]);
      g.beginPath(); g.moveTo(x, PAD.t + 6); g.lineTo(x + 28, PAD.t + 6); g.stroke();
      g.setLineDash([]); g.fillStyle = '#333'; g.fillText(name, x + 32, PAD.t + 10);
    });
  }
  function drawPlot() {
    pctx.drawImage(plotted, 0, 0);
    var x = plotX(state.t);
    pctx.strokeStyle = '#d00'; pctx.lineWidth = 1.5;
    pctx.beginPath(); pctx.moveTo(x, PAD.t); pctx.lineTo(x, plot.height - PAD.b); pctx.stroke();
  }

  // ---- controls ------------------------------------------------------------
  var playButton = document.getElementById('play');
  function setPlaying(on) { state.playing = on; state.last = null; playButton.textContent = on ? 'pause' : 'play'; }
  playButton.onclick = function () { setPlaying(!state.playing); };
  document.getElementById('slider').oninput = function (e) {
    setPlaying(false); state.t = tMin + (tMax - tMin) * e.target.value / 1000; render();
  };
  document.getElementById('speed').onchange = function (e) { state.speed = parseFloat(e.target.value); };
  document.getElementById('follow').onchange = function (e) { state.follow = e.target.checked; render(); };
  var drag = null;
  view.onmousedown = function (e) { drag = [e.clientX, e.clientY]; };
  window.onmouseup = function () { drag = null; };
  window.onmousemove = function (e) {
    if (!drag) return;
    cam.az -= (e.clientX - drag[0]) * 0.01;
    cam.el = Math.max(-1.5, Math.min(1.5, cam.el + (e.clientY - drag[1]) * 0.01));
    drag = [e.clientX, e.clientY]; render();
  };
  view.onwheel = function (e) { e.preventDefault(); cam.dist *= Math.exp(e.deltaY * 0.001); render(); };
  document.getElementById('legend').innerHTML = runs.map(function (r) {
    return '<span><i style="background:' + r.color + ';opacity:' + r.opacity + '"></i>' +
      r.label.replace(/[&<>]/g, function (ch) { return { '&': '&amp;', '<': '&lt;', '>': '&gt;' }[ch]; }) + '</span>';
  }).join('');
  function tick(now) {
    if (state.playing) {
      if (state.last !== null) {
        state.t += (now - state.last) / 1000 * state.speed;
        if (state.t > tMax) state.t = tMin + (state.t - tMax) % ((tMax - tMin) || 1);
      }
      state.last = now; render();
    }
    window.requestAnimationFrame(tick);
  }

  // ---- the hook for tests and tools ---------------------------------------
  function indexOf(list, name) {
    var i = list.indexOf(name);
    if (i < 0) throw new Error('no body or point named ' + name);
    return i;
  }
  function unlift(p) { return data.planar ? [p[0], p[2], -p[1]] : p; }
  window.lagrangeScene = {
    frameCount: runs[0].count,
    frameCounts: runs.map(function (r) { return r.count; }),
    runs: runs.map(function (r) { return r.label; }),
    start: tMin, end: tMax,
    setTime: function (t) { setPlaying(false); state.t = Math.max(tMin, Math.min(tMax, t)); render(); },
    time: function () { return state.t; },
    play: function () { setPlaying(true); },
    pause: function () { setPlaying(false); },
    bodyWorldPosition: function (name, run) {
      return unlift(poseAt(runs[run || 0], state.t).bodies[indexOf(data.bodies, name)].origin);
    },
    pointWorldPosition: function (name, run) {
      return unlift(poseAt(runs[run || 0], state.t).points[indexOf(data.points, name)]);
    },
    bodyScreenPosition: function (name, run) {
      var p = project(camera(), poseAt(runs[run || 0], state.t).bodies[indexOf(data.bodies, name)].origin);
      return [p[0], p[1]];
    },
    pixelHash: function () {
      var px = ctx.getImageData(0, 0, view.width, view.height).data, h = 2166136261;
      for (var i = 0; i < px.length; i++) { h ^= px[i]; h = Math.imul(h, 16777619) >>> 0; }
      return h;
    }
  };
  drawStaticPlot();
  render();
  window.lagrangeScene.ready = true;
  window.requestAnimationFrame(tick);
})();
