// The page: one model (the model file's JSON form), its sweep, the sample shown; the panels
// draw from these and change them only through the server's API.
import {post, get, file, download} from "./api.js";
import {Canvas, box} from "./canvas.js";
import {Plot} from "./plot.js";
import {movePoint} from "./geometry.js";
import {renderTable} from "./table.js";
import {showCentres, derive} from "./method.js";
import * as draw from "./draw.js";
import {synthesisPanel, posesOnDrawing} from "./synth.js";
import {follower} from "./follow.js";
import {chosen, shownUnits, shownColumn, toShown, fromShown} from "./units.js";
import {withLength, num} from "./table.js";
import {forcesPanel} from "./dynamics.js";
import {inputSliders} from "./inputs.js";

const $ = (id) => document.getElementById(id);
const state = {model: null, source: null, study: null, index: 0, config: null,
               history: [], future: [], playing: false, busy: false, pending: null,
               draft: false, frames: 0, lastUpdateMs: null, seq: 0, dragQ: null, hover: null,
               moves: 0, predicted: null, followGap: 0, answers: []};
window.kinelab = state;

function status(text, error = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", error);
}

// -- the model and its sweep ------------------------------------------------------------
const lu = () => state.study.units.length;
const column = (name) => state.study.columns[name];
const place = (p, i) => {             // [null, null] for a point a narrowed sweep leaves out
  const x = column(`${p}.x[${lu()}]`), y = column(`${p}.y[${lu()}]`);
  return x && y ? [x[i], y[i]] : [null, null];
};

// `columns` narrows the sweep's columns to those named (the inputs' always come), and
// `points` to those points' places (all by default): a drag asks only for what it redraws,
// the rest follows when it ends.
async function study(model, source, columns = undefined, points = undefined) {
  const t0 = performance.now();
  const s = await post("/api/study", {model, source, columns, points});
  state.lastStudyMs = performance.now() - t0;
  return s;
}

// Show `model`; on success it becomes the model (as assembled), else `onError` decides.
// The page shows the model asked for last: an answer for one asked for before it is dropped.
async function setModel(model, source, {record = true, refit = true, keepDraft = false} = {}) {
  const ticket = ++state.seq;
  const before = state.model;
  try {
    const s = await study(model, source);
    if (ticket !== state.seq) return false;
    if (record && before) { state.history.push({model: before, source: state.source}); state.future = []; }
    accept(s, source, refit);
    const moved = Object.entries(s.moved)
      .map(([p, d]) => `${p} moved ${Number(d.toPrecision(4))} ${s.units.length}`).join(", ");
    const switched = (s.switched || []).length
      ? `; in the other assembly mode of ${s.switched.join(", ")} (the sketch's does not close)` : "";
    const open = s.unassembled.length
      ? `${s.unassembled.length} of ${s.samples} samples of the input range do not close` : "";
    status([moved || switched ? "assembled: " + (moved || "no point moved") + switched : "", open]
      .filter(Boolean).join("; "));
    return true;
  } catch (err) {
    if (ticket !== state.seq) return false;
    if (keepDraft) {           // a drawing on its way: kept as it is, the reason shown
      if (record && before) { state.history.push({model: before, source: state.source}); state.future = []; }
      state.model = model; state.source = source; state.study = null; state.draft = true;
      showTable();
      redraw();
    } else if (state.model) {  // refused: the model stays, and the table shows it again
      showTable();
    }
    status(err.message, true);
    return false;
  }
}

function accept(s, source, refit) {
  state.study = s; state.model = s.model; state.source = source; state.draft = false;
  state.config = null; state.dragQ = null;     // the last configuration was of the model before
  state.predicted = null;
  unselect();                                  // names of the model before
  if (state.index >= s.samples) state.index = 0;
  if (s.unassembled.includes(state.index)) {      // show a sample where the loops close
    const good = Array.from({length: s.samples}, (_, i) => i).find((i) => !s.unassembled.includes(i));
    if (good !== undefined) state.index = good;
  }
  $("scrub").max = s.samples - 1;
  $("title").textContent = `${s.model.name}${source ? " — " + source : ""}`;
  if (refit) fitView();
  fillPlotChoices();
  showTable();
  redraw();
  plotNow();
  configurationSoon();
}

