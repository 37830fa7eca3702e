"""Six-bar synthesis by optimisation: path, function and motion generation.

A six-bar has too many dimensions for the closed forms of four-bar synthesis, so it is
synthesised numerically, with kinelab's own engine: the design variables are the places of
the linkage's joints (and of its path point) in the first precision position, which is the
model's sketch, so every candidate is assembled there by construction and keeps that
sketch's assembly modes.  Many random candidates are moved at once through
:func:`kinelab.kinematics.analyze_designs` (one kernel run for all of them), the best are
refined together by a batched Levenberg-Marquardt whose Jacobians are also one kernel run
(forward differences of all candidates' perturbed designs), and each result is built as a
model and checked by :func:`kinelab.analyze`.

The task is normalised first (centred, turned and scaled to unit size), so a task moved,
turned or scaled gives the same linkages moved, turned or scaled.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.kinematics import analyze, analyze_designs
from kinelab.model import Mechanism
from kinelab.synthesis._arguments import angle_array, point_array
from kinelab.synthesis._results import SolutionList

__all__ = ["sixbar", "SixBarSolution", "SIXBAR_KINDS"]


@dataclass(frozen=True)
class _Kind:
    """One six-bar inversion: its links (the coupler carries the path point P), the link
    whose motion a motion task prescribes (``coupler``, with a second point ``coupler_ref``
    that gives its angle), the output of a function task (``output`` from ``output_ref[0]``
    to ``output_ref[1]``), its dyads' middle joints (transmission angles) and a sketch."""

    name: str
    links: tuple
    coupler: str
    coupler_ref: str
    output: str
    output_ref: tuple
    dyads: tuple          # (middle joint, end, end)
    sketch: dict
    description: str

    @property
    def points(self) -> tuple:
        return tuple(self.sketch)


