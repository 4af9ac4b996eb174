// Browser tests of the built page (web/dist, from web/build.sh) in
// Debian's Chromium, driven by playwright-core: the page's id buffers equal
// the `hider` command line's for every registered hider on three scenes,
// a dropped textured OBJ renders, no console error appears; screenshots go
// to web/test-output (look at them).
//
// Environment: CHROMIUM (default /usr/bin/chromium), HIDER_BIN (default
// target/debug/hider, built with `cargo build -p hider-cli`).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { readFileSync, writeFileSync, mkdtempSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { openPage, pick as pickScene, web, out } from "./support.js";

const root = join(web, "..");
const scratch = mkdtempSync(join(tmpdir(), "hider-web-"));
const hiderBin = process.env.HIDER_BIN || join(root, "target/debug/hider");
const SIZE = 48;

let page, base, close;
let problems = [];

before(async () => {
  ({ page, base, problems, close } = await openPage({ viewport: { width: 1400, height: 1100 } }));
});

after(async () => {
  await close?.();
});

test("the wasm module is served as application/wasm", async () => {
  const response = await fetch(`${base}pkg/hider_web_bg.wasm`);
  assert.equal(response.headers.get("content-type"), "application/wasm");
});

const pick = (choice) => pickScene(page, choice);

// Every hider's ids from the page at SIZE x SIZE with a turned camera,
// and the camera's command-line flags.
async function pageIds() {
  return page.evaluate((size) => {
    const { state } = window.hiderApp;
    state.page.set_size(size, size);
    state.page.set_orbit(0.5, 0.3, 0.1, 0.02, -0.01);
    const ids = {};
    for (const name of state.hiders) {
      const frame = state.page.render(name);
      ids[name] = Array.from(frame.ids());
      frame.free();
    }
    const flags = state.page.camera_flags();
    // Back to the page's own view.
    state.page.set_size(state.size, state.size);
    return { ids, flags, obj: state.page.obj_text() };
  }, SIZE);
}

function cliIds(model, name, flags) {
  const ids = join(scratch, `${name}.ids`);
  execFileSync(hiderBin, ["render", model, "--size", String(SIZE), "--algo", name,
    "--ids-out", ids, "-o", join(scratch, `${name}.png`), ...flags], { stdio: ["ignore", "ignore", "pipe"] });
  const bytes = readFileSync(ids);
  return Array.from(new Int32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4));
}

async function compareWithCli(choice, model, shot) {
  await pick(choice);
  await page.screenshot({ path: join(out, shot) });
  const { ids, flags, obj } = await pageIds();
  if (model === null) {
    model = join(scratch, "scene.obj");
    writeFileSync(model, obj);
  }
  const names = Object.keys(ids);
  assert.ok(names.length >= 15, `only ${names.length} hiders`);
  for (const name of names) {
    const native = cliIds(model, name, flags);
    assert.equal(ids[name].length, native.length, name);
    const differing = ids[name].filter((id, k) => id !== native[k]).length;
    assert.equal(differing, 0, `${choice}: ${name}: ${differing} pixels differ from hider render`);
    assert.ok(native.some((id) => id >= 0), `${choice}: ${name}: nothing covered`);
  }
}

test("the spider's ids equal the command line's for every hider", async () => {
  await compareWithCli("bundled|spider", join(root, "assets/spider/spider.obj"), "compare-spider.png");
});

test("gen:intersecting's ids equal the command line's for every hider", async () => {
  await compareWithCli("spec|gen:intersecting", "gen:intersecting", "compare-intersecting.png");
});

test("a hard case's ids equal the command line's for every hider", async () => {
  await compareWithCli("spec|hard:cyclic_overlap", null, "compare-cyclic-overlap.png");
});

test("the error overlay marks the naive painter's wrong pixels on gen:intersecting", async () => {
  await pick("spec|gen:intersecting");
  const wrong = await page.evaluate(() => window.hiderApp.state.results.get("painter-naive").wrong);
  assert.ok(wrong > 0, "the naive painter gets an intersection wrong");
  await page.check("#overlay");
  await page.screenshot({ path: join(out, "compare-overlay.png") });
  const red = await page.evaluate(() => {
    const c = document.querySelector('.cell[data-hider="painter-naive"] canvas');
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let k = 0; k < d.length; k += 4) if (d[k] === 255 && d[k + 1] === 0 && d[k + 2] === 0) n++;
    return n;
  });
  assert.ok(red > 0, "no overlay pixel drawn");
  await page.uncheck("#overlay");
});

