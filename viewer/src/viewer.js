// The page Sinew writes next to a run (io/viewer_writer.hpp): loads the GLB embedded in the
// page, shows one frame at a time (morph target f is frame f), colours the vertices by the
// chosen per-vertex field, and offers play/pause, a frame slider and a field menu.
// URL parameters fix the state for screenshots: ?frame=N&field=NAME&play=0&controls=0.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const settings = JSON.parse(document.getElementById('sinew-settings').textContent);
const params = new URLSearchParams(window.location.search);

function decodeBase64(text) {
  const bytes = atob(text.replace(/\s+/g, ''));
  const out = new Uint8Array(bytes.length);
  for (let i = 0; i < bytes.length; ++i) out[i] = bytes.charCodeAt(i);
  return out.buffer;
}

function element(tag, style, parent) {
  const e = document.createElement(tag);
  Object.assign(e.style, style);
  if (parent) parent.appendChild(e);
  return e;
}

function showError(message) {
  document.body.dataset.error = message;
  const box = element('pre', { color: '#a00', padding: '1em', whiteSpace: 'pre-wrap' }, document.body);
  box.textContent = 'Sinew viewer: ' + message;
}

function formatValue(v) {
  const a = Math.abs(v);
  return a === 0 ? '0' : a >= 1e4 || a < 1e-2 ? v.toExponential(2) : String(Number(v.toPrecision(3)));
}

// Colour of t in [0, 1] from the file's stops (linear RGB, evenly spaced).
function colorAt(stops, t, out, offset) {
  const s = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const k = Math.min(Math.floor(s), stops.length - 2);
  const a = s - k;
  for (let c = 0; c < 3; ++c) out[offset + c] = (1 - a) * stops[k][c] + a * stops[k + 1][c];
}

