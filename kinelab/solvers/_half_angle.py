"""E cos θ + F sin θ + G = 0 by the half-angle (tangent) substitution, vectorised."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError
from kinelab.solvers._angles import wrap_angle
from kinelab.solvers._arguments import finite, flag, reals, tolerance

__all__ = ["HalfAngleSolution", "half_angle"]

# A root counts as double (tangent case) when |G| and sqrt(E² + F²) agree to this, relative
# to sqrt(E² + F² + G²): about 45 ulp, wide enough for the rounding of coefficients that come
# out of a mechanism's geometry at a toggle, narrow enough that the two merged roots lie
# within ~1.4e-7 rad of each other (separation ~ 2 sqrt(2 tol)).
_TANGENT_TOL = 1e-14
# A larger tolerance would merge roots that are visibly apart (about 2 sqrt(2 tol) rad).
_MAX_TOL = 1e-3


@dataclass(frozen=True)
class HalfAngleSolution:
    """Roots of ``E cos θ + F sin θ + G = 0``, element by element.

    The shapes below use ``...`` for the broadcast shape of ``E``, ``F`` and ``G``.

    Attributes
    ----------
    theta : ndarray, shape (..., 2), rad in (-π, π]
        ``theta[..., 0]`` is the "+" root of the notes' formula
        ``u = tan(θ/2) = (-F + sqrt(E² + F² - G²)) / (G - E)``, ``theta[..., 1]`` the "−"
        root.  Equivalently ``theta[..., 0] = atan2(F, E) - acos(-G / sqrt(E² + F²))`` and
        ``theta[..., 1] = atan2(F, E) + acos(-G / sqrt(E² + F²))`` (mod 2π), so each column
        follows one assembly branch continuously as the coefficients vary.  Where there is
        one root (``count == 1``) both columns hold it.  Where there is none
        (``count == 0``) both columns hold the **closest-approach angle**, the θ that makes
        ``|E cos θ + F sin θ + G|`` smallest (``atan2(F, E)`` if G < 0, ``atan2(-F, -E)``
        if G > 0); there the equation misses by ``gap``.  Never NaN.
    count : ndarray of int, shape (...)
        Number of distinct real roots: 2, 1 (tangent: ``E² + F² = G²``) or 0
        (``E² + F² < G²``, or the degenerate ``E = F = 0``).
    gap : ndarray, shape (...)
        ``max(|G| - sqrt(E² + F²), 0)``: by how much the equation fails to have a root, in
        the units of E, F, G; zero where ``count > 0`` (and where E = F = G = 0).
    """

    theta: np.ndarray
    count: np.ndarray
    gap: np.ndarray

    @property
    def real(self) -> np.ndarray:
        """Shape (...) bool: the equation has at least one real root there."""
        return self.count > 0

    def __repr__(self) -> str:
        return (f"HalfAngleSolution(theta={self.theta!r}, count={self.count!r}, "
                f"gap={self.gap!r})")


def half_angle(E: ArrayLike, F: ArrayLike, G: ArrayLike, *, strict: bool = False,
               tol: float = _TANGENT_TOL) -> HalfAngleSolution:
    """Solve ``E cos θ + F sin θ + G = 0`` for θ, in every case.

    The substitution ``u = tan(θ/2)`` (``cos θ = (1 - u²)/(1 + u²)``,
    ``sin θ = 2u/(1 + u²)``) turns the equation into the quadratic
    ``(G - E) u² + 2F u + (G + E) = 0`` (*Mecanismos*, eq. 24), with roots
    ``u = (-F ± s)/(G - E)``, ``s = sqrt(E² + F² - G²)``.  Two refinements make this
    exact in floating point:

    - ``θ = 2 atan2(-F ± s, G - E)``: no division, so the root θ = π, which the quadratic
      loses when ``G = E`` (its leading coefficient vanishes, ``u → ∞``), comes out
      naturally;
    - when ``-F ± s`` would cancel, the same root is taken from the product of the roots,
      ``u = (G + E)/(-F ∓ s)`` (the stable quadratic formula).

    Parameters
    ----------
    E, F, G : float or array_like, broadcastable to a common shape (...)
        Coefficients, in any one unit (often m or m²).
    strict : bool, default False
        Raise :class:`~kinelab.errors.AssemblyError` if any element has no real root,
        instead of reporting it in ``count`` and ``gap``.
    tol : float, default 1e-14
        Relative tolerance, from 0 to below 1e-3, (to ``sqrt(E² + F² + G²)``) within which ``|G|`` and
        ``sqrt(E² + F²)`` count as equal: a double root (``count == 1``).

    Returns
    -------
    HalfAngleSolution
        ``theta`` (..., 2) rad, ``count`` (...) int, ``gap`` (...).

    Raises
    ------
    AssemblyError
        With ``strict=True``, where ``|G| > sqrt(E² + F²)``; the message gives by how much
        and where.  Its ``gap`` attribute is the largest gap.
    ModelError
        If the coefficients do not broadcast or are not finite real numbers.

    References
    ----------
    *Mecanismos*, §4.5, eqs. 23-24 and Ex. 4.2.

    Examples
    --------
    *Mecanismos*, Ex. 4.2 (four-bar L1 = 2, L2 = L3 = L4 = 1, θ2 = 0): E = 2, F = 0, G = 1,
    so ``2 cos θ4 + 1 = 0`` and θ4 = ±120°:

    >>> sol = kl.solvers.half_angle(2.0, 0.0, 1.0)
    >>> np.degrees(sol.theta), sol.count
    (array([-120., 120.]), array(2))

    The root θ = π that ``u = tan(θ/2)`` loses when G = E (here ``cos θ + sin θ + 1 = 0``):

    >>> np.degrees(kl.solvers.half_angle(1.0, 1.0, 1.0).theta)
    array([-90., 180.])

    Tangent (one root) and no root (closest approach, and by how much it misses):

    >>> sol = kl.solvers.half_angle([1.0, 1.0], [0.0, 0.0], [-1.0, -1.5])
    >>> sol.theta, sol.count, sol.gap
    (array([[0., 0.], [0., 0.]]), array([1, 0]), array([0. , 0.5]))
    """
    strict = flag("strict", strict)
    tol = tolerance("tol", tol, zero=True, below=_MAX_TOL)
    coefficients = {name: reals(name, c) for name, c in (("E", E), ("F", F), ("G", G))}
    try:
        E, F, G = np.broadcast_arrays(*coefficients.values())
    except ValueError:
        shapes = ", ".join(f"{name} {c.shape}" for name, c in coefficients.items())
        raise ModelError(f"E, F, G: expected arrays of shapes that broadcast together, got "
                         f"{shapes}; pass arrays of one common shape") from None
    for name, c in zip("EFG", (E, F, G)):
        finite(name, c, "check the geometry that produced them")

    R = np.hypot(E, F)
    scale = np.hypot(R, G)                     # no under- or overflow in squares
    margin = R - np.abs(G)                     # > 0: two roots, < 0: none
    degenerate = R == 0.0                      # E = F = 0: no θ-dependence at all
    tangent = (np.abs(margin) <= tol * scale) & ~degenerate
    count = np.where(degenerate | (margin < 0) & ~tangent, 0, np.where(tangent, 1, 2))

    # The equation is homogeneous in (E, F, G): work with unit-size coefficients, so that
    # nothing below under- or overflows whatever their magnitude.
    unit = np.where(scale > 0, scale, 1.0)
    e, f, g, r = E / unit, F / unit, G / unit, R / unit
    # s = sqrt(e² + f² - g²) as sqrt((r - |g|)(r + |g|)): no cancellation in squares.
    s = np.sqrt(np.where(count == 2, (r - np.abs(g)) * (r + np.abs(g)), 0.0))
    theta = np.empty(E.shape + (2,))
    for column, sigma in enumerate((1.0, -1.0)):
        # Use (-f + σs, g - e) when -f and σs share a sign (no cancellation), otherwise the
        # product form (g + e, -f - σs), whose second member is then -σ(|f| + s) != 0.
        # With two roots s > 0, so neither pair is ever (0, 0).
        first = sigma * f <= 0
        num = np.where(first, -f + sigma * s, g + e)
        den = np.where(first, g - e, -f - sigma * s)
        theta[..., column] = 2.0 * np.arctan2(num, den)

    closest = np.where(G > 0, np.arctan2(-F, -E), np.arctan2(F, E))
    theta = np.where((count < 2)[..., None], closest[..., None], theta)
    theta = wrap_angle(theta)
    gap = np.where(count == 0, np.maximum(-margin, 0.0), 0.0)

    if strict and (count == 0).any():
        raise _no_root_error(E, F, G, count, gap)
    return HalfAngleSolution(theta=theta, count=count, gap=gap)


def _no_root_error(E, F, G, count, gap) -> AssemblyError:
    missing = count == 0
    where = np.unravel_index(int(np.argmax(np.where(missing, gap, -1.0))), gap.shape)
    at = f" at index {tuple(int(i) for i in where)}" if gap.ndim else ""
    e, f, g = float(E[where]), float(F[where]), float(G[where])
    if e == 0.0 and f == 0.0:
        why = (f"E = F = 0, so θ drops out of the equation (G = {g:.6g})"
               + ("; every θ satisfies it and none is singled out" if g == 0.0 else ""))
    else:
        why = (f"|G| - sqrt(E² + F²) = {abs(g):.6g} - {np.hypot(e, f):.6g} = "
               f"{float(gap[where]):.6g} > 0")
    return AssemblyError(
        f"E cos θ + F sin θ + G = 0 has no real root at {int(missing.sum())} of "
        f"{missing.size} entries; worst{at}: E = {e:.6g}, F = {f:.6g}, G = {g:.6g}, {why}; "
        f"the links cannot reach: change the input or the dimensions, or pass strict=False "
        f"to get count == 0 and the closest-approach angle there",
        loop="E cos θ + F sin θ + G = 0", gap=float(gap.max()))