# Sketches (m): reasonable, assembled, Grashof-crank designs, used as the model's names and
# as a reference for the random starts' spread.
_KINDS = {k.name: k for k in (
    _Kind("watt1",
          (("ground", ("O2", "O4")), ("crank", ("O2", "A", "C")), ("coupler", ("A", "B", "D")),
           ("rocker", ("O4", "B")), ("link5", ("C", "E", "P")), ("link6", ("D", "E"))),
          "link5", "C", "link6", ("D", "E"), (("B", "A", "O4"), ("E", "C", "D")),
          {"O2": (0.0, 0.0), "A": (0.5, 0.87), "C": (-0.7, 0.7), "B": (3.0, 2.5), "O4": (4.0, 0.0),
           "D": (1.5, 3.0), "E": (-0.5, 3.0), "P": (-1.0, 2.0)},
          "Watt I: ground binary; the ternary crank (O2, A, C) and the ternary coupler "
          "(A, B, D) of the four-bar O2-A-B-O4 carry the dyad C-E-D (link5 C-E, link6 D-E); "
          "input the crank at O2, path/motion link link5 (point P), output link6's angle"),
    _Kind("watt2",
          (("ground", ("O2", "O4", "O6")), ("crank", ("O2", "A")), ("coupler", ("A", "B")),
           ("rocker", ("O4", "B", "C")), ("link5", ("C", "D", "P")), ("output", ("O6", "D"))),
          "link5", "C", "output", ("O6", "D"), (("B", "A", "O4"), ("D", "C", "O6")),
          {"O2": (0.0, 0.0), "A": (0.5, 0.866), "B": (3.52, 3.1), "O4": (5.63, -0.76),
           "C": (4.51, 1.21), "O6": (7.07, 0.04), "D": (6.32, 2.53), "P": (5.6, 2.6)},
          "Watt II (kl.mechanisms.watt6): ground ternary; the ternary rocker (O4, B, C) of the "
          "crank-rocker O2-A-B-O4 drives the four-bar O4-C-D-O6; input the crank at O2, "
          "path/motion link link5 (C, D, point P), output the output link at O6"),
    _Kind("stephenson1",
          (("ground", ("O2", "O4")), ("crank", ("O2", "A", "C")), ("coupler", ("A", "B")),
           ("rocker", ("O4", "B", "D")), ("link5", ("C", "E", "P")), ("link6", ("D", "E"))),
          "link5", "C", "link6", ("D", "E"), (("B", "A", "O4"), ("E", "C", "D")),
          {"O2": (0.0, 0.0), "A": (0.5, 0.87), "C": (-0.7, 0.7), "B": (3.0, 2.5), "O4": (4.0, 0.0),
           "D": (4.8, 1.8), "E": (1.8, 4.2), "P": (0.2, 3.2)},
          "Stephenson I: ground binary (O2, O4) joining the two ternary links, the crank "
          "(O2, A, C) and the rocker (O4, B, D) of the four-bar O2-A-B-O4; the dyad C-E-D "
          "(link5 C-E, link6 D-E) joins them; input the crank at O2, path/motion link link5 "
          "(point P), output link6's angle"),
    _Kind("stephenson2",
          (("ground", ("O2", "O4")), ("crank", ("O2", "A")), ("coupler", ("A", "B", "C", "P")),
           ("link4", ("B", "D")), ("link5", ("C", "E")), ("output", ("O4", "D", "E"))),
          "coupler", "A", "output", ("O4", "D"), (("D", "B", "O4"), ("E", "C", "O4")),
          {"O2": (0.0, 0.0), "A": (0.0, 1.0), "B": (2.0, 2.2), "C": (1.2, 2.8), "P": (1.0, 3.6),
           "O4": (4.0, 0.0), "D": (3.4, 2.0), "E": (4.4, 2.4)},
          "Stephenson II: ground binary (O2, O4); the crank O2-A carries the ternary coupler "
          "(A, B, C), held by link4 (B-D) and link5 (C-E) from the ternary output (O4, D, E); "
          "no dyad solves it (the engine's Newton groups do); input the crank at O2, "
          "path/motion link the coupler (point P), output the output link at O4"),
    _Kind("stephenson3",
          (("ground", ("O2", "O4", "O6")), ("crank", ("O2", "A")), ("coupler", ("A", "B", "C")),
           ("rocker", ("O4", "B")), ("link5", ("C", "D", "P")), ("output", ("O6", "D"))),
          "link5", "C", "output", ("O6", "D"), (("B", "A", "O4"), ("D", "C", "O6")),
          {"O2": (0.0, 0.0), "A": (0.0, 1.0), "B": (3.68, 2.75), "O4": (5.69, -1.03),
           "C": (2.18, 3.47), "O6": (5.92, 2.14), "D": (4.34, 5.26), "P": (3.0, 5.0)},
          "Stephenson III (kl.mechanisms.stephenson6): ground ternary; the ternary coupler "
          "(A, B, C) of the four-bar O2-A-B-O4 drives the dyad C-D-O6; input the crank at O2, "
          "path/motion link link5 (C, D, point P), output the output link at O6"),
)}

SIXBAR_KINDS = tuple(_KINDS)
_MU_MARGIN = math.radians(0.5)
_REACH = 60.0     # farthest a joint may be from the task's centre, in task sizes


def _model(kind: _Kind, pts: Mapping[str, tuple[float, float]], parameters: dict) -> Mechanism:
    from kinelab.mechanisms._catalogue import _from_points
    return _from_points(f"{kind.name}_sixbar", {p: tuple(map(float, pts[p])) for p in kind.points},
                        kind.links, "jO2", dict(kind=kind.name, **parameters))


@dataclass(frozen=True, eq=False)
class SixBarSolution:
    """One synthesised six-bar.

    Attributes
    ----------
    model : Mechanism
        The linkage in its first precision position (its sketch); input ``jO2``.
    q : ndarray (n,)
        Crank angle at each precision point, rad.
    errors : ndarray (n,)
        Error at each point, measured by :func:`kinelab.analyze` of ``model``: distance of
        P from the target (path), that plus the task size times the angle error (motion),
        the output angle error (function, rad).
    relative_error : float
        The largest error over the task's size (path, motion) or in rad (function).
    defects : tuple of str
        "branch defect", "circuit defect", "order defect", "transmission angle defect"
        with an explanation; empty when the crank carries the linkage through the points
        in order on one assembly mode.
    min_transmission_angle : float
        Smallest transmission angle at the dyads' middle joints between the first and the
        last point, rad (NaN when the crank cannot get there).
    kind : str
        The kind asked for.
    direction : int
        +1 when the crank turns CCW from the first point to the last, -1 CW.
    """

    model: Mechanism
    q: np.ndarray
    errors: np.ndarray
    relative_error: float
    defects: tuple
    min_transmission_angle: float
    kind: str = ""
    direction: int = 1

    @property
    def valid(self) -> bool:
        return not self.defects

    def __repr__(self) -> str:
        state = "valid" if self.valid else "; ".join(d.split(":")[0] for d in self.defects)
        return (f"SixBarSolution({self.kind}, max relative error {self.relative_error:.2e}, "
                f"min transmission {math.degrees(self.min_transmission_angle):.1f} deg, {state})")


