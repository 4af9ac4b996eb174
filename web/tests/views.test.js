// Browser tests of the page's A-buffer inspector, depth-precision and
// Y-buffer views and of its touch gestures, on the built page (web/dist)
// in Debian's Chromium via playwright-core. Screenshots go to
// web/test-output (look at them).
//
// Environment: CHROMIUM (default /usr/bin/chromium).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { join } from "node:path";
import { openPage, pick as pickScene, out } from "./support.js";


let page, close;
let problems = [];

before(async () => {
  ({ page, problems, close } = await openPage({ hasTouch: true }));
});

after(async () => {
  await close?.();
});

const pick = (choice) => pickScene(page, choice);

test("hovering a pixel of the A-buffer inspector lists its fragments and the frame's colour", async () => {
  await pick("spec|gen:intersecting");
  await page.click('.tab[data-view="steps"]');
  await page.waitForFunction(() => document.getElementById("inspect-body").dataset.recorded === "32");
  const image = page.locator("#i-image");
  await image.scrollIntoViewIfNeeded();
  const box = await image.boundingBox();
  // A pixel on the intersection line: several fragments.
  // The pixel with the longest list, found through the page's own inspector.
  const target = await page.evaluate(() => {
    const host = document.getElementById("inspect-body");
    let best = null;
    for (let y = 0; y < 32; y++) {
      for (let x = 0; x < 32; x++) {
        window.hiderApp.extras().inspect.inspect(x, y);
        const n = Number(host.dataset.fragments);
        if (!best || n > best.n) best = { x, y, n };
      }
    }
    return best;
  });
  assert.ok(target.n >= 2, `no pixel with two fragments (${target.n})`);
  await page.mouse.move(box.x + (target.x + 0.5) * box.width / 32, box.y + (target.y + 0.5) * box.height / 32);
  await page.waitForFunction((t) => document.getElementById("inspect-body").dataset.pixel === `${t.x},${t.y}`, target);
  const panel = await page.evaluate(() => ({
    rows: document.querySelectorAll("#i-panel .mask-row").length,
    masks: document.querySelectorAll("#i-panel canvas.mask").length,
    text: document.getElementById("i-panel").textContent,
  }));
  assert.equal(panel.masks, target.n + 1, "one mask grid per fragment plus the sample grid");
  assert.match(panel.text, new RegExp(`pixel \\(${target.x}, ${target.y}\\): ${target.n} fragments`));
  assert.match(panel.text, /zmin|triangle \d+/);
  // The panel's resolve is the A-buffer's frame pixel and the registry
  // abuffer's render of the same view at 32 x 32.
  const check = await page.evaluate((t) => {
    const { state } = window.hiderApp;
    const canvas = document.getElementById("i-image");
    const d = canvas.getContext("2d").getImageData(t.x * 8 + 4, t.y * 8 + 4, 1, 1).data;
    state.page.set_size(32, 32);
    const frame = state.page.render("abuffer");
    const rgba = frame.rgba();
    frame.free();
    state.page.set_size(state.size, state.size);
    const p = 4 * (t.y * 32 + t.x);
    const swatch = document.querySelector("#i-panel .swatch").style.background;
    return { shown: Array.from(d.slice(0, 3)), registry: Array.from(rgba.slice(p, p + 3)), swatch };
  }, target);
  assert.deepEqual(check.shown, check.registry, "the inspected image differs from the registry's abuffer");
  assert.equal(check.swatch, `rgb(${check.registry.join(", ")})`, "the resolve differs from the frame's pixel");
  await page.locator("#inspect-body").screenshot({ path: join(out, "steps-abuffer-inspector.png") });
});

test("depth precision: a wide gap never fights, a tiny far one fights more in 16 bits than in f32", async () => {
  await page.click('.tab[data-view="steps"]');
  const wide = await page.evaluate(() => window.hiderApp.extras().precision.set(-1.3, 0, 2));
  const names = Object.keys(wide);
  for (const name of ["zbuffer", "zbuffer-f64", "zbuffer-fixed24", "zbuffer-fixed16"]) {
    assert.ok(names.includes(name), `${name} missing from ${names}`);
  }
  for (const [name, share] of Object.entries(wide)) assert.equal(share, 0, `${name} fights at a wide gap`);
  const tiny = await page.evaluate(() => window.hiderApp.extras().precision.set(-5, -2, 3));
  assert.ok(tiny["zbuffer-fixed16"] > tiny.zbuffer, JSON.stringify(tiny));
  assert.ok(tiny["zbuffer-fixed16"] > 0.1, JSON.stringify(tiny));
  await page.locator("#precision-body").scrollIntoViewIfNeeded();
  await page.locator("#precision-body").screenshot({ path: join(out, "steps-precision.png") });
});

