// The model's inputs: given from the drawing (a joint with the ground, R or P, one or several),
// listed in the table with their ranges and speeds, removed; and, for a model of several
// inputs, one slider each under the drawing, moving that input while the others stay.
import {shownColumn} from "./units.js";

// An input drawn turns once a second: its velocities and accelerations are not zero, and
// the table shows the speed to change.
export const defaultSpeed = (units) => (units && units.angle === "rad" ? 2 * Math.PI : 360);

// The degrees of freedom the Kutzbach-Gruebler count gives a drawing (the server knows the
// exact mobility and says so when the inputs do not match it).
export function countedMobility(model) {
  return 3 * (model.links.length - 1) - 2 * (model.joints || []).length;
}

// A slide drawn runs the sketch's size in a second (to two digits).
function slideSpeed(m) {
  const xy = Object.values(m.points);
  const size = Math.max(...[0, 1].map((c) => Math.max(...xy.map((p) => p[c])) - Math.min(...xy.map((p) => p[c]))));
  return size > 0 ? Number(size.toPrecision(2)) : 1;
}

const inputName = (i) => i.name || i.joint;

// The model with the joint between the ground and `point` (R or P) as an input, or null when
// there is none or it is one already.  A one-degree-of-freedom drawing keeps one input: the
// new one takes the place of the one before (and its speed), as the input tool always did;
// a drawing of more gets one more.
export function addInput(model, point) {
  const m = structuredClone(model);
  delete m.catalogue;
  const ground = m.links.find((l) => l.ground);
  const j = ground && (m.joints || []).find((k) => k.point === point && (k.type === "R" || k.type === "P")
                                                   && k.links.includes(ground.name));
  if (!j) return null;
  const inputs = m.inputs || [];
  if (inputs.some((i) => i.joint === j.name)) return null;
  const speed = (k) => (k.type === "P" ? slideSpeed(m) : defaultSpeed(m.units));
  if (!inputs.length || (inputs.length === 1 && countedMobility(m) <= 1)) {
    const before = inputs[0], kindBefore = before && (m.joints || []).find((k) => k.name === before.joint);
    const same = before && (kindBefore && kindBefore.type) === j.type;
    m.inputs = [{joint: j.name, speed: same ? before.speed ?? speed(j) : speed(j)}];
  } else {
    m.inputs = [...inputs, {joint: j.name, speed: speed(j)}];
  }
  return m;
}

// The model without input `name` (its joint's, if it has no name of its own).
export function withoutInput(model, name) {
  const m = structuredClone(model);
  delete m.catalogue;
  m.inputs = (m.inputs || []).filter((i) => inputName(i) !== name);
  if (!m.inputs.length) delete m.inputs;
  return m;
}

// A range as typed: two numbers "start, stop", or nothing (the server's own: one input's
// reachable range).  `read(text, what)` reads one number (the table's, in the units shown).
export function typedRange(text, read, what) {
  const parts = String(text).split(",").map((s) => s.trim());
  if (parts.length === 1 && parts[0] === "") return null;
  if (parts.length !== 2)
    throw new Error(`${what}: expected two numbers, start and stop, such as 0, 360; got '${String(text).trim()}'`);
  const r = parts.map((t, k) => read(t, `${what} ${k ? "stop" : "start"}`));
  if (r[0] === r[1]) throw new Error(`${what}: the start and the stop are the same (${parts[0]}); give the input room to move`);
  return r;
}

// -- the sliders ------------------------------------------------------------------------------
// One slider per input of a sweep of several inputs, in `root` (shown only then).  Each runs
// over its input's range; moved, it sets `state.dragQ` to the pair (the others where they are
// shown) and the server's configuration there is drawn (`state.configurationSoon`).
export function inputSliders(root, state) {
  const box = document.createElement("div");
  box.id = "input-sliders";
  box.hidden = true;
  root.append(box);
  let shownFor = null;

  const now = () => {
    const s = state.study;
    if (Array.isArray(state.dragQ) && state.dragQ.length === s.inputs.length) return state.dragQ;
    return s.inputs.map((n) => s.columns[n][state.index]);
  };

  function build(s) {
    box.replaceChildren();
    shownFor = s;
    box.hidden = !(s && s.inputs.length > 1);
    if (box.hidden) return;
    for (const [k, column] of s.inputs.entries()) {
      const input = (s.model.inputs || [])[k] || {};
      const known = s.columns[column].filter((v) => v !== null);
      const [lo, hi] = input.range ? [Math.min(...input.range), Math.max(...input.range)]
        : [Math.min(...known), Math.max(...known)];
      const label = document.createElement("label");
      const slider = document.createElement("input");
      Object.assign(slider, {type: "range", min: lo, max: hi, step: "any"});
      slider.dataset.input = inputName(input);
      slider.dataset.column = column;
      slider.setAttribute("aria-label", `input ${inputName(input)}`);
      const value = document.createElement("span");
      value.className = "value";
      label.append(`${inputName(input)} `, slider, value);
      slider.addEventListener("input", () => move(k, Number(slider.value)));
      box.append(label);
    }
  }

  function move(k, value) {
    if (!state.study) return;
    state.pause();
    const q = [...now()];
    q[k] = value;
    if (q.some((v) => v === null || !Number.isFinite(v))) return;
    state.dragQ = q;
    state.predicted = null;
    show();
    state.configurationSoon();
  }

  // Called with every redraw: made again for a new sweep, else only its values set.
  function show() {
    const s = state.study;
    if (s !== shownFor) build(s);
    if (box.hidden) return;
    const q = now();
    for (const [k, slider] of [...box.querySelectorAll("input")].entries()) {
      if (q[k] === null || q[k] === undefined) continue;
      slider.value = q[k];
      const c = shownColumn(slider.dataset.column, [q[k]], s.units);
      slider.nextSibling.textContent = `${Number(c.values[0].toPrecision(6))} ${(/\[([^\]]*)\]$/.exec(c.name) || ["", ""])[1]}`;
    }
  }

  return {show};
}
