"""Assembly: from a rough sketch and exact lengths to the nearest assembled configuration.

A person knows the lengths of the links and draws the linkage by eye.  Here the drawing is
moved, as little as possible, until every link has its length and every point its place:
the assembled configuration nearest to the sketch (least squares over the points).

The constraints are those of natural coordinates (García de Jalón): the points are the
unknowns; a link keeps the distance between its first two points (its ``length``, else as
drawn) and each other point's place in its frame (its ``local`` place, else as drawn);
a prismatic joint keeps its point on the guide's line (at its ``offset`` from the origin,
else as drawn) and the slider's angle to the guide.  The ground's points are the frame and
stay where they are.  The nearest configuration x to the sketch x0 on c(x) = 0 is where
x - x0 is normal to the constraints; it is found by the Gauss-Newton projection
``x <- x0 - J+ (J (x0 - x) + c(x))``, whose fixed points are exactly those.
"""
from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from kinelab.errors import AssemblyError, ModelError, describe, shown
from kinelab.kinematics._geometry import sketch_angle
from kinelab.model import Mechanism, Point, Units, exact_places

__all__ = ["Assembly", "assemble", "pose", "needs_assembly", "check_assembled", "assembly_miss",
           "SketchNotAssembled"]

_TOL = 1e-14          # relative to the mechanism's size: assembled
_ITERATIONS = 60
_MOVED = 1e-9         # relative: a point that moved less than this did not move


@dataclass(frozen=True)
class Assembly:
    """A mechanism assembled from its sketch.

    Attributes
    ----------
    mechanism : Mechanism
        The same mechanism with every point at its assembled place (m).
    moved : dict of str to float
        How far each point that moved went, m, largest first.
    """

    mechanism: Mechanism
    moved: Mapping[str, float]

    @property
    def largest_move(self) -> float:
        return max(self.moved.values(), default=0.0)


def needs_assembly(m: Mechanism) -> bool:
    """Whether the model gives lengths, places or offsets that the sketch must be moved to."""
    return (any(link.length is not None or link.local or link.sides for link in m.links)
            or any(j.offset is not None for j in m.joints))


def assemble(mechanism: Mechanism, *, units: Units | None = None) -> Assembly:
    """Move a rough sketch to the assembled configuration nearest to it.

    The links' ``length`` and ``local`` places and the prismatic joints' ``offset`` are
    exact; everything else keeps its shape as the sketch draws it, and the ground's points
    stay.  The branch (assembly mode) is the sketch's: a dyad drawn on one side of the
    line of its ends stays on that side.

    Parameters
    ----------
    mechanism : Mechanism
        A planar mechanism whose points are a sketch (rough where lengths are given).
    units : Units, optional
        The units lengths are written in, in messages (default m).

    Returns
    -------
    Assembly
        The assembled mechanism and which points moved, by how much.

    Raises
    ------
    AssemblyError
        No assembly near the sketch: names the loop, the link and the gap, and for a loop
        of bars the inequality its lengths fail.
    ModelError
        The ground's points disagree with the ground's length (the frame is not moved); or
        the nearest assembly is on another branch than the sketch shows.

    Examples
    --------
    A four-bar drawn by eye, with its exact lengths (crank 1, coupler 3, rocker 2.5):

    >>> from kinelab.model import Mechanism, Point, Units, Link, Joint, Input
    >>> rough = Mechanism("fourbar", (Point("O2", 0, 0), Point("A", 0.1, 1.05),
    ...                               Point("B", 2.6, 2.5), Point("O4", 3, 0)),
    ...     (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A"), length=1.0),
    ...      Link("coupler", ("A", "B"), length=3.0), Link("rocker", ("O4", "B"), length=2.5)),
    ...     tuple(Joint(f"j{p}", "R", ab, point=p) for p, ab in
    ...           (("O2", ("ground", "crank")), ("A", ("crank", "coupler")),
    ...            ("B", ("coupler", "rocker")), ("O4", ("ground", "rocker")))),
    ...     (Input(joint="jO2"),))
    >>> a = kl.kinematics.assemble(rough)
    >>> m = a.mechanism
    >>> round(float(np.hypot(*np.subtract(m.point("B").xy, m.point("A").xy))), 12)
    3.0
    >>> sorted(a.moved)                          # the ground's points stay
    ['A', 'B']
    """
    if not isinstance(mechanism, Mechanism):
        raise ModelError(f"mechanism: expected a kinelab Mechanism, got {type(mechanism).__name__}")
    if mechanism.space != "planar":
        raise ModelError(f"space: assembly is for planar mechanisms, got {shown(mechanism.space)}")
    system = _Constraints(mechanism, units or Units())
    x0 = system.x0
    x = _nearest(system, x0)
    residual = system.residual(x)
    if not np.all(np.abs(residual) <= 1e3 * _TOL * system.scale):
        text, loop, link, gap = system.no_assembly(x)
        raise AssemblyError(text, loop=loop, gap=gap, link=link)
    points = system.points_at(x)
    moved = {n: float(math.dist(points[n], (p.x, p.y))) for n, p in
             ((p.name, p) for p in mechanism.points)}
    moved = {n: d for n, d in sorted(moved.items(), key=lambda kv: -kv[1])
             if d > _MOVED * system.scale}
    joints = tuple(system.turned_axis(j, points) for j in mechanism.joints)
    out = dataclasses.replace(mechanism, points=tuple(Point(p.name, *points[p.name])
                                                      for p in mechanism.points), joints=joints)
    _same_branches(mechanism, out)
    return Assembly(out, moved)


