"""Dimensional synthesis of spherical four-bars: function generation (the spherical form of
Freudenstein's equation) and motion generation through three or four orientations of the
coupler (the spherical form of Burmester's theory).

Every linkage comes back as a :class:`kinelab.spatial.SphericalFourBar`, and every reported
error is measured by moving it with that class's own analysis, not from the equations the
synthesis solved.

**Function generation.**  With the frame and angles of
:class:`~kinelab.spatial.SphericalFourBar` (arcs α1 ground, α2 crank, α3 coupler, α4
rocker), the loop closes when ``A cos θ4 + B sin θ4 = C``.  Dividing by ``sin α2 sin α4``,

    K1 cos θ4 - K2 cos θ2 + K3 = cos α1 cos θ2 cos θ4 + sin θ2 sin θ4,
    K1 = sin α1 cot α2,   K2 = sin α1 cot α4,
    K3 = (cos α3 - cos α1 cos α2 cos α4) / (sin α2 sin α4),

linear in (K1, K2, K3) once the ground arc α1 is chosen: three angle pairs fix the
linkage, more are met in the least-squares sense.  On a sphere much larger than the linkage
(α1 → 0, the arcs small) it becomes the planar ``K1 cos θ4 - K2 cos θ2 + K3 = cos(θ2 -
θ4)``.  Back from the constants: ``α2 = atan2(sin α1, K1)``, ``α4 = atan2(sin α1, K2)``
(each in (0, π)) and ``cos α3 = cos α1 cos α2 cos α4 + K3 sin α2 sin α4``, which must lie
in (-1, 1).

**Motion generation.**  A coupler orientation is a rotation matrix ``R_j`` (body to ground
frame).  A crank (or rocker) joins a fixed axis ``u`` to an axis ``b`` of the coupler (in
the coupler's own frame); the arc between them is constant:
``u · R_j b = u · R_1 b``.  For three orientations, choose ``u``: the two conditions
``((R_j - R_1)ᵀ u) · b = 0``, j = 2, 3, are linear in b, whose direction is their cross
product (the spherical circle point).  For four orientations the three conditions have a
non-zero solution only where ``det[(R_2 - R_1)ᵀ u, (R_3 - R_1)ᵀ u, (R_4 - R_1)ᵀ u] = 0``,
a cubic cone in u: the spherical centre-point curve, sampled here as the planar
:func:`~kinelab.synthesis.four_positions` samples its curve.

References
----------
C. H. Chiang, *Kinematics of Spherical Mechanisms*, Cambridge University Press, 1988.
J. M. McCarthy and G. S. Soh, *Geometric Design of Linkages*, 2nd ed., Springer, 2011,
ch. 7.
"""
from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.solvers import wrap_angle
from kinelab.solvers._arguments import flag, reals, whole
from kinelab.spatial import SphericalFourBar
from kinelab.synthesis._arguments import angle_array
from kinelab.synthesis._results import SolutionList

__all__ = ["spherical_freudenstein", "spherical_function", "SphericalFunctionSolution",
           "SphericalMotionSolution", "spherical_three_orientations",
           "spherical_center_axes", "SphericalCenterAxes", "spherical_four_orientations"]

_REACHED = 1e-9      # rad: a synthesized linkage reaches a prescribed angle or orientation
_DEGENERATE = 1e-10  # relative: singular values below this fix nothing
_MAX_PAIRS = 10_000
_MAX_SAMPLES = 100_000


# -- shared ---------------------------------------------------------------------------------
def _unit(name: str, value: ArrayLike) -> np.ndarray:
    v = reals(name, value)
    if v.shape != (3,):
        raise ModelError(f"{name}: expected a direction of three numbers, got shape {v.shape}")
    n = float(np.linalg.norm(v))
    if not n > 0.0 or not math.isfinite(n):
        raise ModelError(f"{name}: expected a direction (not all zero), got {describe(value)}")
    return v / n


