// SPDX-License-Identifier: GPL-3.0-or-later
// roifem serve's page: draws the brain's surface as the server's frames move it, sends the hand.
// Messages: src/serve/hand_message.hpp (page -> server), src/serve/page_messages.hpp (server -> page).
import * as THREE from '/three/build/three.module.js';
import { OrbitControls } from '/three/examples/jsm/controls/OrbitControls.js';

// The hand's message kinds, their codes, sizes and payloads: the server's one table
// (src/serve/hand_message.cpp), as its hello sends it. Nothing is sent before the hello.
let HAND = null;

// What the tests (and a curious user's console) read: window.roifem.
const live = {
  hello: null, state: null, ready: false, frames: 0, framesDrawn: 0, fps: 0,
  latencies: [], notices: [], role: null, shown: null, meshes: 0,
  screenOf: null,  // (x, y, z) mm at rest -> {x, y} in client pixels
};
window.roifem = live;

// ---- The view ----
const container = document.getElementById('view');
// No antialiasing and one pixel per CSS pixel: a software renderer (headless Chromium's SwiftShader) draws
// twice the frames.
const renderer = new THREE.WebGLRenderer({ antialias: false });
renderer.setPixelRatio(1);
container.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x15171c);
const camera = new THREE.PerspectiveCamera(40, 1, 1, 5000);
const controls = new OrbitControls(camera, renderer.domElement);
scene.add(new THREE.AmbientLight(0xffffff, 0.45));
const light = new THREE.DirectionalLight(0xffffff, 0.7);
scene.add(light);

function resize() {
  const w = container.clientWidth, h = container.clientHeight;
  renderer.setSize(w, h);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
}
window.addEventListener('resize', resize);
resize();

let brain = null;         // THREE.Mesh
let rest = null;          // Float32Array 3V, mm
let displacement = null;  // Float32Array 3V, mm
let flags = null;         // Uint8Array V
let triangles = null;     // Uint32Array 3T
const roiPoints = [];     // per model: THREE.Points
let fixedPoints = null;
let tool = null;
let barMax = 1;

// The 2D canvases (plots, colour bar) drawn on the CPU: drawn by the GPU process (Chromium's
// default), each plot's redraw held up the WebGL frames behind it under a software renderer
// (latency p90 74-94 ms against 50-54; docs/simulator.md).
const CPU_CANVAS = { willReadFrequently: true };

function colour(s, out, k) {  // s in [0, 1]: dark blue -> cyan -> yellow -> red
  const stops = [[0.19, 0.22, 0.45], [0.15, 0.65, 0.75], [0.95, 0.85, 0.25], [0.85, 0.2, 0.15]];
  const x = Math.min(Math.max(s, 0), 1) * (stops.length - 1), i = Math.min(Math.floor(x), stops.length - 2), f = x - i;
  for (let c = 0; c < 3; ++c) out[k + c] = stops[i][c] * (1 - f) + stops[i + 1][c] * f;
}

function drawColourBar() {
  const bar = document.getElementById('colour-bar'), g = bar.getContext('2d', CPU_CANVAS);
  const rgb = [0, 0, 0];
  for (let x = 0; x < bar.width; ++x) {
    colour(x / (bar.width - 1), rgb, 0);
    g.fillStyle = `rgb(${rgb.map((v) => Math.round(255 * v)).join(',')})`;
    g.fillRect(x, 0, 1, bar.height);
  }
  document.getElementById('bar-max').textContent = barMax.toPrecision(2);
}