# ---------------------------------------------------------------- the task
def _task(kind_name: object, task: object):
    if not isinstance(kind_name, str) or kind_name not in _KINDS:
        raise ModelError(f"kind: expected one of {', '.join(repr(k) for k in _KINDS)}, got "
                         f"{describe(kind_name)}")
    kind = _KINDS[kind_name]
    if not isinstance(task, Mapping):
        raise ModelError(f"task: expected a mapping with 'path', 'function' or 'poses', got "
                         f"{describe(task)}")
    known = {"path", "inputs", "function", "poses"}
    extra = [k for k in task if k not in known]
    if extra:
        raise ModelError(f"task: unknown key {describe(extra[0])}; expected 'path' (with "
                         "optional 'inputs'), 'function' or 'poses'")
    which = [k for k in ("path", "function", "poses") if k in task]
    if len(which) != 1:
        raise ModelError("task: expected exactly one of 'path', 'function', 'poses', got "
                         f"{'none' if not which else ', '.join(which)}")
    mode = which[0]
    if "inputs" in task and mode != "path":
        raise ModelError("task['inputs']: crank angles go with a 'path' task only; remove them")
    if mode == "path":
        pts = point_array("task['path']", task["path"])
        if pts.ndim != 2 or len(pts) < 3:
            raise ModelError(f"task['path']: expected at least 3 points (x, y), shape (n, 2), got "
                             f"shape {pts.shape}; add points")
        inputs = None
        if "inputs" in task:
            inputs = angle_array("task['inputs']", task["inputs"])
            if inputs.shape != (len(pts),):
                raise ModelError(f"task['inputs']: expected one crank angle per point, shape "
                                 f"({len(pts)},), got shape {inputs.shape}")
            if np.any(np.diff(inputs) == 0):
                raise ModelError("task['inputs']: expected different crank angles at different "
                                 "points, got a repeated angle; give each point its own angle")
        _spread("task['path']", pts)
        return kind, mode, pts, inputs, None
    if mode == "poses":
        poses = np.asarray(_reals("task['poses']", task["poses"]))
        if poses.ndim != 2 or poses.shape[1] != 3 or len(poses) < 2:
            raise ModelError(f"task['poses']: expected at least 2 poses (x, y, angle), shape "
                             f"(n, 3), got shape {poses.shape}; add poses")
        pts = point_array("task['poses'] (x, y)", poses[:, :2])
        ang = angle_array("task['poses'] (angle)", poses[:, 2])
        turn = np.abs(np.angle(np.exp(1j * (ang[1:] - ang[0]))))
        if np.all(turn < 1e-6):
            raise ModelError("task['poses']: the poses do not turn (every angle equals the "
                             "first); a coupler that only translates is a path task: give "
                             "{'path': points}, or make the angles differ")
        _spread("task['poses']", pts)
        return kind, mode, pts, None, ang
    f = task["function"]
    if not isinstance(f, (tuple, list)) or len(f) != 2:
        raise ModelError(f"task['function']: expected (input_angles, output_angles), got "
                         f"{describe(f)}")
    x = angle_array("task['function'][0]", f[0])
    y = angle_array("task['function'][1]", f[1])
    if x.ndim != 1 or x.shape != y.shape or len(x) < 3:
        raise ModelError(f"task['function']: expected at least 3 pairs, input and output angles "
                         f"of the same shape (n,), got {x.shape} and {y.shape}; add pairs")
    if np.any(np.diff(x) == 0):
        raise ModelError("task['function'][0]: expected different input angles, got a "
                         "repeated angle; give each pair its own input angle")
    return kind, mode, None, x, y


def _reals(name, value):
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ModelError(f"{name}: expected real numbers, got {describe(value)}") from None
    if not np.all(np.isfinite(a)):
        raise ModelError(f"{name}: expected finite numbers, got a non-finite value; replace it")
    return a


