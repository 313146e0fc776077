// INHerit-SG web viewer: map picker, floor tabs with the BEV and object markers, the
// hierarchy tree, and natural-language search with the answer highlighted on the map; a
// 3D view of the same floor (viewer3d.js) is one click away.
"use strict";

const state = {
  map: null, // served map name
  floors: [], // [{id, label, level}]
  floor: null, // floor id shown
  transform: null, // {ox, oy, cell, width, height} of the BEV shown
  objects: new Map(), // object id -> {id, label, position, floor_id}
  result: null, // last query result JSON
  selected: null, // object id picked in the tree
  imageUrls: {}, // slot -> object URL to revoke
  view: "plan", // "plan" (BEV picture) or "3d" (three.js, viewer3d.js)
};

const $ = (id) => document.getElementById(id);

function setStatus(text, isError = false) {
  const el = $("status");
  el.textContent = text;
  el.classList.toggle("error", isError);
}

function authHeaders() {
  const key = $("key-input").value.trim();
  return key ? { Authorization: `Bearer ${key}` } : {};
}

async function apiFetch(path, options = {}) {
  const headers = { ...authHeaders(), ...(options.headers || {}) };
  const resp = await fetch(path, { ...options, headers });
  if (!resp.ok) {
    let message = `${resp.status} ${resp.statusText}`;
    try {
      const body = await resp.json();
      if (body && body.message) message = body.message;
    } catch (_) {
      // not JSON: keep the status line
    }
    throw new Error(message);
  }
  return resp;
}

const api = (path, options) => apiFetch(path, options).then((r) => r.json());
const mapPath = (suffix) => `/v1/maps/${encodeURIComponent(state.map)}${suffix}`;

// Images go through fetch so that the bearer key is sent; shown as object URLs.
async function showImage(slot, img, path) {
  const resp = await apiFetch(path);
  const url = URL.createObjectURL(await resp.blob());
  if (state.imageUrls[slot]) URL.revokeObjectURL(state.imageUrls[slot]);
  state.imageUrls[slot] = url;
  await new Promise((resolve, reject) => {
    img.onload = resolve;
    img.onerror = () => reject(new Error(`cannot show ${path}`));
    img.src = url;
  });
  return resp;
}

// ------------------------------------------------------------------ maps and floors
async function loadMaps() {
  const data = await api("/v1/maps");
  const select = $("map-select");
  select.replaceChildren();
  for (const m of data.maps) {
    const opt = document.createElement("option");
    opt.value = m.name;
    opt.textContent = m.status === "ok" ? m.name : `${m.name} (${m.status})`;
    opt.disabled = m.status !== "ok";
    select.append(opt);
  }
  const first = data.maps.find((m) => m.status === "ok");
  if (!first) {
    setStatus("No map is open on this server.", true);
    return;
  }
  select.value = first.name;
  await openMap(first.name);
}

async function openMap(name) {
  state.map = name;
  state.result = null;
  state.selected = null;
  clearResult();
  setStatus(`Loading ${name}…`);
  const [floors, tree] = await Promise.all([
    api(mapPath("/floors?limit=1000")),
    api(mapPath("/hierarchy")),
  ]);
  state.floors = floors.floors.sort((a, b) => (a.level ?? 0) - (b.level ?? 0));
  renderTabs();
  renderTree(tree);
  if (state.floors.length) await showFloor(state.floors[0].id);
  else setStatus("This map has no floors yet.");
}

function renderTabs() {
  const nav = $("floor-tabs");
  nav.replaceChildren();
  for (const f of state.floors) {
    const b = document.createElement("button");
    b.type = "button";
    b.role = "tab";
    b.dataset.floor = f.id;
    b.textContent = f.label || f.id;
    b.title = `${f.id}: ${f.rooms} rooms, ${f.objects} objects`;
    b.addEventListener("click", () => showFloor(f.id).catch(fail));
    nav.append(b);
  }
}

async function loadObjects(floorId) {
  const out = [];
  for (let offset = 0; ; offset += 1000) {
    const q = `/objects?floor=${encodeURIComponent(floorId)}&limit=1000&offset=${offset}`;
    const page = await api(mapPath(q));
    out.push(...page.objects);
    if (out.length >= page.total || page.objects.length === 0) break;
  }
  return out;
}

async function showFloor(floorId) {
  state.floor = floorId;
  for (const b of $("floor-tabs").children) {
    b.setAttribute("aria-selected", String(b.dataset.floor === floorId));
  }
  const bevPath = mapPath(`/bev.png?floor=${encodeURIComponent(floorId)}`);
  const [resp, objects] = await Promise.all([
    showImage("bev", $("bev-image"), bevPath),
    loadObjects(floorId),
  ]);
  const [ox, oy] = resp.headers.get("X-BEV-Origin").split(",").map(Number);
  const [width, height] = resp.headers.get("X-BEV-Size").split(",").map(Number);
  state.transform = { ox, oy, cell: Number(resp.headers.get("X-BEV-Cell")), width, height };
  state.objects = new Map(objects.map((o) => [o.id, o]));
  fitBev();
  renderMarkers();
  if (state.view === "3d") await show3d();
  setStatus(`${state.map} · ${floorId} · ${objects.length} objects`);
}

