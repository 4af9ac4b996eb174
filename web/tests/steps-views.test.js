// Browser tests of the scanline and Warnock step-through views (issue 41):
// the scanline's edge table, active edge list and runs are shown as the
// trace holds them and the last row gives the scanline's frame; a click on
// a Warnock window lists its polygons' classes; no console error.
// Screenshots go to web/test-output (look at them).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { join } from "node:path";
import { openPage, out } from "./support.js";

const EDGE = 11, ACTIVE = 3, SPAN = 9, CLASS = 5;

let page, close;
let problems = [];

before(async () => {
  ({ page, problems, close } = await openPage({ viewport: { width: 1500, height: 1100 } }));
  await page.selectOption("#scene", "spec|gen:cyclic");
  await page.waitForFunction(() => !document.querySelector(".cell.pending"), null, { timeout: 300000 });
  await page.click('.tab[data-view="steps"]');
  await page.selectOption("#z-size", "64");
});

after(async () => {
  await close?.();
});

test("the scanline view shows the trace's active edge list, runs and edge table", async () => {
  // Three rows the scene crosses: its first, middle and last (steps count
  // rows swept, so row r is shown at step r + 1).
  const crossed = await page.evaluate(() => {
    const edges = window.hiderApp.state.page.scanline_edges();
    let lo = 1e9, hi = -1;
    for (let i = 0; i < edges.length / 11; i++) { lo = Math.min(lo, edges[i * 11]); hi = Math.max(hi, edges[i * 11 + 1]); }
    return [lo, hi];
  });
  assert.ok(crossed[1] >= crossed[0], "no edge in the table");
  const rows = [];
  for (const row of [crossed[0] + 1, Math.floor((crossed[0] + crossed[1]) / 2) + 1, crossed[1] + 1]) {
    await page.evaluate((r) => window.hiderApp.steps().scanline.go(r), row);
    rows.push(await page.evaluate((r) => {
      const { state } = window.hiderApp;
      const host = document.getElementById("scanline-steps");
      const cur = r - 1;
      const edges = state.page.scanline_edges(), active = state.page.scanline_active(cur);
      // The edges of the table whose rows hold this one (from the table's
      // own numbers), against the list the view shows.
      let live = 0, bucket = 0;
      for (let i = 0; i < edges.length / 11; i++) {
        if (edges[i * 11] <= cur && cur <= edges[i * 11 + 1]) live++;
        if (edges[i * 11] === cur) bucket++;
      }
      const xs = [];
      for (let k = 0; k < active.length / 3; k++) xs.push(active[k * 3 + 1]);
      return {
        shownAel: document.querySelectorAll("#s-ael tr").length - 1,
        dataAel: Number(host.dataset.ael),
        traceAel: active.length / 3,
        live,
        sorted: xs.every((x, k) => k === 0 || xs[k - 1] <= x),
        shownRuns: document.querySelectorAll("#s-spans tr").length - 1,
        traceRuns: state.page.scanline_spans(cur).length / 9,
        shownBucket: Number(host.dataset.bucket),
        bucket,
        etRows: document.querySelectorAll("#s-et tr").length - 1,
        edges: edges.length / 11,
      };
    }, row));
  }
  for (const r of rows) {
    assert.ok(r.traceAel > 0, `an empty active edge list: ${JSON.stringify(r)}`);
    assert.equal(r.shownAel, r.traceAel, "the active edge list table is not the trace's");
    assert.equal(r.dataAel, r.traceAel);
    assert.equal(r.traceAel, r.live, "the active edges are not the table's edges spanning the row");
    assert.ok(r.sorted, "the active edge list is not sorted by x");
    assert.equal(r.shownRuns, r.traceRuns, "the runs table is not the trace's");
    assert.equal(r.shownBucket, r.bucket, "the highlighted bucket is not the row's");
    assert.equal(r.etRows, r.edges, "the edge table does not list every edge");
  }
  // Selecting a run highlights the edges bounding its span.
  const mid = Math.floor((crossed[0] + crossed[1]) / 2);
  await page.evaluate((r) => window.hiderApp.steps().scanline.go(r), mid + 1);
  const runs = await page.evaluate((r) => window.hiderApp.state.page.scanline_spans(r), mid);
  let pick = 0;
  for (let k = 0; k < runs.length / SPAN; k++) if (runs[k * SPAN + 6] > 0) { pick = k; break; }
  await page.click(`#s-spans tr[data-k="${pick}"]`);
  const selected = await page.evaluate(() => document.querySelectorAll("#s-ael tr.sel").length);
  const bounding = await page.evaluate(([r, k]) => window.hiderApp.state.page.scanline_span_edges(r, k).length, [mid, pick]);
  assert.ok(bounding > 0, "the selected run's span names no edge");
  assert.equal(selected, bounding, "the bounding edges are not highlighted in the list");
  assert.match(await page.textContent("#s-why"), /span/);
  await page.locator("#scanline-steps").screenshot({ path: join(out, "steps-scanline-tables.png") });
  await page.evaluate(() => window.hiderApp.steps().scanline.select(0));
  // The last row: all runs together are the page's scanline frame.
  await page.evaluate(() => window.hiderApp.steps().scanline.go(64));
  const last = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const ids = state.page.scanline_ids(64);
    state.page.set_size(64, 64);
    const frame = state.page.render("scanline").ids();
    state.page.set_size(state.size, state.size);
    return {
      same: Array.from(ids).every((id, k) => id === frame[k]),
      covered: Array.from(frame).filter((id) => id >= 0).length,
      label: document.getElementById("s-label").textContent,
    };
  });
  assert.ok(last.covered > 0);
  assert.ok(last.same, "the last row's image differs from the page's scanline frame");
  assert.match(last.label, /row 64 of 64/);
});

