// The scanline sweep, row by row, with its data structures: the edge table,
// the active edge list of the current row and the row's runs, all read from
// the trace the scanline records itself (ScanlineOptions::record_spans).
// Nothing here walks edges or compares depths: it draws what the trace holds.
const $ = (id) => document.getElementById(id);

// Strides of the flat arrays the page's handle returns (scanline_steps.rs).
const EDGE = 11, ACTIVE = 3, SPAN = 9;
const HOW = [null, ["whole span", [43, 108, 176]], ["split at a depth crossing", [238, 136, 0]],
  ["one-row depth buffer", [170, 51, 170]]];
const WHY = [null,
  "nearest at both ends of the span: one depth comparison at the span's ends decides it whole",
  "a piece of a span split where two depths cross (the comparison flips inside the span)",
  "the span split too often: the one-row depth buffer fallback decided it pixel by pixel"];
const VIEW = 384;
const fmt = (v, d = 2) => Number(v).toFixed(d);

export function buildScanlineSteps(app, idColour) {
  const body = $("steps-body");
  const host = document.createElement("div");
  host.id = "scanline-steps";
  host.innerHTML = `
    <h2>The scanline sweep, row by row</h2>
    <p>Watkins' scanline algorithm walks the image one row at a time. The <b>edge table</b> holds every
    non-horizontal edge in the bucket of the first row whose centre it crosses, with its x there and the
    step <i>dx/dy</i> it moves by per row. At each row the edges of its bucket join the <b>active edge
    list</b>; each active edge gives its polygon's first (left edge) or last (right edge) covered pixel on the
    row, and leaves after its last row. Between two consecutive crossings the same polygons cover every
    pixel: a <b>span</b>, decided once by comparing depths at its ends, or split where two depths cross.
    Step or scrub the rows; click a run in the table to see the edges that bound its span (yellow). Runs of
    the current row: <span style="color:#2b6cb0">blue</span> whole spans, <span style="color:#e80">orange</span>
    split pieces, <span style="color:#a3a">purple</span> the one-row depth buffer fallback. All is recorded by
    the scanline itself (<code>ScanlineOptions::record_spans</code>); all rows together are its frame.</p>
    <div class="controls">
      <button id="s-back" title="row back">◀</button>
      <button id="s-play">play</button>
      <button id="s-next" title="row forward">▶</button>
      <input id="s-scrub" type="range" min="0" max="0" value="0" style="width: 20rem">
      <span id="s-label">—</span>
    </div>
    <div class="stage">
      <figure><canvas id="s-ids" width="${VIEW}" height="${VIEW}" style="width:${VIEW}px;height:${VIEW}px"></canvas>
        <figcaption>rows swept so far (false colour), the current row's runs by how they were decided,<br>
        its active edges (cyan left, pink right) and their crossings</figcaption></figure>
      <div class="s-tables">
        <h3 id="s-ael-title">Active edge list</h3>
        <table id="s-ael" class="data"></table>
        <h3 id="s-spans-title">Runs of the row</h3>
        <table id="s-spans" class="data"></table>
        <p id="s-why" class="hint"></p>
      </div>
      <div class="s-tables">
        <h3 id="s-et-title">Edge table</h3>
        <div id="s-et-box" style="max-height:${VIEW}px;overflow:auto"><table id="s-et" class="data"></table></div>
      </div>
    </div>`;
  body.appendChild(host);
  const page = () => app.state.page;
  let side = 64, rows = 0, row = 0, edges = [], selected = 0, timer = null;

  // The edge table, built once per recording: one line per edge, grouped by
  // bucket (first row), the current row's bucket highlighted at each step.
  const buildEdgeTable = () => {
    const lines = [];
    let buckets = 0, last = -1;
    for (let i = 0; i < edges.length / EDGE; i++) {
      const e = edges.subarray(i * EDGE, (i + 1) * EDGE);
      if (e[0] !== last) { buckets++; last = e[0]; }
      lines.push(`<tr data-b="${e[0]}" data-e="${i}"><td>${e[0]}</td><td>${i}</td><td>${e[2]}</td>`
        + `<td>${e[4] ? "right" : "left"}</td><td>${e[0]}–${e[1]}</td><td>${fmt(e[5])}</td><td>${fmt(e[6], 3)}</td></tr>`);
    }
    $("s-et").innerHTML = `<tr><th>bucket (row)</th><th>edge</th><th>triangle</th><th>side</th><th>rows</th>`
      + `<th>x at top</th><th>dx/dy</th></tr>${lines.join("")}`;
    $("s-et-title").textContent = `Edge table: ${edges.length / EDGE} edges in ${buckets} buckets`;
  };

  const draw = () => {
    const cur = row - 1;
    const ids = page().scanline_ids(row), how = page().scanline_how(row);
    const data = new Uint8ClampedArray(side * side * 4);
    for (let p = 0; p < ids.length; p++) {
      const tint = how[p] ? HOW[how[p]][1] : idColour(ids[p]);
      data.set([...tint, 255], 4 * p);
    }
    const small = document.createElement("canvas");
    small.width = side; small.height = side;
    small.getContext("2d").putImageData(new ImageData(data, side, side), 0, 0);
    const c = $("s-ids"), g = c.getContext("2d"), s = VIEW / side;
    c.width = VIEW; c.height = VIEW;
    g.imageSmoothingEnabled = false;
    g.drawImage(small, 0, 0, VIEW, VIEW);
    const active = cur >= 0 ? page().scanline_active(cur) : new Float64Array(0);
    const spans = cur >= 0 ? page().scanline_spans(cur) : new Float64Array(0);
    const nSpans = spans.length / SPAN;
    if (selected >= nSpans) selected = 0;
    const bounding = new Set(cur >= 0 && nSpans ? Array.from(page().scanline_span_edges(cur, selected)) : []);
    if (cur >= 0) {
      // The current row, outlined across the image.
      g.strokeStyle = "rgba(255,255,255,0.8)";
      g.lineWidth = 1;
      g.strokeRect(0.5, cur * s + 0.5, VIEW - 1, s - 1);
      // Each active edge as a segment, its crossing of the row centre dotted.
      for (let k = 0; k < active.length / ACTIVE; k++) {
        const i = active[k * ACTIVE], x = active[k * ACTIVE + 1];
        const e = edges.subarray(i * EDGE, (i + 1) * EDGE);
        const mine = bounding.has(i);
        g.strokeStyle = mine ? "#ffe000" : e[4] ? "rgba(255,120,200,0.8)" : "rgba(90,220,255,0.8)";
        g.lineWidth = mine ? 3 : 1;
        g.beginPath();
        g.moveTo(e[7] * s, e[8] * s);
        g.lineTo(e[9] * s, e[10] * s);
        g.stroke();
        g.fillStyle = g.strokeStyle;
        g.beginPath();
        g.arc(x * s, (cur + 0.5) * s, mine ? 4 : 2.5, 0, 2 * Math.PI);
        g.fill();
      }
      if (nSpans) {
        const r = spans.subarray(selected * SPAN, (selected + 1) * SPAN);
        g.strokeStyle = "#ffe000";
        g.lineWidth = 2;
        g.strokeRect(r[6] * s + 1, cur * s - 2, (r[7] - r[6] + 1) * s - 2, s + 4);
      }
    }
    // The active edge list, sorted by x.
    const ael = [];
    for (let k = 0; k < active.length / ACTIVE; k++) {
      const [i, x, bound] = active.subarray(k * ACTIVE, (k + 1) * ACTIVE);
      const e = edges.subarray(i * EDGE, (i + 1) * EDGE);
      ael.push(`<tr${bounding.has(i) ? ' class="sel"' : ""}><td>${i}</td><td>${e[2]}</td><td>${e[4] ? "right" : "left"}</td>`
        + `<td>${fmt(x)}</td><td>${bound}</td><td>${fmt(e[6], 3)}</td><td>${e[0]}–${e[1]}</td></tr>`);
    }
    $("s-ael").innerHTML = `<tr><th>edge</th><th>triangle</th><th>side</th><th>x at row</th>`
      + `<th>${"first / last column"}</th><th>dx/dy</th><th>rows</th></tr>${ael.join("")}`;
    $("s-ael-title").textContent = cur >= 0
      ? `Active edge list at row ${cur}: ${active.length / ACTIVE} edges, sorted by x` : "Active edge list";
    host.dataset.ael = String(active.length / ACTIVE);
    // The row's runs.
    const runs = [];
    for (let k = 0; k < nSpans; k++) {
      const r = spans.subarray(k * SPAN, (k + 1) * SPAN);
      const [r0, g0, b0] = HOW[r[3]][1];
      runs.push(`<tr data-k="${k}"${k === selected ? ' class="sel"' : ""}><td>${r[0]}–${r[1]}</td><td>${r[2]}</td>`
        + `<td>${fmt(r[4], 5)}</td><td>${fmt(r[5], 5)}</td><td style="color:rgb(${r0},${g0},${b0})">${HOW[r[3]][0]}</td>`
        + `<td>${r[6]}–${r[7]}</td><td>${r[8]}</td></tr>`);
    }
    $("s-spans").innerHTML = `<tr><th>columns</th><th>triangle</th><th>depth at first</th><th>depth at last</th>`
      + `<th>decided</th><th>span</th><th>polygons</th></tr>${runs.join("")}`;
    $("s-spans-title").textContent = cur >= 0 ? `Runs of row ${cur}: ${nSpans}` : "Runs of the row";
    $("s-why").textContent = nSpans ? `Run ${selected}: ${WHY[spans[selected * SPAN + 3]]}.` : "";
    host.dataset.spans = String(nSpans);
    // The edge table: the current row's bucket highlighted and scrolled to.
    for (const tr of $("s-et").querySelectorAll("tr.cur")) tr.classList.remove("cur");
    const bucket = $("s-et").querySelectorAll(`tr[data-b="${cur}"]`);
    for (const tr of bucket) tr.classList.add("cur");
    if (bucket.length) $("s-et-box").scrollTop = bucket[0].offsetTop - 24;
    host.dataset.bucket = String(bucket.length);
    $("s-label").textContent = `row ${row} of ${rows}` + (cur >= 0 ? ` (showing row ${cur}; ${bucket.length} edges start here)` : "");
    $("s-scrub").value = String(row);
    body.dataset.row = String(row);
  };
  const go = (next) => { row = Math.max(0, Math.min(rows, next)); selected = 0; draw(); };
  const stop = () => { clearInterval(timer); timer = null; $("s-play").textContent = "play"; };
  $("s-back").addEventListener("click", () => { stop(); go(row - 1); });
  $("s-next").addEventListener("click", () => { stop(); go(row + 1); });
  $("s-scrub").addEventListener("input", () => { stop(); go(Number($("s-scrub").value)); });
  $("s-play").addEventListener("click", () => {
    if (timer) { stop(); return; }
    if (row >= rows) go(0);
    $("s-play").textContent = "pause";
    timer = setInterval(() => { if (row >= rows) stop(); else go(row + 1); }, Math.max(40, 4000 / Math.max(1, rows)));
  });
  $("s-spans").addEventListener("click", (e) => {
    const tr = e.target.closest("tr[data-k]");
    if (tr) { selected = Number(tr.dataset.k); draw(); }
  });
  const select = (k) => { selected = k; draw(); };
  const record = (size) => {
    stop();
    side = size;
    rows = page().scanline_trace(side);
    edges = page().scanline_edges();
    buildEdgeTable();
    $("s-scrub").max = String(rows);
    go(Math.floor(rows / 2));
  };
  return { record, go, select };
}