def _rotations(value, count: int | None) -> np.ndarray:
    """Rotation matrices (n, 3, 3) from matrices or a scipy Rotation, checked."""
    if hasattr(value, "as_matrix") and callable(value.as_matrix):
        value = value.as_matrix()
    R = reals("rotations", value)
    if R.ndim != 3 or R.shape[1:] != (3, 3):
        raise ModelError(f"rotations: expected rotation matrices of shape (n, 3, 3) (or a "
                         f"scipy Rotation), got shape {R.shape}")
    n = R.shape[0]
    if count is not None and n != count:
        raise ModelError(f"rotations: expected {count} orientations, got {n}")
    err = np.abs(np.einsum("nji,njk->nik", R, R) - np.eye(3)).max(axis=(1, 2))
    det = np.linalg.det(R)
    bad = np.flatnonzero((err > 1e-9) | (det < 0.0))
    if bad.size:
        raise ModelError(f"rotations[{int(bad[0])}]: expected a rotation matrix (orthonormal, "
                         f"det +1), off by {float(err[bad[0]]):.3g}")
    for j in range(1, n):
        if np.abs(R[j] - R[0]).max() < 1e-9:
            raise ModelError(f"rotations[{j}]: the same orientation as rotations[0]; give "
                             f"distinct orientations")
    return R


def _arc(u: np.ndarray, v: np.ndarray) -> float:
    return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))


def _frame(u_O2: np.ndarray, u_O4: np.ndarray) -> np.ndarray:
    """T (rows x, y, z): ground coordinates to SphericalFourBar's frame, T u_O2 = z and
    T u_O4 in the xz half-plane x > 0."""
    z = u_O2
    x = u_O4 - (u_O4 @ z) * z
    x = x / np.linalg.norm(x)
    return np.stack([x, np.cross(z, x), z])


def _coupler_frame(u_A: np.ndarray, u_B: np.ndarray) -> np.ndarray:
    """SphericalFourBar's coupler matrix (columns x: tangent at A towards B, y, z = u_A)."""
    x = u_B - (u_A @ u_B) * u_A
    x = x / np.linalg.norm(x)
    return np.stack([x, np.cross(u_A, x), u_A], axis=-1)


def _rotation_angle(R: np.ndarray) -> np.ndarray:
    """Angle of rotation matrices (..., 3, 3), rad, accurate near 0."""
    skew = np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0],
                     R[..., 1, 0] - R[..., 0, 1]], -1)
    tr = np.trace(R, axis1=-2, axis2=-1)
    return np.arctan2(0.5 * np.linalg.norm(skew, axis=-1), 0.5 * (tr - 1.0))


# -- function generation --------------------------------------------------------------------
def _ground(value, degrees: bool) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise ModelError(f"ground: expected the ground arc, a number in "
                         f"{'(0, 180) deg' if degrees else '(0, π) rad'}, got {describe(value)}")
    x = math.radians(float(value)) if degrees else float(value)
    if not 0.0 < x < math.pi:
        raise ModelError(f"ground: expected the ground arc in "
                         f"{'(0, 180) deg' if degrees else '(0, π) rad'}, got {describe(value)}")
    return x


def _pairs(theta2, theta4, degrees: bool) -> tuple[np.ndarray, np.ndarray]:
    t2 = angle_array("input_angles", theta2, degrees)
    t4 = angle_array("output_angles", theta4, degrees)
    if t2.shape != t4.shape or t2.ndim != 1 or t2.size < 3:
        raise ModelError(f"input_angles, output_angles: expected two arrays of the same shape "
                         f"(n,), n >= 3, got {t2.shape} and {t4.shape}")
    if t2.size > _MAX_PAIRS:
        raise ModelError(f"input_angles: expected at most {_MAX_PAIRS:,} pairs, got {t2.size:,}")
    return t2, t4


def _system(t2: np.ndarray, t4: np.ndarray, a1: float) -> tuple[np.ndarray, np.ndarray]:
    M = np.column_stack([np.cos(t4), -np.cos(t2), np.ones_like(t2)])
    rhs = math.cos(a1) * np.cos(t2) * np.cos(t4) + np.sin(t2) * np.sin(t4)
    return M, rhs


