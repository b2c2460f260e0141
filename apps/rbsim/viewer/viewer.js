// rbsim's run viewer: plays the run that rbsim wrote into the page (<script id="rbsim-run">, the
// schema in docs/scenes.md) with three.js. Bundled by build.mjs into viewer.bundle.js, which rbsim
// inlines into run.html: no imports or fetches at run time, so the page plays from file://.
//
// URL parameters (all optional): t=SECONDS (start paused there), camera=x,y,z and target=x,y,z
// (world coordinates, m), fov=DEGREES (vertical), speed=FACTOR, trails=1, contacts=0, flat=1 (unlit
// colours, as a test finds bodies by colour), paused=1, colliders=1 (robot links that have visual
// geometry show their collision geometry too, see-through).

import {
  ArrowHelper,
  BufferAttribute,
  BufferGeometry,
  Color,
  DirectionalLight,
  Group,
  HemisphereLight,
  Line,
  LineBasicMaterial,
  Mesh,
  MeshBasicMaterial,
  MeshLambertMaterial,
  PerspectiveCamera,
  Quaternion,
  Scene,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const SLEEP_TINT = new Color(0.35, 0.45, 0.95);
const ARROW_COLOUR = 0xffd400;

function bytes(base64) {
  const text = atob(base64);
  const out = new Uint8Array(text.length);
  for (let i = 0; i < text.length; ++i) out[i] = text.charCodeAt(i);
  return out;
}
const floats = (b) => new Float32Array(bytes(b).buffer);
const uints = (b) => new Uint32Array(bytes(b).buffer);

function parameters() {
  const p = new URLSearchParams(window.location.search);
  const vector = (name) => {
    if (!p.has(name)) return null;
    const v = p.get(name).split(',').map(Number);
    return v.length === 3 && v.every(Number.isFinite) ? new Vector3(v[0], v[1], v[2]) : null;
  };
  const number = (name, fallback) => (p.has(name) && Number.isFinite(Number(p.get(name))) ? Number(p.get(name)) : fallback);
  return {
    t: p.has('t') ? number('t', 0) : null,
    camera: vector('camera'),
    target: vector('target'),
    fov: number('fov', 40),
    speed: number('speed', 1),
    trails: p.get('trails') === '1',
    contacts: p.get('contacts') !== '0',
    flat: p.get('flat') === '1',
    colliders: p.get('colliders') === '1',
    paused: p.get('paused') === '1' || p.has('t'),
  };
}

function style() {
  const css = document.createElement('style');
  css.textContent = `
    html, body { margin: 0; height: 100%; font: 13px system-ui, sans-serif; background: #f4f4f2; color: #222; }
    #rbsim { display: grid; grid-template-columns: 1fr 360px; grid-template-rows: 1fr auto; height: 100%; }
    #view { grid-row: 1; grid-column: 1; position: relative; min-height: 0; }
    #view canvas { display: block; width: 100%; height: 100%; }
    #side { grid-row: 1 / 3; grid-column: 2; padding: 10px; overflow: auto; border-left: 1px solid #ccc; background: #fff; }
    #controls { grid-row: 2; grid-column: 1; display: flex; gap: 10px; align-items: center; padding: 8px 10px;
                border-top: 1px solid #ccc; background: #fff; }
    #controls input[type=range] { flex: 1; }
    #clock { font-variant-numeric: tabular-nums; min-width: 9em; }
    h1 { font-size: 15px; margin: 0 0 6px; }
    .entry { white-space: nowrap; margin-right: 8px; }
    .key { display: inline-block; width: 10px; height: 10px; margin-right: 4px; border: 1px solid #888; }
    canvas.plot { width: 100%; height: 170px; display: block; margin: 6px 0 12px; }
    #notes pre { font: 11px ui-monospace, monospace; white-space: pre; overflow-x: auto; margin: 0; }`;
  document.head.appendChild(css);
}

function layout(run) {
  const root = document.createElement('div');
  root.id = 'rbsim';
  root.innerHTML = `
    <div id="view"></div>
    <div id="controls">
      <button id="play" type="button">Pause</button>
      <input id="slider" type="range" min="0" max="${run.times.length - 1}" step="any" value="0" aria-label="time">
      <span id="clock"></span>
      <label>speed <select id="speed">${[0.1, 0.25, 0.5, 1, 2, 4].map((s) => `<option value="${s}">${s}×</option>`).join('')}</select></label>
      <label><input id="trails" type="checkbox"> trails</label>
      <label><input id="contacts" type="checkbox"> contacts</label>
      ${run.bodies.some((b) => b.visual) ? '<label><input id="colliders" type="checkbox"> colliders</label>' : ''}
    </div>
    <div id="side">
      <h1></h1>
      <div id="legend"></div>
      <canvas class="plot" id="energy"></canvas>
      <canvas class="plot" id="drift"></canvas>
      <div id="notes"></div>
    </div>`;
  document.body.appendChild(root);
  root.querySelector('h1').textContent = `rbsim: ${run.title}`;
  if (run.notes) {  // lines the run wrote for the reader (a drop's resting poses), as text
    const pre = document.createElement('pre');
    pre.textContent = run.notes.join('\n');
    root.querySelector('#notes').appendChild(pre);
  }
  return root;
}

// A plot of series against time, with a cursor at `time` (redrawn as it moves).
class Plot {
  constructor(canvas, times, series, title) {
    this.canvas = canvas;
    this.times = times;
    this.series = series; // [{label, values, colour}]
    this.title = title;
  }

  draw(time) {
    const c = this.canvas;
    const ratio = window.devicePixelRatio || 1;
    const w = c.clientWidth;
    const h = c.clientHeight;
    if (c.width !== Math.round(w * ratio)) c.width = Math.round(w * ratio);
    if (c.height !== Math.round(h * ratio)) c.height = Math.round(h * ratio);
    const g = c.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    const t0 = this.times[0];
    const t1 = this.times[this.times.length - 1];
    let lo = Infinity;
    let hi = -Infinity;
    for (const s of this.series) {
      for (const v of s.values) {
        if (Number.isFinite(v)) {
          lo = Math.min(lo, v);
          hi = Math.max(hi, v);
        }
      }
    }
    if (!(hi > lo)) {
      const pad = Math.abs(hi) > 0 ? Math.abs(hi) * 0.1 : 1;
      lo -= pad;
      hi += pad;
    } else {
      const pad = (hi - lo) * 0.06;
      lo -= pad;
      hi += pad;
    }
    const left = 58;
    const top = 30; // the title, then the series' names, above the frame
    const right = w - 8;
    const bottom = h - 18;
    const x = (t) => left + ((t - t0) / Math.max(t1 - t0, 1e-12)) * (right - left);
    const y = (v) => bottom - ((v - lo) / (hi - lo)) * (bottom - top);
    g.strokeStyle = '#bbb';
    g.strokeRect(left, top, right - left, bottom - top);
    g.fillStyle = '#222';
    g.font = '11px system-ui, sans-serif';
    g.fillText(this.title, left, 11);
    g.fillText(hi.toPrecision(3), 2, top + 8);
    g.fillText(lo.toPrecision(3), 2, bottom);
    g.fillText(`${t1.toFixed(2)} s`, right - 40, h - 4);
    let lx = left;
    for (const s of this.series) {
      g.strokeStyle = s.colour;
      g.lineWidth = 1.5;
      g.beginPath();
      this.times.forEach((t, i) => (i ? g.lineTo(x(t), y(s.values[i])) : g.moveTo(x(t), y(s.values[i]))));
      g.stroke();
      g.fillStyle = s.colour;
      g.fillText(s.label, lx, 25);
      lx += g.measureText(s.label).width + 12;
    }
    g.strokeStyle = '#d00';
    g.lineWidth = 1;
    g.beginPath();
    g.moveTo(x(time), top);
    g.lineTo(x(time), bottom);
    g.stroke();
  }
}

function meshGeometry(entry) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(floats(entry.positions), 3));
  geometry.setIndex(new BufferAttribute(uints(entry.indices), 1));
  geometry.computeVertexNormals();
  return geometry;
}

