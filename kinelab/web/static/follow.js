// The linkage between the samples of its sweep, drawn at once while the move tool drags a
// point; the server's solve of the same drag follows and replaces it.
//
// The sweep holds, at every sample, each point's place and its velocity and acceleration
// coefficients K = dP/dq and L = d²P/dq² (one input).  Between two samples each coordinate
// is the quintic that has those six values at both ends (Hermite): with samples 1° apart
// it differs from the solved place by about 1e-12 of the linkage's size (its error goes
// as the sixth power of the step), far below a pixel.  Each prismatic joint's guide turns
// with its guide link, and each gear's direction with its own link, whose angle is
// interpolated the same way.  Where a sample of the
// two does not close, or is singular (no K or L), nothing is predicted: the drag waits for
// the server there.

// The quintic Hermite basis on [0, 1]: value, first and second derivative at 0, then at 1.
function basis(t) {
  const t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  return [1 - 10 * t3 + 15 * t4 - 6 * t5, t - 6 * t3 + 8 * t4 - 3 * t5,
          0.5 * t2 - 1.5 * t3 + 1.5 * t4 - 0.5 * t5, 10 * t3 - 15 * t4 + 6 * t5,
          -4 * t3 + 7 * t4 - 3 * t5, 0.5 * t3 - t4 + 0.5 * t5];
}

const GOLDEN = (Math.sqrt(5) - 1) / 2;
const known = (...values) => values.every((v) => v !== null && v !== undefined && Number.isFinite(v));

// A follower of a sweep (`study`, as /api/study answers it), or null where it cannot
// follow (several inputs, or the columns of K and L not there: a sweep narrowed for an
// edit drag).
export function follower(study) {
  if (!study || study.inputs.length !== 1) return null;
  const c = study.columns, names = Object.keys(c);
  const column = (prefix) => { const n = names.find((k) => k.startsWith(prefix)); return n ? c[n] : null; };
  const q = c[study.inputs[0]];
  const u = study.units.length;
  const paths = {};
  for (const p of Object.keys(study.model.points)) {
    const xy = [c[`${p}.x[${u}]`], c[`${p}.y[${u}]`]];
    const K = [column(`${p}.x.K[`), column(`${p}.y.K[`)], L = [column(`${p}.x.L[`), column(`${p}.y.L[`)];
    if (!xy.every(Boolean) || !K.every(Boolean) || !L.every(Boolean)) return null;
    paths[p] = {xy, K, L};
  }
  const toRad = study.units.angle === "deg" ? Math.PI / 180 : 1;
  const guides = {};
  for (const j of study.drawing.joints) {
    if (j.type !== "P" || !study.guides || !study.guides[j.name]) continue;
    const link = j.links[0];
    const angle = c[`${link}.angle[${study.units.angle}]`], K = column(`${link}.K[`), L = column(`${link}.L[`);
    if (!angle || !K || !L) return null;
    guides[j.name] = {u: study.guides[j.name], angle, K, L};
  }
  const turns = {};
  for (const [link, u] of Object.entries(study.turns || {})) {
    const angle = c[`${link}.angle[${study.units.angle}]`], K = column(`${link}.K[`), L = column(`${link}.L[`);
    if (!angle || !K || !L) return null;
    turns[link] = {u, angle, K, L};
  }
  return new Follower(study, q, paths, guides, toRad, turns);
}

class Follower {
  constructor(study, q, paths, guides, toRad, turns) {
    Object.assign(this, {study, q, paths, guides, toRad, turns});
  }

  // Whether the piece between samples i and i + 1 can be followed.
  closes(i) {
    const q = this.q;
    if (i < 0 || i + 1 >= q.length || !known(q[i], q[i + 1]) || q[i + 1] === q[i]) return false;
    for (const {xy, K, L} of Object.values(this.paths))
      for (let a = 0; a < 2; a++)
        if (!known(xy[a][i], xy[a][i + 1], K[a][i], K[a][i + 1], L[a][i], L[a][i + 1])) return false;
    for (const g of [...Object.values(this.guides), ...Object.values(this.turns)])
      if (!known(g.angle[i], g.angle[i + 1], g.K[i], g.K[i + 1], g.L[i], g.L[i + 1]) || !g.u[i]) return false;
    return true;
  }

