"""Assembly: from a sketch and exact dimensions to the assembled configuration.

A person knows the dimensions of the links and draws the linkage by eye; a designer changes
a length of an assembled linkage.  Either way the points are a configuration that has
*drawn* dimensions (the sketch's own distances, places and offsets, which it satisfies
exactly) and the model *declares* others: the links' ``length`` and ``local`` places, the
prismatic joints' ``offset``, and the ground's points (pivots).  Assembly moves the points
to the configuration with the declared dimensions, at the same inputs (an input's value is
held at the sketch's: the crank keeps its drawn angle, a slide its drawn slide) and on the
same branch, in three steps:

1. **Continuation in the dimensions.**  The dimensions are a homotopy
   ``p(t) = (1 - t) p_drawn + t p_declared`` from the sketch's (t = 0) to the declared
   ones (t = 1), and the configuration follows them: a predictor along the tangent
   ``dx/dt = -J+ dc/dt`` and a Gauss-Newton corrector at each t, with adaptive steps (a
   step is taken again at half the size when its corrector does not contract, when it
   moves too far from the prediction, or when a dyad crosses the line of its ends).  The
   path keeps every dyad on the side of its line the sketch shows.
2. **A search over the branches**, when the path stops (the sketch's branch ceases to
   exist somewhere between t = 0 and 1): the loops are closed in closed form on every
   branch of every dyad, and Newton groups from a fixed set of starts (see
   ``_closure``).  The configuration on the sketch's branch is taken when it exists, else
   the one with the fewest dyads on another side (of those, the nearest to the sketch), and
   the result says which dyads changed side.
3. **Refusal**, when no configuration exists at those inputs: the error names the loop,
   the true gap (the least distance by which it fails to close at those inputs over its
   branches, see ``_closure``), the inputs at which it does close, and the nearest value
   of the changed dimension at which it closes at these.

The constraints are those of natural coordinates (García de Jalón): the points are the
unknowns; a link keeps the distance between its first two points (its ``length``, else as
drawn) and each other point's place in its frame (its ``local`` place, else as drawn);
a prismatic joint keeps its point on the guide's line (at its ``offset`` from the origin,
else as drawn) and the slider's angle to the guide; an input keeps its value.  The ground's
points are the frame.  Without inputs the configuration is the one nearest to the sketch
(least squares over the points): the corrector is the projection
``x <- x0 - J+ (J (x0 - x) + c(x))``, whose fixed points are where ``x - x0`` is normal
to the constraints (with inputs held it is Newton's step).
"""
from __future__ import annotations

import dataclasses
import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from kinelab.errors import AssemblyError, ModelError, describe, quoted, shown
from kinelab.kinematics._closure import Closure, Frames, decompose, rotate
from kinelab.kinematics._geometry import sketch_angle
from kinelab.model import Mechanism, Point, Units, exact_places, is_real, length_problem

__all__ = ["Assembly", "assemble", "reassemble", "pose", "needs_assembly", "check_assembled",
           "assembly_miss", "SketchNotAssembled"]

_TOL = 1e-14          # relative to the mechanism's size: assembled
_MOVED = 1e-9         # relative: a point that moved less than this did not move
_CORRECTOR = 8        # Gauss-Newton steps of a corrector
_POLISH = 40          # ... of the last one, at the declared dimensions
_CONTRACTION = 0.7    # a corrector's step must shrink at least this much each time
_SHORTEST = 2.0 ** -20   # the shortest step in t: below it the path has stopped
_ATTEMPTS = 400          # steps tried along one path, at most
_SEARCH_STARTS = 24   # starts of the search for a mechanism that does not decompose
_GRID = 721           # inputs (and dimensions) tried when looking for where it closes


@dataclass(frozen=True)
class Assembly:
    """A mechanism assembled from its sketch.

    Attributes
    ----------
    mechanism : Mechanism
        The same mechanism with every point at its assembled place (m).
    moved : dict of str to float
        How far each point that moved went, m, largest first.
    switched : tuple of str
        The dyads (and Newton groups) assembled in another mode than the sketch shows,
        because the sketch's does not exist at its inputs with these dimensions; empty when
        every one kept its side.
    """

    mechanism: Mechanism
    moved: Mapping[str, float]
    switched: tuple[str, ...] = ()

    @property
    def largest_move(self) -> float:
        return max(self.moved.values(), default=0.0)


def needs_assembly(m: Mechanism) -> bool:
    """Whether the model gives lengths, places or offsets that the sketch must be moved to."""
    return (any(link.length is not None or link.local or link.sides for link in m.links)
            or any(j.offset is not None for j in m.joints))