function main() {
  const run = JSON.parse(document.getElementById('rbsim-run').textContent);
  const options = parameters();
  style();
  const root = layout(run);
  const view = root.querySelector('#view');
  const times = run.times;
  const last = times.length - 1;
  const up = new Vector3(...run.up);

  const renderer = new WebGLRenderer({ antialias: !options.flat, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xf4f4f2);
  view.appendChild(renderer.domElement);
  const scene = new Scene();
  const material = (rgb) =>
    options.flat
      ? new MeshBasicMaterial({ color: new Color(...rgb) })
      : new MeshLambertMaterial({ color: new Color(...rgb), flatShading: true });
  if (!options.flat) {
    scene.add(new HemisphereLight(0xffffff, 0x777766, 1.6));
    const sun = new DirectionalLight(0xffffff, 1.8);
    sun.position.copy(up.clone().multiplyScalar(3).add(new Vector3(1, -1.5, 0)));
    scene.add(sun);
  }
  for (const s of run.statics) scene.add(new Mesh(meshGeometry(s), material(s.color)));

  // A body is drawn as its visual geometry when it has one (a robot link), its collision geometry
  // then see-through on request; else as its collision geometry.
  const seeThrough = (rgb) => {
    const m = material(rgb);
    m.transparent = true;
    m.opacity = 0.35;
    m.depthWrite = false;
    return m;
  };
  const bodies = run.bodies.map((b) => {
    const mesh = new Group();
    const shown = new Mesh(meshGeometry(b.visual || b), material(b.color));
    mesh.add(shown);
    let collider = null;
    if (b.visual) {
      collider = new Mesh(meshGeometry(b), seeThrough(b.color));
      collider.visible = options.colliders;
      mesh.add(collider);
    }
    scene.add(mesh);
    const translations = floats(b.translations);
    const rotations = floats(b.rotations);
    const asleep = b.asleep ? bytes(b.asleep) : null;
    const trail = new BufferGeometry();
    trail.setAttribute('position', new BufferAttribute(translations, 3));
    const line = new Line(trail, new LineBasicMaterial({ color: new Color(...b.color).multiplyScalar(0.6) }));
    line.visible = options.trails;
    scene.add(line);
    return { mesh, shown, collider, translations, rotations, asleep, trail, line, colour: new Color(...b.color) };
  });

  // Spatial tendons (strings): a dark line through their points, moved with the samples.
  const tendons = (run.tendons || []).map((t) => {
    const points = floats(t.points);
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(points.slice(0, 3 * t.count), 3));
    const line = new Line(geometry, new LineBasicMaterial({ color: 0x333333 }));
    scene.add(line);
    return { count: t.count, points, geometry };
  });

  // The camera: given, or looking at the run's bounds from the front-right, a little above.
  const lo = new Vector3(...run.bounds.min);
  const hi = new Vector3(...run.bounds.max);
  const centre = lo.clone().add(hi).multiplyScalar(0.5);
  const radius = Math.max(hi.clone().sub(lo).length() / 2, 1e-3);
  const camera = new PerspectiveCamera(options.fov, 1, radius / 100, radius * 100);
  camera.up.copy(up);
  const side = Math.abs(up.z) > 0.5 ? new Vector3(1.2, -2.0, 0.9) : new Vector3(1.2, 0.9, 2.0);
  const target = options.target || centre;
  camera.position.copy(options.camera || target.clone().add(side.normalize().multiplyScalar((radius / Math.tan((options.fov * Math.PI) / 360)) * 0.9)));
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(target);
  controls.update();

  const arrows = new Group();
  scene.add(arrows);
  const pool = [];
  const contacts = run.contacts ? run.contacts.map(floats) : null;
  const typicalArrow = 0.05 * Math.max(...hi.clone().sub(lo).toArray(), 1e-3); // as rbsim sets force_scale

  const energy = new Plot(root.querySelector('#energy'), times, [
    { label: 'kinetic', values: run.diagnostics.kinetic, colour: '#c33' },
    { label: 'potential', values: run.diagnostics.potential, colour: '#36c' },
    { label: 'total', values: run.diagnostics.kinetic.map((k, i) => k + run.diagnostics.potential[i]), colour: '#222' },
  ], 'energy (J)');
  const drift = new Plot(root.querySelector('#drift'), times, [
    { label: 'energy drift', values: run.diagnostics.energy_drift, colour: '#222' },
    { label: '|L| drift', values: run.diagnostics.momentum_drift, colour: '#2a2' },
  ], 'relative drift since t = 0');
  const named = run.bodies.slice(0, 12);
  root.querySelector('#legend').innerHTML =
    named.map((b, i) => `<span class="entry"><span class="key" style="background:#${bodies[i].colour.getHexString()}"></span>${b.name.replace(/[<&]/g, '')}</span>`).join(' ') +
    (run.bodies.length > named.length ? ` and ${run.bodies.length - named.length} more bodies` : '') +
    `<p>${contacts ? `Contact forces are yellow arrows (${run.force_scale > 0 ? `${(1 / run.force_scale).toPrecision(3)} N per metre, at most twice the usual length` : 'none'}); sleeping bodies are tinted blue.` : 'This run was written without contacts.'}</p>`;

  const slider = root.querySelector('#slider');
  const clock = root.querySelector('#clock');
  const play = root.querySelector('#play');
  const speed = root.querySelector('#speed');
  const trails = root.querySelector('#trails');
  const showContacts = root.querySelector('#contacts');
  const showColliders = root.querySelector('#colliders');
  if (showColliders) showColliders.checked = options.colliders;
  speed.value = String(options.speed);
  if (speed.value === '') speed.value = '1';
  trails.checked = options.trails;
  showContacts.checked = options.contacts && !!contacts;
  showContacts.disabled = !contacts;

  // One sample (rbsim poses): a still scene, no clock or plots.
  if (last === 0) {
    for (const id of ['#play', '#slider', '#clock', '#energy', '#drift']) root.querySelector(id).style.display = 'none';
    for (const label of root.querySelectorAll('#controls label')) label.style.display = 'none';
    root.querySelector('#legend p').remove();
  }
  let playing = !options.paused && last > 0;
  let position = 0; // in samples, fractional
  const sampleAt = (t) => {
    if (t <= times[0]) return 0;
    if (t >= times[last]) return last;
    let a = 0;
    let b = last;
    while (b - a > 1) {
      const m = (a + b) >> 1;
      if (times[m] <= t) a = m;
      else b = m;
    }
    return a + (t - times[a]) / Math.max(times[b] - times[a], 1e-12);
  };
  const timeAt = (p) => {
    const i = Math.min(Math.floor(p), last);
    return i >= last ? times[last] : times[i] + (p - i) * (times[i + 1] - times[i]);
  };

  const qa = new Quaternion();
  const qb = new Quaternion();
  function pose() {
    const i = Math.min(Math.floor(position), last);
    const j = Math.min(i + 1, last);
    const f = position - i;
    for (const b of bodies) {
      const t = b.translations;
      b.mesh.position.set(
        t[3 * i] + f * (t[3 * j] - t[3 * i]),
        t[3 * i + 1] + f * (t[3 * j + 1] - t[3 * i + 1]),
        t[3 * i + 2] + f * (t[3 * j + 2] - t[3 * i + 2]),
      );
      const r = b.rotations;
      qa.set(r[4 * i], r[4 * i + 1], r[4 * i + 2], r[4 * i + 3]);
      qb.set(r[4 * j], r[4 * j + 1], r[4 * j + 2], r[4 * j + 3]);
      b.mesh.quaternion.slerpQuaternions(qa, qb, f);
      const sleeping = b.asleep && b.asleep[Math.round(position)] === 1;
      b.shown.material.color.copy(b.colour);
      if (sleeping) b.shown.material.color.lerp(SLEEP_TINT, 0.55);
      if (b.collider) b.collider.visible = showColliders.checked;
      b.line.visible = trails.checked;
      b.trail.setDrawRange(0, i + 1);
    }
    for (const t of tendons) {
      const at = t.geometry.attributes.position;
      const n = 3 * t.count;
      for (let k = 0; k < n; ++k) at.array[k] = t.points[n * i + k] + f * (t.points[n * j + k] - t.points[n * i + k]);
      at.needsUpdate = true;
    }
    // The contacts of the sample at or before the time shown.
    let used = 0;
    if (contacts && showContacts.checked && run.force_scale > 0) {
      const c = contacts[i];
      for (let k = 0; k + 5 < c.length; k += 6) {
        const force = new Vector3(c[k + 3], c[k + 4], c[k + 5]);
        // At most twice the typical arrow (an impact's force would cross the scene): longer is clamped.
        const length = Math.min(force.length() * run.force_scale, 2 * typicalArrow);
        if (!(length > 0)) continue;
        if (used === pool.length) {
          const arrow = new ArrowHelper(new Vector3(0, 0, 1), new Vector3(), 1, ARROW_COLOUR);
          // Drawn over the bodies: a contact lies under the body it pushes.
          for (const part of [arrow.line, arrow.cone]) {
            part.material.depthTest = false;
            part.renderOrder = 10;
          }
          pool.push(arrow);
          arrows.add(arrow);
        }
        const arrow = pool[used++];
        arrow.position.set(c[k], c[k + 1], c[k + 2]);
        arrow.setDirection(force.normalize());
        const head = Math.min(length * 0.3, typicalArrow * 0.25);
        arrow.setLength(length, head, head * 0.6);
        arrow.visible = true;
      }
    }
    for (let k = used; k < pool.length; ++k) pool[k].visible = false;
    const t = timeAt(position);
    slider.value = String(position);
    clock.textContent = `t = ${t.toFixed(3)} s / ${times[last].toFixed(3)} s`;
    energy.draw(t);
    drift.draw(t);
    play.textContent = playing ? 'Pause' : 'Play';
  }

  function resize() {
    const w = view.clientWidth;
    const h = view.clientHeight;
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }

  slider.addEventListener('input', () => {
    position = Math.min(Math.max(Number(slider.value), 0), last);
    playing = false;
    pose();
  });
  play.addEventListener('click', () => {
    if (!playing && position >= last) position = 0;
    playing = !playing;
    pose();
  });
  trails.addEventListener('change', pose);
  showContacts.addEventListener('change', pose);
  if (showColliders) showColliders.addEventListener('change', pose);
  for (const canvas of [root.querySelector('#energy'), root.querySelector('#drift')]) {
    canvas.addEventListener('click', (e) => {
      const r = canvas.getBoundingClientRect();
      const f = (e.clientX - r.left - 58) / Math.max(r.width - 66, 1);
      position = sampleAt(times[0] + Math.min(Math.max(f, 0), 1) * (times[last] - times[0]));
      playing = false;
      pose();
    });
  }
  window.addEventListener('resize', resize);

  if (options.t !== null) position = sampleAt(options.t);
  resize();
  pose();
  let before = performance.now();
  let frames = 0;
  function frame(now) {
    const elapsed = (now - before) / 1000;
    before = now;
    if (playing) {
      const t = Math.min(timeAt(position) + elapsed * Number(speed.value), times[last]);
      position = sampleAt(t);
      if (t >= times[last]) playing = false;
      pose();
    }
    controls.update();
    renderer.render(scene, camera);
    window.rbsim.frames = ++frames;
    requestAnimationFrame(frame);
  }
  // For tests and scripts: the time shown, the camera, frames drawn so far.
  window.rbsim = {
    frames: 0,
    time: () => timeAt(position),
    setTime: (t) => {
      position = sampleAt(t);
      playing = false;
      pose();
    },
    camera: () => ({
      position: camera.position.toArray(),
      target: controls.target.toArray(),
      up: camera.up.toArray(),
      fov: camera.fov,
      aspect: camera.aspect,
    }),
  };
  requestAnimationFrame(frame);
}

main();
