// The explorable page: the Compare view. Every image comes from the
// hider-web WebAssembly module (the project's crates); this file only
// draws buffers, handles input and times calls.
import init, { Page } from "./pkg/hider_web.js";
import { drawChart } from "./chart.js";
import { buildSteps } from "./steps.js";
import { buildInspect } from "./inspect.js";
import { buildPrecision } from "./precision.js";
import { buildYBuffer } from "./ybuffer.js";

const $ = (id) => document.getElementById(id);
const status = (text, error = false) => {
  $("status").textContent = text;
  $("status").classList.toggle("error", error);
};

// The bundled models: fetched from assets/ (copied there by build.sh) and
// loaded through the same path as a dropped file.
const BUNDLED = {
  spider: ["spider/spider.obj", "spider/spider.mtl", "spider/SpiderTex.jpg", "spider/drkwood2.jpg",
           "spider/engineflare1.jpg", "spider/wal67ar_small.jpg", "spider/wal69ar_small.jpg"],
  cube: ["cube.obj", "cube.mtl"],
  intersecting: ["intersecting.obj", "intersecting.mtl"],
  cyclic: ["cyclic.obj", "cyclic.mtl"],
  coplanar: ["coplanar.obj", "coplanar.mtl"],
  sphere: ["sphere.obj", "sphere.mtl"],
  checker_plane: ["checker_plane.obj", "checker_plane.mtl", "checker.png"],
};

const state = {
  page: null,
  hiders: [],
  orbit: { yaw: 0, pitch: 0, zoom: 0, panX: 0, panY: 0 },
  size: 256,
  main: "zbuffer",
  results: new Map(), // hider -> { frame data, time, score }
  generation: 0, // bumps on every view change: stale grid work stops
  frameTimes: [],
};

function blit(canvas, rgba, size, map = null) {
  canvas.width = size;
  canvas.height = size;
  const data = new Uint8ClampedArray(rgba);
  if (map) {
    for (let k = 0; k < map.length; k++) {
      if (map[k]) { data[4 * k] = 255; data[4 * k + 1] = 0; data[4 * k + 2] = 0; data[4 * k + 3] = 255; }
    }
  }
  canvas.getContext("2d").putImageData(new ImageData(data, size, size), 0, 0);
}

function applyOrbit() {
  const o = state.orbit;
  state.page.set_orbit(o.yaw, o.pitch, o.zoom, o.panX, o.panY);
}

// One hider's frame with its time (the wasm call, measured in the page).
function renderTimed(name) {
  const t0 = performance.now();
  const frame = state.page.render(name);
  const ms = performance.now() - t0;
  return { frame, ms };
}

function renderMain() {
  applyOrbit();
  const { frame, ms } = renderTimed(state.main);
  state.frameTimes.push(ms);
  if (state.frameTimes.length > 30) state.frameTimes.shift();
  const mean = state.frameTimes.reduce((a, b) => a + b, 0) / state.frameTimes.length;
  let map = null;
  const known = state.results.get(state.main);
  if ($("overlay").checked && known && known.map) map = known.map;
  blit($("view"), frame.rgba(), state.size, map);
  $("frame-time").textContent =
    `${state.main}: ${ms.toFixed(1)} ms this frame, ${mean.toFixed(1)} ms mean of ${state.frameTimes.length} ` +
    `(${(1000 / mean).toFixed(0)} frames/s) · ${state.page.triangles()} triangles`;
  frame.free();
}

// The grid: every hider, one per task so the page stays responsive; the
// oracle's ids are computed once per view by the first score.
let gridTimer = null;
let steps = null;
let extras = null; // the inspector, depth-precision and Y-buffer views
function scheduleGrid() {
  clearTimeout(gridTimer);
  state.generation++;
  state.results.clear();
  for (const cell of document.querySelectorAll(".cell")) cell.classList.add("pending");
  const generation = state.generation;
  gridTimer = setTimeout(() => renderGrid(generation), 150);
}

function renderGrid(generation) {
  const queue = [...state.hiders];
  const step = () => {
    if (generation !== state.generation) return;
    const name = queue.shift();
    if (name === undefined) {
      status(`${state.hiders.length} hiders rendered`);
      document.body.dataset.gridDone = String(generation);
      if ($("overlay").checked) renderMain();
      return;
    }
    status(`rendering ${name}…`);
    try {
      applyOrbit();
      const { frame, ms } = renderTimed(name);
      const score = state.page.score(frame);
      const result = { ms, wrong: score.wrong(), differing: score.differing(), map: score.map(), stats: frame.stats() };
      state.results.set(name, result);
      drawCell(name, frame.rgba(), result);
      frame.free();
      score.free();
      drawChart($("chart"), state.results, state.main);
    } catch (e) {
      reportError(`${name}: ${e.message || e}`);
    }
    setTimeout(step, 0);
  };
  step();
}