def _nearest(system: _Constraints, x0: np.ndarray) -> np.ndarray:
    """Gauss-Newton projection of x0 onto c(x) = 0 (see the module docstring)."""
    x = x0.copy()
    tol = _TOL * system.scale
    if not len(x):
        return x
    for _ in range(_ITERATIONS):
        c, J = system.residual(x), system.jacobian(x)
        step = _min_norm(J, J @ (x0 - x) + c)
        x_new = x0 - step
        if not np.all(np.isfinite(x_new)):
            break
        done = np.max(np.abs(x_new - x)) <= tol
        x = x_new
        if done and np.max(np.abs(system.residual(x))) <= 1e3 * tol:
            break
    return x


def assembly_miss(m: Mechanism) -> float:
    """By how much, relative to the mechanism's size, its sketch misses the lengths, places
    and offsets it declares (0 when it declares none)."""
    if not needs_assembly(m) or m.space != "planar":
        return 0.0
    system = _Constraints(m)
    return system.worst(system.x0)[1] / system.scale


class SketchNotAssembled(ModelError):
    """A model whose sketch misses the lengths, places or offsets it declares (a rough
    sketch that was not assembled): ``miss`` says which, and by how much."""

    __module__ = "kinelab.kinematics"      # where users find it

    def __init__(self, part: str, by: float):
        self.miss = f"{describe(part)} misses its declared length or place by {by:.6g} m"
        super().__init__(f"the sketch is not assembled: {self.miss}; assemble it first, with "
                         "kl.kinematics.assemble(mechanism).mechanism")


def check_assembled(m: Mechanism) -> None:
    """Raise SketchNotAssembled when a model's sketch does not have the lengths, places
    and offsets it declares."""
    if not needs_assembly(m) or m.space != "planar":
        return
    system = _Constraints(m)
    name, miss = system.worst(system.x0)
    if miss > 1e-9 * system.scale:
        raise SketchNotAssembled(name, miss)


def _min_norm(J, b: np.ndarray) -> np.ndarray:
    """The smallest dx with J dx = b (least squares where J is rank deficient): dense for
    the mechanisms people draw, iterative for huge ones."""
    if J.shape[1] <= 2000:
        dx, *_ = np.linalg.lstsq(J.toarray(), b, rcond=None)
        return dx
    from scipy.sparse.linalg import lsqr
    return lsqr(J, b, atol=1e-15, btol=1e-15, iter_lim=20 * J.shape[1])[0]


