"""Closing a mechanism's loops at given inputs with given dimensions, on every branch.

Assembly (``_assemble``) needs what the analysis engine cannot give it: the engine's plan is
compiled from an assembled sketch, and here the sketch is not yet assembled at the
dimensions asked for.  So this module decomposes the linkage itself, from its structure
alone (which links, points, joints and inputs), into the same kinds of groups as the
engine (Assur groups: a link turned by an input or locked by a slide, a link placed on a
known point, the dyads RRR, RRP, RPR and PRP in closed form, and larger groups by
Newton-Raphson), and closes them for a batch of inputs and dimensions at once:

- on *every* branch: each dyad splits a configuration into its two assembly modes, each
  Newton group into the distinct solutions found from a fixed set of starts;
- with the *gap* of every configuration that does not close: the least distance by which
  the first group that fails misses, over all the configurations of the groups before it.
  For a dyad it is closed form (an RRR dyad X-Y-Z with links b, c misses by the distance
  of |XZ| outside [|b - c|, b + c]); a Newton group is cut open at its first revolute
  joint between two of its own links and misses by the least distance between the two
  ends of that joint, over every configuration of the opened group (found from the same
  fixed starts: the same in every run).

Conventions (those of the model): the ground is the frame, angle 0; a link's angle is the
direction from its first point to its second; a link with one point has the direction of
the axis of the prismatic joint it slides in (fixed in that joint's guide); an angle input
on joint (a, b) is ``theta_b - theta_a``; a slide is ``u . (point - origin)``.

Every link has its *local* coordinates: its first point at (0, 0), its second at
(length, 0), its other points at (along, left); the ground's are the plane's.
"""
from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from kinelab.kinematics._geometry import sketch_angle
from kinelab.model import Mechanism

__all__ = ["Group", "Decomposition", "decompose", "Frames", "Closure", "Closed", "SCAN_STARTS"]

SIGNED = ("RRR", "RRP", "RPR", "newton")   # groups with more than one assembly mode
_STARTS = 24            # Newton groups: starts per configuration (the first is the given one)
SCAN_STARTS = 6         # ... when scanning many inputs or dimensions
_CUT_STARTS = 8         # ... when measuring the gap of a group that does not close
_NEWTON_ITERATIONS = 25
_SCAN_ITERATIONS = 16
_CHECK = 1e-9           # relative to the size: a redundant joint closes to within this


# -- the frames of the links ------------------------------------------------------------------
class Frames:
    """Each link's direction at a configuration, from the places of its points.

    A link with two points or more: the unit vector from its first point to its second;
    the ground: +x; a moving link with one point: its prismatic joint's axis, turned with
    that joint's other link.  The constant angles are read off the start configuration
    ``m`` (the model's sketch): ``theta0`` of every link (the ground's 0), and of every
    prismatic joint its axis ``beta`` and its slider's angle ``delta``, both relative to
    its guide.
    """

    def __init__(self, m: Mechanism):
        self.m = m
        self.names = m.link_names
        self.index = {n: i for i, n in enumerate(self.names)}
        self.points = {n: i for i, n in enumerate(m.point_names)}
        ground = m.ground.name
        self.theta0 = {n: 0.0 if n == ground else sketch_angle(m, n) for n in self.names}
        self.beta, self.delta = {}, {}
        for j in m.joints:
            if j.type == "P" and j.axis is not None and len(j.axis) == 2:
                g, s = j.links
                self.beta[j.name] = math.atan2(j.axis[1], j.axis[0]) - self.theta0[g]
                self.delta[j.name] = self.theta0[s] - self.theta0[g]
        # how each link's direction follows from the points: ("ground",), ("points", a, b)
        # or ("joint", other link, angle from it)
        self.rule = {}
        for link in m.links:
            if link.ground:
                self.rule[link.name] = ("ground",)
            elif len(link.points) >= 2:
                self.rule[link.name] = ("points", self.points[link.points[0]],
                                        self.points[link.points[1]])
            else:
                prismatic = sorted((j for j in m.joints_of(link.name)
                                    if j.type == "P" and j.name in self.beta),
                                   key=lambda j: j.links[1] != link.name)
                if prismatic:
                    j = prismatic[0]
                    other = j.links[0] if j.links[1] == link.name else j.links[1]
                    turn = self.theta0[link.name] - self.theta0[other]
                    self.rule[link.name] = ("joint", other, turn)
                else:
                    self.rule[link.name] = ("fixed", self.theta0[link.name])

    def direction(self, P: np.ndarray, link: str, depth: int = 0) -> np.ndarray:
        """The unit direction of ``link`` with its points at ``P`` (..., n_points, 2)."""
        rule = self.rule[link]
        if rule[0] == "points":
            d = P[..., rule[2], :] - P[..., rule[1], :]
            return d / np.hypot(d[..., 0], d[..., 1])[..., None]
        if rule[0] == "joint" and depth <= len(self.names):
            return rotate(self.direction(P, rule[1], depth + 1), rule[2])
        angle = 0.0 if rule[0] == "ground" else rule[1] if rule[0] == "fixed" else self.theta0[link]
        e = np.array([math.cos(angle), math.sin(angle)])
        return e if P.ndim == 2 else np.broadcast_to(e, P.shape[:-2] + (2,))

    def gradient(self, P: np.ndarray, link: str, depth: int = 0):
        """(e, [(point, de/dP_point)]): a link's direction at P (n_points, 2) and its
        derivative with respect to the places of the points it depends on (2 x 2 each)."""
        rule = self.rule[link]
        if rule[0] == "points":
            d = P[rule[2]] - P[rule[1]]
            n = math.hypot(d[0], d[1])
            e = d / n
            D = (np.eye(2) - np.outer(e, e)) / n
            return e, [(rule[2], D), (rule[1], -D)]
        if rule[0] == "joint" and depth <= len(self.names):
            e, grads = self.gradient(P, rule[1], depth + 1)
            c, s = math.cos(rule[2]), math.sin(rule[2])
            Rm = np.array([[c, -s], [s, c]])
            return Rm @ e, [(i, Rm @ D) for i, D in grads]
        return np.array(self.direction(P, link), float), []

    def dependencies(self, link: str, depth: int = 0) -> set[int]:
        """The points a link's direction depends on."""
        rule = self.rule[link]
        if rule[0] == "points":
            return {rule[1], rule[2]}
        if rule[0] == "joint" and depth <= len(self.names):
            return self.dependencies(rule[1], depth + 1)
        return set()

    def axis(self, P: np.ndarray, joint: str) -> np.ndarray:
        """A prismatic joint's axis in the plane (unit), turned with its guide."""
        g = self.m.joint(joint).links[0]
        return rotate(self.direction(P, g), self.beta[joint])

    def input_value(self, P: np.ndarray, inp) -> float:
        """An input's value at the configuration P (rad or m)."""
        if inp.joint is not None and self.m.joint(inp.joint).type == "P":
            j = self.m.joint(inp.joint)
            origin = j.origin or self.m.link(j.links[0]).points[0]
            u = self.axis(P, j.name)
            return float(u @ (P[self.points[j.point]] - P[self.points[origin]]))
        a, b = self.m.joint(inp.joint).links if inp.joint is not None else inp.links
        ea, eb = self.direction(P, a), self.direction(P, b)
        return math.atan2(float(ea[0] * eb[1] - ea[1] * eb[0]), float(ea @ eb))


