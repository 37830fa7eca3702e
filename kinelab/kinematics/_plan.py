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
from kinelab.model import MIN_LENGTH, Joint, Mechanism, cam_pair, cam_values, gear_mesh
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

    kind: str                  # "driven", "locked", "placed", "RRR", "RRP", "RPR", "PRP", "lines",
                               # "gear", "cam", "newton"
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
    recipe: _Recipe | None = field(default=None, repr=False, compare=False)
    _columns: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    _found: dict = field(default_factory=dict, init=False, repr=False, compare=False)
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

    def designs(self, points, axes=None) -> Designs:
        """The plan's numbers for D designs of this mechanism's topology, from their sketches.

        Parameters
        ----------
        points : mapping of str to array_like (D, 2), or array_like (D, P, 2)
            Each design's sketch: the places of the mechanism's points, by name, or in the
            order of ``mechanism.points`` (m).  Every design keeps the model's joints, inputs
            and the plan's operations; its own sketch gives its links' dimensions, its dyads'
            assembly modes and its inputs' values there.
        axes : mapping of str to array_like (D, 2) or (2,), optional
            The directions of prismatic joints' axes in the designs' sketches, by joint name
            (default: each joint's axis as the mechanism gives it).

        Returns
        -------
        Designs
            Its ``valid`` marks the designs whose sketch this plan can take: a design
            whose sketch draws a dyad straight, puts two of the plan's points on one link at
            one place where the mechanism's sketch does not (or the other way round), or
            gives a link no length, needs a plan of its own (``build_plan``).
        """
        return self.recipe.designs(points, axes)


@dataclass(frozen=True)
class Designs:
    """The numbers of a plan for D designs of one topology (:meth:`Plan.designs`): each
    design's operation parameters, constants, the inputs and link angles at its sketch,
    its size, the numbers and starting state of its Newton groups, and whether it is valid."""

    ops_f: np.ndarray            # (D, n_ops, 8)
    const_values: np.ndarray     # (D, n_const)
    q_sketch: np.ndarray         # (D, M)
    sketch_angles: np.ndarray    # (D, n_links)
    scale: np.ndarray            # (D,)
    group_f: np.ndarray | None   # (D, constraint rows, 8): con_f of the Newton groups
    group_x0: np.ndarray | None  # (D, unknowns): their state at the sketch
    valid: np.ndarray            # (D,) bool

    def __len__(self) -> int:
        return len(self.valid)


class _Recipe:
    """How a plan's numbers follow from a sketch (kept on the plan, see ``Plan.designs``)."""

    def __init__(self, b: _Builder):
        self.m = b.m
        self.ops = list(b.recipes)
        self.groups = [numbers for *_, numbers in b.groups]
        self.coincide = list(b.coincide)
        self.sources = dict(b.sources)
        self.constants, self.inputs_at = b.constants, b.inputs_at

    def geometry(self, points, axes=None) -> _Geometry:
        names = self.m.point_names
        if isinstance(points, dict):
            missing = [n for n in names if n not in points]
            if missing:
                raise ModelError(f"points: expected a place for every point of the mechanism, "
                                 f"missing {', '.join(repr(n) for n in missing)}")
            xy = {n: np.asarray(points[n], float) for n in names}
        else:
            a = np.asarray(points, float)
            if a.ndim != 3 or a.shape[1:] != (len(names), 2):
                raise ModelError(f"points: expected an array (D, {len(names)}, 2) of the points' "
                                 f"places, got shape {a.shape}")
            xy = {n: a[:, i] for i, n in enumerate(names)}
        shapes = {v.shape for v in xy.values()}
        if len(shapes) != 1 or len(next(iter(shapes))) != 2 or next(iter(shapes))[1] != 2:
            raise ModelError(f"points: expected every place of shape (D, 2), got {sorted(shapes)}")
        D = next(iter(shapes))[0]
        prismatic = [j.name for j in self.m.joints if j.type == "P"]
        given = {}
        for name, a in (axes or {}).items():
            if name not in prismatic:
                raise ModelError(f"axes: expected prismatic joints' names ({', '.join(map(repr, prismatic))}), "
                                 f"got {name!r}")
            a = np.asarray(a, float)
            if a.shape not in ((2,), (D, 2)) or not np.all(np.isfinite(a)) or np.any(_norm(a) == 0):
                raise ModelError(f"axes.{name}: expected a non-zero direction, (2,) or (D, 2), got "
                                 f"shape {a.shape}")
            given[name] = np.broadcast_to(a, (D, 2))
        return _Geometry(self.m, xy, self.sources, given)

    def designs(self, points, axes=None) -> Designs:
        G = self.geometry(points, axes)
        D = len(G.scale)
        ops_f = np.zeros((D, len(self.ops), 8))
        for op, recipe in enumerate(self.ops):
            if recipe is not None:
                for col, v in enumerate(recipe(G)):
                    ops_f[:, op, col] = v
        group_f = group_x0 = None
        if self.groups:
            parts = [numbers(G) for numbers in self.groups]
            group_f = np.concatenate([f for f, _ in parts], 1)
            group_x0 = np.concatenate([x for _, x in parts], 1)
        const_values = self.constants(G)
        valid = np.isfinite(ops_f).all(axis=(1, 2)) & np.isfinite(const_values).all(axis=1)
        for a, b in self.coincide:           # points the plan takes as one place
            valid &= _norm(G.xy[a] - G.xy[b]) <= 1e-14 * G.scale
        return Designs(ops_f=ops_f, const_values=const_values, q_sketch=self.inputs_at(G),
                       sketch_angles=np.stack([G.theta[n] for n in self.m.link_names], -1),
                       scale=G.scale, group_f=group_f, group_x0=group_x0, valid=valid)


