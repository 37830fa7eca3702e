// The units numbers are shown in: the model's own unless others are chosen.  Only what is
// shown changes: the model keeps its units and its numbers.
export const METRES = {mm: 0.001, cm: 0.01, m: 1, in: 0.0254};
export const RADIANS = {deg: Math.PI / 180, rad: 1};
export const chosen = {length: "", angle: ""};      // "": the model's

// The units shown for a model in `units` ({length, angle}), and the factors from the model's
// numbers to those shown (L for lengths, A for angles).
export function shownUnits(units) {
  const u = units || {length: "m", angle: "rad"};
  const length = chosen.length || u.length, angle = chosen.angle || u.angle;
  return {length, angle, L: METRES[u.length] / METRES[length], A: RADIANS[u.angle] / RADIANS[angle]};
}

// A number of the model shown (12 significant digits: no 100.00000000000001 for 0.1 m).
export const toShown = (v, f) => v === null || v === undefined || v === "" ? v : Number((v * f).toPrecision(12));
// A number typed in the units shown, in the model's.
export const fromShown = (v, f) => f === 1 ? v : Number((v / f).toPrecision(14));

// A column's name and numbers in the units shown: "B.x[mm]" -> "B.x[in]", scaled; the
// unit's first part is a length or an angle of the model's (mm/s, deg/s^2 ...).
export function shownColumn(name, values, units) {
  const m = /\[([^\]]*)\]$/.exec(name);
  if (!m || !units) return {name, values};
  const s = shownUnits(units), [first, ...rest] = m[1].split("/");
  let f = 1, to = first;
  if (first === units.length) { f = s.L; to = s.length; }
  else if (first === units.angle) { f = s.A; to = s.angle; }
  if (f === 1 && to === first) return {name, values};
  return {name: name.slice(0, m.index) + `[${[to, ...rest].join("/")}]`,
          values: values && values.map((v) => v === null ? null : v * f)};
}
