"""A synthesized four-bar as a kinelab model, and the checks every solution carries.

The model is built straight from its four pivots in position 1 (not from lengths), so its
sketch *is* position 1 and the engine follows position 1's assembly branch.  The checks
then move it with the planar kinematics engine (:func:`kinelab.analyze`):

- every prescribed pose must be reached on that branch at the crank angle where the
  crank pin is in its prescribed place;
- **branch defect**: a prescribed pose lies on the other branch, or the crank cannot
  turn from position 1 to it (either way round) without passing a limit or singular
  (dead-centre) configuration;
- **order defect**: the crank cannot pass the positions in the order 1, 2, ..., n while
  turning one way;
- the Grashof class and the smallest transmission angle met on the way, against a limit
  (:data:`TRANSMISSION_LIMIT`, 30 deg, by default): a linkage below it has a
  **transmission angle defect**.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.kinematics import KinematicSolution, analyze, plan, transmission_angle
from kinelab.mechanisms import Grashof, grashof
from kinelab.model import (MAX_LENGTH, MIN_LENGTH, Input, Joint, Link, Mechanism, Point,
                           is_real, length_problem)
from kinelab.synthesis._positions import as_xy, cross, fmt

__all__ = ["fourbar_model", "CheckedLinkage", "Travel", "travel", "circuits", "nearer_branch",
           "TRANSMISSION_LIMIT", "transmission_limit", "transmission_defects", "planned"]

_SWEEP_STEP = math.radians(0.5)   # crank step of the sweeps that look for limit positions
_DEGENERATE = 1e-12               # relative length below which a link has no length
MAX_SPAN = 1e6                    # longest link over shortest: beyond, the shortest's motion is
                                  # within the rounding of the loop's closure (eps x 1e6 ~ 2e-10)
# The smallest transmission angle a synthesized linkage may have over its travel, unless the
# task says otherwise: a rule of thumb for smooth running and good force transmission.  Alt,
# who introduced the transmission angle (1932), asked for about 40 deg; 30 deg is the looser
# floor common in practice, and the one kept here.
TRANSMISSION_LIMIT = math.radians(30.0)
_MU_SLACK = 1e-9                  # rad: a transmission angle this close to the limit meets it


def fourbar_model(A0: ArrayLike, B0: ArrayLike, A1: ArrayLike, B1: ArrayLike,
                  P: ArrayLike | None = None, *, name: str = "fourbar") -> Mechanism:
    """A four-bar model built from its pivots (and coupler point) in one configuration.

    The catalogue's names: links ``ground`` (``O2 = A0``, ``O4 = B0``), ``crank``
    (``O2, A``), ``coupler`` (``A, B`` and ``P``), ``rocker`` (``O4, B``); joints ``jO2,
    jA, jB, jO4``; the input is ``jO2`` (q = the crank's angle from +x).  The given
    configuration is the model's sketch, so it fixes the assembly branch.

    Parameters
    ----------
    A0, B0 : array_like, shape (2,)
        Fixed pivots of the crank and of the rocker, m.
    A1, B1 : array_like, shape (2,)
        Moving pivots (crank pin and rocker pin), m.
    P : array_like, shape (2,), optional
        A coupler point, m.

    Returns
    -------
    Mechanism
        ``parameters`` holds ``kind = "fourbar"``, the four lengths, the coupler point as
        (along AB, perpendicular to AB) from A, and the branch ("open" when B is to the
        left of the line from A to O4, as in :func:`kinelab.mechanisms.fourbar`).

    Raises
    ------
    ModelError
        A link of zero length (two pivots in the same place).

    Examples
    --------
    >>> m = kl.synthesis.fourbar_model(A0=(0, 0), B0=(2, 0), A1=(1, 0), B1=(1.5, 0.8660254037844386))
    >>> sol = kl.analyze(m, q=0.0)                       # *Mecanismos*, Ex. 4.2 (open branch)
    >>> np.degrees(sol.angle("rocker")).round(9), m.parameters["branch"]
    (np.float64(120.0), 'open')
    """
    A0, B0, A1, B1 = (as_xy(n, v) for n, v in (("A0", A0), ("B0", B0), ("A1", A1), ("B1", B1)))
    pts = [A0, B0, A1, B1] + ([as_xy("P", P)] if P is not None else [])
    size = max(float(np.ptp(np.array(pts), axis=0).max()), 1e-300)
    lengths = {"ground": (B0, A0, "the fixed pivots A0 and B0"),
               "crank": (A1, A0, "the crank's pivots A0 and A1"),
               "coupler": (B1, A1, "the moving pivots A1 and B1"),
               "rocker": (B1, B0, "the rocker's pivots B0 and B1")}
    value = {}
    problems = []
    for link, (a, b, what) in lengths.items():
        value[link] = float(np.hypot(*(a - b)))      # hypot: no underflow at small scales
        if value[link] <= _DEGENERATE * size:
            problems.append(f"{link}: {what} coincide at {fmt(a)}, so the "
                            f"{link} has no length; choose another pivot")
    if problems:
        raise ModelError(problems)
    # a linkage outside the sizes kinelab computes with (a task given at the scale of atoms
    # or of planets): one line for the task, not one per link
    out = [f"{link} {value[link]:.3g} m" for link in lengths if length_problem(value[link])]
    far = max(float(np.abs(np.array(pts)).max()), 0.0)
    if out or far > MAX_LENGTH:
        what = (f"links ({', '.join(out)})" if out else f"pivots (up to {far:.3g} m from the "
                "origin)")
        raise ModelError(f"the four-bar found has {what} outside the sizes kinelab computes with "
                         f"(lengths from {MIN_LENGTH:g} m to {MAX_LENGTH:g} m, coordinates up to "
                         f"{MAX_LENGTH:g} m); give the task in other units, near the origin")
    shortest, longest = min(value.values()), max(value.values())
    if longest > MAX_SPAN * shortest:
        raise ModelError(f"the four-bar found has links from {shortest:.3g} m to {longest:.3g} m, "
                         f"more than {MAX_SPAN:g} times apart: its motion is lost in the rounding "
                         "of the longest; choose pivots nearer the positions")
    e = (B1 - A1) / value["coupler"]
    side = float(cross(B0 - A1, B1 - A1))
    points = [Point("O2", *map(float, A0)), Point("A", *map(float, A1)),
              Point("B", *map(float, B1)), Point("O4", *map(float, B0))]
    coupler_points: tuple[str, ...] = ("A", "B")
    coupler_point = None
    if P is not None:
        Pv = as_xy("P", P)
        points.append(Point("P", *map(float, Pv)))
        coupler_points = ("A", "B", "P")
        r = Pv - A1
        coupler_point = (float(r @ e), float(cross(e, r)))
    return Mechanism(
        name=name, points=tuple(points),
        links=(Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
               Link("coupler", coupler_points), Link("rocker", ("O4", "B"))),
        joints=tuple(Joint(f"j{p}", "R", (a, b), point=p) for p, a, b in (
            ("O2", "ground", "crank"), ("A", "crank", "coupler"), ("B", "coupler", "rocker"),
            ("O4", "ground", "rocker"))),
        inputs=(Input(joint="jO2"),),
        parameters=dict(kind="fourbar", **value, coupler_point=coupler_point,
                        branch="open" if side > 0 else "crossed"),
    )


def model_grashof(model: Mechanism) -> Grashof:
    """Grashof class of a four-bar model from :func:`fourbar_model`."""
    p = model.parameters
    return grashof(p["ground"], p["crank"], p["coupler"], p["rocker"])


def transmission_limit(value, degrees: bool = False) -> float:
    """The ``min_transmission_angle`` of a task, rad: None for :data:`TRANSMISSION_LIMIT`, else
    an angle in [0, pi/2) rad ([0, 90) deg with ``degrees``)."""
    if value is None:
        return TRANSMISSION_LIMIT
    top, unit = ("90", "deg") if degrees else ("pi/2", "rad")
    if not (is_real(value) and 0.0 <= value < (90.0 if degrees else math.pi / 2)):
        raise ModelError(f"min_transmission_angle: expected an angle in [0, {top}) {unit}, got "
                         f"{describe(value)}")
    return math.radians(float(value)) if degrees else float(value)


def _deg(angle: float) -> str:
    return f"{math.degrees(angle):.4g} deg"


def transmission_defects(mu_min: float, limit: float, span: str) -> tuple[str, ...]:
    """The transmission angle defect of a linkage whose transmission angle drops to
    ``mu_min`` (rad) ``span`` ("between position 1 and position 3"), when that is below
    ``limit``; none when it is not (or when no travel was measured: other defects say why)."""
    if not mu_min < limit - _MU_SLACK:
        return ()
    return (f"transmission angle defect: the transmission angle drops to {_deg(mu_min)} "
            f"{span}, below the limit of {_deg(limit)} (min_transmission_angle): the coupler "
            "pushes the rocker too nearly along it; choose another linkage, or lower the limit",)


def planned(model: Mechanism, where: str, remedy: str) -> Mechanism:
    """The synthesized four-bar ``model``, its engine plan made (and cached on it).

    The model is sketched in a configuration the task prescribes.  Where the coupler and
    the rocker are in line there, the sketch is a dead centre where the two assembly modes
    meet, and the engine cannot start from it; that is said in the task's terms: ``where``
    names the task's item (``"input_range, output_range: at the precision point x = 0"``),
    ``remedy`` what to change.  The engine's own error is kept as the cause."""
    try:
        plan(model)
    except ModelError as exc:
        O2, A, B, O4 = (np.array(model.point(n).xy) for n in ("O2", "A", "B", "O4"))
        size = max(float(np.ptp(np.array([O2, A, B, O4]), axis=0).max()), 1e-300)
        flat = abs(float(cross(A - O2, O4 - O2))) <= 1e-9 * size * size
        what = ("the linkage is flat: its four pivots lie on one line, the crank, the coupler and "
                "the rocker all along the ground line" if flat else
                f"the crank pin {fmt(A)}, the rocker pin {fmt(B)} and the rocker's pivot "
                f"{fmt(O4)} are in line, so the coupler and the rocker are")
        raise ModelError(f"{where}: {what}: a dead centre, where the four-bar's two assembly modes "
                         "meet, so it cannot tell which one is meant (and transmits no force to "
                         f"the rocker there); {remedy}") from exc
    return model


class CheckedLinkage:
    """What every synthesized four-bar result offers (it has ``model``, ``defects``,
    ``min_transmission_angle`` and ``transmission_limit``)."""

    model: Mechanism
    defects: tuple[str, ...]
    min_transmission_angle: float
    transmission_limit: float

    @property
    def valid(self) -> bool:
        """No defect: the engine reaches every prescribed configuration, in order, on one
        branch, with a transmission angle of at least ``transmission_limit`` all the way."""
        return not self.defects

    @property
    def meets_transmission_limit(self) -> bool:
        """The smallest transmission angle over the travel is at least ``transmission_limit``
        (False when it could not be measured)."""
        return bool(self.min_transmission_angle >= self.transmission_limit - _MU_SLACK)

    @property
    def lengths(self) -> dict[str, float]:
        """The link lengths ``ground, crank, coupler, rocker``, m."""
        return {k: self.model.parameters[k] for k in ("ground", "crank", "coupler", "rocker")}

    @property
    def state(self) -> str:
        """'valid', or the names of the defects."""
        return "valid" if self.valid else "; ".join(d.split(":")[0] for d in self.defects)


@dataclass(frozen=True, eq=False)
class Travel:
    """How the crank carries a four-bar through prescribed configurations (internal)."""

    direction: int                 # +1 CCW, -1 CW, 0: no single sense works
    branch_defect: bool
    order_defect: bool
    min_transmission_angle: float  # rad, over the travel from the first to the last
    defects: tuple[str, ...]


def travel(model: Mechanism, q: np.ndarray,
           reached: Callable[[KinematicSolution, np.ndarray], np.ndarray]) -> Travel:
    """Sweep the crank of ``model`` from q[0] both ways and classify the motion.

    Parameters
    ----------
    model : Mechanism
        Sketched in configuration 1 (so its branch is configuration 1's).
    q : ndarray, shape (n,)
        Crank angle of each prescribed configuration, rad.
    reached : callable
        ``reached(sol, idx)`` -> (n,) bool: whether the engine's configuration at samples
        ``idx`` of ``sol`` is the prescribed one.
    """
    n = q.size
    reach = {}
    deltas = {}
    mu_min = {}
    # The distance from the crank pin to O4 is monotonic between its extremes, where the
    # crank points at O4 or away from it; so is the transmission angle.  Sampling those two
    # angles as well makes the sweep exact: a limit position, however narrow the gap it
    # opens, and the smallest transmission angle are both met at a sample.
    g = np.subtract(model.point("O4").xy, model.point("O2").xy)
    extremes = math.atan2(g[1], g[0]) + np.array([0.0, np.pi])
    for d in (1, -1):
        delta = np.mod(d * (q - q[0]), 2 * np.pi)
        delta[0] = 0.0
        turns = np.mod(d * (extremes - q[0]), 2 * np.pi)
        grid = np.unique(np.concatenate([
            np.linspace(0.0, delta.max(), max(2, math.ceil(delta.max() / _SWEEP_STEP) + 1)),
            delta, turns[turns < delta.max()]]))
        sol = analyze(model, q[0] + d * grid, unreachable="mask", at_singular="flag")
        sign0 = np.sign(sol.det_J[0])
        good = sol.assembled & ~sol.singular & (np.sign(sol.det_J) == sign0)
        clear = np.logical_and.accumulate(good)
        idx = np.searchsorted(grid, delta)
        reach[d] = clear[idx] & reached(sol, idx)
        deltas[d] = delta
        mu = transmission_angle(sol)
        upto = np.arange(grid.size) <= idx.max()
        ok = clear & upto
        mu_min[d] = float(np.min(mu[ok])) if ok.any() else float("nan")
    defects = []
    reachable = reach[1] | reach[-1]
    # the order is judged on the positions that can be reached at all (a branch defect is
    # reported once, as such)
    works = [d for d in (1, -1) if reachable.any()
             and np.all(np.diff(deltas[d][reachable]) > 0) and reach[d][reachable].all()]
    branch_defect = not reachable.all()
    if branch_defect:
        lost = ", ".join(str(j + 1) for j in np.flatnonzero(~reachable))
        defects.append(f"branch defect: position(s) {lost} cannot be reached from position 1 "
                       "on its assembly branch without passing a limit or dead-centre position")
    order_defect = not works
    if order_defect:
        defects.append("order defect: turning the crank one way does not pass the positions "
                       f"in the order 1..{n}")
        direction = 0
        both = [mu_min[d] for d in (1, -1) if not math.isnan(mu_min[d])]
        mu = min(both) if both else float("nan")
    else:
        direction = min(works, key=lambda d: deltas[d][reachable].max())
        mu = mu_min[direction]
    return Travel(direction, branch_defect, order_defect, mu, tuple(defects))


# The joint whose angle tells a Grashof four-bar's two circuits apart: one of the joints of
# the link opposite the shortest.  Its two links can never come into line (that would need
# s + l > p + q), so the sign of its angle is fixed on each circuit (Chase and Mirth,
# "Circuits and branches of single-degree-of-freedom planar linkages", 1993).
_CIRCUIT_JOINT = {"crank-rocker": "B", "rocker-crank": "A", "double-crank": "A",
                  "double-rocker": "O2"}


def circuits(A0: np.ndarray, B0: np.ndarray, A: np.ndarray, B: np.ndarray,
             kind: Grashof) -> np.ndarray | None:
    """The circuit (+1 or -1) of each configuration of a Grashof four-bar, shape (n,), from
    its pivots A0, B0 and its moving pivots A, B (n, 2); None when the linkage has one
    circuit (non-Grashof or change-point)."""
    joint = _CIRCUIT_JOINT.get(kind.kind) if kind.margin > 0 else None
    if joint is None:
        return None
    u, v = {"B": (B - A, B - B0), "A": (A - A0, B - A), "O2": (B0 - A0, A - A0)}[joint]
    return np.sign(cross(u, v))


def nearer_branch(sol: KinematicSolution, idx: np.ndarray, B: np.ndarray,
                  B0: np.ndarray) -> np.ndarray:
    """(n,) bool: the engine's rocker pin at samples ``idx`` is nearer the prescribed pins
    ``B`` (n, 2) than its mirror image across the line from the crank pin to ``B0`` (where
    the other assembly branch puts it) is."""
    Ae, Be = sol.position("A")[idx], sol.position("B")[idx]
    d = B0 - Ae
    n = np.stack([-d[:, 1], d[:, 0]], -1) / np.linalg.norm(d, axis=1)[:, None]
    Bm = Be - 2.0 * np.sum((Be - Ae) * n, axis=1)[:, None] * n
    near = np.linalg.norm(Be - B, axis=1) <= np.linalg.norm(Bm - B, axis=1)
    return near & np.all(np.isfinite(Be), axis=1)


def at_inputs(model: Mechanism, q: np.ndarray) -> KinematicSolution:
    """The engine's configurations at q on the sketch's branch (masked where it cannot close)."""
    return analyze(model, q, unreachable="mask", at_singular="flag")


def finite_or_inf(a: np.ndarray) -> np.ndarray:
    """Errors with the samples the engine could not assemble set to +inf (never NaN)."""
    return np.where(np.isfinite(a), a, np.inf)
