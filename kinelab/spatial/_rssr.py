"""The RSSR spatial four-bar (*Mecanismos*, §7.3): input-output equation, velocity,
acceleration, and where its two branches meet (limit positions) or cross (change points)."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError, SingularityError, check_choice, describe
from kinelab.solvers import wrap_angle
from kinelab.spatial._branches import through_change_point
from kinelab.spatial._common import as_angles, as_array, as_length, indices, rate, together

__all__ = ["RSSR", "RSSRPositions", "RSSRSolution"]

# Dimensionless tolerances.
# _MEETS: |G| within this (relative to the mechanism's size², H1² + H3² + L3² + (L1 - L0)²
# + L2²) of the reach 2 r3 |L1 - L0| at θ1 = ±π/2 is a crossing geometry (of the reach
# 2 r3 sqrt((L1 - L0)² + H1²) at θ1 = 0, a loop that closes only at 0 and π).  Rounding of
# the dimensions leaves a few 1e-16; a mechanism farther from it is another mechanism, with
# two limit positions a gap apart near ±π/2 or with branches that pass close by.
_MEETS = 1e-12
# _TANGENT: the discriminant D = m0 + k cos² θ1 this small relative to |m0| + k |cos θ1|
# (which bounds its rounding, the rounding of cos θ1 at an input given near a limit
# position included) is zero: the two branches meet there.
_TANGENT = 1e-14


class _Layout(NamedTuple):
    """One RSSR's discriminant ``D(θ1) = E² + F² - G² = m0 + k cos² θ1``."""

    d: float          # L1 - L0, m
    crank: float      # 4 (H3² + L3²), m²
    G: float          # G, or the crossing (isolated) value it rounds to, m²
    k: float          # 4 (H3² + L3²) H1², m⁴
    m0: float         # 4 (H3² + L3²)(L1 - L0)² - G², m⁴: D at θ1 = ±π/2
    crossing: bool    # m0 = 0 < k: the branches cross at θ1 = ±π/2
    isolated: bool    # m0 = -k < 0: the loop closes only at θ1 = 0 and π


class _Roots(NamedTuple):
    positions: RSSRPositions
    c1: np.ndarray
    s1: np.ndarray
    D: np.ndarray         # the discriminant, 0 where the branches meet, m⁴
    meet: np.ndarray      # D = 0


@dataclass(frozen=True)
class RSSRPositions:
    """Both output angles of an RSSR for each input angle, and why they exist.

    Attributes
    ----------
    theta1 : ndarray, shape () or (N,), rad
    E, F, G : ndarray, shape () or (N,)
        The coefficients of ``E cos θ3 + F sin θ3 + G = 0`` (*Mecanismos*, eq. 74), m².
    theta3 : ndarray, shape (2,) or (N, 2), rad in (-π, π]
        Column 0 branch ``+1`` (``∂Φ/∂θ3 > 0``), column 1 branch ``-1`` (see
        :class:`RSSR`).  Both hold the single solution where the branches meet, and the
        closest approach where there is none: read them only where ``feasible``.  Through
        a change point a branch passes from one column to the other.
    feasible : ndarray of bool, shape () or (N,)
        ``E² + F² >= G²``: the coupler can close the loop at this input.
    gap : ndarray, shape () or (N,), m²
        ``|G| - sqrt(E² + F²)`` where infeasible (by how much the loop misses), else 0.
    A : ndarray, shape (3,) or (N, 3), m
        Centre of the ball joint on the input crank.
    B : ndarray, shape (2, 3) or (N, 2, 3), m
        Centre of the ball joint on the output crank, on each branch.
    """

    theta1: np.ndarray
    E: np.ndarray
    F: np.ndarray
    G: np.ndarray
    theta3: np.ndarray
    feasible: np.ndarray
    gap: np.ndarray
    A: np.ndarray
    B: np.ndarray