def spherical_freudenstein(input_angles: ArrayLike, output_angles: ArrayLike,
                           ground: float = math.pi / 2, *, degrees: bool = False) -> np.ndarray:
    """The constants (K1, K2, K3) of the spherical Freudenstein equation.

    ``K1 cos θ4 - K2 cos θ2 + K3 = cos α1 cos θ2 cos θ4 + sin θ2 sin θ4`` (see the module),
    exact through three pairs, least squares (the normal equations ``MᵀM K = Mᵀ r``) for
    more.

    Parameters
    ----------
    input_angles, output_angles : array_like, shape (n,), n >= 3
        θ2 and θ4 in the frame of :class:`~kinelab.spatial.SphericalFourBar`, rad (deg
        with ``degrees``).
    ground : float
        The ground arc α1, in (0, π) rad (deg with ``degrees``).

    Returns
    -------
    ndarray, shape (3,)

    Examples
    --------
    The constants of a known linkage come back from three of its positions:

    >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
    >>> q = np.array([-0.5, 0.0, 0.5])
    >>> K = kl.synthesis.spherical_freudenstein(q, m.analyze(q).theta4, ground=1.2)
    >>> np.allclose(K, [np.sin(1.2) / np.tan(0.4), np.sin(1.2) / np.tan(0.9),
    ...                 (np.cos(1.1) - np.cos(1.2) * np.cos(0.4) * np.cos(0.9))
    ...                 / (np.sin(0.4) * np.sin(0.9))], rtol=0, atol=1e-12)
    True
    """
    degrees = flag("degrees", degrees)
    t2, t4 = _pairs(input_angles, output_angles, degrees)
    a1 = _ground(ground, degrees)
    M, rhs = _system(t2, t4, a1)
    s = np.linalg.svd(M, compute_uv=False)
    if s[-1] <= _DEGENERATE * s[0]:
        raise ModelError("input_angles, output_angles: these pairs do not fix the spherical "
                         "Freudenstein constants (a repeated or symmetric pair); spread them")
    K, *_ = np.linalg.lstsq(M, rhs, rcond=None)
    return K


@dataclass(frozen=True, eq=False)
class SphericalFunctionSolution:
    """A spherical four-bar function generator and its structural error.

    Attributes
    ----------
    linkage : SphericalFourBar
        The linkage, on the assembly (``branch``) that best follows the pairs.
    K : ndarray, shape (3,)
        The spherical Freudenstein constants.
    input_angles, output_angles : ndarray, shape (n,)
        The prescribed θ2 and θ4, rad.
    output : ndarray, shape (n,)
        θ4 from the linkage's analysis at each θ2, rad (NaN where it does not close).
    structural_error : ndarray, shape (n,)
        ``output - output_angles`` wrapped to (-π, π], rad; +inf where the loop does not
        close at that input.
    residual : ndarray, shape (n,)
        The equation's residual at each pair (for comparison; not the structural error).
    fit : str
        ``"exact"`` (three pairs) or ``"least squares"``.
    """

    linkage: SphericalFourBar
    K: np.ndarray
    input_angles: np.ndarray
    output_angles: np.ndarray
    output: np.ndarray
    structural_error: np.ndarray
    residual: np.ndarray
    fit: str

    @property
    def max_error(self) -> float:
        """Largest |structural error|, rad."""
        return float(np.max(np.abs(self.structural_error)))

    def __repr__(self) -> str:
        a = ", ".join(f"{x:.6g}" for x in self.linkage.arcs)
        return (f"SphericalFunctionSolution(arcs=({a}) rad, branch={self.linkage.branch!r}, "
                f"fit={self.fit!r}, max_error={self.max_error:.3g} rad)")


