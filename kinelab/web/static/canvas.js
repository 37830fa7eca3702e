// The drawing: links, joints, ground, traced paths, gears, cams, instant centres; pointer input.
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
    // {down(name, xy, event), move(name, xy), up(name, xy), hover(xy), panning(), viewed()}
    this.handlers = handlers;
    this.view = null;
    this.dragging = null;
    this.panning = null;           // a pan under way: the pointer's last screen place
    this.touches = new Map();      // touch pointers down, for a pinch
    this.grid = true;
    this.unitScale = 1;            // shown units per model unit (the grid's steps are in those)
    svg.addEventListener("pointerdown", (e) => this.pointer(e, "down"));
    svg.addEventListener("pointermove", (e) => this.pointer(e, "move"));
    svg.addEventListener("pointerup", (e) => this.pointer(e, "up"));
    svg.addEventListener("pointercancel", (e) => this.pointer(e, "cancel"));
    svg.addEventListener("wheel", (e) => {
      if (!this.view) return;
      e.preventDefault();
      const r = svg.getBoundingClientRect();
      this.zoom(Math.exp(-e.deltaY * 0.0015), [e.clientX - r.left, e.clientY - r.top]);
    }, {passive: false});
    svg.addEventListener("auxclick", (e) => e.preventDefault());
    svg.addEventListener("dblclick", (e) => {
      const d = e.target.dataset && e.target.dataset.dim;
      if (d && this.handlers.dimension) this.handlers.dimension(d, e.target);
    });
  }

  // The view only: the model's numbers never change with it.  A new view object each time,
  // so that the paths are drawn again.
  zoom(k, [X, Y]) {
    const v = this.view;
    this.view = {s: v.s * k, ox: X - (X - v.ox) * k, oy: Y - (Y - v.oy) * k};
    if (this.handlers.viewed) this.handlers.viewed();
  }
  pan(dX, dY) {
    const v = this.view;
    this.view = {s: v.s, ox: v.ox + dX, oy: v.oy + dY};
    if (this.handlers.viewed) this.handlers.viewed();
  }

  // The grid's step in model units: 1, 2 or 5 times a power of ten in the units shown,
  // at least `px` pixels apart.
  gridStep(px = 36) {
    const shown = px / this.view.s * this.unitScale;
    const e = Math.pow(10, Math.floor(Math.log10(shown)));
    const step = [1, 2, 5, 10].map((k) => k * e).find((v) => v >= shown * (1 - 1e-9));
    return step / this.unitScale;
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
    let here = [e.clientX - r.left, e.clientY - r.top];
    // a drag the browser took over (a pointercancel, whose place may be 0, 0) ends where the
    // pointer last was
    if (kind === "cancel") { kind = "up"; here = this.lastHere || here; } else this.lastHere = here;
    const xy = this.toModel(here);
    if (e.pointerType === "touch" && this.pinch(e, kind, here)) return;
    if (kind === "down" && (e.button === 1 || (this.handlers.panning && this.handlers.panning()))) {
      e.preventDefault();
      this.panning = here;
      this.svg.setPointerCapture(e.pointerId);
      return;
    }
    if (this.panning) {
      if (kind === "move") { this.pan(here[0] - this.panning[0], here[1] - this.panning[1]); this.panning = here; }
      if (kind === "up") this.panning = null;
      return;
    }
    if (kind === "down") {
      const name = e.target.dataset ? e.target.dataset.point : undefined;
      this.dragging = name || null;
      // a handler answering "capture" takes the drag itself (a pose being placed)
      if (this.handlers.down(name, xy, e) === "capture") this.dragging = {from: xy};
      if (this.dragging) this.svg.setPointerCapture(e.pointerId);
    } else if (kind === "move" && this.dragging) {
      this.handlers.move(this.dragging, xy);
    } else if (kind === "move" && this.handlers.hover) {
      this.handlers.hover(xy);
    } else if (kind === "up") {
      const name = this.dragging;
      this.dragging = null;
      this.handlers.up(name, xy);
    }
  }

  // Two fingers: zoom about their middle by the change of their distance, pan with it.
  pinch(e, kind, here) {
    const T = this.touches;
    if (kind === "down") T.set(e.pointerId, here);
    if (kind === "up") { T.delete(e.pointerId); this.pinched = T.size > 0 && this.pinched; return this.pinched; }
    if (T.size < 2) return false;
    if (kind === "down") { this.dragging = null; this.pinched = true; return true; }
    const [a0, b0] = [...T.values()];
    T.set(e.pointerId, here);
    const [a1, b1] = [...T.values()];
    const d0 = Math.hypot(b0[0] - a0[0], b0[1] - a0[1]), d1 = Math.hypot(b1[0] - a1[0], b1[1] - a1[1]);
    const m0 = [(a0[0] + b0[0]) / 2, (a0[1] + b0[1]) / 2], m1 = [(a1[0] + b1[0]) / 2, (a1[1] + b1[1]) / 2];
    this.pan(m1[0] - m0[0], m1[1] - m0[1]);
    if (d0 > 0 && d1 > 0) this.zoom(d1 / d0, m1);
    return true;
  }

  // The grid's lines over the whole canvas, the axes through the origin darker.
  gridLines() {
    const w = this.svg.clientWidth || 600, h = this.svg.clientHeight || 400;
    const step = this.gridStep();
    const [x0, y1] = this.toModel([0, 0]), [x1, y0] = this.toModel([w, h]);
    const items = [];
    for (let i = Math.ceil(x0 / step); i <= Math.floor(x1 / step); i++) {
      const [X] = this.toScreen([i * step, 0]);
      items.push([`x ${i}`, "line", {class: i === 0 ? "grid-axis" : "grid-line", x1: X, y1: 0, x2: X, y2: h}]);
    }
    for (let i = Math.ceil(y0 / step); i <= Math.floor(y1 / step); i++) {
      const [, Y] = this.toScreen([0, i * step]);
      items.push([`y ${i}`, "line", {class: i === 0 ? "grid-axis" : "grid-line", x1: 0, y1: Y, x2: w, y2: Y}]);
    }
    this.svg.dataset.gridStep = step;
    return items;
  }

  // scene: {points: {name: [x, y]}, drawing, traces: {name: [[x, y], ...]}, marks, centres,
  //         guides: {joint: [ux, uy]} (each P joint's slide direction now),
  //         turns: {link: [ux, uy]} (each gear's and cam's direction now: its link's angle;
  //                 see gears() and cams()),
  //         pending: a point waiting for the second click of a link, hover: [x, y],
  //         poses: [{xy, angle, label, key}] (angle in rad; arrows, numbered unless labelled;
  //                 without an angle a point marked as `mark` says, "fixed" (a pivot),
  //                 "moving" or "point" (a path's points, joined); one with a key has a
  //                 handle to drag it by, data-target its key; with `ray` (rad) instead, a
  //                 ray from xy at that angle, class `side`, its handle RAY px along it)}
  // The elements are kept and changed in place: a drag changes a few attributes, and the
  // paths (hundreds of samples) are drawn again only when they, or the view, change.
  draw(scene) {
    const svg = this.svg;
    if (!this.view) { svg.replaceChildren(); this.layers = null; return; }
    if (!this.layers) {
      svg.replaceChildren();
      this.layers = {};
      for (const name of ["grid", "paths", "cams", "gears", "links", "joints", "dims", "points", "poses", "centres"])
        this.layers[name] = {g: el("g", {"data-layer": name}, svg), byKey: new Map()};
      this.drawn = {};
    }
    const P = scene.points, d = scene.drawing, L = this.layers;
    const S = (p) => this.toScreen(p);
    if (this.view !== this.drawn.gridView || this.grid !== this.drawn.grid) {
      patch(L.grid, this.grid ? this.gridLines() : []);
      this.drawn.gridView = this.view; this.drawn.grid = this.grid;
    }
    const known = (xy) => xy && xy[0] !== null && xy[1] !== null;
    if (scene.traces !== this.drawn.traces || scene.marks !== this.drawn.marks || this.view !== this.drawn.view) {
      const items = [];
      for (const [name, path] of Object.entries(scene.traces || {})) {
        const pts = path.filter(known).map(S);
        if (pts.length > 1) items.push([`t ${name}`, "polyline", {class: "trace", points: pts.join(" "), "data-trace": name}]);
      }
      (scene.marks || []).forEach((m, i) => {
        const [X, Y] = S(m.xy);
        if (m.kind === "singular") items.push([`m ${i}`, "circle", {class: "mark-singular", cx: X, cy: Y, r: 4}]);
        else items.push([`m ${i}`, "rect", {class: "mark-change", x: X - 5, y: Y - 5, width: 10, height: 10}]);
      });
      patch(L.paths, items);
      Object.assign(this.drawn, {traces: scene.traces, marks: scene.marks, view: this.view});
    }
    const sel = scene.selected || {};
    const picked = (kind, name) => sel.kind === kind && sel.name === name ? " selected" : "";
    const links = [];
    for (const link of d.links) {
      const pts = link.points.filter((p) => known(P[p]));
      if (pts.length < 2) continue;
      links.push([`l ${link.name}`, pts.length > 2 ? "polygon" : "polyline",
                  {class: "link" + (link.ground ? " ground" : "") + picked("link", link.name), "data-link": link.name,
                   points: pts.map((p) => S(P[p])).join(" ")}]);
    }
    patch(L.links, links);
    patch(L.cams, this.cams(scene, known));
    patch(L.gears, this.gears(scene, known));
    const joints = [];
    for (const j of d.joints) {
      if (j.type !== "P" || !known(P[j.point])) continue;
      const [X, Y] = S(P[j.point]);
      const a = (scene.guides && scene.guides[j.name]) || (Array.isArray(j.axis) ? j.axis : [1, 0]);
      if (!known(a)) continue;
      const n = Math.hypot(a[0], a[1]), ux = a[0] / n, uy = -a[1] / n;     // on the screen, y down
      const ang = Math.atan2(uy, ux) * 180 / Math.PI;
      joints.push([`g ${j.name}`, "line", {class: "guide", x1: X - 60 * ux, y1: Y - 60 * uy,
                                           x2: X + 60 * ux, y2: Y + 60 * uy, "data-guide": j.name}]);
      joints.push([`b ${j.name}`, "rect", {class: "joint P" + picked("joint", j.name), x: X - 10, y: Y - 6, width: 20, height: 12,
                                           transform: `rotate(${ang} ${X} ${Y})`, "data-block": j.name}]);
    }
    patch(L.joints, joints);
    const place = labelPlacer(Object.values(P).filter(known).map(S));
    // dimensions: along a link (a -> b), upright, a little to its side; an input's at its pivot
    const dims = [];
    for (const dm of scene.dims || []) {
      if (!known(dm.a) || (dm.b && !known(dm.b))) continue;
      const [X0, Y0] = S(dm.a);
      let attrs;
      if (dm.b) {
        const [X1, Y1] = S(dm.b);
        let ang = Math.atan2(Y1 - Y0, X1 - X0) * 180 / Math.PI;
        if (ang > 90) ang -= 180; else if (ang <= -90) ang += 180;
        // on the side of the link where it covers less of what is placed (its left first)
        const n = Math.hypot(X1 - X0, Y1 - Y0) || 1;
        let least = Infinity;
        for (const off of [10, -16]) {
          const X = (X0 + X1) / 2 + off * (Y1 - Y0) / n, Y = (Y0 + Y1) / 2 - off * (X1 - X0) / n;
          const at = {x: X, y: Y, "text-anchor": "middle", transform: `rotate(${ang} ${X} ${Y})`};
          const c = place.cost(textBox(at, dm.text, DIM_SIZE));
          if (c < least) { attrs = at; least = c; }
        }
      } else {
        attrs = {x: X0 - 12, y: Y0 + 26, "text-anchor": "end"};
      }
      dims.push([`d ${dm.name}`, "text", {class: "dim", "data-dim": dm.name, ...attrs}, dm.text]);
      place.reserve(textBox(attrs, dm.text, DIM_SIZE));       // the points' labels keep off it
    }
    patch(L.dims, dims);
    const inputPoints = new Set((d.inputs || []).map((i) => {
      const j = d.joints.find((k) => k.name === i.joint); return j ? j.point : null; }));
    const jointed = new Set(d.joints.map((j) => j.point));
    const points = [];
    for (const [name, xy] of Object.entries(P)) {
      if (!known(xy)) continue;
      const [X, Y] = S(xy);
      const ground = d.ground_points.includes(name);
      if (ground) points.push([`g ${name}`, "path", {class: "link ground", d: `M${X - 9},${Y + 12} L${X + 9},${Y + 12} M${X},${Y} L${X - 7},${Y + 12} M${X},${Y} L${X + 7},${Y + 12}`}]);
      if (name === scene.pending) {
        points.push(["pending ring", "circle", {class: "pending", cx: X, cy: Y, r: 11, "data-pending": name}]);
        if (scene.hover) {
          const [U, V] = S(scene.hover);
          points.push(["pending line", "line", {class: "pending-link", x1: X, y1: Y, x2: U, y2: V}]);
        }
      }
      points.push([`c ${name}`, "circle", {class: (jointed.has(name) ? "joint " : "") + "point" + (ground ? " ground" : "") +
                                            (inputPoints.has(name) ? " input" : "") +
                                            (picked("point", name) || (sel.point === name ? " selected" : "")),
                                           cx: X, cy: Y, r: jointed.has(name) ? 6 : 4.5, "data-point": name}]);
      const [x, y] = place(X, Y, name, 12);
      points.push([`t ${name}`, "text", {class: "label", x, y}, name]);
    }
    patch(L.points, points);
    L.poses.g.replaceChildren();
    const path = scene.poses.filter((t) => t.mark === "point").map((t) => S(t.xy));
    if (path.length > 1) el("polyline", {class: "target-path", points: path.join(" ")}, L.poses.g);
    let n = 0;
    for (const pose of scene.poses) {
      const [X, Y] = S(pose.xy);
      // a handle to drag it by, over it
      const handle = (g) => { if (pose.key) el("circle", {class: "handle", cx: X, cy: Y, r: 9, "data-target": pose.key}, g); };
      if (pose.ray !== undefined) {     // a ray from its pivot, its handle RAY px along it
        const c = Math.cos(pose.ray), s = Math.sin(pose.ray), R = Canvas.RAY;
        const g = el("g", {class: `target ray ${pose.side}`, "data-target": pose.key}, L.poses.g);
        el("line", {x1: X, y1: Y, x2: X + (R + 16) * c, y2: Y - (R + 16) * s}, g);
        el("circle", {class: "end", cx: X + R * c, cy: Y - R * s, r: 4}, g);
        el("text", {class: "target-label", x: X + (R + 28) * c - 4, y: Y - (R + 28) * s + 4}, g).textContent = pose.label;
        el("circle", {class: "handle", cx: X + R * c, cy: Y - R * s, r: 9, "data-target": pose.key}, g);
        continue;
      }
      if (pose.angle === undefined) {
        const g = el("g", {class: `target ${pose.mark}`, "data-target": pose.key}, L.poses.g);
        if (pose.mark === "fixed") el("path", {d: `M${X - 9},${Y + 12} L${X + 9},${Y + 12} M${X},${Y} L${X - 7},${Y + 12} M${X},${Y} L${X + 7},${Y + 12}`}, g);
        el("circle", {cx: X, cy: Y, r: pose.mark === "point" ? 3.5 : 5}, g);
        const [x, y] = place(X, Y, pose.label, 12);
        el("text", {class: "target-label", x, y}, g).textContent = pose.label;
        handle(g);
        continue;
      }
      n += 1;
      const len = 42;
      const [U, V] = [X + len * Math.cos(pose.angle), Y - len * Math.sin(pose.angle)];
      const g = el("g", {class: "pose", "data-pose": n}, L.poses.g);
      el("line", {x1: X, y1: Y, x2: U, y2: V}, g);
      const head = [[-10, 5], [-10, -5]].map(([a, b]) =>
        [U + a * Math.cos(pose.angle) + b * Math.sin(pose.angle), V - a * Math.sin(pose.angle) + b * Math.cos(pose.angle)]);
      el("polygon", {points: [[U, V], ...head].join(" ")}, g);
      el("circle", {cx: X, cy: Y, r: 3.5}, g);
      el("text", {class: "pose-label", x: X - 14, y: Y + 14}, g).textContent = pose.label ?? String(n);
      handle(g);
    }
    const centres = [];
    for (const c of scene.centres || []) {
      if (c.at_infinity || !c.position) continue;
      const [X, Y] = S(c.position);
      if (!isFinite(X) || !isFinite(Y) || Math.abs(X) > 1e5 || Math.abs(Y) > 1e5) continue;
      const key = c.links.join("-");
      centres.push([`c ${key}`, "circle", {class: "centre", cx: X, cy: Y, r: 3, "data-centre": key}]);
      const text = `I ${c.links.join(",")}`, [x, y] = place(X, Y, text, 10);
      centres.push([`t ${key}`, "text", {class: "centre-label", x, y}, text]);
    }
    patch(L.centres, centres);
  }

  // Each cam of drawing.cams (the server's profile in the cam's own frame, model units): its
  // profile, a path whose outline is made once a model and placed each frame by its transform
  // alone (the cam's centre, the view's scale, the cam's angle: scene.turns, or its first two
  // points' direction where there is none, the sketch); its base circle dashed about its
  // centre; its follower's contact point marked; a translating follower's line of motion
  // through it, from beyond the cam's centre.  Each element carries data-cam (the joint).
  cams(scene, known) {
    const items = [], P = scene.points, turns = scene.turns || {}, guides = scene.guides || {};
    const s = this.view.s;
    for (const cam of scene.drawing.cams || []) {
      const c = P[cam.centre], data = {"data-cam": cam.joint};
      if (!known(c)) continue;
      const [X, Y] = this.toScreen(c);
      if (cam.profile) {
        let u = turns[cam.cam];
        if (!known(u)) {
          const link = scene.drawing.links.find((l) => l.name === cam.cam), pts = link ? link.points : [];
          const a = P[pts[0]], b = P[pts[1]];
          u = known(a) && known(b) ? [b[0] - a[0], b[1] - a[1]] : null;
        }
        if (known(u)) {
          const deg = Math.atan2(u[1], u[0]) * 180 / Math.PI;
          items.push([`${cam.joint} profile`, "path", {class: "cam-profile" + (cam.kind === "pitch" ? " cam-pitch" : ""), d: outline(cam), ...data,
                      transform: `translate(${X} ${Y}) scale(${s} ${-s}) rotate(${deg})`}]);
        }
        items.push([`${cam.joint} base`, "circle", {class: "cam-base", cx: X, cy: Y, r: cam.base_radius * s, ...data}]);
      }
      const at = P[cam.contact];
      if (!known(at)) continue;
      if (cam.motion === "translating") {
        const j = scene.drawing.joints.find((q) => q.name === cam.follower_joint);
        let u = guides[cam.follower_joint] || (j && Array.isArray(j.axis) ? j.axis : null);
        if (known(u)) {
          const n = Math.hypot(u[0], u[1]), ux = u[0] / n, uy = u[1] / n;
          const along = (at[0] - c[0]) * ux + (at[1] - c[1]) * uy, reach = cam.base_radius || Math.abs(along);
          const [X0, Y0] = this.toScreen([at[0] - (along + 0.6 * reach) * ux, at[1] - (along + 0.6 * reach) * uy]);
          const [X1, Y1] = this.toScreen([at[0] + 0.6 * reach * ux, at[1] + 0.6 * reach * uy]);
          items.push([`${cam.joint} line`, "line", {class: "cam-line", x1: X0, y1: Y0, x2: X1, y2: Y1, ...data}]);
        }
      }
      const [U, V] = this.toScreen(at);
      items.push([`${cam.joint} contact`, "circle", {class: "cam-contact", cx: U, cy: V, r: 8, ...data}]);
    }
    return items;
  }

  // Each gear pair of drawing.gears (the server's pitch radii, in model units): a gear's pitch
  // circle about its centre, a radius at its direction (scene.turns: its link's analysed
  // angle) and TICKS - 1 ticks a TICKS-th of a turn apart, outwards (inwards on a ring, the
  // larger gear of an internal pair); a rack's pitch line along its slide, to the right of the
  // axis through the pinion's centre, with ticks a TICKS-th of the pinion's pitch circumference
  // apart (so that they roll with the pinion's), carried by the rack's point, the one at its
  // point marked longer.  Without a direction (the sketch), the circle alone.  Each element
  // carries data-gear (the joint) and data-gear-link (the gear).
  gears(scene, known) {
    const items = [], P = scene.points, turns = scene.turns || {}, guides = scene.guides || {};
    const s = this.view.s, T = 6;               // a tick's length, px
    for (const pair of scene.drawing.gears || []) {
      const pinion = pair.gears[0];
      for (const [k, g] of pair.gears.entries()) {
        const key = `${pair.joint} ${k}`, data = {"data-gear": pair.joint, "data-gear-link": g.link};
        if (g.rack) {
          const c = P[pinion.centre], at = P[g.point];
          const j = scene.drawing.joints.find((q) => q.name === g.slide);
          let u = guides[g.slide] || (j && Array.isArray(j.axis) ? j.axis : null);
          if (!known(c) || !known(at) || !known(u)) continue;
          const n = Math.hypot(u[0], u[1]); u = [u[0] / n, u[1] / n];
          const right = [u[1], -u[0]], along = (at[0] - c[0]) * u[0] + (at[1] - c[1]) * u[1];
          const ref = [c[0] + g.radius * right[0] + along * u[0], c[1] + g.radius * right[1] + along * u[1]];
          const step = 2 * Math.PI * g.radius / TICKS, span = TICKS * step;
          const [X0, Y0] = this.toScreen([ref[0] - span * u[0], ref[1] - span * u[1]]);
          const [X1, Y1] = this.toScreen([ref[0] + span * u[0], ref[1] + span * u[1]]);
          items.push([`${key} pitch`, "line", {class: "pitch rack", x1: X0, y1: Y0, x2: X1, y2: Y1, ...data}]);
          const [nx, ny] = [-right[0], right[1]];          // towards the pinion, on the screen
          let d = "";
          for (let i = -TICKS; i <= TICKS; i++) {
            if (i === 0) continue;
            const [X, Y] = this.toScreen([ref[0] + i * step * u[0], ref[1] + i * step * u[1]]);
            d += `M${X},${Y} L${X + T * nx},${Y + T * ny} `;
          }
          items.push([`${key} ticks`, "path", {class: "gear-ticks", d, ...data}]);
          const [X, Y] = this.toScreen(ref);
          items.push([`${key} mark`, "line", {class: "gear-mark", x1: X, y1: Y, x2: X + 2.5 * T * nx,
                                              y2: Y + 2.5 * T * ny, ...data}]);
          continue;
        }
        const c = P[g.centre];
        if (!known(c)) continue;
        const [X, Y] = this.toScreen(c), R = g.radius * s;
        const ring = pair.mesh === "internal" && g.radius > pair.gears[1 - k].radius;
        items.push([`${key} pitch`, "circle", {class: "pitch" + (ring ? " ring" : ""), cx: X, cy: Y, r: R, ...data}]);
        const u = turns[g.link];
        if (!known(u)) continue;
        const a = Math.atan2(u[1], u[0]);
        items.push([`${key} mark`, "line", {class: "gear-mark", x1: X, y1: Y, x2: X + R * Math.cos(a),
                                            y2: Y - R * Math.sin(a), ...data}]);
        const out = ring ? -T : T;
        let d = "";
        for (let i = 1; i < TICKS; i++) {
          const b = a + 2 * Math.PI * i / TICKS, cb = Math.cos(b), sb = -Math.sin(b);
          d += `M${X + R * cb},${Y + R * sb} L${X + (R + out) * cb},${Y + (R + out) * sb} `;
        }
        items.push([`${key} ticks`, "path", {class: "gear-ticks", d, ...data}]);
      }
    }
    return items;
  }
}

