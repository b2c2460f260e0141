// rbsim's run.html in a real browser: Debian's headless Chromium, driven by playwright-core.
//   node page_test.mjs RBSIM_BINARY
// A scene of three coloured spheres on the ground is run with the csv, contacts and html outputs;
// the page must load from file:// with no console error and no network request. The test sets the
// camera through URL parameters, projects the trajectory CSV with its own pinhole camera model,
// and finds each sphere by its colour in the screenshot within 2 px, at several times; the time
// slider moves the scene; and the contact arrows are drawn where contacts.jsonl puts the contacts.
// Prints 'N passed, N failed'; exits non-zero on any failure.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { inflateSync } from 'node:zlib';
import { chromium } from 'playwright-core';

const rbsim = process.argv[2];
let passed = 0;
let failed = 0;
let largest = 0; // px: the largest distance of a found body from its projection
function check(name, ok, detail = '') {
  if (ok) {
    passed += 1;
  } else {
    failed += 1;
    console.log(`FAIL: ${name}${detail ? `: ${detail}` : ''}`);
  }
}

// --- A PNG decoder (8-bit RGB or RGBA, not interlaced: what Chromium writes) ----------------
function decodePng(buffer) {
  let at = 8;
  let width = 0;
  let height = 0;
  let channels = 0;
  const data = [];
  while (at < buffer.length) {
    const length = buffer.readUInt32BE(at);
    const type = buffer.toString('latin1', at + 4, at + 8);
    const body = buffer.subarray(at + 8, at + 8 + length);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      if (body[8] !== 8 || body[12] !== 0) throw new Error('PNG: only 8-bit, non-interlaced');
      channels = { 2: 3, 6: 4 }[body[9]];
      if (!channels) throw new Error(`PNG: colour type ${body[9]}`);
    } else if (type === 'IDAT') {
      data.push(body);
    }
    at += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(data));
  const stride = width * channels;
  const out = new Uint8Array(width * height * 3);
  let previous = new Uint8Array(stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    const row = new Uint8Array(stride);
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? row[i - channels] : 0;
      const b = previous[i];
      const c = i >= channels ? previous[i - channels] : 0;
      let p = 0;
      if (filter === 1) p = a;
      else if (filter === 2) p = b;
      else if (filter === 3) p = (a + b) >> 1;
      else if (filter === 4) {
        const e = a + b - c;
        const pa = Math.abs(e - a);
        const pb = Math.abs(e - b);
        const pc = Math.abs(e - c);
        p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      row[i] = (line[i] + p) & 255;
    }
    for (let x = 0; x < width; ++x) {
      for (let k = 0; k < 3; ++k) out[(y * width + x) * 3 + k] = row[x * channels + k];
    }
    previous = row;
  }
  return { width, height, rgb: out };
}

// The centroid of the pixels within `tolerance` of `colour`, and their count.
function find(image, colour, tolerance = 40, near = null, radius = Infinity) {
  let sx = 0;
  let sy = 0;
  let n = 0;
  for (let y = 0; y < image.height; ++y) {
    for (let x = 0; x < image.width; ++x) {
      if (near && Math.hypot(x + 0.5 - near[0], y + 0.5 - near[1]) > radius) continue;
      const i = (y * image.width + x) * 3;
      const d = Math.hypot(image.rgb[i] - colour[0], image.rgb[i + 1] - colour[1], image.rgb[i + 2] - colour[2]);
      if (d > tolerance) continue;
      sx += x + 0.5;
      sy += y + 0.5;
      n += 1;
    }
  }
  return n ? { x: sx / n, y: sy / n, n } : { n: 0 };
}

// --- The test's own camera: a pinhole at `eye` looking at `target`, `up` up, vertical fov. -----
function projector(eye, target, up, fovDegrees, width, height) {
  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => {
    const l = Math.hypot(...a);
    return a.map((v) => v / l);
  };
  const back = unit(sub(eye, target)); // the camera looks along −back
  const right = unit(cross(up, back));
  const top = cross(back, right);
  const f = 1 / Math.tan((fovDegrees * Math.PI) / 360);
  const aspect = width / height;
  return (p) => {
    const d = sub(p, eye);
    const depth = -dot(d, back);
    const nx = (f * dot(d, right)) / depth / aspect;
    const ny = (f * dot(d, top)) / depth;
    return [((nx + 1) / 2) * width, ((1 - ny) / 2) * height];
  };
}

