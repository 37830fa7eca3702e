"""The certificate of a synthesized linkage: the linkage analysed again at every task point.

The synthesis computes a linkage from the task (poles, Burmester's curves, Freudenstein's
equation, a least-squares fit, the construction of a crank-rocker); here the linkage it
returns is handed to :func:`kinelab.kinematics.analyze` like any model, at every task point
-- each prescribed position's crank angle, each precision point, each target, each dead
centre -- and what it reaches is compared with the task and with what the synthesis
reported: the coupler point and angle in each position, the pivots, the function's values,
the path's errors, the swing, stroke and time ratio between the dead centres (where the
output's K vanishes), the smallest transmission angle.
"""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from kinelab import kinematics
from kinelab.errors import ModelError
from kinelab.solvers import wrap_angle
from kinelab.verify._certificate import Certificate, Comparison, Quantity

__all__ = ["certify_synthesis", "certify_solutions"]

REACHED = 1e-9
"""Relative to the task's size (or 1 rad, or the function's span): the synthesis solves
linear equations in the task's coordinates and the engine places the linkage back; both
round at ~1e-15, amplified by the equations' conditioning (nearly collinear poles, nearly
coincident positions) by up to 1e6 before a task becomes degenerate."""
AGREE = 1e-12
"""A reported number the synthesis measured with the engine, measured again: rounding."""
CLAIMED = 1e-6
"""A position the synthesis reports within this of the task (relative to its size, or in rad)
is one it claims to reach: the re-analysis must then reach it within :data:`REACHED`."""
DEAD_CENTRE = 1e-9
"""rad: the dead centres are bisected to ~1e-12 rad, then the output's K / L there says how
far the true one is."""
ROUTE = "re-analysis at every task point"


class _Checks:
    """Comparisons of one solution, by quantity."""

    def __init__(self, label: str):
        self.label = label
        self.by: dict[str, list[Comparison]] = {}
        self.units: dict[str, str] = {}
        self.notes: list[str] = []

    def add(self, quantity: str, unit: str, route: str, samples: int, disagreement: float,
            bound: float, reason: str) -> None:
        self.units[quantity] = unit
        self.by.setdefault(quantity, []).append(
            Comparison(route, int(samples), disagreement, bound, reason))

    def certificate(self, what: str, reported: str) -> Certificate:
        return Certificate(what, tuple(Quantity(n, reported, self.units[n], tuple(c))
                                       for n, c in self.by.items()), tuple(self.notes))


def _largest(a) -> float:
    a = np.abs(np.asarray(a, float))
    if a.size == 0:
        return 0.0
    return math.nan if np.isnan(a).any() else float(a.max())


def _same(reported, recomputed, scale: float) -> float:
    """Largest |reported - recomputed| / scale, infinities agreeing with infinities (the
    synthesis reports +inf where the linkage cannot close)."""
    a, b = np.asarray(reported, float), np.asarray(recomputed, float)
    both_inf = np.isinf(a) & np.isinf(b) & (np.sign(a) == np.sign(b))
    d = np.where(both_inf, 0.0, np.abs(a - b))
    return _largest(d) / scale


def certify_synthesis(solution, *, function=None, requested: Mapping | None = None,
                      label: str | None = None) -> Certificate:
    """The certificate of a linkage from :mod:`kinelab.synthesis` (see the module
    docstring).  ``function`` is the prescribed f(x) of a function generator; ``requested``
    the design values a crank-rocker or quick return was asked for (``swing``,
    ``time_ratio``, ``stroke``: rad, m), compared with what it reaches; ``label`` names the
    linkage in the notes (default: its model's name)."""
    kind = type(solution).__name__
    checks = _Checks(label or f"'{solution.model.name}'")
    if kind == "MotionSolution":
        _motion(solution, checks)
    elif kind == "FunctionSolution":
        if function is None or not callable(function):
            raise ModelError("function: expected the prescribed function f(x) of the function "
                             "generator (certify(solution, function=f)); the re-analysis "
                             "compares the linkage's output with it")
        _function(solution, function, checks)
    elif kind == "PathSolution":
        _path(solution, checks)
    else:
        _design(solution, dict(requested or {}), checks)
    name = solution.model.name
    return checks.certificate(f"synthesized {kind_name(kind)} '{name}'", "synthesis")


def certify_solutions(solutions, subject: str, *, function=None,
                      requested: Mapping | None = None) -> Certificate:
    """One certificate of every linkage of a task (none: nothing to certify, and said)."""
    solutions = list(solutions)
    if not solutions:
        return Certificate(subject, (), ("no linkage was found: nothing to certify",))
    return Certificate.merge([certify_synthesis(s, function=function, requested=requested,
                                                label=f"linkage {i}")
                              for i, s in enumerate(solutions, 1)], subject, "linkage")


def kind_name(kind: str) -> str:
    return {"MotionSolution": "motion generator", "FunctionSolution": "function generator",
            "PathSolution": "path generator", "CrankRocker": "crank-rocker",
            "QuickReturn": "quick return"}[kind]


