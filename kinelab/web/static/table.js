// The table beside the drawing: exact coordinates, lengths, joints, the inputs and the
// branches; typing a value changes the model, the server re-assembles it (a refused value
// leaves the model, and the table, as they were).
import {movePoint, movePivot, groundLength, offsetOf, dist, sideOf, sideRefs,
        measuredSides} from "./geometry.js";
import {shownUnits, toShown, fromShown} from "./units.js";
import {typedRange, withoutInput} from "./inputs.js";

function cell(row, content) {
  const td = document.createElement("td");
  if (content instanceof Node) td.append(content); else td.textContent = content;
  row.append(td);
  return td;
}

function input(value, onchange, cls = "") {
  const i = document.createElement("input");
  i.value = value; i.className = cls;
  i.addEventListener("change", () => onchange(i.value));
  return i;
}

function table(head) {
  const t = document.createElement("table");
  const tr = document.createElement("tr");
  for (const h of head) { const th = document.createElement("th"); th.textContent = h; tr.append(th); }
  t.append(tr);
  return t;
}

// A number as a model file writes one: decimal digits, a point, an exponent; nothing else
// (JavaScript's Number would read "" as 0, "0x10" as 16 and "1e999" as Infinity).
export const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$/;
export function num(text, what = "value") {
  const t = String(text).trim();
  if (t === "") throw new Error(`${what}: expected a number, got an empty field; type a value (the model keeps its own)`);
  const v = Number(t);
  if (!DECIMAL.test(t) || !Number.isFinite(v))
    throw new Error(`${what}: expected a decimal number such as 12.5 or 1e3, got '${t}'`);
  return v;
}

