// The forces tab: the masses and loads of the model (its links' mass, centre of mass and
// inertia; its [dynamics] section: gravity, point masses, forces, torques, springs,
// dampers), typed in tables; the inverse dynamics of its sweep as `kinelab dynamics`
// computes it: the input's torque (or force), the joint reactions and the shaking force,
// plotted against the input, listed at the configuration shown and drawn on the linkage.
import {post, file, download} from "./api.js";
import {Plot} from "./plot.js";
import {el} from "./canvas.js";
import {local} from "./geometry.js";

const make = (tag, attrs = {}, text = "") => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
};
const fmt = (v) => v === null || v === undefined ? "–" : Number(Number(v).toPrecision(6)).toString();
// A number where the text is one, else the text itself (a law's expression of t, q, qd, or
// a mistake): the server reads it as the model file's value, and says what is wrong with it.
const value = (text) => { const t = text.trim(); return t !== "" && Number.isFinite(Number(t)) ? Number(t) : t; };

function fresh(prefix, taken) {
  if (!taken.includes(prefix)) return prefix;
  for (let i = 2; ; i++) if (!taken.includes(prefix + i)) return prefix + i;
}

// The panel in `root`.  `state` is the page's (model, study, index); `edit(model)` makes a
// model the page's (false when the server refuses it); `canvas` is the drawing's.
export function forcesPanel(root, {state, edit, canvas}) {
  const panel = {root, state, edit, canvas, model: null, answer: null};
  root.innerHTML = `
    <div class="row"><button id="forces-compute" title="Solve the forces again">compute</button>
      <button id="forces-csv" title="The table kinelab dynamics writes">export .csv</button>
      <label><input type="checkbox" id="forces-arrows" checked> forces on the drawing</label></div>
    <div id="forces-message" role="alert"></div>
    <div id="forces-place-hint" class="hint"></div>
    <div id="forces-results">
      <div class="row"><label>y <select id="forces-y"></select></label>
        <label>x <select id="forces-x"></select></label></div>
      <svg id="forces-plot" role="img" aria-label="forces plot"></svg>
      <table id="forces-now"></table>
    </div>
    <div id="forces-data"></div>
    <p class="hint">The masses and loads are the model file's (see docs/dynamics.md): gravity,
    forces, torques, springs and dampers in SI units whatever the drawing's; a force or torque
    may be a number or an expression of t, q, qd.  The numbers are those of
    <code>kinelab dynamics</code> of the saved model.</p>`;
  const $ = (sel) => root.querySelector(sel);
  panel.plot = new Plot($("#forces-plot"), (i) => { state.pause && state.pause(); state.setIndex(i); });
  $("#forces-compute").onclick = () => compute(panel);
  $("#forces-csv").onclick = () => exportCsv(panel);
  $("#forces-arrows").onchange = () => { if (state.model) state.setIndex(state.index, {exact: true}); };
  $("#forces-y").onchange = () => plotNow(panel);
  $("#forces-x").onchange = () => plotNow(panel);
  const tab = document.querySelector("#tabs button[data-tab=forces]");
  if (tab) tab.addEventListener("click", () => { renderData(panel); ensure(panel); });
  panel.active = () => root.classList.contains("active");
  // a centre of mass or a force being placed on the drawing takes the next press on it
  // (before the drawing's own tools see it)
  canvas.svg.parentNode.addEventListener("pointerdown", (e) => {
    if (!panel.placing || !panel.active() || !canvas.svg.contains(e.target) || !canvas.view) return;
    e.stopPropagation();
    e.preventDefault();
    const r = canvas.svg.getBoundingClientRect();
    placeAt(panel, canvas.toModel([e.clientX - r.left, e.clientY - r.top]),
            e.target.dataset ? e.target.dataset.point : undefined);
  }, {capture: true});
  // Called after every redraw of the drawing: a new model is solved again (at once if the
  // tab is open, else when it opens), and the arrows are drawn at the configuration shown.
  panel.draw = () => {
    if (state.model !== panel.model) {
      panel.model = state.model;
      if (panel.active()) { renderData(panel); ensure(panel); }
    }
    drawArrows(panel);
    showNow(panel);
  };
  return panel;
}

