// The depth-precision view: two near-coplanar planes rendered by every
// registered depth-buffer variant (hider-zbuffer's depth formats and
// sources, through the registry), each scored against the oracle. The
// page only draws the frames and the fighting pixels the crates report.
import { Precision } from "./pkg/hider_web.js";

const $ = (id) => document.getElementById(id);
const SIDE = 64;

export function buildPrecision(app) {
  const host = $("precision-body");
  host.innerHTML = `
    <h2>Depth precision: two planes, every depth format</h2>
    <p>Two parallel planes, the nearer one 10 units from the eye, the second <i>gap</i> × 10 behind it, both
    slightly tilted. Each depth buffer stores window depth in its own format; where two depths round to the
    same stored value, the earlier-drawn plane (the far one) wins and the planes <i>fight</i>. Window depth
    spends its resolution near the near plane, so pulling <i>near</i> in or pushing <i>far</i> out makes
    things worse; 16-bit fixed point gives up first. The fighting pixels (red) are those whose plane is not
    the oracle's.</p>
    <div class="controls">
      <label>gap <input id="pr-gap" type="range" min="-7" max="-1" step="0.1" value="-3"> <span id="pr-gap-v"></span></label>
      <label>near <input id="pr-near" type="range" min="-3" max="0.9" step="0.1" value="-1"> <span id="pr-near-v"></span></label>
      <label>far <input id="pr-far" type="range" min="1.2" max="6" step="0.1" value="3"> <span id="pr-far-v"></span></label>
      <label><input id="pr-marks" type="checkbox" checked> mark fights</label>
    </div>
    <div id="pr-grid" class="grid"></div>`;
  const precision = new Precision();
  const value = (id) => Math.pow(10, Number($(id).value));
  const run = () => {
    const gap = value("pr-gap"), near = value("pr-near"), far = value("pr-far");
    $("pr-gap-v").textContent = `${gap.toPrecision(2)} (${(gap * 10).toPrecision(2)} units)`;
    $("pr-near-v").textContent = near.toPrecision(2);
    $("pr-far-v").textContent = `${far.toPrecision(2)} (far/near ${(far / near).toPrecision(2)})`;
    const n = precision.run(gap, near, far, SIDE);
    const covered = precision.covered();
    const grid = $("pr-grid");
    grid.replaceChildren();
    const shares = {};
    for (let k = 0; k < n; k++) {
      const name = precision.name(k), fights = precision.fights(k);
      const data = new Uint8ClampedArray(precision.rgba(k));
      if ($("pr-marks").checked) {
        const map = precision.map(k);
        for (let p = 0; p < map.length; p++) if (map[p]) data.set([255, 0, 0, 255], 4 * p);
      }
      const cell = document.createElement("div");
      cell.className = "fmt-cell";
      cell.dataset.format = name;
      cell.title = precision.describe(k);
      cell.innerHTML = `<div class="name"></div><canvas width="${SIDE}" height="${SIDE}"></canvas><div class="nums"></div>`;
      cell.querySelector(".name").textContent = name;
      cell.querySelector("canvas").getContext("2d").putImageData(new ImageData(data, SIDE, SIDE), 0, 0);
      const share = covered ? fights / covered : 0;
      cell.querySelector(".nums").innerHTML = `<b>${fights}</b> fighting pixels · ${(100 * share).toFixed(1)} %`;
      cell.classList.toggle("wrong", fights > 0);
      grid.append(cell);
      shares[name] = share;
    }
    host.dataset.shares = JSON.stringify(shares);
    return shares;
  };
  const guarded = () => { try { run(); } catch (e) { app.reportError(e.message || String(e)); } };
  for (const id of ["pr-gap", "pr-near", "pr-far", "pr-marks"]) $(id).addEventListener("input", guarded);
  document.querySelector('.tab[data-view="steps"]').addEventListener("click", guarded);
  // For the tests: set the sliders' exponents and run.
  const set = (gapExp, nearExp, farExp) => {
    $("pr-gap").value = String(gapExp); $("pr-near").value = String(nearExp); $("pr-far").value = String(farExp);
    return run();
  };
  return { run, set };
}