def _same_branches(sketch: Mechanism, assembled: Mechanism) -> None:
    """The assembled configuration is on the branch the sketch shows (each dyad's side)."""
    from kinelab.kinematics._plan import SIGN_FIELDS, build_plan

    try:
        before = build_plan(sketch)
    except ModelError:          # the rough sketch cannot be planned (a dyad drawn straight)
        return
    after = build_plan(assembled)
    for k, row in enumerate(before.ops_i):
        field_ = SIGN_FIELDS.get(int(row[0]))
        if field_ is None or before.ops_f[k, field_] == after.ops_f[k, field_]:
            continue
        step = before.step_of_op(k)
        raise ModelError(f"the nearest assembly puts {step.label if step else 'a dyad'} on the "
                         "other side of the line of its ends than the sketch draws it; draw its "
                         "middle joint further from that line, on the side you mean")


class _Constraints:
    """The constraints of a sketch, in the coordinates of its points that may move.

    Rows: a link's distance between its first two points; the place of each other point
    in the link's frame (two rows, linear in the points); a prismatic joint's point on its
    guide's line, and a slider's angle to its guide.  The first two kinds are evaluated for
    all links at once; the last two, few, one by one.
    """

    def __init__(self, m: Mechanism, units: Units = Units()):
        self.m = m
        self.units = units
        names = [p.name for p in m.points]
        self.index = {n: i for i, n in enumerate(names)}
        self.sketch = np.array([[p.x, p.y] for p in m.points], float).reshape(-1, 2)
        ground = set(m.ground.points)
        free = np.array([n not in ground for n in names], bool)
        self.free_points = np.flatnonzero(free)
        self.column = np.full(len(names), -1, np.int64)
        self.column[self.free_points] = 2 * np.arange(len(self.free_points))
        self.x0 = self.sketch[self.free_points].ravel().copy()
        self.scale = float(max(np.ptp(self.sketch[:, 0]), np.ptp(self.sketch[:, 1]), 1e-300))
        xy = {n: self.sketch[i] for n, i in self.index.items()}
        dist, frame, self.special = [], [], []
        problems = []
        for link in m.links:
            pts = link.points
            if link.ground:
                if link.length is not None:
                    d = math.dist(xy[pts[0]], xy[pts[1]])
                    if abs(d - link.length) > 1e-9 * link.length:
                        problems.append(
                            f"link '{link.name}': length: the ground's points are the frame and "
                            f"are not moved; they are {self.length(d)} apart but its length is "
                            f"{self.length(link.length)}; correct the points or the length")
                continue
            if len(pts) < 2:
                continue
            a, b = pts[0], pts[1]
            d_ab = xy[b] - xy[a]
            L = link.length if link.length is not None else float(np.hypot(*d_ab))
            if L == 0.0:
                continue
            dist.append((self.index[a], self.index[b], L, link.name))
            local = exact_places(link, xy)      # its local places and its sides
            for p in pts[2:]:
                if p in local:
                    along, left = local[p]
                    lam, mu = along / L, left / L
                else:       # as drawn: its place in the frame of the first two points
                    r = xy[p] - xy[a]
                    d2 = float(d_ab @ d_ab)
                    lam, mu = float(r @ d_ab) / d2, float(d_ab[0] * r[1] - d_ab[1] * r[0]) / d2
                frame.append((self.index[p], self.index[a], self.index[b], lam, mu, link.name))
        for j in m.joints:
            if j.type != "P" or j.axis is None:
                continue
            g, s = (m.link(n) for n in j.links)
            origin = j.origin or g.points[0]
            beta = math.atan2(j.axis[1], j.axis[0]) - sketch_angle(m, g.name)
            u = _direction(xy, g, beta)
            offset = j.offset if j.offset is not None else _cross(u, xy[j.point] - xy[origin])
            self.special.append(("line", j.name, (j.point, origin, g.name, beta, offset)))
            if len(s.points) >= 2 and len(g.points) >= 2:
                delta = sketch_angle(m, s.name) - sketch_angle(m, g.name)
                self.special.append(("slider", j.name, (g.name, s.name, delta)))
        if problems:
            raise ModelError(problems, source=f"mechanism '{m.name}'")
        self.dist = (np.array([r[0] for r in dist], np.int64), np.array([r[1] for r in dist], np.int64),
                     np.array([r[2] for r in dist], float))
        self.frame = tuple(np.array([r[k] for r in frame], np.int64 if k < 3 else float).reshape(-1)
                           for k in range(5))
        # what each row is, for messages: (link or joint name, width)
        self.labels = ([(r[3], 1) for r in dist] + [(r[5], 2) for r in frame]
                       + [(name, 1) for _, name, _ in self.special])

    # -- the points --------------------------------------------------------------------
    def all_points(self, x: np.ndarray) -> np.ndarray:
        P = self.sketch.copy()
        P[self.free_points] = x.reshape(-1, 2)
        return P

    def points_at(self, x: np.ndarray) -> dict[str, tuple[float, float]]:
        P = self.all_points(x)
        return {n: (float(P[i, 0]), float(P[i, 1])) for n, i in self.index.items()}

    def _frame_of(self, P, link_name: str):
        pts = self.m.link(link_name).points
        if len(pts) < 2:
            return np.array([1.0, 0.0])
        d = P[self.index[pts[1]]] - P[self.index[pts[0]]]
        return d / np.hypot(*d)

    def _special(self, P) -> np.ndarray:
        out = []
        for kind, _, data in self.special:
            if kind == "line":
                p, o, g, beta, offset = data
                u = _rotate(self._frame_of(P, g), beta)
                out.append(_cross(u, P[self.index[p]] - P[self.index[o]]) - offset)
            else:
                g, s, delta = data
                out.append(_cross(_rotate(self._frame_of(P, g), delta), self._frame_of(P, s))
                           * self.scale)
        return np.array(out, float)

    # -- residual and Jacobian ---------------------------------------------------------
    def residual(self, x: np.ndarray) -> np.ndarray:
        P = self.all_points(x)
        ia, ib, L = self.dist
        d = P[ib] - P[ia]
        r_dist = (np.einsum("ij,ij->i", d, d) - L * L) / (2 * L)
        ip, fa, fb, lam, mu = self.frame
        e = P[fb] - P[fa]
        r_frame = P[ip] - P[fa] - lam[:, None] * e - mu[:, None] * np.stack([-e[:, 1], e[:, 0]], -1)
        return np.concatenate([r_dist, r_frame.ravel(), self._special(P)])

    def jacobian(self, x: np.ndarray):
        """The constraints' Jacobian with respect to the free coordinates, sparse: distance
        and frame rows exactly; the few joint rows by central differences of their own
        points."""
        from scipy import sparse

        P = self.all_points(x)
        rows, cols, vals = [], [], []

        def put(r, point_index, block):       # block (k, 2): d rows / d (x, y) of a point
            c = self.column[point_index]
            keep = c >= 0
            for comp in range(2):
                rows.append(np.broadcast_to(r, block.shape[:1])[keep])
                cols.append(c[keep] + comp)
                vals.append(block[keep, comp])

        ia, ib, L = self.dist
        n_dist = len(L)
        d = (P[ib] - P[ia]) / L[:, None]
        r = np.arange(n_dist)
        put(r, ia, -d)
        put(r, ib, d)
        ip, fa, fb, lam, mu = self.frame
        base = n_dist + 2 * np.arange(len(lam))
        one = np.ones_like(lam)
        zero = np.zeros_like(lam)
        # row x: p_x - a_x - lam (b_x - a_x) + mu (b_y - a_y); row y: p_y - a_y - lam e_y - mu e_x
        put(base, ip, np.stack([one, zero], -1))
        put(base, fa, np.stack([lam - 1, -mu], -1))
        put(base, fb, np.stack([-lam, mu], -1))
        put(base + 1, ip, np.stack([zero, one], -1))
        put(base + 1, fa, np.stack([mu, lam - 1], -1))
        put(base + 1, fb, np.stack([-mu, -lam], -1))
        first = n_dist + 2 * len(lam)
        if self.special:
            h = 1e-7 * self.scale
            for k in range(len(self.x0)):
                point = self.free_points[k // 2]
                if not self._touches_special(point):
                    continue
                Pp, Pm = P.copy(), P.copy()
                Pp[point, k % 2] += h
                Pm[point, k % 2] -= h
                col = (self._special(Pp) - self._special(Pm)) / (2 * h)
                nz = np.flatnonzero(col)
                rows.append(first + nz)
                cols.append(np.full(len(nz), k))
                vals.append(col[nz])
        n_rows = first + len(self.special)
        if not rows:
            return sparse.csr_matrix((n_rows, len(x)))
        return sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                                 shape=(n_rows, len(x)))

    def _touches_special(self, point: int) -> bool:
        name = self.m.points[point].name
        for kind, _, data in self.special:
            if kind == "line":
                p, o, g, _, _ = data
                if name in (p, o) or name in self.m.link(g).points[:2]:
                    return True
            else:
                g, s, _ = data
                if name in self.m.link(g).points[:2] or name in self.m.link(s).points[:2]:
                    return True
        return False

    # -- what a failure says -------------------------------------------------------------
    def worst(self, x: np.ndarray) -> tuple[str, float]:
        """(link or joint, residual) of the constraint missed the most."""
        r = np.abs(self.residual(x))
        row, best, name = 0, 0.0, ""
        for label, width in self.labels:
            v = float(np.max(r[row:row + width]))
            if v > best:
                best, name = v, label
            row += width
        return name, best

    def no_assembly(self, x: np.ndarray) -> tuple[str, str, str, float]:
        """(message, loop, link to blame, gap in m) of a sketch that no assembly is near.

        A loop of bars whose longest bar is longer than the others together cannot close
        in any configuration, and misses by exactly that excess: such a loop is named, the
        first in the order of the links, with its inequality.  Otherwise the loop through
        the constraint missed the most where the search stopped, and by how much."""
        for link in self.m.links:
            if link.ground:
                continue
            loop = _loop_through(self.m, link.name)
            bars = _bar_lengths(self.m, loop) if loop else None
            if not bars:
                continue
            longest = max(bars, key=bars.get)
            rest = {k: v for k, v in bars.items() if k != longest}
            excess = bars[longest] - sum(rest.values())
            if excess > 0:
                text = (f"no assembly: the loop {'-'.join(loop)} cannot close; it misses by "
                        f"{self.length(excess)}: its longest bar is longer than the others "
                        f"together: {longest} {self.length(bars[longest])} > "
                        + " + ".join(f"{k} {self.length(v, unit=False)}" for k, v in rest.items())
                        + f" = {self.length(sum(rest.values()))}; shorten {longest} to at most "
                        f"{self.length(sum(rest.values()))} or lengthen the others")
                return text, "-".join(loop), longest, excess
        name, gap = self.worst(x)
        loop = _loop_through(self.m, name) if name in self.m.link_names else None
        where = f"the loop {'-'.join(loop)}" if loop else f"'{name}'"
        text = (f"no assembly near the sketch: {where} cannot close; it misses by "
                f"{self.length(gap)} at {'link' if name in self.m.link_names else 'joint'} '{name}'"
                "; check the lengths, or draw the sketch closer to an assembly")
        blame = name if name in self.m.link_names else ""
        return text, "-".join(loop) if loop else name, blame, gap

    def length(self, v: float, unit: bool = True) -> str:
        """A length for a message, in the units the model is written in."""
        return f"{self.units.convert(v, 'm'):.6g}" + (f" {self.units.length}" if unit else "")

    def turned_axis(self, j, points):
        """A prismatic joint's axis, turned with its guide from the sketch to the assembly
        (the axis is given in the sketch's frame and is fixed in the guide)."""
        if j.type != "P" or j.axis is None or len(j.axis) != 2:
            return j
        g = self.m.link(j.links[0])
        if len(g.points) < 2:
            return j
        before = sketch_angle(self.m, g.name)
        a, b = points[g.points[0]], points[g.points[1]]
        turn = math.atan2(b[1] - a[1], b[0] - a[0]) - before
        if turn == 0.0:
            return j
        axis = _rotate(np.asarray(j.axis, float), turn)
        return dataclasses.replace(j, axis=(float(axis[0]), float(axis[1])))