// -- the server's answer ------------------------------------------------------------------
// The forces of the model shown, asked for once per model: a moment after its last change
// (an edit drag changes it at every step), one request at a time.
function ensure(panel) {
  if (panel.state.dynamicsOf === panel.state.model) return;
  clearTimeout(panel.soon);
  panel.soon = setTimeout(() => compute(panel), 120);
}

async function compute(panel) {
  const {state} = panel;
  if (!state.model || !state.study) return;
  if (panel.asking) { panel.again = true; return; }
  const model = state.model;
  panel.asking = true;
  message(panel, "");
  try {
    const answer = await post("/api/dynamics", {model, source: state.source});
    if (state.model !== model) return;               // the model changed meanwhile: again
    panel.answer = answer;
    state.dynamics = answer;
    state.dynamicsOf = model;         // the model these forces are of
    fillChoices(panel);
    plotNow(panel);
    showNow(panel);
    drawArrows(panel);
    panel.root.querySelector("#forces-results").hidden = false;
  } catch (err) {
    if (state.model !== model) return;
    panel.answer = null;
    state.dynamics = null;
    state.dynamicsOf = model;
    panel.root.querySelector("#forces-results").hidden = true;
    drawArrows(panel);
    message(panel, (/mass: missing/.test(err.message)
      ? "Give each moving link its mass, centre of mass and inertia below, or mark it massless.\n" : "")
      + err.message);
  } finally {
    panel.asking = false;
    if (panel.again) { panel.again = false; compute(panel); }
  }
}

function message(panel, text) {
  const box = panel.root.querySelector("#forces-message");
  box.textContent = text;
  box.classList.toggle("error", Boolean(text));
}

async function exportCsv(panel) {
  const {state} = panel;
  try {
    const blob = await file("/api/dynamics", {model: state.model, source: state.source, format: "csv"});
    download(blob, panel.answer ? panel.answer.file : `${state.model.name || "model"}_dynamics.csv`);
  } catch (err) { message(panel, err.message); }
}

// -- plot and values at the configuration shown -------------------------------------------
function series(panel) {
  const a = panel.answer, c = a.columns, out = {};
  for (const e of a.efforts) out[e] = c[e];
  for (const r of a.reactions) {
    out[`${r.joint}.reaction[N]`] = c[r.x].map((x, i) => x === null || c[r.y][i] === null ? null : Math.hypot(x, c[r.y][i]));
    out[r.x] = c[r.x]; out[r.y] = c[r.y];
  }
  const s = a.shaking;    // null when the reactions are refused (a rocking cam follower)
  if (s) out["shaking_force[N]"] = c[s.x].map((x, i) => x === null || c[s.y][i] === null ? null : Math.hypot(x, c[s.y][i]));
  for (const n of Object.keys(c)) if (!(n in out) && !a.inputs.includes(n) && n !== "t[s]") out[n] = c[n];
  return out;
}

function fillChoices(panel) {
  const y = panel.root.querySelector("#forces-y"), x = panel.root.querySelector("#forces-x");
  const names = Object.keys(series(panel));
  const keepY = y.value, keepX = x.value;
  y.replaceChildren(...names.map((n) => new Option(n, n)));
  const xs = [...panel.answer.inputs, "t[s]", "sample"];
  x.replaceChildren(...xs.map((n) => new Option(n, n)));
  y.value = names.includes(keepY) ? keepY : panel.answer.efforts[0];
  x.value = xs.includes(keepX) ? keepX : xs[0];
}

function plotNow(panel) {
  const a = panel.answer;
  if (!a) return;
  const yName = panel.root.querySelector("#forces-y").value, xName = panel.root.querySelector("#forces-x").value;
  const x = xName === "sample" ? Array.from({length: a.samples}, (_, i) => i) : a.columns[xName];
  panel.plot.draw({x, y: series(panel)[yName], xName, yName, singular: a.singular});
  panel.plot.at(panel.state.index);
}