// A surface the server sends: the first, then a cut model's after each cut (or a switch to a model with
// another surface). The view stays where the user turned it.
function onMesh(buffer) {
  const first = brain === null;
  if (!first) {
    for (const o of [brain, fixedPoints, ...roiPoints]) {
      scene.remove(o);
      o.geometry.dispose();
    }
    roiPoints.length = 0;
  }
  const view = new DataView(buffer);
  const V = view.getUint32(4, true), T = view.getUint32(8, true);
  let offset = 16;
  rest = new Float32Array(buffer.slice(offset, offset + 12 * V)); offset += 12 * V;
  triangles = new Uint32Array(buffer.slice(offset, offset + 12 * T)); offset += 12 * T;
  flags = new Uint8Array(buffer.slice(offset, offset + V));
  displacement = new Float32Array(3 * V);
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(rest), 3));
  geometry.setAttribute('color', new THREE.BufferAttribute(new Float32Array(3 * V), 3));
  geometry.setIndex(new THREE.BufferAttribute(triangles, 1));
  geometry.computeVertexNormals();
  brain = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors }));
  scene.add(brain);
  const points = (mask, colourHex, size) => {
    const index = [];
    for (let v = 0; v < V; ++v) if (flags[v] & mask) index.push(v);
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', geometry.getAttribute('position'));
    g.setIndex(new THREE.BufferAttribute(new Uint32Array(index), 1));
    const p = new THREE.Points(g, new THREE.PointsMaterial({ color: colourHex, size, sizeAttenuation: false }));
    scene.add(p);
    return p;
  };
  fixedPoints = points(1, 0x8a8a8a, 3);
  live.hello.models.forEach((m, k) => roiPoints.push(points(2 << k, 0x4fa3ff, 3)));
  live.meshes += 1;
  live.triangles = T;
  recolour();
  showRoi();
  if (!first) return;
  tool = new THREE.Mesh(new THREE.SphereGeometry(live.hello.radius_mm, 16, 12),
                        new THREE.MeshPhongMaterial({ color: 0xe0e0e0, transparent: true, opacity: 0.6 }));
  tool.visible = false;
  scene.add(tool);
  drawColourBar();
  const box = new THREE.Box3(new THREE.Vector3(...live.hello.box_mm[0]), new THREE.Vector3(...live.hello.box_mm[1]));
  const centre = box.getCenter(new THREE.Vector3()), size = box.getSize(new THREE.Vector3()).length();
  controls.target.copy(centre);
  camera.position.copy(centre).add(new THREE.Vector3(0.15 * size, -1.6 * size, 0.7 * size));
  camera.up.set(0, 0, 1);
  camera.near = size / 100; camera.far = size * 20;
  camera.updateProjectionMatrix();
  controls.update();
  showRoi();
  live.ready = true;
}

function recolour() {
  const V = rest.length / 3, position = brain.geometry.getAttribute('position'), colours = brain.geometry.getAttribute('color');
  const p = position.array, size = recolour.size && recolour.size.length === V ? recolour.size : (recolour.size = new Float32Array(V));
  let largest = 0;
  for (let v = 0, i = 0; v < V; ++v, i += 3) {
    const dx = displacement[i], dy = displacement[i + 1], dz = displacement[i + 2];
    p[i] = rest[i] + dx;
    p[i + 1] = rest[i + 1] + dy;
    p[i + 2] = rest[i + 2] + dz;
    const s = Math.sqrt(dx * dx + dy * dy + dz * dz);
    size[v] = s;
    if (s > largest) largest = s;
  }
  live.largestDisplacementMm = largest;
  const decade = Math.pow(10, Math.floor(Math.log10(Math.max(largest, 1e-3))));
  const top = [1, 2, 3, 5, 10].map((m) => m * decade).find((n) => n >= largest * (1 - 1e-6));
  for (let v = 0; v < V; ++v) colour(size[v] / top, colours.array, 3 * v);
  position.needsUpdate = true;
  colours.needsUpdate = true;
  brain.geometry.computeVertexNormals();
  brain.geometry.computeBoundingSphere();
  if (top !== barMax) {
    barMax = top;
    drawColourBar();
  }
}

// ---- The socket ----
const socket = new WebSocket(`ws://${location.host}/ws`);
socket.binaryType = 'arraybuffer';
let sequence = 0;
const sentAt = new Map();  // target sequence -> performance.now()
let pendingFrame = null, frameShows = 0;

