// The drawing: links, joints, ground, traced paths, instant centres; pointer input.
const NS = "http://www.w3.org/2000/svg";

export function el(name, attrs = {}, parent = null) {
  const e = document.createElementNS(NS, name);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (parent) parent.append(e);
  return e;
}

export class Canvas {
  constructor(svg, handlers) {
    this.svg = svg;
    this.handlers = handlers;      // {down(name, xy, event), move(xy), up(xy), click(xy)}
    this.view = null;
    this.dragging = null;
    svg.addEventListener("pointerdown", (e) => this.pointer(e, "down"));
    svg.addEventListener("pointermove", (e) => this.pointer(e, "move"));
    svg.addEventListener("pointerup", (e) => this.pointer(e, "up"));
  }

  // Fit the view to a box [xmin, ymin, xmax, ymax] (model units), y upwards.
  fit(box) {
    const w = this.svg.clientWidth || 600, h = this.svg.clientHeight || 400;
    let [x0, y0, x1, y1] = box;
    const pad = 0.08 * Math.max(x1 - x0, y1 - y0, 1e-9);
    x0 -= pad; x1 += pad; y0 -= pad; y1 += pad;
    const s = Math.min(w / (x1 - x0), h / (y1 - y0));
    this.view = {s, ox: (w - s * (x1 + x0)) / 2, oy: (h + s * (y1 + y0)) / 2};
  }

  toScreen([x, y]) { const v = this.view; return [v.ox + v.s * x, v.oy - v.s * y]; }
  toModel([X, Y]) { const v = this.view; return [(X - v.ox) / v.s, (v.oy - Y) / v.s]; }

  pointer(e, kind) {
    if (!this.view) return;
    const r = this.svg.getBoundingClientRect();
    const xy = this.toModel([e.clientX - r.left, e.clientY - r.top]);
    if (kind === "down") {
      const name = e.target.dataset ? e.target.dataset.point : undefined;
      this.dragging = name || null;
      // a handler answering "capture" takes the drag itself (a pose being placed)
      if (this.handlers.down(name, xy, e) === "capture") this.dragging = {from: xy};
      if (this.dragging) this.svg.setPointerCapture(e.pointerId);
    } else if (kind === "move" && this.dragging) {
      this.handlers.move(this.dragging, xy);
    } else if (kind === "up") {
      const name = this.dragging;
      this.dragging = null;
      this.handlers.up(name, xy);
    }
  }

  // scene: {points: {name: [x, y]}, drawing, traces: {name: [[x, y], ...]}, marks, centres,
  //         poses: [{xy, angle, label}] (angle in rad; arrows, numbered unless labelled)}
  draw(scene) {
    const svg = this.svg;
    svg.replaceChildren();
    if (!this.view) return;
    const P = scene.points, d = scene.drawing;
    const S = (p) => this.toScreen(p);
    for (const [name, path] of Object.entries(scene.traces || {})) {
      const pts = path.filter((p) => p && p[0] !== null && p[1] !== null).map(S);
      if (pts.length > 1) el("polyline", {class: "trace", points: pts.join(" "), "data-trace": name}, svg);
    }
    for (const m of scene.marks || []) {
      const [X, Y] = S(m.xy);
      if (m.kind === "singular") el("circle", {class: "mark-singular", cx: X, cy: Y, r: 4}, svg);
      else el("rect", {class: "mark-change", x: X - 5, y: Y - 5, width: 10, height: 10}, svg);
    }
    for (const link of d.links) {
      const pts = link.points.filter((p) => P[p] && P[p][0] !== null);
      if (pts.length < 2) continue;
      const shape = pts.length > 2 ? "polygon" : "polyline";
      el(shape, {class: "link" + (link.ground ? " ground" : ""), "data-link": link.name,
                 points: pts.map((p) => S(P[p])).join(" ")}, svg);
    }
    for (const j of d.joints) {
      if (!P[j.point]) continue;
      const [X, Y] = S(P[j.point]);
      if (j.type === "P") {
        const a = Array.isArray(j.axis) ? j.axis : [1, 0], ang = Math.atan2(-a[1], a[0]) * 180 / Math.PI;
        el("line", {class: "guide", x1: X - 60, y1: Y, x2: X + 60, y2: Y, "data-guide": j.name,
                    transform: `rotate(${ang} ${X} ${Y})`}, svg);
        el("rect", {class: "joint P", x: X - 10, y: Y - 6, width: 20, height: 12,
                    transform: `rotate(${ang} ${X} ${Y})`}, svg);
      }
    }
    const inputPoints = new Set((d.inputs || []).map((i) => {
      const j = d.joints.find((k) => k.name === i.joint); return j ? j.point : null; }));
    for (const [name, xy] of Object.entries(P)) {
      if (!xy || xy[0] === null) continue;
      const [X, Y] = S(xy);
      const ground = d.ground_points.includes(name);
      if (ground) el("path", {class: "link ground", d: `M${X - 9},${Y + 12} L${X + 9},${Y + 12} M${X},${Y} L${X - 7},${Y + 12} M${X},${Y} L${X + 7},${Y + 12}`}, svg);
      const jointed = d.joints.some((j) => j.point === name);
      el("circle", {class: (jointed ? "joint " : "") + "point" + (ground ? " ground" : "") +
                    (inputPoints.has(name) ? " input" : ""),
                    cx: X, cy: Y, r: jointed ? 6 : 4.5, "data-point": name}, svg);
      el("text", {class: "label", x: X + 8, y: Y - 8}, svg).textContent = name;
    }
    scene.poses.forEach((pose, i) => {
      const [X, Y] = S(pose.xy), L = 42;
      const [U, V] = [X + L * Math.cos(pose.angle), Y - L * Math.sin(pose.angle)];
      const g = el("g", {class: "pose", "data-pose": i + 1}, svg);
      el("line", {x1: X, y1: Y, x2: U, y2: V}, g);
      const head = [[-10, 5], [-10, -5]].map(([a, b]) =>
        [U + a * Math.cos(pose.angle) + b * Math.sin(pose.angle), V - a * Math.sin(pose.angle) + b * Math.cos(pose.angle)]);
      el("polygon", {points: [[U, V], ...head].join(" ")}, g);
      el("circle", {cx: X, cy: Y, r: 3.5}, g);
      el("text", {class: "pose-label", x: X - 14, y: Y + 14}, g).textContent = pose.label ?? String(i + 1);
    });
    for (const c of scene.centres || []) {
      if (c.at_infinity || !c.position) continue;
      const [X, Y] = S(c.position);
      if (!isFinite(X) || !isFinite(Y) || Math.abs(X) > 1e5 || Math.abs(Y) > 1e5) continue;
      el("circle", {class: "centre", cx: X, cy: Y, r: 3, "data-centre": c.links.join("-")}, svg);
      el("text", {class: "centre-label", x: X + 4, y: Y + 12}, svg).textContent = `I ${c.links.join(",")}`;
    }
  }
}

// The bounding box of every place in a list of [x, y] (nulls skipped).
export function box(places) {
  let b = [Infinity, Infinity, -Infinity, -Infinity];
  for (const p of places) {
    if (!p || p[0] === null || p[1] === null) continue;
    b = [Math.min(b[0], p[0]), Math.min(b[1], p[1]), Math.max(b[2], p[0]), Math.max(b[3], p[1])];
  }
  return isFinite(b[0]) ? b : [-1, -1, 1, 1];
}
