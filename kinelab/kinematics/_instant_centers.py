"""Instant centres of velocity of every pair of links (seed 002, §4.5)."""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError
from kinelab.kinematics._solution import KinematicSolution

__all__ = ["InstantCenter", "instant_center", "instant_centers"]

_PARALLEL = 1e-12   # relative angular velocity, against the fastest link's, below which the
                    # pair translates: its instant centre is at infinity


@dataclass(frozen=True)
class InstantCenter:
    """The instant centre I_ab of links a and b: the point with the same velocity on both.

    Attributes
    ----------
    links : (str, str)
    position : ndarray, shape (2,) or (N, 2)
        m; meaningful where ``at_infinity`` is False.
    at_infinity : ndarray of bool, shape () or (N,)
        The links translate relative to each other: the centre lies at infinity.
    direction : ndarray, shape (2,) or (N, 2)
        Unit direction towards the centre at infinity (perpendicular to the relative
        velocity); zero where the centre is finite.
    """

    links: tuple[str, str]
    position: np.ndarray
    at_infinity: np.ndarray
    direction: np.ndarray


def _link_motion(sol: KinematicSolution, link: str, column: int | None):
    """(point on the link, its velocity-like vector, angular velocity-like scalar), (N, ...).

    ``column`` = an input index: use the velocity coefficients K of that input (M = 1 gives
    centres independent of speed); None: use the actual velocities.
    """
    m = sol.mechanism
    ref = m.link(link).points[0]
    i = sol.point_item[ref]
    li = sol.link_item[link]
    jets = sol.item_jets([i, i + 1, li])
    if column is None:
        rates = sol.item_rates([i, i + 1, li])
        return jets[:, :2, 0], rates[:, :2, 0], rates[:, 2, 0]
    return jets[:, :2, 0], jets[:, :2, 1 + column], jets[:, 2, 1 + column]


def instant_center(sol: KinematicSolution, a: str, b: str) -> InstantCenter:
    """Instant centre of links ``a`` and ``b`` at every sample.

    With one input the centres come from the velocity coefficients K, so they do not depend
    on the input speed; with several inputs they come from the velocities (which depend on
    the ratio of the input speeds ``qd``, so ``qd`` must not be zero).

    Solving ``v_a + w_a k x (P - A) = v_b + w_b k x (P - B)`` for P gives
    ``P = -k x (v_b - v_a + w_a k x A - w_b k x B) / (w_a - w_b)``.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=2.0, rocker=1.0)
    >>> sol = kl.analyze(fb, q=np.pi / 2)         # a parallelogram: crank and rocker upright
    >>> ic = kl.kinematics.instant_center(sol, "ground", "coupler")
    >>> bool(ic.at_infinity), np.abs(ic.direction).round(12).tolist()  # the coupler translates
    (True, [0.0, 1.0])
    >>> kl.kinematics.instant_center(sol, "crank", "coupler").position.round(12).tolist()
    [0.0, 1.0]
    """
    return _centers(sol, [(a, b)])[(a, b)]


def instant_centers(sol: KinematicSolution) -> dict[tuple[str, str], InstantCenter]:
    """Every instant centre, keyed by the pair of link names (in model order).

    A mechanism of n links has n (n - 1) / 2 of them; by Kennedy's theorem the three
    centres of any three links lie on one line (tested).
    """
    return _centers(sol, list(itertools.combinations(sol.link_names, 2)))


def _centers(sol: KinematicSolution, pairs) -> dict[tuple[str, str], InstantCenter]:
    """The centres of the given pairs, each link's motion gathered once."""
    column = 0 if sol.M == 1 else None
    if column is None and not np.any(sol.qd):
        raise ModelError("qd: with several inputs the instant centres depend on the ratio of "
                         "the input speeds, and every qd is zero; analyze with the speeds qd")
    motion = {link: _link_motion(sol, link, column) for link in dict.fromkeys(itertools.chain(*pairs))}
    # angular-velocity scale of the mechanism at each sample: the fastest link
    items = list(sol.link_item.values())
    scale = np.max(np.abs(sol.item_jets(items)[:, :, 1 + column] if column is not None
                          else sol.item_rates(items)[:, :, 0]), axis=1)

    def kx(v):
        return np.stack([-v[..., 1], v[..., 0]], axis=-1)
    centers = {}
    for a, b in pairs:
        (pa, va, wa), (pb, vb, wb) = motion[a], motion[b]
        rhs = vb - va + wa[:, None] * kx(pa) - wb[:, None] * kx(pb)
        dw = wa - wb
        infinite = np.abs(dw) <= _PARALLEL * np.maximum(scale, 1e-300)
        with np.errstate(divide="ignore", invalid="ignore"):
            position = np.where(infinite[:, None], 0.0,
                                -kx(rhs) / np.where(infinite, 1.0, dw)[:, None])
        rel = vb - va                      # relative translation velocity where dw = 0
        norm = np.linalg.norm(rel, axis=-1)
        direction = np.where((infinite & (norm > 0))[:, None],
                             kx(rel) / np.where(norm > 0, norm, 1.0)[:, None], 0.0)
        if sol.single:
            position, infinite, direction = position[0], infinite[0], direction[0]
        centers[(a, b)] = InstantCenter((a, b), position, infinite, direction)
    return centers