// `refuse(message)`: a value refused here (not a number, not a pair of points) is shown
// with the reason, and the table drawn again from the model.
// `draft(model)`: a model that may not assemble yet (an input removed), kept as a drawing.
export function renderTable(root, state, {edit, flip, refuse, draft = edit}) {
  root.replaceChildren();
  const m = state.model, u = shownUnits(m.units), L = u.L;
  const len = (v) => toShown(v, L), typed = (v, what) => fromShown(num(v, what), L);
  const h = (text) => { const e = document.createElement("h3"); e.textContent = text; root.append(e); };
  const guarded = (f) => (v) => { try { f(v); } catch (err) { state.error = err.message; refuse(err.message); } };

  h(`points (sketch, ${u.length}) and now`);
  const pt = table(["point", "x", "y", "x now", "y now"]);
  const ground = m.links.find((l) => l.ground);
  for (const [p, xy] of Object.entries(m.points)) {
    const tr = document.createElement("tr"); tr.dataset.point = p;
    cell(tr, p);
    // a pivot moves with every link keeping its dimensions; another point changes the
    // links that carry it
    const move = ground && ground.points.includes(p) ? movePivot : movePoint;
    cell(tr, input(len(xy[0]), guarded((v) => edit(move(m, p, [typed(v, `${p}.x`), xy[1]]))))).dataset.field = "x";
    cell(tr, input(len(xy[1]), guarded((v) => edit(move(m, p, [xy[0], typed(v, `${p}.y`)]))))).dataset.field = "y";
    cell(tr, "").className = "now-x"; cell(tr, "").className = "now-y";
    pt.append(tr);
  }
  root.append(pt);

  h(`links (${u.length})`);
  const lt = table(["link", "points", "length", "length now"]);
  for (const [k, link] of m.links.entries()) {
    const tr = document.createElement("tr"); tr.dataset.link = link.name;
    cell(tr, link.name + (link.ground ? " (ground)" : ""));
    cell(tr, input(link.points.join(", "), guarded((v) => {
      const next = structuredClone(m); delete next.catalogue;
      next.links[k].points = v.split(",").map((s) => s.trim()).filter(Boolean);
      edit(next);
    })));
    const current = link.length ?? (link.points.length > 1 ? dist(m.points[link.points[0]], m.points[link.points[1]]) : "");
    cell(tr, link.points.length > 1 ? input(len(current), guarded((v) => {
      edit(withLength(m, link.name, typed(v, `${link.name}.length`)));
    })) : "").dataset.field = "length";
    cell(tr, "").className = "now-length";
    lt.append(tr);
  }
  root.append(lt);
  sidesTable(root, m, u, h, guarded, edit, len, typed);

  h("joints");
  const jt = table(["joint", "type", "links (P: guide, slider)", "point", `P axis (${u.angle})`,
                    `P offset (${u.length})`]);
  const toAngle = m.units && m.units.angle === "rad" ? 1 : 180 / Math.PI;    // the model's unit
  for (const [k, j] of (m.joints || []).entries()) {
    const tr = document.createElement("tr");
    cell(tr, j.name);
    const sel = document.createElement("select");
    for (const t of ["R", "P"]) sel.append(new Option(t, t));
    // a gear pair keeps its type (R or P would need none of its fields): shown, not offered
    if (!["R", "P"].includes(j.type)) {
      const kind = j.type === "G" ? `G (${j.mesh || "external"})` : j.type;
      sel.append(new Option(kind, j.type));
      sel.disabled = true;
    }
    sel.value = j.type;
    sel.onchange = () => {
      const next = structuredClone(m); delete next.catalogue;
      next.joints[k].type = sel.value;
      if (sel.value === "P" && !next.joints[k].axis) next.joints[k].axis = [1, 0];
      if (sel.value === "R") delete next.joints[k].axis;
      edit(next);
    };
    cell(tr, sel);
    cell(tr, input(j.links.join(", "), guarded((v) => {
      const next = structuredClone(m); delete next.catalogue;
      next.joints[k].links = v.split(",").map((t) => t.trim()).filter(Boolean);
      edit(next);
    }))).dataset.field = "links";
    cell(tr, j.point);
    const axis = Array.isArray(j.axis) ? Math.atan2(j.axis[1], j.axis[0]) * toAngle : j.axis;
    cell(tr, j.type === "P" ? input(axis === undefined ? "" : toShown(axis, u.A), guarded((v) => {
      const next = structuredClone(m); delete next.catalogue;
      // an angle in the model's unit, as a file has it
      next.joints[k].axis = fromShown(num(v, `${j.name}.axis`), u.A);
      edit(next);
    })) : "").dataset.field = "axis";
    const offset = j.type === "P" && j.axis !== undefined ? offsetOf(m, j, toAngle) : null;
    cell(tr, offset !== null ? input(len(offset), guarded((v) => {
      const next = structuredClone(m); delete next.catalogue;
      next.joints[k].offset = typed(v, `${j.name}.offset`);
      edit(next);
    })) : "").dataset.field = "offset";
    tr.dataset.joint = j.name;
    jt.append(tr);
  }
  root.append(jt);

  if (m.inputs && m.inputs.length) {
    h(`inputs (${u.angle} or ${u.length})`);
    const it = table(["input", "joint", "kind", "range (start, stop)", `speed (${u.angle}/s or ${u.length}/s)`, ""]);
    for (const [k, i] of m.inputs.entries()) {
      const tr = document.createElement("tr");
      cell(tr, i.name || i.joint); cell(tr, i.joint || (i.links || []).join("-"));
      const ij = (m.joints || []).find((j) => j.name === i.joint);
      const slide = ij && ij.type === "P", f = slide ? L : u.A;      // a slide's input is a length
      cell(tr, slide ? "P (slide)" : "R (angle)").dataset.field = "kind";
      const what = `${i.name || i.joint}.range`;
      cell(tr, input((i.range || []).map((v) => toShown(v, f)).join(", "), guarded((v) => {
        const next = structuredClone(m);
        const r = typedRange(v, (t, w) => fromShown(num(t, w), f), what);
        if (r) next.inputs[k].range = r; else delete next.inputs[k].range;
        edit(next);
      }))).dataset.field = "range";
      cell(tr, input(toShown(i.speed ?? 0, f), guarded((v) => {
        const next = structuredClone(m);
        next.inputs[k].speed = fromShown(num(v, `${i.name || i.joint}.speed`), f);
        edit(next);
      }))).dataset.field = "speed";
      const remove = document.createElement("button");
      remove.textContent = "remove";
      remove.title = "No longer an input (the linkage then needs another, or one joint more)";
      remove.onclick = () => draft(withoutInput(m, i.name || i.joint));
      cell(tr, remove).dataset.field = "remove";
      tr.dataset.input = i.name || i.joint;
      it.append(tr);
    }
    root.append(it);
  }

  if (state.study && state.study.branches.length) {
    h("branches (assembly modes)");
    for (const b of state.study.branches) {
      const button = document.createElement("button");
      button.textContent = `switch ${b.points.join("-")}`;
      button.title = `the other assembly mode of ${b.step}`;
      button.dataset.step = b.step;
      button.onclick = () => flip(b.step);
      root.append(button, " ");
    }
  }
  renderTable.values(state);
}