async function start() {
  Object.assign(document.body.style, { margin: '0', overflow: 'hidden', fontFamily: 'sans-serif', background: '#eef0f3' });
  const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0xeef0f3);
  document.body.appendChild(renderer.domElement);

  const loader = new GLTFLoader();
  const gltf = await new Promise((resolve, reject) =>
    loader.parse(decodeBase64(document.getElementById('sinew-glb').textContent), '', resolve, reject));
  const parser = gltf.parser;
  const json = parser.json;
  const info = (json.extras && json.extras.sinew) || {};
  const frames = info.frames || [0];
  const times = info.times || frames;
  const stops = info.color_stops || [[0, 0, 0], [1, 1, 1]];

  // The meshes, with their role and per-frame field arrays.
  const objects = [];
  const fieldNames = [];
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  for (const mesh of meshes) {
    const assoc = parser.associations.get(mesh);
    const meshIndex = assoc && assoc.meshes !== undefined ? assoc.meshes : json.nodes[assoc.nodes].mesh;
    const extras = json.meshes[meshIndex].extras || {};
    const fields = {};
    for (const [name, accessors] of Object.entries(extras.fields || {})) {
      fields[name] = await Promise.all(accessors.map((a) => parser.getDependency('accessor', a).then((b) => b.array)));
      if (!fieldNames.includes(name)) fieldNames.push(name);
    }
    mesh.frustumCulled = false;  // morphs move vertices outside the rest bounds
    // Vertex colours multiply the base colour: white under a field, the object's own colour without.
    const own = extras.base_color ? new THREE.Color().setRGB(...extras.base_color.slice(0, 3)) : mesh.material.color.clone();
    objects.push({ mesh, role: extras.role || 'body', fields, ranges: extras.field_ranges || {}, own });
  }

  // With a render surface, the simulation lattice's surface (which encloses it) turns into a faint hull.
  if (objects.some((o) => o.role === 'render_surface')) {
    for (const o of objects.filter((x) => x.role === 'body')) Object.assign(o.mesh.material, { transparent: true, opacity: 0.2, depthWrite: false });
  }

  const scene = new THREE.Scene();
  scene.add(gltf.scene);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8088a0, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.8);
  sun.position.set(2, 4, 3);
  scene.add(sun);
  gltf.scene.updateMatrixWorld(true);

  // Bounds over every frame of the bodies (obstacles such as a ground plane would dwarf them).
  const box = new THREE.Box3();
  const p = new THREE.Vector3();
  const framed = objects.some((o) => o.role === 'body' || o.role === 'render_surface')
    ? objects.filter((o) => o.role === 'body' || o.role === 'render_surface') : objects;
  for (const { mesh } of framed) {
    const base = mesh.geometry.attributes.position;
    const targets = mesh.geometry.morphAttributes.position || [];
    for (let f = -1; f < targets.length; ++f) {
      for (let i = 0; i < base.count; ++i) {
        p.fromBufferAttribute(base, i);
        if (f >= 0) p.x += targets[f].getX(i), p.y += targets[f].getY(i), p.z += targets[f].getZ(i);
        box.expandByPoint(p.applyMatrix4(mesh.matrixWorld));
      }
    }
  }
  const center = box.getCenter(new THREE.Vector3());
  const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 1e-6);
  const camera = new THREE.PerspectiveCamera(35, window.innerWidth / window.innerHeight, radius / 100, radius * 100);
  // A fixed three-quarter view from the front right, slightly above (deterministic screenshots).
  const direction = new THREE.Vector3(1.0, 0.75, 1.6).normalize();
  // Distance: the bounds' corners fill 85 % of the view (a few passes, since perspective makes
  // the projected size depend on the distance).
  let distance = radius / Math.sin(THREE.MathUtils.degToRad(35 / 2));
  const corner = new THREE.Vector3();
  for (let pass = 0; pass < 4; ++pass) {
    camera.position.copy(center).addScaledVector(direction, distance);
    camera.lookAt(center);
    camera.updateMatrixWorld();
    let extent = 0;
    for (let c = 0; c < 8; ++c) {
      corner.set(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y, c & 4 ? box.max.z : box.min.z).project(camera);
      extent = Math.max(extent, Math.abs(corner.x), Math.abs(corner.y));
    }
    if (pass < 3) distance *= Math.max(extent, 1e-3) / 0.85;
  }
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.copy(center);
  controls.update();

  // ---- state
  let frame = Math.min(Math.max(parseInt(params.get('frame') || '0', 10) || 0, 0), frames.length - 1);
  let field = params.has('field') ? params.get('field') : (fieldNames[0] || '');
  if (field && !fieldNames.includes(field)) field = '';
  let playing = params.has('play') ? params.get('play') !== '0' : frames.length > 1;

  function fieldRange(name) {
    let lo = Infinity, hi = -Infinity;
    for (const o of objects) if (o.ranges[name]) lo = Math.min(lo, o.ranges[name][0]), hi = Math.max(hi, o.ranges[name][1]);
    return [lo, hi];
  }

  function apply() {
    const [lo, hi] = field ? fieldRange(field) : [0, 1];
    for (const o of objects) {
      const influences = o.mesh.morphTargetInfluences;
      if (influences) {
        influences.fill(0);
        if (frame > 0) influences[frame - 1] = 1;
      }
      const colors = o.mesh.geometry.attributes.color;
      const values = field && o.fields[field] ? o.fields[field][frame] : null;
      o.mesh.material.vertexColors = Boolean(values && colors);
      if (values && colors) o.mesh.material.color.setRGB(1, 1, 1);
      else o.mesh.material.color.copy(o.own);
      if (values && colors) {
        for (let i = 0; i < values.length; ++i) colorAt(stops, hi > lo ? (values[i] - lo) / (hi - lo) : 0.5, colors.array, 3 * i);
        colors.needsUpdate = true;
      }
      o.mesh.material.needsUpdate = true;
    }
    slider.value = String(frame);
    const t = times[frame];
    label.textContent = `frame ${frames[frame]} (${frame + 1}/${frames.length})` + (t !== frames[frame] ? `, t = ${Number(t).toPrecision(4)} s` : '');
    legend.style.display = field ? 'flex' : 'none';
    if (field) {
      legendName.textContent = field;
      legendLo.textContent = formatValue(Math.abs(lo) < 1e-9 * Math.abs(hi) ? 0 : lo);
      legendHi.textContent = formatValue(hi);
    }
    button.textContent = playing ? 'Pause' : 'Play';
  }

  // ---- controls
  const bar = element('div', { position: 'fixed', left: '0', right: '0', bottom: '0', display: 'flex', gap: '0.8em',
    alignItems: 'center', padding: '0.5em 0.8em', background: 'rgba(255,255,255,0.85)', fontSize: '14px' }, document.body);
  if (params.get('controls') === '0') bar.style.display = 'none';
  const button = element('button', { width: '5em' }, bar);
  button.id = 'play';
  const slider = element('input', { flex: '1' }, bar);
  Object.assign(slider, { type: 'range', min: '0', max: String(frames.length - 1), step: '1', id: 'frame' });
  const label = element('span', { minWidth: '11em' }, bar);
  const select = element('select', {}, bar);
  select.id = 'field';
  for (const name of ['', ...fieldNames]) {
    const opt = element('option', {}, select);
    opt.value = name;
    opt.textContent = name || '(no colour)';
  }
  select.value = field;
  // The colour bar: top right, the field's range over all frames under the ramp.
  const legend = element('div', { position: 'fixed', right: '0.8em', top: '0.5em', flexDirection: 'column', gap: '0.2em',
    fontSize: '13px', color: '#333', width: '11em' }, document.body);
  legend.id = 'legend';
  const legendName = element('span', { textAlign: 'center' }, legend);
  const ramp = element('div', { height: '0.9em', border: '1px solid #888' }, legend);
  const legendRange = element('div', { display: 'flex', justifyContent: 'space-between' }, legend);
  const legendLo = element('span', {}, legendRange);
  const legendHi = element('span', {}, legendRange);
  // CSS wants sRGB: the stops are linear.
  const css = stops.map((c) => `rgb(${c.map((v) => Math.round(255 * (v <= 0.0031308 ? 12.92 * v : 1.055 * v ** (1 / 2.4) - 0.055))).join(',')})`);
  ramp.style.background = `linear-gradient(to right, ${css.join(',')})`;
  const title = element('div', { position: 'fixed', left: '0.8em', top: '0.5em', fontSize: '15px', color: '#333' }, document.body);
  title.textContent = settings.title || 'Sinew';

  button.addEventListener('click', () => { playing = !playing; apply(); });
  slider.addEventListener('input', () => { frame = parseInt(slider.value, 10); playing = false; apply(); });
  select.addEventListener('change', () => { field = select.value; apply(); });
  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
  });

  apply();
  let last = performance.now();
  renderer.setAnimationLoop((now) => {
    if (playing && frames.length > 1 && now - last >= 1000 / (settings.fps || 12)) {
      frame = (frame + 1) % frames.length;
      last = now;
      apply();
    }
    renderer.render(scene, camera);
  });
  renderer.render(scene, camera);
  window.sinewViewer = {
    frames, times, fields: fieldNames,
    setFrame(f) { frame = f; playing = false; apply(); renderer.render(scene, camera); },
    setField(name) { field = name; select.value = name; apply(); renderer.render(scene, camera); },
  };
  document.body.dataset.ready = '1';
}

start().catch((e) => showError(e && e.message ? e.message : String(e)));
