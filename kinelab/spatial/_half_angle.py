"""E cos θ + F sin θ + G = 0 by the half-angle substitution, vectorised (private).

A stand-in for ``kinelab.solvers.half_angle`` with the same column convention, kept
private to this room until the spatial code can import the solvers room.
"""
from __future__ import annotations

import numpy as np

from kinelab.spatial._common import wrap

# |G| and sqrt(E² + F²) closer than this, relative to sqrt(E² + F² + G²), count as equal
# (one double root).  A tool point placed exactly on a workspace boundary by forward
# kinematics misses it by a few ulp; 1e-14 absorbs that and no more.
TANGENT_TOL = 1e-14


def half_angle(E: np.ndarray, F: np.ndarray, G: np.ndarray, *,
               tol: float = TANGENT_TOL) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Roots of ``E cos θ + F sin θ + G = 0``, element by element.

    With ``u = tan(θ/2)`` the equation becomes ``(G - E) u² + 2F u + (G + E) = 0``
    (notes 003, eq. 24), ``u = (-F ± s) / (G - E)``, ``s = sqrt(E² + F² - G²)``.  The
    root is taken as ``θ = 2 atan2(-F ± s, G - E)``, which keeps θ = π when ``G = E``
    (where the quadratic loses it), or, when ``-F ± s`` would cancel, from the product
    of the roots, ``θ = 2 atan2(G + E, -F ∓ s)``.

    On the root with ``+s``, ``dΦ/dθ = F cos θ - E sin θ = +s``; on the other it is
    ``-s``.  The columns therefore follow the two assembly branches continuously and
    meet only where ``s = 0``.

    Returns
    -------
    theta : ndarray, shape (..., 2), rad in (-π, π]
        Column 0 the ``+s`` root, column 1 the ``-s`` root; both hold the double root
        where ``count == 1``, and the closest-approach angle (not a root) where
        ``count == 0``.  Never NaN.
    count : ndarray of int, shape (...)
        Distinct real roots: 2, 1 or 0 (``E² + F² < G²``, or ``E = F = 0``).
    gap : ndarray, shape (...)
        ``max(|G| - sqrt(E² + F²), 0)``, in the units of the coefficients.
    """
    E, F, G = np.broadcast_arrays(*(np.asarray(c, dtype=float) for c in (E, F, G)))
    R = np.hypot(E, F)
    scale = np.hypot(R, G)
    margin = R - np.abs(G)
    tangent = (np.abs(margin) <= tol * scale) & (R > 0)
    count = np.where(tangent, 1, np.where((margin > 0) & (R > 0), 2, 0))
    unit = np.where(scale > 0, scale, 1.0)          # homogeneous: solve with unit size
    e, f, g, r = E / unit, F / unit, G / unit, R / unit
    s = np.sqrt(np.where(count == 2, (r - np.abs(g)) * (r + np.abs(g)), 0.0))
    roots = []
    for sign in (1.0, -1.0):
        direct = sign * f <= 0                      # -f and sign*s add without cancelling
        num = np.where(direct, -f + sign * s, g + e)
        den = np.where(direct, g - e, -f - sign * s)
        roots.append(2.0 * np.arctan2(num, den))
    theta = np.stack(roots, axis=-1)
    # Double root (and no root): the angle that brings E cos θ + F sin θ closest to -G.
    closest = np.where(G > 0, np.arctan2(-F, -E), np.arctan2(F, E))
    theta = wrap(np.where((count < 2)[..., None], closest[..., None], theta))
    gap = np.where(count == 0, np.maximum(-margin, 0.0), 0.0)
    return theta, count, gap