// A hand message of kind `name` ('pick', 'target', ...): `numbers` are its float64s (a point, a
// stroke), `index` its uint32 (a model, compare on or off), as the kind's payload says.
function send(name, numbers, index) {
  if (socket.readyState !== WebSocket.OPEN || !HAND) return;
  const kind = HAND.kinds[name], at = HAND.header_bytes;
  const buffer = new ArrayBuffer(kind.bytes), view = new DataView(buffer);
  view.setUint8(0, kind.code);
  view.setUint32(4, ++sequence, true);
  if (kind.payload === 'point' || kind.payload === 'stroke') numbers.forEach((x, k) => view.setFloat64(at + 8 * k, x, true));
  if (kind.payload === 'index') view.setUint32(at, index, true);
  if (name === 'target') sentAt.set(sequence, performance.now());
  socket.send(buffer);
}

socket.onmessage = (event) => {
  if (typeof event.data === 'string') return onJson(JSON.parse(event.data));
  const tag = new TextDecoder().decode(new Uint8Array(event.data, 0, 4));
  if (tag === 'RFMS') onMesh(event.data);
  if (tag === 'RFFR' && brain) pendingFrame = event.data;  // drawn at the next animation frame
};
socket.onclose = () => note('the server closed the connection');

function onJson(m) {
  if (m.type === 'hello') {
    live.hello = m;
    HAND = m.hand;
    live.role = m.role;
    document.getElementById('scenario').textContent = `${m.scenario}: ${m.vertices} surface nodes, ${m.rate_hz} Hz`;
    document.getElementById('loads').textContent = `loads beside the hand: ${m.loads}`;
    const models = document.getElementById('models');
    m.models.forEach((model, k) => {
      const b = document.createElement('button');
      b.textContent = model.nonlinear ? `${model.name} (NL)` : model.cut ? `${model.name} (cut)` : model.name;
      b.title = `${model.description} (${model.unknowns} unknowns)`;
      b.onclick = () => send('model', null, k);
      models.appendChild(b);
    });
    showRole();
  } else if (m.type === 'state') {
    live.state = m;
    onState(m);
  } else if (m.type === 'notice') {
    note(m.text);
  } else if (m.type === 'role') {
    live.role = m.role;
    showRole();
  }
}

function showRole() {
  document.getElementById('role').textContent = live.role === 'driver' ? 'You drive.' : 'You watch (another page drives).';
}

function note(text) {
  live.notices.push(text);
  const li = document.createElement('li');
  li.textContent = text;
  const list = document.getElementById('notices');
  list.prepend(li);
  while (list.children.length > 30) list.lastChild.remove();
}

// ---- Readouts ----
const forceHistory = [];
let currentModel = -1;
let lastReadout = 0;
function onState(m) {
  const f = m.force_mN, magnitude = Math.hypot(...f);
  forceHistory.push([m.t, magnitude, ...f]);
  if (forceHistory.length > 600) forceHistory.shift();
  if (m.model !== currentModel) {
    currentModel = m.model;
    document.querySelectorAll('#models button').forEach((b, k) => b.classList.toggle('current', k === m.model));
    showRoi();
  }
  if (tool) {
    tool.visible = m.grip_nodes > 0;
    tool.position.set(...m.tool_mm);
  }
  // The readouts and the plot at 10 Hz: text a person reads, and each repaint costs a software
  // renderer a share of the frames.
  const now = performance.now();
  if (now - lastReadout < 100) return;
  lastReadout = now;
  live.shown = m;  // the state the readouts show
  plotDirty = true;
  // A failed tick ends the grab: say so where the force was, not a frozen force that looks live.
  document.getElementById('force').textContent = m.failure ? 'failed' : magnitude.toFixed(2);
  document.getElementById('force-parts').textContent = m.failure ? m.failure : `(${f.map((x) => x.toFixed(2)).join(', ')})`;
  document.getElementById('force-parts').classList.toggle('failure', !!m.failure);
  const t = m.ticks;
  showComparison(m);
  document.getElementById('physics').textContent = m.grip_nodes > 0 || t.rate_hz > 0
    ? `${t.rate_hz.toFixed(0)} ticks/s, median ${t.median_ms.toFixed(3)} ms, p99 ${t.p99_ms.toFixed(3)} ms, ` +
      `late ${t.late_per_10k.toFixed(1)} per 10,000 (of ${t.count})`
    : `idle between grabs (the loop ticks while the hand holds); last grab: median ${t.median_ms.toFixed(3)} ms, ` +
      `p99 ${t.p99_ms.toFixed(3)} ms (of ${t.count})`;
  // A neo-Hookean model: what its fixed budget of Newton iterations left of the law's correction.
  document.getElementById('newton').textContent = !m.newton ? ''
    : m.failure ? 'neo-Hookean: no tick (the grab ended at a failed tick)'
    : m.grip_nodes === 0 ? 'neo-Hookean: no grab'
    : `neo-Hookean: ${m.newton.iterations} Newton iterations a tick, residual ${m.newton.residual.toExponential(1)} of the law's correction`;
}