def spherical_function(input_angles: ArrayLike, output_angles: ArrayLike,
                       ground: float = math.pi / 2, *, degrees: bool = False
                       ) -> SphericalFunctionSolution:
    """A spherical four-bar whose rocker angle θ4 follows the crank angle θ2 through given
    pairs: exactly through three, in the least-squares sense of the spherical Freudenstein
    equation beyond (see :func:`spherical_freudenstein`).

    Parameters
    ----------
    input_angles, output_angles : array_like, shape (n,), n >= 3
        θ2 and θ4, measured as :class:`~kinelab.spatial.SphericalFourBar` measures them,
        rad (deg with ``degrees``).  To generate a function over ranges of relative angles,
        add the start angles of crank and rocker (free choices, as in the planar
        :func:`~kinelab.synthesis.function_generation`).
    ground : float
        The ground arc α1 (the angle between the fixed axes), chosen by the designer; rad
        in (0, π), deg with ``degrees``.

    Returns
    -------
    SphericalFunctionSolution
        The linkage, and its structural error at each pair from its own analysis (both
        assemblies are tried; the one with the smaller largest error is kept).

    Raises
    ------
    ModelError
        Pairs that fix nothing, or constants that give no coupler (``|cos α3| >= 1``:
        choose another ground arc or other pairs).

    Examples
    --------
    Three pairs of a Hooke joint's law ``tan θ4' = tan θ2 / cos β`` (θ4' = θ4 - 90°) on a
    30° ground arc give the Hooke joint back (three quarter-circle arcs):

    >>> beta = np.radians(30)
    >>> t2 = np.radians([10.0, 40.0, 70.0])
    >>> t4 = np.arctan(np.tan(t2) / np.cos(beta)) + np.pi / 2
    >>> s = kl.synthesis.spherical_function(t2, t4, ground=beta)
    >>> np.degrees(s.linkage.arcs).round(9) + 0.0
    array([30., 90., 90., 90.])
    >>> s.fit, bool(s.max_error < 1e-12)
    ('exact', True)
    """
    degrees = flag("degrees", degrees)
    t2, t4 = _pairs(input_angles, output_angles, degrees)
    a1 = _ground(ground, degrees)
    K = spherical_freudenstein(t2, t4, a1)
    M, rhs = _system(t2, t4, a1)
    residual = M @ K - rhs
    s1, c1 = math.sin(a1), math.cos(a1)
    a2, a4 = math.atan2(s1, K[0]), math.atan2(s1, K[1])
    c3 = c1 * math.cos(a2) * math.cos(a4) + K[2] * math.sin(a2) * math.sin(a4)
    if not -1.0 < c3 < 1.0:
        raise ModelError(f"input_angles, output_angles: the constants give cos α3 = {c3:.6g}, "
                         f"no coupler joins crank and rocker; choose another ground arc or "
                         f"other pairs")
    a3 = math.acos(c3)
    if not all(0.0 < a < math.pi for a in (a2, a3, a4)):
        raise ModelError("input_angles, output_angles: the constants put two axes on one line; "
                         "choose another ground arc or other pairs")
    best = None
    for branch in ("open", "crossed"):
        linkage = SphericalFourBar(alpha1=a1, alpha2=a2, alpha3=a3, alpha4=a4, branch=branch)
        out = linkage.analyze(t2, unreachable="mask").theta4
        err = np.where(np.isnan(out), np.inf, wrap_angle(out - t4))
        key = float(np.max(np.abs(err)))
        if best is None or key < best[0]:
            best = (key, linkage, out, err)
    _, linkage, out, err = best
    return SphericalFunctionSolution(
        linkage=linkage, K=K, input_angles=t2, output_angles=t4, output=out,
        structural_error=err, residual=residual,
        fit="exact" if t2.size == 3 else "least squares")


# -- motion generation ----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SphericalMotionSolution:
    """A spherical four-bar that carries its coupler through prescribed orientations.

    Attributes
    ----------
    linkage : SphericalFourBar
        The linkage, on the assembly of the first orientation.
    frame : ndarray, shape (3, 3)
        ``T``: ground coordinates of the task to the linkage's frame (``T u_O2 = z``, O4
        in the xz half-plane, see :class:`~kinelab.spatial.SphericalFourBar`).
    fixed_axes : ndarray, shape (2, 3)
        ``u_O2`` and ``u_O4``, unit vectors in the task's ground frame.
    moving_axes : ndarray, shape (2, 3)
        The axes A and B in the coupler's own (body) frame: at orientation j they point
        along ``R_j a`` and ``R_j b``.
    theta2 : ndarray, shape (n,)
        The crank angle at each orientation, rad.
    rotation_error : ndarray, shape (n,)
        Angle of ``R_jᵀ R'_j``, rad, with ``R'_j`` the coupler orientation the linkage's
        analysis gives at ``theta2[j]`` on its branch (+inf where the loop does not close).
    reached : bool
        Every ``rotation_error`` at most 1e-9 rad: no branch defect.
    """

    linkage: SphericalFourBar
    frame: np.ndarray
    fixed_axes: np.ndarray
    moving_axes: np.ndarray
    theta2: np.ndarray
    rotation_error: np.ndarray
    reached: bool

    def __repr__(self) -> str:
        a = ", ".join(f"{x:.6g}" for x in self.linkage.arcs)
        return (f"SphericalMotionSolution(arcs=({a}) rad, branch={self.linkage.branch!r}, "
                f"reached={self.reached}, max rotation error "
                f"{float(np.max(self.rotation_error)):.3g} rad)")


