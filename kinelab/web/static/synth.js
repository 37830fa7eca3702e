// The synthesis panel: a task typed in a form (the content of a `kinelab synth` task file),
// solved on the server, its linkages listed; any of them opens as the model.
import {post} from "./api.js";
import {DECIMAL} from "./table.js";

const LENGTHS = ["m", "cm", "mm", "in"], ANGLES = ["deg", "rad"];

// Each kind: its units, its fields [key in the task, label, kind, example], the poses it
// takes ("poses": x y angle per line, "points": x y per line, "pairs": input and output
// angle per line) and the task's fixed entries.
// The examples are those of docs/synthesis.md (Flores & Claro, Mecanismos, §6.5 and §6.7).
export const KINDS = {
  "crank-rocker": {label: "crank-rocker: rocker swing and time ratio", task: {task: "crank-rocker"},
    units: ["mm", "deg"], fields: [
      ["crank_rocker.ground", "ground O2O4", "length", "100"],
      ["crank_rocker.swing", "rocker swing", "angle", "45"],
      ["crank_rocker.time_ratio", "time ratio", "", "1.25"],
      ["crank_rocker.crank", "crank (optional)", "length", ""],
      ["crank_rocker.pivot_angle", "pivot angle (optional)", "angle", ""]]},
  "quick-return": {label: "quick return: stroke and time ratio", task: {task: "quick-return"},
    units: ["mm", "deg"], fields: [
      ["quick_return.mechanism", "mechanism", ["offset slider-crank", "slotted lever", "whitworth"], "offset slider-crank"],
      ["quick_return.time_ratio", "time ratio", "", "1.4"],
      ["quick_return.stroke", "stroke", "length", "100"],
      ["quick_return.distance", "distance O2O4 (slotted lever, whitworth)", "length", ""],
      ["quick_return.rod", "rod (optional)", "length", ""]]},
  "three": {label: "motion: three positions", task: {task: "motion"}, units: ["m", "deg"], count: 3,
    poses: "1 1 0\n2 0.5 0\n3 1.5 45", fields: [
      ["pivots.A0", "A0, fixed pivot (or A1)", "point", "5, 0"],
      ["pivots.A1", "A1, moving pivot in position 1", "point", ""],
      ["pivots.B0", "B0, fixed pivot (or B1)", "point", "0, 0"],
      ["pivots.B1", "B1, moving pivot in position 1", "point", ""]]},
  "four": {label: "motion: four positions", task: {task: "motion"}, units: ["cm", "deg"], count: 4,
    poses: "0 0 0\n5 8 10\n10 15 20\n18 20 30", fields: [
      ["pivots.a0x", "a0x, centre point's x", "length", "-20.195"],
      ["pivots.b0x", "b0x, centre point's x", "length", "-29.167"]]},
  "five": {label: "motion: five positions (Burmester's points)", task: {task: "motion"},
    units: ["m", "deg"], count: 5, poses: "1.017 1.8027 55.771\n1.3272 2.356 38.173\n0.9699 2.6022 30.099\n" +
      "0.3165 2.4733 29.379\n-0.2622 2.0126 34.235", fields: []},
  "function": {label: "function generation", task: {task: "function"}, units: ["m", "deg"], fields: [
    ["function.expression", "y = f(x)", "text", "log10(x)"],
    ["function.x_range", "x from, to", "pair", "1, 2"],
    ["function.input_range", "crank angle from, to", "pair", "90, 150"],
    ["function.output_range", "rocker angle from, to", "pair", "0, 90"],
    ["function.points", "precision points", "", "3"],
    ["function.ground", "ground", "length", "1"]]},
  // the pairs of the catalogue crank-rocker (ground 1, crank 1/3, coupler 1, rocker 5/6)
  "function-pairs": {label: "function generation: angle pairs (input -> output)", task: {task: "function"},
    units: ["m", "deg"], pairs: "40 87.1\n70 92.2\n100 102.7", fields: [
      ["function.O2", "O2, input pivot", "point", "0, 0"],
      ["function.O4", "O4, output pivot", "point", "1, 0"]]},
  "path": {label: "path generation", task: {task: "path"}, units: ["m", "deg"],
    points: "0 0\n0.25 0.02\n0.5 0.03\n0.75 0.02\n1 0", fields: [
      ["search.runs", "runs", "", "1"], ["search.maxiter", "iterations", "", "100"],
      ["search.seed", "seed", "", "0"]]},
};

const make = (tag, attrs = {}, text = "") => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  if (text) e.textContent = text;
  return e;
};