function showNow(panel) {
  const a = panel.answer, t = panel.root.querySelector("#forces-now");
  if (!a || !t || !panel.active() || a.samples !== (panel.state.study && panel.state.study.samples)) return;
  const i = panel.state.index, c = a.columns;
  panel.plot.at(i);
  const rows = [["", "x", "y", "magnitude"]];
  for (const [k, e] of a.efforts.entries())
    rows.push([`${a.input_joints[k].name}: ${a.input_joints[k].kind === "angle" ? "input torque [N m]" : "input force [N]"}`, "", "", c[e][i], {effort: e}]);
  for (const r of a.reactions) {
    const x = c[r.x][i], y = c[r.y][i];
    rows.push([`${r.joint} at ${r.point} [N] (on ${r.links[1]} from ${r.links[0]})`, x, y,
               x === null || y === null ? null : Math.hypot(x, y), {reaction: r.joint}]);
  }
  const s = a.shaking;
  if (s) {
    const sx = c[s.x][i], sy = c[s.y][i];
    rows.push(["shaking force [N]", sx, sy, sx === null || sy === null ? null : Math.hypot(sx, sy), {shaking: "force"}]);
    rows.push(["shaking moment [N m] (about the origin)", "", "", c[s.moment][i], {shaking: "moment"}]);
  }
  t.replaceChildren();
  rows.forEach((r, k) => {
    const tr = make("tr");
    if (r[4]) for (const [key, v] of Object.entries(r[4])) tr.dataset[key] = v;
    for (const v of r.slice(0, 4)) tr.append(make(k ? "td" : "th", {}, typeof v === "number" || v === null ? fmt(v) : v));
    if (k && typeof r[3] === "number") tr.lastChild.dataset.value = String(r[3]);
    t.append(tr);
  });
}

// -- arrows on the drawing ------------------------------------------------------------------
function place(state, p) {
  const s = state.study, u = s.units.length, i = state.index;
  const x = s.columns[`${p}.x[${u}]`], y = s.columns[`${p}.y[${u}]`];
  return x && y && x[i] !== null && y[i] !== null ? [x[i], y[i]] : null;
}