def rotate(v: np.ndarray, angle) -> np.ndarray:
    """v (..., 2) turned by ``angle`` (a scalar or an array broadcasting with v[..., 0])."""
    if np.ndim(v) == 1 and np.ndim(angle) == 0:
        c, s = math.cos(angle), math.sin(angle)
        return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


# -- the decomposition ------------------------------------------------------------------------
@dataclass(frozen=True)
class Group:
    """One step of the decomposition.

    ``kind``: "drive" (a link turned by an input), "lock" (a link keeping its angle to
    another across a slide), "place" (a link of known direction on a known point), "two"
    (a link through two known points), "slide" (a link placed by a driven slide), "lines"
    (a link on two slides), "RRR", "RRP", "RPR", "PRP" (dyads) and "newton" (a larger
    group).  ``points`` are the group's joint points in order (X-Y-Z of an RRR).
    """

    kind: str
    links: tuple[str, ...]
    joints: tuple[str, ...] = ()
    points: tuple[str, ...] = ()
    data: tuple = ()

    @property
    def label(self) -> str:
        if self.kind in ("RRR", "RRP", "RPR", "PRP"):
            return (f"the dyad {' and '.join(repr(n) for n in self.links)} "
                    f"({'-'.join(self.points)})")
        if self.kind == "newton":
            return f"the group {', '.join(repr(n) for n in self.links)}"
        return f"'{self.links[0]}'"


@dataclass(frozen=True)
class Decomposition:
    """The groups of a mechanism in the order they are solved, and the joints and inputs
    none of them needs (redundant: checked once everything is placed)."""

    groups: tuple[Group, ...]
    redundant_joints: tuple[str, ...]
    redundant_inputs: tuple[int, ...]

    @property
    def signed(self) -> tuple[int, ...]:
        """Indices of the groups that have assembly modes (a sign, or a Newton solution)."""
        return tuple(k for k, g in enumerate(self.groups) if g.kind in SIGNED)


def decompose(m: Mechanism) -> Decomposition | None:
    """The groups that close ``m`` at its inputs, found from its structure alone; None
    when it has no inputs, joints other than R and P, or links its inputs do not fix."""
    if not m.inputs or any(j.type not in ("R", "P") for j in m.joints):
        return None
    if any(j.type == "P" and (j.axis is None or len(j.axis) != 2 or j.point is None)
           for j in m.joints) or any(j.type == "R" and j.point is None for j in m.joints):
        return None
    return _Decomposer(m).run()