def assemble(mechanism: Mechanism, *, units: Units | None = None,
             pivots: Mapping[str, tuple[float, float]] | None = None) -> Assembly:
    """Move a sketch to the assembled configuration with the dimensions the model declares,
    at the sketch's inputs and on its branch.

    The links' ``length`` and ``local`` places and the prismatic joints' ``offset`` are
    exact; everything else keeps its shape as the sketch draws it, and the ground's points
    stay (or move to ``pivots``).  Each input keeps the value the sketch shows (a crank its
    drawn angle, a slide its drawn slide), and each dyad its side of the line of its ends:
    the configuration is followed by continuation from the sketch's own dimensions to the
    declared ones.  Where that branch does not exist at these inputs, the one with the
    fewest dyads on another side does (of those, the nearest to the sketch), and
    :attr:`Assembly.switched` says which dyads changed side.  A mechanism without inputs
    is moved to the assembly nearest to the sketch (least squares over the points).

    Parameters
    ----------
    mechanism : Mechanism
        A planar mechanism whose points are a sketch (rough where lengths are given).
    units : Units, optional
        The units lengths and inputs are written in, in messages (default SI).
    pivots : mapping of str to (float, float), optional
        New places of some of the ground's points, m: the sketch's are where the
        continuation starts.

    Returns
    -------
    Assembly
        The assembled mechanism, which points moved, by how much, and which dyads changed
        side.

    Raises
    ------
    AssemblyError
        No configuration exists at the sketch's inputs: names the loop, by how much it
        fails to close there (its least gap over every branch), the input values at which
        it does close and the nearest value of the changed dimension that closes it; for a
        loop of bars that cannot close at any input, the inequality its lengths fail.
    ModelError
        The ground's points disagree with the ground's length (the frame is not moved), or
        ``pivots`` names a point that is not the ground's.

    Examples
    --------
    A four-bar drawn by eye, with its exact lengths (crank 1, coupler 3, rocker 2.5): the
    crank keeps its drawn angle, B its side of the line A -> O4.

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
    >>> round(math.degrees(math.atan2(m.point("A").y, m.point("A").x)), 9)   # as drawn
    84.559667969
    >>> round(math.degrees(math.atan2(1.05, 0.1)), 9)
    84.559667969
    >>> sorted(a.moved), a.switched              # the ground's points stay
    (['A', 'B'], ())
    """
    if not isinstance(mechanism, Mechanism):
        raise ModelError(f"mechanism: expected a kinelab Mechanism, got {type(mechanism).__name__}")
    if mechanism.space != "planar":
        raise ModelError(f"space: assembly is for planar mechanisms, got {shown(mechanism.space)}")
    system = _Constraints(mechanism, units or Units(), pivots=pivots)
    closure = system.closure()
    closed = None
    if closure is not None and closure.exact:
        closed = system.close_all(closure)       # closed forms: every branch, at once
        if not closed.closes.any():
            raise system.refusal(closure, closed)       # none closes: nothing to follow
    x, ok = system.follow()
    switched: tuple[str, ...] = ()
    if not ok:
        if closure is not None and closed is None:
            closed = system.close_all(closure)
        x, switched = system.search(closure, closed)
    return system.assembly(x, switched)


def reassemble(mechanism: Mechanism, *, lengths: Mapping[str, float] | None = None,
               local: Mapping[str, Mapping[str, tuple[float, float]]] | None = None,
               offsets: Mapping[str, float] | None = None,
               pivots: Mapping[str, tuple[float, float]] | None = None,
               units: Units | None = None) -> Assembly:
    """The mechanism with some of its dimensions changed, assembled again: continued from
    its configuration, at its inputs, on its branch (see :func:`assemble`).

    Parameters
    ----------
    mechanism : Mechanism
        An assembled mechanism (its sketch is where the continuation starts).
    lengths : mapping of str to float, optional
        New lengths (first two points) of links, m.  The ground's moves its second point
        along the line from its first.
    local : mapping of str to mapping of str to (float, float), optional
        New places of links' other points, ``{link: {point: (along, left)}}``, m.
    offsets : mapping of str to float, optional
        New offsets of prismatic joints, m.
    pivots : mapping of str to (float, float), optional
        New places of the ground's points, m.
    units : Units, optional
        The units of messages (default SI).

    Returns
    -------
    Assembly
        The mechanism with the new dimensions declared, assembled.

    Raises
    ------
    ModelError
        An unknown name or a value that is not a length, place or offset.
    AssemblyError
        No configuration with the new dimensions exists at the mechanism's inputs (see
        :func:`assemble`).

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> a = kl.kinematics.reassemble(fb, lengths={"coupler": 2.0})
    >>> m = a.mechanism
    >>> round(math.dist(m.point("A").xy, m.point("B").xy), 12), list(a.moved)   # the crank stays
    (2.0, ['B'])
    """
    target, moved = _edited(mechanism, lengths, local, offsets, pivots)
    return assemble(target, units=units, pivots=moved)


