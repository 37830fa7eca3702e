"""The 6-SPS (Stewart-Gough) platform of *Mecanismos*, Ex. 6.2: leg lengths, inverse Jacobian,
forward kinematics by Newton-Raphson."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial.transform import Rotation

from kinelab.errors import ConvergenceError, ModelError, SingularityError, describe
from kinelab.model import MAX_LENGTH, MIN_LENGTH, length_problem
from kinelab.solvers._arguments import whole
from kinelab.spatial._common import LENGTH, as_array, as_rotation, indices

__all__ = ["StewartPose", "stewart_leg_lengths", "stewart_inverse_jacobian", "stewart_forward"]

_NEWTON_TOL = 1e-12      # leg-length residual, relative to the size of the base
_SINGULAR = 1e-12        # smallest/largest singular value of the Jacobian
_MAX_ITER = 10_000       # Newton converges in a few steps or not at all
_FAR = 1e3 * MAX_LENGTH  # an iterate this far out has left every platform of the limits


@dataclass(frozen=True)
class StewartPose:
    """A platform pose found by :func:`stewart_forward`.

    Attributes
    ----------
    position : ndarray, shape (3,) or (N, 3)
        Origin of the platform frame in the base frame, m.
    rotation : scipy.spatial.transform.Rotation
        Orientation of the platform frame (one, or N).
    iterations : int
        Newton steps taken (the most over the batch).
    residual : ndarray, shape () or (N,)
        Largest leg-length error at the solution, m.
    """

    position: np.ndarray
    rotation: Rotation
    iterations: int
    residual: np.ndarray


def _geometry(base_points: ArrayLike, platform_points: ArrayLike):
    a = as_array("base_points", base_points, (None, 3), batch=False, limit=LENGTH)
    b = as_array("platform_points", platform_points, (a.shape[0], 3), batch=False,
                 limit=LENGTH)
    return a, b


def _pose(position: ArrayLike, rotation: Rotation) -> tuple[np.ndarray, np.ndarray, bool]:
    """Positions (N, 3) and rotation matrices (N, 3, 3), and whether one pose was given."""
    p = as_array("position", position, (3,), limit=LENGTH)
    R = as_rotation("rotation", rotation).as_matrix()
    single = p.ndim == 1 and R.ndim == 2
    p, R = np.atleast_2d(p), R.reshape(-1, 3, 3)
    if len(p) != len(R) and 1 not in (len(p), len(R)):
        raise ModelError(f"position and rotation: {len(p)} positions and {len(R)} rotations; "
                         f"give one of each, N of each, or one of either")
    N = max(len(p), len(R))
    return np.broadcast_to(p, (N, 3)), np.broadcast_to(R, (N, 3, 3)), single


def _legs(a: np.ndarray, b: np.ndarray, p: np.ndarray, R: np.ndarray):
    """Leg vectors (N, m, 3) from base to platform joint, and platform arms R b (N, m, 3)."""
    arms = np.einsum("nij,kj->nki", R, b, optimize=True)   # one BLAS product for all
    return arms + (p[:, None, :] - a), arms


def _lengths(legs: np.ndarray) -> np.ndarray:
    return np.sqrt(np.einsum("nki,nki->nk", legs, legs))


def stewart_leg_lengths(base_points: ArrayLike, platform_points: ArrayLike,
                        position: ArrayLike, rotation: Rotation) -> np.ndarray:
    """Leg lengths of a 6-SPS platform at a pose: the inverse kinematics.

    Leg ``k`` joins base joint ``a_k`` (fixed, base frame) to platform joint ``b_k``
    (platform frame): ``d_k = |p + R b_k - a_k|``.

    Parameters
    ----------
    base_points : array_like, shape (m, 3)
        Base joint centres in the base frame, m (m = 6 for the 6-SPS).
    platform_points : array_like, shape (m, 3)
        Platform joint centres in the platform frame, m, in the order of the legs.
    position : array_like, shape (3,) or (N, 3)
        Platform frame origin in the base frame, m.
    rotation : scipy.spatial.transform.Rotation
        Platform frame orientation: one rotation, or N.

    Returns
    -------
    ndarray, shape (m,) for one pose or (N, m), m

    Examples
    --------
    A platform that is the base lifted by 1 m: every leg is 1 m long.

    >>> from scipy.spatial.transform import Rotation
    >>> hexagon = np.c_[np.cos(np.arange(6)), np.sin(np.arange(6)), np.zeros(6)]
    >>> kl.spatial.stewart_leg_lengths(hexagon, hexagon, [0, 0, 1.0], Rotation.identity())
    array([1., 1., 1., 1., 1., 1.])
    """
    a, b = _geometry(base_points, platform_points)
    p, R, single = _pose(position, rotation)
    lengths = _lengths(_legs(a, b, p, R)[0])
    return lengths[0] if single else lengths


def _jacobian(legs: np.ndarray, arms: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Inverse Jacobian (N, m, 6) and leg lengths (N, m)."""
    lengths = _lengths(legs)
    if (lengths == 0.0).any():
        raise SingularityError(f"a leg has zero length at sample(s) "
                               f"{indices((lengths == 0.0).any(axis=1))}: its direction is "
                               f"undefined; move the platform off the base joint")
    unit = legs / lengths[..., None]
    return np.concatenate([unit, np.cross(arms, unit)], axis=-1), lengths