def _spread(name, pts):
    size = np.sqrt(np.mean(np.sum((pts - pts.mean(0)) ** 2, axis=1)))
    if not size > 0:
        raise ModelError(f"{name}: expected points in different places, got them all at one "
                         "place; spread the points")


# ---------------------------------------------------------------- the objective
class _Problem:
    """Residuals of many candidates at once, in the task's normalised frame.

    A candidate x is the sketch (every point, flattened) and, for a path without timing,
    the crank's turn from the first point to each other one."""

    def __init__(self, kind, mode, pts, inputs, angles, mu_limit, between=3):
        self.kind, self.mode = kind, mode
        self.model = _model(kind, kind.sketch, {})
        self.names = [p.name for p in self.model.points]
        self.np = 2 * len(self.names)
        self.pts, self.inputs, self.angles = pts, inputs, angles
        self.mu_limit = mu_limit
        self.between = between
        if mode == "function":
            self.n = len(inputs)
            self.dq_free = False
        else:
            self.n = len(pts)
            self.dq_free = mode in ("path", "poses") and inputs is None
        self.nx = self.np + (self.n - 1 if self.dq_free else 0)
        self.default = np.concatenate([np.ravel([kind.sketch[p] for p in self.names]) / 4.0,
                                       np.zeros(self.nx - self.np)])
        self.iP = self.names.index("P")
        self.iA = self.names.index("A")
        self.iO2 = self.names.index("O2")

    def sketch(self, x):
        return x[:, :self.np].reshape(len(x), -1, 2)

    def q(self, x):
        """Crank angles (K, n) at the points, and the samples (K, S) moved through: the
        points and ``between`` steps between consecutive ones (so a linkage that falls
        apart between two points is seen)."""
        S = self.sketch(x)
        a = S[:, self.iA] - S[:, self.iO2]
        q0 = np.arctan2(a[:, 1], a[:, 0])
        if self.dq_free:
            dq = np.concatenate([np.zeros((len(x), 1)), x[:, self.np:]], axis=1)
        else:
            d = self.inputs - self.inputs[0]
            dq = np.broadcast_to(d, (len(x), self.n))
        q = q0[:, None] + dq
        t = np.linspace(0.0, 1.0, self.between + 2)[:-1]
        samples = (q[:, :-1, None] + np.diff(q, axis=1)[:, :, None] * t).reshape(len(x), -1)
        samples = np.concatenate([samples, q[:, -1:]], axis=1)
        return q, samples

    def residuals(self, x):
        """(K, m) residuals; rows of candidates that do not assemble on the way are inf."""
        K = len(x)
        bad = ~np.isfinite(x).all(axis=1)
        if bad.any():
            x = np.where(bad[:, None], self.default, x)
        q, samples = self.q(x)
        step = self.between + 1
        with np.errstate(all="ignore"):
            sol = analyze_designs(self.model, self.sketch(x), samples)
        ok = sol.by_design(sol.assembled).all(axis=1)
        at = np.arange(0, samples.shape[1], step)
        res = []
        if self.mode in ("path", "poses"):
            P = sol.position("P")[:, at]
            res.append((P - self.pts[None]).reshape(K, -1))
        if self.mode == "poses":
            C = sol.position(self.kind.coupler_ref)[:, at]
            res.append(_turn(C - P, self.angles))
        if self.mode == "function":
            a, b = self.kind.output_ref
            res.append(_turn(sol.position(b)[:, at] - sol.position(a)[:, at], self.angles))
        if self.mu_limit:
            mu = _transmission(self.kind, sol.position)
            # aim a little above the limit: a penalty leaves the optimum just inside it
            res.append(10.0 * np.maximum(self.mu_limit + _MU_MARGIN - mu, 0.0))
        # sketch lengths that collapse make a degenerate linkage: keep links above a floor
        S = self.sketch(x)
        res.append(self._short_links(S))
        # and keep the linkage within a few times the task's size
        res.append(np.maximum(np.linalg.norm(S, axis=2) - _REACH, 0.0))
        r = np.concatenate(res, axis=1)
        r[bad | ~ok | ~np.isfinite(r).all(axis=1)] = np.inf
        return r

    def _short_links(self, S):
        out = []
        names = self.names
        for link, pts in self.kind.links:
            for i, a in enumerate(pts):
                for b in pts[i + 1:]:
                    if "P" in (a, b):
                        continue
                    d = np.linalg.norm(S[:, names.index(a)] - S[:, names.index(b)], axis=1)
                    out.append(np.maximum(0.05 - d, 0.0) * 10.0)
        return np.stack(out, axis=1)