def _size(*arrays) -> float:
    pts = np.concatenate([np.reshape(a, (-1, 2)) for a in arrays])
    return float(max(np.ptp(pts[:, 0]), np.ptp(pts[:, 1]), 1e-300))


def _pivots(s, checks: _Checks, size: float, unit: str, moving: bool = True) -> None:
    """A0, B0 where the model's pivots are; A1, B1 where the re-analysis at the first task
    point puts the moving pivots (not for a least-squares fit: its linkage has the fitted
    lengths, and its A1, B1 are the fitted circles' points)."""
    first = kinematics.analyze(s.model, float(s.q[0]), unreachable="mask", at_singular="flag")
    miss = [first.position("O2") - s.A0, first.position("O4") - s.B0]
    if moving:
        miss += [first.position("A") - s.A1, first.position("B") - s.B1]
    checks.add("pivots", unit, "re-analysis at the first task point", len(miss),
               _largest(np.linalg.norm(miss, axis=-1)) / size, REACHED, _REACHED_WHY)


_REACHED_WHY = ("the synthesis' linear algebra and the engine's placement, rounding amplified "
                "by the task's conditioning")


def _motion(s, checks: _Checks) -> None:
    """The coupler point and its rotation at each position's crank angle."""
    size = _size(s.points, s.A0, s.B0, s.A1, s.B1)
    unit = f"the task's size (its positions and pivots), {size:.6g} m; angles: 1 rad"
    n = len(s.q)
    sol = kinematics.analyze(s.model, np.asarray(s.q, float), unreachable="mask",
                             at_singular="flag")
    ok = sol.assembled
    P = sol.position("P")
    dist = np.where(ok, np.linalg.norm(P - s.points, axis=-1), np.inf)
    turn = sol.angle("coupler") - sol.angle("coupler")[0]
    angle = np.where(ok, np.abs(wrap_angle(turn - (s.alpha - s.alpha[0]))), np.inf)
    checks.add("position error", unit, ROUTE, n, _same(s.position_errors, dist, size),
               AGREE, "the engine measured it; measured again, rounding")
    checks.add("angle error", unit, ROUTE, n, _same(s.angle_errors, angle, 1.0), AGREE,
               "the engine measured it; measured again, rounding")
    exact = n <= 5
    if exact:
        # where the synthesis says the linkage reaches the task: there it must, to rounding
        claimed = (s.position_errors <= CLAIMED * size) & (s.angle_errors <= CLAIMED)
        if (~claimed).any():
            checks.notes.append(f"{checks.label}: position(s) "
                                f"{', '.join(str(i + 1) for i in np.flatnonzero(~claimed))} not "
                                f"reached on position 1's branch, as reported ({s.state})")
        checks.add("position reached", unit, ROUTE, int(claimed.sum()),
                   _largest(dist[claimed]) / size, REACHED, _REACHED_WHY)
        checks.add("angle reached", unit, ROUTE, int(claimed.sum()), _largest(angle[claimed]),
                   REACHED, _REACHED_WHY)
    # each dyad's length change between positions, from the task's displacements alone
    c, si = np.cos(s.alpha - s.alpha[0]), np.sin(s.alpha - s.alpha[0])

    def carried(X1):
        r = X1 - s.points[0]
        return s.points + np.stack([c * r[0] - si * r[1], si * r[0] + c * r[1]], -1)
    crank, rocker = (s.model.parameters[k] for k in ("crank", "rocker"))
    residuals = np.stack([np.linalg.norm(carried(s.A1) - s.A0, axis=-1) - crank,
                          np.linalg.norm(carried(s.B1) - s.B0, axis=-1) - rocker], -1)
    checks.add("dyad residual", unit, "the task's displacements of A1 and B1", n,
               _same(s.dyad_residuals, residuals, size), REACHED, _REACHED_WHY)
    _pivots(s, checks, size, unit, moving=exact)


def _function(s, f, checks: _Checks) -> None:
    """The output at every sample of x and at the precision points, against f(x)."""
    x0, xf = float(s.x_samples[0]), float(s.x_samples[-1])
    y0, yf = (float(v) for v in np.asarray(f(np.array([x0, xf])), float))
    (t2s, t2e), (t4s, t4e) = s.input_range, s.output_range
    span = abs(yf - y0) if yf != y0 else 1.0
    unit = f"the span of f over the input range, {span:.6g}"
    x = np.concatenate([s.x_samples, s.x])
    sol = kinematics.analyze(s.model, t2s + (x - x0) / (xf - x0) * (t2e - t2s),
                             unreachable="mask", at_singular="flag")
    # y per rad of output; 1 where the output comes back to its start (pairs of angles,
    # where y is the output angle itself: a function by its formula cannot do that)
    ratio = (yf - y0) / (t4e - t4s) if yf != y0 else 1.0
    wanted = t4s + (np.asarray(f(x), float) - y0) / ratio
    out = np.where(sol.assembled, wrap_angle(sol.angle("rocker") - wanted) * ratio, np.inf)
    m = len(s.x_samples)
    checks.add("structural error", unit, ROUTE, len(x),
               max(_same(s.structural_error, out[:m], span),
                   _same(s.precision_errors, out[m:], span)), AGREE,
               "the engine measured it; measured again, rounding")
    if len(s.x) == 3:
        checks.add("function reached", unit, ROUTE + " (the three precision points)", 3,
                   _largest(out[m:]) / span, REACHED, _REACHED_WHY)