class _Decomposer:
    def __init__(self, m: Mechanism):
        self.m = m
        ground = m.ground.name
        self.placed = {ground}
        self.directed = {ground}
        self.known = set(m.ground.points)
        self.used_joints: set[str] = set()
        self.used_inputs: set[int] = set()
        self.groups: list[Group] = []
        self.prismatic = [j for j in m.joints if j.type == "P"]
        self.revolute = [j for j in m.joints if j.type == "R"]
        self.driven_slides = {}
        self.angle_inputs = []
        for k, inp in enumerate(m.inputs):
            if inp.joint is not None and m.joint(inp.joint).type == "P":
                self.driven_slides[inp.joint] = k
            else:
                a, b = m.joint(inp.joint).links if inp.joint is not None else inp.links
                self.angle_inputs.append((k, a, b))

    def run(self) -> Decomposition | None:
        names = self.m.link_names
        while len(self.placed) < len(names):
            if self._angles() or self._place() or self._dyad():
                continue
            if not self._newton():
                return None
        joints = tuple(j.name for j in self.m.joints if j.name not in self.used_joints)
        inputs = tuple(k for k in range(len(self.m.inputs)) if k not in self.used_inputs)
        return Decomposition(tuple(self.groups), joints, inputs)

    def other(self, j, link):
        return j.links[1] if j.links[0] == link else j.links[0]

    def known_points(self, link):
        return [p for p in self.m.link(link).points if p in self.known]

    def _add(self, group: Group, placed=(), directed=()):
        self.groups.append(group)
        self.used_joints.update(group.joints)
        for n in directed:
            self.directed.add(n)
        for n in placed:
            self.placed.add(n)
            self.directed.add(n)
            self.known.update(self.m.link(n).points)

    def _angles(self) -> bool:
        for k, a, b in self.angle_inputs:
            if k in self.used_inputs:
                continue
            for known, other, sign in ((a, b, 1.0), (b, a, -1.0)):
                if known in self.directed and other not in self.directed:
                    self.used_inputs.add(k)
                    self._add(Group("drive", (other,), (), (), (known, k, sign)), directed=(other,))
                    return True
        for j in self.prismatic:
            if j.name in self.used_joints:
                continue
            g, s = j.links
            for known, other in ((g, s), (s, g)):
                if known in self.directed and other not in self.directed:
                    # the joint's angle part only: its line is still to be closed
                    self._add(Group("lock", (other,), (), (), (known, j.name)), directed=(other,))
                    return True
        return False

    def _place(self) -> bool:
        for link in self.m.link_names:
            if link in self.placed:
                continue
            pts = self.known_points(link)
            if link in self.directed and pts:
                self._add(Group("place", (link,), (), (pts[0],)), placed=(link,))
                return True
            if len(pts) >= 2:
                self._add(Group("two", (link,), (), tuple(pts[:2])), placed=(link,))
                return True
            if link not in self.directed:
                continue
            for j in self.prismatic:
                if (j.name in self.used_joints or link not in j.links
                        or j.name not in self.driven_slides):
                    continue
                partner = self.other(j, link)
                if partner in self.placed:
                    self.used_inputs.add(self.driven_slides[j.name])
                    self._add(Group("slide", (link,), (j.name,), (),
                                    (self.driven_slides[j.name],)), placed=(link,))
                    return True
            lines = [j for j in self.prismatic if j.name not in self.used_joints
                     and link in j.links and self.other(j, link) in self.placed]
            if len(lines) >= 2:
                self._add(Group("lines", (link,), (lines[0].name, lines[1].name),
                                (self.m.link(link).points[0],)), placed=(link,))
                return True
        return False

    def _line_of(self, link, point):
        """A prismatic joint that puts ``point`` of ``link`` (known direction) on a line of a
        placed link."""
        for j in self.prismatic:
            if (j.name not in self.used_joints and link in j.links
                    and self.other(j, link) in self.placed and j.name not in self.driven_slides):
                return j
        return None

    def _dyad(self) -> bool:
        for j in self.revolute:
            if j.name in self.used_joints or j.point in self.known:
                continue
            b, c = j.links
            if b in self.placed or c in self.placed:
                continue
            Y = j.point
            for b, c in ((b, c), (c, b)):
                xb, xc = self.known_points(b), self.known_points(c)
                if b not in self.directed and c not in self.directed and xb and xc:
                    self._add(Group("RRR", (b, c), (j.name,), (xb[0], Y, xc[0])), placed=(b, c))
                    return True
                if b not in self.directed and c in self.directed and xb:
                    jp = self._line_of(c, Y)
                    if jp is not None:
                        self._add(Group("RRP", (b, c), (j.name, jp.name), (xb[0], Y)),
                                  placed=(b, c))
                        return True
            b, c = j.links
            if b in self.directed and c in self.directed:
                jb, jc = self._line_of(b, Y), self._line_of(c, Y)
                if jb is not None and jc is not None and jb is not jc:
                    self._add(Group("PRP", (b, c), (j.name, jb.name, jc.name), (Y,)),
                              placed=(b, c))
                    return True
        for j in self.prismatic:
            if j.name in self.used_joints or j.name in self.driven_slides:
                continue
            G, S = j.links
            if G in self.directed or S in self.directed:
                continue
            zg, xs = self.known_points(G), self.known_points(S)
            if zg and xs:
                self._add(Group("RPR", (G, S), (j.name,), (zg[0], xs[0])), placed=(G, S))
                return True
        return False

    def _equations(self, group: set[str]):
        """The joints and inputs that bind ``group`` (the rest placed or directed), and how
        many equations they give."""
        joints, inputs, count = [], [], 0
        ok = group | self.placed
        for j in self.m.joints:
            if j.name in self.used_joints or not (set(j.links) & group):
                continue
            if not set(j.links) <= ok:
                continue
            joints.append(j.name)
            count += 3 if j.name in self.driven_slides else 2
        for k, a, b in self.angle_inputs:
            # an input whose link is in the group counts, even when it turned that link
            # already (its angle is an unknown of the group again)
            again = k in self.used_inputs and bool({a, b} & group)
            if (k in self.used_inputs and not again) or not ({a, b} & group):
                continue
            if {a, b} <= (group | self.directed):
                inputs.append(k)
                count += 1
        return joints, inputs, count

    def _newton(self) -> bool:
        free = [n for n in self.m.link_names if n not in self.placed]
        around = {n: {self.other(j, n) for j in self.m.joints_of(n)} & set(free) for n in free}
        for size in range(1, len(free) + 1):
            if size > 6 and size < len(free):
                continue
            for combo in itertools.combinations(free, size):
                group = set(combo)
                if not _connected(group, around):
                    continue
                joints, inputs, count = self._equations(group)
                if count == 3 * size:
                    for k in inputs:
                        self.used_inputs.add(k)
                    self.used_joints.update(joints)
                    for j in joints:
                        if j in self.driven_slides:
                            self.used_inputs.add(self.driven_slides[j])
                    self._add(Group("newton", combo, tuple(joints), (), (tuple(inputs),)),
                              placed=combo)
                    return True
        return False


def _connected(group: set[str], around: dict[str, set[str]]) -> bool:
    start = next(iter(group))
    seen, todo = {start}, [start]
    while todo:
        for x in around[todo.pop()] & group:
            if x not in seen:
                seen.add(x)
                todo.append(x)
    return seen == group


# -- closing the groups -------------------------------------------------------------------------
# Inside, points and directions are complex numbers x + iy: a link's direction e is a unit
# complex number, a local place v goes to the plane as e v, and a turn by an angle is a
# product with exp(i angle).


@dataclass
class Closed:
    """Configurations of a batch of B problems (inputs and dimensions), R >= B rows.

    Attributes
    ----------
    P : (R, n_points, 2)   the points (not to be used past the group that failed)
    src : (R,)             the problem each row belongs to
    signs : (R, n_groups)  each group's assembly mode (+1 or -1 for a dyad, the sign of
                           det J of the solution for a Newton group; 0 where there is none)
    gap : (R,)             by how much the row misses (0: it closes), m
    failed : (R,)          the group that failed first (-1: none; n_groups: a redundant joint)
    detail : dict          what each dyad measured, per row (for messages)
    """

    P: np.ndarray
    src: np.ndarray
    signs: np.ndarray
    gap: np.ndarray
    failed: np.ndarray
    detail: dict

    @property
    def closes(self) -> np.ndarray:
        return self.failed < 0

    def per_problem(self, B: int) -> tuple[np.ndarray, np.ndarray]:
        """(closes, gap) of each problem: whether some row closes, and the least gap."""
        gap = np.full(B, np.inf)
        np.minimum.at(gap, self.src, np.where(self.closes, 0.0, self.gap))
        return gap == 0.0, gap


