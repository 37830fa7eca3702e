"""The spherical four-bar (RRRR with four axes through one point): positions, velocity and
acceleration coefficients, Grashof's criterion on the sphere and limit positions."""
from __future__ import annotations

import itertools
import math
import numbers
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError, check_choice, describe, shown
from kinelab.model import Mechanism
from kinelab.solvers import wrap_angle
from kinelab.solvers._arguments import reals
from kinelab.spatial._common import as_angles, as_array, indices, rate, together

__all__ = ["SphericalFourBar", "SphericalFourBarPositions", "SphericalFourBarSolution",
           "SphericalGrashof"]

# Dimensionless tolerances (every quantity here is a cosine, a sine or a triple product of
# unit vectors).
# _CLOSE: a discriminant D = R² - C² down to -_CLOSE R² still closes the loop (with β = 0):
# D is linear in θ2 near a limit position, so this admits inputs within about 1e-12 rad of
# it, which rounding of the limit itself would otherwise refuse.
_CLOSE = 1e-12
# _FOLD: sin β (β the half-angle between the two assemblies) below this is a limit position:
# ∂Φ/∂θ4 = 0 there and K is unbounded.  sin² β grows linearly with the distance from the
# limit, and rounding leaves it a few 1e-16 at a limit given to the last bit: this flags
# inputs within about 1e-12 rad of one, where K would be 1e6 or more.
_FOLD = 1e-6
# _CONCURRENT: the four joint axes of a model meet in one point to this, relative to the
# size of the sketch.
_CONCURRENT = 1e-9

BRANCHES = ("open", "crossed")
KINDS = ("crank-rocker", "double-crank", "rocker-crank", "double-rocker", "change-point",
         "triple-rocker")


def _arc(name: str, value: object, degrees: bool = False) -> tuple[float, str | None]:
    """``value`` as an arc in (0, π) rad, or the problem with it (given and shown in
    degrees with ``degrees``)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    shown = "(0, 180) deg" if degrees else "(0, π) rad"
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        return math.nan, (f"{name}: expected an arc in {shown} (a real number), got "
                          f"{describe(value)}")
    x = float(value)
    if not 0.0 < x < (180.0 if degrees else math.pi):
        return math.nan, (f"{name}: expected an arc in {shown} (the great-circle angle "
                          f"between two joint axes), got {describe(value)}; an arc of 0 or "
                          f"{'180 deg' if degrees else 'π'} puts two axes on one line")
    return (math.radians(x) if degrees else x), None


def _rot_y(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _det(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Triple products ``a · (b × c)`` of vectors (..., 3)."""
    return np.einsum("...i,...i->...", a, np.cross(b, c))


def _full_turn(ground: float, link: float, far: float, near: float) -> bool:
    """``link`` turns fully about its joint with ``ground`` (the chain ground, link, far,
    near, in this order round the loop): as it turns, the arc from the far end of ``link``
    to the far end of ``ground`` sweeps ``[|ground - link|, π - |π - ground - link|]``,
    which must lie within what the other two links span, ``[|far - near|, π - |π - far -
    near|]`` (closed: a change point at an end)."""
    lo, hi = abs(ground - link), math.pi - abs(math.pi - ground - link)
    reach_lo, reach_hi = abs(far - near), math.pi - abs(math.pi - far - near)
    return lo >= reach_lo and hi <= reach_hi


@dataclass(frozen=True)
class SphericalGrashof:
    """Grashof class of a spherical four-bar.

    Attributes
    ----------
    kind : str
        ``"crank-rocker"``, ``"double-crank"``, ``"rocker-crank"``, ``"double-rocker"``
        (Grashof: the coupler turns fully relative to crank and rocker, neither of which
        turns relative to the ground), ``"change-point"`` (s + l = p + q) or
        ``"triple-rocker"`` (non-Grashof).
    grashof : bool
        s + l <= p + q on the reduced arcs: some link turns fully relative to the others.
    crank_rotates, rocker_rotates : bool
        The crank (rocker) turns full circle relative to the ground.
    margin : float
        (p + q) - (s + l) of the reduced arcs, rad.
    reduced : tuple of float
        The arcs (ground, crank, coupler, rocker) of the equivalent linkage used, rad.
    reversed_axes : tuple of str
        The axes reversed to reach it, among ``"O2"``, ``"A"``, ``"B"``, ``"O4"``.
    """

    kind: str
    grashof: bool
    crank_rotates: bool
    rocker_rotates: bool
    margin: float
    reduced: tuple[float, float, float, float]
    reversed_axes: tuple[str, ...]


@dataclass(frozen=True)
class SphericalFourBarPositions:
    """Both assemblies of a spherical four-bar at each input angle.

    Attributes
    ----------
    theta2 : ndarray, shape () or (N,), rad
    A, B, C : ndarray, shape () or (N,)
        The coefficients of ``A cos θ4 + B sin θ4 = C`` (dimensionless).
    theta4 : ndarray, shape (2,) or (N, 2), rad in (-π, π]
        Column 0 ``"open"``, column 1 ``"crossed"``; NaN where not ``assembled``.
    assembled : ndarray of bool, shape () or (N,)
        ``A² + B² >= C²``: the coupler closes the loop at this input.
    """

    theta2: np.ndarray
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    theta4: np.ndarray
    assembled: np.ndarray


