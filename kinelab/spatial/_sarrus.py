"""Sarrus's linkage: a plate lifted straight up by two hinged legs in crossed planes."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError
from kinelab.spatial._common import as_angles, as_length, indices

__all__ = ["SarrusPositions", "sarrus"]


@dataclass(frozen=True)
class SarrusPositions:
    """The plate's rise and the joint angles of Sarrus's linkage.

    Attributes
    ----------
    height : ndarray, shape () or (N,)
        Rise of the plate's hinges above the base's, m.
    angles : ndarray, shape (2, 3) or (N, 2, 3)
        For each leg (the driven one first), the angles of its three hinges, rad, each
        about the hinge axis ``n = out × up`` (so that a positive angle lifts the link
        from ``out`` towards ``up``): the lower link from the base, the upper link from
        the lower, the plate from the upper.  The three add up to zero: the plate stays
        parallel to the base.
    """

    height: np.ndarray
    angles: np.ndarray


def _leg(name: str, leg) -> tuple[float, float]:
    try:
        lower, upper = leg
    except (TypeError, ValueError):
        raise ModelError(f"{name}: expected (lower, upper), two lengths in m, got {leg!r}") \
            from None
    return (as_length(f"{name}[0]", lower, positive=True),
            as_length(f"{name}[1]", upper, positive=True))


def sarrus(theta: ArrayLike, driven: tuple[float, float],
           other: tuple[float, float] | None = None) -> SarrusPositions:
    """Sarrus's linkage over its input angle: how high the plate rides, and every hinge's
    angle, in closed form.

    Two legs join a base to a plate, each of a lower and an upper link on three parallel
    hinges; the two legs' hinges are horizontal and not parallel to each other (at right
    angles in Sarrus's drawing).  Each leg alone lets the plate move in the vertical
    plane of its leg; together they leave only the vertical translation common to both
    (Sarrus, 1853).  Here each leg's plate hinge is straight above its base hinge; in the
    leg's plane, with ``out`` the horizontal direction from the hinge line towards the
    elbow and ``up`` vertical, the driven leg's lower link rises at ``theta`` from ``out``,
    and

        h = l1 sin(theta) + sqrt(l2² − l1² cos²(theta))

    (``h = 2 l sin(theta)`` for equal links).  The other leg's lower link then rises at the
    angle ``phi`` whose elbow lies out at ``s = (l1² − l2² + h²) / (2h)`` above its base
    hinge: ``phi = atan2(s, sqrt(l1² − s²))``.

    Parameters
    ----------
    theta : float or array_like, shape () or (N,)
        Elevation of the driven leg's lower link above the base, rad, in (-π/2, π/2).
    driven : (float, float)
        Lengths of the driven leg's lower and upper links, m.
    other : (float, float), optional
        Those of the other leg, m; default: as the driven leg.

    Returns
    -------
    SarrusPositions
        ``height`` of the shape of ``theta``, ``angles`` with (2, 3) after it.

    Raises
    ------
    AssemblyError
        Where a leg cannot reach: the plate would sink to the base (h <= 0) or rise beyond
        the other leg's reach.

    Examples
    --------
    Links of 50 mm: at 30° the plate rides 2 · 50 · sin 30° = 50 mm up.

    >>> p = kl.spatial.sarrus(np.radians([30.0, 45.0]), (0.05, 0.05))
    >>> p.height.round(12)
    array([0.05      , 0.07071068])
    >>> np.degrees(p.angles[0]).round(9)
    array([[  30.,  120., -150.],
           [  30.,  120., -150.]])
    """
    theta = as_angles("theta", theta)
    l1, l2 = _leg("driven", driven)
    m1, m2 = (l1, l2) if other is None else _leg("other", other)
    reach = l2**2 - (l1 * np.cos(theta)) ** 2
    flat = ~(np.abs(theta) < np.pi / 2) | (reach < 0)
    height = l1 * np.sin(theta) + np.sqrt(np.where(flat, 0.0, reach))
    bad = flat | ~(height > 0) | (height < abs(m1 - m2)) | (height > m1 + m2)
    if bad.any():
        i = np.argmax(np.ravel(bad))
        raise AssemblyError(
            f"Sarrus linkage cannot close at theta = {np.ravel(theta)[i]:.6g} rad (sample(s) "
            f"{indices(np.ravel(bad))}): the plate's rise {np.ravel(height)[i]:.6g} m is not "
            f"within the reach of both legs, (0, {l1 + l2:.6g}] and [{abs(m1 - m2):.6g}, "
            f"{m1 + m2:.6g}] m; narrow theta", loop="driven leg, plate, other leg")
    s = (m1**2 - m2**2 + height**2) / (2.0 * height)
    phi = np.arctan2(s, np.sqrt(np.maximum(m1**2 - s**2, 0.0)))

    def hinges(lower, length, rise):
        upper = np.arctan2(height - rise, -length * np.cos(lower))   # direction of the upper link
        return np.stack([lower, upper - lower, -upper], axis=-1)
    angles = np.stack([hinges(theta, l1, l1 * np.sin(theta)),
                       hinges(phi, m1, m1 * np.sin(phi))], axis=-2)
    return SarrusPositions(height=height, angles=angles)