function drawForcePlot() {
  const canvas = document.getElementById('force-plot'), g = canvas.getContext('2d', CPU_CANVAS);
  g.clearRect(0, 0, canvas.width, canvas.height);
  if (forceHistory.length < 2) return;
  const top = Math.max(1, ...forceHistory.map((r) => Math.max(...r.slice(1).map(Math.abs))));
  const colours = ['#eee', '#e66', '#6e6', '#69f'];
  for (let c = 0; c < 4; ++c) {
    g.strokeStyle = colours[c];
    g.beginPath();
    forceHistory.forEach((r, k) => {
      const x = (k / 599) * canvas.width, y = canvas.height / 2 - (r[1 + c] / top) * (canvas.height / 2 - 4);
      if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
    });
    g.stroke();
  }
  g.fillStyle = '#aab';
  g.fillText(`±${top.toPrecision(2)} mN  |F| x y z`, 4, 12);
}

// ---- Compare: the live model's force error against the full model on the same hand ----
const errorHistory = [];
document.getElementById('compare').onchange = (event) => send('compare', null, event.target.checked ? 1 : 0);
function showComparison(m) {
  const text = document.getElementById('compare-text'), c = m.compare;
  if (!c) { text.textContent = ''; return; }
  if (live.hello.models[m.model].cut) {
    text.textContent = `${m.model_name} is the scalpel's: the full model stays whole, nothing to compare.`;
    return;
  }
  if (live.hello.models[m.model].roi_nodes === 0) {
    text.textContent = 'The live model is a full model: nothing to compare.';
    return;
  }
  if (m.grab > 0 && c.reference === null) {
    text.textContent = `No full model with ${m.model_name}'s law is prepared (roifem serve --models ... full` +
      `${m.newton ? '-neo-hookean' : ''}): nothing to compare.`;
    return;
  }
  if (c.t === 0) { text.textContent = 'From the next grab.'; return; }
  const e = Math.hypot(...c.error_mN);
  errorHistory.push(e);
  if (errorHistory.length > 600) errorHistory.shift();
  text.textContent = `at t = ${c.t.toFixed(3)} s ${c.reference} feels ${Math.hypot(...c.full_force_mN).toFixed(2)} mN; ` +
    `${m.model_name}'s error ${e.toFixed(3)} mN (the grab's largest ${c.largest_error_mN.toFixed(3)} mN of ` +
    `${c.largest_full_force_mN.toFixed(2)} mN), ${c.behind_s.toFixed(2)} s behind`;
  const canvas = document.getElementById('error-plot'), g = canvas.getContext('2d', CPU_CANVAS);
  g.clearRect(0, 0, canvas.width, canvas.height);
  const top = Math.max(1e-3, ...errorHistory);
  g.strokeStyle = '#fa4';
  g.beginPath();
  errorHistory.forEach((v, k) => {
    const x = (k / 599) * canvas.width, y = canvas.height - 2 - (v / top) * (canvas.height - 14);
    if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
  });
  g.stroke();
  g.fillStyle = '#aab';
  g.fillText(`|F_roi - F_full| up to ${top.toPrecision(2)} mN`, 4, 12);
}