class Closure:
    """A decomposition with the mechanism's constant geometry, ready to close batches.

    ``local`` maps each link to its local coordinates (B or 1, n_points_of_link, 2);
    ``fixed`` holds the ground's points (B or 1, n_ground, 2), in the order of the model's
    points; ``offsets`` each prismatic joint's offset (B or 1,); ``q`` the inputs (B or 1, M).
    A batch of one broadcasts against the others.
    """

    def __init__(self, m: Mechanism, frames: Frames, decomposition: Decomposition,
                 scale: float):
        self.m = m
        self.frames = frames
        self.dec = decomposition
        self.scale = scale
        self.pi = frames.points
        self.li = frames.index
        self.slot = {link.name: {p: k for k, p in enumerate(link.points)} for link in m.links}
        self.origin = {j.name: (j.origin or m.link(j.links[0]).points[0])
                       for j in m.joints if j.type == "P"}
        self.ground = m.ground.name
        self.axis = {j: np.exp(1j * b) for j, b in frames.beta.items()}
        self.turn = {j: np.exp(1j * d) for j, d in frames.delta.items()}
        self.driven = {inp.joint: k for k, inp in enumerate(m.inputs)
                       if inp.joint is not None and m.joint(inp.joint).type == "P"}
        # closed forms only: a configuration that is not found does not exist
        self.exact = all(g.kind != "newton" for g in decomposition.groups)

    def solve(self, local, fixed, offsets, q, *, signs=None, starts=_STARTS,
              gaps=True) -> Closed:
        """Close every group for each problem of the batch, on every branch (or, with
        ``signs`` (n_groups,), on that one: 0 lets a group take both).  ``starts``: the
        starts of each Newton group; ``gaps``: whether a Newton group that finds no
        solution measures its gap (else it is infinite)."""
        local = {n: _complex(v) for n, v in local.items()}
        fixed = _complex(fixed)
        offsets = {n: np.asarray(v, float) for n, v in offsets.items()}
        q = np.asarray(q, float)
        B = max([len(q), len(fixed)] + [len(v) for v in local.values()]
                + [len(v) for v in offsets.values()])
        src = np.arange(B)
        P = np.full((B, len(self.pi)), np.nan + 0j)
        E = np.full((B, len(self.li)), np.nan + 0j)
        P[:, sorted(self.pi[p] for p in self.m.ground.points)] = fixed      # the model's order
        E[:, self.li[self.ground]] = 1.0
        st = _State(self, P, E, src, len(self.dec.groups), local, offsets, q)
        for k, group in enumerate(self.dec.groups):
            getattr(self, "_" + group.kind.lower())(
                st, k, group, None if signs is None else signs[k], starts=starts, gaps=gaps)
        self._redundant(st)
        return Closed(np.stack([st.P.real, st.P.imag], -1), st.src, st.signs, st.gap,
                      st.failed, st.detail)

    # -- helpers -------------------------------------------------------------------------
    def loc(self, st, link, point):
        return _take(st.local[link], st.src)[:, self.slot[link][point]]

    def place(self, st, k, link, point, e):
        """Place ``link`` with direction e (R,) through its known ``point``."""
        st.E[:, self.li[link]] = e
        L = _take(st.local[link], st.src)
        O = st.P[:, self.pi[point]] - e * L[:, self.slot[link][point]]
        for p, s in self.slot[link].items():
            if p == point:
                continue
            xy = O + e * L[:, s]
            i = self.pi[p]
            if st.known[i]:
                miss = np.abs(xy - st.P[:, i])
                st.fail(k, miss > _CHECK * self.scale, miss)
            else:
                st.P[:, i] = xy
        for p in self.slot[link]:
            st.known[self.pi[p]] = True

    def line(self, st, j, link, point):
        """(n, h): prismatic joint j puts ``point`` of ``link`` (direction known, not
        placed) on the line Re(conj(n) Y) = h of its placed partner."""
        jt = self.m.joint(j)
        g, s = jt.links
        n = 1j * st.E[:, self.li[g]] * self.axis[j]
        offset = _take(st.offsets[j], st.src)
        e = st.E[:, self.li[link]]
        if link == s:        # the slider: its point p is Y + e (p - Y)
            w = e * (self.loc(st, s, jt.point) - self.loc(st, s, point))
            o = st.P[:, self.pi[self.origin[j]]]
            return n, offset + _dot(n, o) - _dot(n, w)
        # the guide: its origin o is Y + e (o - Y); the slider's point p is placed
        w = e * (self.loc(st, g, self.origin[j]) - self.loc(st, g, point))
        return n, _dot(n, st.P[:, self.pi[jt.point]]) - offset - _dot(n, w)

    # -- the groups -------------------------------------------------------------------------
    def _drive(self, st, k, group, sign, **_):
        known, m_in, s = group.data
        q = _take(st.q, st.src)[:, m_in]
        st.E[:, self.li[group.links[0]]] = st.E[:, self.li[known]] * np.exp(1j * s * q)

    def _lock(self, st, k, group, sign, **_):
        known, j = group.data
        g = self.m.joint(j).links[0]
        t = self.turn[j] if known == g else np.conj(self.turn[j])
        st.E[:, self.li[group.links[0]]] = st.E[:, self.li[known]] * t

    def _place(self, st, k, group, sign, **_):
        link = group.links[0]
        self.place(st, k, link, group.points[0], st.E[:, self.li[link]])

    def _two(self, st, k, group, sign, **_):
        link = group.links[0]
        p1, p2 = group.points
        v = st.P[:, self.pi[p2]] - st.P[:, self.pi[p1]]
        w = self.loc(st, link, p2) - self.loc(st, link, p1)
        miss = np.abs(np.abs(v) - np.abs(w))
        st.fail(k, miss > _CHECK * self.scale, miss)
        self.place(st, k, link, p1, _unit_of(v * np.conj(w)))

    def _slide(self, st, k, group, sign, **_):
        link = group.links[0]
        j = group.joints[0]
        jt = self.m.joint(j)
        g, s = jt.links
        u = st.E[:, self.li[g]] * self.axis[j]
        along = _take(st.q, st.src)[:, group.data[0]] + 1j * _take(st.offsets[j], st.src)
        if link == s:
            st.P[:, self.pi[jt.point]] = st.P[:, self.pi[self.origin[j]]] + along * u
            st.known[self.pi[jt.point]] = True
            self.place(st, k, s, jt.point, st.E[:, self.li[s]])
        else:
            st.P[:, self.pi[self.origin[j]]] = st.P[:, self.pi[jt.point]] - along * u
            st.known[self.pi[self.origin[j]]] = True
            self.place(st, k, g, self.origin[j], st.E[:, self.li[g]])

    def _lines(self, st, k, group, sign, **_):
        link, Y = group.links[0], group.points[0]
        n1, h1 = self.line(st, group.joints[0], link, Y)
        n2, h2 = self.line(st, group.joints[1], link, Y)
        self._meet(st, k, n1, h1, n2, h2, Y)
        self.place(st, k, link, Y, st.E[:, self.li[link]])

    def _prp(self, st, k, group, sign, **_):
        b, c = group.links
        Y = group.points[0]
        n1, h1 = self.line(st, group.joints[1], b, Y)
        n2, h2 = self.line(st, group.joints[2], c, Y)
        self._meet(st, k, n1, h1, n2, h2, Y)
        self.place(st, k, b, Y, st.E[:, self.li[b]])
        self.place(st, k, c, Y, st.E[:, self.li[c]])

    def _meet(self, st, k, n1, h1, n2, h2, Y):
        """The point on both lines; parallel lines miss by the distance between them (or
        meet along a line, not at one point)."""
        det = _cross(n1, n2)
        parallel = np.abs(det) <= 1e-12
        safe = np.where(parallel, 1.0, det)
        xy = ((h1 * n2.imag - h2 * n1.imag) + 1j * (n1.real * h2 - n2.real * h1)) / safe
        st.fail(k, parallel, np.abs(h1 - np.sign(_dot(n1, n2)) * h2))
        st.P[:, self.pi[Y]] = xy
        st.known[self.pi[Y]] = True

    def _rrr(self, st, k, group, sign, **_):
        b, c = group.links
        X, Y, Z = group.points
        rb = np.abs(self.loc(st, b, Y) - self.loc(st, b, X))
        rc = np.abs(self.loc(st, c, Y) - self.loc(st, c, Z))
        PX, PZ = st.P[:, self.pi[X]], st.P[:, self.pi[Z]]
        D = np.abs(PZ - PX)
        gap = np.maximum(np.maximum(D - (rb + rc), np.abs(rb - rc) - D), 0.0)
        st.note(k, D=D, lo=np.abs(rb - rc), hi=rb + rc)
        st.fail(k, (gap > 0) | (D == 0), gap)
        e = _unit_of(PZ - PX)
        a = (rb * rb - rc * rc + D * D) / (2 * np.where(D > 0, D, 1.0))
        h = np.sqrt(np.maximum(rb * rb - a * a, 0.0))
        sig = st.split(k, sign)
        PX, PZ, e, a, h = st.follow(PX, PZ, e, a, h)
        PY = PX + e * (a + 1j * sig * h)
        st.P[:, self.pi[Y]] = PY
        st.known[self.pi[Y]] = True
        self.place(st, k, b, X, _unit_of((PY - PX) * np.conj(self.loc(st, b, Y) - self.loc(st, b, X))))
        self.place(st, k, c, Z, _unit_of((PY - PZ) * np.conj(self.loc(st, c, Y) - self.loc(st, c, Z))))

    def _rrp(self, st, k, group, sign, **_):
        b, c = group.links
        X, Y = group.points
        r = np.abs(self.loc(st, b, Y) - self.loc(st, b, X))
        n, h = self.line(st, group.joints[1], c, Y)
        PX = st.P[:, self.pi[X]]
        s = h - _dot(n, PX)
        gap = np.maximum(np.abs(s) - r, 0.0)
        st.note(k, D=np.abs(s), lo=np.zeros_like(r), hi=r)
        st.fail(k, gap > 0, gap)
        along = np.sqrt(np.maximum(r * r - s * s, 0.0))
        sig = st.split(k, sign)
        PX, s, n, along = st.follow(PX, s, n, along)
        PY = PX + n * (s - 1j * sig * along)          # -i n is the line's direction u
        st.P[:, self.pi[Y]] = PY
        st.known[self.pi[Y]] = True
        self.place(st, k, b, X, _unit_of((PY - PX) * np.conj(self.loc(st, b, Y) - self.loc(st, b, X))))
        self.place(st, k, c, Y, st.E[:, self.li[c]])

    def _rpr(self, st, k, group, sign, **_):
        G, S = group.links
        Z, X = group.points
        j = group.joints[0]
        jt = self.m.joint(j)
        beta = self.frames.beta[j]
        wS = (self.loc(st, S, jt.point) - self.loc(st, S, X)) * self.turn[j]
        wG = self.loc(st, G, self.origin[j]) - self.loc(st, G, Z)
        e = _take(st.offsets[j], st.src) - _cross(self.axis[j], wS - wG)
        v = st.P[:, self.pi[X]] - st.P[:, self.pi[Z]]
        D = np.abs(v)
        gap = np.maximum(np.abs(e) - D, 0.0)
        st.note(k, D=D, lo=np.abs(e), hi=np.full_like(D, np.inf))
        st.fail(k, (gap > 0) | (D == 0), gap)
        sig = st.split(k, sign)
        e, v, D = st.follow(e, v, D)
        ratio = np.clip(e / np.where(D > 0, D, 1.0), -1.0, 1.0)
        phi = beta + np.where(sig > 0, np.arcsin(ratio), math.pi - np.arcsin(ratio))
        eG = _unit_of(v) * np.exp(-1j * phi)
        self.place(st, k, G, Z, eG)
        self.place(st, k, S, X, eG * self.turn[j])

    def _newton(self, st, k, group, sign, *, starts, gaps):
        _NewtonGroup(self, group).solve(st, k, sign, starts, gaps)

    def _redundant(self, st):
        """Joints and inputs no group needed must close on their own."""
        k = len(self.dec.groups)
        for name in self.dec.redundant_joints:
            jt = self.m.joint(name)
            if jt.type != "P":
                continue
            u = st.E[:, self.li[jt.links[0]]] * self.axis[name]
            w = st.P[:, self.pi[jt.point]] - st.P[:, self.pi[self.origin[name]]]
            miss = np.abs(_cross(u, w) - _take(st.offsets[name], st.src))
            st.fail(k, miss > _CHECK * self.scale, miss)
        for m_in in self.dec.redundant_inputs:
            inp = self.m.inputs[m_in]
            q = _take(st.q, st.src)[:, m_in]
            if inp.joint in self.driven:
                jt = self.m.joint(inp.joint)
                u = st.E[:, self.li[jt.links[0]]] * self.axis[jt.name]
                w = st.P[:, self.pi[jt.point]] - st.P[:, self.pi[self.origin[jt.name]]]
                miss = np.abs(_dot(u, w) - q)
            else:
                a, b = self.m.joint(inp.joint).links if inp.joint is not None else inp.links
                miss = np.abs(np.sin(np.angle(st.E[:, self.li[b]] / st.E[:, self.li[a]]) - q)) * self.scale
            st.fail(k, miss > _CHECK * self.scale, miss)


