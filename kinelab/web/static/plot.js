// A plot of one column against the input (or another column), with the animation's cursor,
// singular and change points marked, units on both axes; a click moves the linkage there.
import {el} from "./canvas.js";

const M = {left: 64, right: 12, top: 10, bottom: 40};

export class Plot {
  constructor(svg, onPick) {
    this.svg = svg;
    this.onPick = onPick;
    svg.addEventListener("click", (e) => this.click(e));
  }

  draw({x, y, xName, yName, singular = [], change = []}) {
    this.data = {x, y};
    const svg = this.svg;
    svg.replaceChildren();
    const w = svg.clientWidth || 400, h = svg.clientHeight || 300;
    const good = x.map((v, i) => v !== null && y[i] !== null);
    const xs = x.filter((v, i) => good[i]), ys = y.filter((v, i) => good[i]);
    if (!xs.length) return;
    let [x0, x1] = [Math.min(...xs), Math.max(...xs)];
    let [y0, y1] = [Math.min(...ys), Math.max(...ys)];
    if (x1 - x0 < 1e-12 * (1 + Math.abs(x0))) { x0 -= 1; x1 += 1; }
    if (y1 - y0 < 1e-12 * (1 + Math.abs(y0))) { y0 -= 1; y1 += 1; }
    const pad = 0.05 * (y1 - y0); y0 -= pad; y1 += pad;
    const X = (v) => M.left + (v - x0) / (x1 - x0) * (w - M.left - M.right);
    const Y = (v) => h - M.bottom - (v - y0) / (y1 - y0) * (h - M.top - M.bottom);
    this.scale = {X, Y, x0, x1, w};
    for (const t of ticks(y0, y1)) {
      el("line", {class: "grid", x1: M.left, x2: w - M.right, y1: Y(t), y2: Y(t)}, svg);
      el("text", {x: M.left - 4, y: Y(t) + 4, "text-anchor": "end"}, svg).textContent = fmt(t);
    }
    for (const t of ticks(x0, x1)) {
      el("text", {x: X(t), y: h - M.bottom + 14, "text-anchor": "middle"}, svg).textContent = fmt(t);
    }
    el("line", {class: "axis", x1: M.left, x2: M.left, y1: M.top, y2: h - M.bottom}, svg);
    el("line", {class: "axis", x1: M.left, x2: w - M.right, y1: h - M.bottom, y2: h - M.bottom}, svg);
    el("text", {id: "plot-xlabel", x: (M.left + w) / 2, y: h - 6, "text-anchor": "middle"}, svg).textContent = xName;
    el("text", {id: "plot-ylabel", x: 12, y: h / 2, "text-anchor": "middle",
                transform: `rotate(-90 12 ${h / 2})`}, svg).textContent = yName;
    // runs of good samples, broken at singular or unassembled ones
    let run = [];
    const flush = () => { if (run.length > 1) el("polyline", {class: "curve", points: run.join(" ")}, svg); run = []; };
    const bad = new Set(singular);
    x.forEach((v, i) => { if (good[i] && !bad.has(i)) run.push(`${X(v)},${Y(y[i])}`); else flush(); });
    flush();
    for (const i of singular) if (x[i] !== null)
      el("line", {class: "vline-singular", x1: X(x[i]), x2: X(x[i]), y1: M.top, y2: h - M.bottom}, svg);
    for (const i of change) if (x[i] !== null)
      el("line", {class: "vline-change", x1: X(x[i]), x2: X(x[i]), y1: M.top, y2: h - M.bottom}, svg);
    this.cursor = el("line", {id: "plot-cursor", class: "cursor", y1: M.top, y2: h - M.bottom}, svg);
    this.dot = el("circle", {class: "cursor", r: 3.5, fill: "#d1600a"}, svg);
  }

  // Nothing drawn (a new, empty page).
  clear() {
    this.svg.replaceChildren();
    this.data = null; this.scale = null; this.cursor = null; this.dot = null;
  }

  // Move the cursor to sample i.
  at(i) {
    if (!this.cursor || !this.data) return;
    const {x, y} = this.data, {X, Y} = this.scale;
    if (x[i] === null || x[i] === undefined) return;
    this.cursor.setAttribute("x1", X(x[i]));
    this.cursor.setAttribute("x2", X(x[i]));
    this.cursor.dataset.index = i;
    if (y[i] !== null) { this.dot.setAttribute("cx", X(x[i])); this.dot.setAttribute("cy", Y(y[i])); }
  }

  click(e) {
    if (!this.scale) return;
    const r = this.svg.getBoundingClientRect();
    const px = e.clientX - r.left;
    const {x} = this.data, {X} = this.scale;
    let best = -1, gap = Infinity;
    x.forEach((v, i) => { if (v !== null && Math.abs(X(v) - px) < gap) { gap = Math.abs(X(v) - px); best = i; } });
    if (best >= 0) this.onPick(best);
  }
}

function ticks(a, b) {
  const step = Math.pow(10, Math.floor(Math.log10((b - a) / 5)));
  const k = [1, 2, 5, 10].find((m) => (b - a) / (m * step) <= 6) * step;
  const out = [];
  for (let t = Math.ceil(a / k) * k; t <= b + 1e-9 * k; t += k) out.push(t);
  return out;
}

function fmt(v) { return Math.abs(v) < 1e-12 ? "0" : Number(v.toPrecision(4)).toString(); }
