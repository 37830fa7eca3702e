"""Homogeneous transforms in 2-D and 3-D, rotations, and the motion of a point in a moving frame.

*Mecanismos*, §4.2 (2-D) and §7.2 (3-D) write the location of a point P of frame B in frame A
as ``[A_r_P; 1] = [A_T_B] [B_r_P; 1]`` with ``A_T_B = [[A_R_B, A_r_OB], [0, 1]]``.  Rotations
are :class:`scipy.spatial.transform.Rotation` objects (no quaternion code is written
here); transforms are plain arrays of shape ``(..., 3, 3)`` (2-D) or ``(..., 4, 4)`` (3-D),
so a batch of N frames is one array and composing them is one ``matmul``.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial.transform import Rotation

from kinelab.errors import ModelError, check_choice, describe
from kinelab.solvers._arguments import flag, reals
from kinelab.spatial._common import (LENGTH, as_angles, as_array, as_directions, as_rotation,
                                     as_rotation_matrix, as_transform, as_transform_rate,
                                     as_vectors, rate, together)

__all__ = [
    "AxisAngle", "TransformRates", "PointMotion", "AngularMotion",
    "rotation", "axis_angle", "euler_rotation", "euler_angles", "euler_parameters",
    "rotation_from_euler_parameters", "homogeneous", "planar_transform", "translation",
    "compose", "invert", "transform_points", "skew", "transform_rates", "point_motion",
    "euler_rates",
]

_AXES = ("fixed", "moving")


# -- rotations ------------------------------------------------------------------------------

@dataclass(frozen=True)
class AxisAngle:
    """A rotation as a unit axis and an angle about it (right-hand rule).

    Attributes
    ----------
    axis : ndarray, shape (3,) or (N, 3)
        Unit vector.  For a zero rotation, where any axis will do, it is ``(0, 0, 1)``.
    angle : ndarray, shape () or (N,), rad in [0, π]
    """

    axis: np.ndarray
    angle: np.ndarray


def rotation(axis: str | ArrayLike, angle: ArrayLike, *, degrees: bool = False) -> Rotation:
    """The rotation by ``angle`` about ``axis``: ``Rot(x, α)``, ``Rot(y, β)``, ``Rot(z, γ)``
    or ``Rot(u, θ)`` of *Mecanismos*, §7.2.

    Parameters
    ----------
    axis : {'x', 'y', 'z'} or array_like, shape (3,) or (N, 3)
        A coordinate axis, or a direction (normalised here; need not be unit).
    angle : float or array_like, shape () or (N,)
        rad (degrees with ``degrees=True``), positive by the right-hand rule about
        ``axis``.

    Returns
    -------
    scipy.spatial.transform.Rotation
        One rotation, or N of them when ``axis`` or ``angle`` has a leading N.

    Raises
    ------
    ModelError
        For an unknown axis name, a zero direction, shapes that do not agree, or an angle
        beyond 1000 turns.

    Examples
    --------
    ``Rot(z, 90°)`` turns x into y:

    >>> R = kl.spatial.rotation("z", 90, degrees=True)
    >>> R.apply([1.0, 0.0, 0.0]).round(12)
    array([0., 1., 0.])

    About the diagonal of the cube, 120° permutes the axes:

    >>> kl.spatial.rotation([1, 1, 1], 2 * np.pi / 3).as_matrix().round(12) + 0.0
    array([[0., 0., 1.],
           [1., 0., 0.],
           [0., 1., 0.]])
    """
    angle = as_angles("angle", angle, degrees=flag("degrees", degrees))
    if isinstance(axis, str):
        check_choice("axis", axis, ("x", "y", "z"))
        return Rotation.from_euler(axis, angle[..., None])   # one angle per rotation
    direction, angle = together(("axis", as_directions("axis", axis), 1),
                                ("angle", angle, 0))
    return Rotation.from_rotvec(direction * angle[..., None])


def axis_angle(rotation: Rotation) -> AxisAngle:
    """The axis and angle of ``rotation``: the inverse of :func:`rotation`.

    Examples
    --------
    >>> aa = kl.spatial.axis_angle(kl.spatial.rotation([0, 0, 2], -0.5))
    >>> aa.axis.round(12) + 0.0, float(aa.angle)
    (array([ 0.,  0., -1.]), 0.5)
    """
    rotvec = as_rotation("rotation", rotation).as_rotvec()
    angle = np.linalg.norm(rotvec, axis=-1)
    safe = np.where(angle > 0.0, angle, 1.0)[..., None]
    axis = np.where(angle[..., None] > 0.0, rotvec / safe, np.array([0.0, 0.0, 1.0]))
    return AxisAngle(axis=axis, angle=angle)


def _scipy_sequence(sequence: str, axes: str) -> str:
    check_choice("axes", axes, _AXES)
    if not (isinstance(sequence, str) and 1 <= len(sequence) <= 3
            and set(sequence.lower()) <= set("xyz")):
        raise ModelError(f"sequence: expected 1 to 3 of the letters x, y, z such as 'zyx' or "
                         f"'zxz', got {describe(sequence)}")
    if any(a == b for a, b in zip(sequence.lower(), sequence.lower()[1:])):
        raise ModelError(f"sequence: expected consecutive axes to differ, such as 'zyx' or "
                         f"'zxz', got {describe(sequence)}; two turns in a row about one axis "
                         f"are one turn by their sum")
    # scipy: lower case = extrinsic (fixed axes), upper case = intrinsic (moving axes).
    return sequence.lower() if axes == "fixed" else sequence.upper()


def euler_rotation(sequence: str, angles: ArrayLike, *,
                   axes: Literal["fixed", "moving"] = "fixed",
                   degrees: bool = False) -> Rotation:
    """A composition of rotations about coordinate axes (Euler / Cardan angles).

    *Mecanismos*, §7.2 gives the two readings of a product of elementary rotations:

    - ``axes="fixed"``: the k-th rotation turns about the k-th axis of the **fixed**
      frame A; each new rotation multiplies on the left, so ``sequence="zyx"`` with
      ``angles=(γ, β, α)`` is ``Rot(x, α) Rot(y, β) Rot(z, γ)`` (§7.2 (a));
    - ``axes="moving"``: the k-th rotation turns about the k-th axis of the frame as
      already rotated (z, then x', then z''); each new rotation multiplies on the right,
      so ``sequence="zxz"`` with ``angles=(γ, α, β)`` is ``Rot(z, γ) Rot(x', α) Rot(z'', β)``
      (§7.2 (b)).

    The same matrix product therefore reads both ways: fixed axes in one order are
    moving axes in the reverse order.  (The expanded product printed under §7.2 (a) is in
    the reverse order of its own formula; the formula is the one used here.)

    Parameters
    ----------
    sequence : str
        1 to 3 letters from ``x, y, z``, in the order the rotations are made.
    angles : array_like, shape (k,) or (N, k), k = len(sequence)
        rad (degrees with ``degrees=True``), in the order of ``sequence``.
    axes : {'fixed', 'moving'}

    Returns
    -------
    scipy.spatial.transform.Rotation

    Examples
    --------
    Fixed z, y, x is moving x, y', z'' with the angles reversed:

    >>> a = kl.spatial.euler_rotation("zyx", [0.1, 0.2, 0.3], axes="fixed")
    >>> b = kl.spatial.euler_rotation("xyz", [0.3, 0.2, 0.1], axes="moving")
    >>> bool(np.allclose(a.as_matrix(), b.as_matrix(), rtol=0, atol=1e-15))
    True
    """
    seq = _scipy_sequence(sequence, axes)
    angles = as_angles("angles", angles, (len(seq),), degrees=flag("degrees", degrees))
    return Rotation.from_euler(seq, angles)


def euler_angles(rotation: Rotation, sequence: str, *,
                 axes: Literal["fixed", "moving"] = "fixed",
                 degrees: bool = False) -> np.ndarray:
    """The angles that :func:`euler_rotation` turns into ``rotation``.

    Parameters
    ----------
    rotation : scipy.spatial.transform.Rotation
    sequence : str
        Exactly 3 letters; the middle one differs from its neighbours.
    axes : {'fixed', 'moving'}

    Returns
    -------
    ndarray, shape (3,) or (N, 3)
        rad (degrees with ``degrees=True``).  The first and last are in (-π, π]; the
        middle one in [-π/2, π/2] (``'zyx'``-like sequences) or [0, π] (``'zxz'``-like).
        At gimbal lock scipy warns and sets the last angle to zero.

    Examples
    --------
    >>> R = kl.spatial.euler_rotation("zxz", [30, 40, 50], axes="moving", degrees=True)
    >>> kl.spatial.euler_angles(R, "zxz", axes="moving", degrees=True).round(9)
    array([30., 40., 50.])
    """
    rotation = as_rotation("rotation", rotation)
    seq = _scipy_sequence(sequence, axes)
    if len(seq) != 3:
        raise ModelError(f"sequence: expected 3 letters to recover angles from a rotation, "
                         f"got {describe(sequence)}")
    return rotation.as_euler(seq, degrees=flag("degrees", degrees))


def euler_parameters(rotation: Rotation) -> np.ndarray:
    """The Euler parameters ``(q0, q1, q2, q3)`` of ``rotation`` (*Mecanismos*, §7.2).

    ``q0 = cos(θ/2)``, ``(q1, q2, q3) = sin(θ/2) u`` for a rotation θ about the unit
    axis u; scalar first, as in the notes.  Of the two sets ``±q`` that give the same
    rotation, the one with ``q0 >= 0`` is returned.

    Returns
    -------
    ndarray, shape (4,) or (N, 4)

    Examples
    --------
    >>> q = kl.spatial.euler_parameters(kl.spatial.rotation("y", np.pi / 2))
    >>> q.round(12) + 0.0
    array([0.70710678, 0.        , 0.70710678, 0.        ])
    """
    return as_rotation("rotation", rotation).as_quat(canonical=True, scalar_first=True)


def rotation_from_euler_parameters(q: ArrayLike) -> Rotation:
    """The rotation with Euler parameters ``q = (q0, q1, q2, q3)``, the inverse of
    :func:`euler_parameters`.

    ``q`` need not be of unit length: as in the notes' matrix, whose entries are divided
    by ``Δ = q0² + q1² + q2² + q3²``, it is normalised (after dividing it by its largest
    entry, so that neither a huge nor a tiny ``q`` overflows or vanishes on the way).

    Parameters
    ----------
    q : array_like, shape (4,) or (N, 4)

    Examples
    --------
    >>> R = kl.spatial.rotation_from_euler_parameters([1.0, 0.0, 0.0, 1.0])   # 90° about z
    >>> R.apply([1.0, 0.0, 0.0]).round(12)
    array([0., 1., 0.])
    """
    q = as_array("q", q, (4,))
    biggest = np.abs(q).max(axis=-1, keepdims=True)
    if (biggest == 0.0).any():
        raise ModelError("q: expected Euler parameters not all zero, got (0, 0, 0, 0); "
                         "(1, 0, 0, 0) is no rotation")
    return Rotation.from_quat(q / biggest, scalar_first=True)


# -- homogeneous transforms -----------------------------------------------------------------

def _matrix(rotation: Rotation | ArrayLike) -> np.ndarray:
    if isinstance(rotation, Rotation):
        return rotation.as_matrix()
    return as_rotation_matrix("rotation", rotation)


def homogeneous(rotation: Rotation | ArrayLike, translation: ArrayLike) -> np.ndarray:
    """The homogeneous transform ``[[R, p], [0, 1]]`` (*Mecanismos*, eqs. 13 and 72).

    Parameters
    ----------
    rotation : scipy Rotation, or array_like of shape (..., 2, 2) or (..., 3, 3)
        ``A_R_B``, whose columns are B's unit vectors written in A: orthonormal (to 1e-9),
        with determinant +1.
    translation : array_like, shape (..., d)
        ``A_r_OB``, the origin of B in A, in m (at most 1e9 m in size); d = 2 or 3 as the
        rotation.

    Returns
    -------
    ndarray, shape (..., d + 1, d + 1)
        Broadcast over the leading dimensions of both arguments.

    Examples
    --------
    >>> kl.spatial.homogeneous(kl.spatial.rotation("z", np.pi / 2), [1.0, 2.0, 3.0]).round(12)
    array([[ 0., -1.,  0.,  1.],
           [ 1.,  0.,  0.,  2.],
           [ 0.,  0.,  1.,  3.],
           [ 0.,  0.,  0.,  1.]])
    """
    R = _matrix(rotation)
    d = R.shape[-1]
    p = as_array("translation", translation, (d,), batch="any", limit=LENGTH)
    return _block(*together(("rotation", R, 2), ("translation", p, 1)), 1.0)


def _block(R: np.ndarray, p: np.ndarray, corner: float) -> np.ndarray:
    """``[[R, p], [0, corner]]``: a transform (corner 1) or its time derivative (0)."""
    d = R.shape[-1]
    T = np.zeros(np.broadcast_shapes(R.shape[:-2], p.shape[:-1]) + (d + 1, d + 1))
    T[..., :d, :d] = R
    T[..., :d, d] = p
    T[..., d, d] = corner
    return T


def planar_transform(angle: ArrayLike, translation: ArrayLike = (0.0, 0.0)) -> np.ndarray:
    """The 2-D homogeneous transform of *Mecanismos*, eq. 13: frame B turned by ``angle``
    about A's origin and moved to ``translation``.

    Parameters
    ----------
    angle : float or array_like, shape () or (N,)
        θ, rad, CCW from A's x axis to B's.
    translation : array_like, shape (2,) or (N, 2)
        Origin of B in A, m.

    Returns
    -------
    ndarray, shape (3, 3) or (N, 3, 3)

    Examples
    --------
    The RR robot of *Mecanismos*, Ex. 4.1 (l1 = l2 = 1, θ1 = 30°, θ2 = 60°):
    ``0_r_P = 0_T_1 1_T_2 2_r_P``.

    >>> T01 = kl.spatial.planar_transform(np.radians(30))
    >>> T12 = kl.spatial.planar_transform(np.radians(60), [1.0, 0.0])
    >>> kl.spatial.transform_points(kl.spatial.compose(T01, T12), [1.0, 0.0])
    array([0.8660254, 1.5      ])
    """
    angle = as_angles("angle", angle, batch="any")
    c, s = np.cos(angle), np.sin(angle)
    R = np.stack([np.stack([c, -s], axis=-1), np.stack([s, c], axis=-1)], axis=-2)
    return homogeneous(R, translation)


def translation(vector: ArrayLike) -> np.ndarray:
    """The pure translation ``Trans(d)``: shape (..., d + 1, d + 1) for ``vector`` (..., d).

    Examples
    --------
    >>> kl.spatial.translation([0.2, 0.0, 0.866])[:3, 3]
    array([0.2  , 0.   , 0.866])
    """
    p = reals("vector", vector)
    d = p.shape[-1] if p.ndim else 0
    if d not in (2, 3):
        raise ModelError(f"vector: expected shape (..., 2) or (..., 3), got {p.shape}")
    p = as_array("vector", p, (d,), batch="any", limit=LENGTH)
    return _block(np.eye(d), p, 1.0)


def compose(*transforms: ArrayLike) -> np.ndarray:
    """``T1 T2 ... Tk``: the frame chain ``0_T_k = 0_T_1 1_T_2 ... (k-1)_T_k``.

    Each argument is a rigid transform of shape (..., d + 1, d + 1), all of one d;
    leading dimensions broadcast.

    Examples
    --------
    >>> T = kl.spatial.compose(kl.spatial.translation([1.0, 0.0]),
    ...                        kl.spatial.planar_transform(np.pi / 2))
    >>> kl.spatial.transform_points(T, [1.0, 0.0]).round(12)
    array([1., 1.])
    """
    if not transforms:
        raise ModelError("compose: expected at least one transform, got none")
    first = as_transform("transforms[0]", transforms[0])
    d = first.shape[-1] - 1
    checked = [("transforms[0]", first, 2)] + [
        (f"transforms[{i}]", as_transform(f"transforms[{i}]", T, d), 2)
        for i, T in enumerate(transforms[1:], start=1)]
    result, *rest = together(*checked)
    for T in rest:
        result = result @ T
    return np.array(result)


def invert(transform: ArrayLike) -> np.ndarray:
    """``B_T_A = (A_T_B)⁻¹`` by the transpose form of *Mecanismos*, eq. 20.

    ``[[R, p], [0, 1]]⁻¹ = [[Rᵀ, -Rᵀ p], [0, 1]]``: no matrix inversion, exact for a
    rigid transform (R orthonormal), which every transform built here is; any other
    matrix is refused.

    Examples
    --------
    >>> T = kl.spatial.homogeneous(kl.spatial.rotation("x", 0.3), [1.0, 2.0, 3.0])
    >>> bool(np.allclose(kl.spatial.invert(T) @ T, np.eye(4), rtol=0, atol=1e-15))
    True
    """
    T = as_transform("transform", transform)
    d = T.shape[-1] - 1
    Rt = np.swapaxes(T[..., :d, :d], -1, -2)
    return _block(Rt, -np.einsum("...ij,...j->...i", Rt, T[..., :d, d]), 1.0)


def transform_points(transform: ArrayLike, points: ArrayLike) -> np.ndarray:
    """``R r + p`` for each point: ``A_r_P`` from ``B_r_P`` (*Mecanismos*, eq. 17).

    Parameters
    ----------
    transform : array_like, shape (..., d + 1, d + 1)
    points : array_like, shape (..., d)
        m; leading dimensions broadcast with the transform's.

    Returns
    -------
    ndarray, shape (..., d)

    Examples
    --------
    >>> T = kl.spatial.homogeneous(kl.spatial.rotation("z", np.pi / 2), [1.0, 0.0, 0.0])
    >>> kl.spatial.transform_points(T, [[1.0, 0.0, 0.0], [0.0, 0.0, 2.0]]).round(12) + 0.0
    array([[1., 1., 0.],
           [1., 0., 2.]])
    """
    T = as_transform("transform", transform)
    d = T.shape[-1] - 1
    r = as_array("points", points, (d,), batch="any", limit=LENGTH)
    T, r = together(("transform", T, 2), ("points", r, 1))
    return np.einsum("...ij,...j->...i", T[..., :d, :d], r) + T[..., :d, d]


# -- time derivatives -----------------------------------------------------------------------

def skew(vector: ArrayLike) -> np.ndarray:
    """The cross-product matrix ``[w]×`` with ``[w]× r = w × r``.

    Parameters
    ----------
    vector : array_like, shape (..., 3)

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> kl.spatial.skew([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0]
    array([-3.,  6., -3.])
    """
    w = as_array("vector", vector, (3,), batch="any")
    x, y, z = np.moveaxis(w, -1, 0)
    zero = np.zeros_like(x)
    return np.stack([np.stack([zero, -z, y], -1), np.stack([z, zero, -x], -1),
                     np.stack([-y, x, zero], -1)], -2)


def _spin(name: str, omega: ArrayLike, d: int, unit: str) -> np.ndarray:
    """``[ω]×`` in 3-D (ω of shape (..., 3)), or ``ω [[0, -1], [1, 0]]`` in 2-D (ω (...))."""
    if d == 3:
        return skew(as_vectors(name, omega, 3, limit=rate(unit)))
    w = as_array(name, omega, (), batch="any", limit=rate(unit))
    return w[..., None, None] * np.array([[0.0, -1.0], [1.0, 0.0]])


@dataclass(frozen=True)
class TransformRates:
    """First and second time derivatives of a homogeneous transform.

    Attributes
    ----------
    Td : ndarray, shape (..., d + 1, d + 1)
        ``dT/dt = [[[ω]× R, v], [0, 0]]``.
    Tdd : ndarray, shape (..., d + 1, d + 1)
        ``d²T/dt² = [[([α]× + [ω]×²) R, a], [0, 0]]``.
    """

    Td: np.ndarray
    Tdd: np.ndarray


def transform_rates(transform: ArrayLike, omega: ArrayLike, velocity: ArrayLike,
                    alpha: ArrayLike = 0.0, acceleration: ArrayLike = 0.0) -> TransformRates:
    """``Ṫ`` and ``T̈`` of a moving frame from its angular and linear motion.

    Differentiating ``R`` with ``Ṙ = [ω]× R`` gives ``R̈ = ([α]× + [ω]×[ω]×) R``.

    Parameters
    ----------
    transform : array_like, shape (..., d + 1, d + 1)
        ``A_T_B``.
    omega, alpha : array_like, shape (..., 3) in 3-D, (...) in 2-D
        Angular velocity (rad/s) and acceleration (rad/s²) of B, in A's components.
    velocity, acceleration : array_like, shape (..., d)
        Of B's origin, in A's components, m/s and m/s².

    Returns
    -------
    TransformRates

    Examples
    --------
    A frame turning at 2 rad/s about z, its origin fixed at (1, 0, 0):

    >>> T = kl.spatial.homogeneous(kl.spatial.rotation("z", 0.0), [1.0, 0.0, 0.0])
    >>> rates = kl.spatial.transform_rates(T, [0.0, 0.0, 2.0], [0.0, 0.0, 0.0])
    >>> rates.Td[:3, :3]
    array([[ 0., -2.,  0.],
           [ 2.,  0.,  0.],
           [ 0.,  0.,  0.]])
    >>> rates.Tdd[:3, :3]
    array([[-4.,  0.,  0.],
           [ 0., -4.,  0.],
           [ 0.,  0.,  0.]])
    """
    T = as_transform("transform", transform)
    d = T.shape[-1] - 1
    W, A = _spin("omega", omega, d, "rad/s"), _spin("alpha", alpha, d, "rad/s^2")
    v = as_vectors("velocity", velocity, d, limit=rate("m/s"))
    a = as_vectors("acceleration", acceleration, d, limit=rate("m/s^2"))
    T, W, A, v, a = together(("transform", T, 2), ("omega", W, 2), ("alpha", A, 2),
                             ("velocity", v, 1), ("acceleration", a, 1))
    R = T[..., :d, :d]
    return TransformRates(Td=_block(W @ R, v, 0.0), Tdd=_block((A + W @ W) @ R, a, 0.0))


@dataclass(frozen=True)
class PointMotion:
    """Position, velocity and acceleration of a point given in a moving frame B, in A.

    From *Mecanismos*, eqs. 47-48 (differentiating ``[r; 1] = T [B_r; 1]``):
    ``v = Ṫ [B_r; 1] + T [B_ṙ; 0]`` (drag + relative) and
    ``a = T̈ [B_r; 1] + 2 Ṫ [B_ṙ; 0] + T [B_r̈; 0]`` (drag + Coriolis + relative).

    Attributes
    ----------
    position, velocity, acceleration : ndarray, shape (..., d)
        m, m/s, m/s², in A's components.
    drag_velocity, relative_velocity : ndarray, shape (..., d)
        The two terms of ``velocity``: the velocity of the point of B where P is now, and
        P's velocity relative to B (turned into A's components).
    drag_acceleration, coriolis_acceleration, relative_acceleration : ndarray, shape (..., d)
        The three terms of ``acceleration``; Coriolis is ``2 ω × v_rel``.
    """

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray
    drag_velocity: np.ndarray
    relative_velocity: np.ndarray
    drag_acceleration: np.ndarray
    coriolis_acceleration: np.ndarray
    relative_acceleration: np.ndarray


def point_motion(transform: ArrayLike, Td: ArrayLike, Tdd: ArrayLike, point: ArrayLike,
                 point_velocity: ArrayLike = 0.0,
                 point_acceleration: ArrayLike = 0.0) -> PointMotion:
    """Motion in frame A of a point P that moves in a moving frame B (*Mecanismos*, eqs. 47-48).

    Parameters
    ----------
    transform, Td, Tdd : array_like, shape (..., d + 1, d + 1)
        ``A_T_B`` and its first and second time derivatives (from :func:`transform_rates`
        or by differentiating a chain of transforms, as the notes do).
    point, point_velocity, point_acceleration : array_like, shape (..., d)
        ``B_r_P`` and its time derivatives in B: m, m/s, m/s².

    Returns
    -------
    PointMotion

    Examples
    --------
    A bead sliding out at 1 m/s along a rod that turns at 2 rad/s about z, when it is 0.5 m
    out along x: drag velocity ω × r = (0, 1, 0), relative (1, 0, 0); drag acceleration
    -ω² r = (-2, 0, 0) and Coriolis 2 ω × v_rel = (0, 4, 0).

    >>> T = np.eye(4)
    >>> rates = kl.spatial.transform_rates(T, [0.0, 0.0, 2.0], [0.0, 0.0, 0.0])
    >>> m = kl.spatial.point_motion(T, rates.Td, rates.Tdd, [0.5, 0.0, 0.0], [1.0, 0.0, 0.0])
    >>> m.velocity, m.acceleration
    (array([1., 1., 0.]), array([-2.,  4.,  0.]))
    >>> m.coriolis_acceleration
    array([0., 4., 0.])
    """
    T = as_transform("transform", transform)
    d = T.shape[-1] - 1
    Td, Tdd = as_transform_rate("Td", Td, d), as_transform_rate("Tdd", Tdd, d)
    r = as_vectors("point", point, d, limit=LENGTH)
    rd = as_vectors("point_velocity", point_velocity, d, limit=rate("m/s"))
    rdd = as_vectors("point_acceleration", point_acceleration, d, limit=rate("m/s^2"))
    T, Td, Tdd, r, rd, rdd = together(
        ("transform", T, 2), ("Td", Td, 2), ("Tdd", Tdd, 2), ("point", r, 1),
        ("point_velocity", rd, 1), ("point_acceleration", rdd, 1))

    def times(M, x):
        return np.einsum("...ij,...j->...i", M[..., :d, :d], x)

    drag_v = times(Td, r) + Td[..., :d, d]
    rel_v = times(T, rd)
    drag_a = times(Tdd, r) + Tdd[..., :d, d]
    coriolis = 2.0 * times(Td, rd)
    rel_a = times(T, rdd)
    return PointMotion(position=times(T, r) + T[..., :d, d], velocity=drag_v + rel_v,
                       acceleration=drag_a + coriolis + rel_a, drag_velocity=drag_v,
                       relative_velocity=rel_v, drag_acceleration=drag_a,
                       coriolis_acceleration=coriolis, relative_acceleration=rel_a)


@dataclass(frozen=True)
class AngularMotion:
    """Angular velocity and acceleration of a frame, in the fixed frame's components.

    Attributes
    ----------
    omega : ndarray, shape (3,) or (N, 3), rad/s
    alpha : ndarray, shape (3,) or (N, 3), rad/s²
    """

    omega: np.ndarray
    alpha: np.ndarray


def euler_rates(sequence: str, angles: ArrayLike, rates: ArrayLike,
                accelerations: ArrayLike = 0.0, *,
                axes: Literal["fixed", "moving"] = "fixed") -> AngularMotion:
    """Angular velocity and acceleration of the frame :func:`euler_rotation` describes.

    Written as moving-axes factors ``R = R1 R2 ... Rk`` (a fixed-axes sequence is the
    reverse moving one), factor j turns about ``u_j = R1 ... R(j-1) e_j``, so
    ``ω = Σ θ̇_j u_j`` and, since ``u_j`` turns with ``ω_(j-1) = Σ_(i<j) θ̇_i u_i``,
    ``α = Σ θ̈_j u_j + Σ θ̇_j ω_(j-1) × u_j``.

    Parameters
    ----------
    sequence : str
        As in :func:`euler_rotation`.
    angles, rates, accelerations : array_like, shape (k,) or (N, k)
        rad, rad/s, rad/s², in the order of ``sequence``.
    axes : {'fixed', 'moving'}

    Returns
    -------
    AngularMotion
        ``omega`` and ``alpha`` in the fixed frame, shape (3,) or (N, 3).

    Examples
    --------
    Yaw rate 1 rad/s after a 90° pitch (moving z then y'): the yaw axis is fixed z.

    >>> m = kl.spatial.euler_rates("zy", [0.0, np.pi / 2], [1.0, 0.0], axes="moving")
    >>> m.omega
    array([0., 0., 1.])
    """
    seq = _scipy_sequence(sequence, axes)
    k = len(seq)
    angles = as_angles("angles", angles, (k,))
    rates = as_array("rates", rates, (k,), limit=rate("rad/s"))
    accelerations = reals("accelerations", accelerations)
    if accelerations.ndim == 0 and accelerations == 0.0:
        accelerations = np.zeros(k)
    accelerations = as_array("accelerations", accelerations, (k,), limit=rate("rad/s^2"))
    angles, rates, accelerations = together(("angles", angles, 1), ("rates", rates, 1),
                                            ("accelerations", accelerations, 1))
    letters = seq.lower()
    order = range(k) if axes == "moving" else range(k - 1, -1, -1)
    lead = angles.shape[:-1]
    omega = np.zeros(lead + (3,))
    alpha = np.zeros(lead + (3,))
    prefix = Rotation.identity() if not lead else Rotation.identity(lead[0])
    for j in order:
        unit = np.eye(3)["xyz".index(letters[j])]
        u = prefix.apply(unit)
        alpha = alpha + accelerations[..., j, None] * u + \
            rates[..., j, None] * np.cross(omega, u)
        omega = omega + rates[..., j, None] * u
        prefix = prefix * Rotation.from_euler(letters[j], angles[..., j, None])
    return AngularMotion(omega=omega, alpha=alpha)