function fitView() {
  const places = [];
  if (state.study) for (const p of state.study.drawing.links.flatMap((l) => l.points))
    for (let i = 0; i < state.study.samples; i += 4) places.push(place(p, i));
  for (const xy of Object.values(state.model.points)) places.push(xy);
  // a cam's whole turn: the box of its profile's farthest reach about its centre's places
  if (state.study) for (const cam of state.study.drawing.cams || []) {
    if (!cam.profile) continue;
    const reach = Math.max(...cam.profile.map((p) => p && p[0] !== null ? Math.hypot(p[0], p[1]) : 0));
    for (let i = 0; i < state.study.samples; i += 4) {
      const c = place(cam.centre, i);
      if (c && c[0] !== null) places.push([c[0] - reach, c[1] - reach], [c[0] + reach, c[1] + reach]);
    }
  }
  canvas.fit(box(places));
}

function editModel(model) { return setModel(model, state.source); }

// The table drawn again from the model: a value refused (here or by the server) is
// replaced by the model's own, and the reason shown.
function showTable() { renderTable($("tab-table"), state, {edit: editModel, flip, setIndex, refuse, draft: editDraft}); }
function editDraft(model) { return setModel(model, state.source, {keepDraft: true, refit: false}); }
function refuse(message) { status(message, true); showTable(); }

// An empty page to draw on: no model, no sweep, no plot; undo brings the last model back.
function newDrawing() {
  pause();
  state.seq++;                     // answers on their way are for the page before
  draw.cancel();
  if (state.model) { state.history.push({model: state.model, source: state.source}); state.future = []; }
  unselect();
  Object.assign(state, {model: draw.empty(), source: null, study: null, config: null, dragQ: null,
                        predicted: null, draft: true, index: 0, hover: null, derivation: null});
  $("title").textContent = "";
  $("input-value").textContent = "";
  $("scrub").max = 0; $("scrub").value = 0;
  $("plot-y").replaceChildren(); $("plot-x").replaceChildren();
  plot.clear();
  $("centres").replaceChildren(); $("polygons").replaceChildren(); $("derivation").replaceChildren();
  showTable();
  status("");
  redraw();
}

const shown = (tab) => $(`tab-${tab}`).classList.contains("active");

async function flip(step) {
  const ticket = ++state.seq;
  try {
    const r = await post("/api/flip", {model: state.model, source: state.source, step});
    if (ticket === state.seq) await setModel(r.model, state.source);
  } catch (err) { if (ticket === state.seq) status(err.message, true); }
}

// -- drawing -------------------------------------------------------------------------------
function scene() {
  const poses = document.querySelector("#tabs button[data-tab=synthesis]").classList.contains("active")
    ? posesOnDrawing($("tab-synthesis"), state.model.units) : [];
  if (state.pose) poses.push(state.pose);
  const pending = tool() === "link" ? draw.pending() : null, hover = pending ? state.hover : null;
  if (!state.study) return {points: state.model.points, drawing: draw.drawingOf(state.model), poses,
                            guides: draw.guidesOf(state.model), pending, hover, selected: state.selected,
                            dims: dimensions(state.model.points, draw.drawingOf(state.model))};
  const s = state.study, d = s.drawing;
  const sketch = $("canvas").dataset.sketch === "1";
  const points = {};
  const now = state.predicted || state.config;     // a drag's place drawn at once, then the server's
  for (const p of Object.keys(s.model.points))
    points[p] = sketch ? s.model.points[p] : (now && now.points[p]) || place(p, state.index);
  const {traces, marks} = paths(s);
  const centres = $("show-centres").checked && state.config && !sketch ? state.config.centres : [];
  const guides = sketch ? {} : (now && now.guides) ||
    Object.fromEntries(Object.entries(s.guides || {}).map(([j, a]) => [j, a[state.index]]));
  const turns = sketch ? {} : (now && now.turns) ||
    Object.fromEntries(Object.entries(s.turns || {}).map(([g, a]) => [g, a[state.index]]));
  return {points, drawing: d, traces, marks, centres, guides, turns, poses, pending, hover, selected: state.selected,
          dims: dimensions(points, d)};
}

// Each link's length along it (its first two points, as drawn) and the input's value at
// its pivot, in the units shown.
function dimensions(points, d) {
  if (!$("dims").checked) return [];
  const u = shownUnits(state.model.units), out = [];
  const f = (v) => Number(v.toPrecision(5));
  for (const link of d.links) {
    const [a, b] = link.points;
    if (!b || !points[a] || !points[b] || points[a][0] === null || points[b][0] === null) continue;
    out.push({name: link.name, a: points[a], b: points[b],
              text: `${f(Math.hypot(points[b][0] - points[a][0], points[b][1] - points[a][1]) * u.L)} ${u.length}`});
  }
  const s = state.study;
  if (s && s.inputs.length === 1) {
    const input = (state.model.inputs || [])[0], j = input && d.joints.find((k) => k.name === input.joint);
    const q = state.dragQ !== null && !Array.isArray(state.dragQ) ? state.dragQ : column(s.inputs[0])[state.index];
    if (j && j.type === "R" && q !== null && points[j.point]) {
      const v = shownColumn(s.inputs[0], [q], s.units);
      out.push({name: "input", a: points[j.point], text: `${f(v.values[0])} ${unitOf(v.name)}`});
    }
  }
  return out;
}
const unitOf = (name) => (/\[([^\]]*)\]$/.exec(name) || ["", ""])[1];