def _edited(m: Mechanism, lengths, local, offsets, pivots):
    """The mechanism with the new dimensions declared, and the ground's points to move."""
    problems = []
    links = {link.name: link for link in m.links}
    joints = {j.name: j for j in m.joints}
    ground = m.ground
    moved = {}
    new_links = dict(links)
    for arg, value in (("lengths", lengths), ("local", local), ("offsets", offsets),
                       ("pivots", pivots)):
        if value is not None and not isinstance(value, Mapping):
            problems.append(f"{arg}: expected a mapping of names to values, got {describe(value)}")
    if problems:
        raise ModelError(problems)
    for name, v in (lengths or {}).items():
        link = links.get(name) if isinstance(name, str) else None
        if link is None:
            problems.append(f"lengths: expected one of the links {quoted(links)}, got "
                            f"{describe(name)}")
        elif len(link.points) < 2:
            problems.append(f"lengths.{name}: a link with one point has no length")
        elif not (is_real(v) and v > 0) or length_problem(float(v)):
            why = length_problem(float(v)) if is_real(v) and v > 0 else "expected a positive length (m)"
            problems.append(f"lengths.{name}: {why}, got {describe(v)}")
        elif link.ground:
            a, b = (np.array(m.point(p).xy) for p in link.points[:2])
            d = b - a
            moved[link.points[1]] = tuple(float(c) for c in a + d / np.hypot(*d) * float(v))
            if link.length is not None:
                new_links[name] = dataclasses.replace(new_links[name], length=float(v))
        else:
            new_links[name] = dataclasses.replace(new_links[name], length=float(v))
    for name, places in (local or {}).items():
        link = links.get(name) if isinstance(name, str) else None
        if link is None or not isinstance(places, Mapping):
            problems.append(f"local: expected {{link: {{point: (along, left)}}}} with one of the "
                            f"links {quoted(links)}, got {describe(name)}")
            continue
        merged = dict(new_links[name].local or {})
        by_sides = dict(new_links[name].sides or {})
        for p, xy in places.items():
            if p not in link.points[2:]:
                problems.append(f"local.{name}: expected one of the link's points after its first "
                                f"two ({quoted(link.points[2:])}), got {describe(p)}")
            elif not (isinstance(xy, (tuple, list)) and len(xy) == 2 and all(map(is_real, xy))):
                problems.append(f"local.{name}.{p}: expected (along, left), two finite numbers, "
                                f"got {describe(xy)}")
            else:
                merged[p] = (float(xy[0]), float(xy[1]))
                by_sides.pop(p, None)          # a place given one way: now by local
        new_links[name] = dataclasses.replace(new_links[name], local=merged, sides=by_sides or None)
    new_joints = dict(joints)
    for name, v in (offsets or {}).items():
        j = joints.get(name) if isinstance(name, str) else None
        if j is None or j.type != "P":
            sliding = [n for n, jt in joints.items() if jt.type == "P"]
            problems.append(f"offsets: expected one of the prismatic joints {quoted(sliding)}, got "
                            f"{describe(name)}" if sliding else
                            f"offsets: '{m.name}' has no prismatic joint, got {describe(name)}")
        elif not is_real(v) or length_problem(float(v), positive=False):
            problems.append(f"offsets.{name}: expected a finite number at most 1e9 m in size, "
                            f"got {describe(v)}")
        else:
            new_joints[name] = dataclasses.replace(j, offset=float(v))
    for name, xy in (pivots or {}).items():
        if name not in ground.points:
            problems.append(f"pivots: expected one of the ground's points {quoted(ground.points)}, "
                            f"got {describe(name)}")
        elif not (isinstance(xy, (tuple, list, np.ndarray)) and len(xy) == 2
                  and all(map(is_real, xy))):
            problems.append(f"pivots.{name}: expected (x, y), two finite numbers, got {describe(xy)}")
        else:
            moved[name] = (float(xy[0]), float(xy[1]))
    if ground.length is not None and len(ground.points) >= 2 and ground.name not in (lengths or {}):
        a, b = (np.array(moved.get(p, m.point(p).xy)) for p in ground.points[:2])
        new_links[ground.name] = dataclasses.replace(new_links[ground.name],
                                                     length=float(np.hypot(*(b - a))))
    if problems:
        raise ModelError(problems)
    target = dataclasses.replace(m, links=tuple(new_links[link.name] for link in m.links),
                                 joints=tuple(new_joints[j.name] for j in m.joints))
    return target, moved or None


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
    if isinstance(J, np.ndarray):
        dx, *_ = np.linalg.lstsq(J, b, rcond=None)
        return dx
    from scipy.sparse.linalg import lsqr
    return lsqr(J, b, atol=1e-15, btol=1e-15, iter_lim=20 * J.shape[1])[0]


@functools.lru_cache(maxsize=64)
def _decomposition(key):
    m = key.m
    return decompose(m)


class _Structure:
    """A mechanism's structure, hashable: links, their points, joints and inputs (the
    decomposition depends on nothing else, so that an edited model reuses it)."""

    def __init__(self, m: Mechanism):
        self.m = m
        self.key = (tuple((lk.name, lk.points, lk.ground) for lk in m.links),
                    tuple((j.name, j.type, j.links, j.point, j.origin, j.axis is not None)
                          for j in m.joints),
                    tuple((i.joint, i.links) for i in m.inputs))

    def __hash__(self):
        return hash(self.key)

    def __eq__(self, other):
        return isinstance(other, _Structure) and self.key == other.key