def _turn(v, angles):
    """Angle errors (K, n): the turn of vectors v (K, n, 2) from the first, against the
    prescribed turn of ``angles`` from the first."""
    th = np.arctan2(v[..., 1], v[..., 0])
    return np.angle(np.exp(1j * ((th - th[:, :1]) - (angles - angles[0]))))


def _transmission(kind, position):
    mus = []
    for P, X, Z in kind.dyads:
        u, w = position(X) - position(P), position(Z) - position(P)
        c = np.sum(u * w, axis=-1) / (np.linalg.norm(u, axis=-1) * np.linalg.norm(w, axis=-1))
        mu = np.arccos(np.clip(c, -1.0, 1.0))
        mus.append(np.minimum(mu, np.pi - mu))
    return np.min(np.stack(mus), axis=0)


def _levenberg_marquardt(problem, x, iterations, h=1e-7):
    """Batched Levenberg-Marquardt: every candidate's Jacobian (forward differences) and
    residuals in one kernel run per iteration; each candidate keeps its own damping."""
    K, n = x.shape
    r = problem.residuals(x)
    cost = np.sum(r * r, axis=1)
    lam = np.full(K, 1e-4)
    eye = np.eye(n)
    for _ in range(iterations):
        live = np.isfinite(cost) & (cost > 1e-30)
        if not live.any():
            break
        xl = x[live]
        k = len(xl)
        pert = np.repeat(xl[:, None], n, axis=1) + h * eye
        rp = problem.residuals(pert.reshape(-1, n)).reshape(k, n, -1)
        J = (rp - r[live][:, None]) / h                       # (k, n, m)
        J = np.where(np.isfinite(J), J, 0.0)
        g = np.einsum("knm,km->kn", J, r[live])
        H = np.einsum("knm,kpm->knp", J, J)
        scale = np.maximum(np.max(np.diagonal(H, axis1=1, axis2=2), axis=1), 1e-12)
        idx = np.flatnonzero(live)
        todo = np.ones(k, bool)
        for attempt in range(6):        # raise the damping of those whose step failed
            j = np.flatnonzero(todo)
            A = H[j] + (lam[idx[j]] * scale[j])[:, None, None] * eye
            step = np.linalg.solve(A, -g[j][..., None])[..., 0]
            trial = xl[j] + step
            rt = problem.residuals(trial)
            ct = np.sum(rt * rt, axis=1)
            better = ct < cost[idx[j]]
            won = idx[j][better]
            x[won], r[won], cost[won] = trial[better], rt[better], ct[better]
            lam[won] = np.maximum(lam[won] / 4.0, 1e-15)
            lam[idx[j][~better]] = np.minimum(lam[idx[j][~better]] * 10.0, 1e12)
            todo[j[better]] = False
            if not todo.any():
                break
    return x, r, cost


class _Done(Exception):
    """The residuals are down to rounding: stop refining."""


_ENOUGH = 1e-13     # residual (in task sizes) at which a candidate is refined enough


def _polish(problem, x, cost, h=1e-8):
    """Refine one candidate to the rounding of its residuals: scipy's trust-region least
    squares, each Jacobian one kernel run of the candidate's perturbed designs; it stops
    as soon as every residual is below ``_ENOUGH``."""
    from scipy.optimize import least_squares

    n = x.size
    best = [x, cost]
    if cost <= _ENOUGH ** 2:
        return x, cost

    def fun(v):
        r = problem.residuals(v[None])[0]
        c = float(r @ r)
        if c < best[1]:
            best[:] = [v.copy(), c]
            if np.max(np.abs(r)) <= _ENOUGH:
                raise _Done
        return r

    def jac(v):
        pert = v + h * np.eye(n)
        rp = problem.residuals(np.concatenate([v[None], pert]))
        J = ((rp[1:] - rp[0]) / h).T
        return np.where(np.isfinite(J), J, 0.0)
    try:
        with np.errstate(all="ignore"):
            least_squares(fun, x, jac=jac, method="trf", xtol=1e-15, ftol=1e-15,
                          gtol=1e-15, max_nfev=60)
    except (_Done, ValueError):
        pass
    return best[0], best[1]


