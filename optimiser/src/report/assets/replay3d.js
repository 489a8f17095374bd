// 3D replay of the report pages (report.html, stride sim --html), drawn with three.js (Debian's
// libjs-three r111, inlined into the page by html_replay3d.cpp). Embedded at build time.
//
// Reads #replay-data (html_replay.cpp, html_replay3d.cpp): robot3d = {links: [{name, boxes:
// [[x,y,z, qw,qx,qy,qz, sx,sy,sz]], spheres: [[x,y,z,r,stud]]}], joints: [{parent, child,
// origin: [x,y,z, qw,qx,qy,qz], axis}], feet: [left, right], values_per_frame}; per individual
// `motion` (base64 int16 per frame: torso mm, torso quaternion 1e-4, joint angles 1e-4 rad,
// left and right foot force N, ball mm) and `motion_frames`. The links are the URDF's collision
// boxes and spheres (studs dark), posed by forward kinematics from the torso pose and the joint
// angles; grey balls mark the joints. Around them: the episode's ground (`ground`, its name,
// and `grass_m`, the top of its layer), a 0.5 m grid, the start and goal lines, the ball;
// orange arrows beside the feet show each foot's contact force (0.4 cm per newton, from the
// sole's height).
//
// Time comes from replay.js (event 'stride-replay-time'): one clock, one slider for the 2D
// cards, the 3D view and the accelerometer cursors. The camera is a small orbit control of our
// own: drag orbits, the wheel zooms, shift- or right-drag pans, and "follow" keeps the shown
// robots in the middle. (r111 ships OrbitControls only as an examples/ script; its target
// would have to be moved by hand every frame to follow, which is all this control does.)
// A missing three.js, no WebGL or a broken trajectory gives a note saying so, never an error.
// window.strideReplay3d exposes the state for the browser test (tests/browser/).
(function () {
  'use strict';
  const root = document.getElementById('replay3d');
  const source = document.getElementById('replay-data');
  if (!root || !source) return;
  const view = document.getElementById('replay3d-view');
  const status = document.getElementById('replay3d-status');
  const api = window.strideReplay3d = {state: 'loading', reason: '', time: 0};

  function say(text) {
    const p = document.createElement('p');
    p.className = 'missing';
    p.textContent = text;
    return p;
  }
  function fail(reason) {
    root.dataset.state = 'unavailable';
    api.state = 'unavailable';
    api.reason = reason;
    const controls = document.getElementById('replay3d-controls');
    if (controls) controls.hidden = true;
    if (view) view.replaceChildren(say('The 3D view is unavailable: ' + reason));
    else root.appendChild(say('The 3D view is unavailable: ' + reason));
  }

  if (typeof THREE === 'undefined') return fail('three.js is not in this page.');
  let data;
  try { data = JSON.parse(source.textContent); } catch (e) { return fail('the replay data cannot be read.'); }
  const model = data.robot3d;
  if (!model || !Array.isArray(model.links) || !Array.isArray(model.joints) || !model.values_per_frame)
    return fail('the page has no robot model to draw.');
  const V = model.values_per_frame, J = model.joints.length;
  if (V !== 3 + 4 + J + 6 + 3) return fail('the robot model and its trajectory data do not match.');
  const probe = document.createElement('canvas');
  if (!(probe.getContext('webgl') || probe.getContext('experimental-webgl')))
    return fail('this browser has no WebGL.');

  function decode(b64) {
    const bin = atob(b64);
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
    return new Int16Array(bytes.buffer, 0, Math.floor(bytes.length / 2));
  }
  // Decode and check every individual's trajectory.
  const runs = [], broken = [];
  (data.individuals || []).forEach(function (ind, index) {
    let why = '', values = null;
    if (typeof ind.motion !== 'string' || ind.motion.length === 0) {
      why = 'no trajectory was recorded';
    } else {
      try { values = decode(ind.motion); } catch (e) { why = 'its trajectory is not readable (bad base64)'; }
      const frames = ind.motion_frames;
      if (values && (!(frames >= 1) || values.length !== frames * V))
        why = 'its trajectory is broken (' + values.length + ' values for ' + frames + ' frames of ' + V + ')';
      for (let f = 0; values && !why && f < frames; ++f) {
        const o = f * V + 3;
        const n = (values[o] ** 2 + values[o + 1] ** 2 + values[o + 2] ** 2 + values[o + 3] ** 2) / 1e8;
        if (!(n > 0.9 && n < 1.1)) why = 'its trajectory is broken (the torso orientation at frame ' + f + ' is not a rotation)';
      }
    }
    if (why) broken.push(ind.name + ': ' + why);
    else runs.push({ind: ind, index: index, values: values, frames: ind.motion_frames});
  });
  if (runs.length === 0)
    return fail(broken.length ? broken.join('; ') + '.' : 'no trajectory to replay.');
  if (broken.length) root.insertBefore(say('Not in the 3D view: ' + broken.join('; ') + '.'), view);

  // Renderer, scene, lights, field.
  THREE.Object3D.DefaultUp.set(0, 0, 1);
  const HEIGHT = 440;
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
  } catch (e) {
    return fail('WebGL could not be started (' + (e && e.message ? e.message : e) + ').');
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const canvas = renderer.domElement;
  canvas.id = 'replay3d-canvas';
  canvas.setAttribute('role', 'img');
  canvas.setAttribute('aria-label', '3D replay of ' + runs.map(function (r) { return r.ind.name; }).join(', '));
  view.appendChild(canvas);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xe8f1f8);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667755, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.55);
  sun.position.set(2, -3, 6);
  scene.add(sun);
  // The episode's own ground: its layer's top at grass_m, coloured by its kind (a grey-blue
  // carpet for hard, green for the grass and turf grounds).
  const grass = data.grass_m || 0;
  const groundColour = {seed: 0x8fcf78, turf: 0x7cc56a, soft: 0x9ad483, hard: 0xa9b4c2}[data.ground];
  const goal = data.goal_m;
  const fieldLength = Math.max(6, (goal || 0) + 4);
  const ground = new THREE.Mesh(new THREE.PlaneBufferGeometry(fieldLength + 4, 8),
                                new THREE.MeshLambertMaterial({color: groundColour || 0x8fcf78}));
  ground.position.set(fieldLength / 2 - 1, 0, grass - 0.012);
  scene.add(ground);
  api.ground = {name: data.ground || '', grass_m: grass, top_z: ground.position.z + 0.012,
                colour: ground.material.color.getHex()};
  // Lines on the grass: a 0.5 m grid (flat strips, lit like the grass), the start and goal lines.
  function strip(x0, x1, y0, y1, colour, lift) {
    const m = new THREE.Mesh(new THREE.BoxBufferGeometry(x1 - x0, y1 - y0, 0.002),
                             new THREE.MeshLambertMaterial({color: colour}));
    m.position.set((x0 + x1) / 2, (y0 + y1) / 2, grass - 0.008 + lift);
    scene.add(m);
  }
  const gridX1 = Math.ceil(fieldLength - 1);
  const gridColour = data.ground === 'hard' ? 0x8d98a6 : 0x6fae5c;
  for (let x = -2; x <= gridX1; x += 0.5) strip(x - 0.004, x + 0.004, -3.5, 3.5, gridColour, 0);
  for (let y = -3.5; y <= 3.5; y += 0.5) strip(-2, gridX1, y - 0.004, y + 0.004, gridColour, 0);
  strip(-0.01, 0.01, -3.5, 3.5, 0xffffff, 0.002);
  if (goal) strip(goal - 0.02, goal + 0.02, -3.5, 3.5, 0xd0021b, 0.002);

  function label(text, colour) {
    const c = document.createElement('canvas');
    c.width = 256; c.height = 64;  // powers of two: no resizing by WebGL 1
    const g = c.getContext('2d');
    g.fillStyle = 'rgba(255,255,255,0.85)';
    g.fillRect(0, 8, 256, 48);
    g.fillStyle = colour;
    g.fillRect(0, 8, 10, 48);
    g.fillStyle = '#222';
    g.font = 'bold 26px sans-serif';
    g.fillText(text.length > 16 ? text.slice(0, 15) + '\u2026' : text, 18, 41);
    const s = new THREE.Sprite(new THREE.SpriteMaterial({map: new THREE.CanvasTexture(c), depthTest: false}));
    s.scale.set(0.36, 0.09, 1);
    return s;
  }

  // A contact force arrow: a shaft and a head along +y, scaled and turned by pose().
  const arrowMat = new THREE.MeshLambertMaterial({color: 0xff7f0e});
  function forceArrow() {
    const a = new THREE.Group();
    a.shaft = new THREE.Mesh(new THREE.CylinderBufferGeometry(0.009, 0.009, 1, 10), arrowMat);
    a.head = new THREE.Mesh(new THREE.ConeBufferGeometry(0.022, 0.05, 14), arrowMat);
    a.add(a.shaft, a.head);
    return a;
  }
  const UP_Y = new THREE.Vector3(0, 1, 0);

  // One robot (plus its ball, force arrows and label) per individual, in a "lane" group that
  // the layout moves sideways.
  function quat(a, i) { return new THREE.Quaternion(a[i + 1], a[i + 2], a[i + 3], a[i]); }
  const headLink = model.links.findIndex(function (l) { return /head/.test(l.name); });
  for (const run of runs) {
    const colour = new THREE.Color(run.ind.colour);
    const mats = {
      body: new THREE.MeshLambertMaterial({color: colour}),
      foot: new THREE.MeshLambertMaterial({color: colour.clone().multiplyScalar(0.55)}),
      head: new THREE.MeshLambertMaterial({color: colour.clone().lerp(new THREE.Color(0xffffff), 0.45)}),
      stud: new THREE.MeshLambertMaterial({color: 0x222222}),
      joint: new THREE.MeshLambertMaterial({color: 0x9a9a9a}),
      ball: new THREE.MeshLambertMaterial({color: 0xffffff}),
    };
    run.materials = Object.values(mats);
    const lane = new THREE.Group();
    scene.add(lane);
    const robot = new THREE.Group();
    lane.add(robot);
    const links = [robot], joints = [];
    model.joints.forEach(function (j, k) {
      const origin = new THREE.Group();
      origin.position.set(j.origin[0], j.origin[1], j.origin[2]);
      origin.quaternion.copy(quat(j.origin, 3));
      (links[j.parent] || robot).add(origin);
      const marker = new THREE.Mesh(new THREE.SphereBufferGeometry(0.022, 12, 8), mats.joint);
      origin.add(marker);
      const moving = new THREE.Group();
      origin.add(moving);
      links[j.child] = moving;
      joints[k] = {group: moving, axis: new THREE.Vector3(j.axis[0], j.axis[1], j.axis[2]).normalize()};
    });
    model.links.forEach(function (l, i) {
      const group = links[i] || robot;
      const isFoot = model.feet.indexOf(i) >= 0;
      for (const b of l.boxes) {
        const m = new THREE.Mesh(new THREE.BoxBufferGeometry(b[7], b[8], b[9]), isFoot ? mats.foot : mats.body);
        m.position.set(b[0], b[1], b[2]);
        m.quaternion.copy(quat(b, 3));
        group.add(m);
      }
      for (const s of l.spheres) {
        const m = new THREE.Mesh(new THREE.SphereBufferGeometry(s[3], s[4] ? 8 : 24, s[4] ? 6 : 16),
                                 s[4] ? mats.stud : i === headLink ? mats.head : mats.body);
        m.position.set(s[0], s[1], s[2]);
        group.add(m);
      }
    });
    const ball = data.ball_radius_m > 0
        ? new THREE.Mesh(new THREE.SphereBufferGeometry(data.ball_radius_m, 24, 16), mats.ball) : null;
    if (ball) lane.add(ball);
    const arrows = model.feet.map(function (f) {
      if (f < 0) return null;
      const a = forceArrow();
      lane.add(a);
      return a;
    });
    const tag = label(run.ind.name, run.ind.colour);
    lane.add(tag);
    Object.assign(run, {lane: lane, robot: robot, links: links, joints: joints, ball: ball, arrows: arrows, tag: tag,
                        torso: new THREE.Vector3(), forces: [0, 0], tagLift: 0});
  }

  // Pose at time t (linear between frames, the last frame after the end; as replay.js).
  const tmpQ = new THREE.Quaternion(), tmpQ2 = new THREE.Quaternion(), tmpV = new THREE.Vector3();
  function frameAt(run, t) {
    const dt = data.frame_dt, last = run.frames - 1, end = run.ind.end_s;
    let f = Math.max(0, t) / dt;
    if (t >= end || f >= last) f = last;
    else if (f > last - 1) f = (last - 1) + (t - (last - 1) * dt) / Math.max(1e-9, end - (last - 1) * dt);
    const i = Math.min(Math.floor(f), last);
    return {i: i, j: Math.min(i + 1, last), w: f - i};
  }
  function value(run, fr, k) {
    return (1 - fr.w) * run.values[fr.i * V + k] + fr.w * run.values[fr.j * V + k];
  }
  function pose(run, t) {
    const fr = frameAt(run, t);
    run.torso.set(value(run, fr, 0) / 1000, value(run, fr, 1) / 1000, value(run, fr, 2) / 1000);
    run.robot.position.copy(run.torso);
    const a = run.values, qi = fr.i * V + 3, qj = fr.j * V + 3;
    tmpQ.set(a[qi + 1], a[qi + 2], a[qi + 3], a[qi]).normalize();
    tmpQ2.set(a[qj + 1], a[qj + 2], a[qj + 3], a[qj]).normalize();
    run.robot.quaternion.copy(tmpQ).slerp(tmpQ2, fr.w);
    for (let k = 0; k < J; ++k)
      run.joints[k].group.quaternion.setFromAxisAngle(run.joints[k].axis, value(run, fr, 7 + k) / 1e4);
    const b = 7 + J + 6;
    if (run.ball) run.ball.position.set(value(run, fr, b) / 1000, value(run, fr, b + 1) / 1000, value(run, fr, b + 2) / 1000);
    run.tag.position.set(run.torso.x, run.torso.y, run.torso.z + 0.42 + run.tagLift);
    run.robot.updateMatrixWorld(true);
    run.arrows.forEach(function (arrow, side) {
      if (!arrow) return;
      const o = 7 + J + 3 * side;
      tmpV.set(value(run, fr, o), value(run, fr, o + 1), value(run, fr, o + 2));
      const n = tmpV.length();
      run.forces[side] = n;
      arrow.visible = forcesBox.checked && n > 1 && run.lane.visible;
      if (!arrow.visible) return;
      // Beside the foot on its outer side (so the leg does not hide it), from the sole up.
      const foot = run.links[model.feet[side]] || run.robot;
      const at = foot.localToWorld(new THREE.Vector3(0.02, side === 0 ? 0.11 : -0.11, -0.045));
      run.lane.worldToLocal(at);
      arrow.position.copy(at);
      arrow.quaternion.setFromUnitVectors(UP_Y, tmpV.clone().divideScalar(n));
      const length = Math.max(0.06, n * 0.004);
      arrow.shaft.scale.set(1, length - 0.05, 1);
      arrow.shaft.position.set(0, (length - 0.05) / 2, 0);
      arrow.head.position.set(0, length - 0.025, 0);
    });
  }

  // Controls: which individuals, layout, follow, forces.
  const compare = document.getElementById('replay3d-compare');
  const layout = document.getElementById('replay3d-layout');
  const followBox = document.getElementById('replay3d-follow');
  const forcesBox = document.getElementById('replay3d-forces');
  const first = runs[0];
  if (runs.length === 1) {
    compare.add(new Option(first.ind.name, '0'));
  } else {
    for (let k = 1; k < runs.length; ++k)
      compare.add(new Option(first.ind.name + ' and ' + runs[k].ind.name, String(k)));
    compare.add(new Option('all ' + runs.length, 'all'));
  }
  function shown() {
    if (runs.length === 1) return [first];
    return compare.value === 'all' ? runs : [first, runs[parseInt(compare.value, 10)]];
  }
  function arrange() {
    const list = shown(), ghost = layout.value === 'ghost';
    for (const run of runs) run.lane.visible = list.indexOf(run) >= 0;
    list.forEach(function (run, k) {
      run.lane.position.set(0, ghost ? 0 : 0.65 * k, 0);  // the picks on the left: seen beside, not behind
      run.tagLift = ghost ? 0.1 * k : 0;  // ghosted: the labels stacked, not on top of each other
      const translucent = ghost && list.length > 1 && run === first;  // Ind_O is the ghost
      for (const m of run.materials) {
        m.transparent = translucent;
        m.opacity = translucent ? 0.35 : 1;
        m.depthWrite = !translucent;
        m.needsUpdate = true;
      }
    });
  }

  // The camera: orbit around a target that follows the shown robots.
  const camera = new THREE.PerspectiveCamera(40, 2, 0.05, 100);
  const home = {azimuth: -Math.PI * 0.3, elevation: 0.35, distance: 3.0};  // front right
  const orbit = Object.assign({target: new THREE.Vector3(0, 0, 0.35)}, home);
  function followTarget() {
    if (!followBox.checked) return;
    const list = shown();
    let x = 0, y = 0;
    for (const run of list) { x += run.torso.x; y += run.torso.y + run.lane.position.y; }
    orbit.target.set(x / list.length, y / list.length, 0.35);
  }
  function placeCamera() {
    const c = Math.cos(orbit.elevation);
    camera.position.set(orbit.target.x + orbit.distance * c * Math.cos(orbit.azimuth),
                        orbit.target.y + orbit.distance * c * Math.sin(orbit.azimuth),
                        orbit.target.z + orbit.distance * Math.sin(orbit.elevation));
    camera.lookAt(orbit.target);
  }
  function resize() {
    const w = Math.max(320, view.clientWidth || 640);
    renderer.setSize(w, HEIGHT);
    camera.aspect = w / HEIGHT;
    camera.updateProjectionMatrix();
  }

  function renderNow() {
    for (const run of runs) pose(run, api.time);
    followTarget();
    placeCamera();
    renderer.render(scene, camera);
    status.textContent = 't = ' + api.time.toFixed(2) + ' s \u00b7 ' + shown().map(function (run) {
      return run.ind.name + ': torso x ' + run.torso.x.toFixed(2) + ' m, feet L ' + run.forces[0].toFixed(0) +
             ' N, R ' + run.forces[1].toFixed(0) + ' N';
    }).join(' \u00b7 ');
  }
  let pending = false;
  function requestRender() {
    if (pending) return;
    pending = true;
    requestAnimationFrame(function () { pending = false; renderNow(); });
  }

  let drag = null;
  canvas.addEventListener('contextmenu', function (e) { e.preventDefault(); });
  canvas.addEventListener('pointerdown', function (e) {
    drag = {x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2};
    canvas.setPointerCapture(e.pointerId);
  });
  canvas.addEventListener('pointermove', function (e) {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      followBox.checked = false;
      const s = orbit.distance * 0.0015;
      const right = new THREE.Vector3(-Math.sin(orbit.azimuth), Math.cos(orbit.azimuth), 0);
      orbit.target.addScaledVector(right, -dx * s);
      orbit.target.z = Math.max(0, orbit.target.z + dy * s);
    } else {
      orbit.azimuth -= dx * 0.008;
      orbit.elevation = Math.min(1.5, Math.max(-0.05, orbit.elevation + dy * 0.008));
    }
    requestRender();
  });
  canvas.addEventListener('pointerup', function () { drag = null; });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    orbit.distance = Math.min(25, Math.max(0.4, orbit.distance * Math.exp(e.deltaY * 0.001)));
    requestRender();
  }, {passive: false});
  document.getElementById('replay3d-reset').addEventListener('click', function () {
    Object.assign(orbit, home);
    followBox.checked = true;
    requestRender();
  });
  for (const el of [compare, layout]) el.addEventListener('change', function () { arrange(); requestRender(); });
  for (const el of [followBox, forcesBox]) el.addEventListener('change', requestRender);
  window.addEventListener('resize', function () { resize(); requestRender(); });
  document.addEventListener('stride-replay-time', function (e) {
    api.time = e.detail;
    renderNow();
  });

  // For the browser test: hide the robots (an empty-scene render to compare pixels with), the
  // world positions of every shown link (and each individual's link origins), a fresh render.
  api.render = renderNow;
  api.canvas = canvas;
  api.shown = function () { return shown().map(function (run) { return run.ind.name; }); };
  api.setRobotsVisible = function (on) {
    for (const run of runs) run.robot.visible = on;
    renderNow();
  };
  api.linkPositions = function () {
    const out = [];
    for (const run of shown())
      for (const l of run.links) {
        const p = l.getWorldPosition(new THREE.Vector3());
        out.push([p.x, p.y, p.z]);
      }
    return out;
  };
  // Per shown individual: its index in #replay-data and its links' origins as drawn, in the
  // simulation's world frame (the layout's lane offset taken off), model link order.
  api.linkOrigins = function () {
    return shown().map(function (run) {
      run.lane.updateMatrixWorld(true);
      const links = [];
      for (let i = 0; i < run.links.length; ++i) {
        const l = run.links[i];
        links.push(l ? run.lane.worldToLocal(l.getWorldPosition(new THREE.Vector3())).toArray() : null);
      }
      return {index: run.index, links: links};
    });
  };

  resize();
  arrange();
  const clock = document.getElementById('replay-clock');
  api.time = clock ? parseFloat(clock.dataset.time) || 0 : 0;
  renderNow();
  root.dataset.state = 'ok';
  api.state = 'ok';
})();