test("a dropped OBJ with its MTL and texture renders textured", async () => {
  const before = await page.evaluate(() => document.body.dataset.gridDone || "");
  await page.setInputFiles("#files", ["checker_plane.obj", "checker_plane.mtl", "checker.png"]
    .map((f) => join(root, "assets", f)));
  await page.waitForFunction((b) => (document.body.dataset.gridDone || "") !== b, before, { timeout: 120000 });
  const { warnings, colours } = await page.evaluate(() => {
    const c = document.getElementById("view");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    const seen = new Set();
    for (let k = 0; k < d.length; k += 4) seen.add((d[k] << 16) | (d[k + 1] << 8) | d[k + 2]);
    return { warnings: window.hiderApp.state.page.warnings(), colours: seen.size };
  });
  await page.screenshot({ path: join(out, "compare-dropped-checker.png") });
  assert.equal(warnings, "", "the loader warned");
  assert.ok(colours > 20, `only ${colours} colours: the texture did not show`);
});

test("orbiting with the mouse and keys changes the view", async () => {
  await pick("bundled|cube");
  const box = await page.locator("#view").boundingBox();
  const yaw0 = await page.evaluate(() => window.hiderApp.state.orbit.yaw);
  await page.mouse.move(box.x + 100, box.y + 100);
  await page.mouse.down();
  await page.mouse.move(box.x + 160, box.y + 120, { steps: 4 });
  await page.mouse.up();
  await page.keyboard.press("ArrowUp");
  await page.keyboard.press("-");
  const orbit = await page.evaluate(() => window.hiderApp.state.orbit);
  assert.notEqual(orbit.yaw, yaw0);
  assert.ok(orbit.pitch > 0);
  assert.ok(orbit.zoom > 0);
  await page.mouse.move(box.x + 100, box.y + 100);
  await page.mouse.wheel(0, -300);
  await page.waitForFunction((z) => window.hiderApp.state.orbit.zoom < z, orbit.zoom);
  await page.screenshot({ path: join(out, "compare-cube-orbited.png") });
});

test("the z-buffer step-through ends on the z-buffer's frame", async () => {
  await pick("spec|gen:cyclic");
  await page.click('.tab[data-view="steps"]');
  await page.selectOption("#z-size", "64");
  const result = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const body = document.getElementById("steps-body");
    const steps = Number(body.dataset.steps);
    const last = state.page.zbuffer_step(steps);
    const first = state.page.zbuffer_step(0);
    state.page.set_size(64, 64);
    const frame = state.page.render("zbuffer");
    const same = Array.from(last.ids()).every((id, k) => id === frame.ids()[k]);
    const empty = Array.from(first.ids()).every((id) => id === -1);
    state.page.set_size(state.size, state.size);
    return { steps, same, empty, shown: Number(body.dataset.step) };
  });
  assert.ok(result.steps >= 3, `${result.steps} steps`);
  assert.equal(result.shown, result.steps, "the view opens on the last step");
  assert.ok(result.same, "the last step differs from the z-buffer's frame");
  assert.ok(result.empty, "step 0 is not empty");
  await page.screenshot({ path: join(out, "steps-zbuffer-last.png") });
  await page.click("#z-back");
  await page.screenshot({ path: join(out, "steps-zbuffer-back.png") });
  assert.equal(await page.evaluate(() => document.getElementById("steps-body").dataset.step), String(result.steps - 1));
  // The scanline sweep: all rows give the scanline's frame.
  const sweep = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const all = state.page.scanline_ids(64);
    state.page.set_size(64, 64);
    const frame = state.page.render("scanline");
    const same = Array.from(all).every((id, k) => id === frame.ids()[k]);
    state.page.set_size(state.size, state.size);
    return { same, row: Number(document.getElementById("steps-body").dataset.row) };
  });
  assert.ok(sweep.same, "the full sweep differs from the scanline's frame");
  assert.equal(sweep.row, 32, "the sweep view opens half-way");
  await page.locator("#s-ids").scrollIntoViewIfNeeded();
  await page.screenshot({ path: join(out, "steps-scanline.png"), fullPage: true });
  // The painter's trace: its last step is the page's painter frame, the
  // cyclic triple is blocked and split, step 0 is empty.
  const painter = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const host = document.getElementById("painter-steps");
    const steps = Number(host.dataset.steps);
    const last = state.page.painter_ids(steps);
    state.page.set_size(64, 64);
    const frame = state.page.render("painter").ids();
    state.page.set_size(state.size, state.size);
    const kinds = [];
    for (let k = 1; k <= steps; k++) kinds.push(state.page.painter_event_kind(k));
    return {
      steps, kinds, shown: Number(host.dataset.step),
      same: Array.from(last).every((id, k) => id === frame[k]),
      covered: Array.from(frame).filter((id) => id >= 0).length,
      empty: Array.from(state.page.painter_ids(0)).every((id) => id === -1),
      counts: state.page.painter_test_counts(),
    };
  });
  assert.equal(painter.shown, painter.steps, "the painter view opens on its last step");
  assert.ok(painter.covered > 0, "the painter's frame is empty");
  assert.ok(painter.same, "the painter trace's last step differs from the page's painter frame");
  assert.ok(painter.empty, "the painter's step 0 is not empty");
  for (const kind of ["test", "blocked", "split", "painted"]) {
    assert.ok(painter.kinds.includes(kind), `no ${kind} event in ${painter.kinds.join(" ")}`);
  }
  assert.match(painter.counts, /test \d/, "the table of deciding tests is empty");
  // Step to the first split: the view shows it in words.
  const split = painter.kinds.indexOf("split") + 1;
  await page.evaluate((k) => window.hiderApp.steps().painter.go(k), split);
  assert.equal(await page.evaluate(() => document.getElementById("painter-steps").dataset.kind), "split");
  assert.match(await page.textContent("#p-event"), /split into pieces \d+ and \d+/);
  await page.locator("#painter-steps").screenshot({ path: join(out, "steps-painter-split.png") });
  // "next painted" lands on a painted event.
  await page.click("#p-paint");
  assert.equal(await page.evaluate(() => document.getElementById("painter-steps").dataset.kind), "painted");
  await page.screenshot({ path: join(out, "steps-painter-painted.png") });
  // Warnock's windows: at the last level they tile the frame, and the ids
  // are the page's warnock frame; level 0 decides nothing on this scene.
  const warnock = await page.evaluate(() => {
    const { state } = window.hiderApp;
    const steps = Number(document.getElementById("warnock-steps").dataset.steps);
    const cls = state.page.warnock_classes(steps), ids = state.page.warnock_ids(steps);
    state.page.set_size(64, 64);
    const frame = state.page.render("warnock").ids();
    state.page.set_size(state.size, state.size);
    return {
      steps,
      tiled: Array.from(cls).every((c) => (c & 15) > 0),
      same: Array.from(ids).every((id, k) => id === frame[k]),
      none: Array.from(state.page.warnock_classes(0)).every((c) => c === 0),
      rootCut: state.page.warnock_cuts(1).length === 4,
      lastCuts: state.page.warnock_cuts(steps).length,
    };
  });
  assert.ok(warnock.steps > 2, `${warnock.steps} levels`);
  assert.ok(warnock.tiled, "Warnock's windows at the last level leave pixels undecided");
  assert.ok(warnock.same, "Warnock's last level differs from the page's warnock frame");
  assert.ok(warnock.none, "level 0 shows decided windows");
  assert.ok(warnock.rootCut, "the whole window is not the one cut at step 1");
  assert.equal(warnock.lastCuts, 0, "windows are cut at the last level");
  await page.locator("#warnock-steps").screenshot({ path: join(out, "steps-warnock.png") });
  await page.click('.tab[data-view="compare"]');
});