// A dimension typed in place: a link's length goes the table's way (the server
// re-assembles, or refuses with the reason); the input's value moves the linkage there.
function editDimension(name, target) {
  const r = target.getBoundingClientRect();
  const box = document.createElement("input");
  box.id = "dim-edit";
  box.dataset.dim = name;
  const u = shownUnits(state.model.units);
  const link = state.model.links.find((l) => l.name === name);
  box.value = name === "input" ? target.textContent.split(" ")[0]
    : toShown(link.length ?? Math.hypot(...[0, 1].map((c) => state.model.points[link.points[1]][c] - state.model.points[link.points[0]][c])), u.L);
  box.style.left = `${r.left}px`; box.style.top = `${r.top - 4}px`;
  document.body.append(box);
  box.focus(); box.select();
  let done = false;
  const close = () => { if (!done) { done = true; box.remove(); } };
  box.addEventListener("keydown", (e) => { if (e.key === "Escape") close(); if (e.key === "Enter") box.blur(); });
  box.addEventListener("blur", close);
  box.addEventListener("change", () => {
    if (done) return;                  // left with Esc
    const text = box.value;
    close();
    try {
      if (name !== "input") { editModel(withLength(state.model, name, fromShown(num(text, `${name}.length`), u.L))); return; }
      const s = state.study, k = shownColumn(s.inputs[0], [1], s.units).values[0];   // shown per model unit
      const q = fromShown(num(text, "input"), k);
      const qs = column(s.inputs[0]);
      let best = 0;
      qs.forEach((v, i) => { if (v !== null && Math.abs(v - q) < Math.abs(qs[best] - q)) best = i; });
      pause();
      setIndex(best);
      state.dragQ = q;                 // exactly there: the server's configuration at q
      configurationSoon();
    } catch (err) { refuse(err.message); }
  });
}

// The traced paths and their marks, made once a sweep (the drawing keeps them while the
// linkage moves).
let drawnPaths = {study: null};
function paths(s) {
  if (drawnPaths.study === s) return drawnPaths;
  const d = s.drawing, traces = {}, marks = [];
  for (const p of d.traced) traces[p] = Array.from({length: s.samples}, (_, i) => place(p, i));
  for (const p of d.traced) {
    for (const i of s.singular) marks.push({kind: "singular", xy: place(p, i)});
    for (const c of s.change_points) marks.push({kind: "change", xy: place(p, c.index)});
  }
  drawnPaths = {study: s, traces, marks};
  return drawnPaths;
}

let redrawAsked = false;
function redrawSoon() {          // at most once a frame
  if (redrawAsked) return;
  redrawAsked = true;
  requestAnimationFrame(() => { redrawAsked = false; if (state.model) redraw(); });
}

function redraw() {
  canvas.unitScale = shownUnits(state.model.units).L;
  canvas.draw(scene());
  forces.draw();
  sliders.show();
  if (state.study) {
    $("scrub").value = state.index;
    const q = state.study.inputs.map((n, k) => {      // where the inputs' sliders left it, else the sample's
      const v = Array.isArray(state.dragQ) ? state.dragQ[k] : column(n)[state.index];
      const c = shownColumn(n, [v], state.study.units);
      return `${c.name} = ${fmt(c.values[0])}`;
    });
    $("input-value").textContent = q.join(", ");
  }
}

const fmt = (v) => v === null ? "–" : Number(v.toPrecision(6)).toString();

function setIndex(i, {exact = false} = {}) {
  if (!state.study) return;                 // nothing swept yet (a drawing on its way)
  state.index = Math.max(0, Math.min(state.study.samples - 1, i));
  if (!exact) { state.config = null; state.dragQ = null; }
  state.predicted = null;
  $("canvas").dataset.sketch = "0";
  redraw();
  plot.at(state.index);
  $("plot").dataset.index = state.index;
  if (shown("table")) renderTable.values(state);
  if (!state.playing) configurationSoon();
}