// A number where the text is a decimal one, else the text itself: the server names what
// is wrong ("0x10" is not read as 16).
const value = (text) => { const t = text.trim(); return DECIMAL.test(t) && Number.isFinite(Number(t)) ? Number(t) : t; };
const numbers = (text) => text.split(/[\s,;]+/).filter((t) => t !== "").map(value);
const rows = (text) => text.split("\n").map((l) => l.trim()).filter((l) => l && !l.startsWith("#")).map(numbers);

// The task's targets on the drawing: the poses, the path's points and the pivots, written
// into the form in the task's units (where they stay editable) and drawn in the drawing's.
// A placing asks for them on the drawing: a press for each pose's point and a drag for its
// angle, a press for each point (a drag before letting go moves it), two presses for each
// pair of angles (towards the input ray's direction from O2, then the output ray's from O4).
// Any target drawn is dragged to move it (a pose keeps its angle; a ray's handle turns it
// about its pivot, to whole degrees while the page's snap is on).  Esc cancels a placing or
// a drag: the form is as it was before it.
const METRES = {m: 1, cm: 0.01, mm: 0.001, in: 0.0254};
const short = (v) => Number(v.toPrecision(6)) + 0;          // + 0: no "-0" in the form
const placed = {
  root: null, units: () => null, redraw: () => {}, pixel: () => 1,
  placing: null,      // {what: "poses" | "points" | "pairs" | a pivot's field, count, left, form,
                      //  side: "in" | "out" (the ray of a pair to place next)}
  grabbed: null,      // {key, aim: [x, y] (a pose's angle being dragged), ray, offset, form}
  taken: false,       // the drawing's pointer drag is ours, from its press to its release
  active() { return this.placing !== null; },
  // `what`: "poses" or "points" (that many, in place of those of the form, in the drawing's
  // units), or a point field's key.
  start(what, count = 1) {
    const u = this.units(), root = this.root;
    if (!u) return;
    this.stop();
    if (what === "pairs" && !(this.pivot("in") && this.pivot("out"))) {
      root.querySelector("#synth-place-hint").textContent = "O2 and O4 first: type them or place them on the drawing";
      return;
    }
    this.placing = {what, count, left: count, side: "in", form: this.form()};
    if (what === "poses" || what === "points") {
      for (const [id, v] of [["#synth-length", u.length], ["#synth-angle", u.angle]]) {
        root.querySelector(id).value = v;
        root.querySelector(id).dispatchEvent(new Event("change"));
      }
    }
    if (what === "poses" || what === "points" || what === "pairs") root.querySelector("#synth-poses").value = "";
    this.hint();
    this.redraw();
  },
  hint() {
    const p = this.placing, root = this.root;
    if (!root) return;
    for (const h of root.querySelectorAll(".place-hint")) h.textContent = "";
    if (!p) return;
    const done = p.count - p.left + 1;
    const [where, text] = p.what === "poses"
      ? ["#synth-place-hint", `pose ${done} of ${p.count}: click its point on the drawing, drag towards its angle (Esc cancels)`]
      : p.what === "points" ? ["#synth-place-hint", `point ${done} of ${p.count}: click it on the drawing (Esc cancels)`]
      : p.what === "pairs" ? ["#synth-place-hint", p.side === "in"
        ? `pair ${done} of ${p.count}: click towards its input angle from O2 (Esc cancels)`
        : `pair ${done} of ${p.count}: click towards its output angle from O4 (Esc cancels)`]
      : [`[data-hint='${p.what}']`, "click its place on the drawing (Esc cancels)"];
    const h = root.querySelector(where);
    if (h) h.textContent = text;
  },
  stop() { this.placing = null; this.hint(); },
  // Esc: the form as before the placing or the drag.
  cancel() {
    const was = (this.grabbed && this.grabbed.form) || (this.placing && this.placing.form);
    if (!was) return false;
    this.grabbed = null;
    this.stop();
    this.restore(was);
    this.redraw();
    return true;
  },
  form() {
    const r = this.root;
    return {poses: r.querySelector("#synth-poses")?.value, length: r.querySelector("#synth-length").value,
            angle: r.querySelector("#synth-angle").value,
            fields: [...r.querySelectorAll("[data-field]")].map((e) => [e.dataset.field, e.value])};
  },
  restore(was) {
    const r = this.root;
    const area = r.querySelector("#synth-poses");
    if (area && was.poses !== undefined) area.value = was.poses;
    for (const [key, v] of was.fields) { const e = r.querySelector(`[data-field='${key}']`); if (e) e.value = v; }
    for (const [id, v] of [["#synth-length", was.length], ["#synth-angle", was.angle]]) {
      r.querySelector(id).value = v;
      r.querySelector(id).dispatchEvent(new Event("change"));
    }
  },

  // The drawing's pointer (places in the drawing's units): a press is taken (the answer true)
  // while placing, or on a target drawn (`target` the element pressed).
  down(xy, target) {
    const key = target && target.dataset ? target.dataset.target : undefined;
    if (!this.placing && !key) return false;
    this.taken = true;
    const p = this.placing;
    if (p && p.what === "pairs") {
      const area = this.root.querySelector("#synth-poses");
      // a new pair's input starts as the previous pair's, whose turn it is taken nearest
      const last = rows(area.value).at(-1), from = last && Number.isFinite(last[0]) ? last[0] : 0;
      if (p.side === "in") area.value = (area.value.trim() ? area.value.trim() + "\n" : "") + from;
      const at = `pair ${rows(area.value).length} ${p.side}`;
      this.grabbed = {key: at, ray: true};
      this.turn(at, xy);
    } else if (p) {
      let at = p.what;
      if (p.what === "poses" || p.what === "points") {
        const area = this.root.querySelector("#synth-poses");
        area.value = (area.value.trim() ? area.value.trim() + "\n" : "") + (p.what === "poses" ? "0 0 0" : "0 0");
        at = `${p.what === "poses" ? "pose" : "point"} ${rows(area.value).length}`;
      }
      this.grabbed = {key: at, aim: p.what === "poses" ? xy : null, offset: [0, 0]};
      this.put(at, xy);
    } else {
      const was = targetsOf(this.root, this.units()).find((t) => t.key === key);
      if (!was) { this.taken = false; return false; }
      this.grabbed = was.ray !== undefined ? {key, ray: true, form: this.form()}
        : {key, aim: null, offset: [was.xy[0] - xy[0], was.xy[1] - xy[1]], form: this.form()};
    }
    this.redraw();
    return true;
  },
  move(xy) {
    if (!this.taken) return false;
    const g = this.grabbed;
    if (g && g.ray) this.turn(g.key, xy);
    else if (g && g.aim) this.aim(g.key, g.aim, xy);
    else if (g) this.put(g.key, [xy[0] + g.offset[0], xy[1] + g.offset[1]]);
    if (g) this.redraw();
    return true;
  },
  up(xy) {
    if (!this.taken) return false;
    this.move(xy);
    this.taken = false;
    if (!this.grabbed) return true;             // cancelled on the way
    this.grabbed = null;
    const p = this.placing;
    if (p && p.what === "pairs" && p.side === "in") p.side = "out";
    else if (p) { p.left -= 1; p.side = "in"; if (!p.left) this.placing = null; }
    if (p) this.hint();
    this.redraw();
    return true;
  },

  // Target `key` put at xy (drawing units), written in the task's units to a tenth of the
  // drawing's pixel; a pose keeps its angle.
  put(key, xy) {
    const digits = Math.max(0, Math.min(12, -Math.floor(Math.log10(this.pixel() * this.scale() / 10))));
    const [x, y] = xy.map((v) => Number((v * this.scale()).toFixed(digits)) + 0);
    const [kind, n] = key.split(" ");
    if (kind === "pose" || kind === "point")
      this.line(Number(n), (old) => [x, y, ...old.slice(2)].join(" "));
    else this.root.querySelector(`[data-field='${key}']`).value = `${x}, ${y}`;
  },
  // Pose `key`'s angle, that of the drag from `at` to `to`.
  aim(key, at, to) {
    const angle = Math.hypot(to[0] - at[0], to[1] - at[1]) > 0 ? Math.atan2(to[1] - at[1], to[0] - at[0]) : 0;
    const a = short(this.root.querySelector("#synth-angle").value === "deg" ? angle * 180 / Math.PI : angle);
    this.line(Number(key.split(" ")[1]), (old) => [...old.slice(0, 2), a].join(" "));
  },
  // The fixed pivot of a pair's `side` ("in": O2, "out": O4) in the drawing's units, or null.
  pivot(side) {
    const e = this.root.querySelector(`[data-field='function.${side === "in" ? "O2" : "O4"}']`);
    const xy = e && pointOf(e.value);
    return xy && xy.map((v) => v / this.scale());
  },
  // Pair `key`'s ray ("pair n in" | "pair n out") turned towards xy about its pivot: the
  // angle the turn nearest the ray's angle before (or the previous pair's, for a new one),
  // so that a drag across 180 deg goes on to 181 rather than jumping to -179.
  turn(key, xy) {
    const [, n, side] = key.split(" "), k = side === "in" ? 0 : 1;
    const O = this.pivot(side);
    if (!O || Math.hypot(xy[0] - O[0], xy[1] - O[1]) === 0) return;
    const deg = this.root.querySelector("#synth-angle").value === "deg";
    const r = rows(this.root.querySelector("#synth-poses").value);
    const near = [r[n - 1], r[n - 2]].map((row) => row && row[k]).find(Number.isFinite);
    let a = Math.atan2(xy[1] - O[1], xy[0] - O[0]);
    if (near !== undefined) {
      const ref = deg ? near * Math.PI / 180 : near;
      a += 2 * Math.PI * Math.round((ref - a) / (2 * Math.PI));
    }
    let v = deg ? a * 180 / Math.PI : a;
    if (document.getElementById("snap")?.checked) v = deg ? Math.round(v) : Math.round(v * 180 / Math.PI) * Math.PI / 180;
    v = short(v);
    this.line(Number(n), (old) => (k === 0 ? [v, ...old.slice(1)] : [old[0], v, ...old.slice(2)]).join(" "));
  },
  // The n-th line of the poses or points (counted as `rows` counts them) made anew from its numbers.
  line(n, change) {
    const area = this.root.querySelector("#synth-poses");
    let k = 0;
    area.value = area.value.split("\n").map((l) => {
      const t = l.trim();
      if (!t || t.startsWith("#")) return l;
      k += 1;
      return k === n ? change(t.split(/[\s,;]+/)) : l;
    }).join("\n");
  },
  // Task units per drawing unit.
  scale() { return METRES[this.units().length] / METRES[this.root.querySelector("#synth-length").value]; },
};

