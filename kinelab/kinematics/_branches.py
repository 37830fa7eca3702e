"""Change points: where two assembly modes of a dyad meet and the input can go on.

A closed-form dyad (RRR, RRP, RPR) has two assembly modes, told apart by a sign sigma that
the plan reads off the sketch.  Where the dyad passes through its straight (flattened)
position while the rest of the mechanism keeps moving, the two modes meet: a parallelogram
four-bar at 0 and 180 degrees, every change-point four-bar once a turn, a slotted link whose
crank pin passes through the lever pivot.  Through such a *change point* the motion that
continues smoothly (the one whose K and L continue) is on the *other* sign: keeping sigma
fixed would turn a parallelogram into an antiparallelogram.

This module finds the change points by following the mechanism from its sketch, one input
value at a time on a grid, and records where each dyad's sign flips.  The signed measure
of a dyad (the sine of its transmission-type angle, positive on its sketch's side) touches
zero at a change point with a V shape; Newton's method on its arm finds where, and the
branch is chosen by comparing K and L on both sides.  The result is a :class:`BranchMap`:
for any input value, which signs the dyads have there.  For an angle input that turns a
full turn, the map repeats after one or more turns (a change-point four-bar needs two turns
to come back to its sketch), so it covers every input value with bounded work.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from kinelab.kinematics import _codes as k
from kinelab.kinematics._evaluate import run
from kinelab.kinematics._plan import SIGN_FIELDS, Plan
from kinelab.solvers import wrap_angle

__all__ = ["ChangePoint", "BranchMap", "branch_map"]


_GRID_STEP = math.pi / 360        # rad (angle inputs); slides: this times the mechanism's size
_MEETS = 1e-6                     # a signed measure this small where it touches zero: the
                                  # modes meet (lengths that close to a change-point geometry)
_MAX_TURNS = 8                    # turns followed before the map must have repeated
MAX_PERIODS = 10_000              # periods of a map over which its change points are listed
_SLIDE_REACH = 20.0               # slides are followed this many sizes from the sketch


@dataclass(frozen=True)
class ChangePoint:
    """A configuration where two assembly modes of a dyad meet and the input goes on.

    Attributes
    ----------
    q : float
        The input value there, rad (or m for a slide).
    step : str
        The dyad whose modes meet, as ``plan(m).steps`` names it.
    links : tuple of str
        Its two links.
    followed : {"smooth", "switch"}
        Which way the analysis went on: on the branch whose K and L continue ("smooth"), or
        on the other one ("switch", asked for with ``at_change_point="switch"``).
    """

    q: float
    step: str
    links: tuple[str, ...]
    followed: Literal["smooth", "switch"]


@dataclass(frozen=True)
class _Event:
    q: float
    op: int
    after: np.ndarray       # ops_f beyond the event, in the direction of the walk
    resume: float           # where the walk goes on: just beyond the change point


@dataclass(frozen=True)
class BranchMap:
    """The dyads' signs at every input value, by continuation from the sketch.

    ``up`` lists the events above the sketch's input ``q0`` in increasing order, ``down``
    those below it in decreasing order; each event's ``after`` holds the plan parameters
    beyond it.  With ``period`` (angle inputs that turn fully), the map repeats: the signs
    at q are those at q0 + ((q - q0) mod period), and ``down`` is empty.
    """

    plan: Plan
    q0: float
    up: tuple[_Event, ...]
    down: tuple[_Event, ...]
    period: float | None
    followed: Literal["smooth", "switch"]

    @property
    def trivial(self) -> bool:
        return not self.up and not self.down

    def variants(self, q: np.ndarray) -> tuple[np.ndarray, list[np.ndarray]]:
        """For each input value of ``q`` (N,), the index of its plan parameters in the list
        returned beside it.  A value at a change point (to 1e-10) takes the parameters of
        the side above it, on which the kernel places a folded dyad."""
        tables = [self.plan.ops_f] + [e.after for e in self.up] + [e.after for e in self.down]
        tol = 1e-10 * (1.0 + np.abs(q))
        up = [e.q for e in self.up]
        if self.period is not None:
            r = self.q0 + np.mod(q - self.q0, self.period)
            return np.searchsorted(up, r + tol, side="right"), tables
        n_up = np.searchsorted(up, q + tol, side="right")
        n_down = np.searchsorted([-e.q for e in self.down], -q - tol, side="left")
        index = np.where(q > self.q0, n_up, np.where(n_down > 0, len(self.up) + n_down, 0))
        return index, tables

    def periods(self, lo: float, hi: float) -> int:
        """How many periods of the map the inputs from lo to hi span (0 for a map with none)."""
        return 0 if self.period is None else math.ceil((hi - lo) / self.period)

    def change_points(self, lo: float, hi: float) -> tuple[ChangePoint, ...]:
        """The change points with lo <= q <= hi (to 1e-9, as they are located to about
        1e-12), in increasing q; none over more than MAX_PERIODS periods (a sweep of
        many thousand turns does not list them: the caller who asks says so)."""
        lo, hi = lo - 1e-9 * (1 + abs(lo)), hi + 1e-9 * (1 + abs(hi))
        found = []
        if self.period is not None:
            first = math.floor((lo - self.q0) / self.period) - 1
            last = math.ceil((hi - self.q0) / self.period) + 1
            if self.periods(lo, hi) > MAX_PERIODS:
                return ()
            for turn in range(first, last + 1):
                found += [(e.q + turn * self.period, e.op) for e in self.up]
        else:
            found = [(e.q, e.op) for e in self.up + self.down]
        out = []
        for q, op in sorted(found):
            if lo <= q <= hi:
                step = self.plan.step_of_op(op)
                out.append(ChangePoint(float(q), step.label if step else f"operation {op}",
                                       step.links if step else (), self.followed))
        return tuple(out)


def branched_ops(p: Plan) -> list[int]:
    """The operations of a plan that carry an assembly-mode sign."""
    return [i for i, row in enumerate(p.ops_i) if int(row[0]) in SIGN_FIELDS]


def branch_map(p: Plan, followed: Literal["smooth", "switch"] = "smooth") -> BranchMap:
    """The change points of a one-input closed-form plan, cached on its mechanism."""
    cache = p.mechanism.__dict__.setdefault("_branch_maps", {})
    key = (id(p), followed)
    if key not in cache:
        cache[key] = _Walker(p, followed).map()
    return cache[key]


class _Walker:
    def __init__(self, p: Plan, followed: str):
        self.p = p
        self.followed = followed
        self.ops = branched_ops(p)
        self.items = np.array(sorted({i for op in self.ops for i in _measured_items(p, op)}),
                              np.int64)
        self.column = {int(item): j for j, item in enumerate(self.items)}
        self.is_angle = self.items < p.n_angles
        self.q0 = float(p.q_sketch[0])
        self.angle = p.input_kinds[0] == "angle"
        self.h = _GRID_STEP * (1.0 if self.angle else p.scale)

    # -- evaluation ------------------------------------------------------------------------
    def evaluate(self, ops_f: np.ndarray, q: np.ndarray):
        """(assembled, measures, slopes, jets) at the input values q: for each branched
        operation its signed measure and the measure's derivative with respect to q, and the
        jets (value, K, L) of the coordinates they are read from (only those are written)."""
        q2 = np.ascontiguousarray(np.reshape(q, (-1, 1)), float)
        zero = np.zeros((1, 1))
        out = run(self.p, q2, zero, zero, ops_f=ops_f, stored=self.items)
        ok = out["status"] == k.ST_OK
        J = out["jets"]
        J[~ok] = np.nan                       # what the kernel left there means nothing
        m = np.full((len(q2), len(self.ops)), np.nan)
        dm = np.full_like(m, np.nan)
        with np.errstate(invalid="ignore", divide="ignore"):   # K is not finite at a
            for c, op in enumerate(self.ops):                   # singular configuration
                m[:, c], dm[:, c] = _measure(self.p, op, ops_f, J, self.column)
        return ok, m, dm, J

    # -- the walk ---------------------------------------------------------------------------
    def map(self) -> BranchMap:
        p = self.p
        if not self.ops:
            return BranchMap(p, self.q0, (), (), None, self.followed)
        if self.angle:
            up, closed = self.walk(+1.0, self.q0 + _MAX_TURNS * 2 * math.pi, periodic=True)
            if closed is not None:
                return BranchMap(p, self.q0, tuple(e for e in up if e.q < self.q0 + closed),
                                 (), closed, self.followed)
            up = tuple(e for e in up if e.q <= self.q0 + 2 * math.pi)   # a limit was met
            down, _ = self.walk(-1.0, self.q0 - 2 * math.pi, periodic=False)
            return BranchMap(p, self.q0, up, tuple(down), None, self.followed)
        reach = _SLIDE_REACH * p.scale
        up, _ = self.walk(+1.0, self.q0 + reach, periodic=False)
        down, _ = self.walk(-1.0, self.q0 - reach, periodic=False)
        return BranchMap(p, self.q0, tuple(up), tuple(down), None, self.followed)

    def walk(self, sign: float, limit: float, periodic: bool):
        """Follow the motion from the sketch towards ``limit``: the events met, and (for a
        periodic walk) the period after which the signs are the sketch's again."""
        events: list[_Event] = []
        ops_f = self.p.ops_f.copy()
        start = self.q0
        turn_end = self.q0 + 2 * math.pi
        while sign * (limit - start) > 0:
            stop = turn_end if periodic else limit
            n = max(2, int(math.ceil(abs(stop - start) / self.h)) + 1)
            grid = start + sign * np.linspace(0.0, abs(stop - start), n)
            ok, m, dm, _ = self.evaluate(ops_f, grid)
            reached = n if ok.all() else int(np.argmin(ok))
            event = self.first_event(ops_f, grid[:reached], m[:reached], dm[:reached], sign)
            if event is not None:
                if sign * (event.resume - start) <= 0 or len(events) > 64 * _MAX_TURNS:
                    return events, None       # no progress: give up following (never seen)
                events.append(event)
                ops_f = event.after
                start = event.resume
                continue
            if reached < n:                 # a limit position: the motion ends here
                return events, None
            if not periodic:
                return events, None
            if np.array_equal(ops_f, self.p.ops_f):
                return events, turn_end - self.q0
            start, turn_end = turn_end, turn_end + 2 * math.pi
            if turn_end > limit + 1e-9:
                return events, None
        return events, None

    def first_event(self, ops_f, grid, m, dm, sign):
        """The first change point along the grid (or None).

        A dyad's signed measure m keeps the sign of its branch; where |m| falls towards zero
        at one grid point and rises from it at the next, it may touch zero in between with a
        V: a change point (a smooth minimum that stays above zero is not one).  A grid point
        may also fall on the change point itself, where |m| is zero to rounding.
        """
        if len(grid) < 2:
            return None
        falling = np.sign(m) * dm * sign          # d|m| along the walk
        candidates = []
        for c in range(m.shape[1]):
            at = np.flatnonzero(np.abs(m[:, c]) <= _MEETS)
            candidates += [(int(i), c, True) for i in at]
            pair = np.flatnonzero((falling[:-1, c] < 0) & (falling[1:, c] > 0))
            candidates += [(int(i), c, False) for i in pair]
        for i, c, on_grid in sorted(candidates):
            if on_grid:
                slope = self.slope(grid, dm, i, c)
                event = self.choose(ops_f, self.locate(ops_f, float(grid[i]), c, slope), c, sign,
                                    slope)
            else:
                event = self.refine(ops_f, grid, m[:, c], dm[:, c], i, c, sign)
            if event is not None:
                return event
        return None

    @staticmethod
    def slope(grid, dm, i, c):
        """The measure's slope next to grid point i (its own is not defined there)."""
        near = [dm[j, c] for j in (i - 1, i + 1) if 0 <= j < len(grid) and math.isfinite(dm[j, c])]
        return max((abs(float(v)) for v in near), default=1.0)

    def refine(self, ops_f, grid, m, dm, i, c, sign):
        """Newton's method on the signed measure of operation ``c`` from grid point i, where
        |m| falls, towards grid point i + 1: a V-shaped zero between them is a change point."""
        lo, hi = sorted((grid[i], grid[i + 1]))
        pad = 1e-9 * (hi - lo)
        q, mq, dmq = float(grid[i]), float(m[i]), float(dm[i])
        if not (math.isfinite(dmq) and dmq != 0.0):
            return None                   # a grid point on the change point: seen on its own
        slope = abs(dmq)
        for _ in range(30):
            step = -mq / dmq
            q_new = q + step
            if not lo - pad <= q_new <= hi + pad:
                return None
            q = q_new
            okq, mq_a, dmq_a, _ = self.evaluate(ops_f, np.array([q]))
            if not okq[0]:
                return None
            mq, dmq = float(mq_a[0, c]), float(dmq_a[0, c])
            if abs(mq) <= _MEETS:         # below this, rounding in the dyad's square root
                break                     # makes the measure noise: locate() polishes q
            if not (math.isfinite(dmq) and dmq != 0.0):
                break
            slope = abs(dmq)
        if not abs(mq) <= _MEETS:
            return None
        return self.choose(ops_f, self.locate(ops_f, q, c, slope), c, sign, slope)

    def locate(self, ops_f, q, c, slope):
        """The change point to about 1e-10: where the measure, which is zero there only to
        the square root of rounding, falls on one side and rises on the other, the secant
        through two points 1e-5 of it away (accurate there) meets zero."""
        d = 1e-5 / max(slope, 1e-300)
        ok, m, _, _ = self.evaluate(ops_f, np.array([q - d, q + d]))
        if not ok.all() or not (np.isfinite(m[:, c]).all() and m[0, c] * m[1, c] > 0):
            return q
        left, right = abs(float(m[0, c])), -abs(float(m[1, c]))
        return q - d + 2 * d * left / (left - right)

    def choose(self, ops_f, q_star, c, sign, slope):
        """At a change point, the parameters on the far side: the branch whose coordinates,
        K and L continue those on the near side ("smooth"), or the other one ("switch").
        (Positions count too: a lever whose pin crosses its pivot has the same K on both
        branches, which differ by a half turn.)"""
        op = self.ops[c]
        flipped = ops_f.copy()
        flipped[op, SIGN_FIELDS[int(self.p.ops_i[op, 0])]] *= -1.0
        slope = slope if math.isfinite(slope) and slope > 0.0 else 1.0
        delta = min(2e-2 / slope, self.h / 4)
        before, after = q_star - sign * delta, q_star + sign * delta
        ok_b, _, _, jb = self.evaluate(ops_f, np.array([before]))
        if not ok_b[0]:
            return None
        scores = []
        for cand in (ops_f, flipped):
            ok_a, _, _, ja = self.evaluate(cand, np.array([after]))
            if not ok_a[0]:
                scores.append(math.inf)
                continue
            with np.errstate(invalid="ignore", over="ignore"):
                dq = after - before
                S_pred = jb[0, :, 0] + jb[0, :, 1] * dq + 0.5 * jb[0, :, 2] * dq * dq
                K_pred = jb[0, :, 1] + jb[0, :, 2] * dq
                gap = ja[0, :, 0] - S_pred
                gap = np.where(self.is_angle, wrap_angle(gap), gap / self.p.scale)
                miss = (np.abs(gap) / abs(dq) + np.abs(ja[0, :, 1] - K_pred)
                        + abs(dq) * np.abs(ja[0, :, 2] - jb[0, :, 2]))
            scores.append(float(np.sum(miss[np.isfinite(miss)])))
        if not any(math.isfinite(s) for s in scores):
            return None
        smooth = int(np.argmin(scores))
        pick = smooth if self.followed == "smooth" else 1 - smooth
        if not math.isfinite(scores[pick]):
            pick = smooth
        return _Event(float(q_star), op, (ops_f, flipped)[pick], float(after))