function drawArrows(panel) {
  const {state, canvas} = panel;
  const svg = canvas.svg, old = svg.querySelector("g.forces");
  if (old) old.remove();
  const a = panel.answer;
  if (!a || !panel.active() || !panel.root.querySelector("#forces-arrows").checked || !state.study
      || state.dynamicsOf !== state.model || a.samples !== state.study.samples
      || svg.dataset.sketch === "1" || !canvas.view) return;
  const i = state.index, c = a.columns;
  const g = el("g", {class: "forces"}, svg);
  const defs = el("defs", {}, g);
  for (const kind of ["reaction", "shaking", "load", "effort"]) {
    const m = el("marker", {id: `force-head-${kind}`, viewBox: "0 0 10 10", refX: 9, refY: 5,
                            markerWidth: 6, markerHeight: 6, orient: "auto-start-reverse"}, defs);
    el("path", {d: "M0,0 L10,5 L0,10 z", class: `head-${kind}`}, m);
  }
  // one scale for every force over the whole sweep: the largest is a quarter of the view
  const forces = [];
  for (const r of a.reactions) forces.push([c[r.x], c[r.y]]);
  if (a.shaking) forces.push([c[a.shaking.x], c[a.shaking.y]]);
  for (const f of a.loads.forces) forces.push([f.x, f.y]);
  let most = 0;
  for (const [xs, ys] of forces) xs.forEach((x, k) => { if (x !== null && ys[k] !== null) most = Math.max(most, Math.hypot(x, ys[k])); });
  const size = Math.min(svg.clientWidth || 600, svg.clientHeight || 400) / 4;
  const px = most > 0 ? size / most : 0;
  const arrow = (at, f, kind, label, data) => {
    if (!at || f[0] === null || f[1] === null) return;
    const [X, Y] = canvas.toScreen(at);
    const [U, V] = [X + px * f[0], Y - px * f[1]];
    const line = el("line", {x1: X, y1: Y, x2: U, y2: V, class: `force ${kind}`,
                             "marker-end": `url(#force-head-${kind})`, "data-force": data,
                             "data-value": Math.hypot(f[0], f[1])}, g);
    if (Math.hypot(U - X, V - Y) < 1) line.setAttribute("marker-end", "");
    el("text", {x: U + 4, y: V - 4, class: `force-label ${kind}`}, g).textContent =
      `${label} ${fmt(Math.hypot(f[0], f[1]))} N`;
  };
  for (const r of a.reactions) arrow(place(state, r.point), [c[r.x][i], c[r.y][i]], "reaction", r.joint, r.joint);
  if (a.shaking) {
    const ground = a.shaking.at ? place(state, a.shaking.at) : [0, 0];
    arrow(ground, [c[a.shaking.x][i], c[a.shaking.y][i]], "shaking", "shaking", "shaking");
  }
  a.loads.forces.forEach((f, k) => arrow(place(state, f.point), [f.x[i], f.y[i]], "load", `F${k + 1}`, `force-${k}`));
  // the input's effort: a turning arrow round its joint (a torque), or along its slide
  a.input_joints.forEach((inp, k) => {
    const joint = inp.joint && a.reactions.find((r) => r.joint === inp.joint);
    const at = joint ? place(state, joint.point) : null, v = c[a.efforts[k]][i];
    if (!at || v === null) return;
    const [X, Y] = canvas.toScreen(at), R = 22, sweep = v >= 0 ? 0 : 1;
    const a0 = -Math.PI / 3, a1 = Math.PI * 1.1;                  // CCW from a0 to a1 on the page
    const p0 = [X + R * Math.cos(a0), Y - R * Math.sin(a0)], p1 = [X + R * Math.cos(a1), Y - R * Math.sin(a1)];
    const [from, to] = v >= 0 ? [p0, p1] : [p1, p0];
    el("path", {d: `M${from[0]},${from[1]} A${R},${R} 0 1 ${sweep ? 1 : 0} ${to[0]},${to[1]}`,
                class: "force effort", "marker-end": "url(#force-head-effort)", "data-force": "effort",
                "data-value": v}, g);
    el("text", {x: X + R + 4, y: Y + R + 10, class: "force-label effort"}, g).textContent =
      `${inp.kind === "angle" ? "τ" : "F"} ${fmt(v)} ${inp.kind === "angle" ? "N m" : "N"}`;
  });
}