def _circle_axis(R: np.ndarray, u: np.ndarray, name: str) -> np.ndarray:
    """The moving axis (body frame) for fixed axis ``u``: the null direction of the rows
    ``(R_j - R_1)ᵀ u``, signed so that its arc from u is at most π/2."""
    rows = np.einsum("nji,j->ni", R[1:] - R[0], u)
    if len(rows) == 2:
        b = np.cross(rows[0], rows[1])
        scale = float(np.linalg.norm(rows[0]) * np.linalg.norm(rows[1]))
        if not np.linalg.norm(b) > _DEGENERATE * max(scale, 1e-300):
            raise ModelError(f"{name}: this fixed axis fixes no moving axis (the conditions "
                             f"are dependent); choose another")
    else:
        b = np.linalg.svd(rows)[2][-1]
    b = b / np.linalg.norm(b)
    return b if u @ (R[0] @ b) >= 0.0 else -b


def _linkage(R: np.ndarray, u_O2: np.ndarray, u_O4: np.ndarray, a: np.ndarray,
             b: np.ndarray) -> SphericalMotionSolution:
    """The four-bar of two dyads, checked by its own analysis at every orientation."""
    T = _frame(u_O2, u_O4)
    A1, B1 = R[0] @ a, R[0] @ b
    arcs = dict(alpha1=_arc(u_O2, u_O4), alpha2=_arc(u_O2, A1), alpha3=_arc(A1, B1),
                alpha4=_arc(B1, u_O4))
    for name, v in arcs.items():
        if not 1e-12 < v < math.pi - 1e-12:
            raise ModelError(f"fixed_axes: {name}: two axes of the linkage lie on one line "
                             f"(arc {v:.3g} rad); choose other fixed axes")
    det = float(np.cross(u_O4, B1) @ A1)        # det[u_A, u_O4, u_B]
    linkage = SphericalFourBar(**arcs, branch="open" if det >= 0.0 else "crossed")
    uA = np.einsum("ij,njk,k->ni", T, R, a)     # A at each orientation, linkage frame
    theta2 = np.arctan2(uA[:, 1], uA[:, 0])
    sol = linkage.analyze(theta2, unreachable="mask")
    F = _coupler_frame(a, b)                     # body frame -> coupler's matrix at rest
    # the task's orientation the linkage gives: R'_j = Tᵀ C_j Fᵀ
    made = np.einsum("ji,njk,lk->nil", T, sol.coupler, F)
    err = _rotation_angle(np.einsum("nji,njk->nik", R, made))
    err = np.where(sol.assembled & np.isfinite(err), err, np.inf)
    return SphericalMotionSolution(
        linkage=linkage, frame=T, fixed_axes=np.stack([u_O2, u_O4]),
        moving_axes=np.stack([a, b]), theta2=theta2, rotation_error=err,
        reached=bool(np.all(err <= _REACHED)))


