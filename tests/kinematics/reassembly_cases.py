"""Independent checks of re-assembly: for each catalogue mechanism and example file, what
its edited dimensions allow at its sketch's inputs, computed here from the geometry alone
(law of cosines for the dyads, a circle meeting a line for a slider, a line through a pivot
for a slotted link, brute-force Newton from a grid of starts for the triad), vectorised over
many edits at once.

Each case knows its mechanism's dimensions as measured on its sketch (assembled), how to
apply an edit to them, and, for a batch of edited dimensions, returns per edit:

- ``refused`` and ``gap``: no configuration at the sketch's inputs, and by how much it
  misses: a loop of bars whose longest bar exceeds the others misses by that excess (at
  any input); else the least distance by which the failing dyad misses at the sketch's
  inputs, over the branches of the dyads before it;
- ``points``: where the points are on the sketch's branch (or on the nearest other one, when
  the sketch's does not exist), and ``switched``: the dyads that changed side.

Nothing here calls the assembly under test.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import kinelab as kl

ROOT = __import__("pathlib").Path(__file__).resolve().parents[2]


# -- plane geometry, vectorised over edits (arrays of shape (N,) or (N, 2)) ------------------
def unit(angle):
    return np.stack([np.cos(angle), np.sin(angle)], -1)


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def norm(v):
    return np.hypot(v[..., 0], v[..., 1])


def turn(v, angle):
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


def two_circles(X, Z, b, c, side):
    """The point at b from X and c from Z on ``side`` (+1 left of X -> Z), by the law of
    cosines at X; with the distance of |XZ| outside [|b - c|, b + c] (0 where they meet)."""
    d = norm(Z - X)
    gap = np.maximum(np.maximum(d - (b + c), np.abs(b - c) - d), 0.0)
    cos_a = np.clip((b * b + d * d - c * c) / (2 * b * d), -1.0, 1.0)
    alpha = np.arccos(cos_a)
    e = (Z - X) / d[..., None]
    return X + b[..., None] * turn(e, side * alpha), gap


def circle_line(X, r, y_line, side):
    """The point at r from X on the horizontal line y = y_line, right of X for side +1, and
    by how much the circle misses the line."""
    s = y_line - X[..., 1]
    gap = np.maximum(np.abs(s) - r, 0.0)
    dx = np.sqrt(np.maximum(r * r - s * s, 0.0))
    return np.stack([X[..., 0] + side * dx, y_line + 0 * dx], -1), gap


def excess(*bars):
    """How much the longest of a loop's bars exceeds the others together (<= 0: it can close)."""
    b = np.stack(bars, -1)
    return 2 * b.max(-1) - b.sum(-1)


