// Replay of simulated episodes side by side (report.html, stride sim --html). Embedded at
// build time. Reads the JSON in #replay-data (written by html_replay.cpp):
//   fps_dt: time between frames [s]; figure: {points, strokes: [[a, b, colour, width]],
//   circles: [[point, radius_m]]}; ground (its name: seed, turf, soft, hard or custom);
//   grass_m (the top of its soft layer); ball_radius_m (0: no ball); goal_m (or null);
//   individuals: [{name, colour, note, end_s, frames, data}], data = base64 of little-endian
//   int16 millimetres, per frame (points + 1 ball point) x (x, y, z).
// Each individual gets a card with a side view (x right, following the torso), a front view
// (the robot's left on the right) and a top view of the whole path; the controls play, pause,
// change the speed and scrub the shared time. A cursor on every accelerometer chart (the <svg>
// elements with data-plot="left top right bottom t0 t1") follows the replay's time, and the
// event 'stride-replay-time' (detail: the time [s]) tells the 3D view (replay3d.js).
(function () {
  'use strict';
  const source = document.getElementById('replay-data');
  const cards = document.getElementById('replay-cards');
  if (!source || !cards) return;
  const data = JSON.parse(source.textContent);
  const fig = data.figure;
  const stride = (fig.points + 1) * 3;  // values per frame (points, then the ball)
  const W = 300, VIEW_H = 250, TOP_H = 110, SCALE = 240, GROUND = 232;

  function decode(b64) {
    const bin = atob(b64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new Int16Array(bytes.buffer, 0, Math.floor(bytes.length / 2));
  }

  const runs = data.individuals.map(function (ind) {
    const values = decode(ind.data);
    const frames = Math.min(ind.frames, Math.floor(values.length / stride));
    const card = document.createElement('div');
    card.className = 'replay-card';
    const who = document.createElement('div');
    who.className = 'who';
    who.innerHTML = '<span class="swatch"></span>';
    who.firstChild.style.background = ind.colour;
    who.appendChild(document.createTextNode(ind.name));
    const status = document.createElement('div');
    status.className = 'status';
    const canvas = document.createElement('canvas');
    const dpr = window.devicePixelRatio || 1;
    canvas.width = W * dpr;
    canvas.height = (2 * VIEW_H + TOP_H) * dpr;
    canvas.style.width = W + 'px';
    canvas.style.height = (2 * VIEW_H + TOP_H) + 'px';
    card.append(who, status, canvas);
    cards.appendChild(card);
    // The torso path (point 0) and the ball path, for the trail and the top view.
    const path = [], ball = [];
    let minX = 0, maxX = data.goal_m || 0.5, minY = -0.3, maxY = 0.3;
    for (let f = 0; f < frames; ++f) {
      const o = f * stride;
      const t = [values[o] / 1000, values[o + 1] / 1000, values[o + 2] / 1000];
      const b = [values[o + stride - 3] / 1000, values[o + stride - 2] / 1000,
                 values[o + stride - 1] / 1000];
      path.push(t);
      ball.push(b);
      for (const p of data.ball_radius_m > 0 ? [t, b] : [t]) {
        minX = Math.min(minX, p[0]); maxX = Math.max(maxX, p[0]);
        minY = Math.min(minY, p[1]); maxY = Math.max(maxY, p[1]);
      }
    }
    return {ind: ind, values: values, frames: frames, canvas: canvas, status: status, dpr: dpr,
            path: path, ball: ball, box: [minX - 0.1, maxX + 0.1, minY - 0.1, maxY + 0.1]};
  });

  // Point k of the pose at time t (linear between frames; the last frame after the end).
  function pose(run, t) {
    const dt = data.frame_dt;
    const last = run.frames - 1;
    let f = Math.max(0, t) / dt;
    const lastTime = run.ind.end_s;
    if (t >= lastTime || f >= last) f = last;
    else if (f > last - 1) f = (last - 1) + (t - (last - 1) * dt) / Math.max(1e-9, lastTime - (last - 1) * dt);
    const i = Math.min(Math.floor(f), last), j = Math.min(i + 1, last), w = f - i;
    const out = new Float64Array(stride);
    for (let k = 0; k < stride; ++k)
      out[k] = ((1 - w) * run.values[i * stride + k] + w * run.values[j * stride + k]) / 1000;
    return {p: out, frame: i};
  }

  function drawView(ctx, y0, p, horizontal, title, run, frame) {
    const ref = p[horizontal];  // torso coordinate at the panel's centre
    const sx = function (v) { return W / 2 + SCALE * (v - ref); };
    const sy = function (z) { return y0 + GROUND - SCALE * z; };
    ctx.fillStyle = '#eef6fb';
    ctx.fillRect(0, y0, W, VIEW_H);
    ctx.fillStyle = data.ground === 'hard' ? '#c9d0d8' : '#b7e3a1';  // carpet or grass
    ctx.fillRect(0, sy(data.grass_m), W, SCALE * data.grass_m);
    ctx.strokeStyle = '#6b4f2a';
    ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(0, sy(0)); ctx.lineTo(W, sy(0)); ctx.stroke();
    // Distance marks every 0.25 m, labelled every metre (the side view's x is the field's x).
    ctx.fillStyle = '#555';
    ctx.font = '10px sans-serif';
    const first = Math.ceil((ref - W / 2 / SCALE) * 4) / 4;
    for (let m = first; m < ref + W / 2 / SCALE; m += 0.25) {
      const x = sx(m);
      ctx.strokeStyle = '#6b4f2a';
      ctx.lineWidth = 1;
      ctx.beginPath(); ctx.moveTo(x, sy(0)); ctx.lineTo(x, sy(0) + (Math.abs(m - Math.round(m)) < 1e-6 ? 8 : 4)); ctx.stroke();
      if (Math.abs(m - Math.round(m)) < 1e-6) ctx.fillText(Math.round(m) + ' m', x + 2, sy(0) + 14);
    }
    if (horizontal === 0 && data.goal_m) {
      ctx.strokeStyle = '#c03030';
      ctx.setLineDash([4, 3]);
      ctx.beginPath(); ctx.moveTo(sx(data.goal_m), y0); ctx.lineTo(sx(data.goal_m), sy(0)); ctx.stroke();
      ctx.setLineDash([]);
    }
    // The torso's path so far.
    ctx.strokeStyle = 'rgba(16, 48, 107, 0.35)';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    for (let f = 0; f <= frame && f < run.path.length; ++f) {
      const q = run.path[f];
      if (f === 0) ctx.moveTo(sx(q[horizontal]), sy(q[2])); else ctx.lineTo(sx(q[horizontal]), sy(q[2]));
    }
    ctx.stroke();
    ctx.lineCap = 'round';
    for (const s of fig.strokes) {
      ctx.strokeStyle = s[2];
      ctx.lineWidth = s[3];
      ctx.beginPath();
      ctx.moveTo(sx(p[s[0] * 3 + horizontal]), sy(p[s[0] * 3 + 2]));
      ctx.lineTo(sx(p[s[1] * 3 + horizontal]), sy(p[s[1] * 3 + 2]));
      ctx.stroke();
    }
    ctx.strokeStyle = '#333';
    ctx.lineWidth = 2;
    for (const c of fig.circles) {
      ctx.beginPath();
      ctx.arc(sx(p[c[0] * 3 + horizontal]), sy(p[c[0] * 3 + 2]), SCALE * c[1], 0, 2 * Math.PI);
      ctx.stroke();
    }
    if (data.ball_radius_m > 0) {
      const b = fig.points * 3;
      ctx.fillStyle = 'rgba(255, 255, 255, 0.6)';
      ctx.strokeStyle = '#000';
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      ctx.arc(sx(p[b + horizontal]), sy(p[b + 2]), SCALE * data.ball_radius_m, 0, 2 * Math.PI);
      ctx.fill(); ctx.stroke();
    }
    ctx.fillStyle = '#444';
    ctx.font = '11px sans-serif';
    ctx.fillText(title, 6, y0 + 14);
  }

  function drawTop(ctx, y0, run, frame, p) {
    const [x0, x1, yMin, yMax] = run.box;
    const s = Math.min((W - 12) / (x1 - x0), (TOP_H - 22) / (yMax - yMin));
    const px = function (x) { return 6 + s * (x - x0); };
    const py = function (y) { return y0 + 18 + (TOP_H - 22) / 2 - s * (y - (yMin + yMax) / 2); };
    ctx.fillStyle = '#f3f8ef';
    ctx.fillRect(0, y0, W, TOP_H);
    ctx.fillStyle = '#444';
    ctx.font = '11px sans-serif';
    ctx.fillText('top (path; x right, robot\'s left up)', 6, y0 + 13);
    if (data.goal_m) {
      ctx.strokeStyle = '#c03030';
      ctx.setLineDash([4, 3]);
      ctx.beginPath(); ctx.moveTo(px(data.goal_m), y0 + 16); ctx.lineTo(px(data.goal_m), y0 + TOP_H); ctx.stroke();
      ctx.setLineDash([]);
    }
    const line = function (pts, upto, colour, width) {
      ctx.strokeStyle = colour;
      ctx.lineWidth = width;
      ctx.beginPath();
      for (let f = 0; f <= upto && f < pts.length; ++f)
        if (f === 0) ctx.moveTo(px(pts[f][0]), py(pts[f][1])); else ctx.lineTo(px(pts[f][0]), py(pts[f][1]));
      ctx.stroke();
    };
    line(run.path, run.path.length, 'rgba(0, 0, 0, 0.15)', 1);
    line(run.path, frame, run.ind.colour, 2);
    if (data.ball_radius_m > 0) line(run.ball, frame, '#000', 1);
    ctx.fillStyle = run.ind.colour;
    ctx.beginPath(); ctx.arc(px(p[0]), py(p[1]), 4, 0, 2 * Math.PI); ctx.fill();
    if (data.ball_radius_m > 0) {
      const b = fig.points * 3;
      ctx.strokeStyle = '#000';
      ctx.fillStyle = '#fff';
      ctx.beginPath(); ctx.arc(px(p[b]), py(p[b + 1]), Math.max(3, s * data.ball_radius_m), 0, 2 * Math.PI);
      ctx.fill(); ctx.stroke();
    }
  }

  function draw(t) {
    for (const run of runs) {
      if (run.frames === 0) { run.status.textContent = 'no frames recorded'; continue; }
      const ctx = run.canvas.getContext('2d');
      ctx.setTransform(run.dpr, 0, 0, run.dpr, 0, 0);
      const {p, frame} = pose(run, t);
      drawView(ctx, 0, p, 0, 'side (x right)', run, frame);
      drawView(ctx, VIEW_H, p, 1, 'front (robot\'s left on the right)', run, frame);
      drawTop(ctx, 2 * VIEW_H, run, frame, p);
      const b = fig.points * 3;
      run.status.textContent = t >= run.ind.end_s ? run.ind.note
          : 'torso x = ' + p[0].toFixed(2) + ' m' + (data.ball_radius_m > 0
              ? ', ball moved ' + Math.hypot(p[b] - run.ball[0][0], p[b + 1] - run.ball[0][1]).toFixed(2) + ' m' : '');
    }
  }

  const end = Math.max.apply(null, runs.map(function (r) { return r.ind.end_s; }).concat([0]));
  const play = document.getElementById('replay-play');
  const slider = document.getElementById('replay-time');
  const speed = document.getElementById('replay-speed');
  const clock = document.getElementById('replay-clock');
  slider.max = end.toFixed(2);
  let time = 0, playing = false, last = null;

  // The time cursors on the accelerometer charts.
  const SVG_NS = 'http://www.w3.org/2000/svg';
  const cursors = Array.from(document.querySelectorAll('#accelerometer svg[data-plot]'))
      .map(function (svg) {
        const [left, top, right, bottom, t0, t1] = svg.dataset.plot.split(' ').map(parseFloat);
        const line = document.createElementNS(SVG_NS, 'line');
        line.setAttribute('class', 'replay-cursor');
        line.setAttribute('y1', top);
        line.setAttribute('y2', bottom);
        line.setAttribute('stroke', '#d0021b');
        line.setAttribute('stroke-width', '1.5');
        line.setAttribute('pointer-events', 'none');
        svg.appendChild(line);
        return {line: line, left: left, right: right, t0: t0, t1: t1};
      });
  function moveCursors(t) {
    for (const c of cursors) {
      const inside = t >= c.t0 && t <= c.t1 && c.t1 > c.t0;
      const x = inside ? c.left + (c.right - c.left) * (t - c.t0) / (c.t1 - c.t0) : c.left;
      c.line.setAttribute('x1', x.toFixed(1));
      c.line.setAttribute('x2', x.toFixed(1));
      c.line.setAttribute('visibility', inside ? 'visible' : 'hidden');
      c.line.dataset.time = t.toFixed(3);
    }
  }

  function show(t) {
    time = Math.min(Math.max(0, t), end);
    slider.value = time.toFixed(2);
    clock.textContent = 't = ' + time.toFixed(2) + ' s';
    clock.dataset.time = time.toFixed(3);
    draw(time);
    moveCursors(time);
    document.dispatchEvent(new CustomEvent('stride-replay-time', {detail: time}));
  }
  function tick(now) {
    if (!playing) return;
    if (last !== null) show(time + (now - last) / 1000 * parseFloat(speed.value));
    last = now;
    if (time >= end) { setPlaying(false); return; }
    requestAnimationFrame(tick);
  }
  function setPlaying(on) {
    playing = on;
    play.textContent = on ? 'Pause' : 'Play';
    play.setAttribute('aria-pressed', on ? 'true' : 'false');
    if (on) {
      if (time >= end) show(0);
      last = null;
      requestAnimationFrame(tick);
    }
  }
  play.addEventListener('click', function () { setPlaying(!playing); });
  slider.addEventListener('input', function () { show(parseFloat(slider.value)); });
  show(0);
})();
