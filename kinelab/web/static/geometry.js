// Small plane geometry on [x, y] arrays, and the model edits that keep a link's shape.
export const dist = (a, b) => Math.hypot(b[0] - a[0], b[1] - a[1]);

// The local place of p on a link whose frame runs from a towards b: [along, to the left].
export function local(a, b, p) {
  const L = dist(a, b), ex = (b[0] - a[0]) / L, ey = (b[1] - a[1]) / L;
  const vx = p[0] - a[0], vy = p[1] - a[1];
  return [vx * ex + vy * ey, ex * vy - ey * vx];
}

const round = (v) => Number(v.toPrecision(14));

// The model with point `name` moved to xy: each link that carries it takes its new length
// (first two points) or its new local place, so the server re-assembles around the move.
export function movePoint(model, name, xy) {
  const m = structuredClone(model);
  delete m.catalogue;
  m.points[name] = xy.map(round);
  for (const link of m.links) {
    const pts = link.points;
    if (!pts.includes(name) || pts.length < 2) continue;
    const [a, b] = [m.points[pts[0]], m.points[pts[1]]];
    if (pts.indexOf(name) < 2) {
      if (link.length !== undefined) link.length = round(dist(a, b));
      if (link.local) for (const p of Object.keys(link.local)) link.local[p] = local(a, b, m.points[p]).map(round);
    } else if (link.local && link.local[name] !== undefined) {
      link.local[name] = local(a, b, m.points[name]).map(round);
    }
  }
  return m;
}
