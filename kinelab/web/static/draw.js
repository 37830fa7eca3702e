// Drawing a linkage point by point: each tool turns a click into a new model (JSON form).
import {addInput} from "./inputs.js";

const round = (v) => Number(v.toPrecision(8));
let linkStart = null;          // the first point of a link being drawn

// The point a link waits at for its second click (null when none), and forgetting it.
export const pending = () => linkStart;
export function cancel() { const was = linkStart; linkStart = null; return was !== null; }


export function empty() {
  return {schema: 1, name: "sketch", units: {length: "mm", angle: "deg"}, points: {},
          links: [{name: "ground", points: [], ground: true}], joints: []};
}

// What the canvas draws of a model that may not assemble yet.
export function drawingOf(model) {
  const ground = model.links.find((l) => l.ground);
  return {links: model.links, joints: model.joints || [], traced: [],
          ground_points: ground ? ground.points : [], inputs: model.inputs || []};
}

// Each prismatic joint's slide direction as the sketch has it (an axis [x, y], or an angle
// in the model's unit).
export function guidesOf(model) {
  const toRad = model.units && model.units.angle === "rad" ? 1 : Math.PI / 180;
  const out = {};
  for (const j of model.joints || []) {
    if (j.type !== "P") continue;
    if (Array.isArray(j.axis)) out[j.name] = j.axis;
    else if (typeof j.axis === "number") out[j.name] = [Math.cos(j.axis * toRad), Math.sin(j.axis * toRad)];
  }
  return out;
}

function fresh(prefix, taken) {
  for (let i = 1; ; i++) if (!taken.includes(prefix + i)) return prefix + i;
}

// Pin `link` to the other links that carry point p with an R joint at p.
function pin(m, link, p) {
  for (const other of m.links) {
    if (other.name === link || !other.points.includes(p)) continue;
    const joined = m.joints.some((j) => j.point === p && j.links.includes(link) && j.links.includes(other.name));
    if (!joined) m.joints.push({name: fresh("j" + p, m.joints.map((j) => j.name)), type: "R",
                                links: other.ground ? [other.name, link] : [other.name, link], point: p});
    break;
  }
}

export function apply(tool, model, name, xy) {
  if (!model) return null;
  const m = structuredClone(model);
  delete m.catalogue;
  m.joints = m.joints || [];
  const addPoint = () => {
    const p = fresh("P", Object.keys(m.points));
    m.points[p] = xy.map(round);
    return p;
  };
  if (tool === "point") { if (name) return null; addPoint(); return m; }
  if (tool === "link") {
    const p = name || addPoint();
    if (!linkStart || linkStart === p || !m.points[linkStart]) { linkStart = p; return name ? null : m; }
    const link = fresh("link", m.links.map((l) => l.name));
    m.links.push({name: link, points: [linkStart, p]});
    pin(m, link, linkStart); pin(m, link, p);
    linkStart = null;
    return m;
  }
  if (tool === "slider") return null;          // a drag: see slider()
  if (!name) return null;
  if (tool === "ground") {
    let ground = m.links.find((l) => l.ground);
    if (!ground) { ground = {name: "ground", points: [], ground: true}; m.links.unshift(ground); }
    if (ground.points.includes(name)) return null;
    ground.points.push(name);
    for (const l of m.links) if (!l.ground && l.points.includes(name)) pin(m, l.name, name);
    return m;
  }
  if (tool === "input") return addInput(m, name);
  return null;
}

// A slider block on a guide: a press at point `name` (or at `at`, a new point there) and a
// drag towards `to` for the slide axis.  The block is a new link carrying the point, pinned
// by an R joint to the link already there, and joined to the ground (the guide) by a P joint.
export function slider(model, name, at, to) {
  if (!model) return null;
  const axis = [to[0] - at[0], to[1] - at[1]];
  if (Math.hypot(...axis) === 0) return null;
  const m = structuredClone(model);
  delete m.catalogue;
  m.joints = m.joints || [];
  let p = name;
  if (!p) { p = fresh("P", Object.keys(m.points)); m.points[p] = at.map(round); }
  let ground = m.links.find((l) => l.ground);
  if (!ground) { ground = {name: "ground", points: [], ground: true}; m.links.unshift(ground); }
  if (ground.points.includes(p)) return null;
  const block = fresh("slider", m.links.map((l) => l.name));
  m.links.push({name: block, points: [p]});
  pin(m, block, p);
  const norm = Math.hypot(...axis);
  m.joints.push({name: fresh("slide", m.joints.map((j) => j.name)), type: "P", links: [ground.name, block],
                 point: p, axis: axis.map((v) => Math.round(1e6 * v / norm) / 1e6 + 0)});   // a pixel's worth
  return m;
}

// The model without a point, a link, a joint or an input (sel: {kind, name}), and without
// what refers to it: a point's joints and its places on links, a link's joints, a joint's
// input.  The server says whether what is left is a model.
export function remove(model, sel) {
  const m = structuredClone(model);
  delete m.catalogue;
  m.joints = m.joints || [];
  let joints = [];
  if (sel.kind === "point") {
    delete m.points[sel.name];
    for (const l of m.links) {
      const i = l.points.indexOf(sel.name);
      if (i < 0) continue;
      l.points.splice(i, 1);
      if (i < 2) delete l.length;
      if (l.local) delete l.local[sel.name];
      if (l.sides) delete l.sides[sel.name];
    }
    m.links = m.links.filter((l) => l.ground || l.points.length);
    joints = m.joints.filter((j) => j.point === sel.name || j.links.some((n) => !m.links.find((l) => l.name === n)));
  } else if (sel.kind === "link") {
    m.links = m.links.filter((l) => l.name !== sel.name);
    joints = m.joints.filter((j) => j.links.includes(sel.name));
  } else if (sel.kind === "joint") {
    joints = m.joints.filter((j) => j.name === sel.name);
  } else if (sel.kind === "input") {
    m.inputs = (m.inputs || []).filter((i) => (i.name || i.joint) !== sel.name);
  }
  const gone = new Set(joints.map((j) => j.name));
  m.joints = m.joints.filter((j) => !gone.has(j.name));
  if (m.inputs) m.inputs = m.inputs.filter((i) => !gone.has(i.joint));
  if (m.inputs && !m.inputs.length) delete m.inputs;
  return m;
}