test("the Y-buffer shows each column the nearest segment's colour, and dragging an end redraws it", async () => {
  await page.click('.tab[data-view="ybuffer"]');
  const { W, columns, image } = await page.evaluate(() => {
    const y = window.hiderApp.extras().ybuffer;
    const c = document.getElementById("y-image");
    return {
      W: y.W,
      columns: JSON.parse(document.getElementById("ybuffer-body").dataset.columns),
      image: Array.from(c.getContext("2d").getImageData(0, 0, y.W, 1).data),
    };
  });
  // The starting layout (plane units): a slope from (8, 100) to (120, 20),
  // a flat segment at y 60 over x 4..56 and one at y 40 over x 72..124.
  // Worked out here: the nearest segment per column centre.
  const slope = (x) => 100 + (20 - 100) * (x - 8) / (120 - 8);
  const expected = [];
  for (let x = 0; x < W; x++) {
    const c = x + 0.5;
    const seen = [];
    if (c > 8 && c < 120) seen.push([slope(c), 0]);
    if (c > 4 && c < 56) seen.push([60, 1]);
    if (c > 72 && c < 124) seen.push([40, 2]);
    seen.sort((a, b) => a[0] - b[0]);
    expected.push(seen.length ? seen[0][1] : -1);
  }
  assert.deepEqual(columns, expected);
  // The segments' colours (hider_web::ybuffer::COLOURS).
  const rgb = [[220, 40, 40], [40, 170, 60], [50, 90, 220]];
  for (let x = 0; x < W; x++) {
    const want = expected[x] < 0 ? [0, 0, 0] : rgb[expected[x]];
    assert.deepEqual(image.slice(4 * x, 4 * x + 3), want, `column ${x}`);
  }
  for (const k of [0, 1, 2]) assert.ok(expected.includes(k), `segment ${k} hidden in the layout`);
  await page.locator("#ybuffer-body").screenshot({ path: join(out, "ybuffer.png") });
  // Drag the green segment's right end far back: the slope shows there.
  const plane = await page.locator("#y-plane").boundingBox();
  const s = plane.width / W;
  await page.mouse.move(plane.x + 56 * s, plane.y + (W - 60) * s);
  await page.mouse.down();
  await page.mouse.move(plane.x + 56 * s, plane.y + (W - 126) * s, { steps: 5 });
  await page.mouse.up();
  const after = await page.evaluate(() => JSON.parse(document.getElementById("ybuffer-body").dataset.columns));
  const segs = await page.evaluate(() => window.hiderApp.extras().ybuffer.segs[1]);
  assert.ok(segs[3] > 120, `the end did not move: ${segs}`);
  assert.notDeepEqual(after, columns, "dragging changed nothing");
  assert.equal(after[50], 0, "the slope is in front at column 50 once the green end is far back");
  await page.locator("#ybuffer-body").screenshot({ path: join(out, "ybuffer-dragged.png") });
  await page.click('.tab[data-view="compare"]');
});

test("touch: one finger orbits, two fingers pinch to zoom and pan, and the image changes", async () => {
  await pick("bundled|cube");
  const box = await page.locator("#view").boundingBox();
  const cdp = await page.context().newCDPSession(page);
  const touch = (type, points) => cdp.send("Input.dispatchTouchEvent", {
    type, touchPoints: points.map(([x, y], id) => ({ x: box.x + x, y: box.y + y, id })),
  });
  const snapshot = () => page.evaluate(() => {
    const c = document.getElementById("view");
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let h = 0;
    for (let k = 0; k < d.length; k += 4) h = (h * 31 + d[k] + 7 * d[k + 1] + 13 * d[k + 2]) >>> 0;
    return { orbit: { ...window.hiderApp.state.orbit }, hash: h };
  });
  const start = await snapshot();
  // One finger drags right and down: orbit.
  await touch("touchStart", [[150, 150]]);
  for (let k = 1; k <= 5; k++) await touch("touchMove", [[150 + 12 * k, 150 + 6 * k]]);
  await touch("touchEnd", []);
  const orbited = await snapshot();
  assert.notEqual(orbited.orbit.yaw, start.orbit.yaw, "one finger did not orbit");
  assert.ok(orbited.orbit.pitch > start.orbit.pitch, "one finger down did not pitch");
  assert.notEqual(orbited.hash, start.hash, "the image did not change");
  await page.screenshot({ path: join(out, "touch-orbited.png") });
  // Two fingers spread apart symmetrically: zoom in, no pan.
  await touch("touchStart", [[200, 250], [300, 250]]);
  for (let k = 1; k <= 5; k++) await touch("touchMove", [[200 - 15 * k, 250], [300 + 15 * k, 250]]);
  await touch("touchEnd", []);
  const pinched = await snapshot();
  assert.ok(pinched.orbit.zoom < orbited.orbit.zoom, `pinch out did not zoom in: ${pinched.orbit.zoom}`);
  assert.ok(Math.abs(pinched.orbit.panX - orbited.orbit.panX) < 1e-9, "a symmetric pinch panned");
  assert.notEqual(pinched.hash, orbited.hash, "the image did not change on zoom");
  // Two fingers moving together to the right: pan.
  await touch("touchStart", [[200, 250], [300, 250]]);
  for (let k = 1; k <= 5; k++) await touch("touchMove", [[200 + 10 * k, 250], [300 + 10 * k, 250]]);
  await touch("touchEnd", []);
  const panned = await snapshot();
  assert.ok(panned.orbit.panX < pinched.orbit.panX, `two fingers right did not pan: ${panned.orbit.panX}`);
  assert.ok(Math.abs(panned.orbit.zoom - pinched.orbit.zoom) < 1e-9, "moving two fingers together zoomed");
  assert.notEqual(panned.hash, pinched.hash, "the image did not change on pan");
  await page.screenshot({ path: join(out, "touch-pinched-panned.png") });
});

test("no console error appeared in these views", () => {
  assert.deepEqual(problems, []);
});
