// What every browser test file of the page shares: the built page
// (web/dist) served by the README's serve command on a free port, Debian's
// Chromium driven by playwright-core, a record of console errors, and the
// scene picker. Not a test file itself (node --test runs `*.test.js`).
//
// Environment: CHROMIUM (default /usr/bin/chromium).
import { spawn } from "node:child_process";
import { mkdirSync } from "node:fs";
import { join, dirname } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

/** The web/ folder. */
export const web = join(dirname(fileURLToPath(import.meta.url)), "..");
/** Where the tests save their screenshots (look at them). */
export const out = join(web, "test-output");

/**
 * Serves web/dist, opens the page in Chromium with `context` (playwright's
 * browser-context options: viewport, hasTouch...) and waits until the
 * page is ready. Returns the page, the page's address, the list the
 * page's console errors and uncaught exceptions are pushed to, and
 * `close()`. Node runs the test files in parallel, so each picks a random
 * port.
 */
export async function openPage(context = {}) {
  mkdirSync(out, { recursive: true });
  const port = 8700 + Math.floor(Math.random() * 1000);
  const server = spawn("python3", ["-m", "http.server", "-b", "127.0.0.1", "-d", join(web, "dist"), String(port)], { stdio: "ignore" });
  const base = `http://127.0.0.1:${port}/`;
  for (let i = 0; i < 50; i++) {
    try { if ((await fetch(base)).ok) break; } catch { /* not up yet */ }
    await new Promise((r) => setTimeout(r, 100));
  }
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--no-sandbox"],
  });
  const page = await (await browser.newContext({ viewport: { width: 1400, height: 1100 }, ...context })).newPage();
  const problems = [];
  page.on("console", (m) => { if (m.type() === "error") problems.push(`console: ${m.text()}`); });
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  await page.goto(base);
  await page.waitForSelector("body[data-ready='1']", { timeout: 120000 });
  const close = async () => {
    await browser.close();
    server.kill();
  };
  return { page, base, problems, close };
}

/** Selects `choice` in the scene picker and waits for the grid to finish. */
export async function pick(page, choice) {
  const before = await page.evaluate(() => document.body.dataset.gridDone || "");
  await page.selectOption("#scene", choice);
  await page.waitForFunction((b) => (document.body.dataset.gridDone || "") !== b
    && !document.querySelector(".cell.pending"), before, { timeout: 300000 });
}
