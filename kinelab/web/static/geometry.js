// Small plane geometry on [x, y] arrays, and the model edits that keep a link's shape.
export const dist = (a, b) => Math.hypot(b[0] - a[0], b[1] - a[1]);

// The local place of p on a link whose frame runs from a towards b: [along, to the left].
export function local(a, b, p) {
  const L = dist(a, b), ex = (b[0] - a[0]) / L, ey = (b[1] - a[1]) / L;
  const vx = p[0] - a[0], vy = p[1] - a[1];
  return [vx * ex + vy * ey, ex * vy - ey * vx];
}

const round = (v) => Number(v.toPrecision(14));

// The side of p from the line a -> b ("left" or "right"; null on the line).
export function sideOf(a, b, p) {
  const c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  return c > 0 ? "left" : c < 0 ? "right" : null;
}

// The two points p's sides are measured from, in the order of the link's points (the side
// is of the line from the first to the second); the first two points when it has none.
export function sideRefs(link, p) {
  const given = link.sides && link.sides[p];
  if (!given) return link.points.slice(0, 2);
  return Object.keys(given).filter((k) => k !== "side")
    .sort((x, y) => link.points.indexOf(x) - link.points.indexOf(y));
}

// p's sides from r1 and r2 as the points lie: its distances, and its side of r1 -> r2
// (`was` on the line, where either side is the same place).
export function measuredSides(points, [r1, r2], p, was = "left") {
  return {[r1]: round(dist(points[r1], points[p])), [r2]: round(dist(points[r2], points[p])),
          side: sideOf(points[r1], points[r2], points[p]) || was};
}

// The model with point `name` moved to xy: each link that carries it takes its new length
// (first two points), its new local places and the new sides of the points measured from or
// to it, so the server re-assembles around the move.
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
    for (const [p, given] of Object.entries(link.sides || {})) {
      const refs = sideRefs(link, p);
      if (p === name || refs.includes(name)) link.sides[p] = measuredSides(m.points, refs, p, given.side);
    }
  }
  return m;
}

// The model with the ground's point `name` moved to xy, every moving link keeping its
// dimensions: the lengths and local places of those that carry it are written out as they
// are, so the server re-assembles the linkage on the moved pivot (at the same input, on the
// same branch).
export function movePivot(model, name, xy) {
  const m = structuredClone(model);
  delete m.catalogue;
  for (const link of m.links) {
    const pts = link.points;
    if (link.ground || pts.length < 2 || !pts.includes(name)) continue;
    const [a, b] = [m.points[pts[0]], m.points[pts[1]]];
    if (link.length === undefined) link.length = round(dist(a, b));
    for (const p of pts.slice(2)) {
      link.local = link.local || {};
      if (link.local[p] === undefined) link.local[p] = local(a, b, m.points[p]).map(round);
    }
  }
  m.points[name] = xy.map(round);
  const ground = m.links.find((l) => l.ground);
  if (ground && ground.length !== undefined && ground.points.length > 1)
    ground.length = round(dist(m.points[ground.points[0]], m.points[ground.points[1]]));
  return m;
}

// The model with its ground's length (its first two points) set: its second point moves
// along the line from its first, a pivot moved as `movePivot` moves it.
export function groundLength(model, length) {
  const ground = model.links.find((l) => l.ground);
  const [a, b] = ground.points.slice(0, 2).map((p) => model.points[p]);
  const d = dist(a, b);
  const m = movePivot(model, ground.points[1], [a[0] + (b[0] - a[0]) * length / d,
                                                a[1] + (b[1] - a[1]) * length / d]);
  const g = m.links.find((l) => l.ground);
  if (g.length !== undefined) g.length = length;
  return m;
}

// A prismatic joint's offset: its declared one, else the distance of its point from the
// line through its origin along its axis (to the left), as the sketch draws it; null while
// the drawing has no origin for it yet.
export function offsetOf(model, joint, angleScale) {
  if (joint.offset !== undefined) return joint.offset;
  const axis = Array.isArray(joint.axis) ? joint.axis
    : [Math.cos(joint.axis / angleScale), Math.sin(joint.axis / angleScale)];
  const n = Math.hypot(axis[0], axis[1]);
  const guide = model.links.find((l) => l.name === joint.links[0]);
  const o = model.points[joint.origin || (guide && guide.points[0])], p = model.points[joint.point];
  if (!o || !p) return null;            // a drawing on its way: a guide without points yet
  return round((axis[0] * (p[1] - o[1]) - axis[1] * (p[0] - o[0])) / n);
}
