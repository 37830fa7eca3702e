"""The routes that recompute a kinematic analysis, and its certificate.

Every number of a :class:`~kinelab.kinematics.KinematicSolution` -- link angles, point
positions, slides, K, L, velocities and accelerations -- is computed again by routes that
share none of the analysis' arithmetic:

- **loop closure**, at every sample: each link keeps its shape (every point where the link's
  angle and first point put it), each prismatic joint keeps its point on its guide's line,
  the two links' relative angle, and its slide;
- **the Newton engine** (``method="newton"``: every group by Newton-Raphson in absolute
  coordinates, with continuation), or the closed form when the analysis was the Newton
  engine's;
- **the symbolic derivation**: the loop equations of :mod:`kinelab.derive` differentiated
  by sympy, evaluated at the analysis' S (see :mod:`kinelab.verify._symbolic`);
- **finite differences**: central differences of the positions for K and of K for L, at
  steps h and h/2 combined by Richardson extrapolation.

The last three run on every sample up to :data:`SAMPLES`; beyond, on an evenly spread
subset of that many plus up to :data:`NEAR_SAMPLES` of the samples nearest a singular
configuration (singularity below :data:`NEAR_SINGULAR`), the nearest first.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from kinelab import kinematics
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._codes import NEWTON_TOL
from kinelab.solvers import wrap_angle
from kinelab.verify._certificate import Certificate, Comparison, Quantity

__all__ = ["certify_kinematics", "checked_samples", "SAMPLES", "NEAR_SAMPLES", "NEAR_SINGULAR"]

EVERY = 1000
"""Every sample of a sweep up to this many is checked by every route."""
STRIDE = 128
"""Beyond :data:`EVERY`, the symbolic derivation and finite differences check one sample in
this many, evenly spread (at most :data:`SAMPLES`): their cost, some 50 closed-form samples
each (six analyses per input, sympy's expressions evaluated, the comparisons), then stays
within the plain analysis' own."""
NEWTON_EVERY, NEWTON_STRIDE = 200, 1024
"""The Newton engine, when it is the second engine (about 50 times the closed form's time
per sample, following the sweep by continuation), checks every sample up to the first, one
in the second beyond."""
SAMPLES = 2000
"""The most samples of the evenly spread subset of a route."""
NEAR_SINGULAR = 0.05
"""Singularity measure (the sine of a transmission-type angle, see
``KinematicSolution.singularity``) below which a sample of a large sweep is checked too."""
NEAR_SAMPLES = 500
"""At most this many samples near a singular configuration are added to a subset, the
nearest first."""

EPS = np.finfo(float).eps
H0 = 1e-3
"""Largest finite-difference step (rad, or sizes for a slide input), far from singular
configurations: Richardson's error ~ h^4 S^(5) is then ~1e-12, rounding ~ eps |S| / h ~ 1e-12."""
S_REF = 0.3
"""Below this singularity measure the step shrinks as s^2: near a limit position the input
is about s^2 from it, and the stencil must stay well inside that distance."""

CLOSURE_BOUND = 1e-10
ENGINE_FLOOR = 1e-10      # the contract between the closed form and the Newton engine
AMPLIFIED = 100 * NEWTON_TOL   # what 1/s^2 (K) and 1/s^3 (L) amplify: the Newton engine's
                               # last step, of rounding in the closed form's positions
BRANCH_GAP = 1e-6         # rad or sizes: two routes this far apart are on two assembly modes
FD_FLOOR = 1e-9
FD_SAFETY = 10.0


def checked_samples(sol: KinematicSolution, every: int = EVERY, stride: int = STRIDE,
                    most: int = SAMPLES) -> np.ndarray:
    """The samples a route checks, in the sweep's order: every assembled sample up to
    ``every``; beyond, one in ``stride`` evenly spread (at least ``every``, at most
    ``most``) and up to :data:`NEAR_SAMPLES` of those nearest a singular configuration.
    The same samples for the same sweep on every run.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> len(kl.verify.checked_samples(kl.analyze(fb, np.linspace(0, 6, 800))))
    800
    >>> len(kl.verify.checked_samples(kl.analyze(fb, np.linspace(0, 6, 1_000_000))))
    2000
    """
    N = sol.N
    if N <= every:
        return np.flatnonzero(sol.assembled)
    chosen = np.zeros(N, bool)
    chosen[np.linspace(0, N - 1, min(most, max(every, N // stride))).round().astype(np.int64)] = True
    near = np.flatnonzero(sol.assembled & (sol.singularity < NEAR_SINGULAR))
    if len(near) > NEAR_SAMPLES:
        near = near[np.argsort(sol.singularity[near], kind="stable")[:NEAR_SAMPLES]]
    chosen[near] = True
    return np.flatnonzero(chosen & sol.assembled)


@dataclasses.dataclass(frozen=True)
class _Items:
    """Every named coordinate of a solution, with its kind and its unit: 1 rad for angles,
    the mechanism's size for lengths; and the inputs' units."""

    angle: np.ndarray        # (n_out,) bool
    point: np.ndarray        # (n_out,) bool
    slide: np.ndarray        # (n_out,) bool
    unit: np.ndarray         # (n_out,)
    unit_in: np.ndarray      # (M,)
    size: float

    @classmethod
    def of(cls, sol: KinematicSolution) -> _Items:
        p = sol.plan
        kinds = np.zeros(p.n_out, np.int8)
        kinds[list(p.point_item.values())] = 1
        kinds[[i + 1 for i in p.point_item.values()]] = 1
        kinds[list(p.slide_item.values())] = 2
        size = float(p.scale)
        return cls(angle=kinds == 0, point=kinds == 1, slide=kinds == 2,
                   unit=np.where(kinds == 0, 1.0, size),
                   unit_in=np.array([1.0 if k == "angle" else size for k in p.input_kinds]),
                   size=size)


@dataclasses.dataclass
class _Jets:
    """Values, K, L, velocities and accelerations of every item at the checked samples, in
    units of :class:`_Items` (rad and sizes, per rad or size of input, per second)."""

    value: np.ndarray        # (n, n_out)
    K: np.ndarray            # (n, n_out, M)
    L: np.ndarray            # (n, n_out, M, M)
    v: np.ndarray | None = None     # (n, n_out)
    a: np.ndarray | None = None

    @classmethod
    def of(cls, sol: KinematicSolution, items: _Items, rates: bool = True) -> _Jets:
        N, M = sol.q.shape
        every = np.arange(len(items.unit))
        jets = sol.item_jets(every)
        u, ui = items.unit, items.unit_in
        out = cls(value=jets[:, :, 0] / u,
                  K=jets[:, :, 1:1 + M] * ui / u[:, None],
                  L=jets[:, :, 1 + M:].reshape(N, -1, M, M) * ui[:, None] * ui / u[:, None, None])
        if rates:
            r = sol.item_rates(every)
            out.v, out.a = r[:, :, 0] / u, r[:, :, 1] / u
        return out

    def rates_from(self, qd: np.ndarray, qdd: np.ndarray) -> None:
        """Velocities ``K q'`` and accelerations ``K q'' + q'^T L q'`` (inputs in units)."""
        self.v = np.einsum("nia,na->ni", self.K, qd)
        self.a = np.einsum("nia,na->ni", self.K, qdd) + np.einsum("niab,na,nb->ni", self.L, qd, qd)


def _subset(sol: KinematicSolution, idx: np.ndarray) -> KinematicSolution:
    """The samples ``idx`` of ``sol`` as a solution of their own."""
    take = {name: np.ascontiguousarray(getattr(sol, name)[idx])
            for name in ("q", "qd", "qdd", "stored_jets", "stored_rates", "det_J",
                         "singularity", "singular", "assembled")}
    return dataclasses.replace(sol, single=False, newton_state=None, **take)


def _inputs(sol: KinematicSolution):
    """q, qd, qdd of a solution, shaped as analyze takes them back."""
    if sol.M > 1:
        return sol.q, sol.qd, sol.qdd
    return sol.q[:, 0], sol.qd[:, 0], sol.qdd[:, 0]


def _largest(diff: np.ndarray, scale: np.ndarray | float = 1.0) -> float:
    """max |diff| / scale over the samples and items, NaN if a difference is NaN."""
    if diff.size == 0 or len(diff) == 0:
        return 0.0
    d = np.abs(diff) / scale
    return float(d.max()) if not np.isnan(d).any() else math.nan


def _sample_scale(a: np.ndarray) -> np.ndarray:
    """Per sample (axis 0): the larger of 1 and the largest |a| of that sample, shaped to
    broadcast against ``a``."""
    flat = np.abs(a.reshape(len(a), -1)) if len(a) else np.zeros((0, 1))
    s = np.maximum(1.0, flat.max(axis=1, initial=0.0))
    return s.reshape((-1,) + (1,) * (a.ndim - 1))


def _rate_scale(a: np.ndarray) -> np.ndarray:
    """Per sample: the largest |a| of that sample, or 1 where every one is zero (inputs at
    rest: every route gives exactly zero)."""
    flat = np.abs(a.reshape(len(a), -1)) if len(a) else np.zeros((0, 1))
    s = flat.max(axis=1, initial=0.0)
    s = np.where(s > 0, s, 1.0)
    return s.reshape((-1,) + (1,) * (a.ndim - 1))


class _Ledger:
    """Comparisons collected by quantity."""

    def __init__(self):
        self.by: dict[str, list[Comparison]] = {}

    def add(self, quantity: str, route: str, samples: int, disagreement: float, bound: float,
            reason: str) -> None:
        self.by.setdefault(quantity, []).append(
            Comparison(route, int(samples), disagreement, bound, reason))


UNITS = {
    "angle": "1 rad",
    "position": "the mechanism's size, {size:.6g} m",
    "slide": "the mechanism's size, {size:.6g} m",
    "K": "the larger of 1 and the sample's largest |K| (rad or sizes per rad or size of input)",
    "L": "the larger of 1 and the sample's largest |L| (rad or sizes per rad or size of input, squared)",
    "velocity": "the sample's largest velocity (rad/s, sizes/s)",
    "acceleration": "the sample's largest acceleration (rad/s^2, sizes/s^2)",
}


def route_name(p) -> str:
    """How a plan solves its groups: the name of its route in the certificate."""
    kinds = {s.kind for s in p.steps} - {"driven", "locked", "placed"}
    if "newton" not in kinds:
        return "closed form"
    return "Newton engine" if kinds == {"newton"} else "closed form and Newton groups"


def certify_kinematics(sol: KinematicSolution) -> Certificate:
    """The certificate of a kinematic analysis (see the module docstring for the routes)."""
    m, p = sol.mechanism, sol.plan
    items = _Items.of(sol)
    ledger = _Ledger()
    notes: list[str] = []
    reported = route_name(p)
    followed = sol.change_points[0].followed if sol.change_points else "smooth"
    geared = any(j.type in ("G", "C") for j in m.joints)    # closed form only: no Newton plan
    newton_plan = None if geared else kinematics.plan(m, method="newton")
    other_method = "auto" if p is newton_plan else "newton"
    other_plan = p if geared else kinematics.plan(m, method=other_method)

    _closure(sol, items, ledger)

    idx = checked_samples(sol)
    sub = _subset(sol, idx)
    good = ~sub.singular                   # derivatives defined
    bad_sing = int(sol.singular.sum())
    if bad_sing:
        notes.append(f"{bad_sing} sample(s) flagged singular: K, L, velocities and "
                     "accelerations are undefined there (NaN) and not compared; their "
                     "positions are")
    if not sol.assembled.all():
        notes.append(f"{int((~sol.assembled).sum())} sample(s) do not assemble (NaN): not checked")
    if sol.N > min(EVERY, NEWTON_EVERY, CLOSURE_EVERY):
        notes.append(f"samples checked: every one up to {CLOSURE_EVERY} by loop closure, "
                     f"{EVERY} by the symbolic derivation and finite differences, "
                     f"{NEWTON_EVERY} by the Newton engine; beyond, one in {CLOSURE_STRIDE}, "
                     f"{STRIDE} and {NEWTON_STRIDE} (at most {SAMPLES} but for loop closure), "
                     "evenly spread, and those nearest a singular configuration")
    mine = _Jets.of(sub, items)
    qd, qdd = sub.qd / items.unit_in, sub.qdd / items.unit_in
    bounds, why = _engine_bounds(sub)

    # -- the other engine ------------------------------------------------------------------
    if geared and any(j.type == "C" for j in m.joints):
        notes.append("no second engine: cam joints are solved in closed form only (from the "
                     "cam's motion program); compared by the other routes")
    elif geared:
        notes.append("no second engine: gear joints are solved in closed form only (their "
                     "relation is linear in the angles); compared by the other routes")
    elif route_name(other_plan) == reported:
        notes.append(f"no second engine: every group is solved by the {reported} either way; "
                     "compared by the other routes")
    elif followed == "switch" and sol.change_points:
        notes.append("the Newton engine: it follows the smooth branch through change points, "
                     "and this analysis switched there; compared by the other routes")
    elif other_method == "auto":        # the closed form: as cheap as the analysis
        _other_engine(m, sub, other_method, items, mine, ledger, notes, bounds, why)
    else:
        part = _subset(sol, checked_samples(sol, NEWTON_EVERY, NEWTON_STRIDE))
        _other_engine(m, part, other_method, items, _Jets.of(part, items), ledger, notes,
                      *_engine_bounds(part))

    # -- the symbolic derivation ---------------------------------------------------------------
    from kinelab.verify._symbolic import symbolic_route
    route = symbolic_route(m, kinematics.plan(m))
    if isinstance(route, str):
        notes.append(f"the symbolic derivation: skipped, {route}")
    else:
        S = sub.item_jets(route.unknown_items)[:, :, 0]
        sym = route.evaluate(sub.q, S)
        theirs = _Jets(value=sym["value"] / items.unit,
                       K=sym["K"] * items.unit_in / items.unit[:, None],
                       L=sym["L"] * items.unit_in[:, None] * items.unit_in
                       / items.unit[:, None, None])
        theirs.rates_from(qd, qdd)
        every = np.ones(len(idx), bool)
        closure = _largest(sym["Phi"], items.size)
        _compare_positions(ledger, "symbolic derivation", mine, theirs, items, every, why,
                           extra=closure)
        _compare_derivatives(ledger, "symbolic derivation", mine, theirs, good, bounds, why)

    # -- finite differences ----------------------------------------------------------------------
    _finite_differences(sol, sub, items, mine, good, qd, qdd, ledger, notes,
                        "newton" if p is newton_plan else "auto", followed)

    quantities = tuple(Quantity(name, reported, UNITS[name].format(size=items.size),
                                tuple(ledger.by[name]))
                       for name in UNITS if name in ledger.by)
    what = f"kinematics of '{m.name}', {sol.N} sample{'s' if sol.N != 1 else ''}"
    return Certificate(what, quantities, tuple(notes))


def _engine_bounds(sub: KinematicSolution) -> tuple[dict, str]:
    """The bounds of the engines and the symbolic route at samples ``sub``: rounding and the
    Newton engine's last step, amplified near a singular configuration (K by 1/s^2, L by
    1/s^3, s the smallest singularity of the samples not flagged)."""
    good = ~sub.singular
    s_min = float(sub.singularity[good].min()) if good.any() else 1.0
    bounds = {"angle": ENGINE_FLOOR, "position": ENGINE_FLOOR, "slide": ENGINE_FLOOR,
              "K": max(ENGINE_FLOOR, AMPLIFIED / s_min ** 2),
              "L": max(ENGINE_FLOOR, AMPLIFIED / s_min ** 3)}
    bounds["velocity"], bounds["acceleration"] = bounds["K"], bounds["L"]
    why = (f"the Newton engine's convergence ({NEWTON_TOL:g} of the size) and rounding, "
           f"amplified near singular configurations (smallest singularity {s_min:.2g})")
    return bounds, why


def _other_engine(m, sub, method, items, mine, ledger, notes, bounds, why) -> None:
    """The same samples by the other engine, from the sketch by continuation.  Samples
    flagged singular are left out of its sweep (continuing through one, the Newton engine's
    L carries errors of ~1e-9 afterwards); samples where it lands on another assembly mode
    (continuing past a limit position it may cross to the other branch) are left out of the
    comparison, and said: their values are checked by loop closure and the symbolic route."""
    rows = np.flatnonzero(~sub.singular)
    if not len(rows):
        return
    part = _subset(sub, rows)
    other = kinematics.analyze(m, *_inputs(part), method=method, unreachable="mask",
                               at_singular="flag")
    name = route_name(other.plan)
    theirs = _Jets.of(other, items)
    mine = dataclasses.replace(mine, **{k: getattr(mine, k)[rows]
                                        for k in ("value", "K", "L", "v", "a")})
    d = theirs.value - mine.value
    d[:, items.angle] = wrap_angle(d[:, items.angle])
    gap = np.abs(d).max(axis=1, initial=0.0)
    same = other.assembled & (gap <= BRANCH_GAP)
    missed = int((~other.assembled).sum())
    if missed:
        notes.append(f"{name}: did not reach {missed} sample(s) from the sketch; compared at "
                     "the others")
    crossed = int((other.assembled & ~same).sum())
    if crossed:
        notes.append(f"{name}: on the other assembly mode at {crossed} sample(s) (continuing "
                     "from the sketch it crossed a limit position); compared at the others")
    _compare_positions(ledger, name, mine, theirs, items, same, why)
    only = int((same & other.singular).sum())
    if only:
        notes.append(f"{name}: flags {only} sample(s) singular that the analysis does not "
                     "(its own measure of its groups); their derivatives are compared by "
                     "the other routes")
    _compare_derivatives(ledger, name, mine, theirs, same & ~other.singular, bounds, why)


def _compare_positions(ledger, route, mine: _Jets, theirs: _Jets, items: _Items, rows,
                       why: str, extra: float = 0.0) -> None:
    """Angles (modulo a turn), points and slides of two routes, at samples ``rows``."""
    d = theirs.value[rows] - mine.value[rows]
    d[:, items.angle] = wrap_angle(d[:, items.angle])
    n = int(rows.sum())
    if not n:
        return
    for quantity, cols, more in (("angle", items.angle, 0.0), ("position", items.point, extra),
                                 ("slide", items.slide, 0.0)):
        if cols.any():
            ledger.add(quantity, route, n, max(_largest(d[:, cols]), more), ENGINE_FLOOR,
                       "the contract between the closed form and the Newton engine; " + why)


def _compare_derivatives(ledger, route, mine: _Jets, theirs: _Jets, rows, bounds, why: str,
                         fd_bounds: dict | None = None) -> None:
    """K, L, velocities and accelerations of two routes at samples ``rows``; each relative
    to its own per-sample scale (see ``UNITS``)."""
    n = int(rows.sum())
    if not n:
        return
    for quantity, a, b, scale in (("K", mine.K, theirs.K, _sample_scale),
                                  ("L", mine.L, theirs.L, _sample_scale),
                                  ("velocity", mine.v, theirs.v, _rate_scale),
                                  ("acceleration", mine.a, theirs.a, _rate_scale)):
        a, b = a[rows], b[rows]
        bound, reason = (bounds[quantity], why) if fd_bounds is None else fd_bounds[quantity]
        ledger.add(quantity, route, n, _largest(b - a, scale(a)), bound, reason)


CHUNK = 65536      # samples of loop closure at a time: arrays that stay in the cache
CLOSURE_EVERY, CLOSURE_STRIDE = 4096, 8
"""Loop closure checks every sample up to the first; beyond, one in the second (and those
nearest a singular configuration): in numpy it costs some ten times the compiled analysis
per sample."""


def _closure(sol: KinematicSolution, items: _Items, ledger: _Ledger) -> None:
    """Loop closure at every sample: each link's points where its angle and first point put
    them; each prismatic joint's point on its guide's line, its links' relative angle and
    its slide.  Residuals relative to the size (lengths) and 1 rad (angles: a point's miss
    over its distance from the link's first point).  A chunk of samples at a time, every
    link and joint of the chunk in one array operation."""
    m, p = sol.mechanism, sol.plan
    xy = {pt.name: np.array([pt.x, pt.y]) for pt in m.points}
    sketch = p.sketch_angles
    n_stored = sol.stored_jets.shape[1]
    extra: list[int] = []       # items not stored per sample (fixed, driven), after them

    def col(item: int) -> int:
        """The column of ``item`` in the values of a chunk (see :func:`_values`)."""
        slot = int(p.item_slot[item])
        if slot >= 0:
            return slot
        if item not in extra:
            extra.append(item)
        return n_stored + extra.index(item)
    turning, pairs = [], []    # links' (angle col, sketch angle); (link, first x, point x, r, arm)
    for link in m.links:
        if link.ground or len(link.points) < 2:
            continue
        first = link.points[0]
        turning.append((col(p.link_item[link.name]), sketch[p.link_item[link.name]]))
        for point in link.points[1:]:
            r = xy[point] - xy[first]
            pairs.append((len(turning) - 1, col(p.point_item[first]),
                          col(p.point_item[first] + 1), col(p.point_item[point]),
                          col(p.point_item[point] + 1), r[0], r[1], float(np.hypot(*r))))
    slides = []         # (guide, slider, origin x, y, point x, y, slide cols, angles, across0)
    for j in m.joints:
        if j.type != "P":
            continue
        g, s_ = j.links
        gi, si = p.link_item[g], p.link_item[s_]
        origin = j.origin or m.link(g).points[0]
        axis0 = math.atan2(j.axis[1], j.axis[0])
        d0 = xy[j.point] - xy[origin]
        slides.append((col(gi), col(si), col(p.point_item[origin]), col(p.point_item[origin] + 1),
                       col(p.point_item[j.point]), col(p.point_item[j.point] + 1),
                       col(p.slide_item[j.name]), sketch[gi], sketch[si], axis0,
                       -math.sin(axis0) * d0[0] + math.cos(axis0) * d0[1]))
    T = np.array(turning, float).reshape(-1, 2)
    P = np.array(pairs, float).reshape(-1, 8)
    J = np.array(slides, float).reshape(-1, 11)
    ti, pi, ji = T[:, 0].astype(np.int64), P[:, :5].astype(np.int64), J[:, :7].astype(np.int64)
    far = P[:, 7] > 1e-6 * items.size       # pairs that show the link's angle
    worst = {"position": 0.0, "angle": 0.0, "slide": 0.0}
    size = items.size
    where = p.item_columns(np.array(extra, np.int64))
    every = sol.assembled.all() and sol.N <= CLOSURE_EVERY
    rows = None if every else checked_samples(sol, CLOSURE_EVERY, CLOSURE_STRIDE, sol.N)
    n = sol.N if every else len(rows)
    for start in range(0, n, CHUNK):
        stop = min(n, start + CHUNK)
        v = _values(sol, where, slice(start, stop) if every else rows[start:stop])
        if len(P):
            turn = v[:, ti] - T[:, 1]                        # one cosine and sine per link
            c, si = np.cos(turn)[:, pi[:, 0]], np.sin(turn)[:, pi[:, 0]]
            miss = np.hypot(v[:, pi[:, 1]] + c * P[:, 5] - si * P[:, 6] - v[:, pi[:, 3]],
                            v[:, pi[:, 2]] + si * P[:, 5] + c * P[:, 6] - v[:, pi[:, 4]])
            _worst(worst, "position", miss / size)
            _worst(worst, "angle", miss[:, far] / P[far, 7])
        if len(J):
            _worst(worst, "angle", wrap_angle(v[:, ji[:, 1]] - v[:, ji[:, 0]] - (J[:, 8] - J[:, 7])))
            th = v[:, ji[:, 0]] - J[:, 7] + J[:, 9]
            dx, dy = v[:, ji[:, 4]] - v[:, ji[:, 2]], v[:, ji[:, 5]] - v[:, ji[:, 3]]
            c, si = np.cos(th), np.sin(th)
            _worst(worst, "position", (-si * dx + c * dy - J[:, 10]) / size)
            _worst(worst, "slide", (c * dx + si * dy - v[:, ji[:, 6]]) / size)
    reason = ("rounding of coordinates of a few sizes, and the Newton groups' convergence "
              "tolerance")
    for kind, value in worst.items():
        if kind != "slide" or items.slide.any():
            ledger.add(kind, "loop closure", n, value, CLOSURE_BOUND, reason)


def _worst(worst: dict, kind: str, residual: np.ndarray) -> None:
    """Keep the largest |residual| of each kind (NaN, once met, stays: it fails)."""
    if residual.size == 0 or math.isnan(worst[kind]):
        return
    r = np.abs(residual)
    worst[kind] = math.nan if np.isnan(r).any() else max(worst[kind], float(r.max()))


def _values(sol: KinematicSolution, extra, rows) -> np.ndarray:
    """The values (no K, L) at samples ``rows`` (a slice or indices) of every stored item,
    in its stored column, then of the items ``extra`` (``plan.item_columns`` of fixed and
    driven items), made as the solution makes them."""
    n_stored = sol.stored_jets.shape[1]
    q = sol.q[rows]
    v = np.empty((len(q), n_stored + len(extra.slots)))
    v[:, :n_stored] = sol.stored_jets[rows, :, 0]
    v[:, n_stored + extra.fixed_cols] = extra.fixed_values
    v[:, n_stored + extra.driven_cols] = wrap_angle(q[:, extra.driven_inputs] * extra.driven_signs)
    return v


def _richardson(d: np.ndarray, size: np.ndarray, h: np.ndarray):
    """The derivative from central differences ``d`` at steps h, h/2, h/4 (axis 0), and an
    estimate of its error.  Each difference is off by c h^2 + O(h^4); combining two steps
    as (4 d_small - d_large) / 3 removes the h^2 term, and the two such combinations differ
    by about 15 times the error of the finer one: their difference bounds it.  Rounding of
    values of size ``size`` adds about eps size / h, times the combination's weights."""
    r_coarse = (4 * d[1] - d[0]) / 3
    r_fine = (4 * d[2] - d[1]) / 3
    return r_fine, np.abs(r_fine - r_coarse) + 32 * EPS * size / h


def _finite_differences(sol, sub, items: _Items, mine: _Jets, good, qd, qdd, ledger, notes,
                        method: str, followed: str) -> None:
    """K from central differences of the positions and L from those of K, steps h, h/2 and
    h/4 combined by Richardson extrapolation, at the checked samples whose stencil stays clear of
    singular configurations, change points and the limits of the reachable range."""
    m = sol.mechanism
    n, M = sub.q.shape
    n_out = len(items.unit)
    s = np.where(good, sub.singularity, 1.0)
    h = H0 * np.minimum(1.0, (s / S_REF) ** 2)            # in units of each input
    K = np.full((n, n_out, M), np.nan)
    L = np.full((n, n_out, M, M), np.nan)
    K_err = np.zeros((n, n_out, M))
    L_err = np.zeros((n, n_out, M, M))
    usable = good.copy()
    fractions = np.array([1.0, 0.5, 0.25])
    steps = np.repeat(fractions, 2) * np.tile([1.0, -1.0], 3)     # +h, -h, +h/2, ...
    spans = 2 * fractions[:, None, None] * h[None, :, None]        # (3, n, 1)
    for a in range(M):
        q = np.repeat(sub.q[None], len(steps), axis=0)
        q[:, :, a] += steps[:, None] * (h * items.unit_in[a])
        flat = q.reshape(-1, M)
        r = kinematics.analyze(m, flat if M > 1 else flat[:, 0], method=method,
                               unreachable="mask", at_singular="flag", at_change_point=followed)
        clear = (r.assembled & ~r.singular).reshape(len(steps), n).all(axis=0)
        if M == 1 and sol.change_points:
            cps = np.array([c.q for c in sol.change_points])
            reach = h[:, None] * items.unit_in[0]
            clear &= ~(np.abs(sub.q[:, :1] - cps[None]) <= 1.01 * reach).any(axis=1)
        usable &= clear
        jets = _Jets.of(r, items, rates=False)
        value = jets.value.reshape(len(steps), n, n_out)
        dv = value[0::2] - value[1::2]                     # (3, n, n_out): h, h/2, h/4
        dv[:, :, items.angle] = wrap_angle(dv[:, :, items.angle])
        K[:, :, a], K_err[:, :, a] = _richardson(dv / spans, np.abs(value[0]) + 1.0, h[:, None])
        k = jets.K.reshape(len(steps), n, n_out, M)
        dk = (k[0::2] - k[1::2]) / spans[..., None]        # dK[:, :, b] / dq_a
        L[:, :, :, a], L_err[:, :, :, a] = _richardson(dk, np.abs(k[0]) + 1.0, h[:, None, None])
    left = int(good.sum() - usable.sum())
    if left:
        notes.append(f"finite differences: {left} sample(s) left out, their stencil (up to "
                     f"{H0:g} rad or sizes either way) meets a singular configuration, a change "
                     "point or the end of the reachable range")
    theirs = _Jets(value=mine.value, K=K, L=L)
    theirs.rates_from(qd, qdd)
    rows = usable
    sK, sL = _sample_scale(mine.K[rows]), _sample_scale(mine.L[rows])
    eK = float(np.max(K_err[rows] / sK, initial=0.0))
    eL = float(np.max(L_err[rows] / sL, initial=0.0))
    # velocities and accelerations carry the errors of K and L, times the rates
    ev = float(np.max(np.einsum("nia,na->ni", K_err[rows], np.abs(qd[rows]))
                      / _rate_scale(mine.v[rows]), initial=0.0))
    ea = float(np.max((np.einsum("nia,na->ni", K_err[rows], np.abs(qdd[rows]))
                       + np.einsum("niab,na,nb->ni", L_err[rows], np.abs(qd[rows]),
                                   np.abs(qd[rows]))) / _rate_scale(mine.a[rows]), initial=0.0))
    reason = ("{:g} times the differences' own error estimate (two Richardson extrapolations "
              "apart, and rounding / h), at least {:g}")
    fd = {q: (max(FD_FLOOR, FD_SAFETY * e), reason.format(FD_SAFETY, FD_FLOOR))
          for q, e in (("K", eK), ("L", eL), ("velocity", ev), ("acceleration", ea))}
    _compare_derivatives(ledger, "finite differences", mine, theirs, rows, None, "", fd)