# -- the cases ------------------------------------------------------------------------------
@dataclass
class Case:
    """A mechanism to edit: its name, the mechanism (assembled), its editable dimensions
    (name -> kind), and its size."""

    name: str
    mechanism: kl.model.Mechanism
    editable: dict
    dims: dict = field(init=False)
    size: float = field(init=False)

    def __post_init__(self):
        m = self.mechanism
        P = {p.name: np.array(p.xy) for p in m.points}
        self.P0 = P
        xs = np.array(list(P.values()))
        self.size = float(max(np.ptp(xs[:, 0]), np.ptp(xs[:, 1])))
        d = {}
        for name, kind in self.editable.items():
            if kind == "length":
                a, b = m.link(name).points[:2]
                d[name] = float(norm(P[b] - P[a]))
            elif kind == "pivot":
                d[name] = P[name].copy()
            elif kind == "offset":
                j = m.joint(name)
                o = P[j.origin or m.link(j.links[0]).points[0]]
                u = np.array(j.axis) / norm(np.array(j.axis))
                d[name] = float(cross(u, P[j.point] - o))
            elif kind == "local":
                link, pt = name.split(".")
                a, b = m.link(link).points[:2]
                e = (P[b] - P[a]) / norm(P[b] - P[a])
                r = P[pt] - P[a]
                d[name] = np.array([r @ e, cross(e, r)])
        for name, kind in list(self.editable.items()):
            if kind == "local":                  # the length of the link the place is on
                link = name.split(".")[0]
                a, b = m.link(link).points[:2]
                d.setdefault(link, float(norm(P[b] - P[a])))
        for g in m.ground.points:            # the pivots, edited or not
            d.setdefault(g, P[g].copy())
        self.dims = d
        self.pivot = "O2" if "O2" in P else "O"
        self.q = math.atan2(*(P["A"] - P[self.pivot])[::-1])

    def effective(self, edit: dict) -> dict:
        """The dimensions after an edit.  A point's place on a link that the model does not
        declare keeps its place relative to the link's first two points (the model's rule):
        it scales with the link's length."""
        out = {**self.dims, **edit}
        m = self.mechanism
        for name, kind in self.editable.items():
            if kind != "local" or name in edit:
                continue
            link, pt = name.split(".")
            if m.link(link).local and pt in m.link(link).local:
                continue
            out[name] = self.dims[name] * (out[link] / self.dims[link]) if link in out else self.dims[name]
        return out

    def batch(self, edits: list[dict]) -> dict:
        """The dimensions of each edit, as arrays over the edits."""
        eff = [self.effective(e) for e in edits]
        return {name: np.array([e[name] for e in eff], float) for name in self.dims}

    @staticmethod
    def kwargs(case, edit: dict) -> dict:
        """The edit as ``reassemble`` keywords."""
        kw = {"lengths": {}, "local": {}, "offsets": {}, "pivots": {}}
        for name, value in edit.items():
            kind = case.editable[name]
            if kind == "length":
                kw["lengths"][name] = float(value)
            elif kind == "pivot":
                kw["pivots"][name] = (float(value[0]), float(value[1]))
            elif kind == "offset":
                kw["offsets"][name] = float(value)
            else:
                link, pt = name.split(".")
                kw["local"].setdefault(link, {})[pt] = (float(value[0]), float(value[1]))
        return {k: v for k, v in kw.items() if v}

    def place(self, D, frame_a, frame_b, local):
        """A point at ``local`` (along, left) in the frame of the points frame_a -> frame_b."""
        e = (frame_b - frame_a) / norm(frame_b - frame_a)[..., None]
        return frame_a + local[..., :1] * e + local[..., 1:] * np.stack([-e[..., 1], e[..., 0]], -1)

    def crank_pin(self, D, pivot=None, crank="crank", q=None):
        return D[pivot or self.pivot] + D[crank][..., None] * unit(np.full(len(D[crank]), self.q if q is None else q))

    def side(self, X, Y, Z):
        """The sketch's side of Y relative to the line X -> Z."""
        P = self.P0
        return float(np.sign(cross(P[Z] - P[X], P[Y] - P[X])))


class FourBar(Case):
    def expect(self, D):
        A = self.crank_pin(D)
        B, gap = two_circles(A, D["O4"], D["coupler"], D["rocker"], self.side("A", "B", "O4"))
        ex = excess(norm(D["O4"] - D["O2"]), D["rocker"], D["coupler"], D["crank"])
        points = {"A": A, "B": B}
        if "coupler.P" in D:
            points["P"] = self.place(D, A, B, D["coupler.P"])
        return _verdict(ex, gap, points, np.zeros(len(gap), bool))


class SliderCrank(Case):
    def expect(self, D):
        A = self.crank_pin(D)
        side = float(np.sign(self.P0["B"][0] - self.P0["A"][0]))
        B, gap = circle_line(A, D["rod"], D["O2"][:, 1] + D["slide"], side)
        return _verdict(np.full(len(gap), -1.0), gap, {"A": A, "B": B}, np.zeros(len(gap), bool))


