// INHerit-SG viewer, 3D view: room footprints, object boxes coloured by room and the
// graph's edges (object relations, room connections) of one floor, drawn with three.js
// (vendored under /static/vendor/three). The search answer is red with a pointer above
// it, the other candidates orange. viewer.js drives it through window.isg3d.
import * as THREE from "three";
import { OrbitControls } from "three/addons/controls/OrbitControls.js";

const PALETTE = [0x7fb3d5, 0xf5b7b1, 0x82e0aa, 0xd7bde2, 0xf8c471, 0x76d7c4, 0xf1948a, 0xaab7b8];
const ANSWER = 0xd62828;
const CANDIDATE = 0xf0a020;
const SELECTED = 0x2aa876;
const RELATION = 0x556070;
const CONNECTION = 0x1e7d4f;

const view = {
  renderer: null,
  scene: null,
  camera: null,
  controls: null,
  root: null, // THREE.Group of the shown floor
  boxes: new Map(), // object id -> {mesh, edges, colour, object}
  marker: null, // pointer above the answer
  data: null, // the /scene3d JSON shown
  answer: null,
  candidates: [],
  selected: null,
  frames: 0,
  webgl: false,
  error: null,
};

const $ = (id) => document.getElementById(id);

function webglAvailable() {
  try {
    const probe = document.createElement("canvas");
    return Boolean(probe.getContext("webgl2") || probe.getContext("webgl"));
  } catch (_) {
    return false;
  }
}

