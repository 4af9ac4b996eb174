// The error-against-time chart: one point per hider for the current view,
// time on a log axis, wrong pixels on a linear one; plain SVG.
const NS = "http://www.w3.org/2000/svg";

function el(name, attrs, text) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text !== undefined) e.textContent = text;
  return e;
}

export function drawChart(svg, results, highlight) {
  svg.replaceChildren();
  const W = 420, H = 300, L = 50, R = 10, T = 10, B = 40;
  const points = [...results].map(([name, r]) => ({ name, ms: Math.max(r.ms, 0.01), wrong: r.wrong }));
  svg.append(el("rect", { x: L, y: T, width: W - L - R, height: H - T - B, fill: "none", stroke: "#ccc" }));
  if (points.length === 0) return;
  const lo = Math.log10(Math.min(...points.map((p) => p.ms))) - 0.1;
  const hi = Math.log10(Math.max(...points.map((p) => p.ms))) + 0.1;
  const top = Math.max(1, ...points.map((p) => p.wrong)) * 1.1;
  const x = (ms) => L + ((Math.log10(ms) - lo) / (hi - lo || 1)) * (W - L - R);
  const y = (w) => H - B - (w / top) * (H - T - B);
  for (let e = Math.floor(lo); e <= Math.ceil(hi); e++) {
    const ms = 10 ** e;
    if (Math.log10(ms) < lo || Math.log10(ms) > hi) continue;
    svg.append(el("line", { x1: x(ms), x2: x(ms), y1: T, y2: H - B, stroke: "#eee" }));
    svg.append(el("text", { x: x(ms), y: H - B + 14, "font-size": 10, "text-anchor": "middle" }, `${ms} ms`));
  }
  svg.append(el("text", { x: (W + L) / 2, y: H - 6, "font-size": 11, "text-anchor": "middle" }, "render time (log)"));
  svg.append(el("text", { x: 12, y: (H - B) / 2, "font-size": 11, transform: `rotate(-90 12 ${(H - B) / 2})`, "text-anchor": "middle" }, "wrong pixels"));
  svg.append(el("text", { x: L - 4, y: y(0) + 4, "font-size": 10, "text-anchor": "end" }, "0"));
  svg.append(el("text", { x: L - 4, y: y(top / 1.1) + 4, "font-size": 10, "text-anchor": "end" }, String(Math.round(top / 1.1))));
  for (const p of points) {
    const g = el("g", {});
    g.append(el("title", {}, `${p.name}: ${p.ms.toFixed(1)} ms, ${p.wrong} wrong`));
    const mine = p.name === highlight;
    g.append(el("circle", { cx: x(p.ms), cy: y(p.wrong), r: mine ? 6 : 4, fill: p.wrong > 0 ? "#d22" : "#2b6cb0", opacity: 0.8 }));
    // Only the shown hider and the wrong ones are labelled (the others
    // crowd the zero line); every point names itself on hover.
    if (mine || p.wrong > 0) {
      g.append(el("text", { x: x(p.ms) + 6, y: y(p.wrong) - 4, "font-size": 10, fill: "#222" }, p.name));
    }
    svg.append(g);
  }
}