// -- the plot ------------------------------------------------------------------------------
function fillPlotChoices() {
  const names = Object.keys(state.study.columns);
  const y = $("plot-y"), x = $("plot-x");
  const keepY = y.value, keepX = x.value;
  const inputs = state.study.inputs;
  const preferred = names.find((n) => n.endsWith(".transmission[" + state.study.units.angle + "]"))
    || names.find((n) => /\.angle\[/.test(n) && !n.startsWith("ground") && !inputs.includes(n)) || names[0];
  const label = (n) => shownColumn(n, null, state.study.units).name;
  y.replaceChildren(...names.map((n) => new Option(label(n), n)));
  x.replaceChildren(...[...inputs, "sample"].map((n) => new Option(label(n), n)));
  y.value = names.includes(keepY) ? keepY : preferred;
  x.value = [...inputs, "sample"].includes(keepX) ? keepX : inputs[0];
}

function plotNow() {
  if (!state.study) return;
  const s = state.study, yName = $("plot-y").value, xName = $("plot-x").value;
  const x = xName === "sample" ? {name: xName, values: Array.from({length: s.samples}, (_, i) => i)}
    : shownColumn(xName, column(xName), s.units);
  const y = shownColumn(yName, column(yName), s.units);
  plot.draw({x: x.values, y: y.values, xName: x.name, yName: y.name, singular: s.singular,
             change: s.change_points.map((c) => c.index)});
  plot.at(state.index);
}

// -- one configuration: the tracker's exact answer, instant centres ------------------------
let configTimer = null;
function configurationSoon() {
  clearTimeout(configTimer);
  configTimer = setTimeout(configuration, 60);
}

// At the sample shown, or where a drag left the linkage (between samples).
async function configuration() {
  if (!state.study) return;
  const {model, study, index, dragQ} = state;
  const q = dragQ !== null ? [dragQ].flat() : study.inputs.map((n) => column(n)[index]);
  if (q.some((v) => v === null)) return;
  try {
    const c = await post("/api/configuration", {model, source: state.source, q: q.length === 1 ? q[0] : q});
    if (state.model !== model || state.study !== study || state.index !== index || state.dragQ !== dragQ) return;
    state.config = c;
    showCentres($("centres"), $("polygons"), c, state.study);
    redraw();
    if (shown("table")) renderTable.values(state);
  } catch (err) { if (state.model === model) status(err.message, true); }
}

// -- pointer: move (the linkage follows), edit (the sketch changes), draw ------------------
// The move tool draws the linkage where the sweep puts it at once (follow.js), in the frame
// of the pointer's move, and asks the server to solve the same drag: its answer, the
// tracker's configuration, replaces the drawing when it comes.
let following = {study: null, follower: null};
function predict(name, xy) {
  const s = state.study;
  if (following.study !== s) following = {study: s, follower: follower(s)};
  const p = following.follower && following.follower.nearest(name, xy);
  state.predicted = p ? {...p, move: state.moves} : null;
  if (!p) return;
  state.index = p.index;
  $("canvas").dataset.sketch = "0";
  redraw();
  plot.at(p.index);
}

// How far the drawing drawn at once was from the server's solve, over the drags of this
// page (a fraction of the drawing's size; about 1e-12).
function check(c) {
  const f = following.study === state.study && following.follower;
  const at = f && c.q.length === 1 ? f.at(c.q[0]) : null;
  if (!at) return;
  const size = Math.max(1e-300, ...Object.values(at.points).flat().map(Math.abs));
  for (const [p, xy] of Object.entries(c.points))
    if (xy[0] !== null && at.points[p])
      state.followGap = Math.max(state.followGap, Math.hypot(xy[0] - at.points[p][0], xy[1] - at.points[p][1]) / size);
}

// One request at a time: a pointer move made while one is answered waits, and only the
// newest waiting move is sent when the answer is drawn.
async function dragTo(name, xy, move = state.moves, at = performance.now()) {
  if (state.busy) { state.pending = [name, xy, move, at]; return; }
  state.busy = true;
  const t0 = performance.now();
  const before = state.model;
  try {
    if (tool() === "move") {
      // what the drawing shows, and the polygons while their tab is open; the rest of the
      // configuration comes when the drag ends
      const method = shown("method");
      const parts = ["guides", "turns", ...($("show-centres").checked || method ? ["centres"] : []),
                     ...(method ? ["polygons"] : [])];
      const c = await post("/api/drag", {model: before, source: state.source, point: name, to: xy, parts});
      if (state.model !== before) return;         // another model since: not this one's drag
      state.config = c;
      state.dragQ = c.q.length === 1 ? c.q[0] : c.q;
      check(c);
      if (method) showCentres($("centres"), $("polygons"), c, state.study);
      if (state.predicted && state.predicted.move > move) return;    // a newer move is drawn
      state.predicted = null;
      const q0 = c.q[0], qs = column(state.study.inputs[0]);
      let best = 0;
      qs.forEach((v, i) => { if (v !== null && Math.abs(v - q0) < Math.abs(qs[best] - q0)) best = i; });
      state.index = best;
      $("canvas").dataset.sketch = "0";
      redraw();
      plot.at(best);
      if (shown("table")) renderTable.values(state);
      answered(at);
    } else {
      const model = movePoint(before, name, xy);
      const s = await study(model, state.source, [$("plot-y").value, $("plot-x").value],
                            state.study.drawing.traced);
      if (state.model !== before) return;
      state.lastDragStudyMs = state.lastStudyMs;
      state.study = s; state.model = s.model; state.config = null; state.dragQ = null; state.draft = false;
      if (state.index >= s.samples) state.index = 0;
      state.narrowed = true;          // every column again when the drag ends
      $("canvas").dataset.sketch = "1";
      redraw();
      plotNow();
      answered(at);
    }
    if ($("status").textContent) status("");
  } catch (err) {
    if (state.model === before) {           // the last good configuration stays
      state.predicted = null;
      redraw();
      status(`drag refused: ${err.message}`, true);
    }
  } finally {
    state.lastUpdateMs = performance.now() - t0;
    state.busy = false;
    if (state.pending) { const [n, p, m, t] = state.pending; state.pending = null; dragTo(n, p, m, t); }
  }
}

// The times from a pointer move to the server's answer for it drawn (the last 1,000).
function answered(at) {
  state.answers.push(performance.now() - at);
  if (state.answers.length > 1000) state.answers.splice(0, state.answers.length - 1000);
}

const tool = () => document.querySelector("input[name=tool]:checked").value;
let dragStart = null;

// -- snapping, selection ------------------------------------------------------------------------
// A place snapped (while *snap* is on) to another point of the sketch within a few pixels,
// else to the grid's nearest crossing.
function snapped(xy, except = null) { return snapTo(xy, except).xy; }
function snapTo(xy, except = null) {
  if (!$("snap").checked || !canvas.view) return {xy};
  const near = 10 / canvas.view.s;
  let best = null, bd = near;
  for (const [p, q] of Object.entries(state.model.points)) {
    if (p === except || !q || q[0] === null) continue;
    const d = Math.hypot(q[0] - xy[0], q[1] - xy[1]);
    if (d <= bd) { best = p; bd = d; }
  }
  if (best) return {xy: [...state.model.points[best]], point: best};
  const on = onLine(xy, near, except);
  if (on) return {xy: on};
  const step = canvas.gridStep();
  return {xy: xy.map((v) => Number((Math.round(v / step) * step).toPrecision(12)))};
}

// The nearest place within `near` on a line between two points of a link (the links as
// drawn), or null: snapping puts a point on a link's line before the grid.
function onLine(xy, near, except) {
  const P = state.model.points;
  let best = null, bd = near;
  for (const link of state.model.links || []) {
    const names = link.points.filter((n) => n !== except && P[n] && P[n][0] !== null);
    for (let i = 0; i < names.length; i++) for (let j = i + 1; j < names.length; j++) {
      const [a, b] = [P[names[i]], P[names[j]]];
      const dx = b[0] - a[0], dy = b[1] - a[1], l2 = dx * dx + dy * dy;
      if (!(l2 > 0)) continue;
      const t = Math.min(1, Math.max(0, ((xy[0] - a[0]) * dx + (xy[1] - a[1]) * dy) / l2));
      const q = [a[0] + t * dx, a[1] + t * dy], d = Math.hypot(q[0] - xy[0], q[1] - xy[1]);
      if (d <= bd) { best = q; bd = d; }
    }
  }
  return best;
}

// What a click with *select* picks: a link, a slider block, or a point; a point clicked
// again picks its joints and then its input in turn.
function pick(target, name) {
  const m = state.model, was = state.selected;
  const ds = (target && target.dataset) || {};
  if (ds.link) return {kind: "link", name: ds.link};
  if (ds.block) return {kind: "joint", name: ds.block};
  if (!name) return null;
  const choices = [{kind: "point", name}];
  for (const j of m.joints || []) if (j.point === name) {
    choices.push({kind: "joint", name: j.name, point: name});
    for (const i of m.inputs || []) if (i.joint === j.name) choices.push({kind: "input", name: i.name || i.joint, point: name});
  }
  const k = was ? choices.findIndex((c) => c.kind === was.kind && c.name === was.name) : -1;
  return choices[(k + 1) % choices.length];
}

function unselect(sel = null) {
  state.selected = sel;
  $("selection").textContent = sel ? `selected: ${sel.kind} ${sel.name}` : "";
  $("delete").disabled = !sel;
}
function select(sel) { unselect(sel); if (state.model) redraw(); }

function deleteSelected() {
  const sel = state.selected;
  if (!sel || !state.model) return;
  select(null);
  setModel(draw.remove(state.model, sel), state.source, {keepDraft: true, refit: false});
}

const canvas = new Canvas($("canvas"), {
  down(name, xy, e) {
    if (placing.down(xy, e && e.target)) return "capture";     // the synthesis task's targets
    if (tool() === "select") { canvas.dragging = null; select(pick(e && e.target, name)); return; }
    if (!name) ({xy, point: name} = snapTo(xy));      // on a point snapped to: as a click on it
    const t = tool();
    if (t === "slider") {          // the drag gives the guide's direction
      state.sliderAt = name;
      state.pose = {xy: name ? state.model.points[name] : xy, angle: 0, label: "guide"};
      redraw();
      return "capture";
    }
    if ((t === "move" || t === "edit") && name && state.study) {
      if (t === "move" && state.study.drawing.ground_points.includes(name)) { canvas.dragging = null; return; }
      dragStart = {model: state.model, source: state.source};
      if (t === "edit") { $("canvas").dataset.sketch = "1"; redraw(); }
      return;
    }
    canvas.dragging = null;
    const next = draw.apply(t, state.model, name, xy);
    if (next) setModel(next, state.source, {keepDraft: true, refit: !state.study});
    else redraw();                 // a link's first point, shown waiting for its second
  },
  hover(xy) {                      // a link's first point waits for its second
    if (tool() !== "link" || !draw.pending()) return;
    state.hover = xy;
    redrawSoon();
  },
  move(name, xy) {
    if (placing.move(xy)) return;
    if (!name.from) {
      state.moves += 1;
      if (tool() === "move") predict(name, xy);
      dragTo(name, tool() === "edit" ? snapped(xy, name) : xy);
      return;
    }
    if (tool() === "slider" && !placing.active()) xy = snapped(xy);
    const [x0, y0] = state.pose.xy;
    state.pose = {...state.pose, angle: Math.atan2(xy[1] - y0, xy[0] - x0)};
    redraw();
  },
  async up(name, xy) {
    if (placing.up(xy)) return;
    if (name && name.from && tool() === "slider" && !placing.active()) {
      xy = snapped(xy);
      const at = state.pose.xy;
      state.pose = null;
      const next = draw.slider(state.model, state.sliderAt, at, xy);
      if (next) setModel(next, state.source, {keepDraft: true, refit: !state.study});
      else redraw();
      return;
    }
    if (!name || !dragStart) return;
    while (state.busy || state.pending) await new Promise((r) => setTimeout(r, 10));
    if (tool() === "edit" && state.model !== dragStart.model) {
      state.history.push(dragStart); state.future = [];
    }
    dragStart = null;
    if (state.narrowed) {
      state.narrowed = false;
      const model = state.model;
      try {
        const s = await study(model, state.source);
        if (state.model === model) accept(s, state.source, false);
      } catch (err) { if (state.model === model) status(err.message, true); }
      $("canvas").dataset.sketch = "1";
      redraw();
    }
    configurationSoon();
  },
  panning: () => tool() === "pan" || (space.held && (space.panned = true)),
  dimension: (name, target) => editDimension(name, target),
  viewed: () => { if (state.model) redrawSoon(); },
});

const plot = new Plot($("plot"), (i) => { pause(); setIndex(i); });
const forces = forcesPanel($("tab-forces"), {state, edit: editModel, status, canvas});
const sliders = inputSliders($("player"), state);

// -- animation -------------------------------------------------------------------------------
let last = null, phase = 0;
function frame(t) {
  if (!state.playing) return;
  if (last !== null && state.study) {
    const speed = Number($("speed").value);
    phase += (t - last) / 4000 * speed * state.study.samples;     // a sweep in 4 s at speed 1
    const steps = Math.floor(phase);
    phase -= steps;
    if (steps) { setIndex((state.index + steps) % state.study.samples); state.frames += 1; }
  }
  last = t;
  requestAnimationFrame(frame);
}
function play() {
  if (!state.study) return;
  state.playing = true; last = null; $("play").textContent = "pause";
  $("show-centres").dataset.was = $("show-centres").checked;
  requestAnimationFrame(frame);
}
function pause() {
  if (!state.playing) return;
  state.playing = false; $("play").textContent = "play";
  configurationSoon();
}

// -- undo / redo, files -------------------------------------------------------------------------
async function undo() {
  const prev = state.history.pop();
  if (!prev) return;
  draw.cancel();
  const now = {model: state.model, source: state.source};
  if (await setModel(prev.model, prev.source, {record: false, keepDraft: true})) state.future.push(now);
  else state.future.push(now);
}
async function redo() {
  const next = state.future.pop();
  if (!next) return;
  draw.cancel();
  state.history.push({model: state.model, source: state.source});
  await setModel(next.model, next.source, {record: false, keepDraft: true});
}

// The model chosen last is the one shown, whatever order the answers come in.
async function open(name) {
  const ticket = ++state.seq;
  try {
    const r = await get(`/api/examples/${encodeURIComponent(name)}`);
    if (ticket !== state.seq) return;
    draw.cancel();
    await setModel(r.model, r.source);
  } catch (err) { if (ticket === state.seq) status(err.message, true); }
}

async function loadFile(f) {
  const ticket = ++state.seq;
  try {
    const text = await f.text();
    const r = await post("/api/load", {text, source: f.name});
    if (ticket !== state.seq) return;
    draw.cancel();
    await setModel(r.model, r.source);
  } catch (err) { if (ticket === state.seq) status(err.message, true); }
}

async function save(format) {
  try {
    const r = await post("/api/save", {model: state.model, source: state.source, format});
    const stem = (state.source || state.model.name || "model").replace(/\.(toml|json)$/i, "");
    download(new Blob([r.text], {type: "text/plain"}), `${stem}.${format}`);
  } catch (err) { status(err.message, true); }
}

function svgText(svg) {
  const clone = svg.cloneNode(true);
  for (const g of clone.querySelectorAll("[data-layer=grid]")) g.remove();     // a guide for drawing, not part of it
  clone.setAttribute("xmlns", "http://www.w3.org/2000/svg");
  clone.setAttribute("width", svg.clientWidth);
  clone.setAttribute("height", svg.clientHeight);
  const style = document.createElementNS("http://www.w3.org/2000/svg", "style");
  style.textContent = [...document.styleSheets].flatMap((s) => [...s.cssRules].map((r) => r.cssText)).join("\n");
  clone.prepend(style);
  return new XMLSerializer().serializeToString(clone);
}

async function svgToPng(svg) {
  const img = new Image();
  img.src = URL.createObjectURL(new Blob([svgText(svg)], {type: "image/svg+xml"}));
  await img.decode();
  const c = document.createElement("canvas");
  c.width = svg.clientWidth * 2; c.height = svg.clientHeight * 2;
  const g = c.getContext("2d");
  g.fillStyle = "#fff"; g.fillRect(0, 0, c.width, c.height);
  g.drawImage(img, 0, 0, c.width, c.height);
  return new Promise((r) => c.toBlob(r, "image/png"));
}

async function exportAs(kind) {
  const stem = (state.source || state.model.name || "model").replace(/\.(toml|json)$/i, "");
  try {
    if (kind === "drawing-svg" || kind === "plot-svg") {
      const svg = $(kind === "drawing-svg" ? "canvas" : "plot");
      download(new Blob([svgText(svg)], {type: "image/svg+xml"}), `${stem}_${kind.split("-")[0]}.svg`);
    } else if (kind === "drawing-png" || kind === "plot-png") {
      download(await svgToPng($(kind === "drawing-png" ? "canvas" : "plot")), `${stem}_${kind.split("-")[0]}.png`);
    } else {
      status(`making ${kind}…`);
      const server = kind === "outline-svg" ? "svg" : kind;
      const blob = await file("/api/export", {model: state.model, source: state.source, kind: server});
      download(blob, `${stem}${kind === "outline-svg" ? "_outlines" : ""}.${server}`);
      status("");
    }
  } catch (err) { status(err.message, true); }
}

// -- wiring -------------------------------------------------------------------------------------
$("play").onclick = () => state.playing ? pause() : play();
$("scrub").oninput = (e) => { pause(); setIndex(Number(e.target.value)); };
$("plot-y").onchange = plotNow;
$("plot-x").onchange = plotNow;
$("show-centres").onchange = redraw;
$("undo").onclick = undo;
$("fit").onclick = () => { if (state.model) { fitView(); redraw(); } };
$("grid").onchange = () => { canvas.grid = $("grid").checked; if (state.model) redraw(); };
$("delete").onclick = deleteSelected;
$("dims").onchange = () => { if (state.model) redraw(); };
for (const id of ["unit-length", "unit-angle"]) $(id).onchange = () => {
  chosen.length = $("unit-length").value; chosen.angle = $("unit-angle").value;
  if (!state.model) return;
  showTable();
  if (state.study) { fillPlotChoices(); plotNow(); }
  redraw();
};
$("redo").onclick = redo;
$("save-toml").onclick = () => save("toml");
$("save-json").onclick = () => save("json");
$("new").onclick = newDrawing;
$("open").onchange = (e) => { if (e.target.value) open(e.target.value); e.target.value = ""; };
$("load").onchange = (e) => { if (e.target.files[0]) loadFile(e.target.files[0]); e.target.value = ""; };
$("export").onchange = (e) => { if (e.target.value) exportAs(e.target.value); e.target.value = ""; };
$("derive").onclick = () => derive($("derivation"), state, $("lang").value, status);
$("derive-md").onclick = async () => {
  if (!state.derivation) await derive($("derivation"), state, $("lang").value, status);
  if (state.derivation) download(new Blob([state.derivation.markdown], {type: "text/markdown"}),
                                 `${state.model.name}_derivation.md`);
};
for (const b of document.querySelectorAll("#tabs button")) b.onclick = () => {
  for (const o of document.querySelectorAll("#tabs button")) o.classList.toggle("active", o === b);
  for (const t of document.querySelectorAll(".tab")) t.classList.toggle("active", t.id === "tab-" + b.dataset.tab);
  if (b.dataset.tab === "plot") plotNow();
  if (b.dataset.tab === "table" && state.study) renderTable.values(state);
  if (b.dataset.tab === "method" && state.study) {       // drags leave the polygons out while it is closed
    if (state.config && state.config.polygons !== undefined) showCentres($("centres"), $("polygons"), state.config, state.study);
    else configurationSoon();
  }
  if (state.model) redraw();                // the poses show with the synthesis tab
};
for (const r of document.querySelectorAll("input[name=tool]")) r.addEventListener("change", () => {
  draw.cancel();                            // a link's first point waits no more
  state.hover = null;
  if (tool() !== "select") unselect();
  if (state.model) redraw();
});
document.addEventListener("keydown", (e) => {
  if (e.key === "Escape" && draw.pending()) { draw.cancel(); state.hover = null; if (state.model) redraw(); return; }
  if (e.target.tagName === "INPUT" && e.target.type !== "range" && e.target.type !== "radio") return;
  if ((e.ctrlKey || e.metaKey) && e.key === "z") { e.preventDefault(); undo(); }
  else if ((e.ctrlKey || e.metaKey) && (e.key === "y" || (e.shiftKey && e.key === "Z"))) { e.preventDefault(); redo(); }
  else if ((e.key === "Delete" || e.key === "Backspace") && state.selected) { e.preventDefault(); deleteSelected(); }
  else if (e.key === " " && e.target.tagName !== "BUTTON") { e.preventDefault(); space.held = true; }
});
// Space held while dragging pans; pressed and let go without a drag, it plays or pauses.
const space = {held: false, panned: false};
document.addEventListener("keyup", (e) => {
  if (e.key !== " " || !space.held) return;
  if (!space.panned) state.playing ? pause() : play();
  space.held = false; space.panned = false;
});
window.addEventListener("resize", () => { if (state.model) { fitView(); redraw(); plotNow(); } });
const placing = synthesisPanel($("tab-synthesis"), {
  open: (model, source) => setModel(model, source), status,
  units: () => state.model && state.model.units, redraw: () => state.model && redraw(),
  pixel: () => 1 / canvas.view.s});
state.setIndex = setIndex;
state.canvas = canvas;
state.play = play;
state.pause = pause;
state.configurationSoon = configurationSoon;

(async () => {
  try {
    const list = await get("/api/catalogue");
    const sel = $("open");
    for (const n of list.examples) sel.append(new Option(`example: ${n}`, n));
    for (const n of list.catalogue) sel.append(new Option(`catalogue: ${n}`, `catalogue:${n}`));
    const start = await get("/api/start");
    if (start.model) await setModel(start.model, start.source, {record: false});
    else await open(list.examples.includes("crank_rocker") ? "crank_rocker" : "catalogue:fourbar");
    state.history = [];
  } catch (err) { status(err.message, true); }
  document.body.dataset.ready = "1";
})();