def _measured_items(p: Plan, op: int) -> tuple[int, ...]:
    """The coordinates (kernel items) the signed measure of a branched operation is read from."""
    row = p.ops_i[op]
    kind = int(row[0])
    if kind == k.OP_RRR:
        return int(row[1]), int(row[2])
    if kind == k.OP_RRP:
        return int(row[1]), int(row[5])
    return int(row[1]), int(row[2]), int(row[2]) + 1, int(row[3]), int(row[3]) + 1


def _measure(p: Plan, op: int, ops_f: np.ndarray, J: np.ndarray,
             column: dict[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """Signed measure of a branched operation (positive on its sign's side, zero where its
    dyad is straight) and its derivative with respect to the input, per sample, from the
    jets J (N, items, 3) of the coordinates ``column`` maps."""
    row, f = p.ops_i[op], ops_f[op]
    kind = int(row[0])

    def value(item):
        j = J[:, column[int(item)]]
        return j[:, 0], j[:, 1]

    if kind == k.OP_RRR:                    # sin of the angle from r_b to r_c
        tb, kb = value(row[1])
        tc, kc = value(row[2])
        d = (tc - f[4]) - (tb - f[3])
        return np.sin(d), np.cos(d) * (kc - kb)
    if kind == k.OP_RRP:                    # cos of the angle from the slide to the arm
        tb, kb = value(row[1])
        tg, kg = value(row[5])
        d = (tb - f[3]) - (tg + f[1])
        return np.cos(d), -np.sin(d) * (kb - kg)
    # RPR: the slide of X along the turning line from the foot of Z, over |X - Z| at the sketch
    tG, kG = value(row[1])
    (xx, kxx), (xy, kxy) = value(row[2]), value(int(row[2]) + 1)
    (zx, kzx), (zy, kzy) = value(row[3]), value(int(row[3]) + 1)
    wx, wy, dwx, dwy = xx - zx, xy - zy, kxx - kzx, kxy - kzy
    tu = tG + math.atan2(f[3], f[2])
    ux, uy = np.cos(tu), np.sin(tu)
    rho = math.hypot(f[0], f[1])
    t = wx * ux + wy * uy
    dt = dwx * ux + dwy * uy + kG * (-wx * uy + wy * ux)
    return t / rho, dt / rho