def spherical_three_orientations(rotations, fixed_axes) -> SphericalMotionSolution:
    """A spherical four-bar whose coupler takes three given orientations, the fixed axes
    chosen: the moving axes follow from linear conditions (the spherical form of the
    planar :func:`~kinelab.synthesis.three_positions` with fixed pivots given).

    Parameters
    ----------
    rotations : array_like, shape (3, 3, 3), or scipy.spatial.transform.Rotation
        The coupler's orientations ``R_j`` (body to ground), as rotation matrices (from
        axis-angle or Euler angles: ``Rotation.from_rotvec(...)``,
        ``Rotation.from_euler(...)``).
    fixed_axes : array_like, shape (2, 3)
        The directions of the fixed axes O2 (crank) and O4 (rocker) through the sphere's
        centre, in the ground frame (normalised here).

    Returns
    -------
    SphericalMotionSolution

    Raises
    ------
    ModelError
        Orientations that are not rotations or repeat, a fixed axis that fixes no moving
        axis, or two axes of the result on one line.

    Examples
    --------
    Three orientations of the coupler of a known linkage, and its own fixed axes, give the
    linkage back:

    >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
    >>> sol = m.analyze([0.0, 0.4, 0.8])
    >>> s = kl.synthesis.spherical_three_orientations(sol.coupler,
    ...                                               [sol.u_O2[0], sol.u_O4[0]])
    >>> np.round(s.linkage.arcs, 12).tolist(), s.reached
    ([1.2, 0.4, 1.1, 0.9], True)
    """
    R = _rotations(rotations, 3)
    axes = reals("fixed_axes", fixed_axes)
    if axes.shape != (2, 3):
        raise ModelError(f"fixed_axes: expected two directions, shape (2, 3), got {axes.shape}")
    u_O2, u_O4 = _unit("fixed_axes[0]", axes[0]), _unit("fixed_axes[1]", axes[1])
    a = _circle_axis(R, u_O2, "fixed_axes[0]")
    b = _circle_axis(R, u_O4, "fixed_axes[1]")
    return _linkage(R, u_O2, u_O4, a, b)


@dataclass(frozen=True, eq=False)
class SphericalCenterAxes:
    """Samples of the spherical centre-point curve of four orientations.

    Attributes
    ----------
    center : ndarray, shape (m, 3)
        Fixed axes (unit vectors, ground frame) whose moving axis keeps a constant arc
        through all four orientations: roots of ``det[(R_j - R_1)ᵀ u] = 0``, a cubic cone.
    circle : ndarray, shape (m, 3)
        The moving axis of each, in the coupler's body frame.
    residual : ndarray, shape (m,)
        ``max_j |u · (R_j - R_1) b|`` of each pair (rounding).
    """

    center: np.ndarray
    circle: np.ndarray
    residual: np.ndarray


def spherical_center_axes(rotations, *, samples: int = 721) -> SphericalCenterAxes:
    """Sample the spherical centre-point curve (the cone of fixed axes) of four coupler
    orientations.

    Each fixed axis is taken up to sign (u and -u are one line); the directions ``(cos φ
    e1 + sin φ e2 + λ e3)`` over ``samples`` values of φ in [0, π) cover every line but
    e3, and on each the determinant is a cubic in λ whose real roots are the samples
    (e1, e2, e3 a fixed generic frame).

    Parameters
    ----------
    rotations : array_like, shape (4, 3, 3), or scipy Rotation
    samples : int
        Values of φ.

    Returns
    -------
    SphericalCenterAxes
    """
    R = _rotations(rotations, 4)
    samples = whole("samples", samples, 8, _MAX_SAMPLES)
    D = R[1:] - R[0]                                      # (3, 3, 3)
    # a generic frame, so that no sampled family is special for a task's round numbers
    c, s = math.cos(0.37), math.sin(0.37)
    E = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) @ np.array(
        [[1.0, 0.0, 0.0], [0.0, math.cos(0.61), math.sin(0.61)],
         [0.0, -math.sin(0.61), math.cos(0.61)]])
    phi = np.arange(samples) * (math.pi / samples)
    base = np.cos(phi)[:, None] * E[0] + np.sin(phi)[:, None] * E[1]      # (m, 3)

    def det(lam):
        u = base + lam * E[2]                                             # (m, 3)
        rows = np.einsum("kji,mj->mki", D, u)                             # (m, 3, 3)
        return np.linalg.det(rows)
    lams = np.array([-1.0, 0.0, 1.0, 2.0])
    vals = np.stack([det(x) for x in lams], -1)                           # (m, 4)
    coef = np.linalg.solve(np.vander(lams, 4), vals.T).T                  # c3, c2, c1, c0
    big = np.abs(coef).max(axis=1, keepdims=True)
    cubic = np.abs(coef[:, 0]) > 1e-12 * big[:, 0]
    comp = np.zeros((samples, 3, 3))
    lead = np.where(cubic, coef[:, 0], 1.0)
    comp[:, 0, :] = -coef[:, 1:] / lead[:, None]
    comp[:, 1, 0] = comp[:, 2, 1] = 1.0
    roots = np.linalg.eigvals(comp)                                       # (m, 3)
    real = cubic[:, None] & (np.abs(roots.imag) <= 1e-9 * (1.0 + np.abs(roots.real)))
    idx, k = np.nonzero(real)
    u = base[idx] + roots.real[idx, k][:, None] * E[2]
    u = u / np.linalg.norm(u, axis=1, keepdims=True)
    # each root's moving axis: the null direction of its three conditions
    rows = np.einsum("kji,mj->mki", D, u)
    b = np.linalg.svd(rows)[2][:, -1]
    b = np.where((np.einsum("mi,ij,mj->m", u, R[0], b) < 0.0)[:, None], -b, b)
    residual = np.abs(np.einsum("mki,mi->mk", rows, b)).max(axis=1)
    return SphericalCenterAxes(center=u, circle=b, residual=residual)


