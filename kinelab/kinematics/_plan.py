"""From a mechanism to a solution plan: the order in which its unknowns can be found.

The position problem Phi(q, S) = 0 of a planar linkage is solved group by group, as in a
structural (Assur) decomposition:

1. angles first where they follow directly: a driven joint gives ``theta_b = theta_a + q``;
   a prismatic joint locks the angles of the two links it joins;
2. a link whose angle is known is placed by a revolute joint on a placed link, by a driven
   slide, or by two slides (intersection of two lines);
3. dyads (class-II Assur groups) in closed form: RRR (two circles), RRP (circle and line),
   RPR (a line turning about a pivot), PRP (two lines);
4. whatever is left is grouped into the smallest set of links whose constraints determine
   them (a triad or larger Assur group), solved by Newton-Raphson with continuation.

Joints that no step needed are redundant constraints (a parallelogram's extra link); they
hold at the sketch and are checked on every sample.

The assembly mode (branch) of every closed-form dyad is read off the sketch and kept.
"""
from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass, field

import numpy as np

from kinelab.errors import ModelError, shown
from kinelab.kinematics import _codes as k
from kinelab.kinematics._geometry import sketch_angle
from kinelab.model import MIN_LENGTH, Joint, Mechanism
from kinelab.solvers import wrap_angle

_SKETCH_SINGULAR = 1e-9   # a dyad this close to straight at the sketch cannot fix its branch
SIGN_FIELDS = {k.OP_RRR: 2, k.OP_RRP: 2, k.OP_RPR: 4}   # where a dyad's assembly-mode sign
                                                        # sits in its row of ops_f


class Names(dict):
    """Items by name: a key that cannot be a name (a list, say) is simply not among them,
    so that a lookup says "expected one of ..." instead of raising TypeError."""

    def __contains__(self, key) -> bool:
        return isinstance(key, str) and dict.__contains__(self, key)


@dataclass(frozen=True)
class Step:
    """One group of the decomposition, for people: what it solves and how."""

    kind: str                  # "driven", "locked", "placed", "RRR", "RRP", "RPR", "PRP", "lines", "newton"
    links: tuple[str, ...]
    joints: tuple[str, ...]
    label: str
    op: int = -1               # index of its operation in the plan (groups with a det J)
    points: tuple[str, ...] = ()   # the group's joint points, in order (e.g. X-Y-Z of an RRR)


@dataclass(frozen=True)
class Plan:
    """A mechanism compiled for the kernel (see the module docstring).

    The kernel's state is one jet row per item: the link angles (items ``0 .. nl-1``, in
    model order), then x and y of each named point, then the slides of the prismatic
    joints (the *named* items, ``n_out`` of them), then the points the plan adds on links
    (lines' reference points).  Of the named items, only ``stored_items`` are written out
    per sample: the ground's angle and points keep ``fixed_values`` (K = L = 0), and a link
    turned by an input from the ground has the angle ``sign q[m]`` (``driven_items``: item
    -> (m, sign)), as its K and L are ``sign`` and 0.
    """

    mechanism: Mechanism
    link_item: Names
    point_item: Names
    slide_item: Names
    n_items: int
    n_out: int
    ops_i: np.ndarray
    ops_f: np.ndarray
    const_items: np.ndarray
    const_values: np.ndarray
    stored_items: np.ndarray
    fixed_values: dict[int, float]
    driven_items: dict[int, tuple[int, float]]
    groups: tuple[np.ndarray, ...] | None
    q_sketch: np.ndarray
    sketch_angles: np.ndarray
    steps: tuple[Step, ...]
    redundant: tuple[str, ...]
    scale: float
    input_kinds: tuple[str, ...] = field(default=())   # "angle" or "slide" per input
    _columns: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    memo: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    """What analyses derive from the plan once (its change points, its packed form)."""

    @property
    def n_angles(self) -> int:
        return len(self.link_item)

    @functools.cached_property
    def item_slot(self) -> np.ndarray:
        """For each named item, its column in the stored arrays, or -1 (fixed or driven)."""
        slot = np.full(self.n_out, -1, np.int64)
        slot[self.stored_items] = np.arange(len(self.stored_items))
        return slot

    def item_columns(self, items) -> ItemColumns:
        """Where the named ``items`` are: stored columns, fixed values, inputs (kept per
        distinct list of items, as dynamics asks for the same ones at every step)."""
        items = np.atleast_1d(np.asarray(items, np.int64))
        key = items.tobytes()
        cols = self._columns.get(key)
        if cols is None:
            cols = self._columns[key] = ItemColumns.of(self, items)
        return cols

    @property
    def uses_newton(self) -> bool:
        return self.groups is not None

    def step_of_op(self, op: int) -> Step | None:
        for s in self.steps:
            if s.op == op:
                return s
        return None