function showRoi() {
  const on = document.getElementById('show-roi').checked;
  roiPoints.forEach((p, k) => { p.visible = on && k === currentModel; });
  dirty = true;
}
document.getElementById('show-roi').onchange = showRoi;
document.getElementById('save').onclick = () => send('save');
document.getElementById('whole').onclick = () => send('whole');

// ---- The hand ----
const raycaster = new THREE.Raycaster();
let drag = null;  // {restPoint, hitPoint, plane, depth, lastY}
function rayAt(event) {
  const r = renderer.domElement.getBoundingClientRect();
  raycaster.setFromCamera(new THREE.Vector2(((event.clientX - r.left) / r.width) * 2 - 1, -((event.clientY - r.top) / r.height) * 2 + 1), camera);
}
function restPointOf(hit) {  // the hit on the drawn (moved) surface, at rest
  const f = hit.face, p = brain.geometry.getAttribute('position').array;
  const at = (i, a) => new THREE.Vector3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
  const bary = new THREE.Triangle(at(f.a, p), at(f.b, p), at(f.c, p)).getBarycoord(hit.point, new THREE.Vector3());
  const moved = at(f.a, displacement).multiplyScalar(bary.x).add(at(f.b, displacement).multiplyScalar(bary.y))
    .add(at(f.c, displacement).multiplyScalar(bary.z));
  return hit.point.clone().sub(moved);
}
// The scalpel (a cut model): press on the surface, drag, release. The blade's edge runs along the view
// direction from just above the surface point pressed to the depth set; the stroke sweeps it by the
// drag in the view plane. The server removes every tetrahedron the swept surface crosses (a [[cut]]
// in remove mode, docs/simulator.md).
const scalpelBox = document.getElementById('scalpel'), depthInput = document.getElementById('cut-depth');
let stroke = null;  // {edgeFrom, edgeTo, hitPoint, plane, along, line}
function strokeLine(a, b) {
  const g = new THREE.BufferGeometry().setFromPoints([a, b]);
  const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: 0xff5050, depthTest: false }));
  scene.add(line);
  return line;
}
function startStroke(hit) {
  const direction = camera.getWorldDirection(new THREE.Vector3()), restPoint = restPointOf(hit);
  const depth = Math.max(0.5, Number(depthInput.value) || 10);
  stroke = { edgeFrom: restPoint.clone().addScaledVector(direction, -2), edgeTo: restPoint.clone().addScaledVector(direction, depth),
             hitPoint: hit.point.clone(), along: hit.point.clone(),
             plane: new THREE.Plane().setFromNormalAndCoplanarPoint(direction, hit.point), line: strokeLine(hit.point, hit.point) };
}
function endStroke() {
  const move = stroke.along.clone().sub(stroke.hitPoint);
  scene.remove(stroke.line);
  stroke.line.geometry.dispose();
  if (move.length() >= 0.5) sendCut(stroke.edgeFrom.toArray(), stroke.edgeTo.toArray(), move.toArray());
  else note('cut: not sent (drag at least 0.5 mm)');
  stroke = null;
  dirty = true;
}
function sendCut(edgeFrom, edgeTo, move) {
  send('cut', [...edgeFrom, ...edgeTo, ...move]);
}
renderer.domElement.addEventListener('pointerdown', (event) => {
  if (!brain || event.button !== 0) return;
  rayAt(event);
  const hit = raycaster.intersectObject(brain)[0];
  if (!hit) return;
  controls.enabled = false;
  if (scalpelBox.checked) return startStroke(hit);
  const restPoint = restPointOf(hit), normal = camera.getWorldDirection(new THREE.Vector3());
  drag = { restPoint, hitPoint: hit.point.clone(), plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit.point),
           depth: 0, lastY: event.clientY, along: hit.point.clone() };
  send('pick', restPoint.toArray());
});
window.addEventListener('pointermove', (event) => {
  if (stroke) {
    rayAt(event);
    const onPlane = raycaster.ray.intersectPlane(stroke.plane, new THREE.Vector3());
    if (onPlane) stroke.along = onPlane;
    stroke.line.geometry.setFromPoints([stroke.hitPoint, stroke.along]);
    dirty = true;
    return;
  }
  if (!drag) return;
  const view = camera.getWorldDirection(new THREE.Vector3());
  if (event.shiftKey) {  // depth: up moves away from the viewer
    drag.depth += (drag.lastY - event.clientY) * 0.1;
  } else {
    rayAt(event);
    const onPlane = raycaster.ray.intersectPlane(drag.plane, new THREE.Vector3());
    if (onPlane) drag.along = onPlane;
  }
  drag.lastY = event.clientY;
  const target = drag.restPoint.clone().add(drag.along.clone().sub(drag.hitPoint)).add(view.multiplyScalar(drag.depth));
  send('target', target.toArray());
});
window.addEventListener('pointerup', () => {
  if (stroke) {
    controls.enabled = true;
    return endStroke();
  }
  if (!drag) return;
  drag = null;
  controls.enabled = true;
  send('release');
});

