"""Position, velocity and acceleration analysis of any planar mechanism."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab import _compiled
from kinelab import _memory as memory
from kinelab.errors import AssemblyError, ModelError, check_choice, describe, shown
from kinelab.kinematics import _codes as k
from kinelab.kinematics._codes import SINGULAR_TOL
from kinelab.kinematics._assemble import check_assembled
from kinelab.kinematics._branches import (MAX_PERIODS, BranchMap, ChangePoint, branch_map,
                                          branched_ops)
from kinelab.kinematics._columns import INPUT_SI_UNITS
from kinelab.kinematics._input_errors import SingularInput, UnreachableInput
from kinelab.kinematics._evaluate import PARALLEL_FROM, outputs
from kinelab.kinematics._evaluate import run as _run
from kinelab.kinematics._plan import Plan, build_plan
from kinelab.kinematics._solution import DesignSolution, KinematicSolution
from kinelab.model import MAX_LENGTH, MAX_RATE, Mechanism, gear_mesh, real_array
from kinelab.solvers import bisect, wrap_angle
from kinelab.solvers._arguments import number, whole

__all__ = ["analyze", "analyze_designs", "plan", "reachable_ranges", "turns_fully",
           "change_points", "assembly_status", "AssemblyStatus"]

_NOTHING = np.empty(0, np.int64)   # items written out where only the status matters

def plan(mechanism: Mechanism, *, method: Literal["auto", "newton"] = "auto") -> Plan:
    """The solution plan of a mechanism: how its position problem is decomposed.

    ``plan(m).steps`` lists the groups (driven links, dyads RRR/RRP/RPR/PRP, Newton
    groups) in the order they are solved.  Plans are cached on the mechanism.
    """
    if not isinstance(mechanism, Mechanism):
        raise ModelError(f"mechanism: expected a kinelab Mechanism, got {type(mechanism).__name__}; "
                         "build one with kinelab.mechanisms or kinelab.load")
    check_choice("method", method, ("auto", "newton"))
    cache = mechanism.__dict__.setdefault("_plans", {})
    if method not in cache:
        check_assembled(mechanism)
        cache[method] = build_plan(mechanism, method=method)
    return cache[method]


def _finite(name: str, value: ArrayLike) -> np.ndarray:
    """``value`` as a new C-ordered float array of finite numbers (the solution keeps it, so
    a caller who changes their own array afterwards must not change it)."""
    if type(value) is float and math.isfinite(value):       # one number: the common case
        return np.array(value)
    a = real_array(value)                                     # a copy
    if a is None:
        raise ModelError(f"{name}: expected numbers, got {describe(value)}")
    if not np.isfinite(a).all():
        bad = np.argwhere(~np.isfinite(a))[0].tolist()
        raise ModelError(f"{name}: expected finite numbers, got {a[tuple(bad)]}"
                         + (f" at index {bad}" if bad else ""))
    return a if a.flags.c_contiguous else a.copy(order="C")


def _rates(name: str, value: ArrayLike, M: int, shape: tuple[int, ...]) -> np.ndarray:
    """Rates of the inputs as rows (N, M) like q, or (1, M) when one row holds for all."""
    a = _finite(name, value)
    if a.ndim == 0:
        return np.full((1, M), float(a))
    if a.shape == shape:
        return a.reshape(-1, M)
    try:
        b = np.broadcast_to(a, shape).reshape(-1, M)
    except ValueError:
        raise ModelError(f"{name}: shape {a.shape} does not match q's shape {shape}") from None
    return np.array(b[:1] if b.strides[0] == 0 else b, dtype=float, order="C")


# The largest input values: an angle within a million turns of 0, where float64 still
# resolves it to 1e-9 rad (a sweep's range in a model file keeps to MAX_TURNS; a long motion
# goes further); a slide within MAX_LENGTH; rates within MAX_RATE (accelerations take the
# square of a speed).
INPUT_TURNS = 1_000_000
MAX_SEARCH_SAMPLES = 1_000_000    # samples of a turn a search for limit positions may take
Q_LIMITS = {"angle": INPUT_TURNS * 2 * math.pi, "slide": MAX_LENGTH}
_SMALL_SWEEP = 2 * PARALLEL_FROM        # samples below which a sweep runs on one thread


def _within_limits(p: Plan, q2: np.ndarray, qd2: np.ndarray, qdd2: np.ndarray) -> None:
    """Refuse input values beyond the model's limits (q by each input's kind)."""
    kinds = p.input_kinds
    q_limits = [Q_LIMITS[k] for k in kinds]
    for name, a, limits in (("q", q2, q_limits), ("qd", qd2, None), ("qdd", qdd2, None)):
        if a.size <= 64:            # a few values (one configuration): Python is quicker
            ok = all(abs(v) <= (MAX_RATE if limits is None else limits[k])
                     for row in a.tolist() for k, v in enumerate(row))
        else:
            ok = bool((np.abs(a) <= (MAX_RATE if limits is None else np.array(limits))).all())
        if ok:
            continue
        over = ~(np.abs(a) <= (MAX_RATE if limits is None else np.array(limits)))
        i, k = np.argwhere(over)[0]
        unit = INPUT_SI_UNITS[kinds[k]] + ("" if name == "q" else "/s" if name == "qd" else "/s^2")
        what = (f"angles within {INPUT_TURNS:,} turns of 0 either way (beyond, float64 "
                "resolves them to worse than 1e-9 rad)" if name == "q" and kinds[k] == "angle"
                else f"at most {(MAX_RATE if limits is None else limits[k]):g} {unit} in size")
        where = f" at index {[int(i), int(k)] if len(kinds) > 1 else int(i)}" if a.size > 1 else ""
        raise ModelError(f"{name}: expected {what}, got {a[i, k]:g}{where}")


def _normalise_q(q, qd, qdd, M: int, p: Plan):
    """q (N, M), qd and qdd (N, M) or (1, M), all new arrays within the limits of the
    plan ``p``'s inputs, and whether q was one sample."""
    if M == 1 and type(qd) is float and type(qdd) is float and abs(qd) <= MAX_RATE \
            and abs(qdd) <= MAX_RATE:
        # the common call, one input swept at a constant rate: checked in a few operations
        # (NaN fails every comparison, and goes on to the checks below, which name it)
        limit = Q_LIMITS[p.input_kinds[0]]
        if type(q) is float:
            if abs(q) <= limit:
                return np.array([[q]]), np.array([[qd]]), np.array([[qdd]]), True
        elif type(q) is np.ndarray and q.dtype == np.float64 and q.ndim == 1 and q.size \
                and -limit <= q.min() and q.max() <= limit:
            return q.reshape(-1, 1).copy(), np.array([[qd]]), np.array([[qdd]]), False
    qa = _finite("q", q)
    if M == 1:
        if qa.ndim > 1:
            raise ModelError(f"q: expected shape () or (N,) for a mechanism with one input, got {qa.shape}")
        single = qa.ndim == 0
    else:
        if qa.ndim not in (1, 2) or qa.shape[-1] != M:
            raise ModelError(f"q: expected shape ({M},) or (N, {M}) for a mechanism with {M} "
                             f"inputs, got {qa.shape}")
        single = qa.ndim == 1
    q2, qd2, qdd2 = qa.reshape(-1, M), _rates("qd", qd, M, qa.shape), _rates("qdd", qdd, M, qa.shape)
    _within_limits(p, q2, qd2, qdd2)
    return q2, qd2, qdd2, single


