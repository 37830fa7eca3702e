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
import {forcesPanel} from "./dynamics.js";

const $ = (id) => document.getElementById(id);
const state = {model: null, source: null, study: null, index: 0, config: null,
               history: [], future: [], playing: false, busy: false, pending: null,
               draft: false, frames: 0, lastUpdateMs: null};
window.kinelab = state;

function status(text, error = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", error);
}

// -- the model and its sweep ------------------------------------------------------------
const lu = () => state.study.units.length;
const column = (name) => state.study.columns[name];
const place = (p, i) => [column(`${p}.x[${lu()}]`)[i], column(`${p}.y[${lu()}]`)[i]];

// `columns` narrows the sweep's columns to those named (the points' and the inputs' always
// come): a drag asks only for what it redraws, the rest follows when it ends.
async function study(model, source, columns = undefined) {
  const t0 = performance.now();
  const s = await post("/api/study", {model, source, columns});
  state.lastStudyMs = performance.now() - t0;
  return s;
}

// Show `model`; on success it becomes the model (as assembled), else `onError` decides.
async function setModel(model, source, {record = true, refit = true, keepDraft = false} = {}) {
  const before = state.model;
  try {
    const s = await study(model, source);
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
    if (keepDraft) {           // a drawing on its way: kept as it is, the reason shown
      if (record && before) { state.history.push({model: before, source: state.source}); state.future = []; }
      state.model = model; state.source = source; state.study = null; state.draft = true;
      redraw();
    } else if (state.model) {  // refused: the model stays, and the table shows it again
      renderTable($("tab-table"), state, {edit: editModel, flip, setIndex});
    }
    status(err.message, true);
    return false;
  }
}

function accept(s, source, refit) {
  state.study = s; state.model = s.model; state.source = source; state.draft = false;
  state.config = null;             // the last configuration was of the model before
  if (state.index >= s.samples) state.index = 0;
  if (s.unassembled.includes(state.index)) {      // show a sample where the loops close
    const good = Array.from({length: s.samples}, (_, i) => i).find((i) => !s.unassembled.includes(i));
    if (good !== undefined) state.index = good;
  }
  $("scrub").max = s.samples - 1;
  $("title").textContent = `${s.model.name}${source ? " — " + source : ""}`;
  if (refit) fitView();
  fillPlotChoices();
  renderTable($("tab-table"), state, {edit: editModel, flip, setIndex});
  redraw();
  plotNow();
  configurationSoon();
}

function fitView() {
  const places = [];
  if (state.study) for (const p of state.study.drawing.links.flatMap((l) => l.points))
    for (let i = 0; i < state.study.samples; i += 4) places.push(place(p, i));
  for (const xy of Object.values(state.model.points)) places.push(xy);
  canvas.fit(box(places));
}

function editModel(model) { return setModel(model, state.source); }

async function flip(step) {
  try {
    const r = await post("/api/flip", {model: state.model, source: state.source, step});
    await setModel(r.model, state.source);
  } catch (err) { status(err.message, true); }
}

// -- drawing -------------------------------------------------------------------------------
function scene() {
  const poses = document.querySelector("#tabs button[data-tab=synthesis]").classList.contains("active")
    ? posesOnDrawing($("tab-synthesis"), state.model.units) : [];
  if (state.pose) poses.push(state.pose);
  if (!state.study) return {points: state.model.points, drawing: draw.drawingOf(state.model), poses};
  const s = state.study, d = s.drawing;
  const sketch = $("canvas").dataset.sketch === "1";
  const points = {};
  for (const p of Object.keys(s.model.points))
    points[p] = sketch ? s.model.points[p] : (state.config && state.config.points[p]) || place(p, state.index);
  const traces = {};
  for (const p of d.traced) traces[p] = Array.from({length: s.samples}, (_, i) => place(p, i));
  const marks = [];
  for (const p of d.traced) {
    for (const i of s.singular) marks.push({kind: "singular", xy: place(p, i)});
    for (const c of s.change_points) marks.push({kind: "change", xy: place(p, c.index)});
  }
  const centres = $("show-centres").checked && state.config && !sketch ? state.config.centres : [];
  return {points, drawing: d, traces, marks, centres, poses};
}

function redraw() {
  canvas.draw(scene());
  forces.draw();
  if (state.study) {
    $("scrub").value = state.index;
    const q = state.study.inputs.map((n) => `${n} = ${fmt(column(n)[state.index])}`);
    $("input-value").textContent = q.join(", ");
  }
}

const fmt = (v) => v === null ? "–" : Number(v.toPrecision(6)).toString();

function setIndex(i, {exact = false} = {}) {
  state.index = Math.max(0, Math.min(state.study.samples - 1, i));
  if (!exact) state.config = null;
  $("canvas").dataset.sketch = "0";
  redraw();
  plot.at(state.index);
  $("plot").dataset.index = state.index;
  renderTable.values && renderTable.values(state);
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
  y.replaceChildren(...names.map((n) => new Option(n, n)));
  x.replaceChildren(...[...inputs, "sample"].map((n) => new Option(n, n)));
  y.value = names.includes(keepY) ? keepY : preferred;
  x.value = [...inputs, "sample"].includes(keepX) ? keepX : inputs[0];
}

function plotNow() {
  if (!state.study) return;
  const s = state.study, yName = $("plot-y").value, xName = $("plot-x").value;
  const x = xName === "sample" ? Array.from({length: s.samples}, (_, i) => i) : column(xName);
  plot.draw({x, y: column(yName), xName, yName, singular: s.singular,
             change: s.change_points.map((c) => c.index)});
  plot.at(state.index);
}

// -- one configuration: the tracker's exact answer, instant centres ------------------------
let configTimer = null;
function configurationSoon() {
  clearTimeout(configTimer);
  configTimer = setTimeout(configuration, 60);
}