// ------------------------------------------------------------------ 3D view
// viewer3d.js is an ES module (loaded after this script): wait for it once.
const view3dReady = new Promise((resolve) => {
  if (window.isg3d) resolve(window.isg3d);
  else document.addEventListener("isg3d:ready", () => resolve(window.isg3d), { once: true });
});

async function show3d() {
  const isg3d = await view3dReady;
  if (!state.floor) return;
  const path = mapPath(`/scene3d?floor=${encodeURIComponent(state.floor)}`);
  const drawn = await isg3d.show(() => api(path));
  if (!drawn) setStatus(isg3d.info().error, true);
  sync3d();
}

// Tell the 3D view what the plan shows: the answer, the candidates, the selection.
function sync3d() {
  if (!window.isg3d || state.view !== "3d") return;
  const answerId = state.result && state.result.answer ? state.result.answer.id : null;
  const candidateIds = state.result ? state.result.candidates.map((c) => c.id) : [];
  window.isg3d.highlight(answerId, candidateIds);
  window.isg3d.select(state.selected);
}

async function setView(name) {
  state.view = name;
  for (const b of $("view-switch").children) {
    b.setAttribute("aria-pressed", String(b.dataset.view === name));
  }
  $("bev-wrap").hidden = name !== "plan";
  $("view3d").hidden = name !== "3d";
  if (name === "3d") await show3d();
  else fitBev();
}

// Fit the BEV into the map panel (markers are placed in % of the picture, so they follow).
function fitBev() {
  const tf = state.transform;
  if (!tf) return;
  const panel = $("map-panel");
  const room = panel.clientWidth - 24;
  const tall = panel.clientHeight - $("floor-tabs").offsetHeight - 72;
  const scale = Math.max(0.1, Math.min(room / tf.width, tall / tf.height, 3));
  $("bev-image").style.width = `${Math.floor(tf.width * scale)}px`;
}

// ------------------------------------------------------------------ markers
function renderMarkers() {
  const layer = $("markers");
  layer.replaceChildren();
  const tf = state.transform;
  if (!tf) return;
  const answerId = state.result && state.result.answer ? state.result.answer.id : null;
  const candidateIds = new Set(
    state.result ? state.result.candidates.map((c) => c.id).filter((id) => id !== answerId) : [],
  );
  // the answer and the candidates may carry positions the listing lacks (e.g. rooms)
  const shown = new Map(state.objects);
  if (state.result) {
    for (const c of [state.result.answer, ...state.result.candidates]) {
      if (c && c.position && c.floor_id === state.floor && !shown.has(c.id)) shown.set(c.id, c);
    }
  }
  for (const node of shown.values()) {
    if (!node.position) continue;
    const col = (node.position[0] - tf.ox) / tf.cell;
    const row = (tf.oy - node.position[1]) / tf.cell;
    const m = document.createElement("button");
    m.type = "button";
    m.className = "marker";
    if (node.id === answerId) m.classList.add("answer");
    else if (candidateIds.has(node.id)) m.classList.add("candidate");
    if (node.id === state.selected) m.classList.add("selected");
    m.dataset.id = node.id;
    m.title = `${node.label} (${node.id})`;
    m.style.left = `${(100 * col) / tf.width}%`;
    m.style.top = `${(100 * row) / tf.height}%`;
    m.addEventListener("click", () => selectNode(node.id).catch(fail));
    layer.append(m);
  }
  sync3d();
}

// ------------------------------------------------------------------ hierarchy tree
function treeLabel(node) {
  const frag = document.createDocumentFragment();
  frag.append(node.label || node.layer);
  const id = document.createElement("span");
  id.className = "id";
  id.textContent = node.id;
  frag.append(id);
  return frag;
}

function treeNode(node, open) {
  if (!node.children.length) {
    const leaf = document.createElement("div");
    leaf.className = "leaf";
    leaf.dataset.id = node.id;
    leaf.dataset.layer = node.layer;
    leaf.append(treeLabel(node));
    leaf.addEventListener("click", () => selectNode(node.id).catch(fail));
    return leaf;
  }
  const det = document.createElement("details");
  det.open = open;
  det.dataset.id = node.id;
  const sum = document.createElement("summary");
  sum.dataset.id = node.id;
  sum.append(treeLabel(node));
  det.append(sum);
  for (const child of node.children) det.append(treeNode(child, false));
  return det;
}