test("a click on a Warnock window lists each polygon's class", async () => {
  // The first step past the whole image with a window classified against
  // two polygons or more, and a pixel of it.
  const [step, px, py] = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const steps = Number(document.getElementById("warnock-steps").dataset.steps);
    for (let k = 2; k <= steps; k++) {
      for (let y = 0; y < 64; y++) {
        for (let x = 0; x < 64; x++) {
          const w = state.page.warnock_window_at(k, x, y);
          const win = state.page.warnock_window(w), cls = state.page.warnock_window_classes(w);
          let live = 0;
          for (let i = 0; i < cls.length / 5; i++) live += cls[i * 5 + 2] > 0 ? 1 : 0;
          if (win[5] === 0 && live >= 2) return [k, x, y];
        }
      }
    }
    return [-1, -1, -1];
  });
  assert.ok(step >= 2, "no classified window with two polygons below the whole image");
  await page.evaluate((k) => window.hiderApp.steps().warnock.go(k), step);
  const canvas = page.locator("#w-canvas");
  await canvas.scrollIntoViewIfNeeded();
  const box = await canvas.boundingBox();
  await page.mouse.click(box.x + box.width * (px + 0.5) / 64, box.y + box.height * (py + 0.5) / 64);
  const shown = await page.evaluate(([x, y, k]) => {
    const { state } = window.hiderApp;
    const host = document.getElementById("warnock-steps");
    const w = Number(host.dataset.window);
    const win = state.page.warnock_window(w), cls = state.page.warnock_window_classes(w);
    return {
      w,
      level: win[4],
      holds: win[0] <= x && x < win[2] && win[1] <= y && y < win[3],
      classes: cls.length / 5,
      listed: Number(host.dataset.classes),
      rows: document.querySelectorAll("#w-classes tr").length - 1,
      kinds: new Set(Array.from({ length: cls.length / 5 }, (_, i) => cls[i * 5 + 2])).size,
      text: document.getElementById("w-window-text").textContent,
      expect: state.page.warnock_window_at(k, x, y),
    };
  }, [px, py, step]);
  assert.ok(shown.w >= 0, "no window selected");
  assert.equal(shown.w, shown.expect, "the clicked window is not the one at the clicked pixel");
  assert.ok(shown.holds, "the window does not hold the clicked pixel");
  assert.ok(shown.level <= step - 1, `level ${shown.level} at step ${step}`);
  assert.ok(shown.classes > 0, "no classes recorded for the window");
  assert.equal(shown.listed, shown.classes);
  assert.ok(shown.rows > 0, "the class table is empty");
  assert.match(shown.text, /window .*level/);
  assert.match(shown.text, /subdivided|decided/);
  await page.locator("#warnock-steps").screenshot({ path: join(out, "steps-warnock-classes.png") });
  // Step 1 on the whole image: every triangle of the scene is classified.
  await page.evaluate(() => window.hiderApp.steps().warnock.go(1));
  const root = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const w = Number(document.getElementById("warnock-steps").dataset.window);
    return { level: state.page.warnock_window(w)[4], classes: state.page.warnock_window_classes(w).length / 5, tris: state.page.triangles() };
  });
  assert.equal(root.level, 0);
  assert.equal(root.classes, root.tris, "the whole image does not classify every triangle");
});

test("on two piercing triangles the sweep shows a split span and Warnock a surrounder in front", async () => {
  await page.click('.tab[data-view="compare"]');
  await page.selectOption("#scene", "spec|gen:intersecting");
  await page.waitForFunction(() => !document.querySelector(".cell.pending"), null, { timeout: 300000 });
  await page.click('.tab[data-view="steps"]');
  // The first row with a run split where the two depths cross.
  const found = await page.evaluate(() => {
    const { state } = window.hiderApp;
    for (let r = 0; r < 64; r++) {
      const runs = state.page.scanline_spans(r);
      for (let k = 0; k < runs.length / 9; k++) if (runs[k * 9 + 3] === 2) return [r, k];
    }
    return [-1, -1];
  });
  assert.ok(found[0] >= 0, "no split run on the piercing pair");
  await page.evaluate(([r, k]) => { const s = window.hiderApp.steps().scanline; s.go(r + 1); s.select(k); }, found);
  assert.match(await page.textContent("#s-why"), /split where two depths cross/);
  await page.locator("#scanline-steps").screenshot({ path: join(out, "steps-scanline-split.png") });
  // Warnock: a window decided by a surrounder in front, its hidden polygon
  // listed as culled.
  const pick = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const steps = Number(document.getElementById("warnock-steps").dataset.steps);
    for (let k = 1; k <= steps; k++) {
      for (let y = 0; y < 64; y += 2) {
        for (let x = 0; x < 64; x += 2) {
          const w = state.page.warnock_window_at(k, x, y), win = state.page.warnock_window(w);
          if (win[4] === k - 1 && win[6] === 4 && win[10] > 0) return [k, x, y];
        }
      }
    }
    return [-1, -1, -1];
  });
  assert.ok(pick[0] > 0, "no window decided by a surrounder in front");
  await page.evaluate(([k, x, y]) => { const w = window.hiderApp.steps().warnock; w.go(k); w.choose(x, y); }, pick);
  assert.match(await page.textContent("#w-window-text"), /surrounding polygon in front/);
  assert.match(await page.textContent("#w-classes"), /culled/);
  await page.locator("#warnock-steps").screenshot({ path: join(out, "steps-warnock-front.png") });
});

test("no console error appeared", () => {
  assert.deepEqual(problems, []);
});