# ---------------------------------------------------------------- checks by the engine
def _check(kind, mode, model, q, pts, angles, size, mu_limit):
    """Move ``model`` with kl.analyze through the points; errors and defects."""
    n = len(q)
    sol = analyze(model, q=q, unreachable="mask", at_singular="flag")
    errors = np.full(n, np.inf)
    if np.all(sol.assembled):
        if mode in ("path", "poses"):
            errors = np.linalg.norm(sol.position("P") - pts, axis=1)
        if mode == "poses":
            C = sol.position(kind.coupler_ref) - sol.position("P")
            errors = errors + size * np.abs(_turn(C[None], angles)[0])
        if mode == "function":
            a, b = kind.output_ref
            errors = np.abs(_turn((sol.position(b) - sol.position(a))[None], angles)[0])
    rel = float(np.max(errors) / (1.0 if mode == "function" else size))
    defects = []
    d = int(np.sign(q[-1] - q[0])) or 1
    order = np.all(np.diff(q) * d > 0)
    if not order:
        defects.append("order defect: turning the crank one way does not pass the points in "
                       f"the order 1..{n}")
    # sweep the crank from the first point to the last: on one assembly mode, never at a
    # limit or dead-centre position, and within a turn (else another circuit is in between)
    span = abs(q[-1] - q[0])
    grid = q[0] + d * np.linspace(0.0, span, max(2, int(math.ceil(span / math.radians(0.25)))))
    grid = np.unique(np.concatenate([grid, q])) if d > 0 else -np.unique(-np.concatenate([grid, q]))
    sweep = analyze(model, q=grid, unreachable="mask", at_singular="flag")
    s0 = np.sign(sweep.det_J[0])
    good = sweep.assembled & ~sweep.singular & (np.sign(sweep.det_J) == s0)
    mu = float("nan")
    if not good.all():
        lost = np.flatnonzero(~np.logical_and.accumulate(good))
        if not sweep.assembled.all():
            defects.append(f"circuit defect: the linkage cannot be moved from point 1 to point "
                           f"{n} (it falls apart at q = {grid[lost[0]]:.4f} rad): the points lie "
                           "on different circuits")
        else:
            defects.append(f"branch defect: a limit or dead-centre position at q = "
                           f"{grid[lost[0]]:.4f} rad lies between the points")
    else:
        mu = float(np.min(_transmission(kind, sweep.position)))
        if span >= 2 * np.pi:
            defects.append("circuit defect: the points need more than one turn of the crank")
    if mu_limit and not (mu >= mu_limit - 1e-9):
        defects.append(f"transmission angle defect: the smallest transmission angle is "
                       f"{math.degrees(mu):.1f} deg, below {math.degrees(mu_limit):.1f} deg")
    return errors, rel, tuple(defects), mu, d