// Where a point field's text is two numbers: [x, y], else null.
const pointOf = (text) => { const v = numbers(text); return v.length === 2 && v.every(Number.isFinite) ? v : null; };

// The targets of the form, in the drawing's units: poses ({key, xy, angle in rad}), and the
// path's points and the pivots ({key, xy, mark: "point" | "fixed" | "moving", label}).
function targetsOf(root, units) {
  const kind = KINDS[root.querySelector("#synth-kind").value];
  const area = root.querySelector("#synth-poses");
  if (!kind || !units) return [];
  const scale = METRES[root.querySelector("#synth-length").value] / METRES[units.length];
  const deg = root.querySelector("#synth-angle").value === "deg";
  const at = (x, y) => [x * scale, y * scale];
  const out = [];
  if (area) rows(area.value).forEach((r, i) => {
    if (kind.poses && r.length === 3 && r.every(Number.isFinite))
      out.push({key: `pose ${i + 1}`, xy: at(r[0], r[1]), angle: deg ? r[2] * Math.PI / 180 : r[2]});
    else if (kind.points && r.length === 2 && r.every(Number.isFinite))
      out.push({key: `point ${i + 1}`, xy: at(r[0], r[1]), mark: "point", label: String(i + 1)});
  });
  const fields = {};
  for (const [key, , type] of kind.fields) {
    const xy = type === "point" && pointOf(root.querySelector(`[data-field='${key}']`).value);
    if (xy) out.push({key, xy: fields[key] = at(...xy), mark: key.endsWith("0") || kind.pairs ? "fixed" : "moving",
                      label: key.split(".")[1]});
  }
  // each pair: a ray from O2 at its input angle, one from O4 at its output angle (a pair
  // half placed, or half typed: its input ray alone)
  if (area && kind.pairs) rows(area.value).forEach((r, i) => {
    r.slice(0, 2).forEach((v, k) => {
      const O = fields[k ? "function.O4" : "function.O2"], side = k ? "out" : "in";
      if (O && Number.isFinite(v))
        out.push({key: `pair ${i + 1} ${side}`, xy: O, ray: deg ? v * Math.PI / 180 : v, side, label: String(i + 1)});
    });
  });
  return out;
}