@dataclass(frozen=True)
class ItemColumns:
    """Named items split by where their values are (``cols`` index the list of items)."""

    slots: np.ndarray              # stored column of each item, -1 if not stored
    contiguous: slice | None       # all stored, in consecutive columns: a view
    solved_cols: np.ndarray
    fixed_cols: np.ndarray
    fixed_values: np.ndarray
    fixed_constants: np.ndarray    # where each fixed item is among the plan's constants
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
                   fixed_constants=ints([plan.const_items.tolist().index(int(items[c]))
                                         for c in fixed]),
                   driven_cols=ints(driven), driven_inputs=ints([m for m, _ in drive]),
                   driven_signs=np.array([sg for _, sg in drive], float),
                   others=np.flatnonzero(slots < 0))


# fields of each operation that hold point indices (converted to items at the end)
_POINT_FIELDS = {k.OP_RIGID_POINT: (1, 3), k.OP_SLIDE_POINT: (1, 2), k.OP_LINES: (1, 2, 4),
                 k.OP_RRR: (3, 4, 5), k.OP_RRP: (2, 3, 4), k.OP_RPR: (2, 3),
                 k.OP_SLIDE_OUT: (2, 3), k.OP_TWO_POINTS: (2, 3), k.OP_FRAME_POINT: (1, 2, 3),
                 k.OP_GEAR_SLIDE: (1, 2), k.OP_CAM_SLIDE: (1, 2)}


def _angle(v) -> float:
    return math.atan2(v[1], v[0])


def _rot(theta: float, v) -> np.ndarray:
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


# -- the numbers of a plan, for one sketch or for the sketches of many designs ----------------
# Every number an operation carries (a dyad's arm lengths and branch, a point's place on its
# link, a slide's axis ...) comes from the sketch.  The builder decides the operations from
# the mechanism's own sketch and records, beside each, how its numbers follow from a sketch
# (a *recipe*): the same recipes, given the sketches of D designs of one topology at once
# (point places of shape (D, 2)), give each design's numbers in a few array operations
# (``Plan.designs``).  For the plan's own sketch D = 1.

def _angles(v: np.ndarray) -> np.ndarray:
    """Direction of vectors (..., 2), rad."""
    return np.arctan2(v[..., 1], v[..., 0])