def _slot(case, D, A, joint, pivot, guide, flip=False):
    """A slotted guide pivoted at ``pivot`` whose slot (offset e from it) passes through A:
    the guide's direction on the sketch's side (the other with ``flip``), and how much the
    slot misses A."""
    P, m = case.P0, case.mechanism
    j = m.joint(joint)
    u0 = np.array(j.axis) / norm(np.array(j.axis))
    sigma = float(np.sign(u0 @ (P["A"] - P[pivot]))) * (-1.0 if flip else 1.0)
    beta = math.atan2(*u0[::-1]) - math.atan2(*(P[m.link(guide).points[1]] - P[pivot])[::-1])
    v = A - D[pivot]
    d = norm(v)
    e = D[joint]
    gap = np.maximum(np.abs(e) - d, 0.0)
    s = np.clip(e / d, -1, 1)
    # cross(u, v) = d sin(angle(v) - angle(u)) = e, with u . v of the side's sign
    psi = np.arctan2(v[:, 1], v[:, 0]) - np.where(sigma > 0, np.arcsin(s), math.pi - np.arcsin(s))
    return psi - beta, gap


class SlottedLink(Case):
    guide = "rocker"
    joint = "slide"

    def expect(self, D):
        A = self.crank_pin(D)
        phi, gap = _slot(self, D, A, self.joint, "O4", self.guide)
        C = D["O4"] + D[self.guide][:, None] * unit(phi)
        return _verdict(np.full(len(gap), -1.0), gap, {"A": A, "C": C}, np.zeros(len(gap), bool))


class Whitworth(Case):
    def expect(self, D):
        P = self.P0
        A = self.crank_pin(D)
        side2 = float(np.sign(P["D"][0] - P["C"][0]))
        results = []
        for flip in (False, True):           # the lever's two assembly modes
            phi, gap1 = _slot(self, D, A, "slot", "O4", "lever", flip)
            C = D["O4"] + D["lever"][:, None] * unit(phi)
            Dp, gap2 = circle_line(C, D["rod"], D["O4"][:, 1] + D["ram_slide"], side2)
            results.append((C, Dp, gap2))
        (C, Dp, g_same), (C2, Dp2, g_other) = results
        switch = (gap1 == 0) & (g_same > 0) & (g_other == 0)
        gap = np.where(gap1 > 0, gap1, np.where(switch, 0.0, np.minimum(g_same, g_other)))
        points = {"A": A, "C": np.where(switch[:, None], C2, C),
                  "D": np.where(switch[:, None], Dp2, Dp)}
        return _verdict(np.full(len(gap), -1.0), gap, points, switch)


class FiveBar(Case):
    def expect(self, D):
        P = self.P0
        A = self.crank_pin(D, "O2", "crank1")
        qB = math.atan2(*(P["B"] - P["O4"])[::-1])
        B = self.crank_pin(D, "O4", "crank2", qB)
        Pp, gap = two_circles(A, B, D["coupler1"], D["coupler2"], self.side("A", "P", "B"))
        ex = excess(norm(D["O4"] - D["O2"]), D["crank1"], D["coupler1"], D["coupler2"], D["crank2"])
        return _verdict(ex, gap, {"A": A, "B": B, "P": Pp}, np.zeros(len(gap), bool))


class SixBar(Case):
    """Watt (rocker O4-B-C ternary) or Stephenson (coupler A-B-C ternary) six-bar: two RRR
    dyads, the second on the first's two branches."""

    def expect(self, D):
        stephenson = len(self.mechanism.link("coupler").points) == 3
        A = self.crank_pin(D)
        s1, s2 = self.side("A", "B", "O4"), self.side("C", "D", "O6")
        out = []
        for side in (s1, -s1):
            B, gap1 = two_circles(A, D["O4"], D["coupler"], D["rocker"], np.full(len(A), side))
            C = self.place(D, A, B, D["coupler.C"]) if stephenson else self.place(D, D["O4"], B, D["rocker.C"])
            Dp, gap2 = two_circles(C, D["O6"], D["link5"], D["output"], np.full(len(A), s2))
            out.append((B, C, Dp, gap1, gap2))
        (B, C, Dp, gap1, g_same), (B2, C2, Dp2, _, g_other) = out
        if stephenson:
            ex2 = excess(norm(D["coupler.C"]), D["crank"], norm(D["O6"] - D["O2"]), D["output"], D["link5"])
        else:
            ex2 = excess(norm(D["rocker.C"]), norm(D["O6"] - D["O4"]), D["output"], D["link5"])
        ex1 = excess(norm(D["O4"] - D["O2"]), D["rocker"], D["coupler"], D["crank"])
        ex = np.where(ex1 > 0, ex1, ex2)
        switch = (gap1 == 0) & (g_same > 0) & (g_other == 0)
        gap = np.where(gap1 > 0, gap1, np.where(switch, 0.0, np.minimum(g_same, g_other)))
        pick = switch[:, None]
        points = {"A": A, "B": np.where(pick, B2, B), "C": np.where(pick, C2, C),
                  "D": np.where(pick, Dp2, Dp)}
        return _verdict(ex, gap, points, switch)