// -- the masses and loads, typed ------------------------------------------------------------
function renderData(panel) {
  const {state} = panel;
  const box = panel.root.querySelector("#forces-data");
  box.replaceChildren();
  const m = state.model;
  if (!m) return;
  const u = (m.units && m.units.length) || "m";
  const dyn = m.dynamics || {};
  const massless = new Set(dyn.massless || []);
  const pointNames = Object.keys(m.points);
  const linkNames = m.links.map((l) => l.name);
  const h = (text) => box.append(make("h3", {}, text));
  // every edit: a copy of the model changed, given to the page, which re-assembles it
  const change = (f) => async () => {
    const next = structuredClone(state.model);
    delete next.catalogue;
    next.dynamics = next.dynamics || {};
    f(next, next.dynamics);
    for (const k of Object.keys(next.dynamics))
      if (Array.isArray(next.dynamics[k]) && !next.dynamics[k].length) delete next.dynamics[k];
    if (next.dynamics.point_masses && !Object.keys(next.dynamics.point_masses).length) delete next.dynamics.point_masses;
    if (!Object.keys(next.dynamics).length) delete next.dynamics;
    const ok = await panel.edit(next);
    if (!ok) { message(panel, document.getElementById("status").textContent); renderData(panel); }
  };
  const text = (value, onchange, attrs = {}) => {
    const i = make("input", {spellcheck: "false", ...attrs});
    i.value = value === undefined || value === null ? "" : value;
    i.addEventListener("change", () => onchange(i.value)());
    return i;
  };
  const choose = (options, value, onchange, blank = null) => {
    const s = make("select");
    if (blank !== null) s.append(new Option(blank, ""));
    for (const o of options) s.append(new Option(o, o));
    s.value = value ?? "";
    s.onchange = () => onchange(s.value)();
    return s;
  };
  const remove = (f) => { const b = make("button", {class: "remove", title: "remove"}, "×"); b.onclick = change(f); return b; };
  const table = (head) => { const t = make("table"); const tr = make("tr"); for (const x of head) tr.append(make("th", {}, x)); t.append(tr); box.append(t); return t; };
  const row = (t, cells, data = {}) => {
    const tr = make("tr");
    for (const [k, v] of Object.entries(data)) tr.dataset[k] = v;
    for (const cell of cells) {
      const td = make("td");
      if (Array.isArray(cell)) { td.dataset.field = cell[0]; td.append(cell[1]); }
      else if (cell instanceof Node) td.append(cell); else td.textContent = cell;
      tr.append(td);
    }
    t.append(tr);
    return tr;
  };

  h(`masses of the links (kg; inertia in kg ${u}² about the centre of mass)`);
  const lt = table(["link", "massless", "mass", "centre of mass", "", "inertia"]);
  m.links.forEach((link, k) => {
    if (link.ground) return;
    const none = make("input", {type: "checkbox"});
    none.checked = massless.has(link.name);
    none.onchange = change((n, d) => {
      const set = new Set(d.massless || []);
      if (none.checked) { set.add(link.name); delete n.links[k].mass; delete n.links[k].inertia; delete n.links[k].center_of_mass; }
      else set.delete(link.name);
      d.massless = [...set];
    });
    const field = (key) => text(link[key], (v) => change((n, d) => {
      if (v.trim() === "") delete n.links[k][key]; else n.links[k][key] = value(v);
      if (key === "mass" && v.trim() !== "") d.massless = (d.massless || []).filter((x) => x !== link.name);
    }));
    const G = choose([...link.points, "+ new point"], link.center_of_mass, (v) => change((n) => {
      if (v === "") { delete n.links[k].center_of_mass; return; }
      n.links[k].center_of_mass = v === "+ new point" ? centreOfMassPoint(n, k) : v;
    }), "–");
    const put = make("button", {class: "place", title: "Click on the drawing where its centre of mass is"}, "place");
    put.onclick = () => startPlacing(panel, {kind: "centre", link: link.name},
                                     `click on the drawing where the centre of mass of ${link.name} is`);
    row(lt, [link.name, ["massless", none], ["mass", field("mass")], ["center_of_mass", G], put,
             ["inertia", field("inertia")]], {link: link.name});
  });

  h("gravity (m/s²)");
  const g = dyn.gravity || [0, 0];
  const gt = table(["gx", "gy", ""]);
  const standard = make("button", {id: "forces-standard-gravity"}, "0, −9.81");
  standard.onclick = change((n, d) => { d.gravity = [0, -9.81]; });
  row(gt, [["gx", text(g[0], (v) => change((n, d) => { d.gravity = [value(v), g[1]]; }))],
           ["gy", text(g[1], (v) => change((n, d) => { d.gravity = [g[0], value(v)]; }))], standard]);

  // "+ force" and the like: a row added to the section (its id: forces-add-force, ...)
  const adder = (label, f) => {
    const b = make("button", {class: "add", id: `forces-add-${label.slice(2).replace(" ", "-")}`}, label);
    b.onclick = change(f);
    box.append(b);
  };

  h("point masses (kg)");
  const pm = dyn.point_masses || {};
  const pt = table(["point", "mass", ""]);
  for (const [p, v] of Object.entries(pm)) {
    row(pt, [choose(pointNames, p, (w) => change((n, d) => {
      const next = {}; for (const [q, x] of Object.entries(d.point_masses)) next[q === p ? w : q] = x; d.point_masses = next;
    })), ["mass", text(v, (w) => change((n, d) => { d.point_masses[p] = value(w); }))],
      remove((n, d) => { delete d.point_masses[p]; })], {pointMass: p});
  }
  adder("+ point mass", (n, d) => {
    const free = pointNames.find((p) => !(p in pm));
    if (free) d.point_masses = {...(d.point_masses || {}), [free]: 1.0};
  });

  h("forces (N, x and y in the ground frame: numbers or expressions of t, q, qd)");
  const ft = table(["point", "on link", "fx", "fy", ""]);
  (dyn.forces || []).forEach((f, k) => {
    const carriers = m.links.filter((l) => l.points.includes(f.point)).map((l) => l.name);
    row(ft, [["point", choose(pointNames, f.point, (v) => change((n, d) => { d.forces[k].point = v; delete d.forces[k].link; }))],
             ["link", choose(carriers, f.link, (v) => change((n, d) => { if (v) d.forces[k].link = v; else delete d.forces[k].link; }), "first moving")],
             ["fx", text(f.fx ?? 0, (v) => change((n, d) => { d.forces[k].fx = value(v); }))],
             ["fy", text(f.fy ?? 0, (v) => change((n, d) => { d.forces[k].fy = value(v); }))],
             remove((n, d) => { d.forces.splice(k, 1); })], {force: k});
  });
  const onDrawing = make("button", {class: "add", id: "forces-place-force"}, "+ force at a point of the drawing");
  onDrawing.onclick = () => startPlacing(panel, {kind: "force"}, "click on the point of the drawing the force acts at");
  box.append(onDrawing);
  adder("+ force", (n, d) => {
    const moving = m.links.find((l) => !l.ground && l.points.length);
    d.forces = [...(d.forces || []), {point: moving ? moving.points[moving.points.length - 1] : pointNames[0], fx: 0, fy: 0}];
  });

  h("torques (N m, counter-clockwise: numbers or expressions of t, q, qd)");
  const tt = table(["link", "torque", "reacting link", ""]);
  (dyn.torques || []).forEach((t, k) => {
    row(tt, [["link", choose(linkNames, t.link, (v) => change((n, d) => { d.torques[k].link = v; }))],
             ["torque", text(t.torque, (v) => change((n, d) => { d.torques[k].torque = value(v); }))],
             ["reacting", choose(linkNames, t.reacting, (v) => change((n, d) => { if (v) d.torques[k].reacting = v; else delete d.torques[k].reacting; }), "none")],
             remove((n, d) => { d.torques.splice(k, 1); })], {torque: k});
  });
  adder("+ torque", (n, d) => {
    const moving = m.links.find((l) => !l.ground);
    d.torques = [...(d.torques || []), {link: moving ? moving.name : linkNames[0], torque: 0}];
  });

  for (const [kind, key] of [["springs", "stiffness"], ["dampers", "damping"]]) {
    h(kind === "springs" ? "springs (stiffness in N/m, free length in m)" : "dampers (damping in N s/m)");
    const st = table(kind === "springs" ? ["from", "to", "stiffness", "free length", ""] : ["from", "to", "damping", ""]);
    (dyn[kind] || []).forEach((s, k) => {
      const cells = [["from", choose(pointNames, s.points[0], (v) => change((n, d) => { d[kind][k].points[0] = v; }))],
                     ["to", choose(pointNames, s.points[1], (v) => change((n, d) => { d[kind][k].points[1] = v; }))],
                     [key, text(s[key], (v) => change((n, d) => { d[kind][k][key] = value(v); }))]];
      if (kind === "springs") cells.push(["free_length", text(s.free_length ?? 0, (v) => change((n, d) => { d[kind][k].free_length = value(v); }))]);
      cells.push(remove((n, d) => { d[kind].splice(k, 1); }));
      row(st, cells, {[kind === "springs" ? "spring" : "damper"]: k});
    });
    adder(`+ ${kind.slice(0, -1)}`, (n, d) => {
      const [a, b] = pointNames;
      d[kind] = [...(d[kind] || []), kind === "springs" ? {points: [a, b], stiffness: 0, free_length: 0}
                                                       : {points: [a, b], damping: 0}];
    });
  }
}