class _State:
    """The rows of a batch being closed, group by group."""

    def __init__(self, closure, P, E, src, n_groups, local, offsets, q):
        R = len(src)
        self.P, self.E, self.src = P, E, src
        self.signs = np.zeros((R, n_groups))
        self.gap, self.failed, self.detail = np.zeros(R), np.full(R, -1), {}
        self.local, self.offsets, self.q = local, offsets, q
        self.known = np.zeros(P.shape[1], bool)
        self.known[[closure.pi[p] for p in closure.m.ground.points]] = True
        self._parent = np.arange(R)

    def fail(self, k, bad, gap):
        """Rows where group k does not close (and none before it failed) miss by ``gap``."""
        new = np.asarray(bad, bool) & (self.failed < 0)
        if new.any():
            self.failed = np.where(new, k, self.failed)
            self.gap = np.where(new, np.broadcast_to(gap, new.shape), self.gap)

    def note(self, k, **values):
        R = len(self.src)
        self.detail[k] = {n: np.broadcast_to(v, (R,)).copy() for n, v in values.items()}

    def split(self, k, sign):
        """Each row becomes two, one per assembly mode of group k (or keeps ``sign``)."""
        R = len(self.src)
        if sign is not None and sign != 0:
            self._parent = np.arange(R)
            self.signs[:, k] = sign
            return np.full(R, float(sign))
        self.expand(np.concatenate([np.arange(R), np.arange(R)]))
        sig = np.repeat([1.0, -1.0], R)
        self.signs[:, k] = sig
        return sig

    def expand(self, parent):
        self._parent = parent
        self.P, self.E, self.src = self.P[parent], self.E[parent], self.src[parent]
        self.signs, self.gap, self.failed = self.signs[parent], self.gap[parent], self.failed[parent]
        self.detail = {k: {n: v[parent] for n, v in d.items()} for k, d in self.detail.items()}

    def follow(self, *arrays):
        """Per-row arrays computed before the last split, expanded with the rows (a batch
        of one stays one)."""
        return tuple(a if np.ndim(a) == 0 or len(a) == 1 else a[self._parent] for a in arrays)


