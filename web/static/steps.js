// The step-through view: the z-buffer triangle by triangle, replayed from
// the trace hider-zbuffer records (ZBuffer::render_traced). Nothing here
// computes coverage or depth: it draws what the trace holds.
import { buildPainterSteps } from "./painter-steps.js";
import { buildScanlineSteps } from "./scanline-steps.js";
import { buildWarnockSteps } from "./warnock-steps.js";

const $ = (id) => document.getElementById(id);

// A distinct colour per primitive id (a drawing aid, like --shade ids).
function idColour(id) {
  if (id < 0) return [0, 0, 0];
  // Muted hues a golden angle apart: neighbouring ids differ, and none
  // is as bright as the outcome colours drawn over them.
  const h = (id * 137.508) % 360, f = (n) => {
    const k = (n + h / 30) % 12;
    return Math.round(255 * (0.55 - 0.15 * Math.max(-1, Math.min(k - 3, 9 - k, 1))));
  };
  return [f(0), f(8), f(4)];
}

export function buildSteps(app) {
  const body = $("steps-body");
  body.innerHTML = `
    <h2>The z-buffer, triangle by triangle</h2>
    <p>Each step draws one triangle in submission order. At every pixel centre it covers, the depth
    test compares its depth with the stored one: <span style="color:#0a0">green</span> pixels passed
    (id and depth written), <span style="color:#d22">red</span> ones failed (something nearer was
    there). The trace is recorded by <code>hider_zbuffer::ZBuffer::render_traced</code>; its last step
    is the z-buffer's frame.</p>
    <div class="controls">
      <label>Size <select id="z-size"><option>32</option><option selected>64</option><option>128</option></select></label>
      <button id="z-record">record the current view</button>
      <button id="z-back" title="step back">◀</button>
      <button id="z-play">play</button>
      <button id="z-next" title="step forward">▶</button>
      <input id="z-scrub" type="range" min="0" max="0" value="0" style="width: 20rem">
      <span id="z-label">—</span>
    </div>
    <div class="stage">
      <figure><canvas id="z-colour" width="64" height="64" style="width:384px;height:384px"></canvas>
        <figcaption>ids (false colour) with the step's depth tests</figcaption></figure>
      <figure><canvas id="z-depth" width="64" height="64" style="width:384px;height:384px"></canvas>
        <figcaption>depth buffer (nearest dark, farthest light, stretched over the drawn range; clear value white)</figcaption></figure>
    </div>`;
  const scanline = buildScanlineSteps(app, idColour);
  const painter = buildPainterSteps(app, idColour);
  const warnock = buildWarnockSteps(app, idColour);
  let steps = 0, k = 0, side = 64, timer = null;
  const draw = () => {
    const step = app.state.page.zbuffer_step(k);
    const ids = step.ids(), depth = step.depth(), outcome = step.outcome(), prim = step.prim();
    step.free();
    const colour = new Uint8ClampedArray(side * side * 4);
    const grey = new Uint8ClampedArray(side * side * 4);
    // Depth stretched over the covered pixels' range: window depth
    // crowds near 1 under perspective.
    let lo = 1, hi = 0;
    for (let p = 0; p < ids.length; p++) if (ids[p] >= 0) { lo = Math.min(lo, depth[p]); hi = Math.max(hi, depth[p]); }
    const span = hi > lo ? hi - lo : 1;
    for (let p = 0; p < ids.length; p++) {
      let [r, g, b] = idColour(ids[p]);
      if (outcome[p] === 1) [r, g, b] = [40, 200, 60];
      if (outcome[p] === 2) [r, g, b] = [220, 40, 40];
      colour.set([r, g, b, 255], 4 * p);
      const d = ids[p] < 0 ? 255 : Math.round(40 + 180 * (depth[p] - lo) / span);
      grey.set([d, d, d, 255], 4 * p);
    }
    for (const [id, data] of [["z-colour", colour], ["z-depth", grey]]) {
      const c = $(id);
      c.width = side; c.height = side;
      c.getContext("2d").putImageData(new ImageData(data, side, side), 0, 0);
    }
    const passed = outcome.filter((o) => o === 1).length, failed = outcome.filter((o) => o === 2).length;
    $("z-label").textContent = k === 0 ? `step 0 of ${steps}: nothing drawn`
      : `step ${k} of ${steps}: triangle ${prim}, ${passed} passed, ${failed} failed`;
    $("z-scrub").value = String(k);
    body.dataset.step = String(k);
    body.dataset.steps = String(steps);
  };
  const go = (next) => { k = Math.max(0, Math.min(steps, next)); draw(); };
  const stop = () => { clearInterval(timer); timer = null; $("z-play").textContent = "play"; };
  const record = () => {
    stop();
    side = Number($("z-size").value);
    steps = app.state.page.zbuffer_trace(side);
    $("z-scrub").max = String(steps);
    go(steps);
    scanline.record(side);
    painter.record(side);
    warnock.record(side);
  };
  $("z-record").addEventListener("click", () => { try { record(); } catch (e) { app.reportError(e.message || String(e)); } });
  $("z-size").addEventListener("change", record);
  $("z-back").addEventListener("click", () => { stop(); go(k - 1); });
  $("z-next").addEventListener("click", () => { stop(); go(k + 1); });
  $("z-scrub").addEventListener("input", () => { stop(); go(Number($("z-scrub").value)); });
  $("z-play").addEventListener("click", () => {
    if (timer) { stop(); return; }
    if (k >= steps) go(0);
    $("z-play").textContent = "pause";
    const every = Math.max(15, Math.min(300, 6000 / Math.max(1, steps)));
    timer = setInterval(() => { if (k >= steps) stop(); else go(k + 1); }, every);
  });
  return { record, go, scanline, painter, warnock };
}