function renderTree(tree) {
  const root = $("tree");
  root.replaceChildren();
  for (const floor of tree.floors) root.append(treeNode(floor, true));
  if (tree.unassigned.length) {
    root.append(treeNode({ id: "", label: "unassigned", layer: "group", children: tree.unassigned }, false));
  }
}

function markTree(id) {
  for (const el of document.querySelectorAll("#tree .selected")) el.classList.remove("selected");
  const el = document.querySelector(`#tree .leaf[data-id="${CSS.escape(id)}"], #tree summary[data-id="${CSS.escape(id)}"]`);
  if (!el) return;
  el.classList.add("selected");
  for (let p = el.parentElement; p && p.id !== "tree"; p = p.parentElement) {
    if (p.tagName === "DETAILS") p.open = true;
  }
  el.scrollIntoView({ block: "nearest" });
}

async function selectNode(id) {
  state.selected = id;
  markTree(id);
  if (id.startsWith("obj:") || state.objects.has(id)) {
    const detail = await api(mapPath(`/objects/${encodeURIComponent(id)}`));
    if (detail.floor_id && detail.floor_id !== state.floor) await showFloor(detail.floor_id);
    else renderMarkers();
    await showView(id, `${detail.label} (${id})`);
  }
}

// ------------------------------------------------------------------ search
function clearResult() {
  $("answer").textContent = "No query yet.";
  $("answer").dataset.id = "";
  $("candidates").replaceChildren();
  $("trace").replaceChildren();
  $("view-figure").hidden = true;
}

async function showView(nodeId, caption) {
  const fig = $("view-figure");
  try {
    const resp = await showImage("view", $("view-image"), mapPath(`/nodes/${encodeURIComponent(nodeId)}/view.jpg`));
    $("view-caption").textContent = `${caption} · best view ${resp.headers.get("X-Keyframe-Id")}`;
    fig.hidden = false;
  } catch (err) {
    $("view-caption").textContent = `${caption}: no keyframe (${err.message})`;
    fig.hidden = false;
  }
}

function renderResult(result) {
  const ans = $("answer");
  ans.replaceChildren();
  const a = result.answer;
  ans.dataset.id = a ? a.id : "";
  if (a) {
    ans.append(`${a.label} (${a.id})`);
    const meta = document.createElement("span");
    meta.className = "meta";
    const where = [a.room, a.floor_id].filter(Boolean).join(", ");
    meta.textContent = `${where} · score ${a.score}`;
    ans.append(meta);
  } else {
    ans.textContent = "No answer.";
  }
  const list = $("candidates");
  list.replaceChildren();
  for (const c of result.candidates) {
    const li = document.createElement("li");
    li.dataset.id = c.id;
    li.textContent = `${c.label} (${c.id}) ${c.room ? `in ${c.room}` : ""} · ${c.score}`;
    li.addEventListener("click", () => selectNode(c.id).catch(fail));
    list.append(li);
  }
  const trace = $("trace");
  trace.replaceChildren();
  for (const step of result.trace) {
    const li = document.createElement("li");
    li.textContent = step;
    trace.append(li);
  }
}

async function runQuery(text) {
  setStatus(`Searching: ${text}`);
  const result = await api(mapPath("/query"), {
    method: "POST",
    headers: { "Content-Type": "application/json" },
    body: JSON.stringify({ text }),
  });
  state.result = result;
  state.selected = null;
  renderResult(result);
  const a = result.answer;
  if (a && a.floor_id && a.floor_id !== state.floor) await showFloor(a.floor_id);
  else renderMarkers();
  if (a) {
    markTree(a.id);
    await showView(a.id, `${a.label} (${a.id})`);
  }
  setStatus(a ? `Answer: ${a.label} (${a.id})` : "No answer found.");
}

function fail(err) {
  setStatus(err.message || String(err), true);
}

// ------------------------------------------------------------------ wiring
function init() {
  const keyInput = $("key-input");
  keyInput.value = sessionStorage.getItem("inherit-sg-key") || "";
  keyInput.addEventListener("change", () => {
    sessionStorage.setItem("inherit-sg-key", keyInput.value.trim());
    loadMaps().catch(fail);
  });
  $("map-select").addEventListener("change", (e) => openMap(e.target.value).catch(fail));
  $("query-form").addEventListener("submit", (e) => {
    e.preventDefault();
    const text = $("query-input").value.trim();
    if (text && state.map) runQuery(text).catch(fail);
  });
  window.addEventListener("resize", fitBev);
  for (const b of $("view-switch").children) {
    b.addEventListener("click", () => setView(b.dataset.view).catch(fail));
  }
  document.addEventListener("isg3d:pick", (e) => selectNode(e.detail.id).catch(fail));
  loadMaps().catch(fail);
}

document.addEventListener("DOMContentLoaded", init);