def spherical_four_orientations(rotations, fixed_axes=None, *, samples: int = 721,
                                candidates: int = 24) -> SolutionList:
    """Spherical four-bars whose coupler takes four given orientations: both fixed axes
    on the spherical centre-point curve (:func:`spherical_center_axes`).

    Parameters
    ----------
    rotations : array_like, shape (4, 3, 3), or scipy Rotation
        The coupler's orientations (body to ground).
    fixed_axes : array_like, shape (2, 3), optional
        Approximate fixed axes: each is replaced by the sampled centre axis nearest it (as a
        line), and one linkage is returned.  Without them, ``candidates`` centre axes spread
        along the curve are paired in every way.
    samples : int
        Samples of the curve.
    candidates : int
        Centre axes tried in pairs without ``fixed_axes``.

    Returns
    -------
    SolutionList of SphericalMotionSolution
        The linkages that reach all four orientations on one assembly (``reached``), sorted
        by their largest rotation error; ``reason`` says why candidates were left out.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
    >>> R = m.analyze([0.0, 0.3, 0.6, 0.9]).coupler
    >>> found = kl.synthesis.spherical_four_orientations(R)
    >>> len(found) > 0 and all(s.reached for s in found)
    True
    """
    R = _rotations(rotations, 4)
    curve = spherical_center_axes(R, samples=samples)
    if len(curve.center) < 2:
        return SolutionList([], reason="the centre-point curve has fewer than two samples")
    if fixed_axes is not None:
        axes = reals("fixed_axes", fixed_axes)
        if axes.shape != (2, 3):
            raise ModelError(f"fixed_axes: expected two directions, shape (2, 3), got "
                             f"{axes.shape}")
        picks = []
        for k in range(2):
            u = _unit(f"fixed_axes[{k}]", axes[k])
            picks.append(int(np.argmax(np.abs(curve.center @ u))))
        if picks[0] == picks[1]:
            raise ModelError("fixed_axes: both are nearest the same centre axis; give two "
                             "directions further apart")
        pairs = [tuple(picks)]
    else:
        candidates = whole("candidates", candidates, 2, 200)
        pick = np.unique(np.round(np.linspace(0, len(curve.center) - 1,
                                              min(candidates, len(curve.center)))).astype(int))
        pairs = [(int(i), int(j)) for n, i in enumerate(pick) for j in pick[n + 1:]]
    found, refused = [], 0
    for i, j in pairs:
        u, v = curve.center[i], curve.center[j]
        if abs(float(u @ v)) > 1.0 - 1e-9:
            refused += 1
            continue
        try:
            s = _linkage(R, u, v, curve.circle[i], curve.circle[j])
        except ModelError:
            refused += 1
            continue
        if s.reached:
            found.append(s)
        else:
            refused += 1
    found.sort(key=lambda s: float(np.max(s.rotation_error)))
    reason = (f"{refused} of {len(pairs)} pair(s) of centre axes left out: a branch defect "
              f"(an orientation on the other assembly or out of reach) or axes on one line"
              if refused else "")
    return SolutionList(found, reason=reason)
