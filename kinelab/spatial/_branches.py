"""Where two branches of a one-input mechanism cross: K and L along each.

At a change point of ``Φ(q, S) = 0`` (one input q, one secondary coordinate S), both
``Φ_q`` and ``Φ_S`` vanish: ``K = -Φ_q / Φ_S`` is 0/0 and the row ``[Φ_q Φ_S]`` has lost
rank.  (Where only ``Φ_S`` vanishes, it is a limit position instead: K is unbounded.)
Along a branch through it, ``S = Sc + K δ + L δ²/2 + …`` with ``δ = q - qc``, and ``Φ = 0``
order by order gives

- δ²: ``½ Φ_SS K² + Φ_qS K + ½ Φ_qq = 0``: each root is the K of one branch;
- δ³: ``L = -(Φ_qqq + 3 Φ_qqS K + 3 Φ_qSS K² + Φ_SSS K³) / (3 (Φ_qS + Φ_SS K))``.

Along a branch ``Φ_S ≈ (Φ_qS + Φ_SS K) δ``, so the sign of ``Φ_qS + Φ_SS K`` tells which
branch has which sign of Φ_S just past the change point (δ > 0).
"""
from __future__ import annotations

import numpy as np

__all__ = ["through_change_point"]


def through_change_point(phi_qq, phi_qS, phi_SS, phi_qqq, phi_qqS, phi_qSS, phi_SSS,
                         sign) -> tuple[np.ndarray, np.ndarray]:
    """K and L at change points of ``Φ(q, S) = 0``, on the branch along which ``Φ_S`` has
    the sign ``sign`` (±1) just past the change point (towards larger q).

    Parameters
    ----------
    phi_qq, …, phi_SSS : array_like, broadcast together
        Second and third partial derivatives of Φ at the change points.
    sign : array_like of ±1, broadcast with them

    Returns
    -------
    K, L : ndarray
        ``dS/dq`` and ``d²S/dq²`` along that branch.  The caller makes sure the branches
        cross (two distinct real roots): where they only touch, or the point is isolated,
        these are not defined.

    Examples
    --------
    ``Φ = (S - q - q²)(S + 2q - q²/2)``: two branches cross at the origin, ``S = q + q²``
    (K = 1, L = 2, Φ_S > 0 past it) and ``S = -2q + q²/2`` (K = -2, L = 1, Φ_S < 0):

    >>> from kinelab.spatial._branches import through_change_point
    >>> jets = (-4.0, 1.0, 2.0, -9.0, -3.0, 0.0, 0.0)       # Φ_qq, Φ_qS, Φ_SS, Φ_qqq, …
    >>> [tuple(float(x) for x in through_change_point(*jets, s)) for s in (1, -1)]
    [(1.0, 2.0), (-2.0, 1.0)]
    """
    a, b, c = 0.5 * np.asarray(phi_SS), np.asarray(phi_qS), 0.5 * np.asarray(phi_qq)
    slope = sign * np.sqrt(np.maximum(b * b - 4.0 * a * c, 0.0))     # Φ_qS + Φ_SS K
    # The root with 2 a K + b = slope, from whichever form does not cancel; the second also
    # serves a = 0, where the other branch is the line q = qc (S moves, q does not).
    with np.errstate(divide="ignore", invalid="ignore"):
        K = np.where(sign * b > 0.0, 2.0 * c / (-b - slope), (slope - b) / (2.0 * a))
        L = -(phi_qqq + 3.0 * phi_qqS * K + 3.0 * phi_qSS * K**2 + phi_SSS * K**3) / (
            3.0 * slope)
    return K, L