// What the drawing shows of the task (the canvas's poses).
export {targetsOf as posesOnDrawing};

function put(task, key, v) {
  const [section, name] = key.split(".");
  (task[section] ??= {})[name] = v;
}

// The task the form describes, as the task file's content.
export function taskOf(root) {
  const kind = KINDS[root.querySelector("#synth-kind").value];
  const task = structuredClone(kind.task);
  task.units = {length: root.querySelector("#synth-length").value, angle: root.querySelector("#synth-angle").value};
  const poses = root.querySelector("#synth-poses");
  if (kind.poses) {
    const r = rows(poses.value);
    task.positions = {points: r.map((p) => p.slice(0, 2)), angles: r.map((p) => p[2])};
  } else if (kind.points) {
    task.positions = {points: rows(poses.value)};
  } else if (kind.pairs) {
    task.function = {pairs: rows(poses.value)};
  }
  for (const [key, , type] of kind.fields) {
    const text = root.querySelector(`[data-field='${key}']`).value;
    if (text.trim() === "") continue;
    put(task, key, type === "point" || type === "pair" ? numbers(text) : type === "text" || Array.isArray(type) ? text : value(text));
  }
  return task;
}

function form(root, kindName, units) {
  const kind = KINDS[kindName];
  const box = root.querySelector("#synth-form");
  box.replaceChildren();
  const [lu, au] = kind.units;
  root.querySelector("#synth-length").value = lu;
  root.querySelector("#synth-angle").value = au;
  const unit = (type) => type === "length" || type === "point" ? () => root.querySelector("#synth-length").value
    : type === "angle" ? () => root.querySelector("#synth-angle").value : () => "";
  if (kind.poses || kind.points || kind.pairs) {
    const label = make("label", {}, kind.poses ? "poses: x y angle, one per line" : kind.points
      ? "points: x y, one per line" : "precision pairs: input angle, output angle (from +x), one per line");
    const area = make("textarea", {id: "synth-poses", rows: 6, spellcheck: "false"});
    area.value = kind.poses || kind.points || kind.pairs;
    area.oninput = () => placed.redraw();
    label.append(make("br"), area);
    box.append(label);
  }
  if (kind.poses || kind.points || kind.pairs) {
    const row = make("div", {class: "row"});
    const hint = make("span", {id: "synth-place-hint", class: "hint place-hint"});
    if (kind.poses) {
      const place = make("button", {id: "synth-place", title: "Click on the drawing for each pose's point, drag for its angle"},
                         `place ${kind.count} poses on the drawing`);
      place.onclick = () => placed.start("poses", kind.count);
      row.append(place, hint);
    } else {
      const pairs = Boolean(kind.pairs), low = pairs ? 3 : 2;
      const count = make("input", {id: "synth-place-count", type: "number", min: low, max: 100, step: 1,
                                   value: rows(kind.points || kind.pairs).length,
                                   title: pairs ? "How many pairs to place" : "How many points to place"});
      const place = make("button", {id: "synth-place", title: pairs
        ? "For each pair, click on the drawing towards its input angle from O2, then towards its output angle from O4"
        : "Click on the drawing for each point of the path, in order"}, "place");
      place.onclick = () => {
        const n = Number(count.value);
        if (Number.isInteger(n) && n >= low && n <= 100) placed.start(pairs ? "pairs" : "points", n);
        else hint.textContent = `the ${pairs ? "pairs" : "points"} to place: a whole number from ${low} to 100, not '${count.value}'`;
      };
      row.append(place, count, make("span", {}, pairs ? "pairs on the drawing" : "points on the drawing"), hint);
    }
    box.append(row);
  }
  const t = make("table");
  for (const [key, label, type, example] of kind.fields) {
    const tr = make("tr");
    const td = make("td");
    let input;
    if (Array.isArray(type)) {
      input = make("select");
      for (const c of type) input.append(new Option(c, c));
    } else input = make("input", {spellcheck: "false"});
    input.value = example;
    input.dataset.field = key;
    td.append(input);
    const u = make("td", {class: "unit"});
    const show = unit(type);
    u.textContent = show();
    u.dataset.unit = type;
    tr.append(make("td", {}, label), td, u);
    if (type === "point") {               // x, y: drawn, and placed on the drawing
      input.oninput = () => placed.redraw();
      const place = make("button", {class: "place-point", "data-place": key,
                                    title: "Click on the drawing where it goes (drag it there afterwards to move it)"}, "place");
      place.onclick = () => placed.start(key);
      const cell = make("td");
      cell.append(place, make("span", {class: "hint place-hint", "data-hint": key}));
      tr.append(cell);
    }
    t.append(tr);
  }
  box.append(t);
  const refresh = () => { for (const u of box.querySelectorAll("td.unit")) u.textContent = unit(u.dataset.unit)(); };
  root.querySelector("#synth-length").onchange = () => { refresh(); placed.redraw(); };
  root.querySelector("#synth-angle").onchange = () => { refresh(); placed.redraw(); };
}