// The share of the view's pixels that differ from its empty background, read right after a render
// (the drawing buffer is not kept after it is shown).
live.drawnShare = () => {
  renderer.render(scene, camera);
  const gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const pixels = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const background = [0x15, 0x17, 0x1c];
  let differ = 0;
  for (let i = 0; i < pixels.length; i += 4)
    if (Math.abs(pixels[i] - background[0]) + Math.abs(pixels[i + 1] - background[1]) + Math.abs(pixels[i + 2] - background[2]) > 12) differ += 1;
  return differ / (w * h);
};

live.screenOf = (x, y, z) => {
  const p = new THREE.Vector3(x, y, z).project(camera), r = renderer.domElement.getBoundingClientRect();
  return { x: r.left + ((p.x + 1) / 2) * r.width, y: r.top + ((1 - p.y) / 2) * r.height };
};

// ---- The loop: a frame that came is drawn (nothing else redraws but a turn of the view), then its
// latency is measured. Drawing only what changed leaves a software renderer its time for the frames.
let dirty = true, plotDirty = false;
controls.addEventListener('change', () => { dirty = true; });
window.addEventListener('resize', () => { dirty = true; });
let second = performance.now(), drawnThisSecond = 0;
function animate() {
  requestAnimationFrame(animate);
  const now = performance.now();
  if (pendingFrame) {
    const view = new DataView(pendingFrame);
    const V = view.getUint32(4, true), seq = view.getUint32(8, true);
    if (3 * V === displacement.length) {  // a frame of the surface drawn (not one sent before a new surface)
      displacement.set(new Float32Array(pendingFrame, 24, 3 * V));
      recolour();
      live.frames += 1;
      frameShows = seq;
      dirty = true;
    }
    pendingFrame = null;
  }
  if (plotDirty) {
    drawForcePlot();
    plotDirty = false;
  }
  if (dirty) {
    light.position.copy(camera.position);
    renderer.render(scene, camera);
    live.framesDrawn += 1;
    ++drawnThisSecond;
    dirty = false;
  }
  // Latency: from a target's sending to the first drawn frame that applied it.
  for (const [seq, sent] of sentAt) {
    if (seq > frameShows) continue;
    live.latencies.push(now - sent);
    sentAt.delete(seq);
  }
  if (live.latencies.length > 2000) live.latencies.splice(0, live.latencies.length - 2000);
  if (now - second >= 1000) {
    live.fps = (1000 * drawnThisSecond) / (now - second);
    second = now;
    drawnThisSecond = 0;
    const f = live.state ? live.state.frame : null;
    document.getElementById('display').textContent = `${live.fps.toFixed(0)} frames/s drawn, ${live.frames} from the server` +
      (f ? `; the server builds one in ${f.build_ms.toFixed(2)} ms (the static part's surface: ${f.recovery_ms.toFixed(1)} ms, at most 1/40 of the time)` : '');
  }
}
animate();
