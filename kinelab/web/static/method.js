// The method: instant centres and the velocity and acceleration polygons of the
// configuration shown; the derivation in the notes' notation.
import {post} from "./api.js";
import {el} from "./canvas.js";

const f = (v) => v === null ? "–" : Number(v.toPrecision(6)).toString();

export function showCentres(list, polygons, config, study) {
  const u = study.units.length;
  const rows = config.centres.map((c) => `<tr><td>I ${c.links.join(", ")}</td><td>${
    c.at_infinity ? `at infinity, direction (${c.direction.map(f).join(", ")})`
                  : `(${c.position.map(f).join(", ")}) ${u}`}</td></tr>`);
  list.innerHTML = `<h3>instant centres</h3>` + (config.singular
    ? "<p>singular configuration: the centres are undefined here</p>"
    : `<table>${rows.join("")}</table>`);
  polygons.replaceChildren();
  if (!config.polygons) {
    polygons.innerHTML = "<p class='hint'>Velocity and acceleration polygons: undefined at a singular configuration.</p>";
    return;
  }
  for (const [kind, letter, unit] of [["velocity", "V", `${u}/s`], ["acceleration", "A", `${u}/s²`]]) {
    const h = document.createElement("h3");
    h.textContent = `${kind} polygon (${unit}, from the pole O${letter})`;
    polygons.append(h);
    drawPolygon(polygons, config.polygons[kind], letter, study, kind);
  }
}

const PART = {normal: ["n", "part-normal"], tangential: ["t", "part-tangential"],
              coriolis: ["c", "part-coriolis"], sliding: ["s", "part-sliding"]};

// A label such as V_BA or A^n_BA: the letter, a superscript, a subscript.
function label(svg, x, y, letter, sub, sup = "") {
  const t = el("text", {x, y, class: "polygon-label"}, svg);
  t.append(letter);
  if (sup) el("tspan", {"baseline-shift": "super", "font-size": "8"}, t).textContent = sup;
  el("tspan", {"baseline-shift": "sub", "font-size": "8", ...(sup ? {dx: -4} : {})}, t).textContent = sub;
  return t;
}

// One polygon, as kinelab's figures draw it: from the pole, each point's absolute vector;
// between vertices, each side (velocity: V_BA; acceleration: its parts head to tail, A^n_BA
// then A^t_BA, or A^c then A^s); each link's image shaded.
function drawPolygon(root, poly, letter, study, kind) {
  const W = 340, H = 240;
  const svg = el("svg", {width: W, height: H, class: "polygon", "data-polygon": kind}, root);
  const defs = el("defs", {}, svg);
  const marker = el("marker", {id: `head-${kind}`, viewBox: "0 0 10 10", refX: 9, refY: 5,
                               markerWidth: 7, markerHeight: 7, orient: "auto-start-reverse"}, defs);
  el("path", {d: "M0,0 L10,5 L0,10 z", fill: "context-stroke"}, marker);
  const vertex = {...poly.vertices, ...poly.coincident};
  const places = [[0, 0], ...Object.values(vertex)];
  for (const side of poly.sides) {
    let at = vertex[side.reference];
    for (const v of Object.values(side.parts)) { at = [at[0] + v[0], at[1] + v[1]]; places.push(at); }
  }
  const ok = places.filter((v) => v && v[0] !== null && v[1] !== null);
  const xs = ok.map((v) => v[0]), ys = ok.map((v) => v[1]);
  const x0 = Math.min(...xs), x1 = Math.max(...xs), y0 = Math.min(...ys), y1 = Math.max(...ys);
  const size = Math.max(x1 - x0, y1 - y0, 1e-300);
  const tiny = 1e-9 * size;
  const s = Math.min((W - 90) / Math.max(x1 - x0, 1e-300), (H - 50) / Math.max(y1 - y0, 1e-300));
  const S = ([x, y]) => [W / 2 + s * (x - (x0 + x1) / 2), H / 2 - s * (y - (y0 + y1) / 2)];
  const arrow = (from, to, cls, data) => {
    const [X0, Y0] = S(from), [X1, Y1] = S(to);
    el("line", {x1: X0, y1: Y0, x2: X1, y2: Y1, class: cls, "marker-end": `url(#head-${kind})`, "data-side": data}, svg);
    return [(X0 + X1) / 2, (Y0 + Y1) / 2];
  };
  const long = (v) => v && v[0] !== null && Math.hypot(v[0], v[1]) > tiny;
  for (const [link, points] of Object.entries(poly.images)) {
    if (points.length >= 3) el("polygon", {class: "image", "data-image": link,
                                           points: points.map((p) => S(vertex[p])).join(" ")}, svg);
  }
  for (const p of Object.keys(poly.vertices)) {
    if (!long(poly.vertices[p])) continue;
    const [X, Y] = arrow([0, 0], poly.vertices[p], "absolute", p);
    label(svg, X + 3, Y - 3, letter, p);
  }
  for (const side of poly.sides) {
    const start = vertex[side.reference], end = vertex[side.point];
    if (!long([end[0] - start[0], end[1] - start[1]])) continue;
    const sub = `${side.point}${side.reference}`;
    if (letter === "V") {
      if (!long(start)) continue;              // from a point at rest: the absolute arrow itself
      const [X, Y] = arrow(start, end, "side", `${side.point} ${side.reference}`);
      label(svg, X + 3, Y + 10, letter, sub);
      continue;
    }
    let at = start;
    for (const [part, v] of Object.entries(side.parts)) {
      if (!long(v)) continue;
      const next = [at[0] + v[0], at[1] + v[1]];
      const [X, Y] = arrow(at, next, PART[part][1], `${side.point} ${side.reference} ${part}`);
      label(svg, X + 3, Y + 10, letter, sub, PART[part][0]);
      at = next;
    }
  }
  const [OX, OY] = S([0, 0]);
  el("circle", {cx: OX, cy: OY, r: 2.5, class: "pole"}, svg);
  label(svg, OX - 16, OY + 12, "O", letter);
  const groups = new Map();                  // vertices that coincide share one label
  for (const [p, v] of Object.entries(vertex)) {
    if (!v || v[0] === null) continue;
    const key = S(v).map((c) => Math.round(c)).join(",");
    groups.set(key, [...(groups.get(key) || []), p.toLowerCase()]);
  }
  for (const [key, names] of groups) {
    const [X, Y] = key.split(",").map(Number);
    el("text", {x: X + 4, y: Y - 10, class: "vertex-label"}, svg).textContent = names.join(", ");
  }
}

export async function derive(root, state, lang, status) {
  root.textContent = "deriving…";
  try {
    const d = await post("/api/derive", {model: state.model, source: state.source, lang});
    state.derivation = d;
    root.replaceChildren();
    for (const s of d.sections) {
      const h = document.createElement("h3");
      h.textContent = s.title;
      root.append(h);
      for (const item of s.items) {
        const div = document.createElement("div");
        if (item.mathml) div.innerHTML = item.mathml;      // MathML made by the server from sympy
        else div.textContent = `${item.label}: ${item.text}`;
        root.append(div);
      }
    }
  } catch (err) { root.textContent = ""; status(err.message, true); }
}
