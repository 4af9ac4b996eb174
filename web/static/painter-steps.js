// The painter's step-through: Newell, Newell & Sancha's ordering replayed
// event by event from the trace hider-painter records
// (PainterOptions::trace). The pixels come from Page::painter_ids, which
// paints the pieces painted so far with the painter's own coverage rule;
// nothing here decides an order or a coverage.
const $ = (id) => document.getElementById(id);

const KIND_COLOUR = {
  test: "#2b6cb0", blocked: "#d22", move: "#e80", cycle: "#a3a",
  split: "#e80", culled: "#888", painted: "#0a0", none: "#444",
};

export function buildPainterSteps(app, idColour) {
  const host = document.createElement("div");
  host.id = "painter-steps";
  host.innerHTML = `
    <h2 id="z-painter">The painter, test by test</h2>
    <p>Newell, Newell &amp; Sancha's painter, one recorded event a step: the candidate P (the farthest
    piece not yet painted, <span style="color:#fff;background:#333">&nbsp;white&nbsp;</span>) compared with
    each piece Q it may hide (<span style="color:#2b6cb0">blue</span>), and the test that settled the pair:
    1 depth extents, 2 x extents, 3 y extents, 4 P behind Q's plane, 5 Q in front of P's plane,
    6 projections apart — or none (<span style="color:#d22">blocked</span>). A blocking Q is moved to
    the head of the list; blocked again, the two form a cycle, broken by a split
    (<span style="color:#e80">orange</span>: the halves). When every test passes, P is painted. The
    trace is recorded by the painter itself (<code>PainterOptions::trace</code>); the pixels are the
    pieces painted so far, and the last step is the painter's frame.</p>
    <div class="controls">
      <button id="p-back" title="event back">◀</button>
      <button id="p-play">play</button>
      <button id="p-next" title="event forward">▶</button>
      <button id="p-paint" title="to the next piece painted">next painted »</button>
      <input id="p-scrub" type="range" min="0" max="0" value="0" style="width: 20rem">
      <span id="p-label">—</span>
    </div>
    <div class="stage">
      <figure><canvas id="p-canvas" width="384" height="384" style="width:384px;height:384px"></canvas>
        <figcaption>pixels painted so far (false colour) with the step's pieces outlined</figcaption></figure>
      <div><p id="p-event" style="max-width:28rem;font-weight:bold"></p>
        <table id="p-counts" style="font-size:12px"></table></div>
    </div>`;
  $("steps-body").appendChild(host);
  const page = () => app.state.page;
  let side = 64, steps = 0, k = 0, timer = null;
  const outline = (g, id, scale, colour, width, dash) => {
    const pts = page().painter_outline(id);
    if (pts.length < 6) return;
    g.beginPath();
    for (let v = 0; v < pts.length; v += 2) g.lineTo(pts[v] * scale, pts[v + 1] * scale);
    g.closePath();
    g.setLineDash(dash);
    g.strokeStyle = colour;
    g.lineWidth = width;
    g.stroke();
    g.setLineDash([]);
  };
  const draw = () => {
    const ids = page().painter_ids(k);
    const data = new Uint8ClampedArray(side * side * 4);
    for (let p = 0; p < ids.length; p++) data.set([...idColour(ids[p]), 255], 4 * p);
    const small = document.createElement("canvas");
    small.width = side; small.height = side;
    small.getContext("2d").putImageData(new ImageData(data, side, side), 0, 0);
    const c = $("p-canvas"), g = c.getContext("2d"), scale = c.width / side;
    g.imageSmoothingEnabled = false;
    g.drawImage(small, 0, 0, c.width, c.height);
    const kind = page().painter_event_kind(k), [a, b, h] = page().painter_event_pieces(k);
    if (kind === "split") {
      outline(g, a, scale, "#fff", 1, [4, 4]);
      outline(g, b, scale, KIND_COLOUR.split, 3, []);
      outline(g, h, scale, KIND_COLOUR.split, 3, [6, 3]);
    } else {
      if (b >= 0) outline(g, b, scale, KIND_COLOUR[kind], 3, []);
      if (a >= 0) outline(g, a, scale, kind === "painted" ? KIND_COLOUR.painted : "#fff", 2, []);
    }
    $("p-event").textContent = page().painter_event_text(k);
    $("p-event").style.color = KIND_COLOUR[kind] === "#fff" ? "#000" : KIND_COLOUR[kind];
    $("p-label").textContent = `step ${k} of ${steps}`;
    $("p-scrub").value = String(k);
    host.dataset.step = String(k);
    host.dataset.steps = String(steps);
    host.dataset.kind = kind;
  };
  const go = (next) => { k = Math.max(0, Math.min(steps, next)); draw(); };
  const stop = () => { clearInterval(timer); timer = null; $("p-play").textContent = "play"; };
  $("p-back").addEventListener("click", () => { stop(); go(k - 1); });
  $("p-next").addEventListener("click", () => { stop(); go(k + 1); });
  $("p-paint").addEventListener("click", () => {
    stop();
    let n = k + 1;
    while (n < steps && page().painter_event_kind(n) !== "painted") n++;
    go(n);
  });
  $("p-scrub").addEventListener("input", () => { stop(); go(Number($("p-scrub").value)); });
  $("p-play").addEventListener("click", () => {
    if (timer) { stop(); return; }
    if (k >= steps) go(0);
    $("p-play").textContent = "pause";
    const every = Math.max(15, Math.min(400, 8000 / Math.max(1, steps)));
    timer = setInterval(() => { if (k >= steps) stop(); else go(k + 1); }, every);
  });
  const record = (size) => {
    stop();
    side = size;
    steps = page().painter_trace(side);
    $("p-scrub").max = String(steps);
    const rows = page().painter_test_counts().split("\n").filter((l) => l)
      .map((l) => l.split("\t")).map(([t, n]) => `<tr><td>${t}</td><td style="text-align:right">${n}</td></tr>`);
    $("p-counts").innerHTML = `<tr><th>which test settled a pair</th><th>pairs</th></tr>${rows.join("")}`;
    go(steps);
  };
  return { record, go };
}
