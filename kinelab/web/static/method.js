// The method: instant centres (and the velocity and acceleration polygons where kinelab
// draws them) of the configuration shown; the derivation in the notes' notation.
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
    polygons.innerHTML = "<p class='hint'>Velocity and acceleration polygons: not drawn by this kinelab; the instant centres are below.</p>";
    return;
  }
  for (const [kind, unit] of [["velocity", `${u}/s`], ["acceleration", `${u}/s²`]]) {
    const h = document.createElement("h3");
    h.textContent = `${kind} polygon (${unit}, from the pole o)`;
    polygons.append(h);
    drawPolygon(polygons, config.polygons[kind], study);
  }
}

function drawPolygon(root, vertices, study) {
  const svg = el("svg", {width: 320, height: 220, class: "polygon"}, root);
  const pts = Object.values(vertices).filter((v) => v[0] !== null);
  const r = Math.max(1e-12, ...pts.map((v) => Math.hypot(v[0], v[1])));
  const S = ([x, y]) => [160 + 95 * x / r, 110 - 95 * y / r];
  for (const link of study.drawing.links) {
    const ends = link.points.filter((p) => vertices[p]);
    if (ends.length > 1) el("polygon", {class: "link", points: ends.map((p) => S(vertices[p])).join(" ")}, svg);
  }
  for (const [p, v] of Object.entries(vertices)) {
    const [X, Y] = S(v);
    el("line", {x1: 160, y1: 110, x2: X, y2: Y, stroke: "#d1600a"}, svg);
    el("text", {x: X + 3, y: Y - 3}, svg).textContent = p.toLowerCase();
  }
  el("text", {x: 163, y: 122}, svg).textContent = "o";
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