def _complex(values) -> np.ndarray:
    v = np.asarray(values, float)
    return v[..., 0] + 1j * v[..., 1]


def _take(values, src):
    """Per-problem values (B or 1, ...) for each row: those of a batch of one stay one,
    for numpy to broadcast."""
    return values[src] if len(values) > 1 else values


def _unit_of(z):
    n = np.abs(z)
    return z / np.where(n > 0, n, 1.0)


def _dot(a, b):
    return (np.conj(a) * b).real


def _cross(a, b):
    return (np.conj(a) * b).imag


# -- Newton groups ------------------------------------------------------------------------------
class _NewtonGroup:
    """A group closed by Newton-Raphson in body coordinates (each link's first point and
    angle: z = x, y, theta per link), from a fixed set of starts per row: the first from the
    model's sketch, the others with each link turned by a seeded random generator (the same
    in every run).  The Jacobian is analytic: a point O + e v of a link moves by 1, i and
    i e v with its x, y and angle."""

    def __init__(self, closure: Closure, group: Group):
        self.c = closure
        self.g = group
        self.links = list(group.links)
        self.gi = {n: i for i, n in enumerate(self.links)}
        self.joints = [closure.m.joint(j) for j in group.joints]
        self.inputs = list(group.data[0])
        self.n = 3 * len(self.links)
        self.lengthy = np.arange(self.n) % 3 < 2       # the unknowns that are lengths

    def solve(self, st, k, sign, starts, gaps):
        c = self.c
        R, n, K = len(st.src), self.n, starts
        z0 = self._starts(st, K)                                # (R, K, n)
        rows = np.repeat(np.arange(R), K)
        z, ok, det = self._iterate(st, rows, z0.reshape(R * K, n).copy(),
                                   _NEWTON_ITERATIONS if gaps else _SCAN_ITERATIONS)
        # the distinct solutions of each row, in the order of the starts
        keys = np.round(self._points(st, rows, z) / (1e-7 * c.scale))
        good = np.flatnonzero(ok)
        if sign is not None and sign != 0:
            good = good[np.sign(det[good]) == sign]
        _, first = np.unique(np.column_stack([rows[good], keys[good]]), axis=0, return_index=True)
        picked = good[np.sort(first)]
        pick_rows = rows[picked]
        failing = np.setdiff1d(np.arange(R), pick_rows)
        miss = np.full(len(failing), np.inf)
        if len(failing) and gaps:
            miss = _cut_gap(self, st, failing, z0[failing])
        st.expand(np.concatenate([pick_rows, failing]))
        st.signs[:, k] = np.concatenate([np.sign(det[picked]), np.zeros(len(failing))])
        bad = np.arange(len(st.src)) >= len(pick_rows)
        st.fail(k, bad, np.concatenate([np.zeros(len(pick_rows)), miss]))
        self._write(st, np.concatenate([z[picked], z0[failing, 0].reshape(-1, n)]))

    # -- body coordinates ---------------------------------------------------------------
    def _frames(self, st, rows, z):
        """Each link's (origin, direction, angle, column of its unknowns or -1) in rows."""
        c = self.c
        out = {}
        for name, i in self.gi.items():
            th = z[:, 3 * i + 2]
            out[name] = (z[:, 3 * i] + 1j * z[:, 3 * i + 1], np.exp(1j * th), th, 3 * i)
        return out

    def _frame(self, st, rows, frames, link):
        got = frames.get(link)
        if got is None:
            c = self.c
            e = st.E[rows, c.li[link]]
            got = frames[link] = (st.P[rows, c.pi[c.m.link(link).points[0]]], e,
                                  np.angle(e) if link != c.ground else np.zeros(len(rows)), -1)
        return got

    def _point(self, st, rows, frames, link, point):
        """(place, column, d place / d angle) of a link's point in rows."""
        c = self.c
        if link not in self.gi:
            return st.P[rows, c.pi[point]], -1, None
        O, e, _, col = frames[link]
        v = e * _take(st.local[link], st.src[rows])[:, c.slot[link][point]]
        return O + v, col, 1j * v

    def evaluate(self, st, rows, z, cut=None):
        """(r, J): the group's equations (N, m) and their Jacobian (N, m, n), lengths in m
        and angles times the size; with ``cut`` (a revolute joint), that joint's separation
        and its Jacobian come apart as (r, J, s, S)."""
        c = self.c
        N = len(rows)
        frames = self._frames(st, rows, z)
        r, J = [], []
        apart = None

        def row(value, grads):
            g = np.zeros((N, self.n))
            for col, d in grads:
                g[:, col] += d
            r.append(value)
            J.append(g)

        for j in self.joints:
            a, b = j.links
            if j.type == "R":
                pa, ca, ta = self._point(st, rows, frames, a, j.point)
                pb, cb, tb = self._point(st, rows, frames, b, j.point)
                d = pa - pb
                grads = []       # (column, complex derivative of d)
                if ca >= 0:
                    grads += [(ca, 1.0 + 0j), (ca + 1, 1j), (ca + 2, ta)]
                if cb >= 0:
                    grads += [(cb, -1.0 + 0j), (cb + 1, -1j), (cb + 2, -tb)]
                parts = [(d.real, [(col, np.real(g)) for col, g in grads]),
                         (d.imag, [(col, np.imag(g)) for col, g in grads])]
                if j.name == cut:
                    apart = parts
                else:
                    for value, gr in parts:
                        row(value, gr)
                continue
            Og, eg, thg, cg = self._frame(st, rows, frames, a)
            _, es, ths, cs = self._frame(st, rows, frames, b)
            u = eg * c.axis[j.name]
            pp, cp, tp = self._point(st, rows, frames, b, j.point)
            po, co, to = self._point(st, rows, frames, a, c.origin[j.name])
            w = pp - po
            dw = []                  # (column, d w, d u)
            if cp >= 0:
                dw += [(cp, 1.0 + 0j, 0j), (cp + 1, 1j, 0j), (cp + 2, tp, 0j)]
            if co >= 0:
                dw += [(co, -1.0 + 0j, 0j), (co + 1, -1j, 0j), (co + 2, -to, 0j)]
            if cg >= 0:
                dw.append((cg + 2, 0j, 1j * u))
            row(_cross(u, w) - _take(st.offsets[j.name], st.src[rows]),
                [(col, _cross(u, dwi) + _cross(dui, w)) for col, dwi, dui in dw])
            angle = []
            if cs >= 0:
                angle.append((cs + 2, c.scale))
            if cg >= 0:
                angle.append((cg + 2, -c.scale))
            row(_wrap(ths - thg - c.frames.delta[j.name]) * c.scale, angle)
            if j.name in c.driven:
                q = _take(st.q, st.src[rows])[:, c.driven[j.name]]
                row(_dot(u, w) - q, [(col, _dot(u, dwi) + _dot(dui, w)) for col, dwi, dui in dw])
        for m_in in self.inputs:
            inp = c.m.inputs[m_in]
            a, b = c.m.joint(inp.joint).links if inp.joint is not None else inp.links
            _, _, tha, ca = self._frame(st, rows, frames, a)
            _, _, thb, cb = self._frame(st, rows, frames, b)
            q = _take(st.q, st.src[rows])[:, m_in]
            grads = ([(cb + 2, c.scale)] if cb >= 0 else []) + ([(ca + 2, -c.scale)] if ca >= 0 else [])
            row(_wrap(thb - tha - q) * c.scale, grads)
        out = (np.stack(r, -1), np.stack(J, 1))
        if cut is None:
            return out
        s = np.stack([v for v, _ in apart], -1)
        S = np.zeros((N, 2, self.n))
        for k, (_, gr) in enumerate(apart):
            for col, d in gr:
                S[:, k, col] += d
        return out + (s, S)

    def _iterate(self, st, rows, z, iterations):
        """Newton-Raphson on every row at once: (z, converged, det J at the solution)."""
        scale = self.c.scale
        ok = np.zeros(len(rows), bool)
        det = np.zeros(len(rows))
        active = np.arange(len(rows))
        units = np.where(self.lengthy, scale, 1.0)
        for it in range(iterations):
            if not len(active):
                break
            r, J = self.evaluate(st, rows[active], z[active])
            res = np.abs(r).max(1)
            if it >= iterations // 2:     # a start still far from any solution is given up
                near = res <= 1e-2 * scale
                active, r, J, res = active[near], r[near], J[near], res[near]
            converged = res <= 1e-12 * scale
            det[active] = np.linalg.det(J / units)
            dz = _solve(J, r)
            bad = ~np.isfinite(dz).all(1) | (np.abs(z[active][:, self.lengthy]).max(1) > 1e3 * scale)
            z[active] -= np.where(bad[:, None], 0.0, dz)
            small = (np.abs(dz) / units).max(1) <= 1e-14
            ok[active[converged]] = True
            active = active[~(converged & small) & ~bad]
        if len(active):
            r, J = self.evaluate(st, rows[active], z[active])
            ok[active] = np.abs(r).max(1) <= 1e-10 * scale
            det[active] = np.linalg.det(J / units)
        return z, ok, det

    def _starts(self, st, K):
        """(R, K, n): the sketch's frames, then each link turned by a seeded random angle
        about a point it shares with a placed link (or shifted, when it has none)."""
        c = self.c
        R = len(st.src)
        rng = np.random.default_rng(20240601)
        angles = rng.uniform(-math.pi, math.pi, (K, len(self.links)))
        shifts = rng.normal(0.0, 0.5, (K, len(self.links), 2)) @ np.array([1.0, 1j])
        z = np.zeros((R, K, self.n))
        for name, i in self.gi.items():
            pts = c.m.link(name).points
            O0 = complex(*c.m.point(pts[0]).xy)
            th = c.frames.theta0[name] + np.concatenate([[0.0], angles[1:, i]])     # (K,)
            L = _take(st.local[name], st.src)
            anchor = next((p for p in pts if st.known[c.pi[p]]), None)
            if anchor is not None:
                O = st.P[:, c.pi[anchor], None] - np.exp(1j * th)[None] * L[:, c.slot[name][anchor], None]
            else:
                O = np.broadcast_to(O0 + np.concatenate([[0.0], shifts[1:, i]]) * c.scale, (R, K))
            z[:, :, 3 * i], z[:, :, 3 * i + 1], z[:, :, 3 * i + 2] = O.real, O.imag, th[None]
        return z

    def _points(self, st, rows, z):
        frames = self._frames(st, rows, z)
        pts = [self._point(st, rows, frames, name, p)[0] for name in self.links
               for p in self.c.m.link(name).points]
        P = np.stack(pts, -1)
        return np.concatenate([P.real, P.imag], -1)

    def _write(self, st, z):
        c = self.c
        rows = np.arange(len(st.src))
        frames = self._frames(st, rows, z)
        for name in self.links:
            _, e, _, _ = frames[name]
            st.E[:, c.li[name]] = e
            for p in c.slot[name]:
                if not st.known[c.pi[p]]:
                    st.P[:, c.pi[p]] = self._point(st, rows, frames, name, p)[0]
        for name in self.links:
            for p in c.slot[name]:
                st.known[c.pi[p]] = True


