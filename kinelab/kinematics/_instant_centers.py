"""Instant centres of velocity of every pair of links.

Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*
(Universidade do Minho, 2007), §4.5.
"""
from __future__ import annotations

import itertools
from collections.abc import Iterator, Mapping
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, describe, quoted, shown, suggest
from kinelab.kinematics._geometry import k_cross
from kinelab.kinematics._solution import KinematicSolution, takes_solution

__all__ = ["InstantCenter", "InstantCenters", "instant_center", "instant_centers"]

_PARALLEL = 1e-12   # relative angular velocity, against the fastest link's, below which the
                    # pair translates: its instant centre is at infinity


@dataclass(frozen=True)
class InstantCenter:
    """The instant centre I_ab of links a and b: the point with the same velocity on both.

    I_ab and I_ba are one point: the pair may be named in either order, and the centre is the
    same, down to the direction of a centre at infinity.

    Attributes
    ----------
    links : (str, str)
        The two links, in model order (whatever order they were asked in).
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


class InstantCenters(Mapping):
    """Instant centres keyed by pairs of link names, in either order.

    ``ic["crank", "coupler"]`` and ``ic["coupler", "crank"]`` are the same
    :class:`InstantCenter`; iteration gives each pair once, in model order.
    """

    def __init__(self, centers: dict[tuple[str, str], InstantCenter]):
        self._centers = dict(centers)

    def __getitem__(self, pair) -> InstantCenter:
        if isinstance(pair, tuple) and len(pair) == 2:
            found = self._centers.get(pair) or self._centers.get(pair[::-1])
            if found is not None:
                return found
        raise KeyError(f"{describe(pair)}: expected a pair of two different links, in either order, "
                       f"such as {describe(next(iter(self._centers), ('a', 'b')))}")

    def __iter__(self) -> Iterator[tuple[str, str]]:
        return iter(self._centers)

    def __len__(self) -> int:
        return len(self._centers)

    def __repr__(self) -> str:
        return f"InstantCenters({len(self)} pairs: {', '.join('-'.join(p) for p in self)})"


@takes_solution
def instant_center(sol: KinematicSolution, a: str, b: str) -> InstantCenter:
    """Instant centre of links ``a`` and ``b`` at every sample.

    With one input the centres come from the velocity coefficients K, so they do not depend
    on the input speed; with several inputs they come from the velocities (which depend on
    the ratio of the input speeds ``qd``, so ``qd`` must not be zero).

    Solving ``v_a + w_a k x (P - A) = v_b + w_b k x (P - B)`` for P gives
    ``P = -k x (v_b - v_a + w_a k x A - w_b k x B) / (w_a - w_b)``.

    Parameters
    ----------
    sol : KinematicSolution
    a, b : str
        Two different links, in either order: ``(a, b)`` and ``(b, a)`` give the same centre.

    Returns
    -------
    InstantCenter
        Shapes by the rule of ``sol``: (2,) or (N, 2) positions.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=2.0, crank=1.0, coupler=2.0, rocker=1.0)
    >>> sol = kl.analyze(fb, q=np.pi / 2)         # a parallelogram: crank and rocker upright
    >>> ic = kl.kinematics.instant_center(sol, "ground", "coupler")
    >>> bool(ic.at_infinity), np.abs(ic.direction).round(12).tolist()  # the coupler translates
    (True, [0.0, 1.0])
    >>> kl.kinematics.instant_center(sol, "crank", "coupler").position.round(12).tolist()
    [0.0, 1.0]
    >>> I21 = kl.kinematics.instant_center(sol, "crank", "ground")     # either order: I12
    >>> I21.links, bool(np.allclose(I21.position, sol.position("O2")))  # the crank's pivot
    (('ground', 'crank'), True)
    """
    pair = _model_order(sol, a, b)
    return _centers(sol, [pair])[pair]


@takes_solution
def instant_centers(sol: KinematicSolution) -> InstantCenters:
    """Every instant centre, keyed by a pair of link names in either order.

    A mechanism of n links has n (n - 1) / 2 of them; by Kennedy's theorem the three
    centres of any three links lie on one line (tested).

    Examples
    --------
    >>> sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    >>> ic = kl.kinematics.instant_centers(kl.analyze(sc, q=0.5))
    >>> len(ic), ic["crank", "ground"] is ic["ground", "crank"]
    (6, True)
    """
    return InstantCenters(_centers(sol, list(itertools.combinations(sol.link_names, 2))))


def _model_order(sol: KinematicSolution, a: str, b: str) -> tuple[str, str]:
    """The pair (a, b) as two known, different links, in model order."""
    order = list(sol.link_names)
    for name in (a, b):
        if name not in order:
            raise ModelError(f"link: expected one of {quoted(order)}, got {describe(name)}"
                             f"{suggest(str(name), order)}")
    if a == b:
        raise ModelError(f"links: expected two different links, got {shown(a)} twice; a link has "
                         "no instant centre with itself")
    return (a, b) if order.index(a) < order.index(b) else (b, a)


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
    centers = {}
    for a, b in pairs:
        (pa, va, wa), (pb, vb, wb) = motion[a], motion[b]
        rhs = vb - va + wa[:, None] * k_cross(pa) - wb[:, None] * k_cross(pb)
        dw = wa - wb
        infinite = np.abs(dw) <= _PARALLEL * np.maximum(scale, 1e-300)
        with np.errstate(divide="ignore", invalid="ignore"):
            position = np.where(infinite[:, None], 0.0,
                                -k_cross(rhs) / np.where(infinite, 1.0, dw)[:, None])
        # where dw = 0 the relative velocity is the same at every point: at a's reference
        # point it is v_b + w_b k x (pa - pb) - v_a (a guide turning with its slider counts)
        rel = vb - va + wb[:, None] * k_cross(pa - pb)
        norm = np.linalg.norm(rel, axis=-1)
        direction = np.where((infinite & (norm > 0))[:, None],
                             k_cross(rel) / np.where(norm > 0, norm, 1.0)[:, None], 0.0)
        if sol.single:
            position, infinite, direction = position[0], infinite[0], direction[0]
        centers[(a, b)] = InstantCenter((a, b), position, infinite, direction)
    return centers