// -- placing on the drawing ---------------------------------------------------------------
function startPlacing(panel, what, hint) {
  endPlacing(panel);
  panel.placing = what;
  panel.root.querySelector("#forces-place-hint").textContent = hint + " (Esc: never mind)";
  panel.escape = (e) => { if (e.key === "Escape") endPlacing(panel); };
  document.addEventListener("keydown", panel.escape);
}

function endPlacing(panel) {
  panel.placing = null;
  if (panel.escape) document.removeEventListener("keydown", panel.escape);
  panel.escape = null;
  panel.root.querySelector("#forces-place-hint").textContent = "";
}

// The place of each point in the drawing now: the configuration shown, or the sketch.
function shownPlaces(panel) {
  const {state, canvas} = panel, out = {};
  for (const p of Object.keys(state.model.points))
    out[p] = (canvas.svg.dataset.sketch !== "1" && state.study && place(state, p)) || state.model.points[p];
  return out;
}

async function placeAt(panel, xy, point) {
  const what = panel.placing;
  endPlacing(panel);
  const {state} = panel;
  const next = structuredClone(state.model);
  delete next.catalogue;
  if (what.kind === "force") {
    if (!point) { message(panel, "a force acts at a point: click on one of the drawing's points"); return; }
    next.dynamics = {...(next.dynamics || {})};
    next.dynamics.forces = [...(next.dynamics.forces || []), {point, fx: 0, fy: 0}];
  } else {
    const k = next.links.findIndex((l) => l.name === what.link);
    const at = shownPlaces(panel);
    next.links[k].center_of_mass = centreOfMassAt(next, k, at, xy);
  }
  message(panel, "");
  const ok = await panel.edit(next);
  if (!ok) message(panel, document.getElementById("status").textContent);
}