@dataclass(frozen=True)
class SphericalFourBarSolution:
    """Motion of a spherical four-bar along one assembly.

    Every array has the shape of ``theta2`` (() or (N,)), with a trailing (3,) for a
    direction and (3, 3) for a rotation; samples not ``assembled`` are NaN (with
    ``unreachable="mask"``), and the rates of ``singular`` samples are NaN.

    Attributes
    ----------
    theta2, theta2_dot, theta2_ddot : ndarray
        Input angle (rad), speed (rad/s), acceleration (rad/s²).
    theta3, theta4 : ndarray
        Coupler and rocker angles, rad in (-π, π] (see :class:`SphericalFourBar`).
    K3, K4 : ndarray
        Velocity coefficients ``dθ3/dθ2``, ``dθ4/dθ2``.
    L3, L4 : ndarray
        Acceleration coefficients ``dK3/dθ2``, ``dK4/dθ2``.
    omega3, omega4, alpha3, alpha4 : ndarray
        ``θ̇ = K θ̇2`` and ``θ̈ = K θ̈2 + L θ̇2²``, rad/s and rad/s².
    u_O2, u_A, u_B, u_O4 : ndarray, shape (..., 3)
        Unit vectors along the four joint axes.
    coupler : ndarray, shape (..., 3, 3)
        Orientation of the coupler: columns x (the tangent at A of the arc A→B), y, z = u_A.
    branch : str
        ``"open"`` or ``"crossed"``.
    assembled, singular : ndarray of bool
        The loop closes; the input is at a limit position (``∂Φ/∂θ4 = 0``, K unbounded).
    """

    theta2: np.ndarray
    theta2_dot: np.ndarray
    theta2_ddot: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    K3: np.ndarray
    K4: np.ndarray
    L3: np.ndarray
    L4: np.ndarray
    omega3: np.ndarray
    omega4: np.ndarray
    alpha3: np.ndarray
    alpha4: np.ndarray
    u_O2: np.ndarray
    u_A: np.ndarray
    u_B: np.ndarray
    u_O4: np.ndarray
    coupler: np.ndarray
    branch: str
    assembled: np.ndarray
    singular: np.ndarray