// How far from its pivot a ray's handle is drawn, px: the same at every zoom.
Canvas.RAY = 64;
const TICKS = 12;             // ticks a turn on a gear's pitch circle

// A cam's profile as a path's outline, in the cam's frame and model units: made once a cam
// (the drawing of each study is new), then only turned and carried by the path's transform.
const OUTLINES = new WeakMap();
function outline(cam) {
  let d = OUTLINES.get(cam);
  if (d === undefined) {
    const pts = cam.profile.filter((p) => p && p[0] !== null && p[1] !== null);
    d = pts.map(([x, y], i) => `${i ? "L" : "M"}${x} ${y}`).join(" ") + " Z";
    OUTLINES.set(cam, d);
  }
  return d;
}

// Labels placed so that they cover no label placed before them and no point: each at the
// first of a few places around its anchor that is free, else at the least covered one.  A
// label's box is estimated (a character about CHAR of the font's size wide), which is
// cheap enough for every frame of a drag.
const DIM_SIZE = 11;          // px, as app.css sets .dim
const CHAR = 0.62;            // a character's width, about, in sizes of its font
const PAD = 1.5;              // px kept free around each text
const SPOTS = [[8, -8, 0], [8, 17, 0], [-8, -8, 1], [-8, 17, 1], [0, -12, 0.5], [0, 22, 0.5],
               [16, -16, 0], [16, 26, 0], [-16, -16, 1], [-16, 26, 1], [0, -24, 0.5], [0, 34, 0.5]];

