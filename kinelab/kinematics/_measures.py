"""Design measures computed from the analysis: transmission angle, quick-return time ratio."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.errors import AssemblyError, ModelError, SingularityError, describe, expected_one_of
from kinelab.kinematics._solution import KinematicSolution, takes_solution
from kinelab.model import Mechanism
from kinelab.solvers import bisect, turn_intervals, wrap_angle
from kinelab.solvers._arguments import whole

__all__ = ["transmission_angle", "time_ratio", "TimeRatio"]


@takes_solution
def transmission_angle(sol: KinematicSolution, links: tuple[str, str] = ("coupler", "rocker"),
                       *, acute: bool = True) -> np.ndarray:
    """Transmission angle: the angle between the coupler and the output link, rad.

    For the catalogue four-bar (coupler A->B, rocker O4->B) it is the angle at B between BA
    and BO4, in [0, pi]; with ``acute=True`` (the usual design measure) it is folded to
    [0, pi/2]: 90 deg is ideal, near 0 the linkage locks.  Shape () or (N,).

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=1.0, rocker=1.0)
    >>> round(float(np.degrees(kl.kinematics.transmission_angle(kl.analyze(fb, q=0.0)))), 12)  # Ex. 4.2
    60.0
    """
    if isinstance(links, str) or not isinstance(links, (tuple, list)) or len(links) != 2:
        raise ModelError(f"links: expected two links, the coupler and the output, got "
                         f"{describe(links)}")
    a, b = links
    if a == b:
        raise ModelError(f"links: expected two different links, got {describe(links)}; the "
                         "angle between a link and itself is 0")
    mu = np.abs(wrap_angle(sol.angle(a) - sol.angle(b)))
    return np.minimum(mu, np.pi - mu) if acute else mu


@dataclass(frozen=True)
class TimeRatio:
    """Quick-return time ratio of a crank-driven output.

    Attributes
    ----------
    ratio : float
        Slow-stroke input angle over fast-stroke input angle (>= 1).
    dead_centres : ndarray, shape (2,)
        Input values (rad, in [0, 2 pi)) where the output reverses: its velocity
        coefficient K is zero.
    slow, fast : float
        Input angles swept during each stroke, rad (they add up to one turn).
    """

    ratio: float
    dead_centres: np.ndarray
    slow: float
    fast: float


def time_ratio(mechanism: Mechanism, output: str, *, samples: int = 3601) -> TimeRatio:
    """Time ratio of a quick-return mechanism driven at constant crank speed.

    The output (a link angle or a slide) reverses where its velocity coefficient K
    vanishes; the crank angles between the two reversals give the two strokes.

    Parameters
    ----------
    mechanism : Mechanism
        Driven by one crank angle, which must turn a full turn.
    output : str
        A link or a prismatic joint (a slider's reversal is its joint's).
    samples : int
        Samples over the turn where K's sign changes are looked for (then bisected), from
        3 to 1,000,000.

    Returns
    -------
    TimeRatio

    Raises
    ------
    AssemblyError
        The crank cannot turn a full turn (its ``reachable`` attribute lists the input
        intervals it reaches): the output has no time ratio.
    SingularityError
        The turn passes a singular configuration, where K of the output is undefined.
    ModelError
        Not one crank input, or the output does not reverse exactly twice per turn.

    Examples
    --------
    >>> w = kl.mechanisms.whitworth(crank=1.0, distance=0.5, lever=1.0, rod=2.0)
    >>> round(kl.kinematics.time_ratio(w, "ram_slide").ratio, 12)   # (pi + 2 asin 1/2) / (pi - 2 asin 1/2)
    2.0
    >>> rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    >>> kl.kinematics.time_ratio(rocker, "rocker")       # non-Grashof: |q| <= acos(-0.3125)
    Traceback (most recent call last):
    ...
    kinelab.errors.AssemblyError: time_ratio: 'rocker' has no time ratio: its input 'jO2' cannot turn a full turn; it reaches only [-1.88862, 1.88862] rad (its limit positions); ...
    """
    from kinelab.kinematics._analyze import MAX_SEARCH_SAMPLES, analyze, plan, reachable_ranges

    p = plan(mechanism)
    if p.input_kinds != ("angle",):
        raise ModelError("time_ratio: expected a mechanism driven by one crank angle, "
                         f"got inputs {list(mechanism.input_names)}")
    samples = whole("samples", samples, 3, MAX_SEARCH_SAMPLES)
    if output not in p.link_item and output not in p.slide_item:
        outputs = list(p.link_item) + list(p.slide_item)
        hint = ("; a point has no time ratio of its own: give the link or the prismatic joint "
                "that carries it" if output in p.point_item else "")
        raise ModelError(f"time_ratio: output: {expected_one_of(output, outputs)}{hint}")
    q0 = float(p.q_sketch[0])
    q = q0 + np.linspace(0.0, 2.0 * math.pi, samples)

    def K(x):
        return analyze(mechanism, q=x, unreachable="mask", at_singular="flag").K(output)

    sweep = analyze(mechanism, q=q, unreachable="mask", at_singular="flag")
    k = sweep.K(output)
    name = mechanism.input_names[0]
    if not sweep.assembled.all():
        reach = turn_intervals(reachable_ranges(mechanism))
        spans = " and ".join(f"[{a:.6g}, {b:.6g}]" for a, b in reach)
        raise AssemblyError(
            f"time_ratio: '{output}' has no time ratio: its input '{name}' cannot turn a full "
            f"turn; it reaches only {spans} rad (its limit positions); a time ratio needs a "
            "crank that turns fully: change the link lengths (Grashof's condition for a "
            "four-bar, crank + |offset| < rod for a slider-crank)",
            loop=name, reachable=reach)
    if sweep.singular.any():
        closest = np.where(sweep.singular, sweep.singularity, np.inf)
        at = float(np.mod(q[np.argmin(closest)], 2.0 * math.pi))
        raise SingularityError(
            f"time_ratio: the turn of '{name}' passes a singular configuration near q = "
            f"{at:.6g} rad (det J = 0), where the velocity coefficient K of '{output}' is not "
            "defined; its time ratio is not defined either")
    sign = np.sign(k)
    changes = np.flatnonzero(sign[:-1] * sign[1:] < 0)
    if len(changes) != 2:
        raise ModelError(f"time_ratio: '{output}' reverses {len(changes)} times per turn; a "
                         "quick-return output reverses exactly twice")
    positive = sign[changes] > 0        # K > 0 on the left side of each bracket

    def inside(x):
        k = K(x)
        return np.where(positive, k > 0, k < 0)
    a, b = bisect(inside, q[changes], q[changes + 1])
    dc = 0.5 * (a + b)
    first = float(dc[1] - dc[0])
    second = 2.0 * math.pi - first
    slow, fast = max(first, second), min(first, second)
    return TimeRatio(ratio=slow / fast, dead_centres=np.mod(dc, 2.0 * math.pi), slow=slow, fast=fast)