def _wrap(angle):
    return np.angle(np.exp(1j * angle))


def _solve(J, r):
    """Least-squares steps of a batch: J (N, m, n), r (N, m) -> (N, n)."""
    if not len(J):
        return np.zeros((0, J.shape[2]))
    if J.shape[1] == J.shape[2]:
        try:
            return np.linalg.solve(J, r[..., None])[..., 0]
        except np.linalg.LinAlgError:
            pass
    return (np.linalg.pinv(J, rcond=1e-12) @ r[..., None])[..., 0]


def _min_norm_step(C, r):
    """-C+ r for a batch of full-row-rank C (N, m, n), by the normal equations; least
    squares where C C^T is singular."""
    CCt = C @ C.transpose(0, 2, 1)
    try:
        y = np.linalg.solve(CCt, r[..., None])
        dz = -(C.transpose(0, 2, 1) @ y)[..., 0]
        if np.isfinite(dz).all():
            return dz
    except np.linalg.LinAlgError:
        pass
    return -(np.linalg.pinv(C, rcond=1e-10) @ r[..., None])[..., 0]


def _cut_gap(ng: _NewtonGroup, st, rows, z0) -> np.ndarray:
    """For each row of ``rows`` (where a Newton group found no solution): the least distance
    between the two ends of the group's first revolute joint between two of its own links,
    cut open, over the configurations of the opened group reached from the starts (the
    next such joint where the opened group has no configuration at all).

    Each start is first brought onto the opened group (Gauss-Newton on its constraints),
    then moved along it, within a trust region, by the Gauss-Newton step of the separation
    in the null space of the constraints' Jacobian, brought back onto it and kept when the
    separation shrank: the least separation of each start is a local minimum, and the gap
    the least of them."""
    c = ng.c
    own = [j for j in ng.joints if j.type == "R" and all(n in ng.gi for n in j.links)]
    units = np.where(ng.lengthy, c.scale, 1.0)
    out = np.full(len(rows), np.inf)
    for j in own:
        todo = np.flatnonzero(~np.isfinite(out))
        if not len(todo):
            break
        R, K, n = len(todo), min(z0.shape[1], _CUT_STARTS), z0.shape[2]
        rr = np.repeat(rows[todo], K)

        def project(z, iterations=8):
            for _ in range(iterations):
                r, C, _, _ = ng.evaluate(st, rr, z, cut=j.name)
                dz = _min_norm_step(C * units, r) * units
                dz[~np.isfinite(dz).all(1)] = 0.0
                z = z + dz
                if np.all((np.abs(dz) / units).max(1) <= 1e-14):
                    break
            r, _, s, _ = ng.evaluate(st, rr, z, cut=j.name)
            return z, np.abs(r).max(1) <= 1e-10 * c.scale, np.linalg.norm(s, axis=1)
        z, feasible, sep = project(z0[todo, :K].reshape(R * K, n).copy(), 30)
        sep = np.where(feasible, sep, np.inf)
        damping = np.full(R * K, 1e-3)          # Levenberg-Marquardt, in the size's units
        settled = np.zeros(R * K, bool)
        for _ in range(80):
            live = feasible & ~settled & (damping < 1e8)
            if not live.any():
                break
            _, C, s, S = ng.evaluate(st, rr, z, cut=j.name)
            _, sv, Vt = np.linalg.svd(C * units)
            rank = (sv > 1e-10 * np.maximum(sv[:, :1], 1e-300)).sum(1)
            N = np.where((np.arange(n)[None, :] >= rank[:, None])[:, :, None], Vt, 0.0)
            N = N.transpose(0, 2, 1)                            # (rows, n, n): its null space
            A = (S * units) @ N
            H = A.transpose(0, 2, 1) @ A + np.where(live, damping, 1.0)[:, None, None] * np.eye(n)
            w = -np.linalg.solve(H, (A.transpose(0, 2, 1) @ s[..., None]))[..., 0]
            step = (N @ w[..., None])[..., 0]
            step[~live | ~np.isfinite(step).all(1)] = 0.0
            z_try, ok, sep_try = project(z + step * units)
            better = live & ok & (sep_try < sep)
            z = np.where(better[:, None], z_try, z)
            gain = sep - sep_try
            sep = np.where(better, sep_try, sep)
            damping = np.where(better, damping / 3.0, damping * 4.0)
            # settled: a step that no longer changes the separation beyond rounding
            settled |= better & (gain <= 1e-14 * c.scale)
        out[todo] = sep.reshape(R, K).min(1)
    return out