function drawCell(name, rgba, result) {
  const cell = document.querySelector(`.cell[data-hider="${name}"]`);
  cell.classList.remove("pending");
  cell.classList.toggle("wrong", result.wrong > 0);
  blit(cell.querySelector("canvas"), rgba, state.size, $("overlay").checked ? result.map : null);
  cell.querySelector(".nums").innerHTML =
    `${result.ms.toFixed(1)} ms · <b>${result.wrong}</b> wrong` +
    (result.differing !== result.wrong ? ` (${result.differing} differ)` : "");
  cell.title = result.stats;
}

function buildGrid() {
  const grid = $("grid");
  grid.replaceChildren();
  for (const name of state.hiders) {
    const cell = document.createElement("div");
    cell.className = "cell pending";
    cell.dataset.hider = name;
    cell.innerHTML = `<div class="name"></div><canvas></canvas><div class="nums">—</div>`;
    cell.querySelector(".name").textContent = name;
    cell.querySelector(".name").title = Page.describe(name);
    cell.addEventListener("click", () => { $("main-hider").value = name; setMain(name); });
    grid.append(cell);
  }
}

function setMain(name) {
  state.main = name;
  state.frameTimes = [];
  renderMain();
  drawChart($("chart"), state.results, state.main);
}

function viewChanged() {
  renderMain();
  scheduleGrid();
}

function reportError(message) {
  status(message, true);
  console.error(message);
}

function showWarnings() {
  $("warnings").textContent = state.page.warnings();
}

// Scenes -------------------------------------------------------------

async function loadBundled(name) {
  for (const path of BUNDLED[name]) {
    const response = await fetch(`assets/${path}`);
    if (!response.ok) throw new Error(`assets/${path}: ${response.status}`);
    state.page.add_file(path.split("/").pop(), new Uint8Array(await response.arrayBuffer()));
  }
  state.page.load_files(BUNDLED[name][0].split("/").pop());
}

async function loadScene(choice) {
  status(`loading ${choice}…`);
  const [kind, rest] = choice.split("|");
  if (kind === "bundled") await loadBundled(rest);
  else if (kind === "count") state.page.load_spec(`${rest}:${$("count").value}`);
  else state.page.load_spec(rest);
  state.orbit = { yaw: 0, pitch: 0, zoom: 0, panX: 0, panY: 0 };
  showWarnings();
  viewChanged();
}

async function loadDropped(files) {
  const list = [...files];
  const obj = list.find((f) => f.name.toLowerCase().endsWith(".obj"));
  if (!obj) { reportError("drop an .obj file (with its .mtl and textures)"); return; }
  for (const f of list) state.page.add_file(f.name, new Uint8Array(await f.arrayBuffer()));
  state.page.load_files(obj.name);
  const option = document.createElement("option");
  option.value = "dropped|" + obj.name;
  option.textContent = `dropped: ${obj.name}`;
  $("scene").append(option);
  $("scene").value = option.value;
  state.orbit = { yaw: 0, pitch: 0, zoom: 0, panX: 0, panY: 0 };
  showWarnings();
  viewChanged();
}

function fillScenes() {
  const select = $("scene");
  const group = (label, items) => {
    const g = document.createElement("optgroup");
    g.label = label;
    for (const [value, text] of items) {
      const o = document.createElement("option");
      o.value = value;
      o.textContent = text;
      g.append(o);
    }
    select.append(g);
  };
  group("Bundled", Object.keys(BUNDLED).map((n) => [`bundled|${n}`, n]));
  group("Generated", [
    ["spec|gen:intersecting", "gen:intersecting"], ["spec|gen:cyclic", "gen:cyclic"],
    ["spec|gen:coplanar", "gen:coplanar"], ["spec|gen:cube", "gen:cube"],
    ["count|gen:sphere", "sphere:N"], ["count|gen:soup", "soup:N"],
  ]);
  group("Hard cases", Page.hard_cases().map((n) => [`spec|hard:${n}`, n]));
}

// Input: mouse, touch (pointer events) and keys --------------------