def stewart_inverse_jacobian(base_points: ArrayLike, platform_points: ArrayLike,
                             position: ArrayLike, rotation: Rotation) -> np.ndarray:
    """The inverse Jacobian: leg rates from the platform's twist, ``ḋ = J [v; ω]``.

    Row k is ``[n_kᵀ, (R b_k × n_k)ᵀ]`` with ``n_k`` the unit vector along leg k, since
    ``ḋ_k = n_k · (v + ω × R b_k)``; ``v`` is the velocity of the platform origin and ``ω``
    the platform's angular velocity, both in the base frame.

    Returns
    -------
    ndarray, shape (m, 6) or (N, m, 6)
        Columns: ``v`` (m/s per m/s) then ``ω`` (m/s per rad/s).

    Raises
    ------
    SingularityError
        If a leg has zero length.
    """
    a, b = _geometry(base_points, platform_points)
    p, R, single = _pose(position, rotation)
    J = _jacobian(*_legs(a, b, p, R))[0]
    return J[0] if single else J


def stewart_forward(base_points: ArrayLike, platform_points: ArrayLike,
                    leg_lengths: ArrayLike, position: ArrayLike, rotation: Rotation, *,
                    max_iter: int = 50) -> StewartPose:
    """The platform pose with given leg lengths, by Newton-Raphson from a guess.

    The forward problem has many solutions (up to 40 for a general 6-6 platform); Newton
    finds the one the guess leads to.  Each step solves ``J [δp; δθ] = d - d(pose)`` with
    the inverse Jacobian and moves the platform by ``δp`` and the small rotation ``δθ``
    (about its origin, in the base frame).

    Parameters
    ----------
    base_points, platform_points : array_like, shape (6, 3)
    leg_lengths : array_like, shape (6,) or (N, 6)
        m, each from 1e-9 m to 1e9 m.
    position, rotation
        The guess: shape (3,) or (N, 3), and one Rotation or N.
    max_iter : int
        From 1 to 10,000 Newton steps.

    Returns
    -------
    StewartPose
        Converged to a leg-length residual below 1e-12 times the size of the base.

    Raises
    ------
    SingularityError
        The Jacobian is singular at an iterate (the platform gains a freedom there).
    ConvergenceError
        No convergence in ``max_iter`` steps; the guess is too far.

    Examples
    --------
    A 6-6 platform: base joints in pairs at ±15° about 0°, 120°, 240° (radius 1 m),
    platform joints at ±45° about the same directions (radius 0.5 m).  Set every leg to
    1.2 m and start from the platform level, 1 m up:

    >>> from scipy.spatial.transform import Rotation
    >>> def ring(radius, degrees):
    ...     t = np.radians(degrees)
    ...     return radius * np.c_[np.cos(t), np.sin(t), np.zeros(6)]
    >>> base = ring(1.0, [-15, 15, 105, 135, 225, 255])
    >>> top = ring(0.5, [-45, 45, 75, 165, 195, 285])
    >>> pose = kl.spatial.stewart_forward(base, top, np.full(6, 1.2), [0, 0, 1.0],
    ...                                   Rotation.identity())
    >>> kl.spatial.stewart_leg_lengths(base, top, pose.position, pose.rotation).round(12)
    array([1.2, 1.2, 1.2, 1.2, 1.2, 1.2])

    By symmetry the platform rises straight up, level, to the height where each leg's
    horizontal run (0.61966 m, from -15° on the base to -45° on the platform) and the
    1.2 m leg make ``z = sqrt(1.2² - 0.383975) = 1.02763 m``:

    >>> pose.position.round(8) + 0.0, round(float(pose.rotation.magnitude()), 9)
    (array([0.        , 0.        , 1.02763097]), 0.0)
    """
    a, b = _geometry(base_points, platform_points)
    if a.shape[0] != 6:
        raise ModelError(f"base_points: forward kinematics needs 6 legs, got {a.shape[0]}")
    target = as_array("leg_lengths", leg_lengths, (6,))
    bad = ~((target >= MIN_LENGTH) & (target <= MAX_LENGTH))
    if bad.any():
        where = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ModelError(f"leg_lengths: {length_problem(float(target[where]))}, got "
                         f"{describe(target[where])} at index {where}; a leg's length is "
                         f"the distance between its joints")
    max_iter = whole("max_iter", max_iter, 1, _MAX_ITER)
    p, R, single = _pose(position, rotation)
    single = single and target.ndim == 1
    target = np.atleast_2d(target)
    if len(p) != len(target) and 1 not in (len(p), len(target)):
        raise ModelError(f"leg_lengths and position: {len(target)} sets of leg lengths and "
                         f"{len(p)} poses; give one of each, N of each, or one of either")
    N = len(p) if len(target) == 1 else len(target)
    p, R = np.array(np.broadcast_to(p, (N, 3))), np.array(np.broadcast_to(R, (N, 3, 3)))
    target = np.broadcast_to(target, (N, 6))
    tol = _NEWTON_TOL * max(1.0, float(np.ptp(a, axis=0).max()))
    for iteration in range(max_iter + 1):
        J, lengths = _jacobian(*_legs(a, b, p, R))
        residual = np.abs(lengths - target).max(axis=-1)
        active = residual > tol
        if not active.any() or iteration == max_iter:
            break
        Ja = J[active]
        sv = np.linalg.svd(Ja, compute_uv=False)
        bad = np.zeros(N, dtype=bool)
        bad[active] = sv[:, -1] <= _SINGULAR * sv[:, 0]
        if bad.any():
            raise SingularityError(
                f"stewart_forward: the Jacobian is singular at sample(s) {indices(bad)} (an "
                f"iterate reached a singular pose, where the legs do not hold the platform, "
                f"or the geometry is singular everywhere); start from another guess")
        step = np.linalg.solve(Ja, (target - lengths)[active][..., None])[..., 0]
        p[active] += step[:, :3]
        R[active] = Rotation.from_rotvec(step[:, 3:]).as_matrix() @ R[active]
        if not np.abs(p).max(initial=0.0) <= _FAR:
            far = ~(np.abs(p).max(axis=-1) <= _FAR)
            raise ConvergenceError(
                f"stewart_forward: Newton diverged at sample(s) {indices(far)} (the platform "
                f"went beyond {_FAR:g} m); start nearer the pose")
    if active.any():
        raise ConvergenceError(
            f"stewart_forward: no convergence in {max_iter} steps at sample(s) "
            f"{indices(active)} (leg error {residual.max():.3g} m); start nearer the pose")
    rotation = Rotation.from_matrix(R[0] if single else R)
    return StewartPose(position=p[0] if single else p, rotation=rotation,
                       iterations=iteration, residual=residual[0] if single else residual)
