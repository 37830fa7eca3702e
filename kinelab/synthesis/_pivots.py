"""Pivots of a crank (or rocker) that guides a point of the moving plane on a circle.

A crank with fixed pivot A0 and moving pivot A (a point of the moving plane) keeps its
length, so every position A_j of A lies on one circle about A0 (*Mecanismos*, eq. 67):

    |A_j - A0|^2 = |A_1 - A0|^2,        j = 2 .. n.

Given A0, these are *linear* in A_1 (Suh and Radcliffe, eq. 68); given A_1 they are
linear in A0 (A0 is the centre of the circle through A_1 .. A_n).  With three positions
either way gives one pivot; with four, A0 must lie on the centre-point curve (eq. 71,
:mod:`kinelab.synthesis._burmester`).
"""
from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.model import MAX_LENGTH
from kinelab.synthesis._positions import Positions, as_positions, as_xy, fmt, poles, rotation

__all__ = ["suh_radcliffe_rows", "moving_pivot", "fixed_pivot", "standard_form_dyad"]

_SINGULAR = 1e-10   # sine of the angle between the two equations' normals below which
                    # the pivot is at infinity (to rounding)
_SHORTEST = 1e-9    # a dyad link shorter than this, relative to the task, is no link
_CONSISTENT = 1e-9  # relative residual above which more than three positions disagree


def suh_radcliffe_rows(pos: Positions, A0: np.ndarray) -> np.ndarray:
    """The rows [A~, B, C] of eq. 68/70 for every position j = 2..n, shape (..., n-1, 3).

    Written relative to P1 (unknown a = A1 - P1, fixed pivot a0 = A0 - P1), which is the
    notes' system translated by P1 and better conditioned when the task is far from the
    origin:  [2 R_j^T d_j + 2 (I - R_j^T) a0] . a = 2 d_j . a0 - |d_j|^2, d_j = P_j - P1.
    ``A0`` may carry leading batch axes, shape (..., 2).
    """
    R = rotation(pos.alpha[1:])                        # (n-1, 2, 2)
    d = pos.points[1:] - pos.points[0]                 # (n-1, 2)
    a0 = np.asarray(A0, float)[..., None, :] - pos.points[0]   # (..., 1, 2)
    Rt_d = np.einsum("kji,kj->ki", R, d)               # R^T d
    ItR = np.eye(2) - np.swapaxes(R, -1, -2)           # I - R^T
    lhs = 2.0 * Rt_d + 2.0 * np.einsum("kij,...kj->...ki", ItR, np.broadcast_to(a0, a0.shape[:-2] + d.shape))
    rhs = 2.0 * np.sum(d * a0, axis=-1) - np.sum(d * d, axis=-1)
    return np.concatenate([lhs, rhs[..., None]], axis=-1)


def circle_rows(pos: Positions, A1: np.ndarray) -> np.ndarray:
    """Rows [2 (A_j - A_1), |A_j - A_1|^2] of the centre of the circle through the A_j,
    written for the unknown A0 - A1; shape (n-1, 3)."""
    Aj = pos.carry(A1)
    r = Aj[1:] - Aj[0]
    return np.concatenate([2.0 * r, np.sum(r * r, axis=-1)[:, None]], axis=-1)


def solve_rows(rows: np.ndarray, scale: float, what: str, why_singular: str) -> np.ndarray:
    """Solve k >= 2 equations [a b].x = c for x (2,); raise when x is at infinity or, with
    k > 2, when the equations disagree."""
    M, c = rows[:, :2], rows[:, 2]
    norms = np.linalg.norm(M, axis=1)
    s = np.linalg.svd(M, compute_uv=False)
    if s[-1] <= _SINGULAR * max(norms.max(), 1e-300):
        raise ModelError(f"{what}: {why_singular}")
    x, *_ = np.linalg.lstsq(M, c, rcond=None)
    if rows.shape[0] > 2:
        # one scale for every row: a row may vanish (A0 at a pole P1j satisfies it for any A1)
        res = np.abs(M @ x - c) / max(norms.max() * (np.linalg.norm(x) + scale), 1e-300)
        if res.max() > _CONSISTENT:
            raise ModelError(f"{what}: with {rows.shape[0] + 1} positions the pivot must satisfy "
                             "the compatibility condition (*Mecanismos*, eq. 71), and this one "
                             f"misses it by {res.max():.3g} (relative); choose it on the centre-point "
                             "curve (see four_positions / center_points)")
    return x