// --- The run --------------------------------------------------------------------------------
const dir = mkdtempSync(join(tmpdir(), 'rbsim-page-'));
const spheres = [
  { name: 'red', color: [1, 0, 0], position: [-0.3, 0.0, 0.05], velocity: [0.6, 0.1, 0], pixel: [255, 0, 0] },
  { name: 'green', color: [0, 1, 0], position: [0.0, 0.25, 0.35], velocity: [0, -0.3, 0], pixel: [0, 255, 0] },
  { name: 'blue', color: [0, 0, 1], position: [0.3, -0.15, 0.05], velocity: [-0.4, 0.5, 0], pixel: [0, 0, 255] },
];
const scene = {
  description: 'Three coloured spheres on the ground (tests/rbsim/page_test.mjs)',
  dt: 0.002,
  duration: 1.2,
  output_rate: 25,
  ground: { normal: [0, 0, 1], offset: 0, material: { static_friction: 0.5, kinetic_friction: 0.4 } },
  bodies: spheres.map((s) => ({
    name: s.name,
    solid: { type: 'sphere', radius: 0.05 },
    density: 1000,
    position: s.position,
    velocity: s.velocity,
    color: s.color,
  })),
  forces: [{ type: 'gravity', g: [0, 0, -9.81] }],
};
writeFileSync(join(dir, 'spheres.json'), JSON.stringify(scene));
execFileSync(rbsim, [join(dir, 'spheres.json'), '--out', join(dir, 'out'), '--outputs', 'csv,contacts,html', '-q'], {
  stdio: ['ignore', 'ignore', 'inherit'],
});
const rows = readFileSync(join(dir, 'out', 'trajectory.csv'), 'utf8').trim().split('\n').slice(1).map((l) => l.split(','));
const times = [...new Set(rows.map((r) => r[0]))];
const positionAt = (time, body) => {
  const row = rows.find((r) => r[0] === time && r[1] === body);
  return [Number(row[2]), Number(row[3]), Number(row[4])];
};
const steps = readFileSync(join(dir, 'out', 'contacts.jsonl'), 'utf8').trim().split('\n').map((l) => JSON.parse(l));

