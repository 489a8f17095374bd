// Loads one Stride report page in headless Chromium (puppeteer-core driving the system's
// browser; nothing is downloaded) and checks it like a person would look at it:
//   - no console error, no uncaught exception, no request other than file: and data: URLs;
//   - every expected section is present and not empty (text, a table, a chart or a canvas),
//     and, unless --expect-warnings, none of them says something is missing, Ind_O is named on
//     the front chart and every point there has a tooltip, some naming their front file;
//   - with --replay N: at least N individuals in the replay, a card for each whose canvas has
//     been drawn on, and the replay's time
//     advances after Play is clicked (the clock's data-time and the slider both move), and
//     the slider moves the clock;
//   - with --replay3d: the 3D view (replay3d.js, three.js on SwiftShader's WebGL) is drawn and
//     its pixels show the robot (a render with the robots hidden differs in at least 1500
//     pixels), the slider moves the robot (the links' world positions and the pixels change
//     between the start and 60 % of the replay), its time and the accelerometer charts' cursors
//     follow the clock; the wheel zooms, a drag orbits and "reset view" restores the picture;
//     at a recorded frame the drawn link origins are within 1.1 mm of the recorded ones;
//   - with --world GROUND,GRASS_M,ROBOT: the run's own world drawn: the replay data and the 3D
//     view's ground are GROUND with its layer's top at GRASS_M, the 3D robot is named ROBOT;
//   - with --replay3d-unavailable REGEX: the 3D view says it is unavailable (or leaves an
//     individual out) in words matching REGEX, without a console error;
//   - screenshots of the whole page, of each section and of the replay after playing go to
//     OUT_DIR/NAME-full.png, NAME-SECTION.png; the 3D view to NAME-3d-start.png and
//     NAME-3d-middle.png (and NAME-3d-hidden.png: the same scene without the robots;
//     NAME-3d-orbited.png: zoomed in and turned).
// usage: node check_page.cjs --chromium PATH --modules DIR --out OUT_DIR
//          { --name NAME --page FILE --sections a,b,c [--replay N] [--expect-warnings]
//            [--replay3d | --replay3d-unavailable REGEX] [--world GROUND,GRASS_M,ROBOT] } ...
// (one browser for all pages; exit status 1 if any page fails a check)
'use strict';
const path = require('path');
const fs = require('fs');

function parseArgs(argv) {
  const out = {pages: []};
  let page = null;
  for (let i = 2; i < argv.length; ++i) {
    const a = argv[i];
    if (a === '--name') out.pages.push(page = {name: argv[++i], replay: 0, expectWarnings: false});
    else if (a === '--expect-warnings') page.expectWarnings = true;
    else if (a === '--replay') page.replay = parseInt(argv[++i], 10);
    else if (a === '--replay3d') page.replay3d = true;
    else if (a === '--replay3d-unavailable') page.unavailable3d = new RegExp(argv[++i]);
    else if (a === '--world') {
      const [ground, grass, robot] = argv[++i].split(',');
      page.world = {ground, grass_m: parseFloat(grass), robot};
    }
    else if (['--page', '--sections'].includes(a)) page[a.slice(2)] = argv[++i];
    else out[a.replace(/^--/, '')] = argv[++i];
  }
  for (const k of ['chromium', 'modules', 'out'])
    if (!out[k]) throw new Error('missing --' + k);
  for (const p of out.pages)
    if (!p.page || !p.sections) throw new Error(p.name + ': missing --page or --sections');
  return out;
}

async function main() {
  const opts = parseArgs(process.argv);
  const puppeteer = require(path.join(opts.modules, 'puppeteer-core'));
  fs.mkdirSync(opts.out, {recursive: true});
  const browser = await puppeteer.launch({
    executablePath: opts.chromium,
    headless: true,
    // WebGL without a GPU: SwiftShader, which Chromium only uses when asked to.
    args: ['--no-sandbox', '--disable-gpu', '--disable-dev-shm-usage', '--no-first-run',
           '--allow-file-access-from-files', '--use-angle=swiftshader',
           '--enable-unsafe-swiftshader'],
  });
  let failed = 0;
  try {
    for (const spec of opts.pages) {
      const failures = await checkPage(browser, {...spec, out: opts.out});
      for (const f of failures) console.error(spec.name + ': ' + f);
      if (failures.length > 0) ++failed;
    }
  } finally {
    await browser.close();
  }
  process.exit(failed > 0 ? 1 : 0);
}