const f = (v) => Number(Number(v).toPrecision(5)).toString();

function describe(row, units) {
  const parts = [Object.entries(row.lengths).map(([k, v]) => `${k} ${f(v)}`).join(", ") + ` ${units.length}`];
  if (row.swing !== undefined) parts.push(`swing ${f(row.swing)} ${units.angle}`);
  if (row.stroke !== undefined) parts.push(`stroke ${f(row.stroke)} ${units.length}`);
  if (row.time_ratio !== undefined) parts.push(`time ratio ${f(row.time_ratio)}`);
  const mu = row.min_transmission_angle ?? row.transmission_min;
  if (mu !== undefined) {
    let text = `min transmission ${f(mu)} ${units.angle}`;
    if (row.transmission_limit !== undefined)
      text += ` (${row.meets_transmission_limit ? "meets" : "below"} the ${f(row.transmission_limit)} ${units.angle} limit)`;
    parts.push(text);
  }
  if (row.rms_error !== undefined) parts.push(`rms error ${f(row.rms_error)} ${units.length}`);
  if (row.max_structural_error !== undefined) parts.push(`max structural error ${f(row.max_structural_error)}`);
  return parts.join("; ");
}

function results(root, answer, open) {
  const box = root.querySelector("#synth-results");
  box.replaceChildren();
  const head = make("p", {}, `${answer.solutions.length} linkage(s)` + (answer.reason ? ` (${answer.reason})` : ""));
  box.append(head);
  const t = make("table", {class: "solutions"});
  const hr = make("tr");
  for (const h of ["", "Grashof class", "defects", "linkage", ""]) hr.append(make("th", {}, h));
  t.append(hr);
  answer.solutions.forEach((row, i) => {
    const tr = make("tr", {"data-solution": row.solution});
    const defects = row.defects === undefined ? "–" : row.defects.length ? row.defects.join(", ") : "none";
    const button = make("button", {class: "open-solution"}, "open");
    button.onclick = () => open(answer.models[i], `${answer.name}_solution_${row.solution}.toml`);
    for (const c of [String(row.solution), row.grashof || row.mechanism, defects, describe(row, answer.units)])
      tr.append(make("td", {}, c));
    const td = make("td"); td.append(button); tr.append(td);
    t.append(tr);
  });
  box.append(t);
}