class _Constraints:
    """The constraints of a sketch, in the coordinates of its points that may move, along
    the homotopy of its dimensions from the sketch's (t = 0) to the declared ones (t = 1).

    Rows: a link's distance between its first two points; the place of each other point
    in the link's frame (two rows, linear in the points); a prismatic joint's point on its
    guide's line, and a slider's angle to its guide; each input's value.  The first two
    kinds are evaluated for all links at once; the others, few, one by one.
    """

    def __init__(self, m: Mechanism, units: Units = Units(), pivots=None):
        self.m = m
        self.units = units
        names = [p.name for p in m.points]
        self.index = {n: i for i, n in enumerate(names)}
        self.sketch = np.array([[p.x, p.y] for p in m.points], float).reshape(-1, 2)
        ground = set(m.ground.points)
        free = np.array([n not in ground for n in names], bool)
        self.free_points = np.flatnonzero(free)
        self.fixed_points = np.flatnonzero(~free)
        self.column = np.full(len(names), -1, np.int64)
        self.column[self.free_points] = 2 * np.arange(len(self.free_points))
        self.x0 = self.sketch[self.free_points].ravel().copy()
        self.frames = Frames(m)
        problems = []
        target = self.sketch.copy()
        if pivots is not None and not isinstance(pivots, Mapping):
            raise ModelError(f"pivots: expected a mapping of the ground's points to (x, y), got "
                             f"{describe(pivots)}")
        for name, xy in (pivots or {}).items():
            if name not in ground:
                problems.append(f"pivots: expected one of the ground's points "
                                f"{quoted(m.ground.points)}, got {describe(name)}")
            elif not (isinstance(xy, (tuple, list, np.ndarray)) and len(xy) == 2
                      and all(is_real(c) and not length_problem(float(c), positive=False)
                              for c in xy)):
                problems.append(f"pivots.{name}: expected (x, y), two finite numbers (m), got "
                                f"{describe(xy)}")
            else:
                target[self.index[name]] = xy
        self.fixed = (self.sketch[self.fixed_points].copy(), target[self.fixed_points].copy())
        both = np.concatenate([self.sketch, target])
        self.scale = float(max(np.ptp(both[:, 0]), np.ptp(both[:, 1]), 1e-300))
        xy = {n: self.sketch[i] for n, i in self.index.items()}
        dist, frame, self.special = [], [], []
        drawn_places = []
        for link in m.links:
            pts = link.points
            if link.ground:
                if link.length is not None:
                    d = math.dist(target[self.index[pts[0]]], target[self.index[pts[1]]])
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
            dist.append((self.index[a], self.index[b], L, float(np.hypot(*d_ab)), link.name))
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
                # its place as drawn, and whether the place is given (else it keeps its
                # place relative to the first two points when their distance changes)
                r = xy[p] - xy[a]
                drawn_places.append((float(r @ d_ab) / float(np.hypot(*d_ab)),
                                     _cross(d_ab, r) / float(np.hypot(*d_ab)), p in local))
        for j in m.joints:
            if j.type != "P" or j.axis is None or j.name not in self.frames.beta:
                continue
            g, s = (m.link(n) for n in j.links)
            origin = j.origin or g.points[0]
            u = self.frames.axis(self.sketch, j.name)
            drawn = _cross(u, xy[j.point] - xy[origin])
            offset = j.offset if j.offset is not None else drawn
            self.special.append(("line", j.name, (self.index[j.point], self.index[origin], g.name,
                                                  offset, drawn)))
            if len(s.points) >= 2 and len(g.points) >= 2:
                self.special.append(("slider", j.name, (g.name, s.name, self.frames.delta[j.name])))
        if problems:
            raise ModelError(problems, source=f"mechanism '{m.name}'")
        self.held = [self.frames.input_value(self.sketch, inp) for inp in m.inputs]
        self.kinds = []
        for k, inp in enumerate(m.inputs):
            if inp.joint is not None and m.joint(inp.joint).type == "P":
                j = m.joint(inp.joint)
                origin = j.origin or m.link(j.links[0]).points[0]
                self.special.append(("slide", inp.label, (self.index[j.point], self.index[origin],
                                                          j.name, self.held[k])))
                self.kinds.append("slide")
            else:
                a, b = m.joint(inp.joint).links if inp.joint is not None else inp.links
                self.special.append(("angle", inp.label, (a, b, self.held[k])))
                self.kinds.append("angle")
        self.dist = (np.array([r[0] for r in dist], np.int64), np.array([r[1] for r in dist], np.int64),
                     np.array([r[2] for r in dist], float))
        self.dist_drawn = np.array([r[3] for r in dist], float)
        self.dist_links = [r[4] for r in dist]
        self.frame = tuple(np.array([r[k] for r in frame], np.int64 if k < 3 else float).reshape(-1)
                           for k in range(5))
        self.frame_links = [(r[5], self.m.point_names[r[0]]) for r in frame]
        L_of = dict(zip(self.dist_links, self.dist[2]))
        # along and left, m, as drawn (t = 0) and declared (t = 1)
        self.places = (np.array([[a, b] for a, b, _ in drawn_places], float).reshape(-1, 2),
                       np.stack([self.frame[3], self.frame[4]], -1).reshape(-1, 2)
                       * np.array([L_of[n] for n, _ in self.frame_links]).reshape(-1, 1))
        self.place_given = np.array([g for _, _, g in drawn_places], bool)
        # what each row is, for messages: (link or joint name, width)
        self.labels = ([(r[4], 1) for r in dist] + [(r[5], 2) for r in frame]
                       + [(name, 1) for _, name, _ in self.special])
        self.n_dimension_rows = len(dist) + 2 * len(frame) + sum(
            1 for kind, _, _ in self.special if kind in ("line", "slider"))
        self.hold = bool(m.inputs)
        self._structure = _Structure(m)
        self._owner = np.array([self.dist_links.index(n) for n, _ in self.frame_links], np.int64)
        self._frame_part = None
        self._dims = {}
        # where each block of the distance and frame rows goes in the Jacobian
        n_dist = len(self.dist[2])
        base = n_dist + 2 * np.arange(len(self.frame[3]))
        ip, fa, fb = self.frame[:3]
        self._scatter = []
        for r, pts in ((np.arange(n_dist), ia_) for ia_ in self.dist[:2]):
            self._scatter.append(self._rows_of(r, pts))
        for r, pts in ((base, ip), (base, fa), (base, fb), (base + 1, ip), (base + 1, fa),
                       (base + 1, fb)):
            self._scatter.append(self._rows_of(r, pts))

    @functools.cached_property
    def _frame_flat(self):
        """Where the frame rows' entries go in a dense Jacobian (flat indices) and which of
        their twelve coefficients (x and y of the point, of the first and of the second point,
        for the x row then the y row) each one is: (flat, (coefficient, row))."""
        n = len(self.x0)
        flat, coef, row = [], [], []
        for k, (r, c, keep) in enumerate(self._scatter[2:]):
            for comp in range(2):
                flat.append(r * n + c + comp)
                coef.append(np.full(len(r), 2 * k + comp))
                row.append(np.flatnonzero(keep))
        if not flat:
            return np.zeros(0, np.int64), (np.zeros(0, np.int64), np.zeros(0, np.int64))
        return np.concatenate(flat), (np.concatenate(coef), np.concatenate(row))

    def _rows_of(self, r, points):
        c = self.column[points]
        keep = c >= 0
        return r[keep], c[keep], keep

    # -- the homotopy ------------------------------------------------------------------
    def at(self, t: float) -> dict:
        """The dimensions at t: lengths, places (lam, mu), offsets and the ground's points
        (those at the ends kept: the same object each time)."""
        if t in self._dims:
            return self._dims[t]
        dims = self._at(t)
        if t in (0.0, 1.0):
            self._dims[t] = dims
        return dims

    def _at(self, t: float) -> dict:
        L = self.dist_drawn + t * (self.dist[2] - self.dist_drawn)
        places = self.places[0] + t * (self.places[1] - self.places[0])
        Lp = L[self._owner] if len(self._owner) else np.zeros(0)
        offsets = {}
        for kind, name, data in self.special:
            if kind == "line":
                offsets[name] = data[4] + t * (data[3] - data[4])
        return {"L": L, "lam": places[:, 0] / np.where(Lp > 0, Lp, 1.0) if len(Lp) else Lp,
                "mu": places[:, 1] / np.where(Lp > 0, Lp, 1.0) if len(Lp) else Lp,
                "offsets": offsets, "fixed": self.fixed[0] + t * (self.fixed[1] - self.fixed[0])}

    # -- the points --------------------------------------------------------------------
    def all_points(self, x: np.ndarray, dims: dict | None = None) -> np.ndarray:
        P = self.sketch.copy()
        P[self.fixed_points] = self.fixed[1] if dims is None else dims["fixed"]
        P[self.free_points] = x.reshape(-1, 2)
        return P

    def points_at(self, x: np.ndarray) -> dict[str, tuple[float, float]]:
        P = self.all_points(x)
        return {n: (float(P[i, 0]), float(P[i, 1])) for n, i in self.index.items()}

    def _special(self, P, dims) -> np.ndarray:
        out = []
        f = self.frames
        for kind, name, data in self.special:
            if kind == "line":
                p, o, g, _, _ = data
                u = f.axis(P, name)
                out.append(_cross(u, P[p] - P[o]) - dims["offsets"][name])
            elif kind == "slider":
                g, s, delta = data
                out.append(_cross(rotate(f.direction(P, g), delta), f.direction(P, s)) * self.scale)
            elif kind == "angle":
                a, b, q = data
                out.append(_cross(rotate(f.direction(P, a), q), f.direction(P, b)) * self.scale)
            else:
                p, o, j, q = data
                out.append(float(f.axis(P, j) @ (P[p] - P[o])) - q)
        return np.array(out, float)

    # -- residual and Jacobian ---------------------------------------------------------
    def residual(self, x: np.ndarray, t: float = 1.0, dims: dict | None = None) -> np.ndarray:
        dims = dims or self.at(t)
        P = self.all_points(x, dims)
        ia, ib, _ = self.dist
        L = dims["L"]
        d = P[ib] - P[ia]
        r_dist = (np.einsum("ij,ij->i", d, d) - L * L) / (2 * L)
        ip, fa, fb, _, _ = self.frame
        lam, mu = dims["lam"], dims["mu"]
        e = P[fb] - P[fa]
        r_frame = P[ip] - P[fa] - lam[:, None] * e - mu[:, None] * np.stack([-e[:, 1], e[:, 0]], -1)
        return np.concatenate([r_dist, r_frame.ravel(), self._special(P, dims)])

    def jacobian(self, x: np.ndarray, t: float = 1.0, dims: dict | None = None):
        """The constraints' Jacobian with respect to the free coordinates: dense for the
        mechanisms people draw, sparse past 2000 unknowns (distance and frame rows exactly,
        linear in the points; joint and input rows through the links' directions)."""
        dims = dims or self.at(t)
        P = self.all_points(x, dims)
        ia, ib, _ = self.dist
        d = (P[ib] - P[ia]) / dims["L"][:, None]
        n_rows = len(d) + 2 * len(dims["lam"]) + len(self.special)
        if len(x) <= 2000:
            # the frame rows are linear in the points: their part is the same at every x
            if self._frame_part is None or self._frame_part[0] is not dims:
                self._frame_part = (dims, self._sparse_parts(dims, d, len(x), frames_only=True))
            J = self._frame_part[1].copy()
            (ra, ca, ka), (rb, cb, kb) = self._scatter[:2]
            J[ra, ca], J[ra, ca + 1] = -d[ka, 0], -d[ka, 1]
            J[rb, cb], J[rb, cb + 1] = d[kb, 0], d[kb, 1]
            first = n_rows - len(self.special)
            for k, (points, grads) in enumerate(self._special_gradients(P)):
                for i, g in zip(points, grads):
                    c = self.column[i]
                    if c >= 0:
                        J[first + k, c] += g[0]
                        J[first + k, c + 1] += g[1]
            return J
        rows, cols, vals = self._sparse_parts(dims, d, len(x), P=P)
        from scipy import sparse
        return sparse.csr_matrix((vals, (rows, cols)), shape=(n_rows, len(x)))

    def _sparse_parts(self, dims, d, n, *, frames_only=False, P=None):
        """(rows, cols, values) of the Jacobian (or, with ``frames_only``, the dense matrix
        of its frame rows alone)."""
        lam, mu = dims["lam"], dims["mu"]
        if frames_only:
            J = np.zeros((len(d) + 2 * len(lam) + len(self.special), n))
            flat, which = self._frame_flat
            if len(flat):
                values = np.stack([np.ones_like(lam), np.zeros_like(lam), lam - 1, -mu, -lam, mu,
                                   np.zeros_like(lam), np.ones_like(lam), mu, lam - 1, -mu, -lam])
                J.flat[flat] = values[which]
            return J
        one, zero = np.ones_like(lam), np.zeros_like(lam)
        # frame row x: p_x - a_x - lam (b_x - a_x) + mu (b_y - a_y); row y: p_y - a_y - lam e_y - mu e_x
        blocks = (-d, d, np.stack([one, zero], -1), np.stack([lam - 1, -mu], -1),
                  np.stack([-lam, mu], -1), np.stack([zero, one], -1), np.stack([mu, lam - 1], -1),
                  np.stack([-mu, -lam], -1))
        rows, cols, vals = [], [], []
        for (r, c, keep), block in zip(self._scatter, blocks):
            for comp in range(2):
                rows.append(r)
                cols.append(c + comp)
                vals.append(block[keep, comp])
        first = len(d) + 2 * len(lam)
        for k, (points, grads) in enumerate(self._special_gradients(P)):
            for i, g in zip(points, grads):
                c = self.column[i]
                if c >= 0:
                    rows.append(np.array([first + k, first + k]))
                    cols.append(np.array([c, c + 1]))
                    vals.append(np.asarray(g, float))
        return np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)

    def _special_gradients(self, P):
        """Per joint or input row: the points it depends on and d row / d point (2,)."""
        f = self.frames
        out = []
        for kind, name, data in self.special:
            if kind in ("line", "slide"):
                p, o = data[0], data[1]
                g = self.m.joint(name if kind == "line" else data[2]).links[0]
                e, grads = f.gradient(P, g)
                beta = f.beta[name if kind == "line" else data[2]]
                Rb = _rotation(beta)
                u = Rb @ e
                w = P[p] - P[o]
                # line: cross(u, w); slide: u . w
                du_w = np.array([w[1], -w[0]]) if kind == "line" else w     # d row / d u
                dw = np.array([-u[1], u[0]]) if kind == "line" else u        # d row / d w
                pts, gs = [p, o], [dw, -dw]
                for i, D in grads:
                    pts.append(i)
                    gs.append((Rb @ D).T @ du_w)
                out.append((pts, gs))
            else:
                a, b, angle = data
                ea, ga = f.gradient(P, a)
                eb, gb = f.gradient(P, b)
                Rq = _rotation(angle)
                ua = Rq @ ea
                # cross(ua, eb) * scale
                pts, gs = [], []
                for i, D in ga:
                    pts.append(i)
                    gs.append((Rq @ D).T @ np.array([eb[1], -eb[0]]) * self.scale)
                for i, D in gb:
                    pts.append(i)
                    gs.append(D.T @ np.array([-ua[1], ua[0]]) * self.scale)
                out.append((pts, gs))
        return out

    # -- continuation ------------------------------------------------------------------
    def follow(self) -> tuple[np.ndarray, bool]:
        """Continue the sketch from its own dimensions to the declared ones: (x, reached).

        A step from t to t + dt is predicted along the tangent dx/dt = -J+ dc/dt and
        corrected by Gauss-Newton at t + dt; it is taken when the corrector converges
        without moving far from the prediction and every dyad keeps its side, else tried
        again at half the size.  Steps that converge quickly double the next."""
        x = self.x0.copy()
        if not len(x):
            return x, True
        monitor = self._monitor()
        signs = monitor(x, 0.0)
        drawn = signs != 0             # a dyad drawn straight shows no side to keep

        def kept(x, t):
            return bool(np.all(monitor(x, t)[drawn] == signs[drawn]))
        t, dt, tangent = 0.0, 1.0, None
        for _ in range(_ATTEMPTS):
            if t >= 1.0:
                break
            if tangent is None:
                lo, hi = max(t - 1e-6, 0.0), min(t + 1e-6, 1.0)
                dc = (self.residual(x, hi) - self.residual(x, lo)) / (hi - lo)
                tangent = -_min_norm(self.jacobian(x, t), dc)
            t1 = min(1.0, t + dt)
            predicted = x + (t1 - t) * tangent
            corrected, ok, steps = self.correct(predicted, t1, _CORRECTOR)
            if ok:
                ok = (np.max(np.abs(corrected - predicted))
                      <= 0.5 * max(np.max(np.abs(predicted - x)), 1e-9 * self.scale)
                      and kept(corrected, t1))
            if ok:
                x, t, tangent = corrected, t1, None
                if steps <= 3:
                    dt = min(1.0, 2.0 * dt)
            else:
                dt *= 0.5
                if dt < _SHORTEST:
                    return x, False
        if t < 1.0:
            return x, False
        if not np.all(np.abs(self.residual(x, 1.0)) <= 1e3 * _TOL * self.scale):
            x, ok, _ = self.correct(x, 1.0, _POLISH, polish=True)
            if not ok:
                return x, False
        return x, kept(x, 1.0)

    def correct(self, x: np.ndarray, t: float, iterations: int, polish: bool = False):
        """Gauss-Newton towards the configuration at t nearest to the sketch:
        (x, converged, steps taken).  A corrector along the path gives up when its steps do
        not shrink; the last one (``polish``) goes on to rounding."""
        dims = self.at(t)
        anchor = self.x0
        last = math.inf
        small = (1e-12 if polish else 1e-10) * self.scale
        for k in range(iterations):
            c = self.residual(x, dims=dims)
            J = self.jacobian(x, dims=dims)
            x_new = anchor - _min_norm(J, J @ (anchor - x) + c)
            if not np.all(np.isfinite(x_new)):
                return x, False, k
            step = float(np.max(np.abs(x_new - x)))
            if step > _CONTRACTION * last and step > small:
                if not polish:
                    return x, False, k
                break
            x, last = x_new, step
            if step <= small:
                break
        c = np.abs(self.residual(x, dims=dims))
        done = bool(np.all(c <= 1e3 * _TOL * self.scale)) if polish else bool(
            np.all(c <= 1e-9 * self.scale))
        return x, done, k + 1

    def _monitor(self):
        """The sign of each dyad of the decomposition (its side of the line of its ends)."""
        dec = _decomposition(self._structure) if self.hold else None
        f = self.frames
        idx = self.index
        tests = []
        for g in (dec.groups if dec else ()):
            if g.kind == "RRR":
                X, Y, Z = (idx[p] for p in g.points)
                tests.append(lambda P, X=X, Y=Y, Z=Z: _cross(P[Z] - P[X], P[Y] - P[X]))
            elif g.kind == "RRP":
                X, Y = (idx[p] for p in g.points)
                tests.append(lambda P, X=X, Y=Y, j=g.joints[1]: float(f.axis(P, j) @ (P[Y] - P[X])))
            elif g.kind == "RPR":
                Z, X = (idx[p] for p in g.points)
                tests.append(lambda P, X=X, Z=Z, j=g.joints[0]: float(f.axis(P, j) @ (P[X] - P[Z])))

        def signs(x, t):
            P = self.all_points(x, self.at(t))
            return np.sign([test(P) for test in tests])
        return signs

    # -- the search over branches --------------------------------------------------------
    def closure(self):
        dec = _decomposition(self._structure) if self.hold else None
        return None if dec is None else Closure(self.m, self.frames, dec, self.scale)

    def local_coordinates(self, dims: dict) -> dict:
        """Each link's local coordinates at dimensions ``dims`` (1, n, 2): first point at 0,
        second at (length, 0), others at (along, left); the ground's, the plane's."""
        out = {}
        L_of = dict(zip(self.dist_links, dims["L"]))
        places = {}
        for (link, p), lam, mu in zip(self.frame_links, dims["lam"], dims["mu"]):
            places[(link, p)] = (lam * L_of[link], mu * L_of[link])
        for link in self.m.links:
            pts = link.points
            loc = np.zeros((len(pts), 2))
            if link.ground:
                for k, p in enumerate(pts):
                    loc[k] = dims["fixed"][list(self.fixed_points).index(self.index[p])]
            elif len(pts) >= 2:
                L = L_of.get(link.name)
                if L is None:
                    L = float(np.hypot(*(self.sketch[self.index[pts[1]]] - self.sketch[self.index[pts[0]]])))
                loc[1] = (L, 0.0)
                for k, p in enumerate(pts[2:], 2):
                    loc[k] = places[(link.name, p)]
            out[link.name] = loc[None]
        return out

    def problem(self, dims: dict):
        """(local, fixed, offsets) of the closure at dimensions ``dims``."""
        return (self.local_coordinates(dims), dims["fixed"][None],
                {n: np.array([v]) for n, v in dims["offsets"].items()})

    def close_all(self, closure):
        """The loops closed at the declared dimensions and the held inputs, on every branch."""
        return closure.solve(*self.problem(self.at(1.0)), np.array([self.held]))

    def search(self, closure, closed) -> tuple[np.ndarray, tuple[str, ...]]:
        """The configuration at the declared dimensions on the sketch's branch if it exists,
        else on the nearest other: (x, the groups that changed mode).  Raises AssemblyError
        when there is none."""
        if closure is None:
            return self._search_near(), ()
        rows = np.flatnonzero(closed.closes)
        if not len(rows):
            raise self.refusal(closure, closed)
        start = self._start_signs(closure)
        P = closed.P[rows]
        distance = np.sum((P[:, self.free_points] - self.sketch[self.free_points]) ** 2, axis=(1, 2))
        # the nearest branch: the fewest groups in another mode than the sketch's, then the
        # configuration nearest to the sketch
        known = start != 0
        changes = np.sum(closed.signs[rows][:, known] != start[known], axis=1)
        pool = np.flatnonzero(changes == changes.min())
        pick = pool[np.argmin(distance[pool])]
        row = rows[pick]
        switched = tuple(closure.dec.groups[k].label for k in np.flatnonzero(known)
                         if closed.signs[row, k] != start[k])
        found = closed.P[row][self.free_points].ravel()
        x, ok, _ = self.correct(found, 1.0, _POLISH, polish=True)
        # the closed forms are exact already: a polish that does not converge (at a singular
        # configuration, a dyad straight) leaves them as they are
        return (x if ok else found), switched

    def _start_signs(self, closure) -> np.ndarray:
        """Each group's mode at the sketch (0 where the sketch cannot tell)."""
        groups = closure.dec.groups
        signs = np.zeros(len(groups))
        dyads = [k for k, g in enumerate(groups) if g.kind in ("RRR", "RRP", "RPR")]
        values = self._monitor()(self.x0, 0.0)
        for k, v in zip(dyads, values):
            signs[k] = v
        if any(g.kind == "newton" for g in groups):
            local, fixed, offsets = self.problem(self.at(0.0))
            closed = closure.solve(local, fixed, offsets, np.array([self.held]), gaps=False)
            rows = np.flatnonzero(closed.closes)
            if len(rows):
                P = closed.P[rows]
                d = np.sum((P - self.sketch) ** 2, axis=(1, 2))
                best = rows[np.argmin(d)]
                if d.min() <= (1e-6 * self.scale) ** 2:
                    for k, g in enumerate(groups):
                        if g.kind == "newton":
                            signs[k] = closed.signs[best, k]
        return signs

    def _search_near(self) -> np.ndarray:
        """A mechanism the decomposition does not cover (no inputs, or groups it cannot
        solve): Gauss-Newton projections at the declared dimensions from the sketch and
        from seeded perturbations of it, the nearest configuration reached."""
        rng = np.random.default_rng(20240601)
        best, best_x, miss = math.inf, None, (math.inf, None)
        for k in range(_SEARCH_STARTS):
            sigma = 0.0 if k == 0 else (0.02, 0.1, 0.3)[k % 3]
            start = self.x0 + rng.normal(0.0, sigma * self.scale, self.x0.shape)
            x, ok, _ = self.correct(start, 1.0, _POLISH, polish=True)
            if ok:
                d = float(np.sum((x - self.x0) ** 2))
                if d < best:
                    best, best_x = d, x
            elif np.all(np.isfinite(x)):
                r = float(np.max(np.abs(self.residual(x))))
                if r < miss[0]:
                    miss = (r, x)
        if best_x is not None:
            return best_x
        raise self.refusal(None, None, near=miss[1] if miss[1] is not None else self.x0)

    # -- the result ----------------------------------------------------------------------
    def assembly(self, x: np.ndarray, switched: tuple[str, ...]) -> Assembly:
        m = self.m
        # a point that moved by rounding alone stays where it was drawn
        start = self.x0.reshape(-1, 2)
        still = np.max(np.abs(x.reshape(-1, 2) - start), axis=1) <= 4 * np.finfo(float).eps * self.scale
        x = np.where(still[:, None], start, x.reshape(-1, 2)).ravel()
        points = self.points_at(x)
        moved = {n: float(math.dist(points[n], (p.x, p.y))) for n, p in
                 ((p.name, p) for p in m.points)}
        moved = {n: d for n, d in sorted(moved.items(), key=lambda kv: -kv[1])
                 if d > _MOVED * self.scale}
        P = self.all_points(x)
        joints = tuple(self.turned_axis(j, P) for j in m.joints)
        out = m._moved(tuple(Point(p.name, *points[p.name]) for p in m.points), joints)
        return Assembly(out, moved, switched)

    def turned_axis(self, j, P):
        """A prismatic joint's axis, turned with its guide from the sketch to the assembly
        (the axis is given in the sketch's frame and is fixed in the guide)."""
        if j.type != "P" or j.axis is None or len(j.axis) != 2:
            return j
        g = j.links[0]
        before = self.frames.direction(self.sketch, g)
        after = self.frames.direction(P, g)
        turn = math.atan2(_cross(before, after), float(before @ after))
        if turn == 0.0:
            return j
        axis = rotate(np.asarray(j.axis, float), turn)
        return dataclasses.replace(j, axis=(float(axis[0]), float(axis[1])))

    # -- what a failure says -------------------------------------------------------------
    def worst(self, x: np.ndarray) -> tuple[str, float]:
        """(link or joint, residual) of the dimension missed the most (inputs aside)."""
        r = np.abs(self.residual(x))
        row, best, name = 0, 0.0, ""
        for label, width in self.labels:
            if row >= self.n_dimension_rows:
                break
            v = float(np.max(r[row:row + width]))
            if v > best:
                best, name = v, label
            row += width
        return name, best

    def length(self, v: float, unit: bool = True) -> str:
        """A length for a message, in the units the model is written in."""
        return f"{self.units.convert(v, 'm'):.6g}" + (f" {self.units.length}" if unit else "")

    def refusal(self, closure, closed, near=None) -> AssemblyError:
        from kinelab.kinematics._refusal import refusal
        return refusal(self, closure, closed, near)


def _rotation(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s], [s, c]])


def _cross(a, b) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


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
            axis = rotate(np.asarray(j.axis, float), turn)
            j = dataclasses.replace(j, axis=(float(axis[0]), float(axis[1])))
        joints.append(j)
    return dataclasses.replace(mechanism, points=points, joints=tuple(joints))