async function checkPage(browser, args) {
  const failures = [];
  {
    const page = await browser.newPage();
    await page.setViewport({width: 1400, height: 1000});
    page.on('console', (m) => {
      if (m.type() === 'error') failures.push('console error: ' + m.text());
    });
    page.on('pageerror', (e) => failures.push('uncaught exception: ' + e.message));
    page.on('request', (r) => {
      if (!/^(file|data|about):/.test(r.url())) failures.push('network request: ' + r.url());
    });
    page.on('requestfailed', (r) => failures.push('failed request: ' + r.url()));
    await page.goto('file://' + path.resolve(args.page), {waitUntil: 'load'});

    const sections = await page.evaluate((ids) => ids.map((id) => {
      const s = document.querySelector('section#' + id);
      if (!s) return {id, present: false};
      const body = Array.from(s.children).filter((c) => c.tagName !== 'H2');
      const text = body.map((c) => c.textContent.trim()).join(' ');
      return {id, present: true, text: text.length,
              graphics: s.querySelectorAll('svg, canvas, table').length,
              missing: Array.from(s.querySelectorAll('.missing')).map((m) => m.textContent)};
    }), args.sections.split(','));
    for (const s of sections) {
      if (!s.present) { failures.push('section ' + s.id + ' is absent'); continue; }
      if (s.text === 0 && s.graphics === 0) failures.push('section ' + s.id + ' is empty');
      if (!args.expectWarnings && !(args.unavailable3d && s.id === 'replay') && s.missing.length > 0)
        failures.push('section ' + s.id + ' says: ' + s.missing.join(' / '));
    }
    // The validation section (stride validate's validation.json): a row per individual and
    // world, Ind_O among them, each with its gate (pass, fail, or unavailable: an engine missing
    // from the build).
    if (args.sections.split(',').includes('validation')) {
      const v = await page.evaluate(() => {
        const t = document.querySelector('section#validation table#validation-table');
        if (!t) return null;
        const rows = Array.from(t.querySelectorAll('tr')).slice(1);
        return {rows: rows.length, ind_o: rows.filter((r) => /Ind_O/.test(r.textContent)).length,
                gates: rows.filter((r) => Array.from(r.querySelectorAll('td'))
                    .some((td) => ['pass', 'fail', 'unavailable'].includes(td.textContent.trim()))).length};
      });
      if (!v) failures.push('section validation has no table#validation-table');
      else if (v.rows < 2 || v.ind_o < 1 || v.gates !== v.rows)
        failures.push('validation table: ' + JSON.stringify(v));
    }
    // The front chart names Ind_O and every point has a tooltip (objectives, front file).
    const front = await page.evaluate(() => {
      const svg = document.querySelector('section#pareto svg');
      if (!svg) return null;
      const names = Array.from(svg.querySelectorAll('g.marker text')).map((t) => t.textContent);
      const points = svg.querySelectorAll('g.front-generation circle').length;
      const tips = Array.from(svg.querySelectorAll('g.front-generation circle > title'))
          .map((t) => t.textContent);
      return {names, points, tips: tips.length, files: tips.filter((t) => /front\/\d{3}\.json/.test(t)).length};
    });
    if (front && !args.expectWarnings) {
      if (!front.names.includes('Ind_O')) failures.push('front chart: Ind_O is not named');
      if (front.points === 0 || front.tips !== front.points)
        failures.push('front chart: ' + front.tips + ' tooltips for ' + front.points + ' points');
      if (front.files === 0) failures.push('front chart: no tooltip names a front file');
    }
    const warnings = await page.evaluate(() => {
      const w = document.getElementById('warnings');
      return w && !w.hidden ? w.querySelectorAll('li').length : 0;
    });
    if (args.expectWarnings && warnings === 0) failures.push('no warnings listed at the top');
    if (!args.expectWarnings && warnings > 0) failures.push(warnings + ' warnings listed at the top');

    let replay = null;
    if (args.replay > 0) {
      const cards = await page.evaluate(() => Array.from(
          document.querySelectorAll('#replay-cards canvas')).map((c) => {
        const ctx = c.getContext('2d');
        const px = ctx.getImageData(0, 0, c.width, c.height).data;
        let ink = 0;  // pixels darker than the light panel backgrounds
        for (let i = 0; i < px.length; i += 4) if (px[i] + px[i + 1] + px[i + 2] < 300) ++ink;
        return ink;
      }));
      const people = await page.evaluate(() =>
          JSON.parse(document.getElementById('replay-data').textContent).individuals.length);
      if (people < args.replay)
        failures.push('replay: ' + people + ' individuals in the data, expected at least ' + args.replay);
      if (cards.length !== people)
        failures.push('replay: ' + cards.length + ' cards for ' + people + ' individuals');
      cards.forEach((ink, i) => { if (ink < 200) failures.push('replay card ' + i + ' is blank'); });
      const before = await page.$eval('#replay-clock', (c) => parseFloat(c.dataset.time));
      const sliderBefore = await page.$eval('#replay-time', (s) => parseFloat(s.value));
      await page.click('#replay-play');
      // Wait until the clock moved (or give up after 10 s of page time).
      await page.waitForFunction(
          (t0) => parseFloat(document.getElementById('replay-clock').dataset.time) > t0 + 0.2,
          {timeout: 10000}, before).catch(() => {});
      const after = await page.$eval('#replay-clock', (c) => parseFloat(c.dataset.time));
      const sliderAfter = await page.$eval('#replay-time', (s) => parseFloat(s.value));
      const label = await page.$eval('#replay-play', (b) => b.textContent);
      if (!(after > before)) failures.push('replay: time did not advance after Play (' + before + ' -> ' + after + ')');
      if (!(sliderAfter > sliderBefore)) failures.push('replay: the time slider did not move');
      if (label !== 'Pause') failures.push('replay: the button reads "' + label + '" while playing');
      await page.click('#replay-play');
      // Scrub to the middle with the slider: the clock follows.
      const middle = await page.$eval('#replay-time', (s) => {
        s.value = (parseFloat(s.max) / 2).toFixed(2);
        s.dispatchEvent(new Event('input'));
        return parseFloat(s.value);
      });
      const shown = await page.$eval('#replay-clock', (c) => parseFloat(c.dataset.time));
      if (Math.abs(shown - middle) > 0.01)
        failures.push('replay: the slider set ' + middle + ' s, the clock shows ' + shown);
      await (await page.$('section#replay')).screenshot(
          {path: path.join(args.out, args.name + '-replay-middle.png')});
      replay = {cards: cards.length, ink: cards, time_before: before, time_after: after};
      const el = await page.$('section#replay');
      await el.screenshot({path: path.join(args.out, args.name + '-replay.png')});
    }
    let replay3d = null;
    if (args.replay3d) replay3d = await check3d(page, args, failures);
    if (args.world) replay3d = {...replay3d, world: await checkWorld(page, args.world, failures)};
    if (args.unavailable3d) {
      await page.waitForFunction(() => document.querySelector('#replay3d .missing'),
                                 {timeout: 10000}).catch(() => {});
      const said = await page.evaluate(() => Array.from(
          document.querySelectorAll('#replay3d .missing')).map((m) => m.textContent).join(' / '));
      if (!args.unavailable3d.test(said))
        failures.push('3D view: expected a note matching ' + args.unavailable3d + ', found "' + said + '"');
      replay3d = {said};
      const el = await page.$('#replay3d');
      if (el) await el.screenshot({path: path.join(args.out, args.name + '-3d.png')});
    }
    await page.screenshot({path: path.join(args.out, args.name + '-full.png'), fullPage: true});
    for (const s of sections) {
      const el = s.present && s.id !== 'replay' ? await page.$('section#' + s.id) : null;
      if (el) await el.screenshot({path: path.join(args.out, args.name + '-' + s.id + '.png')});
    }
    console.log(JSON.stringify({page: args.page, sections, front, warnings, replay, replay3d, failures}));
    await page.close();
  }
  return failures;
}