function labelPlacer(points) {
  const taken = points.map(([X, Y]) => [X - 7, Y - 7, X + 7, Y + 7]);
  const covered = (b) => taken.reduce((s, t) =>
    s + Math.max(0, Math.min(b[2], t[2]) - Math.max(b[0], t[0])) *
        Math.max(0, Math.min(b[3], t[3]) - Math.max(b[1], t[1])), 0);
  // where the baseline of a label of `text` in a font of `size` px starts, about (X, Y)
  const place = (X, Y, text, size) => {
    const w = CHAR * size * text.length;
    let best = null, least = Infinity;
    for (const [dx, dy, align] of SPOTS) {
      const x = X + dx - align * w, y = Y + dy;
      const b = [x - PAD, y - 0.8 * size - PAD, x + w + PAD, y + 0.2 * size + PAD];
      const c = covered(b);
      if (c < least) { best = [x, y, b]; least = c; if (c === 0) break; }
    }
    taken.push(best[2]);
    return best;
  };
  place.reserve = (box) => taken.push(box);     // a text placed otherwise: keep off it
  place.cost = covered;                         // how much of what is placed a box covers
  return place;
}

// The box on the screen, [left, top, right, bottom], of a text drawn with `attrs` (x, y,
// text-anchor, a rotation about (x, y)) in a font of `size` px, estimated as labelPlacer's.
function textBox(attrs, text, size) {
  const w = CHAR * size * text.length, h = size;
  const left = {middle: -w / 2, end: -w}[attrs["text-anchor"]] ?? 0;
  // the unrotated box about (x, y), then its corners turned
  const corners = [[left, -0.8 * h], [left + w, -0.8 * h], [left, 0.2 * h], [left + w, 0.2 * h]];
  const turn = /rotate\(([-\d.e]+)/.exec(attrs.transform || "");
  const a = turn ? Number(turn[1]) * Math.PI / 180 : 0, c = Math.cos(a), s = Math.sin(a);
  const xs = corners.map(([u, v]) => attrs.x + u * c - v * s), ys = corners.map(([u, v]) => attrs.y + u * s + v * c);
  return [Math.min(...xs) - PAD, Math.min(...ys) - PAD, Math.max(...xs) + PAD, Math.max(...ys) + PAD];
}

// A layer's elements made as `items` say ([key, tag, attributes, text]), in that order:
// those of a key drawn before are kept, only their changed attributes set.
function patch(layer, items) {
  const now = new Map(), kids = [];
  for (const [key, tag, attrs, text] of items) {
    let e = layer.byKey.get(key);
    if (!e || e.localName !== tag) { e = document.createElementNS(NS, tag); e.drawn = {}; }
    const was = e.drawn;
    for (const k in attrs) {
      const v = String(attrs[k]);
      if (was[k] !== v) { e.setAttribute(k, v); was[k] = v; }
    }
    for (const k in was) if (!(k in attrs)) { e.removeAttribute(k); delete was[k]; }
    if (text !== undefined && e.textContent !== text) e.textContent = text;
    now.set(key, e);
    kids.push(e);
  }
  layer.byKey = now;
  const c = layer.g.children;
  if (c.length !== kids.length || kids.some((e, i) => c[i] !== e)) layer.g.replaceChildren(...kids);
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
