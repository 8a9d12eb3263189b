// graspcd's trajectory viewer: plays a grasp recorded by `graspcd study` or
// `graspcd trajectory` (src/graspcd/study/trajectory.h has the file format) with three.js.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const grasps = JSON.parse(document.getElementById('trajectories').textContent);
const $ = (id) => document.getElementById(id);
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
scene.add(new THREE.HemisphereLight(0xffffff, 0x666666, 2.0));
const sun = new THREE.DirectionalLight(0xffffff, 1.5);
sun.position.set(1, -1, 2);
scene.add(sun);
THREE.Object3D.DEFAULT_UP.set(0, 0, 1);  // MuJoCo's z is up
const camera = new THREE.PerspectiveCamera(40, 1, 0.005, 20);
camera.up.set(0, 0, 1);
const controls = new OrbitControls(camera, canvas);
controls.addEventListener('change', () => render());

const COLORS = {
  segment: 0xc8a878, touching: 0xe03030, object: 0x7090c0, objectTouched: 0x40a040, hand: 0x999999,
};
const METHOD_COLORS = ['#1f77b4', '#ff7f0e', '#2ca02c', '#d62728', '#9467bd', '#8c564b', '#e377c2',
  '#7f7f7f', '#bcbd22', '#17becf'];

let grasp = null;  // the shown trajectory
let root = null;   // its scene objects
let geomObjects = [];
let obbGroups = [[], [], [], []];
let contactGroups = { ours: null, native: null };
let step = 0;
let timer = null;

// MuJoCo's geom frame: position and row-major rotation of step s, geom g.
function setPose(obj, s, g) {
  const p = grasp.steps[s].pos;
  const r = grasp.steps[s].rot;
  const i = 9 * g;
  obj.matrix.set(r[i], r[i + 1], r[i + 2], p[3 * g],
    r[i + 3], r[i + 4], r[i + 5], p[3 * g + 1],
    r[i + 6], r[i + 7], r[i + 8], p[3 * g + 2],
    0, 0, 0, 1);
  obj.matrixWorldNeedsUpdate = true;
}

function meshGeometry(mesh) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(mesh.vertices, 3));
  geometry.setIndex(mesh.faces);
  geometry.computeVertexNormals();
  return geometry;
}

// The shape of a geom in its own frame (MuJoCo's sizes: half-extents, radius and half-length
// along z).
function geomShape(geom, meshGeometries) {
  const [a, b, c] = geom.size;
  switch (geom.type) {
    case 'mesh': return meshGeometries[geom.mesh];
    case 'box': return new THREE.BoxGeometry(2 * a, 2 * b, 2 * c);
    case 'sphere': return new THREE.SphereGeometry(a, 24, 12);
    case 'ellipsoid': return new THREE.SphereGeometry(1, 24, 12).scale(a, b, c);
    case 'capsule': return new THREE.CapsuleGeometry(a, 2 * b, 8, 16).rotateX(Math.PI / 2);
    case 'cylinder': return new THREE.CylinderGeometry(a, a, 2 * b, 24).rotateX(Math.PI / 2);
    default: return null;
  }
}

function obbLines(box, material) {
  const [hx, hy, hz] = box.half;
  const lines = new THREE.LineSegments(
    new THREE.EdgesGeometry(new THREE.BoxGeometry(2 * hx, 2 * hy, 2 * hz)), material);
  const r = box.axes;
  const c = box.center;
  lines.matrixAutoUpdate = false;
  lines.matrix.set(r[0], r[1], r[2], c[0], r[3], r[4], r[5], c[1], r[6], r[7], r[8], c[2], 0, 0, 0, 1);
  return lines;
}