// The run's own world drawn: the page's data and the 3D view name its ground and its layer's
// thickness, and the 3D robot is the run's URDF (its robot name), not the defaults.
async function checkWorld(page, want, failures) {
  const got = await page.evaluate(() => {
    const data = JSON.parse(document.getElementById('replay-data').textContent);
    const g = window.strideReplay3d && window.strideReplay3d.ground;
    return {data_ground: data.ground, data_grass_m: data.grass_m,
            robot: data.robot3d ? data.robot3d.name : null, drawn: g || null};
  });
  if (got.data_ground !== want.ground || got.data_grass_m !== want.grass_m)
    failures.push('replay data: ground ' + got.data_ground + ' ' + got.data_grass_m + ' m, expected ' +
                  want.ground + ' ' + want.grass_m + ' m');
  if (!got.drawn || got.drawn.name !== want.ground || Math.abs(got.drawn.top_z - want.grass_m) > 1e-9)
    failures.push('3D view: ground drawn as ' + JSON.stringify(got.drawn) + ', expected ' +
                  want.ground + ' with its top at ' + want.grass_m + ' m');
  if (got.robot !== want.robot)
    failures.push('3D view: robot ' + got.robot + ', expected the run\'s ' + want.robot);
  return got;
}

// The 3D view: drawn, the robot in its pixels, moved by the slider, in step with the clock and
// the accelerometer cursors.
async function check3d(page, args, failures) {
  await page.waitForFunction(() => window.strideReplay3d && window.strideReplay3d.state !== 'loading',
                             {timeout: 15000}).catch(() => {});
  const state = await page.evaluate(() => window.strideReplay3d
      ? {state: window.strideReplay3d.state, reason: window.strideReplay3d.reason} : null);
  if (!state || state.state !== 'ok') {
    failures.push('3D view not drawn: ' + JSON.stringify(state));
    return state;
  }
  // Move the shared slider to time t (as a person would) and measure the 3D view.
  const at = (fraction) => page.evaluate((fraction) => {
    const s = document.getElementById('replay-time');
    s.value = (parseFloat(s.max) * fraction).toFixed(2);
    s.dispatchEvent(new Event('input'));
    const api = window.strideReplay3d;
    const clock = parseFloat(document.getElementById('replay-clock').dataset.time);
    const cursors = Array.from(document.querySelectorAll('#accelerometer line.replay-cursor'))
        .map((l) => ({time: parseFloat(l.dataset.time), x: parseFloat(l.getAttribute('x1')),
                      visible: l.getAttribute('visibility') !== 'hidden'}));
    return {clock, time: api.time, links: api.linkPositions(), cursors, shown: api.shown()};
  }, fraction);
  // Pixels of the 3D canvas, kept in the page; the number of pixels that differ between two.
  const grab = (key) => page.evaluate((key) => {
    const api = window.strideReplay3d;
    api.render();
    const c = document.createElement('canvas');
    c.width = api.canvas.width;
    c.height = api.canvas.height;
    const g = c.getContext('2d');
    g.drawImage(api.canvas, 0, 0);
    (window.__grabs = window.__grabs || {})[key] = g.getImageData(0, 0, c.width, c.height).data;
    return c.width * c.height;
  }, key);
  const differing = (a, b) => page.evaluate((a, b) => {
    const p = window.__grabs[a], q = window.__grabs[b];
    let n = 0;
    for (let i = 0; i < p.length; i += 4)
      if (Math.abs(p[i] - q[i]) + Math.abs(p[i + 1] - q[i + 1]) + Math.abs(p[i + 2] - q[i + 2]) > 40) ++n;
    return n;
  }, a, b);
  const shot = async (name) => {
    const el = await page.$('#replay3d');
    await el.screenshot({path: path.join(args.out, args.name + '-3d-' + name + '.png')});
  };

  const start = await at(0);
  const total = await grab('start');
  await shot('start');
  await page.evaluate(() => window.strideReplay3d.setRobotsVisible(false));
  await grab('hidden');
  await shot('hidden');
  await page.evaluate(() => window.strideReplay3d.setRobotsVisible(true));
  const robotPixels = await differing('start', 'hidden');
  if (robotPixels < 1500) failures.push('3D view: only ' + robotPixels + ' pixels show the robot');
  if (robotPixels > 0.6 * total) failures.push('3D view: ' + robotPixels + ' of ' + total + ' pixels changed without the robot');
  const middle = await at(0.6);
  await grab('middle');
  await shot('middle');
  const moved = await differing('start', 'middle');
  let travel = 0;
  middle.links.forEach((p, i) => {
    const q = start.links[i];
    if (q) travel = Math.max(travel, Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]));
  });
  if (!(travel > 0.02)) failures.push('3D view: the slider did not move the robot (links moved ' + travel + ' m)');
  if (moved < 200) failures.push('3D view: the slider changed only ' + moved + ' pixels');
  for (const m of [start, middle]) {
    if (Math.abs(m.time - m.clock) > 1e-3) failures.push('3D view at ' + m.time + ' s, clock at ' + m.clock + ' s');
    if (m.cursors.length < 4) failures.push('accelerometer: ' + m.cursors.length + ' time cursors');
    for (const c of m.cursors)
      if (Math.abs(c.time - m.clock) > 1e-3) failures.push('accelerometer cursor at ' + c.time + ' s, clock at ' + m.clock + ' s');
  }
  const startX = start.cursors.filter((c) => c.visible).map((c) => c.x);
  const middleX = middle.cursors.filter((c) => c.visible).map((c) => c.x);
  if (middleX.length === 0 || !(Math.max(...middleX) > Math.max(...startX, 0)))
    failures.push('accelerometer cursors did not move right with the slider');
  // The camera: the wheel zooms, a drag orbits (the picture changes each time), reset restores.
  const box = await (await page.$('#replay3d-canvas')).boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.wheel({deltaY: -400});
  await grab('zoomed');
  const zoomed = await differing('middle', 'zoomed');
  await page.mouse.down();
  await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 30, {steps: 4});
  await page.mouse.up();
  await grab('orbited');
  await shot('orbited');
  const orbited = await differing('zoomed', 'orbited');
  await page.click('#replay3d-reset');
  await grab('reset');
  const reset = await differing('middle', 'reset');
  if (zoomed < 2000) failures.push('3D view: the wheel changed only ' + zoomed + ' pixels');
  if (orbited < 2000) failures.push('3D view: dragging changed only ' + orbited + ' pixels');
  if (reset > 200) failures.push('3D view: reset view left ' + reset + ' pixels changed');
  // The layouts: ghosted puts the individuals over each other, side by side apart.
  const lanes = await page.evaluate(() => {
    const layout = document.getElementById('replay3d-layout');
    const spread = () => {
      const ys = window.strideReplay3d.linkPositions().map((p) => p[1]);
      return Math.max(...ys) - Math.min(...ys);
    };
    const side = spread();
    layout.value = 'ghost';
    layout.dispatchEvent(new Event('change'));
    window.strideReplay3d.render();
    const ghost = spread();
    layout.value = 'side';
    layout.dispatchEvent(new Event('change'));
    window.strideReplay3d.render();
    return {side, ghost, shown: window.strideReplay3d.shown().length};
  });
  if (lanes.shown > 1 && !(lanes.side > lanes.ghost + 0.3))
    failures.push('3D view: side by side is not wider than ghosted ' + JSON.stringify(lanes));
  // Last: it moves the slider to a recorded frame.
  const recorded = await drawnAgainstRecorded(page);
  if (!(recorded.compared > 0)) failures.push('3D view: no link compared with the recorded ones');
  if (!(recorded.worst_mm <= 1.1))
    failures.push('3D view: ' + recorded.where + ' is drawn ' + recorded.worst_mm.toFixed(2) +
                  ' mm from where the simulation recorded it (frame ' + recorded.frame + ')');
  return {state: state.state, robotPixels, total, moved, travel, zoomed, orbited, reset,
          shown: middle.shown, lanes, recorded,
          cursors: middle.cursors.length};
}