class Triad(Case):
    """The triad six-bar: link3 A-C, the triad C-D-E, link4 D-O4, link5 E-O6.  At the crank's
    angle, the configurations are the roots of two equations in the angles of link3 and of
    the triad (D and E at their links' lengths from O4 and O6), found by Newton-Raphson from
    a grid of starts; the gap, when there are none, cuts the triad's joint C open: the least
    distance between C on link3 (a circle about A) and C on the four-bar O4-D-E-O6."""

    grid = 24

    def residual(self, D, A, x):
        C = A + D["link3"][:, None] * unit(x[:, 0])
        e = unit(x[:, 1])
        n = np.stack([-e[:, 1], e[:, 0]], -1)
        Dp = C + D["triad"][:, None] * e
        E = C + D["triad.E"][:, :1] * e + D["triad.E"][:, 1:] * n
        return np.stack([norm(Dp - D["O4"]) - D["link4"], norm(E - D["O6"]) - D["link5"]], -1), C, Dp, E

    def roots(self, D, A):
        """(N, S, 2) roots (NaN where none) from a grid x grid of starts."""
        N = len(A)
        g = np.linspace(-math.pi, math.pi, self.grid, endpoint=False)
        starts = np.stack(np.meshgrid(g, g, indexing="ij"), -1).reshape(-1, 2)
        S = len(starts)
        rep = {k: np.repeat(v, S, axis=0) for k, v in D.items()}
        Ar = np.repeat(A, S, axis=0)
        x = np.tile(starts, (N, 1))
        h = 1e-7
        for _ in range(40):
            r = self.residual(rep, Ar, x)[0]
            J = np.stack([(self.residual(rep, Ar, x + h * np.eye(2)[k])[0]
                           - self.residual(rep, Ar, x - h * np.eye(2)[k])[0]) / (2 * h) for k in (0, 1)], -1)
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
            with np.errstate(all="ignore"):
                dx = np.stack([J[:, 1, 1] * r[:, 0] - J[:, 0, 1] * r[:, 1],
                               J[:, 0, 0] * r[:, 1] - J[:, 1, 0] * r[:, 0]], -1) / det[:, None]
            dx = np.where(np.isfinite(dx), np.clip(dx, -0.5, 0.5), 0.0)
            x = x - dx
        r = self.residual(rep, Ar, x)[0]
        ok = np.abs(r).max(1) <= 1e-10 * self.size
        x[~ok] = np.nan
        return x.reshape(N, S, 2)

    def cut_gap(self, D, A):
        """min over the four-bar O4-D-E-O6 (link4 turning about O4, both branches) of
        ||C - A| - link3|, C on the triad; inf where the four-bar never closes."""
        N = len(A)
        psi = np.linspace(-math.pi, math.pi, 4001)
        best = np.full(N, np.inf)
        # D -> E in the triad's frame (C at 0, D at (triad, 0), E at its place)
        w = D["triad.E"] - np.stack([D["triad"], 0 * D["triad"]], -1)
        de = norm(w)
        for k in range(N):
            def gap(ps, side):
                Dp = D["O4"][k] + D["link4"][k] * unit(ps)
                E, miss = two_circles(Dp, np.broadcast_to(D["O6"][k], Dp.shape), np.full(len(ps), de[k]),
                                      np.full(len(ps), D["link5"][k]), side)
                e = turn((E - Dp) / de[k], -math.atan2(w[k, 1], w[k, 0]))   # the triad's C -> D
                C = Dp - D["triad"][k] * e
                return np.where(miss > 0, np.inf, np.abs(norm(C - A[k]) - D["link3"][k]))
            for side in (1.0, -1.0):
                v = gap(psi, side)
                i = int(np.argmin(v))
                if not np.isfinite(v[i]):
                    continue
                lo, hi = psi[max(i - 1, 0)], psi[min(i + 1, len(psi) - 1)]
                for _ in range(80):            # golden section on the bracket
                    a1, a2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
                    if gap(np.array([a1]), side)[0] < gap(np.array([a2]), side)[0]:
                        hi = a2
                    else:
                        lo = a1
                best[k] = min(best[k], v[i], gap(np.array([0.5 * (lo + hi)]), side)[0])
        return best

    def newton(self, D, A, x, iterations=30):
        h = 1e-7
        for _ in range(iterations):
            r = self.residual(D, A, x)[0]
            J = np.stack([(self.residual(D, A, x + h * np.eye(2)[k])[0]
                           - self.residual(D, A, x - h * np.eye(2)[k])[0]) / (2 * h) for k in (0, 1)], -1)
            det = J[:, 0, 0] * J[:, 1, 1] - J[:, 0, 1] * J[:, 1, 0]
            with np.errstate(all="ignore"):
                dx = np.stack([J[:, 1, 1] * r[:, 0] - J[:, 0, 1] * r[:, 1],
                               J[:, 0, 0] * r[:, 1] - J[:, 1, 0] * r[:, 0]], -1) / det[:, None]
            x = x - np.where(np.isfinite(dx), np.clip(dx, -0.5, 0.5), 0.0)
        return x, np.abs(self.residual(D, A, x)[0]).max(1)

    def continued(self, D1, steps=200):
        """The sketch's configuration followed in small equal steps of the dimensions, from
        the sketch's (t = 0) to D1 (t = 1), lengths, places and pivots in straight lines:
        link3's and the triad's angles at the end, NaN where a step fails to converge or
        jumps (the branch ends on the way)."""
        P = self.P0
        D0 = {k: np.broadcast_to(v, np.shape(D1[k])) for k, v in self.batch([{}]).items()}
        x = np.tile([math.atan2(*(P["C"] - P["A"])[::-1]),
                     math.atan2(*(P["D"] - P["C"])[::-1])], (len(D1["crank"]), 1))
        alive = np.ones(len(x), bool)
        for t in np.linspace(0.0, 1.0, steps + 1)[1:]:
            D = {k: (1 - t) * D0[k] + t * D1[k] for k in D1}
            new, res = self.newton(D, self.crank_pin(D), x.copy(), iterations=6)
            jump = np.abs(np.remainder(new - x + math.pi, 2 * math.pi) - math.pi).max(1)
            alive &= (res <= 1e-10 * self.size) & (jump < 0.1)
            x = np.where(alive[:, None], new, x)
        x[~alive] = np.nan
        return x

    def expect(self, D):
        A = self.crank_pin(D)
        continued = self.continued(D)
        # where the sketch's branch does not continue, the brute-force search; elsewhere the
        # continued configuration is a root
        roots = np.full((len(A), 1, 2), np.nan)
        roots[:, 0] = continued
        lost = np.flatnonzero(~np.isfinite(continued[:, 0]))
        if len(lost):
            more = self.roots({k: v[lost] for k, v in D.items()}, A[lost])
            roots = np.concatenate([roots, np.full((len(A), more.shape[1], 2), np.nan)], 1)
            roots[lost, 1:] = more
        found = np.isfinite(roots[..., 0]).any(1)
        ex1 = excess(norm(D["O4"] - D["O2"]), D["link4"], D["triad"], D["link3"], D["crank"])
        ex2 = excess(norm(D["triad.E"] - np.array([D["triad"], 0 * D["triad"]]).T),
                     D["link5"], norm(D["O6"] - D["O4"]), D["link4"])
        ex = np.where(ex1 > 0, ex1, ex2)
        gap = np.zeros(len(A))
        miss = ~found & (ex <= 0)
        if miss.any():
            idx = np.flatnonzero(miss)
            gap[idx] = self.cut_gap({k: v[idx] for k, v in D.items()}, A[idx])
        gap[~found & (ex > 0)] = np.inf
        v = _verdict(ex, np.where(found, 0.0, np.maximum(gap, 1e-300)), {"A": A},
                     np.zeros(len(A), bool))
        v["roots"] = roots
        v["continued"] = continued
        return v


