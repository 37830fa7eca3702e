"""The RUR (Cardan, Hooke) joint of *Mecanismos*, §7.4, single and double."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, check_choice
from kinelab.solvers._arguments import reals
from kinelab.spatial._common import ANGLE, as_angles, as_array, as_number, rate, together
from kinelab.spatial._transforms import rotation

__all__ = ["CardanMotion", "DoubleCardanMotion", "cardan_output", "cardan_velocity_ratio",
           "cardan_motion", "double_cardan"]

# Two joint angles whose cosines agree to this count as equal, and a yoke phase within
# this of a multiple of π as in phase (for the ``uniform`` flag only).
_SAME = 1e-12


def _follow(phi: np.ndarray, k: np.ndarray) -> np.ndarray:
    """The continuous solution of ``tan(out) = k tan(phi)``, k > 0, with out = phi at
    every multiple of π/2: ``out = phi + atan2((k - 1) sin phi cos phi,
    cos² phi + k sin² phi)``.  The denominator is positive for k > 0, so the correction
    stays inside (-π/2, π/2) and never jumps: the output tracks the input over any
    number of turns."""
    c, s = np.cos(phi), np.sin(phi)
    return phi + np.arctan2((k - 1.0) * s * c, c * c + k * s * s)


def _rate(phi: np.ndarray, k: np.ndarray) -> np.ndarray:
    """d out / d phi = k / (cos² phi + k² sin² phi)."""
    c, s = np.cos(phi), np.sin(phi)
    return k / (c * c + k * k * s * s)


def _rate_slope(phi: np.ndarray, k: np.ndarray) -> np.ndarray:
    """d² out / d phi² = k (1 - k²) sin 2phi / (cos² phi + k² sin² phi)²."""
    c, s = np.cos(phi), np.sin(phi)
    return k * (1.0 - k * k) * np.sin(2.0 * phi) / (c * c + k * k * s * s) ** 2


def _bend(name: str, beta: ArrayLike) -> np.ndarray:
    beta = reals(name, beta)
    bad = ~(np.abs(beta) < np.pi / 2)                   # also catches NaN
    if bad.any():
        raise ModelError(f"{name}: expected |β| < π/2 rad (the joint locks at 90°; practice "
                         f"keeps |β| <= 45°), got {beta[bad].flat[0]:.6g} rad")
    return beta


@dataclass(frozen=True)
class CardanMotion:
    """Output motion of a single Cardan joint.

    Attributes
    ----------
    phi1, phi1_dot, phi1_ddot : ndarray
        Input shaft angle (rad), speed (rad/s), acceleration (rad/s²).
    phi2, phi2_dot, phi2_ddot : ndarray
        Output shaft angle, speed and acceleration.
    ratio : ndarray
        ``φ̇2 / φ̇1 = cos β / (1 - sin² β sin² φ1)`` (*Mecanismos*, eq. 76).
    """

    phi1: np.ndarray
    phi1_dot: np.ndarray
    phi1_ddot: np.ndarray
    phi2: np.ndarray
    phi2_dot: np.ndarray
    phi2_ddot: np.ndarray
    ratio: np.ndarray


def cardan_output(phi1: ArrayLike, beta: ArrayLike) -> np.ndarray:
    """Output shaft angle of a Cardan joint: ``tan φ2 = tan φ1 cos β`` (*Mecanismos*, eq. 75).

    The geometry is the notes' (Fig. 59): the input shaft lies along x0, the output shaft
    along ``Rot(z0, β) x0``; the input yoke pin is ``Rot(x0, φ1) z0`` and the output's
    ``Rot(z0, β) Rot(x2, φ2) (0, -1, 0)``; the cross keeps them perpendicular.  Both angles
    are zero when the input pin is perpendicular to the plane of the shafts.

    The tangent relation alone leaves φ2 ambiguous by π and undefined at φ1 = ±90°; here
    φ2 is the continuous solution that equals φ1 at every multiple of 90°, over any
    number of turns (``φ2 = φ1 + atan2((cos β - 1) sin φ1 cos φ1, cos² φ1 + cos β
    sin² φ1)``), so it can be plotted or differentiated without unwrapping.

    Parameters
    ----------
    phi1 : float or array_like
        Input angle, rad.
    beta : float or array_like, broadcast with ``phi1``
        Angle between the shafts, rad, ``|β| < π/2``.

    Returns
    -------
    ndarray, the broadcast shape of ``phi1`` and ``beta``, rad

    Examples
    --------
    >>> beta = np.radians(30.0)
    >>> phi2 = kl.spatial.cardan_output(np.radians([0.0, 45.0, 90.0, 135.0, 720.0]), beta)
    >>> np.degrees(phi2).round(6)
    array([  0.      ,  40.893395,  90.      , 139.106605, 720.      ])
    """
    phi1, k = together(("phi1", as_angles("phi1", phi1, batch="any"), 0),
                       ("beta", np.cos(_bend("beta", beta)), 0))
    return _follow(phi1, k)


def cardan_velocity_ratio(phi1: ArrayLike, beta: ArrayLike) -> np.ndarray:
    """``φ̇2 / φ̇1 = cos β / (1 - sin² β sin² φ1)`` (*Mecanismos*, eq. 76).

    It swings between ``cos β`` (at φ1 = 0, π) and ``1 / cos β`` (at φ1 = ±π/2) twice a
    turn: the output speed fluctuates even at constant input speed.

    Examples
    --------
    >>> kl.spatial.cardan_velocity_ratio(np.radians([0.0, 90.0]), np.radians(60.0))
    array([0.5, 2. ])
    """
    phi1, k = together(("phi1", as_angles("phi1", phi1, batch="any"), 0),
                       ("beta", np.cos(_bend("beta", beta)), 0))
    return _rate(phi1, k)


def cardan_motion(phi1: ArrayLike, beta: ArrayLike, phi1_dot: ArrayLike = 0.0,
                  phi1_ddot: ArrayLike = 0.0) -> CardanMotion:
    """Output angle, speed and acceleration of a Cardan joint.

    ``φ̈2 = r φ̈1 + (dr/dφ1) φ̇1²`` with ``r`` the velocity ratio and
    ``dr/dφ1 = cos β sin² β sin 2φ1 / (1 - sin² β sin² φ1)²``.

    Parameters
    ----------
    phi1, beta, phi1_dot, phi1_ddot : float or array_like, broadcast together
        rad, rad, rad/s, rad/s².

    Examples
    --------
    >>> m = kl.spatial.cardan_motion(np.radians(45.0), np.radians(30.0), phi1_dot=10.0)
    >>> float(m.phi2_dot), float(m.phi2_ddot)
    (9.89743318610787, 28.278380531736758)
    """
    phi1 = as_angles("phi1", phi1, batch="any")
    k = np.cos(_bend("beta", beta))
    w = as_array("phi1_dot", phi1_dot, batch="any", limit=rate("rad/s"))
    a = as_array("phi1_ddot", phi1_ddot, batch="any", limit=rate("rad/s^2"))
    phi1, k, w, a = together(("phi1", phi1, 0), ("beta", k, 0), ("phi1_dot", w, 0),
                             ("phi1_ddot", a, 0))
    ratio = _rate(phi1, k)
    return CardanMotion(phi1=phi1, phi1_dot=w, phi1_ddot=a, phi2=_follow(phi1, k),
                        phi2_dot=ratio * w, phi2_ddot=ratio * a + _rate_slope(phi1, k) * w**2,
                        ratio=ratio)


@dataclass(frozen=True)
class DoubleCardanMotion:
    """Motion through two Cardan joints and an intermediate shaft.

    Attributes
    ----------
    phi1, phi2, phi3 : ndarray, shape of ``phi1``
        Input, intermediate and output shaft angles, rad.
    phi3_dot, phi3_ddot : ndarray
        Output speed (rad/s) and acceleration (rad/s²).
    ratio : ndarray
        ``φ̇3 / φ̇1``; identically 1 when the transmission is uniform.
    uniform : bool
        The conditions for uniform transmission hold: equal joint angles
        (``cos β1 = cos β2``) and the intermediate yokes phased to the planes of the
        shafts (``phase = plane_angle``, mod π).
    output_axis : ndarray, shape (3,)
        Direction of the output shaft (input along x0, first bend in the x0 y0 plane).
    """

    phi1: np.ndarray
    phi2: np.ndarray
    phi3: np.ndarray
    phi3_dot: np.ndarray
    phi3_ddot: np.ndarray
    ratio: np.ndarray
    uniform: bool
    output_axis: np.ndarray


def double_cardan(phi1: ArrayLike, beta1: float, beta2: float, *,
                  arrangement: Literal["Z", "W"] = "Z", phase: float = 0.0,
                  plane_angle: float = 0.0, phi1_dot: ArrayLike = 0.0,
                  phi1_ddot: ArrayLike = 0.0) -> DoubleCardanMotion:
    """Two Cardan joints in series (*Mecanismos*, §7.4, Fig. 60).

    Input shaft 1 along x0; joint A bends the drive by ``beta1`` in the x0 y0 plane onto
    the intermediate shaft 2; joint B bends it by ``beta2`` onto the output shaft 3, in a
    plane turned by ``plane_angle`` about shaft 2 from the plane of shafts 1 and 2.  In
    the **Z** arrangement the second bend undoes the first (with ``plane_angle = 0`` and
    ``beta2 = beta1`` the output is parallel to the input); in the **W** arrangement it
    continues it (the output meets the input at ``beta1 + beta2``).

    ``phase`` turns the yoke of shaft 2 at B about shaft 2, from the position in which
    both yokes of shaft 2 lie in one plane.  φ2 is measured as in :func:`cardan_output`
    for joint A; φ3 from the position in which the output yoke pin is perpendicular to
    the plane of shafts 2 and 3.  Joint B is driven by shaft 2 with its pin at 90° to the
    reference of joint A, which inverts the relation: ``tan(φ2 + phase - plane_angle) =
    cos β2 tan φ3``.  Hence

    - with ``cos β1 = cos β2`` and ``phase = plane_angle`` (yokes in one plane and all
      shafts coplanar, in either arrangement, or yokes turned to follow the planes)
      ``φ3 = φ1`` at every instant: **uniform** transmission;
    - otherwise the output speed fluctuates about the input's.

    Parameters
    ----------
    phi1 : float or array_like, shape () or (N,)
        Input angle, rad.
    beta1, beta2 : float
        Bend angles of joints A and B, rad, each ``|β| < π/2`` (their signs are set by
        ``arrangement``; only the magnitudes matter here).
    arrangement : {'Z', 'W'}
    phase, plane_angle : float
        rad.
    phi1_dot, phi1_ddot : float or array_like, broadcast to ``phi1``
        rad/s, rad/s².

    Returns
    -------
    DoubleCardanMotion

    Examples
    --------
    Equal bends of 30° in a Z: uniform.  With the second bend 20° instead, the output
    speed fluctuates:

    >>> phi1 = np.radians(np.arange(0, 360, 45))
    >>> kl.spatial.double_cardan(phi1, np.radians(30), np.radians(30)).ratio.round(12)
    array([1., 1., 1., 1., 1., 1., 1., 1.])
    >>> z = kl.spatial.double_cardan(phi1, np.radians(30), np.radians(20))
    >>> z.uniform, z.ratio.min().round(4), z.ratio.max().round(4)
    (False, np.float64(0.9216), np.float64(1.0851))
    """
    check_choice("arrangement", arrangement, ("Z", "W"))
    phi1 = as_angles("phi1", phi1)
    beta1, beta2 = as_number("beta1", beta1), as_number("beta2", beta2)
    k1, k2 = float(np.cos(_bend("beta1", beta1))), float(np.cos(_bend("beta2", beta2)))
    phase, plane = as_number("phase", phase, limit=ANGLE), as_number("plane_angle", plane_angle,
                                                                     limit=ANGLE)
    w = as_array("phi1_dot", phi1_dot, limit=rate("rad/s"))
    a = as_array("phi1_ddot", phi1_ddot, limit=rate("rad/s^2"))
    phi1, w, a = together(("phi1", phi1, 0), ("phi1_dot", w, 0), ("phi1_ddot", a, 0))
    phi2 = _follow(phi1, k1)
    at_b = phi2 + phase - plane                  # joint B's input angle
    phi3 = _follow(at_b, 1.0 / k2)
    r1, r2 = _rate(phi1, k1), _rate(at_b, 1.0 / k2)
    ratio = r2 * r1
    slope = _rate_slope(at_b, 1.0 / k2) * r1**2 + r2 * _rate_slope(phi1, k1)
    uniform = bool(abs(k1 - k2) <= _SAME and abs(np.sin(phase - plane)) <= _SAME)
    second = -1.0 if arrangement == "Z" else 1.0
    axis = (rotation("z", abs(beta1)) * rotation("x", plane)
            * rotation("z", second * abs(beta2))).apply([1.0, 0.0, 0.0])
    return DoubleCardanMotion(phi1=phi1, phi2=phi2, phi3=phi3, phi3_dot=ratio * w,
                              phi3_ddot=ratio * a + slope * w**2, ratio=ratio,
                              uniform=uniform, output_axis=axis)