// The centre of mass of link k at `xy` (in the drawing as shown, `at` its points' places
// there): its point (one of its own, moved, when it is carried by this link alone and no
// joint is there; else a new one), placed in the sketch where it lies in the link's frame,
// and, where the link's shape is given exactly, in its `local` places.  Its name.
function centreOfMassAt(model, k, at, xy) {
  const link = model.links[k];
  if (link.points.length < 2) return link.points[0];
  const [a, b] = link.points;
  const mine = link.center_of_mass;
  const own = mine && link.points.indexOf(mine) > 1 && !(model.joints || []).some((j) => j.point === mine)
    && model.links.filter((l) => l.points.includes(mine)).length === 1;
  const name = own ? mine : fresh(`G_${link.name}`.replace(/[^A-Za-z0-9_]/g, "_"), Object.keys(model.points));
  const [along, left] = local(at[a], at[b], xy);
  const A = model.points[a], B = model.points[b];
  const L = Math.hypot(B[0] - A[0], B[1] - A[1]), ex = (B[0] - A[0]) / L, ey = (B[1] - A[1]) / L;
  const r = (v) => Number(v.toPrecision(10));
  model.points[name] = [r(A[0] + along * ex - left * ey), r(A[1] + along * ey + left * ex)];
  if (link.length !== undefined || link.local) {
    link.local = {...(link.local || {}), [name]: [r(along), r(left)]};
  }
  if (link.sides) { delete link.sides[name]; if (!Object.keys(link.sides).length) delete link.sides; }
  if (!own) link.points.push(name);
  return name;
}

// A new point at the middle of link k's first two points (its only point for a slider),
// carried by the link and placed in its frame where the link's shape is given exactly:
// the centre of mass of a uniform bar.  Its name.
function centreOfMassPoint(model, k) {
  const link = model.links[k];
  const name = fresh(`G_${link.name}`.replace(/[^A-Za-z0-9_]/g, "_"), Object.keys(model.points));
  const [a, b] = link.points.map((p) => model.points[p]);
  if (!b) { model.points[name] = [...a]; link.points.push(name); return name; }
  const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
  model.points[name] = mid.map((v) => Number(v.toPrecision(14)));
  if (link.length !== undefined || link.local) {
    link.local = {...(link.local || {}), [name]: link.length !== undefined ? [link.length / 2, 0] : local(a, b, mid)};
  }
  link.points.push(name);
  return name;
}