const browser = await chromium.launch({
  executablePath: '/usr/bin/chromium',
  args: ['--disable-background-networking', '--disable-component-update', '--disable-sync', '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader', '--no-first-run'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1100, height: 700 } });
  const problems = [];
  page.on('console', (m) => { if (m.type() === 'error' || m.type() === 'warning') problems.push(`console ${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e}`));
  const url = `file://${join(dir, 'out', 'run.html')}`;
  // The only requests: the test's own pages (run.html of this run and of the sleeping sphere's).
  page.on('request', (r) => {
    const file = r.url().split('?')[0];
    if (!(file.startsWith(`file://${dir}/`) && file.endsWith('/run.html'))) problems.push(`request: ${r.url()}`);
  });

  const eye = [0.9, -1.5, 1.0];
  const target = [0, 0, 0.05];
  const fov = 35;
  const camera = `camera=${eye.join(',')}&target=${target.join(',')}&fov=${fov}`;
  async function shoot() {
    const frames = await page.evaluate(() => window.rbsim.frames);
    await page.waitForFunction((n) => window.rbsim.frames > n + 1, frames);
    const canvas = page.locator('#view canvas');
    const box = await canvas.boundingBox();
    return { image: decodePng(await canvas.screenshot()), box };
  }
  async function open(query) {
    await page.goto(`${url}?${query}`);
    await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 2, null, { timeout: 30000 });
    return shoot();
  }
  function expectBodies(shot, time, label) {
    const project = projector(eye, target, [0, 0, 1], fov, shot.image.width, shot.image.height);
    for (const s of spheres) {
      const want = project(positionAt(time, s.name));
      const got = find(shot.image, s.pixel);
      const error = got.n ? Math.hypot(got.x - want[0], got.y - want[1]) : Infinity;
      largest = Math.max(largest, error);
      check(`${label}: the ${s.name} sphere at t = ${time} s within 2 px`, got.n > 50 && error <= 2,
        `found ${got.n} px at (${got.x?.toFixed(2)}, ${got.y?.toFixed(2)}), projected (${want[0].toFixed(2)}, ${want[1].toFixed(2)})`);
    }
  }

  // 1. Several times through the URL, each sphere where the CSV says.
  for (const time of [times[0], times[5], times[15], times[times.length - 1]]) {
    const shot = await open(`t=${time}&${camera}&flat=1&contacts=0`);
    expectBodies(shot, time, 'url');
  }
  // 2. The slider moves the scene: dragged to a sample, the spheres are where that sample has them.
  await open(`t=0&${camera}&flat=1&contacts=0`);
  await page.evaluate(() => {
    const s = document.getElementById('slider');
    s.value = '12';
    s.dispatchEvent(new Event('input', { bubbles: true }));
  });
  const moved = await shoot();
  check('the slider sets the time', Math.abs((await page.evaluate(() => window.rbsim.time())) - Number(times[12])) < 1e-9);
  expectBodies(moved, times[12], 'slider');

  // 3. Contact arrows where the contacts are: at a time the spheres roll on the ground, arrow
  // pixels at each contact point's projection and halfway along its force.
  const time = times[20];
  const shot = await open(`t=${time}&${camera}&flat=1&contacts=1`);
  const run = JSON.parse(await page.evaluate(() => document.getElementById('rbsim-run').textContent));
  const step = steps.find((s) => Math.abs(s.time - Number(time)) < 1e-9);
  const project = projector(eye, target, [0, 0, 1], fov, shot.image.width, shot.image.height);
  check('contacts at the checked time', step && step.contacts.length >= 3, JSON.stringify(step?.contacts.length));
  for (const c of step ? step.contacts : []) {
    const force = c.impulse.map((v) => v / scene.dt);
    // The arrow's length: force × force_scale, at most a tenth of the run's bounds (the viewer's rule).
    const size = Math.max(...run.bounds.max.map((v, k) => v - run.bounds.min[k]));
    const magnitude = Math.hypot(...force);
    const length = Math.min(magnitude * run.force_scale, 0.1 * size);
    const tip = c.point.map((v, k) => v + (0.5 * length * force[k]) / magnitude);
    for (const [where, p] of [['at', c.point], ['halfway along', tip]]) {
      const at = project(p);
      const got = find(shot.image, [255, 212, 0], 60, at, 4);
      check(`an arrow ${where} ${c.a}'s contact`, got.n >= 3, `${got.n} arrow px near (${at[0].toFixed(1)}, ${at[1].toFixed(1)})`);
    }
  }
  const none = await open(`t=${time}&${camera}&flat=1&contacts=0`);
  check('no arrows with contacts=0', find(none.image, [255, 212, 0], 60).n === 0);

  // 4. Sleeping bodies are tinted: a sphere left at rest on the ground with sleeping on falls
  // asleep after half a second; at the end it is drawn in its colour mixed 55 % towards the tint.
  const still = { ...scene, duration: 1.2, contact: { sleeping: true },
    bodies: [{ ...scene.bodies[0], position: [0, 0, 0.05], velocity: [0, 0, 0] }] };
  writeFileSync(join(dir, 'still.json'), JSON.stringify(still));
  execFileSync(rbsim, [join(dir, 'still.json'), '--out', join(dir, 'still'), '--outputs', 'html', '-q'], {
    stdio: ['ignore', 'ignore', 'inherit'],
  });
  const srgb = (c) => Math.round(255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055));
  const tinted = [1 + 0.55 * (0.35 - 1), 0.55 * 0.45, 0.55 * 0.95].map(srgb);
  await page.goto(`file://${join(dir, 'still', 'run.html')}?t=1.2&${camera}&flat=1&contacts=0`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 2, null, { timeout: 30000 });
  const asleep = await shoot();
  const at = projector(eye, target, [0, 0, 1], fov, asleep.image.width, asleep.image.height)([0, 0, 0.05]);
  const found = find(asleep.image, tinted, 12, at, 30);
  check('a sleeping body is tinted', found.n > 50 && find(asleep.image, [255, 0, 0], 40).n === 0,
    `${found.n} px of the tint ${tinted} near (${at[0].toFixed(1)}, ${at[1].toFixed(1)})`);

  // 5. A robot link is drawn as its visual geometry, its collider on request: the arm's <visual>
  // box is drawn in the arm's colour; with colliders=1 the see-through collision shapes (the
  // base bracket's hull, the arm's cylinder) add pixels.
  const arm = fileURLToPath(new URL('../robot/field/arm_on_world.urdf', import.meta.url));
  execFileSync(rbsim, [arm, '--out', join(dir, 'arm'), '--outputs', 'html', '--duration', '0.2', '-q'], {
    stdio: ['ignore', 'ignore', 'ignore'],
  });
  await page.goto(`file://${join(dir, 'arm', 'run.html')}?flat=1&contacts=0&t=0`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 2, null, { timeout: 30000 });
  check('a colliders toggle for a robot with visuals', await page.evaluate(() => {
    const box = document.getElementById('colliders');
    return box !== null && !box.checked;
  }));
  const armRun = JSON.parse(await page.evaluate(() => document.getElementById('rbsim-run').textContent));
  const armBody = armRun.bodies.find((b) => b.name.endsWith('/upper_arm'));
  check('the arm carries its visual geometry', armBody && armBody.visual !== undefined);
  const visualOnly = await shoot();
  const armPixels = find(visualOnly.image, armBody.color.map(srgb), 12).n;
  check('the arm\'s visual box is drawn', armPixels > 300, `${armPixels} px of its colour`);
  await page.evaluate(() => {
    const box = document.getElementById('colliders');
    box.checked = true;
    box.dispatchEvent(new Event('change', { bubbles: true }));
  });
  const withColliders = await shoot();
  let changed = 0;
  for (let k = 0; k < visualOnly.image.rgb.length; k += 3) {
    const a = visualOnly.image.rgb;
    const b = withColliders.image.rgb;
    if (Math.abs(a[k] - b[k]) + Math.abs(a[k + 1] - b[k + 1]) + Math.abs(a[k + 2] - b[k + 2]) > 20) changed += 1;
  }
  check('the colliders toggle draws the collision shapes too', changed > 200, `${changed} px changed`);

  // 6. A string (a spatial tendon) is a dark line from its pin to its ball, where the trajectory
  // has the ball: at a time it swings, line pixels at three points between the pin and the ball.
  const swing = { dt: 0.001, duration: 0.4, output_rate: 50,
    bodies: [{ name: 'bob', solid: { type: 'sphere', radius: 0.03 }, mass: 0.1, position: [0.5, 0, 0.6], color: [1, 0, 0] }],
    tendons: [{ name: 'string', path: [{ body: 'world', point: [0, 0, 0.6] }, { body: 'bob', point: [0.5, 0, 0.6] }],
      range: [0, 0.5] }],
    forces: [{ type: 'gravity', g: [0, 0, -9.81] }] };
  writeFileSync(join(dir, 'swing.json'), JSON.stringify(swing));
  execFileSync(rbsim, [join(dir, 'swing.json'), '--out', join(dir, 'swing'), '--outputs', 'html,csv', '-q'], {
    stdio: ['ignore', 'ignore', 'inherit'],
  });
  const swingRows = readFileSync(join(dir, 'swing', 'trajectory.csv'), 'utf8').trim().split('\n').slice(1).map((l) => l.split(','));
  const swingTime = swingRows[12][0];
  const bob = swingRows[12].slice(2, 5).map(Number);
  await page.goto(`file://${join(dir, 'swing', 'run.html')}?t=${swingTime}&camera=0.25,-2,0.4&target=0.25,0,0.4&fov=35&flat=1`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 2, null, { timeout: 30000 });
  const strung = await shoot();
  const seen = projector([0.25, -2, 0.4], [0.25, 0, 0.4], [0, 0, 1], 35, strung.image.width, strung.image.height);
  for (const f of [0.25, 0.5, 0.75]) {
    const p = seen([0, 0, 0.6].map((v, k) => v + f * (bob[k] - v)));
    const got = find(strung.image, [51, 51, 51], 40, p, 3);
    check(`the string drawn ${f * 100} % of the way to its ball`, got.n >= 1, `${got.n} line px near (${p[0].toFixed(1)}, ${p[1].toFixed(1)})`);
  }
  check('the ball swung below its pin', bob[2] < 0.5 && Math.abs(Math.hypot(bob[0], bob[2] - 0.6) - 0.5) < 1e-6,
    JSON.stringify(bob));

  // 7. A part dropped (rbsim PART): its page plays, and says how the part rests, as the summary does.
  const cube = ['v 0 0 0', 'v 0.1 0 0', 'v 0 0.1 0', 'v 0.1 0.1 0', 'v 0 0 0.1', 'v 0.1 0 0.1', 'v 0 0.1 0.1', 'v 0.1 0.1 0.1',
    'f 1 3 4 2', 'f 5 6 8 7', 'f 1 2 6 5', 'f 3 7 8 4', 'f 1 5 7 3', 'f 2 4 8 6'].join('\n');
  writeFileSync(join(dir, 'cube.obj'), `${cube}\n`);
  const summary = execFileSync(rbsim, [join(dir, 'cube.obj'), '--count', '2', '--orientation', 'random', '--out',
    join(dir, 'drop'), '--outputs', 'html', '-q'], { encoding: 'utf8' });
  await page.goto(`file://${join(dir, 'drop', 'run.html')}?speed=1`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 10, null, { timeout: 30000 });
  const notes = await page.locator('#notes').innerText();
  const restLine = summary.split('\n').find((l) => l.includes('at rest at t ='));
  check('a drop\'s page says how the parts rest, as the summary does', restLine !== undefined &&
    notes.includes(restLine.trim()) && notes.includes('cube#2'), notes);
  check('a drop\'s page plays', (await page.evaluate(() => window.rbsim.time())) > 0);

  // 8. Played: time advances.
  await page.goto(`${url}?${camera}&speed=1`);
  await page.waitForFunction(() => window.rbsim && window.rbsim.frames > 10, null, { timeout: 30000 });
  check('the page plays', (await page.evaluate(() => window.rbsim.time())) > 0);
  check('no console errors and no network requests', problems.length === 0, problems.join('; '));
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
console.log(`bodies found within ${largest.toFixed(2)} px of their projections`);
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
