// Warnock's step-through: the subdivision level by level, from the final
// windows Warnock records itself (WarnockOptions::record_regions). Each
// step decides the windows of one more level; nothing here classifies.
const $ = (id) => document.getElementById(id);

// Colours per rule code (1 + index in hider_warnock::Rule::ALL).
const RULES = [
  null,
  ["empty: no polygon reaches it", [90, 90, 90]],
  ["one polygon inside or intersecting it: drawn by the edge test", [40, 200, 80]],
  ["one polygon surrounds it, alone", [70, 150, 255]],
  ["a surrounding polygon in front of all others", [255, 210, 40]],
  ["down to a pixel: the depth test at its centre", [240, 50, 40]],
  ["pixel handed to the sub-pixel subdivision", [230, 60, 220]],
];

// Colours per polygon class (index in hider_warnock::Class::ALL).
const CLASSES = [
  ["disjoint", [150, 150, 150]],
  ["surrounding", [70, 150, 255]],
  ["contained", [40, 200, 80]],
  ["intersecting", [255, 150, 30]],
];
const WINDOW = 11, CLASS = 5, MAX_ROWS = 200;

export function buildWarnockSteps(app, idColour) {
  const host = document.createElement("div");
  host.id = "warnock-steps";
  const legend = RULES.slice(1, 6).map(([text, c]) =>
    `<span style="color:rgb(${c.join(",")})">■</span> ${text}`).join("; ");
  host.innerHTML = `
    <h2>Warnock's windows, level by level</h2>
    <p>Warnock classifies each polygon against a window (disjoint, surrounding, contained, intersecting)
    and decides the window when that is simple — nothing there, one polygon, or a surrounding polygon in
    front of everything — or cuts it in four. Step <i>k</i> shows the windows decided at the first
    <i>k</i> levels, each coloured by how it was decided (brighter: decided at this step), with the
    frame's ids under them; black pixels are in the windows this step cut (outlined in
    <span style="color:#e80">orange</span>: several polygons reach them and none settles them). ${legend}. The windows are
    recorded by Warnock itself (<code>WarnockOptions::record_regions</code>, decided and cut); at the last step they tile
    the picture and the ids are Warnock's frame.</p>
    <p>Click a window to see each polygon's class against it, as Warnock computed it
    (<code>WarnockOptions::record_classes</code>), and what decided the window: the polygons are drawn in
    their class's colour — ${CLASSES.map(([n, c]) => `<span style="color:rgb(${c.join(",")})">■</span> ${n}`).join(", ")};
    dashed red: culled, hidden behind the surrounding polygon in front at every sample; thick: that
    surrounder.</p>
    <div class="controls">
      <button id="w-back" title="level back">◀</button>
      <button id="w-next" title="level forward">▶</button>
      <input id="w-scrub" type="range" min="0" max="0" value="0" style="width: 20rem">
      <span id="w-label">—</span>
    </div>
    <div class="stage">
      <figure><canvas id="w-canvas" width="384" height="384" style="width:384px;height:384px"></canvas>
        <figcaption>windows decided so far, by rule, over the ids</figcaption></figure>
      <table id="w-counts" class="data"></table>
    </div>
    <div class="stage">
      <div class="s-tables" style="max-width:760px">
        <h3 id="w-window-title">Window</h3>
        <p id="w-window-text"></p>
        <table id="w-class-counts" class="data"></table>
        <div style="max-height:320px;overflow:auto;margin-top:.4rem"><table id="w-classes" class="data"></table></div>
      </div>
    </div>`;
  $("steps-body").appendChild(host);
  const page = () => app.state.page;
  let side = 64, steps = 0, k = 0, pick = [0, 0];
  // The window shown for the picked pixel at this step, its polygons drawn
  // in class colours and listed.
  const drawWindow = (g, scale) => {
    const w = page().warnock_window_at(k, pick[0], pick[1]);
    host.dataset.window = String(w);
    if (w < 0) {
      $("w-window-title").textContent = "Window: step 0 shows none; step forward and click one";
      $("w-window-text").textContent = "";
      $("w-class-counts").innerHTML = $("w-classes").innerHTML = "";
      host.dataset.classes = "0";
      return;
    }
    const win = page().warnock_window(w), cls = page().warnock_window_classes(w);
    const outl = page().warnock_window_outlines(w), n = cls.length / CLASS;
    g.save();
    g.beginPath();
    g.rect(win[0] * scale, win[1] * scale, (win[2] - win[0]) * scale, (win[3] - win[1]) * scale);
    g.clip();
    for (let i = 0; i < n; i++) {
      const c = cls[i * CLASS + 2], hidden = cls[i * CLASS + 3], front = cls[i * CLASS + 4];
      if (c === 0 && n > 300) continue;
      const col = CLASSES[c][1], v = outl.subarray(i * 6, i * 6 + 6);
      g.beginPath();
      g.moveTo(v[0] * scale, v[1] * scale);
      g.lineTo(v[2] * scale, v[3] * scale);
      g.lineTo(v[4] * scale, v[5] * scale);
      g.closePath();
      if (c > 0 && !hidden) { g.fillStyle = `rgba(${col.join(",")},0.25)`; g.fill(); }
      g.setLineDash(hidden ? [4, 3] : []);
      g.strokeStyle = hidden ? "#f44" : `rgb(${col.join(",")})`;
      g.lineWidth = front ? 3 : 1.5;
      g.stroke();
    }
    g.restore();
    g.setLineDash([]);
    g.strokeStyle = "#fff";
    g.lineWidth = 3;
    g.strokeRect(win[0] * scale + 1.5, win[1] * scale + 1.5, (win[2] - win[0]) * scale - 3, (win[3] - win[1]) * scale - 3);
    g.strokeStyle = "#000";
    g.lineWidth = 1;
    g.strokeRect(win[0] * scale + 0.5, win[1] * scale + 0.5, (win[2] - win[0]) * scale - 1, (win[3] - win[1]) * scale - 1);
    $("w-window-title").textContent = `Window ${win[0]}–${win[2]} × ${win[1]}–${win[3]} (level ${win[4]}): ${n} polygons`;
    $("w-window-text").textContent = page().warnock_window_text(w);
    const counts = CLASSES.map(() => 0);
    let hiddenCount = 0;
    const rows = [];
    for (let i = 0; i < n; i++) {
      const [t, prim, c, hidden, front] = cls.subarray(i * CLASS, (i + 1) * CLASS);
      counts[c]++;
      hiddenCount += hidden;
      if (rows.length < MAX_ROWS && (c > 0 || n <= MAX_ROWS)) {
        const col = CLASSES[c][1];
        const note = front ? "the surrounder in front (nearest at the centre)" : hidden ? "culled: hidden behind it at every sample" : "";
        rows.push(`<tr><td>${t}</td><td>${prim}</td><td style="color:rgb(${col.join(",")});text-align:left">${CLASSES[c][0]}</td><td style="text-align:left">${note}</td></tr>`);
      }
    }
    $("w-class-counts").innerHTML = `<tr>${CLASSES.map(([name]) => `<th>${name}</th>`).join("")}<th>culled</th></tr>`
      + `<tr>${counts.map((c) => `<td>${c}</td>`).join("")}<td>${hiddenCount}</td></tr>`;
    const more = n > rows.length ? `<tr><td colspan="4" style="text-align:left">… ${n - rows.length} more (disjoint ones listed only in small windows)</td></tr>` : "";
    $("w-classes").innerHTML = `<tr><th>triangle</th><th>primitive</th><th>class</th><th>note</th></tr>${rows.join("")}${more}`;
    host.dataset.classes = String(n);
  };
  const draw = () => {
    const cls = page().warnock_classes(k), ids = page().warnock_ids(k);
    const data = new Uint8ClampedArray(side * side * 4);
    for (let p = 0; p < cls.length; p++) {
      const rule = cls[p] & 15, now = cls[p] >= 16;
      if (!rule) { data.set([0, 0, 0, 255], 4 * p); continue; }
      const base = idColour(ids[p]), tint = RULES[rule][1], a = now ? 0.75 : 0.4;
      data.set([0, 1, 2].map((i) => Math.round(base[i] * (1 - a) + tint[i] * a)).concat(255), 4 * p);
    }
    const small = document.createElement("canvas");
    small.width = side; small.height = side;
    small.getContext("2d").putImageData(new ImageData(data, side, side), 0, 0);
    const c = $("w-canvas"), g = c.getContext("2d"), scale = c.width / side;
    g.imageSmoothingEnabled = false;
    g.drawImage(small, 0, 0, c.width, c.height);
    // Each decided window outlined, so neighbours decided alike stay apart.
    const win = page().warnock_windows(k);
    g.strokeStyle = "rgba(255,255,255,0.35)";
    g.lineWidth = 1;
    for (let i = 0; i < win.length; i += 4) {
      if ((win[i + 2] - win[i]) * (win[i + 3] - win[i + 1]) === 1 && side > 32) continue;
      g.strokeRect(win[i] * scale + 0.5, win[i + 1] * scale + 0.5,
        (win[i + 2] - win[i]) * scale - 1, (win[i + 3] - win[i + 1]) * scale - 1);
    }
    // The windows this step cut: several polygons reach them, none settles them.
    const cuts = page().warnock_cuts(k);
    g.strokeStyle = "#e80";
    g.lineWidth = 2;
    for (let i = 0; i < cuts.length; i += 4) {
      g.strokeRect(cuts[i] * scale + 1, cuts[i + 1] * scale + 1,
        (cuts[i + 2] - cuts[i]) * scale - 2, (cuts[i + 3] - cuts[i + 1]) * scale - 2);
    }
    host.dataset.cuts = String(cuts.length / 4);
    drawWindow(g, scale);
    const rows = page().warnock_counts(k).split("\n").map((l) => l.split("\t"))
      .map(([r, n, px]) => `<tr><td>${r}</td><td style="text-align:right">${n}</td><td style="text-align:right">${px}</td></tr>`);
    $("w-counts").innerHTML = `<tr><th>decided by</th><th>windows</th><th>pixels</th></tr>${rows.join("")}`;
    $("w-label").textContent = `level ${k} of ${steps}`;
    $("w-scrub").value = String(k);
    host.dataset.step = String(k);
    host.dataset.steps = String(steps);
  };
  const go = (next) => { k = Math.max(0, Math.min(steps, next)); draw(); };
  $("w-back").addEventListener("click", () => go(k - 1));
  $("w-next").addEventListener("click", () => go(k + 1));
  $("w-scrub").addEventListener("input", () => go(Number($("w-scrub").value)));
  const choose = (x, y) => { pick = [x, y]; draw(); };
  $("w-canvas").addEventListener("click", (e) => {
    const c = $("w-canvas"), r = c.getBoundingClientRect();
    const x = Math.floor((e.clientX - r.left) / r.width * side), y = Math.floor((e.clientY - r.top) / r.height * side);
    choose(Math.max(0, Math.min(side - 1, x)), Math.max(0, Math.min(side - 1, y)));
  });
  const record = (size) => {
    side = size;
    pick = [Math.floor(side / 2), Math.floor(side / 2)];
    steps = page().warnock_trace(side);
    $("w-scrub").max = String(steps);
    go(Math.min(steps, 4));
  };
  return { record, go, choose };
}