class Jansen(Case):
    """Jansen's linkage: the crank O-A; the dyads upper-top (A-C-B) and lower-rocker (A-D-B),
    each on its own; E on top and G on leg by their sides (a triangle of three known sides);
    then the dyad thigh-leg (E-F-D), on the four branches of the first two.  Where the
    sketch's branch does not close, the branch with the fewest dyads changed, then the
    configuration nearest to the sketch (the model's rule)."""

    def expect(self, D):
        P, m = self.P0, self.mechanism
        A = self.crank_pin(D)
        s1, s2, s3 = self.side("A", "C", "B"), self.side("A", "D", "B"), self.side("E", "F", "D")
        Eloc = triangle(m.link("top").sides["E"], D["top"])
        Gloc = triangle(m.link("leg").sides["G"], D["leg"])
        free = ["A", "C", "D", "E", "F", "G"]
        rows = []
        for c1 in (s1, -s1):
            C, gap1 = two_circles(A, D["B"], D["upper"], D["top"], np.full(len(A), c1))
            E = self.place(D, D["B"], C, Eloc)
            for c2 in (s2, -s2):
                Dp, gap2 = two_circles(A, D["B"], D["lower"], D["rocker"], np.full(len(A), c2))
                F, gap3 = two_circles(E, Dp, D["thigh"], D["leg"], np.full(len(A), s3))
                G = self.place(D, Dp, F, Gloc)
                pts = {"A": A, "C": C, "D": Dp, "E": E, "F": F, "G": G}
                dist = sum(np.sum((pts[p] - P[p]) ** 2, -1) for p in free)
                rows.append((pts, gap1, gap2, gap3, (c1 != s1) + (c2 != s2), dist))
        gap1, gap2 = rows[0][1], rows[0][2]
        closes = np.stack([(g1 == 0) & (g2 == 0) & (g3 == 0) for _, g1, g2, g3, _, _ in rows])
        # the kept branch: fewest changes, then nearest
        changes = np.stack([np.full(len(A), r[4]) for r in rows])
        best_changes = np.min(np.where(closes, changes, 9), axis=0)
        score = np.where(closes & (changes == best_changes), np.stack([r[5] for r in rows]), np.inf)
        pick = np.argmin(score, axis=0)
        points = {p: np.choose(pick[:, None], [r[0][p] for r in rows]) for p in free}
        gap3 = np.min(np.stack([r[3] for r in rows]), axis=0)
        gap = np.where(gap1 > 0, gap1, np.where(gap2 > 0, gap2, np.where(closes.any(0), 0.0, gap3)))
        switched = np.where(closes.any(0), best_changes, 0)
        EB = norm(Eloc)
        ex1 = excess(norm(D["B"] - D["O"]), D["top"], D["upper"], D["crank"])
        ex2 = excess(norm(D["B"] - D["O"]), D["rocker"], D["lower"], D["crank"])
        ex3 = excess(EB, norm(D["B"] - D["O"]), D["crank"], D["lower"], D["leg"], D["thigh"])
        ex = np.where(ex1 > 0, ex1, np.where(ex2 > 0, ex2, ex3))
        v = _verdict(ex, gap, points, switched)
        # a place by sides that no triangle has: the link itself cannot be built
        v["invalid"] = np.zeros(len(A), bool)
        for link, p in (("top", "E"), ("leg", "G")):
            spec = m.link(link).sides[p]
            a, b = (spec[k] for k in spec if k != "side")
            v["invalid"] |= (D[link] > a + b) | (D[link] < abs(a - b))
        return v