def moving_pivot(points, angles=None, fixed: ArrayLike = None, *,
                 method: Literal["suh-radcliffe", "poles"] = "suh-radcliffe",
                 degrees: bool = False) -> np.ndarray:
    """The moving pivot (in position 1) of a crank whose fixed pivot is given.

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Three (or more) positions of the moving plane.
    fixed : array_like, shape (2,)
        The fixed pivot A0, m.
    method : {"suh-radcliffe", "poles"}
        "suh-radcliffe": the linear system of *Mecanismos*, eq. 68 (least squares over all
        positions when there are more than three, which must then be compatible).
        "poles": Burmester's construction (§6.2, fig. 53) for three positions: the
        line P12-A0 turned about P12 by -alpha_12/2 meets the line P13-A0 turned about
        P13 by -alpha_13/2 in A1.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    ndarray, shape (2,)
        A1, m.

    Raises
    ------
    ModelError
        The moving pivot is at infinity (the positions of A0 seen from the moving
        plane are collinear), or, with four positions or more, ``fixed`` is not a
        centre point.

    Examples
    --------
    *Mecanismos*, §6.5 (Table 4):

    >>> P, alpha = [(1, 1), (2, 0.5), (3, 1.5)], np.radians([0, 45])
    >>> kl.synthesis.moving_pivot(P, alpha, fixed=(5, 0)).round(3)
    array([ 3.548, -1.655])
    >>> kl.synthesis.moving_pivot(P, alpha, fixed=(5, 0), method="poles").round(3)
    array([ 3.548, -1.655])
    """
    pos = as_positions(points, angles, degrees)
    A0 = as_xy("fixed", fixed)
    if pos.n < 3:
        raise ModelError(f"points: a moving pivot needs three positions or more, got {pos.n}; "
                         "with two, every point of the moving plane works (two_positions)")
    if method == "poles":
        return _burmester_moving_pivot(pos, A0)
    if method != "suh-radcliffe":
        raise ModelError(f"method: expected one of 'suh-radcliffe', 'poles', got {describe(method)}")
    scale = float(np.ptp(np.vstack([pos.points, A0]), axis=0).max())
    rows = suh_radcliffe_rows(pos, A0)
    a = solve_rows(rows, scale, f"fixed pivot {fmt(A0)}",
                   "it gives no moving pivot: seen from the moving plane, its positions are "
                   "collinear, so the moving pivot is at infinity (the coupler would need a "
                   "slider); choose another fixed pivot")
    return a + pos.points[0]


def fixed_pivot(points, angles=None, moving: ArrayLike = None, *, degrees: bool = False) -> np.ndarray:
    """The fixed pivot of a crank whose moving pivot (in position 1) is given.

    The centre of the circle through the positions A_1 .. A_n of the moving pivot: the
    intersection of the perpendicular bisectors of A1A2 and A2A3 (*Mecanismos*, §6.2).

    Parameters
    ----------
    points, angles : see :class:`Positions`
        Three (or more) positions of the moving plane.
    moving : array_like, shape (2,)
        The moving pivot A1 in position 1, m.
    degrees : bool
        Angles in degrees.

    Returns
    -------
    ndarray, shape (2,)
        A0, m.

    Raises
    ------
    ModelError
        The positions of A are collinear (the circle is a straight line: a slider, not
        a crank, would guide A), or, with four positions or more, A1 is not a circle
        point.

    Examples
    --------
    The inverse of the *Mecanismos*, §6.5 example:

    >>> P, alpha = [(1, 1), (2, 0.5), (3, 1.5)], np.radians([0, 45])
    >>> A1 = kl.synthesis.moving_pivot(P, alpha, fixed=(5, 0))
    >>> kl.synthesis.fixed_pivot(P, alpha, moving=A1).round(12) + 0.0
    array([5., 0.])
    """
    pos = as_positions(points, angles, degrees)
    A1 = as_xy("moving", moving)
    if pos.n < 3:
        raise ModelError(f"points: a fixed pivot needs three positions or more, got {pos.n}; "
                         "with two it can be anywhere on the perpendicular bisector of A1A2 "
                         "(two_positions)")
    Aj = pos.carry(A1)
    scale = float(np.ptp(np.vstack([pos.points, Aj]), axis=0).max())
    rows = circle_rows(pos, A1)
    x = solve_rows(rows, scale, f"moving pivot {fmt(A1)}",
                   "its positions are collinear (or coincide), so no circle passes through them "
                   "and the fixed pivot is at infinity; choose another moving pivot")
    return x + A1


