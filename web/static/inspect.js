// The A-buffer's pixel inspector: the Compare view's scene and camera
// rendered small by hider-abuffer with its fragment lists kept; hovering
// or tapping a pixel reads that pixel's list back from the A-buffer
// (ABuffer::inspect_pixel) and draws it. Nothing here decides coverage,
// depth or colour: the numbers come from the crate.
import { Inspector } from "./pkg/hider_web.js";

const $ = (id) => document.getElementById(id);
const STRIDE = 11; // numbers per fragment (InspectedPixel::fragments)
const SHOWN = 384; // CSS pixels of the inspected image

// Linear light to an sRGB byte, only to paint a swatch of a fragment's
// colour (the resolved pixel comes from the A-buffer as bytes).
const srgb = (c) => Math.round(255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * Math.pow(c, 1 / 2.4) - 0.055));
const css = (r, g, b) => `rgb(${r},${g},${b})`;

export function buildInspect(app) {
  const host = $("inspect-body");
  host.innerHTML = `
    <h2>The A-buffer, pixel by pixel</h2>
    <p>The view rendered by the A-buffer (Carpenter 1984) with its fragment lists kept. Hover or tap a
    pixel: its list is read back from <code>hider_abuffer::ABuffer::inspect_pixel</code>, each fragment
    with its 8&nbsp;×&nbsp;4 coverage mask, depth range and colour, in the order the resolve sorts them
    (nearest <i>z</i><sub>min</sub> first); the sample grid shows which fragment is in front at each of the
    32 samples, and the resolve is the pixel's colour, computed by the A-buffer's own resolve.</p>
    <div class="controls">
      <label>Size <select id="i-size"><option selected>32</option><option>64</option><option>128</option></select></label>
      <label>Resolve <select id="i-mode">
        <option value="">per-sample depth (abuffer)</option>
        <option value="carpenter">zmin/zmax blender (abuffer-carpenter)</option>
      </select></label>
      <button id="i-record">record the current view</button>
      <span id="i-label">—</span>
    </div>
    <div class="stage">
      <figure><canvas id="i-image" width="32" height="32" style="width:${SHOWN}px;height:${SHOWN}px;touch-action:none;cursor:crosshair"></canvas>
        <figcaption>the A-buffer's frame; the inspected pixel outlined</figcaption></figure>
      <div id="i-panel" class="inspect-panel"><p>Hover a pixel.</p></div>
    </div>`;
  let inspector = null, side = 32, pixel = null;
  const image = $("i-image");

  const drawImage = () => {
    const rgba = new Uint8ClampedArray(inspector.rgba());
    image.width = side * 8; image.height = side * 8;
    const small = document.createElement("canvas");
    small.width = side; small.height = side;
    small.getContext("2d").putImageData(new ImageData(rgba, side, side), 0, 0);
    const g = image.getContext("2d");
    g.imageSmoothingEnabled = false;
    g.drawImage(small, 0, 0, side * 8, side * 8);
    if (pixel) {
      g.strokeStyle = "#ff0"; g.lineWidth = 2;
      g.strokeRect(pixel[0] * 8 + 1, pixel[1] * 8 + 1, 6, 6);
    }
  };

  // An 8 x 4 grid, cell `k` at (k % 8, k / 8), coloured by `fill(k)`.
  const grid = (fill, label = null) => {
    const c = document.createElement("canvas");
    const cell = 14;
    c.width = 8 * cell; c.height = 4 * cell;
    c.className = "mask";
    const g = c.getContext("2d");
    g.font = "9px sans-serif"; g.textAlign = "center"; g.textBaseline = "middle";
    for (let k = 0; k < 32; k++) {
      const x = (k % 8) * cell, y = Math.floor(k / 8) * cell;
      g.fillStyle = fill(k) || "#fff";
      g.fillRect(x, y, cell, cell);
      g.strokeStyle = "#bbb"; g.strokeRect(x + 0.5, y + 0.5, cell - 1, cell - 1);
      const t = label && label(k);
      if (t !== null && t !== undefined && t !== "") { g.fillStyle = "#000"; g.fillText(String(t), x + cell / 2, y + cell / 2 + 1); }
    }
    return c;
  };

  const inspect = (x, y) => {
    if (!inspector || x < 0 || y < 0 || x >= side || y >= side) return;
    pixel = [x, y];
    const px = inspector.pixel(x, y);
    const f = px.fragments(), front = px.front(), complexity = px.depth_complexity();
    const colour = px.color(), coverage = px.coverage(), id = px.id(), depth = px.depth();
    px.free();
    const n = f.length / STRIDE;
    const frag = (i) => {
      const o = i * STRIDE;
      return { mask: f[o] >>> 0, prim: f[o + 1], centrePrim: f[o + 2], zmin: f[o + 3], zmax: f[o + 4],
        centreZ: f[o + 5], rgb: [f[o + 6], f[o + 7], f[o + 8]], alpha: f[o + 9], merged: f[o + 10] === 1 };
    };
    const frags = Array.from({ length: n }, (_, i) => frag(i));
    const swatch = (s) => css(...s.rgb.map(srgb));
    const panel = $("i-panel");
    panel.replaceChildren();
    const head = document.createElement("div");
    const union = frags.reduce((m, s) => (m | s.mask) >>> 0, 0);
    const covered = union.toString(2).split("1").length - 1;
    head.innerHTML = `<b>pixel (${x}, ${y})</b>: ${n} fragment${n === 1 ? "" : "s"} ·
      resolve <span class="swatch" style="background:${css(colour[0], colour[1], colour[2])}"></span>
      rgb(${colour[0]}, ${colour[1]}, ${colour[2]}) · coverage ${covered}/32 = ${coverage.toFixed(4)} ·
      id ${id < 0 ? "none" : id} · depth ${depth.toPrecision(7)}`;
    panel.append(head);
    if (n > 0) {
      const row = document.createElement("div");
      row.className = "mask-row";
      const cap = document.createElement("div");
      cap.innerHTML = `front fragment per sample (number = fragments covering it): how the 32 samples were accumulated; the
        resolve sums each sample's colour over the fragments in front of it (opaque ones hide the rest) and divides by 32`;
      row.append(grid((k) => (front[k] >= 0 ? swatch(frags[front[k]]) : "#111"),
        (k) => (front[k] >= 0 ? `${front[k]}${complexity[k] > 1 ? "/" + complexity[k] : ""}` : "")), cap);
      panel.append(row);
    }
    frags.forEach((s, i) => {
      const row = document.createElement("div");
      row.className = "mask-row";
      const text = document.createElement("div");
      const bits = s.mask.toString(2).split("1").length - 1;
      text.innerHTML = `<b>#${i}</b> <span class="swatch" style="background:${swatch(s)}"></span>
        triangle ${s.prim}${s.merged ? " (merged)" : ""} · ${bits}/32 samples ·
        z<sub>min</sub> ${s.zmin.toPrecision(7)} z<sub>max</sub> ${s.zmax.toPrecision(7)} ·
        centre ${s.centreZ < 0 ? "not covered" : `z ${s.centreZ.toPrecision(7)} (id ${s.centrePrim})`} ·
        opacity ${s.alpha.toFixed(2)} · mask 0x${s.mask.toString(16).padStart(8, "0")}`;
      row.append(grid((k) => ((s.mask >>> k) & 1 ? swatch(s) : null)), text);
      panel.append(row);
    });
    host.dataset.pixel = `${x},${y}`;
    host.dataset.fragments = String(n);
    drawImage();
  };

  const record = () => {
    side = Number($("i-size").value);
    inspector?.free();
    inspector = Inspector.record(app.state.page, side, $("i-mode").value === "carpenter");
    const ids = inspector.ids();
    const covered = ids.filter((id) => id >= 0).length;
    $("i-label").textContent = `${side} × ${side}, ${covered} pixels with a surface at the centre`;
    const p = pixel && pixel[0] < side && pixel[1] < side ? pixel : [side >> 1, side >> 1];
    pixel = null;
    drawImage();
    inspect(p[0], p[1]);
    host.dataset.recorded = String(side);
  };
  const guarded = (f) => (...a) => { try { f(...a); } catch (e) { app.reportError(e.message || String(e)); } };
  const at = (e) => {
    const r = image.getBoundingClientRect();
    return [Math.floor((e.clientX - r.left) / r.width * side), Math.floor((e.clientY - r.top) / r.height * side)];
  };
  image.addEventListener("pointermove", guarded((e) => { const [x, y] = at(e); if (!pixel || x !== pixel[0] || y !== pixel[1]) inspect(x, y); }));
  image.addEventListener("pointerdown", guarded((e) => { const [x, y] = at(e); inspect(x, y); }));
  $("i-record").addEventListener("click", guarded(record));
  $("i-size").addEventListener("change", guarded(record));
  $("i-mode").addEventListener("change", guarded(record));
  // The step-through tab records the view the Compare tab shows.
  document.querySelector('.tab[data-view="steps"]').addEventListener("click", guarded(record));
  return { record, inspect };
}