def triangle(spec, L):
    """(along, left) of a point given by its sides from a link's first two points, L apart:
    at spec[first] from the first and spec[second] from the second, on spec's side (the law
    of cosines; here the two points are always the link's first two)."""
    first, second = (k for k in spec if k != "side")
    a, b = spec[first], spec[second]
    along = (a * a - b * b + L * L) / (2 * L)
    left = np.sqrt(np.maximum(a * a - along * along, 0.0))
    return np.stack([along, left if spec["side"] == "left" else -left], -1)


def _verdict(ex, gap, points, switched):
    bars = ex > 0
    return {"refused": bars | (gap > 0), "bars": bars,
            "gap": np.where(bars, ex, gap), "points": points, "switched": switched}


def cases() -> list[Case]:
    """Every catalogue mechanism and example file, with the dimensions an edit may change."""
    mech = kl.mechanisms
    load = lambda f: kl.load(ROOT / "examples" / f)   # noqa: E731
    four = {"crank": "length", "coupler": "length", "rocker": "length", "O4": "pivot",
            "O2": "pivot", "coupler.P": "local"}
    slider = {"crank": "length", "rod": "length", "slide": "offset", "O2": "pivot"}
    slot = lambda guide, joint: {"crank": "length", guide: "length", joint: "offset", "O4": "pivot",   # noqa: E731
                                 "O2": "pivot"}
    white = {"crank": "length", "lever": "length", "rod": "length", "ram_slide": "offset", "slot": "offset",
             "O4": "pivot", "O2": "pivot"}
    five = {"crank1": "length", "coupler1": "length", "coupler2": "length", "crank2": "length",
            "O4": "pivot"}
    watt = {"crank": "length", "coupler": "length", "rocker": "length", "link5": "length",
            "output": "length", "rocker.C": "local", "O4": "pivot", "O6": "pivot"}
    steph = {"crank": "length", "coupler": "length", "rocker": "length", "link5": "length",
             "output": "length", "coupler.C": "local", "O4": "pivot", "O6": "pivot"}
    triad = {"crank": "length", "link3": "length", "triad": "length", "link4": "length",
             "link5": "length", "triad.E": "local", "O4": "pivot", "O6": "pivot"}

    class SlotCase(SlottedLink):
        pass

    class LeverCase(SlottedLink):
        guide = "lever"
        joint = "slot"
    return [
        FourBar("fourbar", mech.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)), four),
        FourBar("crank_rocker.toml", load("crank_rocker.toml"), four),
        SliderCrank("slider_crank", mech.slider_crank(1.0, 3.0, offset=0.5), slider),
        SliderCrank("engine.toml", load("engine.toml"), slider),
        SliderCrank("offset_slider_crank.toml", load("offset_slider_crank.toml"), slider),
        SlotCase("inverted_slider_crank", mech.inverted_slider_crank(2.0, 1.0), slot("rocker", "slide")),
        SlotCase("inverted_slider_crank.toml", load("inverted_slider_crank.toml"), slot("rocker", "slide")),
        LeverCase("slotted_link", mech.slotted_link(1.0, 2.0), slot("lever", "slot")),
        LeverCase("slotted_link.toml", load("slotted_link.toml"), slot("lever", "slot")),
        Whitworth("whitworth", mech.whitworth(1.0, 0.5, 3.0, 2.5, ram_height=1.0), white),
        Whitworth("whitworth.toml", load("whitworth.toml"), white),
        FiveBar("fivebar", mech.fivebar(3.0, 1.0, 2.0, 2.0, 1.5), five),
        FiveBar("fivebar.toml", load("fivebar.toml"), five),
        SixBar("watt6", mech.watt6(), watt),
        SixBar("stephenson6", mech.stephenson6(), steph),
        SixBar("stephenson6.toml", load("stephenson6.toml"), steph),
        Triad("triad6", mech.triad6(), triad),
        Jansen("jansen.toml", load("jansen.toml"), {
            "crank": "length", "upper": "length", "lower": "length", "top": "length",
            "rocker": "length", "thigh": "length", "leg": "length", "B": "pivot"}),
    ]