// The panel in `root`; `open(model, source)` makes a linkage the model; `status` reports.
// `units()` gives the drawing's units, `pixel()` its pixel's size in them; `redraw()` redraws
// it with the task.  The answer is the task's targets on the drawing: {active(), down(xy,
// element), move(xy), up(xy)} for the drawing's pointer, each true when the drag is theirs.
export function synthesisPanel(root, {open, status, units, redraw, pixel}) {
  Object.assign(placed, {root, units, redraw, pixel});
  document.addEventListener("keydown", (e) => { if (e.key === "Escape") placed.cancel(); });
  for (const b of document.querySelectorAll("#tabs button"))      // another tab: no more placing
    b.addEventListener("click", () => { if (b.dataset.tab !== "synthesis") placed.stop(); });
  root.innerHTML = `<div class="row"><label>task <select id="synth-kind"></select></label>
    <label>length <select id="synth-length"></select></label>
    <label>angle <select id="synth-angle"></select></label></div>
    <div id="synth-form"></div>
    <div class="row"><button id="synth-solve">solve</button></div>
    <div id="synth-results"></div>
    <p class="hint">The task is the content of a <code>kinelab synth</code> task file
    (docs/synthesis.md), solved on the server as the command solves it.</p>`;
  const kind = root.querySelector("#synth-kind");
  for (const [k, v] of Object.entries(KINDS)) kind.append(new Option(v.label, k));
  for (const u of LENGTHS) root.querySelector("#synth-length").append(new Option(u, u));
  for (const u of ANGLES) root.querySelector("#synth-angle").append(new Option(u, u));
  kind.onchange = () => { placed.stop(); form(root, kind.value); root.querySelector("#synth-results").replaceChildren(); redraw(); };
  form(root, kind.value);
  root.querySelector("#synth-solve").onclick = async () => {
    const box = root.querySelector("#synth-results");
    box.textContent = "solving…";
    try {
      const answer = await post("/api/synthesize", {task: taskOf(root)});
      results(root, answer, open);
      status("");
    } catch (err) {
      box.textContent = "";
      status(err.message, true);
    }
  };
  return placed;
}