async function configuration() {
  if (!state.study) return;
  const q = state.study.inputs.map((n) => column(n)[state.index]);
  if (q.some((v) => v === null)) return;
  try {
    const c = await post("/api/configuration", {model: state.model, source: state.source,
                                                 q: q.length === 1 ? q[0] : q});
    state.config = c;
    showCentres($("centres"), $("polygons"), c, state.study);
    redraw();
  } catch (err) { status(err.message, true); }
}

// -- pointer: move (the linkage follows), edit (the sketch changes), draw ------------------
async function dragTo(name, xy) {
  if (state.busy) { state.pending = [name, xy]; return; }
  state.busy = true;
  const t0 = performance.now();
  try {
    if (tool() === "move") {
      const c = await post("/api/drag", {model: state.model, source: state.source, point: name, to: xy});
      state.config = c;
      showCentres($("centres"), $("polygons"), c, state.study);
      const q0 = c.q[0], qs = column(state.study.inputs[0]);
      let best = 0;
      qs.forEach((v, i) => { if (v !== null && Math.abs(v - q0) < Math.abs(qs[best] - q0)) best = i; });
      state.index = best;
      $("canvas").dataset.sketch = "0";
      redraw();
      plot.at(best);
      renderTable.values && renderTable.values(state);
    } else {
      const model = movePoint(state.model, name, xy);
      const s = await study(model, state.source, [$("plot-y").value, $("plot-x").value]);
      state.lastDragStudyMs = state.lastStudyMs;
      state.study = s; state.model = s.model; state.config = null; state.draft = false;
      if (state.index >= s.samples) state.index = 0;
      state.narrowed = true;          // every column again when the drag ends
      $("canvas").dataset.sketch = "1";
      redraw();
      plotNow();
    }
    status("");
  } catch (err) {
    status(`drag refused: ${err.message}`, true);      // the last good configuration stays
  } finally {
    state.lastUpdateMs = performance.now() - t0;
    state.busy = false;
    if (state.pending) { const [n, p] = state.pending; state.pending = null; dragTo(n, p); }
  }
}

const tool = () => document.querySelector("input[name=tool]:checked").value;
let dragStart = null;

const canvas = new Canvas($("canvas"), {
  down(name, xy) {
    if (placing.active()) { state.pose = {xy, angle: 0}; redraw(); return "capture"; }
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
  },
  move(name, xy) {
    if (!name.from) { dragTo(name, xy); return; }
    const [x0, y0] = state.pose.xy;
    state.pose = {...state.pose, angle: Math.atan2(xy[1] - y0, xy[0] - x0)};
    redraw();
  },
  async up(name, xy) {
    if (name && name.from && tool() === "slider" && !placing.active()) {
      const at = state.pose.xy;
      state.pose = null;
      const next = draw.slider(state.model, state.sliderAt, at, xy);
      if (next) setModel(next, state.source, {keepDraft: true, refit: !state.study});
      else redraw();
      return;
    }
    if (name && name.from) { state.pose = null; placing.add(name.from, xy); return; }
    if (!name || !dragStart) return;
    while (state.busy || state.pending) await new Promise((r) => setTimeout(r, 10));
    if (tool() === "edit" && state.model !== dragStart.model) {
      state.history.push(dragStart); state.future = [];
    }
    dragStart = null;
    if (state.narrowed) {
      state.narrowed = false;
      try { accept(await study(state.model, state.source), state.source, false); }
      catch (err) { status(err.message, true); }
      $("canvas").dataset.sketch = "1";
      redraw();
    }
    configurationSoon();
  },
});

const plot = new Plot($("plot"), (i) => { pause(); setIndex(i); });
const forces = forcesPanel($("tab-forces"), {state, edit: editModel, status, canvas});

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
  const now = {model: state.model, source: state.source};
  if (await setModel(prev.model, prev.source, {record: false, keepDraft: true})) state.future.push(now);
  else state.future.push(now);
}
async function redo() {
  const next = state.future.pop();
  if (!next) return;
  state.history.push({model: state.model, source: state.source});
  await setModel(next.model, next.source, {record: false, keepDraft: true});
}

async function open(name) {
  try {
    const r = await get(`/api/examples/${encodeURIComponent(name)}`);
    await setModel(r.model, r.source);
  } catch (err) { status(err.message, true); }
}

async function loadFile(f) {
  try {
    const text = await f.text();
    const r = await post("/api/load", {text, source: f.name});
    await setModel(r.model, r.source);
  } catch (err) { status(err.message, true); }
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
$("redo").onclick = redo;
$("save-toml").onclick = () => save("toml");
$("save-json").onclick = () => save("json");
$("new").onclick = () => setModel(draw.empty(), null, {keepDraft: true});
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
  if (state.model) redraw();                // the poses show with the synthesis tab
};
document.addEventListener("keydown", (e) => {
  if (e.target.tagName === "INPUT" && e.target.type !== "range" && e.target.type !== "radio") return;
  if ((e.ctrlKey || e.metaKey) && e.key === "z") { e.preventDefault(); undo(); }
  else if ((e.ctrlKey || e.metaKey) && (e.key === "y" || (e.shiftKey && e.key === "Z"))) { e.preventDefault(); redo(); }
  else if (e.key === " " && e.target.tagName !== "BUTTON") { e.preventDefault(); state.playing ? pause() : play(); }
});
window.addEventListener("resize", () => { if (state.model) { fitView(); redraw(); plotNow(); } });
const placing = synthesisPanel($("tab-synthesis"), {
  open: (model, source) => setModel(model, source), status,
  units: () => state.model && state.model.units, redraw: () => state.model && redraw()});
state.setIndex = setIndex;
state.play = play;
state.pause = pause;

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