function bindInput() {
  const canvas = $("view");
  const pointers = new Map();
  let pinch = null;
  const moved = () => { renderMain(); scheduleGrid(); };
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, { x: e.clientX, y: e.clientY, pan: e.shiftKey || e.button === 2 });
    // The pinch's reference distance is the two fingers' as the second lands.
    const [a, b] = [...pointers.values()];
    pinch = b ? Math.hypot(a.x - b.x, a.y - b.y) : null;
    canvas.focus();
  });
  canvas.addEventListener("pointermove", (e) => {
    const p = pointers.get(e.pointerId);
    if (!p) return;
    const dx = e.clientX - p.x, dy = e.clientY - p.y;
    p.x = e.clientX; p.y = e.clientY;
    if (pointers.size === 2) {
      const [a, b] = [...pointers.values()];
      const d = Math.hypot(a.x - b.x, a.y - b.y);
      if (pinch !== null && d > 0) state.orbit.zoom += Math.log2(pinch / d);
      pinch = d;
      // Two fingers moving together pan: the midpoint moves half this finger's move.
      state.orbit.panX -= dx / 2 / canvas.clientWidth;
      state.orbit.panY += dy / 2 / canvas.clientHeight;
    } else if (p.pan) {
      state.orbit.panX -= dx / canvas.clientWidth;
      state.orbit.panY += dy / canvas.clientHeight;
    } else {
      state.orbit.yaw -= dx * 0.01;
      state.orbit.pitch = Math.max(-1.55, Math.min(1.55, state.orbit.pitch + dy * 0.01));
    }
    moved();
  });
  const up = (e) => { pointers.delete(e.pointerId); pinch = null; };
  canvas.addEventListener("pointerup", up);
  canvas.addEventListener("pointercancel", up);
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    state.orbit.zoom += Math.sign(e.deltaY) * 0.1;
    moved();
  }, { passive: false });
  canvas.addEventListener("keydown", (e) => {
    const o = state.orbit, a = 0.1;
    const keys = {
      ArrowLeft: () => (e.shiftKey ? (o.panX -= a) : (o.yaw += a)),
      ArrowRight: () => (e.shiftKey ? (o.panX += a) : (o.yaw -= a)),
      ArrowUp: () => (e.shiftKey ? (o.panY += a) : (o.pitch = Math.min(1.55, o.pitch + a))),
      ArrowDown: () => (e.shiftKey ? (o.panY -= a) : (o.pitch = Math.max(-1.55, o.pitch - a))),
      "+": () => (o.zoom -= a), "=": () => (o.zoom -= a), "-": () => (o.zoom += a),
    };
    if (keys[e.key]) { e.preventDefault(); keys[e.key](); moved(); }
  });
  const drop = $("drop");
  for (const target of [drop, canvas]) {
    target.addEventListener("dragover", (e) => { e.preventDefault(); drop.classList.add("over"); });
    target.addEventListener("dragleave", () => drop.classList.remove("over"));
    target.addEventListener("drop", (e) => {
      e.preventDefault();
      drop.classList.remove("over");
      loadDropped(e.dataTransfer.files).catch((err) => reportError(err.message || String(err)));
    });
  }
  $("files").addEventListener("change", (e) =>
    loadDropped(e.target.files).catch((err) => reportError(err.message || String(err))));
}

function bindControls() {
  const guard = (f) => (...args) => Promise.resolve(f(...args)).catch((e) => reportError(e.message || String(e)));
  $("scene").addEventListener("change", guard(() => {
    const v = $("scene").value;
    $("count-label").hidden = !v.startsWith("count|");
    if (!v.startsWith("dropped|")) return loadScene(v);
  }));
  $("count").addEventListener("change", guard(() => loadScene($("scene").value)));
  $("size").addEventListener("change", guard(() => {
    state.size = Number($("size").value);
    state.page.set_size(state.size, state.size);
    state.frameTimes = [];
    viewChanged();
  }));
  $("main-hider").addEventListener("change", () => setMain($("main-hider").value));
  $("overlay").addEventListener("change", () => {
    renderMain();
    for (const [name, result] of state.results) {
      const frame = state.page.render(name);
      drawCell(name, frame.rgba(), result);
      frame.free();
    }
  });
  $("reset").addEventListener("click", () => {
    state.orbit = { yaw: 0, pitch: 0, zoom: 0, panX: 0, panY: 0 };
    viewChanged();
  });
  for (const tab of document.querySelectorAll(".tab")) {
    tab.addEventListener("click", () => {
      for (const t of document.querySelectorAll(".tab")) t.classList.toggle("active", t === tab);
      for (const v of document.querySelectorAll(".view")) v.classList.toggle("active", v.id === tab.dataset.view);
      // The step-through records the view the Compare tab shows.
      if (tab.dataset.view === "steps") {
        try { steps.record(); } catch (e) { reportError(e.message || String(e)); }
      }
    });
  }
}

async function main() {
  await init();
  state.page = new Page();
  state.page.set_size(state.size, state.size);
  state.hiders = Page.hiders();
  for (const name of state.hiders) {
    const o = document.createElement("option");
    o.textContent = name;
    $("main-hider").append(o);
  }
  $("main-hider").value = state.main;
  fillScenes();
  buildGrid();
  bindInput();
  bindControls();
  steps = buildSteps({ state, reportError });
  extras = { inspect: buildInspect({ state, reportError }), precision: buildPrecision({ reportError }), ybuffer: buildYBuffer({ reportError }) };
  $("scene").value = "bundled|spider";
  await loadScene("bundled|spider");
  document.body.dataset.ready = "1";
}

// For the browser tests and the curious: the module's handle and state.
window.hiderApp = { state, loadScene, renderMain, Page, steps: () => steps, extras: () => extras };
main().catch((e) => reportError(`the page did not start: ${e.message || e}`));