def _per_sample(rates: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """Rates of shape (N, M) as given, or their single row as a read-only (N, M) view."""
    if rates.shape == shape:
        return rates
    # np.broadcast_to's view, made directly (it takes ten times as long)
    view = np.ndarray(shape, rates.dtype, rates, 0, (0, rates.strides[1] if shape[1] > 1 else 0))
    view.flags.writeable = False
    return view


def change_points(mechanism: Mechanism, lo: float, hi: float, *,
                  at_change_point: Literal["smooth", "switch"] = "smooth") -> tuple[ChangePoint, ...]:
    """The change points of a one-input mechanism with input between ``lo`` and ``hi``.

    A change point is a configuration where the two assembly modes of a dyad meet and the
    input can go on: there det J = 0, and the motion may continue on either branch (see
    :func:`analyze`'s ``at_change_point``).  Found by following the mechanism from its
    sketch; for mechanisms solved in closed form.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)  # parallelogram
    >>> cps = kl.kinematics.change_points(fb, 0.0, 2 * np.pi)
    >>> np.degrees([c.q for c in cps]).round(6) + 0.0, cps[0].links
    (array([  0., 180., 360.]), ('coupler', 'rocker'))
    """
    p = plan(mechanism)
    check_choice("at_change_point", at_change_point, ("smooth", "switch"))
    lo, hi = number("lo", lo), number("hi", hi)
    limit = Q_LIMITS[p.input_kinds[0]]
    for name, v in (("lo", lo), ("hi", hi)):
        if abs(v) > limit:
            raise ModelError(f"{name}: expected an input within {limit:g} "
                             f"{INPUT_SI_UNITS[p.input_kinds[0]]} of 0, got {v:g}")
    bmap = _branch_map(p, len(mechanism.inputs), at_change_point)
    if bmap is None:
        return ()
    if bmap.periods(lo, hi) > MAX_PERIODS:
        raise ModelError(f"lo, hi: a range of {bmap.periods(lo, hi):,} turns of the change points' "
                         f"pattern; ask for at most {MAX_PERIODS:,} at a time (the pattern "
                         f"repeats every {bmap.period:.6g} {INPUT_SI_UNITS[p.input_kinds[0]]})")
    return bmap.change_points(lo, hi)


@dataclass(frozen=True)
class AssemblyStatus:
    """Whether a mechanism assembles at each input value, and where it is singular.

    Attributes
    ----------
    assembled, singular : ndarray of bool, shape (N,)
    singularity : ndarray, shape (N,)
        The distance from singularity of :class:`KinematicSolution` (NaN where it does not
        assemble).
    """

    assembled: np.ndarray
    singular: np.ndarray
    singularity: np.ndarray


def assembly_status(mechanism: Mechanism, q: ArrayLike, *, method: Literal["auto", "newton"] = "auto",
                    at_change_point: Literal["smooth", "switch"] = "smooth") -> AssemblyStatus:
    """Where a mechanism assembles and where it is singular, over the input values ``q``,
    without keeping its coordinates: the check of a sweep, in memory of a few bytes per
    sample whatever the size of the mechanism.  The same branches as :func:`analyze`.

    Examples
    --------
    >>> rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    >>> kl.kinematics.assembly_status(rocker, [0.0, 1.0, 2.0]).assembled.tolist()
    [True, True, False]
    """
    p = plan(mechanism, method=method)
    M = len(mechanism.inputs)
    check_choice("at_change_point", at_change_point, ("smooth", "switch"))
    q2, qd2, qdd2, _ = _normalise_q(q, 0.0, 0.0, M, p)
    out = _solve(p, _branch_map(p, M, at_change_point), q2, qd2, qdd2, stored=_NOTHING)
    ok = out["status"] == k.ST_OK
    measure = np.where(ok, out["diag"][:, 1], np.nan)
    return AssemblyStatus(ok, ok & (measure < SINGULAR_TOL), measure)


def _require_results(p: Plan, shape: tuple[int, ...], M: int) -> None:
    """Refuse a sweep whose results (and copies of its inputs) exceed the memory budget."""
    N = math.prod(shape[:-1] if M > 1 and len(shape) > 1 else shape)
    n = len(p.stored_items)
    nbytes = N * (8 * n * (3 + M + M * M) + 24 * M + 41)
    if nbytes > memory.memory_budget():          # (the message only then)
        memory.require(nbytes, f"the results of {N:,} samples ({n} coordinates each, with K, "
                       "L and rates)", "analyse fewer samples at a time (a sweep in pieces "
                       "continues with start=)")


def _run_small(p: Plan, q, qd, qdd):
    """The analysis of a sweep of one input at constant rates on one thread, a plan in
    closed form without change points, in one call of the compiled kernel
    (``run_small_one_input``: the checks of q, its copy, the samples, and which samples do
    not assemble and which are singular); None for anything else, or inputs beyond the
    limits (the general checks name them).  The numbers are those of the general path, to
    the bit: the same kernel runs the samples."""
    if not (p.groups is None and type(qd) is float and type(qdd) is float
            and abs(qd) <= MAX_RATE and abs(qdd) <= MAX_RATE):
        return None
    if type(q) is float:
        qs, single = np.array([q]), True
    elif (type(q) is np.ndarray and q.dtype == np.float64 and q.ndim == 1 and q.size
          and q.flags.c_contiguous):
        qs, single = q, False
    else:
        return None
    if len(qs) >= _SMALL_SWEEP or not _compiled.ready("closed_form_one_input"):
        return None
    done = run_small(p, qs, qd, qdd)
    return None if done is None else (done[0], np.array([[qd]]), np.array([[qdd]]), single,
                                      *done[1:])


def run_small(p: Plan, q: np.ndarray, qd: float, qdd: float):
    """The compiled kernel's ``run_small_one_input`` at the inputs q (N,): q (N, 1), the
    outputs, which samples assemble and which are singular, how many of each; or None where
    an input is beyond the limits."""
    from kinelab.kinematics import _kernel
    N = len(q)
    q2 = np.empty((N, 1))
    _, stored, out = outputs(p, q2)
    assembled, singular = np.empty(N, bool), np.empty(N, bool)
    checked, failed, flagged = _kernel.run_small_one_input(
        q, qd, qdd, Q_LIMITS[p.input_kinds[0]], p.ops_i, p.ops_f, p.const_items,
        p.const_values, p.n_items, p.n_angles, stored, SINGULAR_TOL, q2, out["jets"],
        out["rates"], out["diag"], out["status"], out["fail"], assembled, singular)
    return (q2, out, assembled, singular, failed, flagged) if checked else None


def _branch_map(p: Plan, M: int, followed: str) -> BranchMap | None:
    """The change points to follow, for a one-input plan in closed form that has any."""
    key = ("branch map", followed)
    if key not in p.memo:
        bmap = None
        if M == 1 and p.groups is None and branched_ops(p):
            bmap = branch_map(p, followed)
        p.memo[key] = None if bmap is None or bmap.trivial else bmap
    return p.memo[key]


def _solve(p: Plan, bmap: BranchMap | None, q, qd, qdd, resume=None, stored=None):
    """The kernel's outputs at every sample, each on the branch the analysis follows there
    (the change points of ``bmap``; for Newton plans, a turn away when continuation does
    not reach it directly)."""
    out = (_run_branches(p, bmap, q, qd, qdd, stored) if bmap is not None
           else _run(p, q, qd, qdd, resume, stored=stored))
    if p.groups is not None and p.input_kinds == ("angle",) and resume is None:
        _a_turn_away(p, out, q, qd, qdd, stored)
    return out


def _run_branches(p: Plan, bmap: BranchMap, q, qd, qdd, stored=None):
    """Run the kernel with each sample on its own branch: the samples that share the signs
    of their dyads in one call each."""
    index, tables = bmap.variants(q[:, 0])
    used = np.unique(index)
    if len(used) == 1:
        return _run(p, q, qd, qdd, ops_f=tables[int(used[0])], stored=stored)
    out = None
    for v in used.tolist():
        rows = np.flatnonzero(index == v)
        part = _run(p, q[rows], qd if len(qd) == 1 else qd[rows],
                    qdd if len(qdd) == 1 else qdd[rows], ops_f=tables[v], stored=stored)
        if out is None:
            out = {key: np.empty((len(q),) + a.shape[1:], a.dtype) for key, a in part.items()}
        for key, a in part.items():
            out[key][rows] = a
    return out


def _a_turn_away(p: Plan, out, q, qd, qdd, stored=None) -> None:
    """Newton plans: samples that continuation from the sketch did not reach, solved at the
    same crank angle a whole number of turns away, inside the interval it does reach (an
    arc of a crank that cannot turn fully may straddle the end of the swept window, as the
    closed forms see at once: they depend on the angle modulo a turn)."""
    bad = np.flatnonzero(out["status"] != k.ST_OK)
    if not bad.size:
        return
    lo, hi = _continued_range(p, float(p.q_sketch[0]), math.pi, 721)
    turn = 2 * math.pi
    shifted = q[bad, 0] + turn * np.ceil((lo - q[bad, 0]) / turn)
    inside = shifted <= hi
    if not inside.any():
        return
    rows, shifted = bad[inside], shifted[inside]
    order = np.argsort(shifted)
    rows, shifted = rows[order], shifted[order]
    again = _run(p, shifted[:, None], qd if len(qd) == 1 else qd[rows],
                 qdd if len(qdd) == 1 else qdd[rows], stored=stored)
    good = again["status"] == k.ST_OK
    for key in ("jets", "rates", "diag", "status", "fail"):
        out[key][rows[good]] = again[key][good]


def _unreachable(p: Plan, mechanism: Mechanism, method: str, out, q, bad: np.ndarray) -> UnreachableInput:
    """The error of an analysis whose samples ``bad`` do not assemble (or cannot be reached)."""
    i = int(bad[0])
    gap, op = out["fail"][i]
    step = p.step_of_op(int(op))
    reach = reachable_ranges(mechanism, method=method) if len(p.input_kinds) == 1 else None
    return UnreachableInput(step.label if step is not None else f"operation {int(op)}", q[i],
                            p.input_kinds, stalled=out["status"][i] != k.ST_NO_ASSEMBLY,
                            gap=float(gap), reachable=reach)


def reachable_ranges(mechanism: Mechanism, *, samples: int = 1441,
                     method: Literal["auto", "newton"] = "auto") -> list[tuple[float, float]]:
    """Input intervals where a one-input mechanism assembles on its sketch's branch.

    Angle inputs are searched over one turn centred on the sketch, slides over +-10 sizes
    of the mechanism; each bound is refined by bisection to 1e-12.  A full turn is
    reported as ``[(q0 - pi, q0 + pi)]`` (see :func:`turns_fully`), and an angle interval
    that the search window cuts at q0 +- pi comes back whole, reaching below q0 - pi.  With
    closed-form groups every interval of the search is reported; with Newton groups, the
    one continuation reaches from the sketch.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    >>> [tuple(round(v, 5) for v in r) for r in kl.kinematics.reachable_ranges(fb)]  # cos q >= -0.3125
    [(-1.88862, 1.88862)]
    """
    p = plan(mechanism, method=method)
    samples = whole("samples", samples, 3, MAX_SEARCH_SAMPLES)
    if len(p.input_kinds) != 1:
        raise ModelError("reachable_ranges: the mechanism has "
                         f"{len(p.input_kinds)} inputs; it is defined for one")
    q0 = float(p.q_sketch[0])
    half = math.pi if p.input_kinds[0] == "angle" else 10.0 * p.scale
    if p.groups is not None:
        return [_continued_range(p, q0, half, samples)]
    grid = np.linspace(q0 - half, q0 + half, samples)
    ok = _assembles(p, grid)
    if ok.all():
        return [(q0 - half, q0 + half)]
    edges = np.flatnonzero(np.diff(ok.astype(np.int8)))
    lo_ok, hi_ok = grid[edges], grid[edges + 1]
    inside = ok[edges]          # True: the bound is between an assembled sample and a failing one
    a = np.where(inside, lo_ok, hi_ok)   # assembled side
    b = np.where(inside, hi_ok, lo_ok)   # failing side
    a, b = bisect(lambda x: _assembles(p, x), a, b)
    bounds = list(zip(edges.tolist(), a.tolist()))
    ranges = []
    start = q0 - half if ok[0] else None
    for e, v in bounds:
        if ok[e] and not ok[e + 1]:
            ranges.append((start, v))
            start = None
        else:
            start = v
    if start is not None:
        ranges.append((start, q0 + half))
    if p.input_kinds[0] == "angle" and len(ranges) >= 2 and ok[0] and ok[-1]:
        # the window's two ends are one angle: the first and last pieces are one interval
        ranges = [(ranges[-1][0] - 2 * math.pi, ranges[0][1])] + ranges[1:-1]
    return [(float(lo), float(hi)) for lo, hi in ranges]


def turns_fully(mechanism: Mechanism, ranges: list[tuple[float, float]]) -> bool:
    """Whether ``ranges`` (from :func:`reachable_ranges`) say that the mechanism's one
    input is an angle that turns a full turn."""
    spans = real_array(ranges)
    if spans is None or spans.ndim != 2 or spans.shape[1] != 2 or not np.isfinite(spans).all():
        raise ModelError(f"ranges: expected input intervals [(lo, hi), ...] as "
                         f"reachable_ranges gives them, got {describe(ranges)}")
    return (plan(mechanism).input_kinds == ("angle",) and len(spans) == 1
            and bool(spans[0, 1] - spans[0, 0] >= 2 * math.pi - 1e-12))


def _continued_range(p: Plan, q0: float, half: float, samples: int) -> tuple[float, float]:
    """The input interval around the sketch that continuation reaches (Newton plans): one
    sweep outwards each way.  Where a Newton group stops converging, continuation has
    already halved its step down to 1e-9 of it: the input it reached is the bound.  Where a
    closed-form group cannot close, it stopped at once: bisect from the input reached."""
    bounds = []
    for sign in (-1.0, 1.0):
        path = q0 + sign * np.linspace(0.0, half, samples // 2 + 1)
        q = path.reshape(-1, 1)
        out = _run(p, q, np.zeros_like(q), np.zeros_like(q), stored=_NOTHING)
        status = out["status"]
        if (status == k.ST_OK).all():
            bounds.append(float(path[-1]))
            continue
        reached = float(out["state"][0][0])
        if status[np.argmax(status != k.ST_OK)] == k.ST_NO_CONVERGENCE:
            bounds.append(reached)
            continue
        i = int(np.argmax(status != k.ST_OK))
        a, _ = bisect(lambda x: _assembles(p, x), np.array([reached]), path[i:i + 1])
        bounds.append(float(a[0]))
    return min(bounds), max(bounds)


def _assembles(p: Plan, qs: np.ndarray) -> np.ndarray:
    """Whether each input value assembles (on its own: no continuation between them)."""
    if p.groups is None:
        q = np.ascontiguousarray(qs.reshape(-1, 1))
        out = _run(p, q, np.zeros_like(q), np.zeros_like(q), stored=_NOTHING)
        return out["status"] == k.ST_OK
    # Newton groups: continuation from the sketch to each value separately
    res = np.empty(qs.shape, bool)
    for i, v in enumerate(qs):
        q = np.array([[v]])
        out = _run(p, q, np.zeros_like(q), np.zeros_like(q), stored=_NOTHING)
        res[i] = out["status"][0] == k.ST_OK
    return res


# How far from a singular configuration a flagged sample may be: a change point is flagged
# within about SINGULAR_TOL of it (the measure grows like the distance), a limit position
# within about SINGULAR_TOL**2 (like its square root); in rad, or sizes for a slide.
_CHANGE_POINT_ZONE = 10 * SINGULAR_TOL
_LIMIT_ZONE = 10 * SINGULAR_TOL ** 2


def singular_kind(mechanism: Mechanism, q, method: str = "auto",
                  at_change_point: str = "smooth") -> dict:
    """What kind of singular configuration the input values ``q`` (M,) flagged singular are
    next to, as :class:`SingularInput` takes it: a change point (two assembly modes cross:
    ``links``), a limit position (the input's reach ends: ``reachable``), or neither.  Known
    for mechanisms of one input: change points of closed forms, limit positions of every
    plan."""
    p = plan(mechanism, method=method)
    if len(p.input_kinds) != 1:
        return {}
    v = float(q[0])
    unit = 1.0 if p.input_kinds[0] == "angle" else p.scale
    bmap = _branch_map(p, 1, at_change_point)
    if bmap is not None:
        near = bmap.change_points(v - _CHANGE_POINT_ZONE * unit, v + _CHANGE_POINT_ZONE * unit)
        if near:
            nearest = min(near, key=lambda c: abs(c.q - v))
            return dict(kind="change point", links=nearest.step, at=nearest.q)
    ranges = reachable_ranges(mechanism, method=method)
    if ranges and not turns_fully(mechanism, ranges):
        bound = min((b for span in ranges for b in span), key=lambda b: abs(v - b))
        if abs(v - bound) <= _LIMIT_ZONE * unit:
            return dict(kind="limit position", reachable=ranges, at=bound)
    return {}


def _check_redundant(p: Plan, sol: KinematicSolution):
    """Joints the plan did not need must stay closed on their own (parallelogram links)."""
    m = p.mechanism
    ok = sol.assembled
    tol = 1e-9 * p.scale
    xy = {pt.name: np.array([pt.x, pt.y]) for pt in m.points}

    def position(point):
        i = p.point_item[point]
        return sol.item_jets([i, i + 1])[:, :, 0]

    def angle(link):
        i = p.link_item[link]
        return sol.item_jets([i])[:, 0, 0] - p.sketch_angles[i]

    def seen_from(link, point):
        ref = next((n for n in m.link(link).points if n != point), None)
        if ref is None:
            return position(point)
        rel = xy[point] - xy[ref]
        c, s = np.cos(angle(link)), np.sin(angle(link))
        return position(ref) + np.stack([c * rel[0] - s * rel[1], s * rel[0] + c * rel[1]], -1)

    for name in p.redundant:
        j = m.joint(name)
        if j.type == "R":
            err = np.linalg.norm(seen_from(j.links[0], j.point) - seen_from(j.links[1], j.point), axis=-1)
        elif j.type == "G":
            # its ratio, on the velocity coefficients: the phase holds at the sketch, so a
            # ratio kept along the motion keeps the relation; angles are stored wrapped, and
            # a ratio that is not whole cannot be checked across the wrap (m per unit input)
            g = gear_mesh(m, j)
            M = len(m.inputs)

            def K(link):
                return sol.item_jets([p.link_item[link]])[:, 0, 1:1 + M]
            turn = K(g.a) - K(g.carrier)
            moved = (sol.item_jets([p.slide_item[g.slide]])[:, 0, 1:1 + M] if g.mesh == "rack"
                     else (K(g.b) - K(g.carrier)) * p.scale)
            err = np.max(np.abs(moved - g.k * turn * (1.0 if g.mesh == "rack" else p.scale)), -1)
        else:
            g, s_ = j.links
            dang = np.abs(wrap_angle(angle(s_) - angle(g))) * p.scale
            th = angle(g) + math.atan2(j.axis[1], j.axis[0])
            d = seen_from(s_, j.point) - seen_from(g, j.point)
            err = np.maximum(dang, np.abs(-np.sin(th) * d[:, 0] + np.cos(th) * d[:, 1]))
        bad = np.flatnonzero(ok & (err > tol))
        if bad.size:
            i = int(bad[0])
            raise AssemblyError(
                f"joint '{name}' is redundant (not needed to place any link) and does not stay "
                f"closed: it opens by {err[i]:.3g} m at sample {i}; the geometry is not the "
                "special one (e.g. a parallelogram) that keeps it closed; fix the sketch or remove "
                "the joint", loop=name, gap=float(err[i]))


def analyze(mechanism: Mechanism, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0, *,
            unreachable: Literal["raise", "mask"] = "raise",
            at_singular: Literal["auto", "raise", "flag"] = "auto",
            method: Literal["auto", "newton"] = "auto",
            start: KinematicSolution | None = None,
            at_change_point: Literal["smooth", "switch"] = "smooth") -> KinematicSolution:
    """Position, velocity and acceleration of every link, point and slide.

    The position equations Phi(q, S) = 0 are solved group by group (see
    :func:`kinelab.kinematics.plan`); the velocity coefficients ``K = dS/dq = -J^-1 Q``
    and acceleration coefficients ``L = dK/dq`` come from the same Jacobians, exactly.
    Then ``S' = K q'`` and ``S'' = K q'' + q'^T L q'``.

    Parameters
    ----------
    mechanism : Mechanism
    q : float or array_like, shape () or (N,); (M,) or (N, M) when M > 1
        Input coordinates, rad (angle inputs, within a million turns of 0) or m (slides,
        within 1e9 m).
    qd, qdd : float or array_like, broadcast to the shape of q
        Input velocities (rad/s or m/s) and accelerations, each at most 1e100 in size.
    unreachable : {"raise", "mask"}
        Where the loops cannot close: raise :class:`~kinelab.errors.AssemblyError` (naming
        the group, the gap and, for one input, the reachable range) or mark the sample in
        ``sol.assembled`` and fill it with NaN.
    at_singular : {"auto", "raise", "flag"}
        At a singular configuration (det J = 0) velocities are undefined: "flag" marks the
        sample in ``sol.singular`` (its K, L, velocities and accelerations are NaN),
        "raise" raises :class:`~kinelab.errors.SingularityError`; "auto" raises for a single
        configuration and flags within a sweep.
    method : {"auto", "newton"}
        "auto" solves dyads in closed form and the rest by Newton-Raphson; "newton" uses the
        general Newton engine for every group (to cross-check).
    at_change_point : {"smooth", "switch"}
        Where two assembly modes of a dyad meet and the input can go on (a change point: a
        parallelogram four-bar at 0 and 180 degrees), go on along the branch whose K and L
        continue ("smooth": the parallelogram stays a parallelogram) or along the other one
        ("switch": it becomes an antiparallelogram).  Followed for one-input mechanisms
        solved in closed form, from the sketch to each input value; the change points within
        the sweep are in ``sol.change_points``.
    start : KinematicSolution, optional
        An earlier analysis of the same mechanism: Newton groups continue from where it
        ended (its last assembled sample) instead of from the sketch, so a sweep can be run
        in pieces, or a simulation can follow the motion step by step, on the branch it is
        on.  Closed-form groups need no start and ignore it.

    Returns
    -------
    KinematicSolution

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> kl.analyze(sc, q=0.0).position("B")          # dead centre: crank + rod
    array([4., 0.])
    >>> kl.analyze(sc, q=np.linspace(0.1, np.pi - 0.1, 5)).position("B").shape
    (5, 2)
    >>> sol = kl.analyze(sc, q=np.pi / 2, qd=10.0)
    >>> float(sol.K("slide")), float(sol.slide_velocity("slide"))     # dx/dq = -R at 90 deg
    (-1.0, -10.0)
    """
    p = plan(mechanism, method=method)
    M = len(mechanism.inputs)
    if unreachable not in ("raise", "mask"):
        raise ModelError(f"unreachable: expected one of 'raise', 'mask', got {shown(unreachable)}")
    check_choice("at_change_point", at_change_point, ("smooth", "switch"))
    if at_singular not in ("auto", "raise", "flag"):
        raise ModelError(f"at_singular: expected one of 'auto', 'raise', 'flag', got {shown(at_singular)}")
    try:
        shape = np.shape(q)
    except ValueError:                           # ragged nesting: refused below, not numbers
        shape = None
    if shape is not None:
        _require_results(p, shape, M)            # before anything of that size is made
    bmap = _branch_map(p, M, at_change_point)
    quick = _run_small(p, q, qd, qdd) if start is None and bmap is None and M == 1 else None
    if quick is not None:
        q2, qd2, qdd2, single, out, ok, singular, failed, flagged = quick
    else:
        q2, qd2, qdd2, single = _normalise_q(q, qd, qdd, M, p)
        resume = None
        if start is not None:
            if not isinstance(start, KinematicSolution) or start.mechanism != mechanism:
                raise ModelError("start: expected an earlier KinematicSolution of this mechanism")
            if p.groups is not None:
                # the state must be of this plan's Newton groups (another method solves others)
                if start.newton_state is None or start.plan.groups is None or not all(
                        np.array_equal(a, b) for a, b in zip(start.plan.groups, p.groups)):
                    raise ModelError("start: the earlier analysis used another method; analyze "
                                     "with the same method to continue from it")
                resume = start.newton_state
        out = _solve(p, bmap, q2, qd2, qdd2, resume)
        ok = out["status"] == k.ST_OK
        failed = np.count_nonzero(out["status"])
        singular = flagged = None
    jets, rates, diag = out["jets"], out["rates"], out["diag"]
    if failed:                                   # some sample did not assemble
        bad = np.flatnonzero(~ok)
        if unreachable == "raise":
            raise _unreachable(p, mechanism, method, out, q2, bad)
        jets[bad] = np.nan
        rates[bad] = np.nan
        diag[bad] = np.nan
        if singular is None:
            singular = ok & (diag[:, 1] < SINGULAR_TOL)
    elif singular is None:
        singular = diag[:, 1] < SINGULAR_TOL
    if flagged is None:
        flagged = np.count_nonzero(singular)
    if flagged:
        policy = at_singular if at_singular != "auto" else ("raise" if single else "flag")
        if policy == "raise":
            i = int(np.flatnonzero(singular)[0])
            raise SingularInput(q2[i], p.input_kinds, det=float(diag[i, 0]),
                                **singular_kind(mechanism, q2[i], method, at_change_point))
        jets[singular, :, 1:] = np.nan
        rates[singular] = np.nan
    sol = KinematicSolution._made(
        plan=p, q=q2, qd=_per_sample(qd2, q2.shape), qdd=_per_sample(qdd2, q2.shape),
        stored_jets=jets, stored_rates=rates,
        det_J=diag[:, 0], singularity=diag[:, 1], singular=singular, assembled=ok,
        single=single, newton_state=out.get("state"),
        change_points=bmap.change_points(float(q2.min()), float(q2.max())) if bmap else (),
        certificate=None, constants=None)
    if p.redundant:
        _check_redundant(p, sol)
    return sol


def analyze_designs(mechanism: Mechanism, points: ArrayLike, q: ArrayLike, qd: ArrayLike = 0.0,
                    qdd: ArrayLike = 0.0, *, axes=None,
                    method: Literal["auto", "newton"] = "auto") -> DesignSolution:
    """Position, velocity and acceleration of D designs of one mechanism's topology, each over
    its samples, in one run of the kernel.

    A design is the mechanism drawn with other dimensions: its own sketch, the places of
    the mechanism's points (and, where they differ, the directions of its prismatic joints'
    axes).  Every design keeps the mechanism's links, joints and inputs, and the mechanism's
    plan (``plan(mechanism).steps``); its sketch gives its links' lengths, its points'
    places on them, its dyads' assembly modes and its inputs' values there.  So the plan is made once, and each design's numbers come
    from its sketch in a few array operations (``Plan.designs``).

    Parameters
    ----------
    mechanism : Mechanism
        The topology, and the design whose sketch fixes the plan.
    points : array_like, shape (D, P, 2), or mapping of point name to (D, 2)
        The designs' sketches: the places of the mechanism's P points (in the order of
        ``mechanism.points``), m.
    q : array_like, shape (N,) or (N, M) for the same inputs for every design, or (D, N) or
        (D, N, M), each design its own
        Input values, rad or m.
    qd, qdd : array_like
        Input rates, broadcast to the shape of q.
    axes : mapping of str to array_like (D, 2) or (2,), optional
        The designs' prismatic joints' axes in their sketches, by joint name (default the
        mechanism's).
    method : {"auto", "newton"}
        As :func:`analyze`.

    Returns
    -------
    DesignSolution
        Accessors of shape (D, N, ...); samples where a design's loops do not close are
        marked in ``assembled`` (and NaN), singular ones in ``singular``.  Each design stays
        on its sketch's assembly modes: a change point is not followed (an input exactly at
        one is flagged singular), and Newton groups follow each design's samples from its
        sketch, in the order given.

    Raises
    ------
    ModelError
        Points or inputs of the wrong shape, or a mechanism with redundant joints (a
        parallelogram's extra link, which each design's sketch would have to keep closed:
        analyse those one at a time).

    Examples
    --------
    Three slider-cranks with cranks of 1.0, 1.2 and 1.4 (rod 3): their sketches moved, B
    where each closes with the crank upright.

    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> r = np.array([1.0, 1.2, 1.4])
    >>> xy = np.array([[[0, 0], [0, c], [np.sqrt(9 - c * c), 0]] for c in r])
    >>> [p.name for p in sc.points]
    ['O2', 'A', 'B']
    >>> sol = kl.kinematics.analyze_designs(sc, xy, q=np.radians([0.0, 90.0]))
    >>> sol.slide("slide").round(6)          # B at crank + rod, then at sqrt(rod^2 - crank^2)
    array([[4.      , 2.828427],
           [4.2     , 2.749545],
           [4.4     , 2.6533  ]])
    """
    p = plan(mechanism, method=method)
    if p.redundant:
        raise ModelError(f"mechanism: its joints {', '.join(repr(n) for n in p.redundant)} are "
                         "redundant (they close only in its sketch's special geometry); "
                         "analyse its designs one at a time with kl.analyze")
    numbers = p.designs(points, axes)
    D, M = len(numbers), len(mechanism.inputs)
    qa = _finite("q", q)
    per_design = qa.ndim == (3 if M > 1 else 2)
    if not (qa.ndim == (1 if M == 1 else 2) or per_design) or (M > 1 and qa.shape[-1] != M):
        want = "(N,) or (D, N)" if M == 1 else f"(N, {M}) or (D, N, {M})"
        raise ModelError(f"q: expected shape {want} for {D} designs of a mechanism with {M} "
                         f"input(s), got {qa.shape}")
    if per_design and qa.shape[0] != D:
        raise ModelError(f"q: expected the inputs of {D} designs along its first axis, got "
                         f"{qa.shape[0]}")
    shape = qa.shape if per_design else (D,) + qa.shape
    qa = np.broadcast_to(qa, shape)
    n = shape[1]
    _require_results(p, (D * n,) + (shape[2:] if M > 1 else ()), M)
    flat = (-1,) if M == 1 else (-1, M)

    def rates(name, value):
        a = _finite(name, value)
        if a.ndim == 0:
            return a
        try:
            return np.broadcast_to(a, shape).reshape(flat)
        except ValueError:
            raise ModelError(f"{name}: shape {a.shape} does not match q's shape {shape}") from None
    q2, qd2, qdd2, _ = _normalise_q(qa.reshape(flat), rates("qd", qd), rates("qdd", qdd), M, p)
    out = _run(p, q2, qd2, qdd2, designs=numbers)
    jets, rates, diag = out["jets"], out["rates"], out["diag"]
    ok = out["status"] == k.ST_OK
    ok &= np.repeat(numbers.valid, n)
    jets[~ok] = np.nan
    rates[~ok] = np.nan
    diag[~ok] = np.nan
    singular = ok & (diag[:, 1] < SINGULAR_TOL)
    jets[singular, :, 1:] = np.nan
    rates[singular] = np.nan
    return DesignSolution(
        plan=p, q=q2, qd=_per_sample(qd2, q2.shape), qdd=_per_sample(qdd2, q2.shape),
        stored_jets=jets, stored_rates=rates, det_J=diag[:, 0], singularity=diag[:, 1],
        singular=singular, assembled=ok, single=False,
        constants=numbers.const_values, designs=D, valid=numbers.valid)