function buildScene(g) {
  if (root) scene.remove(root);
  grasp = grasps[g];
  root = new THREE.Group();
  const meshGeometries = grasp.meshes.map(meshGeometry);
  const levelMaterials = [0x000000, 0xd02090, 0x2080d0, 0x20a040].map(
    (color) => new THREE.LineBasicMaterial({ color }));
  obbGroups = [[], [], [], []];
  geomObjects = grasp.geoms.map((geom, gi) => {
    const obj = new THREE.Group();
    obj.matrixAutoUpdate = false;
    const shape = geomShape(geom, meshGeometries);
    const material = new THREE.MeshStandardMaterial({
      color: COLORS[geom.role] ?? COLORS.hand, roughness: 0.8, metalness: 0.0,
      transparent: geom.role === 'object', opacity: geom.role === 'object' ? 0.75 : 1.0,
      side: THREE.DoubleSide,
    });
    if (shape) obj.add(new THREE.Mesh(shape, material));
    obj.userData = { geom, material, index: gi };
    // The OBB tree's boxes, in the geom frame, one group per depth.
    const levels = geom.type === 'mesh' ? grasp.meshes[geom.mesh].obb_levels : undefined;
    if (levels && geom.role === 'segment') {
      levels.forEach((boxes, depth) => {
        const group = new THREE.Group();
        boxes.forEach((box) => group.add(obbLines(box, levelMaterials[depth])));
        group.visible = isObbLevelOn(depth);
        obj.add(group);
        obbGroups[depth].push(group);
      });
    }
    root.add(obj);
    return obj;
  });
  contactGroups = { ours: new THREE.Group(), native: new THREE.Group() };
  root.add(contactGroups.ours, contactGroups.native);
  scene.add(root);
  const slider = $('step');
  slider.max = String(grasp.steps.length - 1);
  // Frame the object and the finger segments at step 0 (not the rest of the hand or the support).
  setStep(0);
  const bounds = new THREE.Box3();
  geomObjects.forEach((o) => {
    if (o.userData.geom.role !== 'hand' && o.userData.geom.role !== 'support') {
      bounds.expandByObject(o);
    }
  });
  const center = bounds.getCenter(new THREE.Vector3());
  const size = bounds.getSize(new THREE.Vector3()).length();
  camera.position.copy(center).add(new THREE.Vector3(0.8 * size, -1.1 * size, 0.6 * size));
  controls.target.copy(center);
  controls.update();
  drawPlot();
  showInfo();
  render();
}

function isObbLevelOn(depth) {
  return document.querySelector(`.obb[data-level="${depth}"]`).checked;
}

function contactObjects(contacts, color) {
  const group = new THREE.Group();
  if (contacts.length === 0) return group;
  const points = [];
  const normals = [];
  const scale = 0.015;  // normal length drawn, m
  for (const c of contacts) {
    points.push(...c.pos);
    normals.push(...c.pos, c.pos[0] + scale * c.normal[0], c.pos[1] + scale * c.normal[1],
      c.pos[2] + scale * c.normal[2]);
  }
  const pointGeometry = new THREE.BufferGeometry();
  pointGeometry.setAttribute('position', new THREE.Float32BufferAttribute(points, 3));
  group.add(new THREE.Points(pointGeometry,
    new THREE.PointsMaterial({ color, size: 7, sizeAttenuation: false, depthTest: false })));
  const lineGeometry = new THREE.BufferGeometry();
  lineGeometry.setAttribute('position', new THREE.Float32BufferAttribute(normals, 3));
  group.add(new THREE.LineSegments(lineGeometry,
    new THREE.LineBasicMaterial({ color, depthTest: false })));
  group.renderOrder = 1;
  return group;
}

function setStep(s) {
  step = Math.max(0, Math.min(grasp.steps.length - 1, s));
  $('step').value = String(step);
  const data = grasp.steps[step];
  // Geoms in one of our contacts at this step: the colliding pairs.
  const touching = new Set();
  data.contacts.forEach((c) => c.geoms.forEach((g) => touching.add(g)));
  geomObjects.forEach((obj, g) => {
    setPose(obj, step, g);
    const { geom, material } = obj.userData;
    const base = COLORS[geom.role] ?? COLORS.hand;
    const hit = touching.has(g);
    material.color.setHex(hit ? (geom.role === 'object' ? COLORS.objectTouched : COLORS.touching) : base);
  });
  for (const [key, color] of [['ours', 0xe00000], ['native', 0x0030e0]]) {
    const group = contactGroups[key];
    group.clear();
    group.add(contactObjects(key === 'ours' ? data.contacts : data.native_contacts, color));
    group.visible = $(key).checked;
  }
  $('stepLabel').textContent = `${step + 1} / ${grasp.steps.length}: ${data.contacts.length} ` +
    `contacts (native ${data.native_contacts.length})`;
  drawPlot();
  render();
}

function render() {
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(1, h);
    camera.updateProjectionMatrix();
  }
  renderer.render(scene, camera);
}