def _rotated(theta, v: np.ndarray) -> np.ndarray:
    """Vectors (..., 2) turned by angles theta (...)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], -1)


def _positive(v: np.ndarray) -> np.ndarray:
    """A length that must not be zero (the builder would not have chosen the operation)."""
    return np.where(v > 0.0, v, np.nan)


def _side(value: np.ndarray, size: np.ndarray) -> np.ndarray:
    """A dyad's assembly mode, +1 or -1: NaN where the sketch draws it straight (the builder
    refuses such a sketch, see ``_Builder._branch``)."""
    return np.where(np.abs(value) > _SKETCH_SINGULAR * size, np.sign(value), np.nan)


def _xy(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return v[..., 0], v[..., 1]


def _cross2(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _norm(v: np.ndarray) -> np.ndarray:
    return np.sqrt(v[..., 0] * v[..., 0] + v[..., 1] * v[..., 1])


class _Geometry:
    """A sketch as the recipes read it: the places of the named points (D, 2), the angles of
    the links (D,), the prismatic joints' axes in the sketch (D, 2) and the places of the
    points the plan adds (each at a named point's place)."""

    def __init__(self, m: Mechanism, xy: dict[str, np.ndarray], sources: dict[int, str],
                 axes: dict[str, np.ndarray] | None = None):
        self.m, self.xy, self.sources = m, xy, sources
        self.names = m.point_names
        D = len(next(iter(xy.values())))
        self.axes = {j.name: np.broadcast_to(np.asarray(j.axis, float), (D, 2))
                     for j in m.joints if j.type == "P"}
        self.axes.update(axes or {})
        self.theta = {link.name: self._link_angle(link) for link in m.links}
        span = np.stack(list(xy.values()), 1)                       # (D, points, 2)
        self.scale = np.maximum(np.ptp(span, axis=1).max(axis=-1), MIN_LENGTH)

    def _link_angle(self, link) -> np.ndarray:
        """A link's angle in the sketch (as ``sketch_angle``): from its first point to its
        second; a moving block with one point, the axis of the prismatic joint it slides in
        (else of the one it guides); a ground with one point, 0."""
        D = len(next(iter(self.xy.values())))
        if len(link.points) >= 2:
            return _angles(self.xy[link.points[1]] - self.xy[link.points[0]])
        prismatic = sorted((j for j in self.m.joints_of(link.name) if j.type == "P"),
                           key=lambda j: j.links[1] != link.name)
        if link.ground or not prismatic:
            return np.zeros(D)
        return _angles(self.axes[prismatic[0].name])

    def at(self, idx: int) -> np.ndarray:
        """The place of point idx (a named point, or one the plan added)."""
        return self.xy[self.names[idx] if idx < len(self.names) else self.sources[idx]]

    def axis(self, j: Joint) -> np.ndarray:
        """The direction of prismatic joint j's axis in the sketch, rad (D,)."""
        return _angles(self.axes[j.name])

    def unit(self, j: Joint) -> np.ndarray:
        """Prismatic joint j's axis in the sketch, a unit vector (D, 2)."""
        a = self.axes[j.name]
        return a / _norm(a)[..., None]

    def slide(self, j: Joint) -> np.ndarray:
        """The slide of prismatic joint j in the sketch: u . (point - origin)."""
        origin = j.origin or self.m.link(j.links[0]).points[0]
        u = self.unit(j)
        d = self.xy[j.point] - self.xy[origin]
        return u[..., 0] * d[..., 0] + u[..., 1] * d[..., 1]

    def local(self, link: str, idx: int, anchor: int) -> np.ndarray:
        """Point idx in the frame of link, from the link's anchor (D, 2)."""
        return _rotated(-self.theta[link], self.at(idx) - self.at(anchor))


class _Builder:
    def __init__(self, m: Mechanism):
        if m.space != "planar":
            raise ModelError(f"space: the planar kinematics engine needs a planar mechanism, "
                             f"got {shown(m.space)}; see kinelab.spatial for spatial ones")
        for j in m.joints:
            if j.type not in ("R", "P", "G", "C"):
                raise ModelError(f"joint '{j.name}': the planar kinematics engine handles R and P "
                                 f"joints, got {shown(j.type)} (and G joints, gear pairs, and C "
                                 "joints, cams); kinelab.structure counts its mobility")
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
        self.sources: dict[int, str] = {}          # a point the plan adds: the named point
        self.coincide: list[tuple[str, str]] = []  # named points at one place in the sketch
        self.recipes: list = []                    # per operation: its numbers from a sketch
        self.G = _Geometry(m, {n: xy[None, :] for n, xy in self.xy.items()}, self.sources)
        self.used: set[str] = set()
        self.const_points: list[int] = []
        for pn in m.link(self.ground).points:
            self._set_const(self.P[pn])
        self.anchor[self.ground] = self.P[m.link(self.ground).points[0]]
        self.slides = {j.name: i for i, j in enumerate(x for x in m.joints if x.type == "P")}
        self.gears = [gear_mesh(m, j) for j in m.joints if j.type == "G"]
        self.cams = [cam_pair(m, j) for j in m.joints if j.type == "C"]
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

    def constants(self, G: _Geometry) -> np.ndarray:
        """The values of the plan's constant items (D, 1 + 2 constant points): the ground's
        angle, then x and y of each point fixed in it."""
        ground = wrap_angle(G.theta[self.ground])
        return np.stack([ground] + [v for idx in self.const_points for v in _xy(G.at(idx))], -1)

    def inputs_at(self, G: _Geometry) -> np.ndarray:
        """The inputs' values at the sketch (D, M)."""
        def frame(link):
            return np.zeros_like(G.scale) if link == self.ground else G.theta[link]
        return np.stack([G.slide(rel[1]) if rel[0] == "slide" else frame(rel[2]) - frame(rel[1])
                         for rel in self.relations], -1)

    # -- emitting operations ---------------------------------------------------------------
    def _emit(self, ints, recipe=None) -> int:
        """Add an operation: its integer fields, and the recipe of its numbers (a function
        of a ``_Geometry`` returning each number for every sketch, see ``Plan.designs``)."""
        floats = [] if recipe is None else [float(np.reshape(v, -1)[0]) for v in recipe(self.G)]
        self.ops_i.append(list(ints) + [0] * (8 - len(ints)))
        self.ops_f.append(floats + [0.0] * (8 - len(floats)))
        self.recipes.append(recipe)
        return len(self.ops_i) - 1

    def _set_const(self, idx: int) -> None:
        self.const_points.append(idx)
        self.computed.add(idx)

    def _xy_of(self, idx: int) -> np.ndarray:
        return self.G.at(idx)[0]

    def anchor_xy(self, link: str) -> np.ndarray:
        return self._xy_of(self.anchor[link])

    def point_on(self, link: str, name: str) -> int:
        """Index of a point rigid with a placed link at the sketch place of the named point
        ``name`` (one of the link's own points there, or a point the plan adds)."""
        xy = self.xy[name]
        for pn in self.m.link(link).points:
            if np.allclose(self.xy[pn], xy, rtol=0, atol=1e-14 * self.scale):
                if pn != name:
                    self.coincide.append((pn, name))
                return self.P[pn]
        key = (link, float(xy[0]), float(xy[1]))
        if key not in self.virtual:
            idx = self._new_point(link, name)
            if link == self.ground:
                self._set_const(idx)
            else:
                self._emit_rigid(idx, link)
        else:
            first = self.sources[self.virtual[key]]
            if first != name:
                self.coincide.append((first, name))
        return self.virtual[key]

    def _new_point(self, link: str, name: str) -> int:
        idx = self.n_all
        self.n_all += 1
        self.virtual[(link, float(self.xy[name][0]), float(self.xy[name][1]))] = idx
        self.sources[idx] = name
        return idx

    def _farthest_known(self, link: str, exclude: int) -> tuple[float, int]:
        """(distance, index) of the computed point of a link farthest from its anchor."""
        a = self.anchor[link]
        a_xy = self._xy_of(a)
        known = [(float(np.hypot(*(self.xy[pn] - a_xy))), self.P[pn]) for pn in self.m.link(link).points
                 if self.P[pn] in self.computed and self.P[pn] not in (a, exclude)]
        return max(known, default=(0.0, -1))

    def _emit_rigid(self, idx: int, link: str, far: tuple[float, int] | None = None) -> None:
        """Emit the operation placing point idx rigid with a placed link.

        Through the anchor a and the known point b of the link farthest from it (``far``, if
        the caller keeps it), p = a + lam (b - a) + mu k x (b - a) needs no sine or cosine;
        a link with one known point (a crank on its pivot) turns r by its angle instead.
        """
        a = self.anchor[link]
        if far is None:
            far = self._farthest_known(link, idx)
        if far[0] > 1e-6 * self.scale:
            b = far[1]

            def frame_point(G):
                d, r = G.at(b) - G.at(a), G.at(idx) - G.at(a)
                d2 = d[..., 0] * d[..., 0] + d[..., 1] * d[..., 1]
                d2 = np.where(d2 > (1e-6 * G.scale) ** 2, d2, np.nan)   # as decided above
                return [(r[..., 0] * d[..., 0] + r[..., 1] * d[..., 1]) / d2, _cross2(d, r) / d2]
            self._emit([k.OP_FRAME_POINT, idx, a, b], frame_point)
        else:
            def rigid_point(G):
                r = G.local(link, idx, a)
                return [r[..., 0], r[..., 1]]
            self._emit([k.OP_RIGID_POINT, idx, self.L[link], a], rigid_point)

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
                self._emit_rigid(idx, link, far)
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
                o = self.point_on(g, j.point)
                self._emit([k.OP_SLIDE_OUT, self.slides[j.name], self.P[j.point], o, self.L[g]],
                           lambda G, j=j, g=g: [G.axis(j) - G.theta[g], G.slide(j)])
        redundant = tuple(j.name for j in m.joints if j.name not in self.used)
        idle = [n for n in redundant if m.joint(n).type == "C"]
        if idle:
            raise ModelError(f"cam joints {', '.join(map(repr, idle))}: the follower was placed by "
                             "other joints before its cam, so the cam would only be checked; "
                             "drive the cam (or a link that turns it), not the follower")
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
        for idx in self.const_points:
            const_items += [item(idx), item(idx) + 1]
        const_values = self.constants(self.G)[0].tolist()
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
            input_kinds=self.input_kinds, recipe=_Recipe(self))

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
                    self._emit([k.OP_DRIVE_ANGLE, self.L[other], base, mi], lambda G, s=sign: [s])
                    self.angle_known.add(other)
                    self.steps.append(Step("driven", (other,), (), f"'{other}' turned by input {mi}"))
                    progress = True
        for j in self.m.joints:
            if j.type != "P":
                continue
            for known, other in (j.links, j.links[::-1]):
                if known in self.angle_known and other not in self.angle_known:
                    self._emit([k.OP_LOCK_ANGLE, self.L[other], self.L[known]],
                               lambda G, a=other, b=known: [G.theta[a] - G.theta[b]])
                    self.angle_known.add(other)
                    self.steps.append(Step("locked", (other,), (j.name,),
                                           f"'{other}' keeps its angle to '{known}' (slide '{j.name}')"))
                    progress = True
        return self._cam_angles() | self._gear_angles() or progress

    def _cam_theta(self, G: _Geometry, c) -> np.ndarray:
        """The cam's angle relative to its guide at the sketch (the frame's: 0)."""
        return G.theta[c.cam] - (0.0 if c.guide == self.ground else G.theta[c.guide])

    def _cam_rows(self, c) -> int:
        """The program's table, after its cam operation: CAM_ROWS rows of 8 a piece."""
        for piece in c.table:
            for r in range(k.CAM_ROWS):
                self._emit([k.OP_CAM_DATA], lambda G, v=piece[8 * r:8 * r + 8]: list(v))
        return len(c.table)

    def _cam_angles(self) -> bool:
        """Oscillating followers: with the angles of the cam and its guide known, the
        follower's is the guide's plus ``c0 + S(theta)``, exactly, with its K and L."""
        progress = False
        for c in self.cams:
            if (c.motion != "oscillating" or c.joint in self.used or c.follower in self.angle_known
                    or not {c.cam, c.guide} <= self.angle_known):
                continue
            frame = c.guide == self.ground
            self._emit([k.OP_CAM, self.L[c.follower], self.L[c.cam],
                        -1 if frame else self.L[c.guide], len(c.table)],
                       lambda G, c=c, frame=frame: [
                           G.theta[c.follower] - (0.0 if frame else G.theta[c.guide])
                           - cam_values(c.table, self._cam_theta(G, c))[0]])
            self._cam_rows(c)
            self.angle_known.add(c.follower)
            self.used.add(c.joint)
            self.steps.append(Step("cam", (c.follower,), (c.joint,),
                                   f"follower '{c.follower}' turned by cam '{c.cam}' (cam "
                                   f"'{c.joint}')"))
            progress = True
        return progress

    def _place_cam(self, link: str) -> bool:
        """A translating follower sliding on a placed guide, its cam's angle known: its point
        on the slide line at ``t = S(theta) - S(theta_sketch)`` from the sketch."""
        for c in self.cams:
            if (c.motion != "translating" or c.follower != link or c.joint in self.used
                    or c.cam not in self.angle_known or c.guide not in self.pos_known):
                continue
            j = self.m.joint(c.follower_joint)
            if j.name in self.used:
                continue
            out = self.P[j.point]
            base = self.point_on(c.guide, j.point)
            frame = c.guide == self.ground
            self._emit([k.OP_CAM_SLIDE, out, base, self.L[c.guide], self.L[c.cam],
                        -1 if frame else self.L[c.guide], len(c.table)],
                       lambda G, j=j, c=c: [G.axis(j) - G.theta[c.guide],
                                            -cam_values(c.table, self._cam_theta(G, c))[0]])
            self._cam_rows(c)
            self.used.update((j.name, c.joint))
            self.place(link, out)
            self.steps.append(Step("cam", (link,), (c.joint, j.name),
                                   f"follower '{link}' driven by cam '{c.cam}' along '{j.name}' "
                                   f"(cam '{c.joint}')"))
            return True
        return False

    def _frame_theta(self, G: _Geometry, link: str) -> np.ndarray:
        """A link's angle at the sketch as the plan's items hold it (the ground's wrapped)."""
        return wrap_angle(G.theta[link]) if link == self.ground else G.theta[link]

    def _gear_angles(self) -> bool:
        """Gear pairs: with two of the angles of gear a, gear b and their carrier c known,
        the third follows from ``theta_b - k theta_a - (1 - k) theta_c = const`` (the
        constant from the sketch), exactly, with its K and L; a rack placed on a placed
        carrier gives its pinion's angle from the rack's slide."""
        progress = False
        for g in self.gears:
            if g.joint in self.used:
                continue
            if g.mesh == "rack":
                j = self.m.joint(g.slide)
                if (g.a in self.angle_known or g.b not in self.pos_known
                        or g.carrier not in self.pos_known):
                    continue
                guide = j.links[0]
                sl = len(self.L) + 2 * len(self.P) + self.slides[j.name]
                o = self.point_on(guide, j.point)
                self._emit([k.OP_SLIDE_OUT, self.slides[j.name], self.P[j.point], o, self.L[guide]],
                           lambda G, j=j, g=guide: [G.axis(j) - G.theta[g], G.slide(j)])
                r = g.k
                self._emit([k.OP_GEAR, self.L[g.a], sl, self.L[g.carrier]],
                           lambda G, g=g, j=j, r=r: [
                               self._frame_theta(G, g.a) - self._frame_theta(G, g.carrier)
                               - G.slide(j) / r, 1.0 / r, 1.0])
                out, x, y = g.a, g.b, g.carrier
            else:
                trio = (g.a, g.b, g.carrier)
                unknown = [n for n in trio if n not in self.angle_known]
                if len(unknown) != 1:
                    continue
                out = unknown[0]
                # theta_b - k theta_a - (1 - k) theta_c = const, solved for `out`
                coef = {g.a: -g.k, g.b: 1.0, g.carrier: g.k - 1.0}
                x, y = (n for n in trio if n != out)
                cx, cy = -coef[x] / coef[out], -coef[y] / coef[out]
                self._emit([k.OP_GEAR, self.L[out], self.L[x], self.L[y]],
                           lambda G, out=out, x=x, y=y, cx=cx, cy=cy: [
                               self._frame_theta(G, out) - cx * self._frame_theta(G, x)
                               - cy * self._frame_theta(G, y), cx, cy])
            self.angle_known.add(out)
            self.used.add(g.joint)
            self.steps.append(Step("gear", (out,), (g.joint,),
                                   f"'{out}' geared to '{x}' and '{y}' (gear '{g.joint}')"))
            progress = True
        return progress or self._gear_carrier()

    def _gear_carrier(self) -> bool:
        """Two spur pairs on one carrier through a middle gear (sun-planet-ring), both outer
        gears known and the middle gear and the carrier not: the two meshes make one relation
        of the outer gears, ``theta_2 = K theta_1 + (1 - K) theta_c + const`` with ``K`` the
        product of theirs (Willis' formula), which gives the carrier; the middle gear follows."""
        def toward(g, gear):
            """k of the mesh read from its other gear to ``gear``."""
            return g.k if gear == g.b else 1.0 / g.k
        spur = [g for g in self.gears if g.mesh != "rack" and g.joint not in self.used]
        for g1, g2 in itertools.permutations(spur, 2):
            if g1.carrier != g2.carrier or g1.carrier in self.angle_known:
                continue
            middle = ({g1.a, g1.b} & {g2.a, g2.b}) - self.angle_known
            if len(middle) != 1:
                continue
            mid = middle.pop()
            o1 = g1.a if g1.b == mid else g1.b
            o2 = g2.a if g2.b == mid else g2.b
            if o1 == o2 or not {o1, o2} <= self.angle_known:
                continue
            K = toward(g1, mid) * toward(g2, o2)
            if abs(1.0 - K) <= 1e-12:
                continue                 # the outer gears turn together: no carrier from them
            c = g1.carrier
            cx, cy = -K / (1.0 - K), 1.0 / (1.0 - K)
            self._emit([k.OP_GEAR, self.L[c], self.L[o1], self.L[o2]],
                       lambda G, c=c, o1=o1, o2=o2, cx=cx, cy=cy: [
                           self._frame_theta(G, c) - cx * self._frame_theta(G, o1)
                           - cy * self._frame_theta(G, o2), cx, cy])
            self.angle_known.add(c)
            self.used.add(g2.joint)      # its equation is in this step; g1's gives the middle
            self.steps.append(Step("gear", (c,), (g1.joint, g2.joint),
                                   f"carrier '{c}' from '{o1}' and '{o2}' (gears '{g1.joint}' and "
                                   f"'{g2.joint}', Willis)"))
            return True
        return False

    def _place_rack(self, link: str) -> bool:
        """A rack whose pinion's angle is known, sliding on a placed carrier: its point on the
        slide line at ``t = r ((theta_a - theta_c) - (theta_a - theta_c)_sketch)``."""
        for g in self.gears:
            if (g.mesh != "rack" or g.b != link or g.joint in self.used
                    or g.a not in self.angle_known or g.carrier not in self.pos_known):
                continue
            j = self.m.joint(g.slide)
            if j.name in self.used:
                continue
            guide = j.links[0]
            out = self.P[j.point]
            base = self.point_on(guide, j.point)
            r = g.k
            self._emit([k.OP_GEAR_SLIDE, out, base, self.L[guide], self.L[g.a], self.L[g.carrier]],
                       lambda G, j=j, guide=guide, g=g, r=r: [
                           G.axis(j) - G.theta[guide],
                           -r * (self._frame_theta(G, g.a) - self._frame_theta(G, g.carrier)), r, -r])
            self.used.update((j.name, g.joint))
            self.place(link, out)
            self.steps.append(Step("gear", (link,), (g.joint, j.name),
                                   f"rack '{link}' driven by pinion '{g.a}' along '{j.name}' "
                                   f"(gear '{g.joint}')"))
            return True
        return False

    def _driven_slide(self, j: Joint):
        for rel in self.relations:
            if rel[0] == "slide" and rel[1].name == j.name:
                return rel[2]
        return None

    def _free_joints(self, link: str):
        return [j for j in self.m.joints_of(link) if j.name not in self.used]

    def _partner(self, j: Joint, link: str) -> str:
        return j.links[1] if j.links[0] == link else j.links[0]

    def _line_for(self, link: str, j: Joint, name: str) -> tuple[int, int, object]:
        """The line a point of `link` (at the sketch place of point ``name``) moves on,
        sliding in P joint j on a placed partner: (point of the partner on that line, link
        giving its direction, the recipe of beta, its angle to that link)."""
        partner = self._partner(j, link)
        guide = j.links[0]
        o = self.point_on(partner, name)
        return o, self.L[guide], lambda G: G.axis(j) - G.theta[guide]

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
            self._emit([k.OP_TWO_POINTS, self.L[link], self.P[j1.point], self.P[j2.point]],
                       lambda G, link=link, a=j1.point, b=j2.point:
                       [G.theta[link] - _angles(G.xy[b] - G.xy[a])])
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
            if self._place_rack(link) or self._place_cam(link):
                return True
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
                if link == slider:
                    out = self.P[j.point]
                    base = self.point_on(guide, j.point)
                    sign = 1.0
                else:
                    base = self.P[j.point]
                    out = self._new_point(link, j.point)
                    sign = -1.0
                self._emit([k.OP_SLIDE_POINT, out, base, self.L[guide], mi],
                           lambda G, j=j, guide=guide, sign=sign:
                           [G.axis(j) - G.theta[guide], G.slide(j), sign])
                self.used.add(j.name)
                self.place(link, out)
                self.steps.append(Step("placed", (link,), (j.name,), f"'{link}' driven along '{j.name}'"))
                return True
            slides = [j for j in free if j.type == "P" and self._partner(j, link) in self.pos_known]
            if len(slides) >= 2:
                j1, j2 = slides[:2]
                first = self.m.link(link).points[0]
                o1, l1, b1 = self._line_for(link, j1, first)
                o2, l2, b2 = self._line_for(link, j2, first)
                out = self.P[first]
                op = self._emit([k.OP_LINES, out, o1, l1, o2, l2], lambda G: [b1(G), b2(G)])
                self.used.update((j1.name, j2.name))
                self.place(link, out)
                self.steps.append(Step("lines", (link,), (j1.name, j2.name),
                                       f"'{link}' placed by slides '{j1.name}' and '{j2.name}'", op))
                return True
        return False

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
        self._branch(d[0] * (Y - X)[1] - d[1] * (Y - X)[0], lb * float(np.linalg.norm(d)) + 1e-300,
                     f"the dyad '{b}'-'{c}' ({jx.point}-{j.point}-{jz.point})")

        def rrr(G, x=jx.point, y=j.point, z=jz.point):
            yx, yz, zx = G.xy[y] - G.xy[x], G.xy[y] - G.xy[z], G.xy[z] - G.xy[x]
            lb, lc = _norm(yx), _norm(yz)
            return [_positive(lb), _positive(lc), _side(_cross2(zx, yx), lb * _norm(zx)),
                    G.theta[b] - _angles(yx), G.theta[c] - _angles(yz)]
        op = self._emit([k.OP_RRR, self.L[b], self.L[c], self.P[jx.point], self.P[j.point], self.P[jz.point]],
                        rrr)
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
        o, g, beta = self._line_for(c, jp, j.point)
        axis = _angle(jp.axis)
        u = np.array([math.cos(axis), math.sin(axis)])
        self._branch(float(u @ (Y - X)), lb, f"the dyad '{b}'-'{c}' ({jx.point}-{j.point} "
                     f"and slide '{jp.name}')")

        def rrp(G, x=jx.point, y=j.point):
            yx, u = G.xy[y] - G.xy[x], G.unit(jp)
            lb = _norm(yx)
            return [_positive(lb), beta(G), _side(u[..., 0] * yx[..., 0] + u[..., 1] * yx[..., 1], lb),
                    G.theta[b] - _angles(yx)]
        op = self._emit([k.OP_RRP, self.L[b], self.P[jx.point], self.P[j.point], o, g], rrp)
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
        o1, l1, b1 = self._line_for(b, jb, j.point)
        o2, l2, b2 = self._line_for(c, jc, j.point)
        op = self._emit([k.OP_LINES, self.P[j.point], o1, l1, o2, l2], lambda G: [b1(G), b2(G)])
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
        self._branch(float(u @ (X - Z)), float(np.linalg.norm(X - Z)),
                     f"the dyad '{G}'-'{S}' (slide '{j.name}' between {jz.point} and {jx.point})")

        def rpr(Geo, x=jx.point, z=jz.point):
            xz, u = Geo.xy[x] - Geo.xy[z], Geo.unit(j)
            rho = _rotated(-Geo.theta[G], xz)
            ul = _rotated(-Geo.theta[G], u)
            return [rho[..., 0], rho[..., 1], ul[..., 0], ul[..., 1],
                    _side(u[..., 0] * xz[..., 0] + u[..., 1] * xz[..., 1], _positive(_norm(xz)))]
        # G's angle comes from the op; its anchor Z is known
        op = self._emit([k.OP_RPR, self.L[G], self.P[jx.point], self.P[jz.point]], rpr)
        self._emit([k.OP_LOCK_ANGLE, self.L[S], self.L[G]],
                   lambda Geo: [Geo.theta[S] - Geo.theta[G]])
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
            if j.type in ("G", "C") or j.name in self.used or not (set(j.links) & group):
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
        cammed = [c.joint for c in self.cams
                  if c.joint not in self.used and {c.cam, c.follower, c.guide} & set(free)]
        if cammed:
            raise ModelError(
                f"cam joints {', '.join(repr(n) for n in cammed)}: a cam joint is solved once its "
                "cam's angle and its guide are known, and the inputs leave links "
                f"{', '.join(repr(n) for n in free)} undetermined; drive the cam (or a link that "
                "turns it), not the follower")
        geared = [g.joint for g in self.gears
                  if g.joint not in self.used and {g.a, g.b, g.carrier} & set(free)]
        if geared:
            raise ModelError(
                f"gear joints {', '.join(repr(n) for n in geared)}: a gear pair is solved once two "
                "of the angles of its gears and its carrier are known, and the inputs leave links "
                f"{', '.join(repr(n) for n in free)} with fewer; drive the carrier or one gear of "
                "each pair (an epicyclic train: two of sun, arm and ring, or the arm and the planet)")
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
        """A Newton group's tables: its anchors, the integer rows of its constraints, and the
        recipe of their numbers and of the group's unknowns at the sketch (``x0``): a
        function of a ``_Geometry`` returning (rows of numbers (D, n, 8), x0 (D, 3 links))."""
        gi = {n: i for i, n in enumerate(links)}
        anchors = [self.P[self.m.link(n).points[0]] for n in links]
        for n, a in zip(links, anchors):
            self.anchor[n] = a
        rows_i, makers = [], []

        def side(link, name):
            """(group link, known point, link item, recipe of the point in the group link's
            frame) of one side of a constraint at the sketch place of point ``name``."""
            if link in gi:
                first = self.m.link(link).points[0]
                return gi[link], -1, self.L[link], \
                    lambda G: _rotated(-G.theta[link], G.xy[name] - G.xy[first])
            return -1, self.point_on(link, name), self.L[link], lambda G: np.zeros_like(G.xy[name])

        for c in cons:
            if c[0] == "joint":
                j, mi = c[1], c[2]
                g1, p1, l1, r1 = side(j.links[0], j.point)
                g2, p2, l2, r2 = side(j.links[1], j.point)
                if j.type == "R":
                    rows_i.append([k.C_REVOLUTE, g1, p1, l1, g2, p2, l2, 0])
                    makers.append(lambda G, r1=r1, r2=r2: [*_xy(r1(G)), *_xy(r2(G))])
                else:
                    guide, slider = j.links
                    rows_i.append([k.C_PRISMATIC, g1, p1, l1, g2, p2, l2, 0])
                    makers.append(lambda G, r1=r1, r2=r2, j=j, guide=guide, slider=slider:
                                  [*_xy(r1(G)), *_xy(r2(G)), G.axis(j) - G.theta[guide],
                                   G.theta[slider] - G.theta[guide]])
                    if mi is not None:
                        rows_i.append([k.C_DRIVE_SLIDE, g1, p1, l1, g2, p2, l2, mi])
                        makers.append(lambda G, r1=r1, r2=r2, j=j, guide=guide:
                                      [*_xy(r1(G)), *_xy(r2(G)), G.axis(j) - G.theta[guide],
                                       G.slide(j)])
            else:
                _, a, b, mi = c
                ga = gi.get(a, -1)
                gb = gi.get(b, -1)
                la = -1 if a == self.ground else self.L[a]
                lb = -1 if b == self.ground else self.L[b]
                rows_i.append([k.C_DRIVE_ANGLE, ga, -1, la, gb, -1, lb, mi])
                makers.append(lambda G: [1.0])
        firsts = [self.m.link(n).points[0] for n in links]

        def numbers(G):
            D = len(G.theta[links[0]])
            rows = np.zeros((D, len(makers), 8))
            for r, make in enumerate(makers):
                for col, v in enumerate(make(G)):
                    rows[:, r, col] = v
            x0 = np.stack([v for n, f in zip(links, firsts)
                           for v in (G.xy[f][..., 0], G.xy[f][..., 1], G.theta[n])], -1)
            return rows, x0
        rows_f, x0 = numbers(self.G)
        return anchors, np.array(rows_i, np.int64).reshape(-1, 8), rows_f[0], x0[0], numbers

    def _sketch_jacobian(self, links, cons) -> np.ndarray:
        """Jacobian of the constraints `cons` with respect to the poses of `links`, at the
        sketch (rows: equations, columns: x, y, theta of each link)."""
        saved = (len(self.ops_i), dict(self.virtual), dict(self.sources), list(self.coincide),
                 self.n_all, list(self.const_points), set(self.computed), dict(self.anchor))
        try:
            _, ci, cf, x0, _ = self._group_tables(links, cons)
            pt = np.array([self._xy_of(i) for i in range(self.n_all)], float).reshape(-1, 2)
            ang = np.array([self.theta_s[name] for name in self.m.link_names])
        finally:
            (nops, virtual, sources, coincide, self.n_all, self.const_points, self.computed,
             self.anchor) = saved
            self.virtual = virtual
            self.sources.clear()                 # the geometry reads this very mapping
            self.sources.update(sources)
            self.coincide = coincide
            del self.ops_i[nops:]
            del self.ops_f[nops:]
            del self.recipes[nops:]
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
        anchors, ci, cf, x0, numbers = self._group_tables(links, cons)
        gid = len(self.groups)
        self.groups.append((links, anchors, ci, cf, x0, numbers))
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
        for names, anchors, c_i, c_f, x, _ in self.groups:
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
    (used to check the closed forms against the general engine).  Gear joints (``G``) and
    cam joints (``C``) are solved in closed form only (a gear pair's relation is linear in
    the angles; a follower moves by its cam's program): a mechanism with them has no Newton
    plan.
    """
    if method == "newton" and isinstance(m, Mechanism) and any(j.type == "G" for j in m.joints):
        raise ModelError(f"method: 'newton' puts every link in Newton groups, which do not take gear "
                         f"joints ({', '.join(repr(j.name) for j in m.joints if j.type == 'G')}); "
                         "use method='auto': a gear pair's relation is linear in the angles and "
                         "is solved exactly in closed form")
    if method == "newton" and isinstance(m, Mechanism) and any(j.type == "C" for j in m.joints):
        raise ModelError(f"method: 'newton' puts every link in Newton groups, which do not take cam "
                         f"joints ({', '.join(repr(j.name) for j in m.joints if j.type == 'C')}); "
                         "use method='auto': a cam joint is solved exactly in closed form from its "
                         "cam's angle")
    b = _Builder(m)
    if method == "newton":
        b._dyad = lambda: False          # type: ignore[method-assign]
        b._place_single = lambda: False  # type: ignore[method-assign]
        b._propagate_angles = lambda: False  # type: ignore[method-assign]
    elif method != "auto":
        raise ModelError(f"method: expected one of 'auto', 'newton', got {shown(method)}")
    return b.build()