@dataclass(frozen=True)
class RSSRSolution:
    """Output motion of an RSSR along one branch.

    Attributes
    ----------
    theta1, theta1_dot, theta1_ddot : ndarray, shape () or (N,)
        Input angle (rad), speed (rad/s) and acceleration (rad/s²).
    theta3, theta3_dot, theta3_ddot : ndarray, shape () or (N,)
        Output angle, speed and acceleration.
    K : ndarray, shape () or (N,)
        Velocity coefficient ``dθ3/dθ1 = -Φ_θ1 / Φ_θ3``; at a change point, its limit along
        the branch followed.
    L : ndarray, shape () or (N,)
        Acceleration coefficient ``dK/dθ1``: ``θ̈3 = K θ̈1 + L θ̇1²``; at a change point, its
        limit along the branch followed.
    branch : int
        ``+1`` or ``-1``: the branch at θ1 = 0 (see :class:`RSSR`).
    change_point : ndarray of bool, shape () or (N,)
        The sample is at a change point, where the two branches cross.
    """

    theta1: np.ndarray
    theta1_dot: np.ndarray
    theta1_ddot: np.ndarray
    theta3: np.ndarray
    theta3_dot: np.ndarray
    theta3_ddot: np.ndarray
    K: np.ndarray
    L: np.ndarray
    branch: int
    change_point: np.ndarray