// A link's points after its first two, each by its sides: its distances from two points of
// the link placed before it and its side of the line from the first of them to the second
// (those it is given by, else its first two points' as the sketch draws them).  Typing one
// gives the point by its sides (instead of its local place), and the server re-assembles.
function sidesTable(root, m, u, h, guarded, edit, len, typed) {
  const rows = m.links.flatMap((link, k) => link.points.slice(2).map((p) => [k, link, p]));
  if (!rows.length) return;
  h(`points of links, by their sides (${u.length})`);
  const st = table(["link", "point", "from", "distance", "from", "distance", "side", "distances now"]);
  const f = (v) => Number(v.toPrecision(12));
  for (const [k, link, p] of rows) {
    const refs = sideRefs(link, p);
    const given = (link.sides && link.sides[p]) || measuredSides(m.points, refs, p);
    const write = (spec) => {
      const next = structuredClone(m); delete next.catalogue;
      const l = next.links[k];
      l.sides = {...(l.sides || {}), [p]: spec};
      if (l.local) { delete l.local[p]; if (!Object.keys(l.local).length) delete l.local; }
      edit(next);
    };
    // a new point to measure from: its distance as the points lie, the side of the new pair
    const from = (slot) => {
      const sel = document.createElement("select");
      for (const q of link.points.slice(0, link.points.indexOf(p))) sel.append(new Option(q, q));
      sel.value = refs[slot];
      sel.onchange = guarded(() => {
        const pair = [...refs]; pair[slot] = sel.value;
        if (pair[0] === pair[1]) throw new Error(`${p}: measure its sides from two different points`);
        pair.sort((x, y) => link.points.indexOf(x) - link.points.indexOf(y));
        write(measuredSides(m.points, pair, p, given.side));
      });
      return sel;
    };
    const side = document.createElement("select");
    for (const s of ["left", "right"]) side.append(new Option(s, s));
    side.value = given.side || sideOf(m.points[refs[0]], m.points[refs[1]], m.points[p]) || "left";
    side.onchange = () => write({...given, side: side.value});
    const distance = (slot) => input(len(f(given[refs[slot]])), guarded((v) => write(
      {...given, side: side.value, [refs[slot]]: typed(v, `${p} from ${refs[slot]}`)})));
    const tr = document.createElement("tr");
    tr.dataset.ofLink = link.name; tr.dataset.linkPoint = p; tr.dataset.refs = JSON.stringify(refs);
    cell(tr, link.name); cell(tr, p);
    cell(tr, from(0)).dataset.field = "from1";
    cell(tr, distance(0)).dataset.field = "distance1";
    cell(tr, from(1)).dataset.field = "from2";
    cell(tr, distance(1)).dataset.field = "distance2";
    cell(tr, side).dataset.field = "side";
    cell(tr, "").className = "now-sides";
    st.append(tr);
  }
  root.append(st);
}

// The model with a link's length set (the ground's: its second point moves along the line
// from its first); the table and the drawing's dimensions change lengths through this.
export function withLength(m, name, length) {
  const k = m.links.findIndex((l) => l.name === name);
  if (m.links[k].ground) return groundLength(m, length);
  const next = structuredClone(m); delete next.catalogue;
  next.links[k].length = length;
  return next;
}

// The current configuration's exact values in the table.
renderTable.values = (state) => {
  const s = state.study;
  if (!s) return;
  const u = s.units.length, L = shownUnits(s.units).L;
  const now = {};
  for (const p of Object.keys(s.model.points)) {
    const x = s.columns[`${p}.x[${u}]`], y = s.columns[`${p}.y[${u}]`];   // a narrowed sweep may leave some out
    now[p] = state.config ? state.config.points[p] : x && y ? [x[state.index], y[state.index]] : [null, null];
  }
  const f = (v) => v === null || v === undefined ? "–" : Number((v * L).toPrecision(10)).toString();
  for (const tr of document.querySelectorAll("#tab-table tr[data-point]")) {
    const xy = now[tr.dataset.point] || [null, null];
    tr.querySelector(".now-x").textContent = f(xy[0]);
    tr.querySelector(".now-y").textContent = f(xy[1]);
  }
  for (const tr of document.querySelectorAll("#tab-table tr[data-link]")) {
    const link = s.model.links.find((l) => l.name === tr.dataset.link);
    const [a, b] = link.points;
    tr.querySelector(".now-length").textContent = b && now[a] && now[b] && now[a][0] !== null && now[b][0] !== null
      ? f(dist(now[a], now[b])) : "–";
  }
  const known = (p) => now[p] && now[p][0] !== null;
  for (const tr of document.querySelectorAll("#tab-table tr[data-link-point]")) {
    const p = tr.dataset.linkPoint, refs = JSON.parse(tr.dataset.refs);
    tr.querySelector(".now-sides").textContent = [p, ...refs].every(known)
      ? refs.map((r) => f(dist(now[r], now[p]))).join(", ") : "–";
  }
};
