// The Y-buffer (tinyrenderer's 2D lesson): three segments in a plane,
// seen from its bottom edge. Drag their end points; the 1-pixel-high
// image and its depth buffer (the "y-buffer") come from hider-zbuffer,
// which draws each segment as a quad extruded along the collapsed axis
// (hider_web::ybuffer). Nothing here decides visibility.
import { YBuffer } from "./pkg/hider_web.js";

const $ = (id) => document.getElementById(id);
const W = 128; // image columns; the plane is W x W
const SCALE = 4; // CSS pixels per plane unit
// The lesson's layout: a slope, a segment in front of it on the left,
// one crossing it on the right (plane units; y is the distance from the
// viewer's edge, drawn upwards from the bottom).
const START = [[8, 100, 120, 20], [4, 60, 56, 60], [72, 40, 124, 40]];

export function buildYBuffer(app) {
  const host = $("ybuffer-body");
  host.innerHTML = `
    <h2>The Y-buffer: a depth buffer one pixel high</h2>
    <p>tinyrenderer's 2D lesson, live. Three segments lie in a plane; the viewer looks at them from the
    bottom edge, so each image column sees the segment nearest that edge. Drag the end points. The
    image (one pixel high, stretched) and its depth buffer — the <i>y-buffer</i>, each column's
    distance to the segment in front — are rendered by the project's z-buffer: each segment is a quad
    extruded along the axis the image collapses, seen by an orthographic camera, and the z-buffer's
    depth test per column does the rest.</p>
    <div class="stage">
      <figure><canvas id="y-plane" width="${W * SCALE}" height="${W * SCALE}" style="touch-action:none;background:#fff;border:1px solid #ddd"></canvas>
        <figcaption>the plane, seen from above; the viewer is along the bottom edge</figcaption></figure>
      <div>
        <figure><canvas id="y-image" width="${W}" height="1" style="width:${W * SCALE}px;height:32px"></canvas>
          <figcaption>the 1-pixel-high image (${W} × 1), stretched</figcaption></figure>
        <figure><canvas id="y-plot" width="${W * SCALE}" height="${W * SCALE / 2}" style="background:#fff;border:1px solid #ddd"></canvas>
          <figcaption>the y-buffer: per column, the distance of the segment in front (none: no bar)</figcaption></figure>
      </div>
    </div>`;
  const ybuffer = new YBuffer();
  const segs = START.map((s) => s.slice());
  const colour = [0, 1, 2].map((k) => `rgb(${Array.from(YBuffer.colour(k)).join(",")})`);
  const plane = $("y-plane");
  const toCanvas = (x, y) => [x * SCALE, (W - y) * SCALE];
  const draw = () => {
    ybuffer.render(new Float64Array(segs.flat()), W);
    const ids = ybuffer.segments(), ys = ybuffer.ybuffer();
    const g = plane.getContext("2d");
    g.clearRect(0, 0, plane.width, plane.height);
    // The y-buffer over the plane: where each column's view stops.
    g.fillStyle = "rgba(0,0,0,0.06)";
    for (let x = 0; x < W; x++) if (ids[x] >= 0) g.fillRect(x * SCALE, (W - ys[x]) * SCALE, SCALE, ys[x] * SCALE);
    segs.forEach((s, k) => {
      const [ax, ay] = toCanvas(s[0], s[1]), [bx, by] = toCanvas(s[2], s[3]);
      g.strokeStyle = colour[k]; g.lineWidth = 4;
      g.beginPath(); g.moveTo(ax, ay); g.lineTo(bx, by); g.stroke();
      g.fillStyle = colour[k];
      for (const [px, py] of [[ax, ay], [bx, by]]) { g.beginPath(); g.arc(px, py, 8, 0, 2 * Math.PI); g.fill(); }
    });
    g.fillStyle = "#333"; g.fillRect(0, plane.height - 4, plane.width, 4);
    const image = $("y-image");
    image.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(ybuffer.rgba()), W, 1), 0, 0);
    const plot = $("y-plot"), p = plot.getContext("2d");
    p.clearRect(0, 0, plot.width, plot.height);
    for (let x = 0; x < W; x++) {
      if (ids[x] < 0) continue;
      const h = ys[x] / W * plot.height;
      p.fillStyle = colour[ids[x]];
      p.fillRect(x * SCALE, plot.height - h, SCALE, h);
    }
    host.dataset.columns = JSON.stringify(Array.from(ids));
  };
  const guarded = (f) => (...a) => { try { f(...a); } catch (e) { app.reportError(e.message || String(e)); } };
  let held = null;
  const at = (e) => {
    const r = plane.getBoundingClientRect();
    const x = (e.clientX - r.left) / r.width * W, y = W - (e.clientY - r.top) / r.height * W;
    return [Math.max(0, Math.min(W, x)), Math.max(0, Math.min(W, y))];
  };
  plane.addEventListener("pointerdown", guarded((e) => {
    const [x, y] = at(e);
    let best = 4; // plane units
    segs.forEach((s, k) => [0, 2].forEach((o) => {
      const d = Math.hypot(s[o] - x, s[o + 1] - y);
      if (d < best) { best = d; held = [k, o]; }
    }));
    if (held) plane.setPointerCapture(e.pointerId);
  }));
  plane.addEventListener("pointermove", guarded((e) => {
    if (!held) return;
    const [x, y] = at(e);
    segs[held[0]][held[1]] = x; segs[held[0]][held[1] + 1] = y;
    draw();
  }));
  const release = () => { held = null; };
  plane.addEventListener("pointerup", release);
  plane.addEventListener("pointercancel", release);
  document.querySelector('.tab[data-view="ybuffer"]').addEventListener("click", guarded(draw));
  guarded(draw)();
  return { segs, draw, W, SCALE };
}