# ---------------------------------------------------------------- the public function
def sixbar(kind: str, task: Mapping, *, starts: int = 2000, refine: int = 40,
           iterations: int = 60, solutions: int = 5, min_transmission_angle: float | None = None,
           degrees: bool = False, seed: int | None = 0) -> SolutionList:
    """Six-bar synthesis by optimisation: path, function or motion generation.

    Parameters
    ----------
    kind : {"watt1", "watt2", "stephenson1", "stephenson2", "stephenson3"}
        The inversion.  In every kind the input is the crank ``O2-A`` (joint ``jO2``, q =
        the crank's angle) and the path point is ``P``:

        - ``"watt1"`` (Watt I, ground binary): links ``ground (O2, O4)``, ternary ``crank
          (O2, A, C)``, ternary ``coupler (A, B, D)``, ``rocker (O4, B)``, ``link5 (C, E,
          P)``, ``link6 (D, E)``; path/motion link ``link5``; output ``link6`` (D -> E).
        - ``"watt2"`` (Watt II, the catalogue's :func:`kinelab.mechanisms.watt6` with P on
          link5): ``ground (O2, O4, O6)``, ``crank (O2, A)``, ``coupler (A, B)``, ternary
          ``rocker (O4, B, C)``, ``link5 (C, D, P)``, ``output (O6, D)``; path/motion link
          ``link5``; output ``output`` (O6 -> D).
        - ``"stephenson1"`` (ground binary joining the two ternary links): ``ground (O2,
          O4)``, ternary ``crank (O2, A, C)``, ``coupler (A, B)``, ternary ``rocker (O4, B,
          D)``, ``link5 (C, E, P)``, ``link6 (D, E)``; path/motion link ``link5``; output
          ``link6`` (D -> E).
        - ``"stephenson2"`` (ground binary, next to one ternary link only): ``ground (O2,
          O4)``, ``crank (O2, A)``, ternary ``coupler (A, B, C, P)``, ``link4 (B, D)``,
          ``link5 (C, E)``, ternary ``output (O4, D, E)``; no dyad solves it, so the engine
          uses Newton groups, much slower: give fewer ``starts``; path/motion link
          ``coupler`` (its angle from P to A); output ``output`` (O4 -> D).
        - ``"stephenson3"`` (Stephenson III, the catalogue's
          :func:`kinelab.mechanisms.stephenson6` with P on link5): ``ground (O2, O4, O6)``,
          ``crank (O2, A)``, ternary ``coupler (A, B, C)``, ``rocker (O4, B)``, ``link5 (C,
          D, P)``, ``output (O6, D)``; path/motion link ``link5``; output ``output``.

        The motion link's angle is that of the line from P to its other point (C, or A in
        stephenson2); only its turns from pose 1 matter.
    task : mapping
        One of

        - ``{"path": points}``: P passes through the points (n, 2), m, n >= 3, in order;
          the crank's angles are free unknowns too (16 sketch coordinates and n - 1 turns
          for 2n equations: exact up to 15 points in principle; the random starts find
          exact solutions readily for about 5 to 8);
        - ``{"path": points, "inputs": angles}``: with timing: P is at point i when the
          crank has turned ``angles[i] - angles[0]`` (rad) from point 1 (exact up to 8
          points: the 16 coordinates of the sketch);
        - ``{"function": (input_angles, output_angles)}``: the output link turns
          ``output[i] - output[0]`` while the crank turns ``input[i] - input[0]`` (rad),
          n >= 3 pairs; exact (precision points) while n - 1 is at most the 10 free
          dimensions of the linkage (its sketch up to a similarity), least squares beyond;
        - ``{"poses": [(x, y, angle), ...]}``: the motion link passes through the poses,
          P at (x, y) (m), turned ``angle[i] - angle[0]`` (rad) from pose 1; n >= 2, the
          angles not all equal.
    starts : int
        Random candidates evaluated together in one kernel run.
    refine : int
        The best candidates refined together by batched Levenberg-Marquardt.
    iterations : int
        Levenberg-Marquardt iterations.
    solutions : int
        How many solutions to return, best first.
    min_transmission_angle : float, optional
        rad (deg with ``degrees``): kept by a penalty during the search and checked; a
        solution below it has a transmission angle defect.
    seed : int, optional
        Seed of the random starts (results are repeatable with a seed).

    Returns
    -------
    SolutionList of SixBarSolution
        Best first: valid solutions before defective ones, then by error.  Each one's
        ``errors`` are measured by :func:`kinelab.analyze` of its ``model``.

    Raises
    ------
    ModelError
        An unknown kind, a task that is not one of the above, too few points, non-finite
        values, poses that do not turn.

    Examples
    --------
    The output of the catalogue's Stephenson III over 45 deg of its crank, generated again
    (the output's angle from O6 to D):

    >>> s6 = kl.mechanisms.stephenson6()
    >>> q = np.radians([90, 105, 120, 135])
    >>> sol = kl.analyze(s6, q=q)
    >>> v = sol.position("D") - sol.position("O6")
    >>> phi = np.arctan2(v[:, 1], v[:, 0])
    >>> found = kl.synthesis.sixbar("stephenson3", {"function": (q, phi)}, starts=500,
    ...                             refine=10, iterations=20, seed=0)
    >>> best = found[0]
    >>> best.valid, bool(best.relative_error < 1e-9)
    (True, True)
    >>> check = kl.analyze(best.model, q=best.q)
    >>> w = check.position("D") - check.position("O6")
    >>> turn = np.arctan2(w[:, 1], w[:, 0])
    >>> bool(np.allclose(turn - turn[0], phi - phi[0], atol=1e-9))
    True
    """
    kind, mode, pts, inputs, angles = _task(kind, task)
    for name, value in (("starts", starts), ("refine", refine), ("iterations", iterations),
                        ("solutions", solutions)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise ModelError(f"{name}: expected a positive whole number, got {describe(value)}")
    mu_limit = None
    if min_transmission_angle is not None:
        mu_limit = float(angle_array("min_transmission_angle", min_transmission_angle, degrees))
        if not 0.0 <= mu_limit < np.pi / 2:
            raise ModelError("min_transmission_angle: expected an angle in [0, 90) deg, got "
                             f"{math.degrees(mu_limit):g} deg")
    # normalise: centre, unit size, first point along +x from the centre
    if mode == "function":
        c, s, R, t = np.zeros(2), 1.0, np.eye(2), 0.0
        npts = None
    else:
        c = pts.mean(axis=0)
        s = float(np.sqrt(np.mean(np.sum((pts - c) ** 2, axis=1))))
        v = pts[0] - c
        t = math.atan2(v[1], v[0]) if np.hypot(*v) > 1e-9 * s else 0.0
        R = np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])
        npts = (pts - c) @ R / s          # rotate by -t
    nangles = None if angles is None else (angles - (t if mode == "poses" else 0.0))
    problem = _Problem(kind, mode, npts, inputs, nangles, mu_limit)
    rng = np.random.default_rng(seed)

    x0 = _starts(problem, rng, starts)
    with np.errstate(all="ignore"):
        r = problem.residuals(x0)
    cost = np.sum(r * r, axis=1)
    order = np.argsort(cost)[:refine]
    order = order[np.isfinite(cost[order])]
    if order.size == 0:
        return SolutionList([], reason="no random start assembles through the points; "
                                       "try more starts or another seed")
    x, r, cost = _levenberg_marquardt(problem, x0[order].copy(), iterations)
    best = np.argsort(cost)[:2 * solutions]
    best = best[np.isfinite(cost[best])]
    for i in best:
        x[i], cost[i] = _polish(problem, x[i], cost[i])
    best = best[np.argsort(cost[best])]
    out = []
    size = 1.0 if mode == "function" else s
    for i in best:
        if not np.isfinite(cost[i]) or len(out) >= 4 * solutions:
            break
        S = problem.sketch(x[i:i + 1])[0]
        pts_world = S * s @ R.T + c if mode != "function" else S
        sk = dict(zip(problem.names, map(tuple, pts_world)))
        q, _ = problem.q(x[i:i + 1])
        q = q[0] + (t if mode != "function" else 0.0)    # the frame was turned by -t
        model = _model(kind, sk, dict(task=mode))
        errors, rel, defects, mu, d = _check(kind, mode, model, q, pts, angles, size, mu_limit)
        if not np.isfinite(rel):
            continue
        out.append(SixBarSolution(model, q, errors, rel, defects, mu, kind.name, d))
    out.sort(key=lambda z: (bool(z.defects), z.relative_error))
    return SolutionList(out[:solutions], reason="" if out else
                        "no candidate assembles through the points; try more starts")


def _starts(problem, rng, count):
    """Random sketches in the normalised frame: joints in boxes of random sizes around the
    task, P on the first point; the crank's turns between points, for a path without
    timing, spread evenly over a random part of a turn either way."""
    P = len(problem.names)
    S = rng.uniform(-1.0, 1.0, (count, P, 2))
    if problem.mode == "function":       # a function generator has no size: one box
        S *= 2.0
    else:
        # linkages from about the task's size to ten times it: a small task (a short
        # stretch of a path, poses that turn little) is often met best by a large linkage
        S *= np.exp(rng.uniform(np.log(1.5), np.log(15.0), count))[:, None, None]
    if problem.mode in ("path", "poses"):
        S[:, problem.iP] = problem.pts[0]
    x = S.reshape(count, -1)
    if problem.dq_free:
        n = problem.n
        total = rng.uniform(0.3, 1.9, count) * np.pi * rng.choice([-1.0, 1.0], count)
        w = rng.uniform(0.5, 1.5, (count, n - 1))
        dq = np.cumsum(w, axis=1) / np.sum(w, axis=1, keepdims=True) * total[:, None]
        x = np.concatenate([x, dq], axis=1)
    return x