function setup() {
  if (view.renderer || view.error) return Boolean(view.renderer);
  if (!webglAvailable()) {
    view.error = "WebGL is not available in this browser: the 3D view cannot be drawn.";
    $("view3d-note").textContent = view.error;
    return false;
  }
  const canvas = $("canvas3d");
  view.renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  view.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  view.renderer.setClearColor(0xf4f5f7);
  view.webgl = true;
  view.scene = new THREE.Scene();
  view.camera = new THREE.PerspectiveCamera(45, 1, 0.05, 500);
  view.camera.up.set(0, 0, 1); // the map is z-up
  view.scene.add(new THREE.AmbientLight(0xffffff, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.4);
  sun.position.set(-3, -5, 10);
  view.scene.add(sun);
  view.controls = new OrbitControls(view.camera, canvas);
  view.controls.addEventListener("change", render);
  canvas.addEventListener("click", pick);
  canvas.addEventListener("pointermove", hover);
  new ResizeObserver(resize).observe($("view3d"));
  resize();
  return true;
}

function resize() {
  if (!view.renderer) return;
  const wrap = $("view3d");
  const width = Math.max(200, wrap.clientWidth);
  const height = Math.max(200, wrap.clientHeight - $("view3d-note").offsetHeight);
  view.renderer.setSize(width, height, false);
  view.camera.aspect = width / height;
  view.camera.updateProjectionMatrix();
  render();
}

function render() {
  if (!view.renderer) return;
  view.renderer.render(view.scene, view.camera);
  view.frames += 1;
}

function dispose(group) {
  group.traverse((node) => {
    if (node.geometry) node.geometry.dispose();
    if (node.material) {
      if (node.material.map) node.material.map.dispose();
      node.material.dispose();
    }
  });
}

// ------------------------------------------------------------------ drawing
function roomColours(rooms) {
  const out = new Map();
  rooms.forEach((r, i) => out.set(r.id, PALETTE[i % PALETTE.length]));
  return out;
}

function footprint(room, z, colour) {
  const group = new THREE.Group();
  for (const outline of room.outlines) {
    const shape = new THREE.Shape(outline.map(([x, y]) => new THREE.Vector2(x, y)));
    const fill = new THREE.Mesh(
      new THREE.ShapeGeometry(shape),
      new THREE.MeshBasicMaterial({
        color: colour, transparent: true, opacity: 0.35, side: THREE.DoubleSide, depthWrite: false,
      }),
    );
    fill.position.z = z;
    const points = outline.map(([x, y]) => new THREE.Vector3(x, y, z + 0.01));
    const line = new THREE.LineLoop(
      new THREE.BufferGeometry().setFromPoints(points),
      new THREE.LineBasicMaterial({ color: 0x5a5a5a }),
    );
    group.add(fill, line);
  }
  return group;
}

function textSprite(text, z, at) {
  const canvas = document.createElement("canvas");
  const ctx = canvas.getContext("2d");
  const font = "bold 36px system-ui, sans-serif";
  ctx.font = font;
  canvas.width = Math.ceil(ctx.measureText(text).width) + 24;
  canvas.height = 52;
  ctx.font = font;
  ctx.fillStyle = "rgba(255,255,255,0.85)";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#24323f";
  ctx.textBaseline = "middle";
  ctx.fillText(text, 12, canvas.height / 2);
  const sprite = new THREE.Sprite(
    new THREE.SpriteMaterial({ map: new THREE.CanvasTexture(canvas), depthTest: false }),
  );
  const h = 0.35;
  sprite.scale.set((h * canvas.width) / canvas.height, h, 1);
  sprite.position.set(at[0], at[1], z);
  sprite.renderOrder = 10;
  return sprite;
}

function centre(o) {
  return new THREE.Vector3(
    (o.bbox_min[0] + o.bbox_max[0]) / 2,
    (o.bbox_min[1] + o.bbox_max[1]) / 2,
    (o.bbox_min[2] + o.bbox_max[2]) / 2,
  );
}

function box(o, colour) {
  const size = [0, 1, 2].map((k) => Math.max(0.02, o.bbox_max[k] - o.bbox_min[k]));
  const geometry = new THREE.BoxGeometry(size[0], size[1], size[2]);
  const mesh = new THREE.Mesh(
    geometry,
    new THREE.MeshLambertMaterial({ color: colour, transparent: true, opacity: 0.8 }),
  );
  mesh.position.copy(centre(o));
  mesh.userData.id = o.id;
  const edges = new THREE.LineSegments(
    new THREE.EdgesGeometry(geometry),
    new THREE.LineBasicMaterial({ color: 0x33404d }),
  );
  edges.position.copy(mesh.position);
  return { mesh, edges };
}

function segments(pairs, colour, opacity) {
  const points = pairs.flat();
  const lines = new THREE.LineSegments(
    new THREE.BufferGeometry().setFromPoints(points),
    new THREE.LineBasicMaterial({ color: colour, transparent: true, opacity }),
  );
  return lines;
}

function build(data) {
  if (view.root) {
    view.scene.remove(view.root);
    dispose(view.root);
  }
  view.root = new THREE.Group();
  view.boxes.clear();
  view.marker = null;
  const colours = roomColours(data.rooms);
  const floorZ = new Map(data.floors.map((f) => [f.id, f.z_min ?? 0]));
  for (const room of data.rooms) {
    const z = floorZ.get(room.floor_id) ?? 0;
    view.root.add(footprint(room, z, colours.get(room.id)));
    if (room.position) view.root.add(textSprite(room.label || room.id, z + 0.05, room.position));
  }
  const byId = new Map();
  for (const o of data.objects) {
    const colour = colours.get(o.room_id) ?? 0x9aa5b1;
    const { mesh, edges } = box(o, colour);
    view.boxes.set(o.id, { mesh, edges, colour, object: o });
    byId.set(o.id, o);
    view.root.add(mesh, edges);
  }
  const relationPairs = data.relations
    .filter((r) => byId.has(r.source) && byId.has(r.target))
    .map((r) => [centre(byId.get(r.source)), centre(byId.get(r.target))]);
  if (relationPairs.length) view.root.add(segments(relationPairs, RELATION, 0.45));
  const roomAt = new Map(data.rooms.map((r) => [r.id, r]));
  const connectionPairs = [];
  for (const c of data.connections) {
    const a = roomAt.get(c.source);
    const b = roomAt.get(c.target);
    if (!a || !a.position || !b || !b.position) continue;
    const z = (floorZ.get(a.floor_id) ?? 0) + 0.05;
    const p = new THREE.Vector3(a.position[0], a.position[1], z);
    const q = new THREE.Vector3(b.position[0], b.position[1], z);
    if (c.door) {
      const d = new THREE.Vector3(c.door[0], c.door[1], z);
      connectionPairs.push([p, d], [d, q]);
    } else {
      connectionPairs.push([p, q]);
    }
  }
  if (connectionPairs.length) view.root.add(segments(connectionPairs, CONNECTION, 0.9));
  view.scene.add(view.root);
  frame();
}

// Look at the whole floor from the south-west, above.
function frame() {
  const bounds = new THREE.Box3().setFromObject(view.root);
  if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
  const c = bounds.getCenter(new THREE.Vector3());
  const size = bounds.getSize(new THREE.Vector3());
  const d = Math.max(size.x, size.y, 2) * 1.05;
  view.camera.position.set(c.x - 0.3 * d, c.y - 0.9 * d, c.z + 1.1 * d);
  view.controls.target.copy(c);
  view.controls.update();
  render();
}

// ------------------------------------------------------------------ highlighting
function paint() {
  const candidates = new Set(view.candidates);
  const anyResult = Boolean(view.answer) || candidates.size > 0;
  for (const [id, entry] of view.boxes) {
    let colour = entry.colour;
    let opacity = anyResult ? 0.35 : 0.8;
    if (id === view.answer) [colour, opacity] = [ANSWER, 1.0];
    else if (id === view.selected) [colour, opacity] = [SELECTED, 1.0];
    else if (candidates.has(id)) [colour, opacity] = [CANDIDATE, 0.95];
    entry.mesh.material.color.setHex(colour);
    entry.mesh.material.opacity = opacity;
  }
  if (view.marker) {
    view.root.remove(view.marker);
    dispose(view.marker);
    view.marker = null;
  }
  const target = view.boxes.get(view.answer);
  if (target) {
    const top = target.object.bbox_max[2];
    const cone = new THREE.Mesh(
      new THREE.ConeGeometry(0.15, 0.4, 16),
      new THREE.MeshLambertMaterial({ color: ANSWER }),
    );
    cone.rotation.x = -Math.PI / 2; // point down (-z)
    const c = centre(target.object);
    cone.position.set(c.x, c.y, top + 0.45);
    view.marker = cone;
    view.root.add(cone);
  }
  render();
}

function highlight(answerId, candidateIds) {
  view.answer = answerId || null;
  view.candidates = (candidateIds || []).filter((id) => id !== view.answer);
  if (view.root) paint();
}

function select(id) {
  view.selected = id || null;
  if (view.root) paint();
}

// ------------------------------------------------------------------ picking
function hitAt(event) {
  const rect = view.renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(
    ((event.clientX - rect.left) / rect.width) * 2 - 1,
    -((event.clientY - rect.top) / rect.height) * 2 + 1,
  );
  const ray = new THREE.Raycaster();
  ray.setFromCamera(ndc, view.camera);
  const meshes = [...view.boxes.values()].map((b) => b.mesh);
  const hit = ray.intersectObjects(meshes, false)[0];
  return hit ? view.boxes.get(hit.object.userData.id).object : null;
}

function hover(event) {
  if (!view.root) return;
  const o = hitAt(event);
  $("view3d-note").textContent = o ? `${o.label} (${o.id})` : note();
}

function pick(event) {
  if (!view.root) return;
  const o = hitAt(event);
  if (o) document.dispatchEvent(new CustomEvent("isg3d:pick", { detail: { id: o.id } }));
}

function note() {
  const d = view.data;
  if (!d) return "";
  return `${d.objects.length} objects in ${d.rooms.length} rooms · ${d.relations.length} relations · drag to turn, scroll to zoom, click a box to select it`;
}

// ------------------------------------------------------------------ entry points
// Draw the scene that ``load`` (a function returning the /scene3d JSON) gives.
async function show(load) {
  if (!setup()) return false;
  const data = await load();
  view.data = data;
  build(data);
  paint();
  $("view3d-note").textContent = note();
  return true;
}

// What is drawn, for tests and for the curious (window.isg3d.info() in the console).
function info() {
  return {
    webgl: view.webgl,
    error: view.error,
    objects: view.boxes.size,
    rooms: view.data ? view.data.rooms.length : 0,
    relations: view.data ? view.data.relations.length : 0,
    answer: view.answer,
    candidates: [...view.candidates],
    selected: view.selected,
    frames: view.frames,
    drawCalls: view.renderer ? view.renderer.info.render.calls : 0,
  };
}

window.isg3d = { show, highlight, select, resize, info };
document.dispatchEvent(new Event("isg3d:ready"));