@dataclass(frozen=True, kw_only=True)
class SphericalFourBar:
    """A spherical four-bar: four revolute joints whose axes meet at the centre O of a sphere.

    Each link is an arc of great circle between the two axes it carries, of length (the angle
    between the axes) ``alpha1`` (ground, O2 to O4), ``alpha2`` (crank, O2 to A), ``alpha3``
    (coupler, A to B) and ``alpha4`` (rocker, B to O4), each in (0, π) rad.  The axes are unit
    vectors from O, named by where they pierce the unit sphere; the direction of an axis is
    part of the linkage (reversing one changes the two arcs that meet there to their
    supplements, and moves no link).

    **Frame and angles.**  ``u_O2 = z``, ``u_O4 = Rot(y, α1) z = (sin α1, 0, cos α1)``: the
    ground arc runs from O2 towards +x, as a planar four-bar's ground from O2 to O4.

    - the crank turns by θ2 about u_O2: ``u_A = Rot(z, θ2) Rot(y, α2) z = (sin α2 cos θ2,
      sin α2 sin θ2, cos α2)``; θ2 = 0 puts A on the arc from O2 towards O4;
    - the rocker turns by θ4 about u_O4: ``u_B = Rot(y, α1) Rot(z, θ4) Rot(y, α4) z``;
      θ4 = 0 puts B on the great circle of the ground, beyond O4;
    - the coupler's orientation is ``Rot(z, θ2) Rot(y, α2) Rot(z, θ3 - θ2)``, whose x column
      is the tangent at A of the arc A→B: ``θ3 - θ2`` is the angle at A, about u_A, from the
      crank's arc (continued past A) to the coupler's.

    Near O2, on a sphere much larger than the linkage, these are the planar four-bar's
    angles (CCW from +x, seen from outside the sphere), and the arcs its lengths.

    **Position.**  The coupler keeps ``u_A · u_B = cos α3``.  Expanding,
    ``Φ = A cos θ4 + B sin θ4 - C = 0`` with

    - ``A = sin α4 (sin α2 cos α1 cos θ2 - cos α2 sin α1)``,
    - ``B = sin α4 sin α2 sin θ2``,
    - ``C = cos α3 - cos α4 (sin α2 sin α1 cos θ2 + cos α2 cos α1)``,

    the spherical Freudenstein equation.  With ``R² = A² + B²``, ``ψ = atan2(B, A)`` and
    ``β = atan2(sqrt(R² - C²), C)``, ``θ4 = ψ ∓ β``.  Since ``∂Φ/∂θ4 = det[u_A, u_O4, u_B] =
    ±R sin β``, the two assemblies are told apart as a planar four-bar's: ``"open"``
    (``θ4 = ψ - β``) puts B to the left of the great circle from A to O4, seen from outside
    the sphere, ``"crossed"`` (``θ4 = ψ + β``) to its right.

    **Rates.**  ``K4 = dθ4/dθ2 = -Φ_θ2 / Φ_θ4`` and ``L4 = dK4/dθ2 = -(Φ_θ2θ2 + 2 Φ_θ2θ4 K4
    + Φ_θ4θ4 K4²) / Φ_θ4``.  The coupler's angular velocity is both ``θ̇2 u_O2 + (θ̇3 - θ̇2)
    u_A`` and ``θ̇4 u_O4 + ν u_B``; the dot product with ``u_B × u_O4`` gives
    ``K3 = 1 - det[u_O2, u_B, u_O4] / det[u_A, u_B, u_O4]``, and L3 its exact derivative
    (``du_A/dθ2 = u_O2 × u_A``, ``du_B/dθ2 = K4 u_O4 × u_B``).  With the dot product with
    ``u_A × u_B`` instead, ``K4 = det[u_O2, u_A, u_B] / det[u_O4, u_A, u_B]``: the output
    stands still where O2, A and B lie on one great circle (crank and coupler in line: the
    rocker's limit positions), and K4 is unbounded where A, B and O4 do (coupler and rocker
    in line: the input's limit positions).

    Parameters
    ----------
    alpha1, alpha2, alpha3, alpha4 : float
        Arcs of the ground, crank, coupler and rocker, rad, each in (0, π).
    branch : {"open", "crossed"}
        The assembly :meth:`analyze` follows unless told otherwise.

    References
    ----------
    C. H. Chiang, *Kinematics of Spherical Mechanisms*, Cambridge University Press, 1988.

    Examples
    --------
    A Hooke (Cardan) joint is a spherical four-bar whose crank, coupler and rocker are
    90° arcs (the yokes' pins and the two arms of the cross); its ground arc is the angle β
    between the shafts, both axes pointing along the drive (see :meth:`analyze`):

    >>> hooke = kl.spatial.SphericalFourBar(alpha1=np.radians(30), alpha2=np.pi / 2,
    ...                                     alpha3=np.pi / 2, alpha4=np.pi / 2)
    >>> hooke.grashof().kind
    'double-crank'
    """

    alpha1: float
    alpha2: float
    alpha3: float
    alpha4: float
    branch: Literal["open", "crossed"] = "open"

    def __post_init__(self):
        problems = []
        for name in ("alpha1", "alpha2", "alpha3", "alpha4"):
            value, problem = _arc(name, getattr(self, name))
            if problem:
                problems.append(problem)
            object.__setattr__(self, name, value)
        if not isinstance(self.branch, str) or self.branch not in BRANCHES:
            problems.append(f"branch: expected one of 'open', 'crossed', got "
                            f"{describe(self.branch)}")
        if problems:
            raise ModelError(problems)

    @property
    def arcs(self) -> tuple[float, float, float, float]:
        """``(alpha1, alpha2, alpha3, alpha4)``, rad."""
        return (self.alpha1, self.alpha2, self.alpha3, self.alpha4)

    # -- position -------------------------------------------------------------------------
    def _coefficients(self, theta2: np.ndarray):
        a1, a2, a3, a4 = self.arcs
        s1, c1, s2, c2 = math.sin(a1), math.cos(a1), math.sin(a2), math.cos(a2)
        s4, c4 = math.sin(a4), math.cos(a4)
        ct, st = np.cos(theta2), np.sin(theta2)
        A = s4 * (s2 * c1 * ct - c2 * s1)
        B = s4 * s2 * st
        C = math.cos(a3) - c4 * (s2 * s1 * ct + c2 * c1)
        # d/dθ2 and d²/dθ2² of A, B, C
        d1 = (-s4 * s2 * c1 * st, s4 * s2 * ct, c4 * s2 * s1 * st)
        d2 = (-s4 * s2 * c1 * ct, -s4 * s2 * st, c4 * s2 * s1 * ct)
        return A, B, C, d1, d2

    def _solve(self, theta2: np.ndarray):
        A, B, C, d1, d2 = self._coefficients(theta2)
        R2 = A * A + B * B
        D = R2 - C * C
        assembled = (D >= -_CLOSE * R2) & (R2 > 0.0)
        root = np.sqrt(np.maximum(D, 0.0))
        psi = np.arctan2(B, A)
        beta = np.arctan2(root, C)
        theta4 = np.stack([psi - beta, psi + beta], axis=-1)
        theta4 = np.where(assembled[..., None], wrap_angle(theta4), np.nan)
        return A, B, C, d1, d2, R2, root, theta4, assembled

    def positions(self, theta2: ArrayLike) -> SphericalFourBarPositions:
        """Both assemblies θ4 at each input angle θ2; never raises on an input out of reach
        (see ``assembled``).

        Parameters
        ----------
        theta2 : float or array_like, shape () or (N,)
            rad.

        Returns
        -------
        SphericalFourBarPositions

        Examples
        --------
        >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9)
        >>> m.positions([0.0, 1.0]).theta4.shape
        (2, 2)
        """
        theta2 = as_angles("theta2", theta2)
        A, B, C, _, _, _, _, theta4, assembled = self._solve(theta2)
        return SphericalFourBarPositions(theta2=theta2, A=A, B=B, C=C, theta4=theta4,
                                         assembled=assembled)

    def axes(self, theta2: ArrayLike, theta4: ArrayLike) -> tuple[np.ndarray, ...]:
        """``u_O2, u_A, u_B, u_O4`` (unit vectors, shape (..., 3)) at the given angles (rad,
        broadcast together)."""
        theta2, theta4 = together(("theta2", as_angles("theta2", theta2, batch="any"), 0),
                                  ("theta4", reals("theta4", theta4), 0))
        return self._axes(theta2, theta4)

    def _axes(self, theta2: np.ndarray, theta4: np.ndarray):
        a1, a2, _, a4 = self.arcs
        s2, c2, s4, c4 = math.sin(a2), math.cos(a2), math.sin(a4), math.cos(a4)
        u_O2 = np.broadcast_to(np.array([0.0, 0.0, 1.0]), theta2.shape + (3,))
        u_O4 = np.broadcast_to(np.array([math.sin(a1), 0.0, math.cos(a1)]), theta2.shape + (3,))
        u_A = np.stack([s2 * np.cos(theta2), s2 * np.sin(theta2), np.full_like(theta2, c2)], -1)
        local = np.stack([s4 * np.cos(theta4), s4 * np.sin(theta4),
                          np.full_like(theta4, c4)], -1)
        u_B = local @ _rot_y(a1).T
        return u_O2, u_A, u_B, u_O4

    # -- motion ---------------------------------------------------------------------------
    def analyze(self, theta2: ArrayLike, theta2_dot: ArrayLike = 0.0,
                theta2_ddot: ArrayLike = 0.0, *,
                branch: Literal["open", "crossed"] | None = None,
                unreachable: Literal["raise", "mask"] = "raise") -> SphericalFourBarSolution:
        """Coupler and rocker angles, velocity and acceleration coefficients along one
        assembly.

        Parameters
        ----------
        theta2 : float or array_like, shape () or (N,)
            Input angle, rad.
        theta2_dot, theta2_ddot : float or array_like, broadcast to ``theta2``
            rad/s, rad/s².
        branch : {"open", "crossed"}, optional
            The assembly (see :class:`SphericalFourBar`); default, the four-bar's own.
        unreachable : {"raise", "mask"}
            Where the loop cannot close: raise :class:`~kinelab.errors.AssemblyError` (with
            the reachable input range), or mark the sample in ``assembled`` and fill its
            values with NaN.

        Returns
        -------
        SphericalFourBarSolution

        Examples
        --------
        The Hooke joint of shafts at β = 30° (ground arc β, the other three 90°).  Both
        assemblies are the same joint, the cross turned over; on "crossed", the output
        yoke's pin is at ``θ4 - π/2`` from the plane of the shafts, with
        ``tan(θ4 - π/2) = tan θ2 / cos β``, and ``K4 = 1 / cos β`` at θ2 = 0:

        >>> beta = np.radians(30)
        >>> hooke = kl.spatial.SphericalFourBar(alpha1=beta, alpha2=np.pi / 2,
        ...                                     alpha3=np.pi / 2, alpha4=np.pi / 2)
        >>> sol = hooke.analyze(np.radians([0.0, 45.0]), theta2_dot=10.0, branch="crossed")
        >>> np.degrees(sol.theta4 - np.pi / 2).round(6)
        array([ 0.      , 49.106605])
        >>> sol.K4.round(6), sol.omega4.round(6)
        (array([1.154701, 0.989743]), array([11.547005,  9.897433]))
        """
        branch = self.branch if branch is None else branch
        check_choice("branch", branch, BRANCHES)
        check_choice("unreachable", unreachable, ("raise", "mask"))
        w = as_array("theta2_dot", theta2_dot, limit=rate("rad/s"))
        a = as_array("theta2_ddot", theta2_ddot, limit=rate("rad/s^2"))
        theta2 = as_angles("theta2", theta2)
        theta2, w, a = together(("theta2", theta2, 0), ("theta2_dot", w, 0),
                                ("theta2_ddot", a, 0))
        A, B, C, d1, d2, R2, root, both, assembled = self._solve(theta2)
        if unreachable == "raise" and not assembled.all():
            bad = ~np.atleast_1d(assembled)
            first = float(np.atleast_1d(theta2)[bad][0])
            reach = self.reachable_inputs()
            raise AssemblyError(
                f"spherical four-bar: the loop cannot close at θ2 = {first:.6g} rad "
                f"(sample(s) {indices(bad)}): the coupler's arc α3 = {self.alpha3:.6g} rad "
                f"cannot join A and B; reachable θ2 is {_spans(reach)} rad; narrow the input "
                f"range (or pass unreachable='mask')",
                loop="O2-A-B-O4", gap=float(np.nanmax(np.sqrt(np.maximum(C * C - R2, 0.0)))),
                reachable=reach)
        theta4 = both[..., 0] if branch == "open" else both[..., 1]
        sign = 1.0 if branch == "open" else -1.0
        c4, s4 = np.cos(theta4), np.sin(theta4)
        (A1, B1, C1), (A2, B2, C2) = d1, d2
        phi_2 = A1 * c4 + B1 * s4 - C1
        phi_4 = sign * root                       # = -A sin θ4 + B cos θ4, without rounding
        phi_22 = A2 * c4 + B2 * s4 - C2
        phi_24 = -A1 * s4 + B1 * c4
        phi_44 = -A * c4 - B * s4
        singular = assembled & (root <= _FOLD * np.sqrt(R2))
        with np.errstate(divide="ignore", invalid="ignore"):
            K4 = -phi_2 / phi_4
            L4 = -(phi_22 + 2.0 * phi_24 * K4 + phi_44 * K4 * K4) / phi_4
        with np.errstate(invalid="ignore"):        # NaN where the loop does not close
            theta3, K3, L3, u_O2, u_A, u_B, u_O4, coupler = self._coupler(theta2, theta4, K4)
        blank = singular | ~assembled
        K3, K4, L3, L4 = (np.where(blank, np.nan, x) for x in (K3, K4, L3, L4))
        return SphericalFourBarSolution(
            theta2=theta2, theta2_dot=w, theta2_ddot=a, theta3=theta3, theta4=theta4,
            K3=K3, K4=K4, L3=L3, L4=L4, omega3=K3 * w, omega4=K4 * w,
            alpha3=K3 * a + L3 * w**2, alpha4=K4 * a + L4 * w**2,
            u_O2=u_O2, u_A=u_A, u_B=u_B, u_O4=u_O4, coupler=coupler, branch=branch,
            assembled=assembled, singular=singular)

    def _coupler(self, theta2, theta4, K4):
        """θ3, K3, L3, the axes and the coupler's orientation."""
        u_O2, u_A, u_B, u_O4 = self._axes(theta2, theta4)
        # the coupler: angle at A from the crank's arc to the coupler's
        ct, st = np.cos(theta2), np.sin(theta2)
        s_2, c_2 = math.sin(self.alpha2), math.cos(self.alpha2)
        e1 = np.stack([c_2 * ct, c_2 * st, np.full_like(ct, -s_2)], -1)
        e2 = np.stack([-st, ct, np.zeros_like(ct)], -1)
        gamma = np.arctan2(np.einsum("...i,...i->...", u_B, e2),
                           np.einsum("...i,...i->...", u_B, e1))
        cg, sg = np.cos(gamma)[..., None], np.sin(gamma)[..., None]
        x3 = cg * e1 + sg * e2
        coupler = np.stack([x3, np.cross(u_A, x3), u_A], axis=-1)
        theta3 = np.where(np.isnan(gamma), np.nan, wrap_angle(theta2 + np.nan_to_num(gamma)))
        P = _det(u_O2, u_B, u_O4)
        Q = _det(u_A, u_B, u_O4)
        dA = np.cross(u_O2, u_A)
        dB = K4[..., None] * np.cross(u_O4, u_B)
        dP = _det(u_O2, dB, u_O4)
        dQ = _det(dA, u_B, u_O4) + _det(u_A, dB, u_O4)
        with np.errstate(divide="ignore", invalid="ignore"):
            K3 = 1.0 - P / Q
            L3 = -(dP * Q - P * dQ) / (Q * Q)
        return theta3, K3, L3, u_O2, u_A, u_B, u_O4, coupler

    # -- mobility -------------------------------------------------------------------------
    def _span(self) -> tuple[float, float]:
        """cos θ2 must lie in [lo, hi] for the loop to close: ``u_O4 · u_A = sin α1 sin α2
        cos θ2 + cos α1 cos α2`` is the cosine of the arc O4A, which coupler and rocker span
        from |α3 - α4| to α3 + α4 (or 2π - α3 - α4)."""
        a1, a2, a3, a4 = self.arcs
        k = math.sin(a1) * math.sin(a2)
        base = math.cos(a1) * math.cos(a2)
        return (math.cos(a3 + a4) - base) / k, (math.cos(a3 - a4) - base) / k

    def reachable_inputs(self) -> list[tuple[float, float]]:
        """Intervals of θ2 (rad) where the loop closes, both assemblies alike: the whole
        turn ``[(-π, π)]``, one interval about 0 or about π, two intervals symmetric about
        the ground's plane, or none; each end is a limit position of the input.

        Examples
        --------
        >>> m = kl.spatial.SphericalFourBar(alpha1=0.5, alpha2=0.7, alpha3=0.4, alpha4=0.5)
        >>> [tuple(round(x, 6) for x in span) for span in m.reachable_inputs()]
        [(-1.732095, 1.732095)]
        """
        lo, hi = self._span()
        if lo <= -1.0 and hi >= 1.0:
            return [(-math.pi, math.pi)]
        if lo > 1.0 or hi < -1.0:
            return []
        far = math.acos(max(lo, -1.0))            # |θ2| <= far
        near = math.acos(min(hi, 1.0))            # |θ2| >= near
        if hi >= 1.0:
            return [(0.0 - far, far)]
        if lo <= -1.0:
            return [(near, 2.0 * math.pi - near)]
        return [(0.0 - far, 0.0 - near), (near, far)]

    def input_limits(self) -> list[float]:
        """Input angles θ2 (rad, in (-π, π]) where the input cannot go on: coupler and
        rocker in line (A, B and O4 on one great circle), ``∂Φ/∂θ4 = 0``, K unbounded; the
        two assemblies meet there.  In closed form, from ``u_O4 · u_A = cos(α3 ± α4)``.

        Examples
        --------
        >>> m = kl.spatial.SphericalFourBar(alpha1=0.5, alpha2=0.7, alpha3=0.4, alpha4=0.5)
        >>> np.round(m.input_limits(), 6).tolist()
        [-1.732095, 1.732095]
        >>> m.analyze(m.input_limits()).singular
        array([ True,  True])
        """
        ends = sorted({wrap_angle(x) for span in self.reachable_inputs() for x in span
                       if span != (-math.pi, math.pi)})
        return [float(x) for x in ends]

    def output_limits(self, branch: Literal["open", "crossed"] | None = None
                      ) -> list[tuple[float, float]]:
        """Where the rocker stops and turns back: crank and coupler in line (O2, A and B on
        one great circle), so ``K4 = 0``.  In closed form: there ``u_O2 · u_B = cos(α2 ± α3)``
        fixes ``cos θ4``, and A lies on the great circle O2B, α2 from O2.

        Parameters
        ----------
        branch : {"open", "crossed"}, optional
            Default, the four-bar's own.

        Returns
        -------
        list of (θ2, θ4), rad, sorted by θ2
            The input and output angles there, on that assembly.

        Examples
        --------
        >>> m = kl.spatial.SphericalFourBar(alpha1=0.5, alpha2=0.2, alpha3=0.5, alpha4=0.4)
        >>> [(round(t2, 6), round(t4, 6)) for t2, t4 in m.output_limits()]
        [(-2.193864, 2.477586), (0.628427, 1.335831)]
        """
        branch = self.branch if branch is None else branch
        check_choice("branch", branch, BRANCHES)
        a1, a2, a3, a4 = self.arcs
        found = []
        for arc in (a2 + a3, a3 - a2):
            cos4 = (math.cos(a4) * math.cos(a1) - math.cos(arc)) / (math.sin(a4) * math.sin(a1))
            if not -1.0 <= cos4 <= 1.0:
                continue
            for t4 in {math.acos(cos4), -math.acos(cos4)}:
                u_B = self._axes(np.zeros(()), np.asarray(t4))[2]
                azimuth = math.atan2(u_B[1], u_B[0])
                # A on the meridian of B (same azimuth) or on the other half (azimuth + π),
                # whichever keeps the coupler's arc.
                t2 = min((wrap_angle(azimuth + k * math.pi) for k in (0, 1)),
                         key=lambda t: abs(float(self._axes(np.asarray(t), np.asarray(t4))[1]
                                                 @ u_B) - math.cos(a3)))
                sol = self.analyze(t2, branch=branch, unreachable="mask")
                if sol.assembled and abs(wrap_angle(float(sol.theta4) - t4)) < 1e-6:
                    found.append((float(t2), float(wrap_angle(t4))))
        return sorted(set(found))

    def grashof(self, *, rtol: float = 1e-12) -> SphericalGrashof:
        """Classify the linkage by Grashof's criterion on the sphere.

        Reversing an axis moves no link but changes the two arcs that meet there to their
        supplements (Chiang, 1988).  Among the equivalent linkages so obtained, take those
        with the fewest arcs above π/2: none when an even number of the given arcs exceed
        π/2 (one such linkage), one otherwise (four, one for each place of the long arc).
        The linkage is Grashof (some link turns fully relative to the others) when
        ``s + l <= p + q`` holds for one of them, s and l the shortest and longest arcs.

        Which link turns fully relative to which comes from the exact condition: the crank
        turns relative to the ground when the arc O4A it sweeps, from ``|α1 - α2|`` to
        ``α1 + α2`` (or ``2π - α1 - α2``), lies within what coupler and rocker span, and
        likewise for the other pairs.  The two agree (``tests/spatial``).

        Parameters
        ----------
        rtol : float
            ``s + l`` and ``p + q`` are equal (a change point) within ``rtol`` times π.

        Returns
        -------
        SphericalGrashof

        References
        ----------
        C. H. Chiang, *Kinematics of Spherical Mechanisms*, Cambridge University Press, 1988.

        Examples
        --------
        >>> arcs = dict(alpha1=0.5, alpha2=0.2, alpha3=0.5, alpha4=0.4)
        >>> kl.spatial.SphericalFourBar(**arcs).grashof().kind
        'crank-rocker'

        The same linkage with the axis O2 reversed (ground and crank supplemented):

        >>> g = kl.spatial.SphericalFourBar(**{**arcs, "alpha1": np.pi - 0.5,
        ...                                    "alpha2": np.pi - 0.2}).grashof()
        >>> g.kind, g.reversed_axes
        ('crank-rocker', ('O2',))
        >>> kl.spatial.SphericalFourBar(alpha1=0.5, alpha2=0.7, alpha3=0.4,
        ...                             alpha4=0.5).grashof().kind
        'triple-rocker'
        """
        if (isinstance(rtol, bool) or not isinstance(rtol, numbers.Real)
                or not 0.0 <= rtol <= 1e-2):
            raise ModelError(f"rtol: expected a number from 0 to 0.01, got {describe(rtol)}")
        arcs = self.arcs
        names = ("O2", "A", "B", "O4")     # axis k joins link k and link k + 1 (ground = 0)
        candidates = []
        for flips in itertools.product((0, 1), repeat=3):
            flip = (0,) + flips                     # reversing all four axes changes nothing
            # link k (ground, crank, coupler, rocker) runs from axis k - 1 to axis k
            reduced = tuple(math.pi - arcs[k] if flip[k - 1] ^ flip[k] else arcs[k]
                            for k in range(4))
            long = sum(x > math.pi / 2 for x in reduced)
            s = sorted(reduced)
            # reversing a set of axes or the other ones is the same: name the fewer
            named = [n for n, f in zip(names, flip) if f]
            if len(named) > 2:
                named = [n for n in names if n not in named]
            candidates.append((long, -((s[1] + s[2]) - (s[0] + s[3])), reduced, tuple(named)))
        fewest = min(c[0] for c in candidates)
        best = min(c for c in candidates if c[0] == fewest)
        margin, reduced, reversed_axes = -best[1], best[2], best[3]
        tol = rtol * math.pi
        a1, a2, a3, a4 = arcs
        crank = _full_turn(a1, a2, a3, a4)
        rocker = _full_turn(a1, a4, a3, a2)
        coupler = _full_turn(a2, a3, a4, a1) or _full_turn(a4, a3, a2, a1)
        if abs(margin) <= tol:
            kind = "change-point"
        elif crank and rocker:
            kind = "double-crank"
        elif crank:
            kind = "crank-rocker"
        elif rocker:
            kind = "rocker-crank"
        elif coupler:
            kind = "double-rocker"
        else:
            kind = "triple-rocker"
        return SphericalGrashof(kind=kind, grashof=margin >= -tol, crank_rotates=crank,
                                rocker_rotates=rocker, margin=margin, reduced=reduced,
                                reversed_axes=reversed_axes)

    # -- model files ----------------------------------------------------------------------
    @classmethod
    def from_mechanism(cls, mechanism: Mechanism) -> SphericalFourBar:
        """The spherical four-bar of a model with ``space = "spherical"``: four links in one
        loop, one of them the ground, joined by four R joints whose ``axis`` lines (through
        their points) meet in one point, and one input on a joint of the ground.

        The arcs are the angles between the axes as the model gives them (their directions
        count: see :class:`SphericalFourBar`); the crank is the link the input turns, and the
        sketch (the axes of its moving joints) fixes the assembly, ``branch``.  θ2 is
        measured as :class:`SphericalFourBar` says, from the plane of the two fixed axes,
        whatever the model's frame.

        Raises
        ------
        ModelError
            Naming the field, when the model is not such a four-bar.
        """
        if not isinstance(mechanism, Mechanism):
            raise ModelError(f"mechanism: expected a kinelab Mechanism (kl.load reads one "
                             f"from a model file), got {describe(mechanism)}")
        m = mechanism
        if m.space != "spherical":
            raise ModelError(f"space: expected 'spherical' for a spherical four-bar, got "
                             f"{describe(m.space)}")
        if len(m.links) != 4 or len(m.joints) != 4:
            raise ModelError(f"links, joints: expected four links and four R joints, got "
                             f"{len(m.links)} links and {len(m.joints)} joints")
        problems = []
        for i, j in enumerate(m.joints):
            if j.type != "R":
                problems.append(f"joints[{i}].type: expected 'R', got {describe(j.type)}")
            elif j.axis is None or j.point is None:
                problems.append(f"joints[{i}]: a spherical four-bar's R joint needs its point "
                                f"and its axis (three numbers)")
            elif (len(j.axis) != 3 or not all(math.isfinite(c) for c in j.axis)
                  or not any(j.axis)):
                problems.append(f"joints[{i}].axis: expected three finite numbers, not all "
                                f"zero, got {describe(j.axis)}")
        grounds = [lk.name for lk in m.links if lk.ground]
        if len(grounds) != 1:
            problems.append(f"links: expected one ground link, got {len(grounds)}")
        if len(m.inputs) != 1 or m.inputs[0].joint is None:
            problems.append("inputs: expected one input, on the joint between the ground and "
                            "the crank")
        if problems:
            raise ModelError(problems)
        ground = grounds[0]
        joint = {j.name: j for j in m.joints}.get(m.inputs[0].joint)
        if joint is None or ground not in joint.links:
            raise ModelError(f"inputs[0].joint: expected an R joint of the ground "
                             f"{shown(ground)}, got {describe(m.inputs[0].joint)}")
        crank = joint.links[1] if joint.links[0] == ground else joint.links[0]
        order = [ground, crank]
        used = [joint]
        while len(order) < 5:              # walk the loop: ground, crank, coupler, rocker
            nxt = [j for j in m.joints if j not in used and order[-1] in j.links]
            if len(nxt) != 1:
                raise ModelError(f"joints: expected the four links in one loop, each joined "
                                 f"to two others; link {shown(order[-1])} is joined to "
                                 f"{len(nxt) + 1}")
            used.append(nxt[0])
            order.append(nxt[0].links[1] if nxt[0].links[0] == order[-1] else nxt[0].links[0])
        if order[4] != ground or len(set(order[:4])) != 4:
            raise ModelError("joints: expected the four links in one loop")
        points = {p.name: np.array([p.x, p.y, p.z]) for p in m.points}
        axes = [np.asarray(j.axis, float) / np.linalg.norm(j.axis) for j in used]
        bases = [points[j.point] for j in used]
        # the point nearest all four axis lines: Σ (I - u uᵀ)(x - p) = 0
        M = sum(np.eye(3) - np.outer(u, u) for u in axes)
        rhs = sum((np.eye(3) - np.outer(u, u)) @ p for u, p in zip(axes, bases))
        centre = np.linalg.lstsq(M, rhs, rcond=None)[0]
        size = max(1.0, max(float(np.linalg.norm(p - centre)) for p in bases))
        miss = max(float(np.linalg.norm((np.eye(3) - np.outer(u, u)) @ (centre - p)))
                   for u, p in zip(axes, bases))
        if not miss <= _CONCURRENT * size:
            raise ModelError(f"joints: the axes of the four R joints must meet in one point "
                             f"(the sphere's centre), but they miss by {miss:.3g}; give each "
                             f"joint an axis through the centre")
        u_O2, u_A, u_B, u_O4 = axes[0], axes[1], axes[2], axes[3]

        def arc(u, v):
            return math.atan2(float(np.linalg.norm(np.cross(u, v))), float(u @ v))
        arcs = dict(alpha1=arc(u_O2, u_O4), alpha2=arc(u_O2, u_A), alpha3=arc(u_A, u_B),
                    alpha4=arc(u_B, u_O4))
        for name, value in arcs.items():
            if not 0.0 < value < math.pi:
                raise ModelError(f"joints: {name}: two axes lie on one line (arc "
                                 f"{value:.6g} rad); a spherical four-bar needs distinct axes")
        branch = "open" if float(_det(u_A, u_O4, u_B)) >= 0.0 else "crossed"
        return cls(**arcs, branch=branch)


    def to_mechanism(self, theta2: float | None = None, *, radius: float = 1.0,
                     name: str = "spherical four-bar",
                     input_range: tuple[float, float] | None = None, speed: float = 0.0,
                     acceleration: float = 0.0) -> Mechanism:
        """The linkage as a model with ``space = "spherical"`` (what :meth:`from_mechanism`
        reads back): links ``ground, crank, coupler, rocker``, points ``O2, A, B, O4`` at
        ``radius`` along each axis from the sphere's centre (the origin), R joints ``jO2,
        jA, jB, jO4`` with their axes, and the input on ``jO2``.

        Parameters
        ----------
        theta2 : float, optional
            The input angle of the sketch, rad; default 0 if the loop closes there, else the
            middle of the first reachable interval.
        radius : float
            Radius of the sphere the points lie on, m.
        name : str
        input_range : (float, float), optional
            The input's range, rad.
        speed, acceleration : float
            The input's speed (rad/s) and acceleration (rad/s²).

        Examples
        --------
        >>> m = kl.spatial.SphericalFourBar(alpha1=1.2, alpha2=0.4, alpha3=1.1, alpha4=0.9,
        ...                                 branch="crossed")
        >>> back = kl.spatial.SphericalFourBar.from_mechanism(m.to_mechanism())
        >>> np.allclose(back.arcs, m.arcs, rtol=0, atol=1e-14), back.branch
        (True, 'crossed')
        """
        from kinelab.model import Input, Joint, Link, Point

        reach = self.reachable_inputs()
        if not reach:
            raise AssemblyError("spherical four-bar: the loop closes at no input angle; no "
                                "sketch can be drawn", loop="O2-A-B-O4", gap=math.nan,
                                reachable=[])
        if theta2 is None:
            theta2 = 0.0 if bool(self.positions(0.0).assembled) else 0.5 * sum(reach[0])
        sol = self.analyze(theta2)
        names = ("O2", "A", "B", "O4")
        axes = [np.asarray(x, float) for x in (sol.u_O2, sol.u_A, sol.u_B, sol.u_O4)]
        points = tuple(Point(n, *(float(radius) * u)) for n, u in zip(names, axes))
        links = (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
                 Link("coupler", ("A", "B")), Link("rocker", ("B", "O4")))
        pairs = (("ground", "crank"), ("crank", "coupler"), ("coupler", "rocker"),
                 ("rocker", "ground"))
        joints = tuple(Joint(f"j{n}", "R", pair, point=n, axis=tuple(float(c) for c in u))
                       for n, pair, u in zip(names, pairs, axes))
        return Mechanism(name, points, links, joints,
                         inputs=(Input(joint="jO2", range=input_range, speed=speed,
                                       acceleration=acceleration),), space="spherical")


def _spans(reach: list[tuple[float, float]]) -> str:
    return " ∪ ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in reach) or "empty"