test("frame time of the spider at 512 x 512 with the z-buffer (measured, reported)", async () => {
  await pick("bundled|spider");
  const ms = await page.evaluate(() => {
    const { state, renderMain } = window.hiderApp;
    state.size = 512;
    state.page.set_size(512, 512);
    state.main = "zbuffer";
    const median = (f) => {
      const times = [];
      for (let k = 0; k < 60; k++) {
        state.orbit.yaw = k * 0.05;
        const t0 = performance.now();
        f();
        times.push(performance.now() - t0);
      }
      times.sort((a, b) => a - b);
      return times[30];
    };
    // The page's frame: render, colour pass, copy out, draw on the canvas.
    const frame = median(renderMain);
    // The hider's front end and render alone (what `hider render --repeat`
    // times), at the rest orbit as the command line's fit camera.
    // Per call, median and minimum of 200, as `hider render --repeat`
    // reports them (the minimum is the least disturbed by other load).
    const bare = {};
    for (const name of ["zbuffer", "zbuffer-tiled"]) {
      state.page.set_orbit(0, 0, 0, 0, 0);
      const times = [];
      for (let k = 0; k < 200; k++) {
        const t0 = performance.now();
        state.page.render_bare(name);
        times.push(performance.now() - t0);
      }
      times.sort((a, b) => a - b);
      bare[name] = { median: times[100], min: times[0] };
    }
    return { frame, bare };
  });
  writeFileSync(join(out, "frame-time.json"), JSON.stringify(ms, null, 1));
  console.log(`spider 512x512 in the page: frame (zbuffer, with colour and drawing) median ${ms.frame.toFixed(2)} ms; ` +
    `render_scene alone (median, min): ${JSON.stringify(ms.bare)}`);
  await page.screenshot({ path: join(out, "compare-spider-512.png") });
});

test("no console error appeared", () => {
  assert.deepEqual(problems, []);
});