// The links where the simulation put them: the 3D view poses them by forward kinematics from
// the recorded torso pose and joint angles (replay3d.js); the 2D replay's first points are the
// link origins the simulator recorded (stick_figure.hpp, millimetres). At a recorded frame
// (60 % of the replay) every shown individual's drawn link origins must be within 1.1 mm of the
// recorded ones on each axis: both are rounded to the millimetre (the 3D view's torso position,
// the 2D points: 0.5 mm each), its angles to 1e-4 rad (under 0.1 mm at the foot); measured
// worst 0.98 mm on the walk, kick and sim-kick pages. A wrong joint axis, origin or angle is
// centimetres off.
async function drawnAgainstRecorded(page) {
  return page.evaluate(() => {
    const data = JSON.parse(document.getElementById('replay-data').textContent);
    const slider = document.getElementById('replay-time');
    const frame = Math.round(parseFloat(slider.max) * 0.6 / data.frame_dt);
    slider.value = (frame * data.frame_dt).toFixed(2);
    slider.dispatchEvent(new Event('input'));
    const decode = (b64) => {
      const bin = atob(b64);
      const bytes = new Uint8Array(bin.length);
      for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
      return new Int16Array(bytes.buffer, 0, Math.floor(bytes.length / 2));
    };
    const per = (data.figure.points + 1) * 3;  // values per 2D frame: points, then the ball
    let worst = 0, compared = 0, where = '';
    for (const run of window.strideReplay3d.linkOrigins()) {
      const ind = data.individuals[run.index];
      const f = Math.min(frame, ind.motion_frames - 1);
      if (f >= ind.frames) continue;
      const points = decode(ind.data);
      run.links.forEach((p, i) => {
        if (!p) return;
        for (let a = 0; a < 3; ++a) {
          const d = Math.abs(p[a] * 1000 - points[f * per + 3 * i + a]);
          if (d > worst) {
            worst = d;
            where = ind.name + ' link ' + i + ' axis ' + 'xyz'[a];
          }
        }
        ++compared;
      });
    }
    return {frame, compared, worst_mm: worst, where};
  });
}

main().catch((e) => { console.error(e.stack || String(e)); process.exit(1); });