  // A coordinate on piece i at t in [0, 1].
  static value(f, K, L, i, h, b) {
    return b[0] * f[i] + h * b[1] * K[i] + h * h * b[2] * L[i] +
           b[3] * f[i + 1] + h * b[4] * K[i + 1] + h * h * b[5] * L[i + 1];
  }

  place(p, i, t) {
    const {xy, K, L} = this.paths[p], h = this.q[i + 1] - this.q[i], b = basis(t);
    return [Follower.value(xy[0], K[0], L[0], i, h, b), Follower.value(xy[1], K[1], L[1], i, h, b)];
  }

  // A direction turning with a link ({u, angle, K, L}: at every sample) on piece i at t.
  turned(g, i, h, b) {
    let turn = g.angle[i + 1] - g.angle[i];              // the link's turn, unwrapped
    const full = 2 * Math.PI / this.toRad;
    turn -= full * Math.round(turn / full);
    const d = h * b[1] * g.K[i] + h * h * b[2] * g.L[i] +
              b[3] * turn + h * b[4] * g.K[i + 1] + h * h * b[5] * g.L[i + 1];
    const a = d * this.toRad, [ux, uy] = g.u[i];
    return [ux * Math.cos(a) - uy * Math.sin(a), ux * Math.sin(a) + uy * Math.cos(a)];
  }

  // Every point, guide and gear's direction on piece i at t: {q, index, points, guides, turns}.
  configuration(i, t) {
    const h = this.q[i + 1] - this.q[i], b = basis(t);
    const points = {};
    for (const p of Object.keys(this.paths)) points[p] = this.place(p, i, t);
    const guides = {}, turns = {};
    for (const [name, g] of Object.entries(this.guides)) guides[name] = this.turned(g, i, h, b);
    for (const [name, g] of Object.entries(this.turns)) turns[name] = this.turned(g, i, h, b);
    return {q: this.q[i] + t * h, index: t < 0.5 ? i : i + 1, points, guides, turns};
  }

  // The configuration at input q (in the model's unit), or null where it cannot follow.
  at(q) {
    const Q = this.q;
    let i = -1;
    for (let k = 0; k + 1 < Q.length; k++)
      if (known(Q[k], Q[k + 1]) && (Q[k] - q) * (Q[k + 1] - q) <= 0) { i = k; break; }
    if (i < 0 || !this.closes(i)) return null;
    return this.configuration(i, (q - Q[i]) / (Q[i + 1] - Q[i]));
  }

  // Where `point` comes nearest to `to` ([x, y], the model's units) on its path: the
  // nearest sample, then the nearest place on the pieces either side of it; null where
  // those do not close.
  nearest(point, to) {
    const path = this.paths[point];
    if (!path) return null;
    const [X, Y] = path.xy;
    const gap2 = (xy) => (xy[0] - to[0]) ** 2 + (xy[1] - to[1]) ** 2;
    let best = -1, gap = Infinity;
    for (let i = 0; i < X.length; i++) {
      if (X[i] === null || Y[i] === null) continue;
      const g = gap2([X[i], Y[i]]);
      if (g < gap) { gap = g; best = i; }
    }
    if (best < 0) return null;
    let found = null;
    for (const i of [best - 1, best]) {
      if (!this.closes(i)) continue;
      let a = 0, b = 1;
      let c = b - GOLDEN * (b - a), d = a + GOLDEN * (b - a);
      let fc = gap2(this.place(point, i, c)), fd = gap2(this.place(point, i, d));
      while (b - a > 1e-12) {
        if (fc < fd) { b = d; d = c; fd = fc; c = b - GOLDEN * (b - a); fc = gap2(this.place(point, i, c)); }
        else { a = c; c = d; fc = fd; d = a + GOLDEN * (b - a); fd = gap2(this.place(point, i, d)); }
      }
      const t = fc < fd ? c : d, g = Math.min(fc, fd);
      if (!found || g < found.g) found = {i, t, g};
    }
    return found ? this.configuration(found.i, found.t) : null;
  }
}