@dataclass(frozen=True)
class ItemColumns:
    """Named items split by where their values are (``cols`` index the list of items)."""

    slots: np.ndarray              # stored column of each item, -1 if not stored
    contiguous: slice | None       # all stored, in consecutive columns: a view
    solved_cols: np.ndarray
    fixed_cols: np.ndarray
    fixed_values: np.ndarray
    driven_cols: np.ndarray
    driven_inputs: np.ndarray      # the input m turning each driven item
    driven_signs: np.ndarray
    others: np.ndarray             # fixed and driven columns

    @classmethod
    def of(cls, plan: Plan, items: np.ndarray) -> ItemColumns:
        slots = plan.item_slot[items]
        contiguous = None
        if (slots >= 0).all():
            s0 = int(slots[0]) if len(slots) else 0
            if np.array_equal(slots, np.arange(s0, s0 + len(slots))):
                contiguous = slice(s0, s0 + len(slots))
        fixed = [c for c, it in enumerate(items.tolist()) if it in plan.fixed_values]
        driven = [c for c, it in enumerate(items.tolist()) if it in plan.driven_items]
        drive = [plan.driven_items[int(items[c])] for c in driven]
        ints = functools.partial(np.array, dtype=np.int64)
        return cls(slots=slots, contiguous=contiguous, solved_cols=np.flatnonzero(slots >= 0),
                   fixed_cols=ints(fixed),
                   fixed_values=np.array([plan.fixed_values[int(items[c])] for c in fixed], float),
                   driven_cols=ints(driven), driven_inputs=ints([m for m, _ in drive]),
                   driven_signs=np.array([sg for _, sg in drive], float),
                   others=np.flatnonzero(slots < 0))


# fields of each operation that hold point indices (converted to items at the end)
_POINT_FIELDS = {k.OP_RIGID_POINT: (1, 3), k.OP_SLIDE_POINT: (1, 2), k.OP_LINES: (1, 2, 4),
                 k.OP_RRR: (3, 4, 5), k.OP_RRP: (2, 3, 4), k.OP_RPR: (2, 3),
                 k.OP_SLIDE_OUT: (2, 3), k.OP_TWO_POINTS: (2, 3), k.OP_FRAME_POINT: (1, 2, 3)}


def _angle(v) -> float:
    return math.atan2(v[1], v[0])


def _rot(theta: float, v) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