def _direction(xy, link, beta) -> np.ndarray:
    pts = link.points
    if len(pts) < 2:
        return np.array([math.cos(beta), math.sin(beta)])
    d = xy[pts[1]] - xy[pts[0]]
    return _rotate(d / np.hypot(*d), beta)


def _rotate(v, angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _k_cross(v):
    return np.array([-v[1], v[0]])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _loop_through(m: Mechanism, link: str) -> list[str] | None:
    """The joint points of the shortest loop of the linkage through ``link``: a path from
    one of its joints back to another without using the link itself (breadth first)."""
    joints = [j for j in m.joints if j.point is not None]
    own = [j for j in joints if link in j.links]
    if len(own) < 2:
        return None
    start, goal = own[0], own[1]
    # nodes: joints; two joints are adjacent when they share a link other than `link`
    by_link: dict[str, list] = {}
    for j in joints:
        for n in j.links:
            by_link.setdefault(n, []).append(j)
    previous = {start.name: None}
    todo = [start]
    while todo:
        j = todo.pop(0)
        if j.name == goal.name:
            path = []
            while j is not None:
                path.append(j.point)
                j = previous[j.name]
            return path[::-1]
        for n in j.links:
            if n == link:
                continue
            for k in by_link[n]:
                if k.name not in previous:
                    previous[k.name] = j
                    todo.append(k)
    return None


def _bar_lengths(m: Mechanism, loop: list[str]) -> dict[str, float] | None:
    """For a loop whose every side is a link with a known distance between its two joints,
    those distances by link name (the sketch's where no length is given)."""
    xy = {p.name: (p.x, p.y) for p in m.points}
    ring = loop + loop[:1]
    bars = {}
    for a, b in zip(ring, ring[1:]):
        shared = [link for link in m.links if a in link.points and b in link.points]
        if len(shared) != 1:
            return None
        link = shared[0]
        if link.length is not None and set(link.points[:2]) == {a, b}:
            bars[link.name] = link.length
        else:
            bars[link.name] = math.dist(xy[a], xy[b])
    return bars


def pose(mechanism: Mechanism, q) -> Mechanism:
    """The same mechanism sketched at input ``q``, on the branch the analysis follows there.

    Every point moves to its place at q (from :func:`kinelab.kinematics.analyze`: on the
    sketch's branch, continued smoothly through change points), every prismatic joint's
    axis turns with its guide, and the inputs, lengths, masses and parameters stay.  Use it
    to read the mobility or draw the mechanism at another pose, to change the reference
    configuration, or to place a synthesized linkage in any of its positions.

    Parameters
    ----------
    mechanism : Mechanism
    q : float or array_like, shape () or (M,)
        The inputs of the new sketch, rad or m.

    Returns
    -------
    Mechanism

    Raises
    ------
    AssemblyError
        The mechanism does not assemble at q.
    SingularityError
        q is a singular configuration: a sketch there could not show its branch.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> at = fb.at(np.radians(30.0))
    >>> np.degrees(kl.kinematics.plan(at).q_sketch).round(9)
    array([30.])
    >>> sol = kl.analyze(fb, np.radians(30.0))
    >>> bool(np.allclose(at.point("B").xy, sol.position("B"), rtol=0, atol=1e-15))
    True
    """
    from kinelab.errors import SingularityError
    from kinelab.kinematics._analyze import analyze

    sol = analyze(mechanism, q, at_singular="flag")
    if not sol.single:
        M = len(mechanism.inputs)
        raise ModelError(f"q: expected one configuration, shape {'()' if M == 1 else f'({M},)'}, "
                         f"got shape {np.shape(q)}; sketch each configuration on its own")
    if bool(np.any(sol.singular)):
        raise SingularityError(f"q: {np.round(sol.q[0], 9).tolist()} is a singular configuration "
                               f"of '{mechanism.name}' (det J = 0): a sketch there cannot show "
                               "its assembly mode; choose an input a little way off it")
    points = tuple(dataclasses.replace(p, x=float(xy[0]), y=float(xy[1]))
                   for p, xy in ((p, np.reshape(sol.position(p.name), -1)) for p in mechanism.points))
    joints = []
    for j in mechanism.joints:
        if j.type == "P" and j.axis is not None and len(j.axis) == 2:
            guide = j.links[0]
            turn = float(np.reshape(sol.angle(guide), -1)[0]) - sketch_angle(mechanism, guide)
            axis = _rotate(np.asarray(j.axis, float), turn)
            j = dataclasses.replace(j, axis=(float(axis[0]), float(axis[1])))
        joints.append(j)
    return dataclasses.replace(mechanism, points=points, joints=tuple(joints))