@dataclass(frozen=True, kw_only=True)
class RSSR:
    """The RSSR mechanism of *Mecanismos*, §7.3 (Fig. 58).

    Geometry (all in the ground frame ``O x0 y0 z0``, m):

    - the input crank (link 1) turns by θ1 about the y0 axis through O; its ball-joint
      centre is ``1_r_A = (0, L1, H1)``, so ``A = (H1 sin θ1, L1, H1 cos θ1)``;
    - the output crank (link 3) turns by θ3 about a line parallel to x0 through
      ``(·, L0, 0)``; ``3_r_B = (D3, -L3, H3)`` with ``0_T_3 = Trans(-D3, L0, 0) Rot(x, θ3)``, so
      ``B = (0, L0 - L3 cos θ3 - H3 sin θ3, H3 cos θ3 - L3 sin θ3)`` (D3 cancels);
    - the coupler (link 2) keeps ``|A - B| = L2`` (its spin about AB is idle).

    Expanding ``|A - B|² = L2²`` gives ``Φ = E cos θ3 + F sin θ3 + G = 0`` with
    ``E = 2[(L1 - L0) L3 - H1 H3 cos θ1]``, ``F = 2[(L1 - L0) H3 + H1 L3 cos θ1]``,
    ``G = H1² + H3² + (L1 - L0)² + L3² - L2²`` (eq. 74; checked, as printed).

    **Feasibility.**  Real output angles exist where ``D = E² + F² - G² >= 0``.  Here
    ``E² + F² = 4 (L3² + H3²) ((L1 - L0)² + H1² cos² θ1)``, so
    ``D = m0 + k cos² θ1`` with ``k = 4 (L3² + H3²) H1²`` and ``m0 = 4 (L3² + H3²)(L1 - L0)²
    - G²`` (D at θ1 = ±90°): the input range is symmetric about θ1 = 0 and θ1 = π, and
    :meth:`reachable_inputs` gives it.  Where two solutions exist they are the two ways to
    assemble the loop, named by ``branch``: ``+1`` where ``Φ_θ3 = ∂Φ/∂θ3 = F cos θ3 -
    E sin θ3 > 0`` (turning the output crank forward pulls B away from A), ``-1`` where it
    is negative.

    **Where the branches meet** (``D = 0``, so ``Φ_θ3 = 0``), ``Φ_θ1 = ∂Φ/∂θ1`` tells two
    different things apart:

    - a **limit position** (a fold), where ``Φ_θ1 ≠ 0``: the input cannot go on (it is at
      the end of its reachable range) and the output speed ``K θ̇1`` is unbounded;
    - a **change point**, where ``Φ_θ1 = 0`` too (the row ``[Φ_θ1 Φ_θ3]`` loses rank): the
      two branches cross, and the input goes on along either of them with finite K.
      Since ``Φ_θ1 = -G D' / (2 (E² + F²))`` there and ``D' = -2 k cos θ1 sin θ1``, this
      happens at θ1 = ±90° when ``m0 = 0``, that is ``|G| = 2 r3 |L1 - L0|`` with
      ``r3 = sqrt(H3² + L3²)``, or ``L2² = H1² + (L1 - L0 ± r3)²``: one assembly puts B on
      the input axis, where |AB| does not change as the input turns, so that branch is
      θ3 = const, and the other one crosses it at θ1 = ±90°.  The whole turn is then
      reachable (:meth:`change_points`).  *Mecanismos*' example is one.
      (At θ1 = 0 and π, ``D' = 0`` where the loop closes only there: an isolated
      configuration, from which the mechanism cannot move.)

    A branch that goes smoothly through a change point changes the sign of ``Φ_θ3``, so
    ``branch`` names the branch at θ1 = 0 (and wherever it is reached from there without a
    change point), and :meth:`analyze` follows it through change points as
    ``at_change_point`` says.

    (Where ``Φ_θ1 = 0`` but ``Φ_θ3 ≠ 0``, K = 0: the output stands still for a moment; driven
    from the output, the input crank is at a dead centre there, as in the example at
    θ1 = 0 on branch -1.)

    Parameters
    ----------
    H1, L1 : float
        Input crank: radius and offset along its axis, m.
    L0 : float
        Offset of the output axis from O along y0, m.
    L2 : float
        Coupler length, m (> 0).
    H3, L3 : float
        Output crank: the two components of B in its frame, m (not both zero).

    Examples
    --------
    *Mecanismos*, §7.3: θ1 = 0, H1 = H3 = 1, L1 = L3 = 0, L0 = L2 = 1 gives E = F = -2, G = 2,
    so θ3 = 0° or 90°:

    >>> m = kl.spatial.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)
    >>> pos = m.positions(0.0)
    >>> float(pos.E), float(pos.F), float(pos.G)
    (-2.0, -2.0, 2.0)
    >>> np.degrees(pos.theta3).round(9) + 0.0
    array([90.,  0.])

    At θ3 = 90° the ball joint B would sit at O, on the input shaft itself: that assembly
    is geometrically possible but physically not, which is why the notes keep θ3 = 0°
    (``branch=-1``):

    >>> pos.B.round(12) + 0.0
    array([[0., 0., 0.],
           [0., 1., 1.]])

    Here ``|G| = 2 = 2 r3 |L1 - L0|``: the branches cross at θ1 = ±90°, and the input turns
    fully:

    >>> np.degrees(m.change_points()).tolist(), m.reachable_inputs()
    ([-90.0, 90.0], [(-3.141592653589793, 3.141592653589793)])
    """

    H1: float
    L1: float
    L0: float
    L2: float
    H3: float
    L3: float

    def __post_init__(self):
        for name in ("H1", "L1", "L0", "H3", "L3"):
            object.__setattr__(self, name, as_length(name, getattr(self, name)))
        object.__setattr__(self, "L2", as_length("L2", self.L2, positive=True))
        if self.H3 == 0.0 and self.L3 == 0.0:
            raise ModelError("H3, L3: the output crank has zero length (B on its axis); give "
                             "B an offset from the output axis")
        lay = self._layout()
        if lay.k == 0.0 and lay.d == 0.0 and lay.G == 0.0:
            raise ModelError("H1, L1, L0, L2: A stays at the centre of B's circle (H1 = 0, "
                             "L1 = L0, L2² = H3² + L3²), so every θ3 closes the loop and the "
                             "input does not drive the output; change one of them")

    # -- position -------------------------------------------------------------------------
    def _layout(self) -> _Layout:
        d = self.L1 - self.L0
        r3 = math.hypot(self.H3, self.L3)
        crank = 4.0 * r3 * r3
        G = self.H1**2 + self.H3**2 + d**2 + self.L3**2 - self.L2**2
        k = crank * self.H1**2
        tol = _MEETS * (self.H1**2 + r3 * r3 + d * d + self.L2**2)
        low, high = 2.0 * r3 * abs(d), 2.0 * r3 * math.hypot(d, self.H1)
        if abs(abs(G) - low) <= tol:            # D(±π/2) = 0: cross there (H1 = 0: always)
            return _Layout(d, crank, math.copysign(low, G), k, 0.0, k > 0.0, False)
        if abs(abs(G) - high) <= tol:           # D(0) = D(π) = 0 and D < 0 elsewhere
            return _Layout(d, crank, math.copysign(high, G), k, -k, False, True)
        return _Layout(d, crank, G, k, crank * d * d - G * G, False, False)

    def _roots(self, theta1: np.ndarray) -> _Roots:
        lay = self._layout()
        c1, s1 = np.cos(theta1), np.sin(theta1)
        E = np.asarray(2.0 * (lay.d * self.L3 - self.H1 * self.H3 * c1))
        F = np.asarray(2.0 * (lay.d * self.H3 + self.H1 * self.L3 * c1))
        G = np.full_like(E, self.H1**2 + self.H3**2 + lay.d**2 + self.L3**2 - self.L2**2)
        R2 = lay.crank * (lay.d**2 + self.H1**2 * c1 * c1)         # E² + F², no cancellation
        # The roots of eq. 74 are θ3 = atan2(F, E) ∓ acos(-G / sqrt(E² + F²)), those of the
        # half-angle method (§4.5); written with the discriminant in closed form, which is
        # exact where the branches cross, instead of from E, F, G (rounding would leave it a
        # few 1e-16 off there, and the roots 1e-8 apart).
        D = lay.m0 + lay.k * c1 * c1
        meet = np.abs(D) <= _TANGENT * (abs(lay.m0) + lay.k * np.abs(c1))
        if not lay.crossing:         # there D = k c1² has no rounding to remove, and keeps
            D = np.where(meet, 0.0, D)   # the roots' limits where E = F = G = 0 (every θ3)
        feasible = D >= 0.0
        root = np.sqrt(np.maximum(D, 0.0))
        psi = np.arctan2(F, E)
        beta = np.arctan2(root, 0.0 - lay.G)   # 0 or π where there is no root: the closest
        theta3 = wrap_angle(np.stack([psi - beta, psi + beta], axis=-1))
        gap = np.where(feasible, 0.0, -D / (np.sqrt(R2) + abs(lay.G)))
        A = np.stack([self.H1 * s1, np.full_like(theta1, self.L1), self.H1 * c1], axis=-1)
        pos = RSSRPositions(theta1=theta1, E=E, F=F, G=G, theta3=theta3, feasible=feasible,
                            gap=gap, A=A, B=self._B(theta3))
        return _Roots(pos, c1, s1, D, meet & feasible)

    def positions(self, theta1: ArrayLike) -> RSSRPositions:
        """Both output angles θ3 for each input angle θ1 (never raises on an infeasible
        input: see ``feasible``).

        Parameters
        ----------
        theta1 : float or array_like, shape () or (N,)
            rad.

        Returns
        -------
        RSSRPositions
        """
        return self._roots(as_angles("theta1", theta1)).positions

    def _B(self, theta3: np.ndarray) -> np.ndarray:
        c3, s3 = np.cos(theta3), np.sin(theta3)
        return np.stack([np.zeros_like(c3), self.L0 - self.L3 * c3 - self.H3 * s3,
                         self.H3 * c3 - self.L3 * s3], axis=-1)

    def reachable_inputs(self) -> list[tuple[float, float]]:
        """Intervals of θ1 (rad) where the loop closes, both branches alike.

        From ``D = m0 + k cos² θ1 >= 0`` (see :class:`RSSR`): the whole turn ``[(-π, π)]``,
        nothing ``[]``, or ``|cos θ1| >= c``, two intervals ``(-a, a)`` and
        ``(π - a, π + a)`` with ``a = arccos c``, ended by limit positions.  Change points
        do not end an interval: the input goes on through them.

        Examples
        --------
        >>> kl.spatial.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0).reachable_inputs()
        [(-3.141592653589793, 3.141592653589793)]
        """
        lay = self._layout()
        if lay.k == 0.0:
            return [(-np.pi, np.pi)] if lay.m0 >= 0.0 else []
        kappa = -lay.m0 / lay.k                              # needed cos² θ1
        if kappa <= 0.0:
            return [(-np.pi, np.pi)]
        if kappa > 1.0:
            return []
        a = float(np.arccos(np.sqrt(kappa)))
        return [(0.0 - a, a), (np.pi - a, np.pi + a)]       # 0.0 - a: no "-0" when a = 0

    def change_points(self) -> list[float]:
        """Inputs θ1 in (-π, π] (rad) where the two branches cross: ``[-π/2, π/2]`` when
        ``|G| = 2 r3 |L1 - L0|`` (see :class:`RSSR`), else none.

        Examples
        --------
        >>> kl.spatial.RSSR(H1=1.0, L1=0.0, L0=0.5, L2=0.8, H3=0.6, L3=0.2).change_points()
        []
        """
        return [-np.pi / 2, np.pi / 2] if self._layout().crossing else []

    # -- motion ---------------------------------------------------------------------------
    def analyze(self, theta1: ArrayLike, theta1_dot: ArrayLike = 0.0,
                theta1_ddot: ArrayLike = 0.0, *, branch: Literal[1, -1] = 1,
                at_change_point: Literal["smooth", "switch"] = "smooth") -> RSSRSolution:
        """Output angle, speed and acceleration along one branch.

        Write eq. 74 as ``Φ = R cos(θ3 - ψ) + G`` with ``R² = E² + F²`` and
        ``ψ = atan2(F, E)``: ``θ3 = ψ ∓ β``, ``cos β = -G / R``, ``sin β = sqrt(D) / R``.
        Then ``K = -Φ_θ1 / Φ_θ3 = ψ' ∓ β'`` and ``L = dK/dθ1 = ψ'' ∓ β''`` (``'`` is d/dθ1),
        with ``β' = G k cos θ1 sin θ1 / (R² sqrt(D))`` and ``β''`` its derivative, written
        without the cancellations that ``-(Φ_θ1θ1 + 2 Φ_θ1θ3 K + Φ_θ3θ3 K²) / Φ_θ3`` suffers
        near a change point.

        At a change point ``Φ_θ1 = Φ_θ3 = 0``; along a branch through it,
        ``θ3 = θ3c + K δ + L δ²/2 + …`` (``δ = θ1 - θ1c``), and ``Φ = 0`` order by order gives

        - δ²: ``½ Φ_θ3θ3 K² + Φ_θ1θ3 K + ½ Φ_θ1θ1 = 0``, a quadratic whose two roots are the
          K of the two branches;
        - δ³: ``L = -(Φ_111 + 3 Φ_113 K + 3 Φ_133 K² + Φ_333 K³) / (3 (Φ_θ1θ3 + Φ_θ3θ3 K))``
          (indices 1 = θ1, 3 = θ3).

        Along a branch, ``Φ_θ3 ≈ (Φ_θ1θ3 + Φ_θ3θ3 K) δ``: the root followed is the one whose
        ``Φ_θ1θ3 + Φ_θ3θ3 K`` has the sign of the branch just past the change point.

        Parameters
        ----------
        theta1 : float or array_like, shape () or (N,)
            rad.
        theta1_dot, theta1_ddot : float or array_like, broadcast to ``theta1``
            rad/s, rad/s².
        branch : {1, -1}
            The branch at θ1 = 0: the sign of ``Φ_θ3`` there (see :class:`RSSR`).  Without
            change points it keeps that sign everywhere.
        at_change_point : {"smooth", "switch"}
            Where the branches cross (θ1 = ±90°, :meth:`change_points`), go on along the
            branch whose K and L continue ("smooth", so past ±90° the sign of ``Φ_θ3`` is
            ``-branch``), or along the other one ("switch": the sign of ``Φ_θ3`` stays
            ``branch``).  The branch at each input depends only on the input (mod 2π), not
            on the other samples; at the change point itself, K and L are those of the
            branch followed past it (towards larger θ1).

        Returns
        -------
        RSSRSolution

        Raises
        ------
        AssemblyError
            Where the loop cannot close; the message gives the reachable input range.
        SingularityError
            At a limit position (the message gives the reachable input range, which it
            ends), or at an isolated configuration (a loop that closes only at θ1 = 0 and π).

        Examples
        --------
        >>> m = kl.spatial.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)
        >>> sol = m.analyze([0.0, 0.5], theta1_dot=1.0, branch=-1)
        >>> sol.theta3.round(12) + 0.0, sol.K.round(12) + 0.0
        (array([0.        , 0.13021469]), array([0.        , 0.54167751]))

        Through the change points at ±90°, K stays finite (±2 there):

        >>> sol = m.analyze(np.radians([-135.0, -90.0, 90.0, 135.0]), branch=-1)
        >>> np.degrees(sol.theta3).round(6) + 0.0
        array([160.528779,  90.      ,  90.      , 160.528779])
        >>> sol.K.round(6) + 0.0, sol.change_point
        (array([-0.942809, -2.      ,  2.      ,  0.942809]), array([False,  True,  True, False]))
        """
        if isinstance(branch, bool):       # True == 1, but it is not a branch's name
            raise ModelError(f"branch: expected one of 1, -1, got {describe(branch)}")
        check_choice("branch", branch, (1, -1))
        check_choice("at_change_point", at_change_point, ("smooth", "switch"))
        w = as_array("theta1_dot", theta1_dot, limit=rate("rad/s"))
        a = as_array("theta1_ddot", theta1_ddot, limit=rate("rad/s^2"))
        theta1 = as_angles("theta1", theta1)
        theta1, w, a = together(("theta1", theta1, 0), ("theta1_dot", w, 0),
                                ("theta1_ddot", a, 0))
        roots = self._roots(theta1)
        pos, c1, s1 = roots.positions, roots.c1, roots.s1
        theta1 = pos.theta1
        if not pos.feasible.all():
            bad = ~np.atleast_1d(pos.feasible)
            first = float(np.atleast_1d(theta1)[bad][0])
            reach = self.reachable_inputs()
            raise AssemblyError(
                f"RSSR: the loop cannot close at θ1 = {first:.6g} rad (sample(s) "
                f"{indices(bad)}): the coupler L2 = {self.L2:.6g} m cannot join A and B; "
                f"reachable θ1 is {_spans(reach)} rad; narrow the input range",
                loop="A-B (coupler)", gap=float(np.max(pos.gap)), reachable=reach)
        lay = self._layout()
        change = roots.meet & lay.crossing
        if lay.k > 0.0:
            self._refuse_folds(theta1, roots.meet & ~change, lay)
        # The sign of Φ_θ3 on the branch followed: past the change points at ±π/2 (seen
        # from θ1 = 0, where cos θ1 < 0) a smooth branch has the other one.  At a change
        # point, θ3, K and L are those of the branch followed past it towards larger θ1,
        # with the sign `ahead`; the sample may lie (by rounding) on either side of it, and
        # the branch has the sign -ahead on the side before it.
        smooth = at_change_point == "smooth"
        sign = np.where(lay.crossing & (c1 < 0.0) & smooth, -branch, branch)
        ahead = np.where((s1 > 0.0) & smooth, -branch, branch)
        sign = np.where(change, np.where(c1 * s1 < 0.0, ahead, -ahead), sign)
        theta3 = np.where(sign == 1, pos.theta3[..., 0], pos.theta3[..., 1])
        K, L = self._rates(lay, c1, s1, roots.D, -sign, change)
        if change.any():
            K, L = np.array(K), np.array(L)
            K[change], L[change] = self._through(pos.E[change], pos.F[change], c1[change],
                                                 s1[change], theta3[change], ahead[change])
        return RSSRSolution(theta1=theta1, theta1_dot=w, theta1_ddot=a, theta3=theta3,
                            theta3_dot=K * w, theta3_ddot=K * a + L * w**2, K=K, L=L,
                            branch=branch, change_point=change)

    def _refuse_folds(self, theta1, fold, lay: _Layout) -> None:
        """Raise at the samples where the branches meet and the input cannot go on."""
        if not fold.any():
            return
        at = np.atleast_1d(fold)
        first = float(np.atleast_1d(theta1)[at][0])
        reach = self.reachable_inputs()
        if lay.isolated:
            raise SingularityError(
                f"RSSR: θ1 = {first:.6g} rad (sample(s) {indices(at)}) is an isolated "
                f"configuration: the loop closes only at θ1 = 0 and π (the coupler L2 = "
                f"{self.L2:.6g} m just joins A and B there), so the mechanism cannot move; "
                f"change a dimension")
        raise SingularityError(
            f"RSSR: θ1 = {first:.6g} rad (sample(s) {indices(at)}) is a limit position: the "
            f"two branches meet there (∂Φ/∂θ3 = 0) and the input cannot go on (∂Φ/∂θ1 ≠ 0), "
            f"so the output speed is unbounded; reachable θ1 is {_spans(reach)} rad; keep θ1 "
            f"strictly inside it")

    def _rates(self, lay: _Layout, c1, s1, D, s, change):
        """K = ψ' + s β' and L = ψ'' + s β'' where the branches do not meet (s = ±1: the
        sign of β in θ3 = ψ + s β)."""
        if lay.k == 0.0:                   # H1 = 0: A stays on the input axis
            return np.zeros_like(c1), np.zeros_like(c1)
        d, H1, G, k = lay.d, self.H1, lay.G, lay.k
        rho2 = d * d + H1 * H1 * c1 * c1                 # R² = crank ρ²
        R2 = lay.crank * rho2
        with np.errstate(divide="ignore", invalid="ignore"):   # change points: see _through
            psi_1 = -d * H1 * s1 / rho2
            psi_2 = -d * H1 * c1 * (rho2 + 2.0 * H1 * H1 * s1 * s1) / (rho2 * rho2)
            root = np.sqrt(D)
            beta_1 = G * k * c1 * s1 / (R2 * root)
            # d/dθ1 of β' = -G D' / (2 R² sqrt(D)), with D D'' - D'²/2 = -2k (m0 cos 2θ1 +
            # k c1⁴) in closed form: no difference of two large terms near a change point.
            beta_2 = (G * k * (lay.m0 * (c1 - s1) * (c1 + s1) + k * c1**4) / (R2 * D * root)
                      + 2.0 * G * k * k * (c1 * s1)**2 / (R2 * R2 * root))
        K = np.where(change, 0.0, psi_1 + s * beta_1)
        L = np.where(change, 0.0, psi_2 + s * beta_2)
        return K, L

    def _through(self, E, F, c1, s1, theta3, sign):
        """K and L at change points, from the expansion of Φ about them (see
        :mod:`kinelab.spatial._branches`); ``sign``: the sign of Φ_θ3 on the branch followed
        just past the change point."""
        e1, f1 = -2.0 * self.H1 * self.H3, 2.0 * self.H1 * self.L3      # E = e0 + e1 cos θ1
        E1, F1 = -e1 * s1, -f1 * s1                                        # d/dθ1, …
        E2, F2 = -e1 * c1, -f1 * c1
        E3, F3 = e1 * s1, f1 * s1
        c3, s3 = np.cos(theta3), np.sin(theta3)
        phi_1, phi_3 = E1 * c3 + F1 * s3, F * c3 - E * s3                 # both ~0 here
        return through_change_point(E2 * c3 + F2 * s3, F1 * c3 - E1 * s3, -E * c3 - F * s3,
                                    E3 * c3 + F3 * s3, F2 * c3 - E2 * s3, -phi_1, -phi_3, sign)


def _spans(reach: list[tuple[float, float]]) -> str:
    """Reachable intervals as a message shows them."""
    return " ∪ ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in reach) or "empty"