def _path(s, checks: _Checks) -> None:
    size = _size(s.points, s.A0, s.B0, s.A1, s.B1)
    unit = f"the task's size (its targets and pivots), {size:.6g} m"
    sol = kinematics.analyze(s.model, np.asarray(s.q, float), unreachable="mask",
                             at_singular="flag")
    dist = np.where(sol.assembled, np.linalg.norm(sol.position("P") - s.points, axis=-1), np.inf)
    checks.add("path error", unit, ROUTE, len(s.q), _same(s.errors, dist, size), AGREE,
               "the engine measured it; measured again, rounding")
    _pivots(s, checks, size, unit)


def _design(s, requested: dict, checks: _Checks) -> None:
    """A crank-rocker or quick return: its output stops at the dead centres; the swing or
    stroke between them, the time ratio from them, the smallest transmission angle."""
    kind = type(s).__name__
    to_rad = math.radians if s.degrees else (lambda v: v)
    dc = np.array([to_rad(float(v)) for v in s.dead_centres])
    if kind == "CrankRocker":
        output, slide = "rocker", False
    else:
        output, slide = {"offset slider-crank": ("slide", True), "slotted lever": ("lever", False),
                         "whitworth": ("ram_slide", True)}[s.kind]
    sol = kinematics.analyze(s.model, dc, at_singular="flag")
    K, L = sol.K(output), sol.L(output)
    size = float(kinematics.plan(s.model).scale)
    checks.add("dead centre", "1 rad of crank angle", "K / L of the output there", 2,
               _largest(K / np.where(L != 0, L, np.inf)), DEAD_CENTRE, "the bisection's "
               "tolerance (1e-12 rad) and rounding, through K = L dq near a dead centre")
    if slide:
        travel = abs(float(sol.slide(output)[1] - sol.slide(output)[0]))
        unit = f"the mechanism's size, {size:.6g} m"
        checks.add("stroke", unit, ROUTE, 2, abs(travel - s.stroke) / size, AGREE,
                   "the engine measured it; measured again, rounding")
        if "stroke" in requested:
            checks.add("stroke", unit, "the task's stroke", 1,
                       abs(travel - requested["stroke"]) / size, REACHED, _REACHED_WHY)
    else:
        swing = abs(float(wrap_angle(sol.angle(output)[1] - sol.angle(output)[0])))
        checks.add("swing", "1 rad", ROUTE, 2, abs(swing - to_rad(s.swing)), AGREE,
                   "the engine measured it; measured again, rounding")
        if "swing" in requested:
            checks.add("swing", "1 rad", "the task's swing", 1,
                       abs(swing - requested["swing"]), REACHED, _REACHED_WHY)
    stroke = float(np.mod(dc[1] - dc[0], 2 * np.pi))
    ratio = max(stroke, 2 * np.pi - stroke) / min(stroke, 2 * np.pi - stroke)
    checks.add("time ratio", "1", "the crank angles between the dead centres", 2,
               abs(ratio - s.time_ratio), AGREE, "the engine measured it; measured again, rounding")
    if "time_ratio" in requested:
        checks.add("time ratio", "1", "the task's time ratio", 1,
                   abs(ratio - requested["time_ratio"]), REACHED, _REACHED_WHY)
    if kind == "CrankRocker":
        at = kinematics.analyze(s.model, np.array([0.0, np.pi]))
        mu = np.abs(wrap_angle(at.angle("coupler") - at.angle("rocker")))
        mu = np.minimum(mu, np.pi - mu)
        checks.add("transmission angle", "1 rad", "re-analysis with the crank along the ground",
                   2, abs(float(mu.min()) - to_rad(s.transmission_min)), AGREE,
                   "the engine measured it; measured again, rounding")
        lengths = {"ground": ("O2", "O4"), "crank": ("O2", "A"), "coupler": ("A", "B"),
                   "rocker": ("O4", "B")}
        miss = [np.linalg.norm(sol.position(b) - sol.position(a), axis=-1) - getattr(s, k)
                for k, (a, b) in lengths.items()]
        checks.add("lengths", f"the mechanism's size, {size:.6g} m", ROUTE, 2,
                   _largest(miss) / size, AGREE * 100, "rounding of the placed points")
    elif s.transmission_min is not None:
        rod = kinematics.analyze(s.model, np.array([np.pi / 2, -np.pi / 2])).angle("rod")
        tilt = np.abs(wrap_angle(rod))
        mu = np.pi / 2 - float(np.max(np.minimum(tilt, np.pi - tilt)))
        checks.add("transmission angle", "1 rad", "re-analysis with the crank across the slide",
                   2, abs(mu - to_rad(s.transmission_min)), AGREE,
                   "the engine measured it; measured again, rounding")