// Detection time per grasp step, one line per method, and the current step.
function drawPlot() {
  const plot = $('plot');
  const ctx = plot.getContext('2d');
  plot.width = plot.clientWidth;
  plot.height = plot.clientHeight;
  const W = plot.width;
  const H = plot.height;
  const pad = { l: 56, r: 10, t: 10, b: 30 };
  ctx.clearRect(0, 0, W, H);
  const methods = Object.entries(grasp.times_ns ?? {});
  const legend = $('legend');
  legend.innerHTML = '';
  if (methods.length === 0) {
    ctx.fillText('no detection times in this trajectory', pad.l, H / 2);
    return;
  }
  const n = grasp.steps.length;
  const all = methods.flatMap(([, ns]) => ns).map((v) => v / 1e6).filter((v) => v > 0);
  const maxMs = Math.max(...all, 1e-3);
  // Log scale (default): the methods differ by orders of magnitude.
  const log = $('logScale').checked;
  const minMs = log ? Math.max(Math.min(...all, maxMs) / 1.5, maxMs * 1e-6) : 0;
  const frac = log
    ? (ms) => (Math.log10(Math.max(ms, minMs)) - Math.log10(minMs)) / (Math.log10(maxMs) - Math.log10(minMs) || 1)
    : (ms) => ms / maxMs;
  const x = (i) => pad.l + (W - pad.l - pad.r) * (n > 1 ? i / (n - 1) : 0);
  const y = (ms) => H - pad.b - (H - pad.t - pad.b) * frac(ms);
  ctx.strokeStyle = '#000';
  ctx.strokeRect(pad.l, pad.t, W - pad.l - pad.r, H - pad.t - pad.b);
  ctx.fillStyle = '#000';
  ctx.font = '11px sans-serif';
  for (let k = 0; k <= 4; ++k) {
    const ms = log ? minMs * (maxMs / minMs) ** (k / 4) : (maxMs * k) / 4;
    ctx.fillText(ms < 0.1 ? ms.toPrecision(2) : ms.toFixed(2), 4, y(ms) + 4);
  }
  ctx.fillText('ms', pad.l + 4, pad.t + 12);
  ctx.fillText('grasp step', W / 2 - 25, H - 8);
  methods.forEach(([name, ns], k) => {
    const color = METHOD_COLORS[k % METHOD_COLORS.length];
    ctx.strokeStyle = color;
    ctx.beginPath();
    ns.forEach((v, i) => (i === 0 ? ctx.moveTo(x(i), y(v / 1e6)) : ctx.lineTo(x(i), y(v / 1e6))));
    ctx.stroke();
    const item = document.createElement('span');
    item.style.color = color;
    item.textContent = `${name}: ${(ns[step] / 1e6).toFixed(3)} ms `;
    legend.appendChild(item);
  });
  ctx.strokeStyle = '#888';
  ctx.beginPath();
  ctx.moveTo(x(step), pad.t);
  ctx.lineTo(x(step), H - pad.b);
  ctx.stroke();
}

function showInfo() {
  const first = grasp.first_contact
    .map((s, i) => (s > 0 ? `${grasp.segment_names[i]}: step ${s}` : null)).filter(Boolean);
  $('info').textContent = `${grasp.name} (${grasp.scene})\nrecorded with ${grasp.recorded_with}, ` +
    `${grasp.grasp_steps} closing grasp steps, ${grasp.held ? 'held' : 'not held'}\n` +
    `first contact: ${first.join(', ') || 'none'}`;
}

// Controls.
grasps.forEach((g, i) => $('grasp').add(new Option(g.name, String(i))));
$('grasp').addEventListener('change', (e) => buildScene(Number(e.target.value)));
$('step').addEventListener('input', (e) => setStep(Number(e.target.value)));
$('ours').addEventListener('change', () => setStep(step));
$('native').addEventListener('change', () => setStep(step));
document.querySelectorAll('.obb').forEach((box) => box.addEventListener('change', () => {
  obbGroups.forEach((groups, depth) => groups.forEach((g) => { g.visible = isObbLevelOn(depth); }));
  render();
}));
$('play').addEventListener('click', () => {
  if (timer) {
    clearInterval(timer);
    timer = null;
    $('play').textContent = 'play';
    return;
  }
  if (step >= grasp.steps.length - 1) setStep(0);
  $('play').textContent = 'pause';
  timer = setInterval(() => {
    if (step >= grasp.steps.length - 1) { $('play').click(); return; }
    setStep(step + 1);
  }, 60);
});
$('logScale').addEventListener('change', drawPlot);
window.addEventListener('resize', () => { drawPlot(); render(); });
buildScene(0);
document.body.dataset.ready = '1';