class _Builder:
    def __init__(self, m: Mechanism):
        if m.space != "planar":
            raise ModelError(f"space: the planar kinematics engine needs a planar mechanism, "
                             f"got {shown(m.space)}; see kinelab.spatial for spatial ones")
        for j in m.joints:
            if j.type not in ("R", "P"):
                raise ModelError(f"joint '{j.name}': the planar kinematics engine handles R and P "
                                 f"joints, got {shown(j.type)}; kinelab.structure counts its mobility")
        if not m.inputs:
            raise ModelError("inputs: the mechanism has no input; add one (an R joint angle, "
                             "a P joint slide or the angle between two links)")
        self.m = m
        self.L = {name: i for i, name in enumerate(m.link_names)}
        self.P = {name: i for i, name in enumerate(m.point_names)}
        self.xy = {p.name: np.array([p.x, p.y], float) for p in m.points}
        self.point_xy = [self.xy[p.name] for p in m.points]       # by index
        self.n_all = len(self.P)
        self.ground = m.ground.name
        span = np.array(list(self.xy.values()))
        # the mechanism's size: every length tolerance is relative to it
        self.scale = float(max(np.ptp(span[:, 0]), np.ptp(span[:, 1]), MIN_LENGTH))
        self.theta_s = {link.name: sketch_angle(m, link.name) for link in m.links}
        self.ops_i: list[list[int]] = []
        self.ops_f: list[list[float]] = []
        self.steps: list[Step] = []
        self.angle_known = {self.ground}
        self.pos_known = {self.ground}
        self.anchor: dict[str, int] = {}
        self.computed: set[int] = set()
        self.virtual: dict[tuple[str, float, float], int] = {}
        self.used: set[str] = set()
        self.const_points: list[int] = []
        self.const_xy: list[np.ndarray] = []
        for pn in m.link(self.ground).points:
            self._set_const(self.P[pn], self.xy[pn])
        self.anchor[self.ground] = self.P[m.link(self.ground).points[0]]
        self.slides = {j.name: i for i, j in enumerate(x for x in m.joints if x.type == "P")}
        self.relations = self._input_relations()
        self.groups: list[tuple[list[str], list[tuple]]] = []

    # -- sketch geometry -------------------------------------------------------------------
    def _axis_angle(self, j: Joint) -> float:
        return _angle(j.axis)

    def _slide_sketch(self, j: Joint) -> float:
        origin = j.origin or self.m.link(j.links[0]).points[0]
        u = np.asarray(j.axis, float) / math.hypot(*j.axis)
        return float(u @ (self.xy[j.point] - self.xy[origin]))

    def _input_relations(self):
        """Per input: ('angle', a, b, m) meaning theta'_b - theta'_a = q_m, or ('slide', j, m)."""
        rel = []
        self.q_sketch = np.zeros(len(self.m.inputs))
        kinds = []
        for mi, inp in enumerate(self.m.inputs):
            if inp.joint is not None and self.m.joint(inp.joint).type == "P":
                j = self.m.joint(inp.joint)
                rel.append(("slide", j, mi))
                self.q_sketch[mi] = self._slide_sketch(j)
                kinds.append("slide")
            else:
                a, b = self.m.joint(inp.joint).links if inp.joint is not None else inp.links
                rel.append(("angle", a, b, mi))
                self.q_sketch[mi] = self._frame_angle(b) - self._frame_angle(a)
                kinds.append("angle")
        self.input_kinds = tuple(kinds)
        return rel

    def _frame_angle(self, link: str) -> float:
        return 0.0 if link == self.ground else self.theta_s[link]

    # -- emitting operations ---------------------------------------------------------------
    def _emit(self, ints, floats=()) -> int:
        self.ops_i.append(list(ints) + [0] * (8 - len(ints)))
        self.ops_f.append(list(floats) + [0.0] * (8 - len(floats)))
        return len(self.ops_i) - 1

    def _set_const(self, idx: int, xy) -> None:
        self.const_points.append(idx)
        self.const_xy.append(np.asarray(xy, float))
        self.computed.add(idx)

    def _local(self, link: str, xy) -> np.ndarray:
        """Sketch point xy in the frame of link (anchored at its anchor, rotated back)."""
        a = self.anchor_xy(link)
        return _rot(-self.theta_s[link], np.asarray(xy, float) - a)

    def anchor_xy(self, link: str) -> np.ndarray:
        idx = self.anchor[link]
        return self._xy_of(idx)

    def _xy_of(self, idx: int) -> np.ndarray:
        if idx < len(self.point_xy):
            return self.point_xy[idx]
        for (link, x, y), i in self.virtual.items():
            if i == idx:
                return np.array([x, y])
        raise KeyError(idx)

    def point_on(self, link: str, xy) -> int:
        """Index of a point rigid with a placed link at sketch position xy (named or new)."""
        xy = np.asarray(xy, float)
        for pn in self.m.link(link).points:
            if np.allclose(self.xy[pn], xy, rtol=0, atol=1e-14 * self.scale):
                return self.P[pn]
        key = (link, float(xy[0]), float(xy[1]))
        if key not in self.virtual:
            idx = self.n_all
            self.n_all += 1
            self.virtual[key] = idx
            if link == self.ground:
                self._set_const(idx, xy)
            else:
                self._emit_rigid(idx, link, xy)
        return self.virtual[key]

    def _farthest_known(self, link: str, exclude: int) -> tuple[float, int]:
        """(distance, index) of the computed point of a link farthest from its anchor."""
        a = self.anchor[link]
        a_xy = self._xy_of(a)
        known = [(float(np.hypot(*(self.xy[pn] - a_xy))), self.P[pn]) for pn in self.m.link(link).points
                 if self.P[pn] in self.computed and self.P[pn] not in (a, exclude)]
        return max(known, default=(0.0, -1))

    def _emit_rigid(self, idx: int, link: str, xy, far: tuple[float, int] | None = None) -> None:
        """Emit the operation placing point idx (at sketch xy) rigid with a placed link.

        Through the anchor a and the known point b of the link farthest from it (``far``, if
        the caller keeps it), p = a + lam (b - a) + mu k x (b - a) needs no sine or cosine;
        a link with one known point (a crank on its pivot) turns r by its angle instead.
        """
        a = self.anchor[link]
        a_xy = self._xy_of(a)
        if far is None:
            far = self._farthest_known(link, idx)
        if far[0] > 1e-6 * self.scale:
            d = self._xy_of(far[1]) - a_xy
            r = np.asarray(xy, float) - a_xy
            d2 = float(d @ d)
            self._emit([k.OP_FRAME_POINT, idx, a, far[1]],
                       [float(r @ d) / d2, float(d[0] * r[1] - d[1] * r[0]) / d2])
        else:
            self._emit([k.OP_RIGID_POINT, idx, self.L[link], a], self._local(link, xy))

    def place(self, link: str, anchor: int) -> None:
        """Mark a link placed (angle and anchor known) and compute its named points."""
        self.angle_known.add(link)
        self.pos_known.add(link)
        self.anchor[link] = anchor
        self.computed.add(anchor)
        far = self._farthest_known(link, -1)     # kept up to date: linear in the points
        a_xy = self._xy_of(anchor)
        for pn in self.m.link(link).points:
            idx = self.P[pn]
            if idx not in self.computed:
                self._emit_rigid(idx, link, self.xy[pn], far)
                self.computed.add(idx)
                far = max(far, (float(np.hypot(*(self.xy[pn] - a_xy))), idx))

    # -- the decomposition -----------------------------------------------------------------
    def build(self) -> Plan:
        m = self.m
        self.check_mobility()
        while len(self.pos_known) < len(m.links):
            if self._propagate_angles() or self._place_single() or self._dyad():
                continue
            self._newton_group()
        for j in m.joints:
            if j.type == "P":
                g, s = j.links
                o = self.point_on(g, self.xy[j.point])
                self._emit([k.OP_SLIDE_OUT, self.slides[j.name], self.P[j.point], o, self.L[g]],
                           [self._axis_angle(j) - self.theta_s[g], self._slide_sketch(j)])
        redundant = tuple(j.name for j in m.joints if j.name not in self.used)
        nl, npn, ns = len(self.L), len(self.P), len(self.slides)

        def item(p: int) -> int:
            return nl + 2 * p if p < npn else nl + 2 * npn + ns + 2 * (p - npn)
        ops_i = np.array(self.ops_i, np.int64).reshape(-1, 8)
        for row in ops_i:
            for f in _POINT_FIELDS.get(int(row[0]), ()):
                row[f] = item(int(row[f]))
            if row[0] == k.OP_SLIDE_OUT:
                row[1] = nl + 2 * npn + int(row[1])
        const_items = [self.L[self.ground]]
        const_values = [float(wrap_angle(self.theta_s[self.ground]))]
        for idx, xy in zip(self.const_points, self.const_xy):
            const_items += [item(idx), item(idx) + 1]
            const_values += [float(xy[0]), float(xy[1])]
        fixed = {i: v for i, v in zip(const_items, const_values) if i < nl + 2 * npn + ns}
        driven = {int(row[1]): (int(row[3]), float(f[0])) for row, f in zip(ops_i, self.ops_f)
                  if row[0] == k.OP_DRIVE_ANGLE and row[2] == -1}
        return Plan(
            mechanism=m, link_item=Names(self.L),
            point_item=Names({name: item(i) for name, i in self.P.items()}),
            slide_item=Names({name: nl + 2 * npn + i for name, i in self.slides.items()}),
            n_items=nl + 2 * self.n_all + ns, n_out=nl + 2 * npn + ns,
            ops_i=ops_i, ops_f=np.array(self.ops_f, float).reshape(-1, 8),
            const_items=np.array(const_items, np.int64),
            const_values=np.array(const_values, float),
            stored_items=np.array([i for i in range(nl + 2 * npn + ns)
                                   if i not in fixed and i not in driven], np.int64),
            fixed_values=fixed, driven_items=driven,
            groups=self._pack_groups(item) if self.groups else None,
            q_sketch=self.q_sketch.copy(),
            sketch_angles=np.array([self.theta_s[n] for n in m.link_names]),
            steps=tuple(self.steps), redundant=redundant, scale=self.scale,
            input_kinds=self.input_kinds)

    def _propagate_angles(self) -> bool:
        progress = False
        for rel in self.relations:
            if rel[0] != "angle":
                continue
            _, a, b, mi = rel
            for known, other, sign in ((a, b, 1.0), (b, a, -1.0)):
                if known in self.angle_known and other not in self.angle_known:
                    base = -1 if known == self.ground else self.L[known]
                    if other == self.ground:
                        continue
                    self._emit([k.OP_DRIVE_ANGLE, self.L[other], base, mi], [sign])
                    self.angle_known.add(other)
                    self.steps.append(Step("driven", (other,), (), f"'{other}' turned by input {mi}"))
                    progress = True
        for j in self.m.joints:
            if j.type != "P":
                continue
            for known, other in (j.links, j.links[::-1]):
                if known in self.angle_known and other not in self.angle_known:
                    self._emit([k.OP_LOCK_ANGLE, self.L[other], self.L[known]],
                               [self.theta_s[other] - self.theta_s[known]])
                    self.angle_known.add(other)
                    self.steps.append(Step("locked", (other,), (j.name,),
                                           f"'{other}' keeps its angle to '{known}' (slide '{j.name}')"))
                    progress = True
        return progress

    def _driven_slide(self, j: Joint):
        for rel in self.relations:
            if rel[0] == "slide" and rel[1].name == j.name:
                return rel[2]
        return None

    def _free_joints(self, link: str):
        return [j for j in self.m.joints_of(link) if j.name not in self.used]

    def _partner(self, j: Joint, link: str) -> str:
        return j.links[1] if j.links[0] == link else j.links[0]

    def _line_for(self, link: str, j: Joint, xy) -> tuple[int, int, float]:
        """The line a point of `link` (at sketch xy) moves on, sliding in P joint j on a placed
        partner: (point of the partner on that line, link giving its direction, beta)."""
        partner = self._partner(j, link)
        guide = j.links[0]
        o = self.point_on(partner, xy)
        return o, self.L[guide], self._axis_angle(j) - self.theta_s[guide]

    def _place_single(self) -> bool:
        return self._place_by_two_hinges() or self._place_known_angle()

    def _place_by_two_hinges(self) -> bool:
        """A link hinged on two placed links (a binary link across a parallelogram): its angle
        follows the two hinge points; the second hinge is then a redundant constraint."""
        for link in self.m.link_names:
            if link in self.angle_known:
                continue
            hinges = [j for j in self._free_joints(link)
                      if j.type == "R" and self._partner(j, link) in self.pos_known]
            hinges = [j for j in hinges if self.P[j.point] in self.computed]
            if len(hinges) < 2 or hinges[0].point == hinges[1].point:
                continue
            j1, j2 = hinges[:2]
            p1, p2 = self.xy[j1.point], self.xy[j2.point]
            self._emit([k.OP_TWO_POINTS, self.L[link], self.P[j1.point], self.P[j2.point]],
                       [self.theta_s[link] - _angle(p2 - p1)])
            self.used.add(j1.name)       # j2 stays unused: it is checked as redundant
            self.place(link, self.P[j1.point])
            self.steps.append(Step("placed", (link,), (j1.name, j2.name),
                                   f"'{link}' through '{j1.point}' and '{j2.point}'"))
            return True
        return False

    def _place_known_angle(self) -> bool:
        for link in self.m.link_names:
            if link in self.pos_known or link not in self.angle_known:
                continue
            free = self._free_joints(link)
            for j in free:
                if j.type == "R" and self._partner(j, link) in self.pos_known:
                    self.used.add(j.name)
                    self.place(link, self.P[j.point])
                    self.steps.append(Step("placed", (link,), (j.name,),
                                           f"'{link}' hinged at '{j.point}'"))
                    return True
            for j in free:
                mi = self._driven_slide(j) if j.type == "P" else None
                if mi is None or self._partner(j, link) not in self.pos_known:
                    continue
                guide, slider = j.links
                beta = self._axis_angle(j) - self.theta_s[guide]
                s0 = self._slide_sketch(j)
                if link == slider:
                    out = self.P[j.point]
                    base = self.point_on(guide, self.xy[j.point])
                    sign = 1.0
                else:
                    base = self.P[j.point]
                    out = self._new_point(link, self.xy[j.point])
                    sign = -1.0
                self._emit([k.OP_SLIDE_POINT, out, base, self.L[guide], mi], [beta, s0, sign])
                self.used.add(j.name)
                self.place(link, out)
                self.steps.append(Step("placed", (link,), (j.name,), f"'{link}' driven along '{j.name}'"))
                return True
            slides = [j for j in free if j.type == "P" and self._partner(j, link) in self.pos_known]
            if len(slides) >= 2:
                j1, j2 = slides[:2]
                a_xy = self.xy[self.m.link(link).points[0]]
                o1, l1, b1 = self._line_for(link, j1, a_xy)
                o2, l2, b2 = self._line_for(link, j2, a_xy)
                out = self.P[self.m.link(link).points[0]]
                op = self._emit([k.OP_LINES, out, o1, l1, o2, l2], [b1, b2])
                self.used.update((j1.name, j2.name))
                self.place(link, out)
                self.steps.append(Step("lines", (link,), (j1.name, j2.name),
                                       f"'{link}' placed by slides '{j1.name}' and '{j2.name}'", op))
                return True
        return False

    def _new_point(self, link: str, xy) -> int:
        idx = self.n_all
        self.n_all += 1
        self.virtual[(link, float(xy[0]), float(xy[1]))] = idx
        return idx

    def _known_hinge(self, link: str, exclude: str):
        for j in self._free_joints(link):
            if j.name != exclude and j.type == "R" and self._partner(j, link) in self.pos_known:
                return j
        return None

    def _known_slide(self, link: str, exclude: str):
        for j in self._free_joints(link):
            if (j.name != exclude and j.type == "P" and self._partner(j, link) in self.pos_known
                    and self._driven_slide(j) is None):
                return j
        return None

    def _branch(self, value: float, size: float, what: str) -> float:
        if abs(value) <= _SKETCH_SINGULAR * size:
            raise ModelError(f"the sketch puts {what} in a singular (straight) position, so its "
                             "assembly mode is undefined; move a point of the sketch off that line")
        return 1.0 if value > 0 else -1.0

    def _dyad(self) -> bool:
        for j in self.m.joints:
            if j.name in self.used:
                continue
            b, c = j.links
            if b in self.pos_known or c in self.pos_known:
                continue
            for b, c in ((b, c), (c, b)):
                if j.type == "R" and self._rrr(j, b, c):
                    return True
                if j.type == "R" and self._rrp(j, b, c):
                    return True
                if j.type == "R" and self._prp(j, b, c):
                    return True
            if j.type == "P" and self._rpr(j):
                return True
        return False

    def _rrr(self, j, b, c) -> bool:
        if b in self.angle_known or c in self.angle_known:
            return False
        jx, jz = self._known_hinge(b, j.name), self._known_hinge(c, j.name)
        if jx is None or jz is None:
            return False
        X, Y, Z = self.xy[jx.point], self.xy[j.point], self.xy[jz.point]
        lb, lc = float(np.linalg.norm(Y - X)), float(np.linalg.norm(Y - Z))
        if lb == 0.0 or lc == 0.0:
            return False
        d = Z - X
        sigma = self._branch(d[0] * (Y - X)[1] - d[1] * (Y - X)[0], lb * float(np.linalg.norm(d)) + 1e-300,
                             f"the dyad '{b}'-'{c}' ({jx.point}-{j.point}-{jz.point})")
        op = self._emit([k.OP_RRR, self.L[b], self.L[c], self.P[jx.point], self.P[j.point], self.P[jz.point]],
                        [lb, lc, sigma, self.theta_s[b] - _angle(Y - X), self.theta_s[c] - _angle(Y - Z)])
        self.used.update((j.name, jx.name, jz.name))
        self.computed.add(self.P[j.point])
        self.place(b, self.P[jx.point])
        self.place(c, self.P[jz.point])
        self.steps.append(Step("RRR", (b, c), (jx.name, j.name, jz.name),
                               f"dyad '{b}'-'{c}' (RRR {jx.point}-{j.point}-{jz.point})", op,
                               (jx.point, j.point, jz.point)))
        return True

    def _rrp(self, j, b, c) -> bool:
        if b in self.angle_known or c not in self.angle_known:
            return False
        jx, jp = self._known_hinge(b, j.name), self._known_slide(c, j.name)
        if jx is None or jp is None:
            return False
        X, Y = self.xy[jx.point], self.xy[j.point]
        lb = float(np.linalg.norm(Y - X))
        if lb == 0.0:
            return False
        o, g, beta = self._line_for(c, jp, Y)
        u = np.array([math.cos(self._axis_angle(jp)), math.sin(self._axis_angle(jp))])
        sigma = self._branch(float(u @ (Y - X)), lb, f"the dyad '{b}'-'{c}' ({jx.point}-{j.point} "
                             f"and slide '{jp.name}')")
        op = self._emit([k.OP_RRP, self.L[b], self.P[jx.point], self.P[j.point], o, g],
                        [lb, beta, sigma, self.theta_s[b] - _angle(Y - X)])
        self.used.update((j.name, jx.name, jp.name))
        self.computed.add(self.P[j.point])
        self.place(b, self.P[jx.point])
        self.place(c, self.P[j.point])
        self.steps.append(Step("RRP", (b, c), (jx.name, j.name, jp.name),
                               f"dyad '{b}'-'{c}' (RRP {jx.point}-{j.point} on slide '{jp.name}')",
                               op, (jx.point, j.point)))
        return True

    def _prp(self, j, b, c) -> bool:
        if b not in self.angle_known or c not in self.angle_known:
            return False
        jb, jc = self._known_slide(b, j.name), self._known_slide(c, j.name)
        if jb is None or jc is None:
            return False
        Y = self.xy[j.point]
        o1, l1, b1 = self._line_for(b, jb, Y)
        o2, l2, b2 = self._line_for(c, jc, Y)
        op = self._emit([k.OP_LINES, self.P[j.point], o1, l1, o2, l2], [b1, b2])
        self.used.update((j.name, jb.name, jc.name))
        self.place(b, self.P[j.point])
        self.place(c, self.P[j.point])
        self.steps.append(Step("PRP", (b, c), (jb.name, j.name, jc.name),
                               f"dyad '{b}'-'{c}' (PRP at {j.point})", op))
        return True

    def _rpr(self, j) -> bool:
        G, S = j.links
        if G in self.angle_known or S in self.angle_known:
            return False
        jx, jz = self._known_hinge(S, j.name), self._known_hinge(G, j.name)
        if jx is None or jz is None:
            return False
        X, Z = self.xy[jx.point], self.xy[jz.point]
        if np.linalg.norm(X - Z) == 0.0:
            return False
        u = np.asarray(j.axis, float) / math.hypot(*j.axis)
        sigma = self._branch(float(u @ (X - Z)), float(np.linalg.norm(X - Z)),
                             f"the dyad '{G}'-'{S}' (slide '{j.name}' between {jz.point} and {jx.point})")
        rho = _rot(-self.theta_s[G], X - Z)
        ul = _rot(-self.theta_s[G], u)
        # G's angle comes from the op; its anchor Z is known
        op = self._emit([k.OP_RPR, self.L[G], self.P[jx.point], self.P[jz.point]],
                        [rho[0], rho[1], ul[0], ul[1], sigma])
        self._emit([k.OP_LOCK_ANGLE, self.L[S], self.L[G]], [self.theta_s[S] - self.theta_s[G]])
        self.used.update((j.name, jx.name, jz.name))
        self.place(G, self.P[jz.point])
        self.place(S, self.P[jx.point])
        self.steps.append(Step("RPR", (G, S), (jz.name, j.name, jx.name),
                               f"dyad '{G}'-'{S}' (RPR {jz.point}-slide '{j.name}'-{jx.point})", op,
                               (jz.point, jx.point)))
        return True

    # -- larger groups: Newton-Raphson ------------------------------------------------------
    def _group_equations(self, group: set[str]):
        """Constraints that bind the links of `group` (the rest placed): list and count."""
        cons, count = [], 0
        for j in self.m.joints:
            if j.name in self.used or not (set(j.links) & group):
                continue
            if not all(n in group or n in self.pos_known for n in j.links):
                continue
            mi = self._driven_slide(j) if j.type == "P" else None
            cons.append(("joint", j, mi))
            count += 2 if mi is None else 3      # a driven slide adds its driving equation
        for rel in self.relations:
            if rel[0] != "angle":
                continue
            _, a, b, mi = rel
            if not ({a, b} & group):
                continue
            if not all(n in group or n in self.angle_known for n in (a, b)):
                continue
            cons.append(("drive", a, b, mi))
            count += 1
        return cons, count

    def _newton_group(self) -> None:
        free = [n for n in self.m.link_names if n not in self.pos_known]
        neighbours = {n: {self._partner(j, n) for j in self.m.joints_of(n)} & set(free) for n in free}
        for size in range(1, min(len(free), 6) + 1):
            for combo in itertools.combinations(free, size):
                group = set(combo)
                if not _connected(group, neighbours):
                    continue
                cons, count = self._group_equations(group)
                if count == 3 * size and self._full_rank(list(combo), cons):
                    return self._emit_group(list(combo), cons)
        cons, count = self._group_equations(set(free))
        if count == 3 * len(free) and self._full_rank(free, cons):
            return self._emit_group(free, cons)
        unknowns = 3 * len(free)
        if count < unknowns:
            raise ModelError(
                f"links {', '.join(repr(n) for n in free)} are not determined by the joints and "
                f"inputs: {unknowns} unknowns but {count} equations, so the mechanism has "
                f"{unknowns - count} more degree(s) of freedom than inputs; add an input or a joint")
        raise ModelError(
            f"links {', '.join(repr(n) for n in free)} are over-determined or locked at the sketch "
            f"({count} equations for {unknowns} unknowns, or a singular sketch); check the joints "
            "and inputs, or move the sketch off a singular configuration")

    def _group_tables(self, links: list[str], cons):
        gi = {n: i for i, n in enumerate(links)}
        anchors = [self.P[self.m.link(n).points[0]] for n in links]
        for n, a in zip(links, anchors):
            self.anchor[n] = a
        rows_i, rows_f = [], []

        def side(link, xy):
            if link in gi:
                r = _rot(-self.theta_s[link], np.asarray(xy) - self.xy[self.m.link(link).points[0]])
                return gi[link], -1, self.L[link], r
            return -1, self.point_on(link, xy), self.L[link], np.zeros(2)

        for c in cons:
            if c[0] == "joint":
                j, mi = c[1], c[2]
                xy = self.xy[j.point]
                if j.type == "R":
                    g1, p1, l1, r1 = side(j.links[0], xy)
                    g2, p2, l2, r2 = side(j.links[1], xy)
                    rows_i.append([k.C_REVOLUTE, g1, p1, l1, g2, p2, l2, 0])
                    rows_f.append([r1[0], r1[1], r2[0], r2[1], 0.0, 0.0, 0.0, 0.0])
                else:
                    g1, p1, l1, r1 = side(j.links[0], xy)
                    g2, p2, l2, r2 = side(j.links[1], xy)
                    beta = self._axis_angle(j) - self.theta_s[j.links[0]]
                    rows_i.append([k.C_PRISMATIC, g1, p1, l1, g2, p2, l2, 0])
                    rows_f.append([r1[0], r1[1], r2[0], r2[1], beta,
                                   self.theta_s[j.links[1]] - self.theta_s[j.links[0]], 0.0, 0.0])
                    if mi is not None:
                        rows_i.append([k.C_DRIVE_SLIDE, g1, p1, l1, g2, p2, l2, mi])
                        rows_f.append([r1[0], r1[1], r2[0], r2[1], beta, self._slide_sketch(j), 0.0, 0.0])
            else:
                _, a, b, mi = c
                ga = gi.get(a, -1)
                gb = gi.get(b, -1)
                la = -1 if a == self.ground else self.L[a]
                lb = -1 if b == self.ground else self.L[b]
                rows_i.append([k.C_DRIVE_ANGLE, ga, -1, la, gb, -1, lb, mi])
                rows_f.append([1.0] + [0.0] * 7)
        x0 = np.concatenate([[*self.xy[self.m.link(n).points[0]], self.theta_s[n]] for n in links])
        return anchors, np.array(rows_i, np.int64), np.array(rows_f, float), x0

    def _sketch_jacobian(self, links, cons) -> np.ndarray:
        """Jacobian of the constraints `cons` with respect to the poses of `links`, at the
        sketch (rows: equations, columns: x, y, theta of each link)."""
        saved = (len(self.ops_i), dict(self.virtual), self.n_all, list(self.const_points),
                 [c.copy() for c in self.const_xy], set(self.computed), dict(self.anchor))
        try:
            _, ci, cf, x0 = self._group_tables(links, cons)
            pt = np.array([self._xy_of(i) for i in range(self.n_all)], float).reshape(-1, 2)
            ang = np.array([self.theta_s[name] for name in self.m.link_names])
        finally:
            (nops, self.virtual, self.n_all, self.const_points, self.const_xy, self.computed,
             self.anchor) = saved
            del self.ops_i[nops:]
            del self.ops_f[nops:]
        # a jet of the sketch: angles, then x, y of every point known so far
        from kinelab.kinematics import _interpreter
        nl, M = len(self.L), len(self.q_sketch)
        jet = np.zeros((nl + 2 * len(pt), 1 + M + M * M))
        jet[:nl, 0] = ang
        jet[nl:, 0] = pt.ravel()
        ci = ci.copy()
        for row in ci:
            for gcol, pcol in ((1, 2), (4, 5)):
                if row[gcol] < 0 and row[pcol] >= 0:
                    row[pcol] = nl + 2 * row[pcol]
        group = np.array([[0, len(links), 0, len(ci), *range(len(links)), *[0] * len(links)]],
                         np.int64)
        G = _interpreter._Group(0, group, ci, cf, M)
        _, A = _interpreter._residual(G, x0, _interpreter._Known(G, jet, M), 0.0, 0.0)
        return A

    def _full_rank(self, links, cons) -> bool:
        s = np.linalg.svd(self._sketch_jacobian(links, cons), compute_uv=False)
        return bool(s[-1] > 1e-9 * s[0])

    def check_mobility(self) -> None:
        """The inputs must match the linkage's degrees of freedom: its exact mobility at the
        sketch (the rank of the joints' constraints, kinelab.structure)."""
        from kinelab.structure import mobility

        mob = mobility(self.m)
        n_in = len(self.m.inputs)
        if mob.exact != n_in:
            more = "more" if mob.exact > n_in else "fewer"
            raise ModelError(
                f"inputs: the linkage has {mob.exact} degree(s) of freedom at the sketch (exact "
                f"mobility; Kutzbach-Gruebler counts {mob.kutzbach_gruebler}) but {n_in} "
                f"input(s); give it {mob.exact} input(s), or {more} joints")

    def _emit_group(self, links, cons) -> None:
        anchors, ci, cf, x0 = self._group_tables(links, cons)
        gid = len(self.groups)
        self.groups.append((links, anchors, ci, cf, x0))
        op = self._emit([k.OP_NEWTON, gid])
        joints = tuple(c[1].name for c in cons if c[0] == "joint")
        self.used.update(joints)
        for n, a in zip(links, anchors):
            self.computed.add(a)
        for n, a in zip(links, anchors):
            self.place(n, a)
        self.steps.append(Step("newton", tuple(links), joints,
                               f"group {', '.join(repr(n) for n in links)} (solved by Newton-Raphson)", op))

    def _pack_groups(self, item):
        width = 4 + 2 * max(len(names) for names, *_ in self.groups)
        rows, ci, cf, x0 = [], [], [], []
        offset, c0 = 0, 0
        for names, anchors, c_i, c_f, x in self.groups:
            c_i = c_i.copy()
            for row in c_i:       # known sides (g = -1) name a point: make it an item
                for gcol, pcol in ((1, 2), (4, 5)):
                    if row[gcol] < 0 and row[pcol] >= 0:
                        row[pcol] = item(int(row[pcol]))
            row = [offset, len(names), c0, c0 + len(c_i)]
            row += [self.L[n] for n in names] + [item(a) for a in anchors]
            rows.append(row + [0] * (width - len(row)))
            ci.append(c_i)
            cf.append(c_f)
            x0.append(x)
            offset += len(x)
            c0 += len(c_i)
        return (np.array(rows, np.int64), np.concatenate(ci), np.concatenate(cf),
                np.concatenate(x0))


def _connected(group: set[str], neighbours: dict[str, set[str]]) -> bool:
    start = next(iter(group))
    seen, todo = {start}, [start]
    while todo:
        n = todo.pop()
        for x in neighbours[n] & group:
            if x not in seen:
                seen.add(x)
                todo.append(x)
    return seen == group


def build_plan(m: Mechanism, *, method: str = "auto") -> Plan:
    """Decompose a planar mechanism into its solution plan.

    ``method="newton"`` skips the closed forms: every moving link goes into Newton groups
    (used to check the closed forms against the general engine).
    """
    b = _Builder(m)
    if method == "newton":
        b._dyad = lambda: False          # type: ignore[method-assign]
        b._place_single = lambda: False  # type: ignore[method-assign]
        b._propagate_angles = lambda: False  # type: ignore[method-assign]
    elif method != "auto":
        raise ModelError(f"method: expected one of 'auto', 'newton', got {shown(method)}")
    return b.build()