def _burmester_moving_pivot(pos: Positions, A0: np.ndarray) -> np.ndarray:
    if pos.n != 3:
        raise ModelError(f"method: 'poles' is Burmester's construction for three positions, got "
                         f"{pos.n}; use method='suh-radcliffe'")
    p = poles(pos)
    lines = []          # each: a point of the line that carries A1, and its direction
    for j in (2, 3):
        k = p.pairs.index((1, j))
        if not p.finite[k]:
            # a pure translation t (pole at infinity): A1 is on the bisector's image, the
            # line through A0 - t/2 perpendicular to t (the limit of the construction)
            t = pos.points[j - 1] - pos.points[0]
            lines.append((A0 - 0.5 * t, np.array([-t[1], t[0]])))
            continue
        Pij = p.P[k]
        d = A0 - Pij
        if np.linalg.norm(d) <= 1e-12 * max(np.linalg.norm(Pij), pos.size):
            raise ModelError(f"fixed pivot {fmt(A0)} is the pole P1{j}, so the line P1{j}-A0 of "
                             "Burmester's construction is undefined; choose another fixed pivot")
        lines.append((Pij, rotation(-0.5 * p.alpha[k]) @ d))
    (p1, d1), (p2, d2) = lines
    M = np.column_stack([d1, -d2])
    if abs(np.linalg.det(M)) <= _SINGULAR * np.linalg.norm(d1) * np.linalg.norm(d2):
        raise ModelError(f"fixed pivot {fmt(A0)} gives no moving pivot: the two turned lines of "
                         "Burmester's construction are parallel (the moving pivot is at "
                         "infinity); choose another fixed pivot")
    t = np.linalg.solve(M, p2 - p1)
    return p1 + t[0] * d1


def standard_form_dyad(pos: Positions, beta: np.ndarray, name: str,
                       link: str = "crank") -> tuple[np.ndarray, np.ndarray]:
    """The dyad of three positions whose link turns by ``beta = (beta_2, beta_3)`` (rad).

    Erdman and Sandor's standard form (Norton, *Design of Machinery*, ch. 5): with W the
    link, from its fixed pivot to its moving pivot in position 1, and Z from the moving
    pivot to the coupler point P1 (complex numbers), position j puts P at
    ``A0 + W e^{i beta_j} + Z e^{i alpha_j}``, so

        W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j = P_j - P_1,   j = 2, 3,

    two complex equations, linear in W and Z once beta_2, beta_3 are chosen.  Returns the
    fixed pivot A0 = P1 - Z - W and the moving pivot A1 = P1 - Z, m.  ``name`` is the
    argument blamed when the equations fix no dyad, ``link`` the link's name in that
    message.
    """
    delta = (pos.points[1:] - pos.points[0]) @ np.array([1.0, 1j])       # (2,) complex
    eb = np.exp(1j * beta) - 1.0
    ea = np.exp(1j * pos.alpha[1:]) - 1.0
    det = eb[0] * ea[1] - eb[1] * ea[0]
    norm = np.sqrt((abs(eb[0]) ** 2 + abs(ea[0]) ** 2) * (abs(eb[1]) ** 2 + abs(ea[1]) ** 2))
    if not abs(det) > _SINGULAR * norm:
        raise ModelError(f"{name}: these rotations of the {link} and the coupler's rotations "
                         "alpha_2, alpha_3 do not fix the dyad (W (e^(i beta_j) - 1) + "
                         "Z (e^(i alpha_j) - 1) = delta_j is singular: the rotations are both "
                         "zero, equal to the coupler's, or in proportion to them); choose other "
                         "rotations")
    W = (delta[0] * ea[1] - delta[1] * ea[0]) / det
    Z = (eb[0] * delta[1] - eb[1] * delta[0]) / det
    P1 = pos.points[0]
    A1 = P1 - np.array([Z.real, Z.imag])
    A0 = A1 - np.array([W.real, W.imag])
    if not abs(W) > _SHORTEST * pos.size:
        raise ModelError(f"{name}: with these rotations the {link} comes out of zero length "
                         f"(its pivots both at {fmt(A0)}); choose other rotations")
    if not np.all(np.abs(np.concatenate([A0, A1])) <= MAX_LENGTH):
        raise ModelError(f"{name}: with these rotations the {link}'s pivots come out at "
                         f"{fmt(A0)} and {fmt(A1)}, beyond the coordinates kinelab computes "
                         f"with ({MAX_LENGTH:g} m); choose other rotations")
    return A0, A1
