"""The RSSR spatial four-bar (*Mecanismos*, §7.3): input-output equation, velocity,
acceleration."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError, SingularityError, check_choice, describe
from kinelab.spatial._common import as_angles, as_array, as_length, indices, rate, together
from kinelab.solvers import half_angle

__all__ = ["RSSR", "RSSRPositions", "RSSRSolution"]


@dataclass(frozen=True)
class RSSRPositions:
    """Both output angles of an RSSR for each input angle, and why they exist.

    Attributes
    ----------
    theta1 : ndarray, shape () or (N,), rad
    E, F, G : ndarray, shape () or (N,)
        The coefficients of ``E cos θ3 + F sin θ3 + G = 0`` (*Mecanismos*, eq. 74), m².
    theta3 : ndarray, shape (2,) or (N, 2), rad in (-π, π]
        Column 0 branch ``+1``, column 1 branch ``-1`` (see :class:`RSSR`).  Both hold
        the single solution where the branches meet, and the closest approach where
        there is none: read them only where ``feasible``.
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
    """Output motion of an RSSR on one branch.

    Attributes
    ----------
    theta1, theta1_dot, theta1_ddot : ndarray, shape () or (N,)
        Input angle (rad), speed (rad/s) and acceleration (rad/s²).
    theta3, theta3_dot, theta3_ddot : ndarray, shape () or (N,)
        Output angle, speed and acceleration.
    K : ndarray, shape () or (N,)
        Velocity coefficient ``dθ3/dθ1 = -Φ_θ1 / Φ_θ3``.
    L : ndarray, shape () or (N,)
        Acceleration coefficient ``dK/dθ1``: ``θ̈3 = K θ̈1 + L θ̇1²``.
    branch : int
        ``+1`` or ``-1``.
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

    Expanding ``|A - B|² = L2²`` gives ``E cos θ3 + F sin θ3 + G = 0`` with
    ``E = 2[(L1 - L0) L3 - H1 H3 cos θ1]``, ``F = 2[(L1 - L0) H3 + H1 L3 cos θ1]``,
    ``G = H1² + H3² + (L1 - L0)² + L3² - L2²`` (eq. 74; checked, as printed).

    **Feasibility.**  Real output angles exist where ``E² + F² >= G²``.  Here
    ``E² + F² = 4 (L3² + H3²) ((L1 - L0)² + H1² cos² θ1)``, so the input range is
    symmetric about θ1 = 0 and θ1 = π; :meth:`reachable_inputs` gives it.  Where two
    solutions exist they are the two ways to assemble the loop; which one a real
    mechanism uses is fixed by how it was built (and the mechanism stays on it, since
    the branches meet only at the edge of the input range), so it is chosen here with
    ``branch``: ``+1`` where ``∂Φ/∂θ3 = F cos θ3 - E sin θ3 > 0`` (turning the output
    crank forward pulls B away from A), ``-1`` where it is negative.  Where the branches
    meet (``∂Φ/∂θ3 = 0``) the output speed is unbounded for a moving input: a singular
    (dead) position.

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

    # -- position -------------------------------------------------------------------------
    def _coefficients(self, theta1: np.ndarray):
        d = self.L1 - self.L0
        c1 = np.cos(theta1)
        E = np.asarray(2.0 * (d * self.L3 - self.H1 * self.H3 * c1))
        F = np.asarray(2.0 * (d * self.H3 + self.H1 * self.L3 * c1))
        G = np.full_like(E, self.H1**2 + self.H3**2 + d**2 + self.L3**2 - self.L2**2)
        return E, F, G

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
        theta1 = as_angles("theta1", theta1)
        E, F, G = self._coefficients(theta1)
        _roots = half_angle(E, F, G)
        theta3, count, gap = _roots.theta, _roots.count, _roots.gap
        A = np.stack([self.H1 * np.sin(theta1), np.full_like(theta1, self.L1),
                      self.H1 * np.cos(theta1)], axis=-1)
        return RSSRPositions(theta1=theta1, E=E, F=F, G=G, theta3=theta3, feasible=count > 0,
                             gap=gap, A=A, B=self._B(theta3))

    def _B(self, theta3: np.ndarray) -> np.ndarray:
        c3, s3 = np.cos(theta3), np.sin(theta3)
        return np.stack([np.zeros_like(c3), self.L0 - self.L3 * c3 - self.H3 * s3,
                         self.H3 * c3 - self.L3 * s3], axis=-1)

    def reachable_inputs(self) -> list[tuple[float, float]]:
        """Intervals of θ1 (rad) where the loop closes.

        From ``E² + F² - G² = 4 (L3² + H3²)((L1 - L0)² + H1² cos² θ1) - G² >= 0``: the
        whole turn ``[(-π, π)]``, nothing ``[]``, or ``|cos θ1| >= c``, two intervals
        ``(-a, a)`` and ``(π - a, π + a)`` with ``a = arccos c``.

        Examples
        --------
        >>> kl.spatial.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0).reachable_inputs()
        [(-3.141592653589793, 3.141592653589793)]
        """
        G = self._coefficients(np.zeros(1))[2][0]
        crank = 4.0 * (self.L3**2 + self.H3**2)
        d2 = (self.L1 - self.L0) ** 2
        if self.H1 == 0.0:
            return [(-np.pi, np.pi)] if crank * d2 >= G * G else []
        kappa = (G * G / crank - d2) / self.H1**2           # needed cos² θ1
        if kappa <= 0.0:
            return [(-np.pi, np.pi)]
        if kappa > 1.0:
            return []
        a = float(np.arccos(np.sqrt(kappa)))
        return [(-a, a), (np.pi - a, np.pi + a)]

    # -- motion ---------------------------------------------------------------------------
    def analyze(self, theta1: ArrayLike, theta1_dot: ArrayLike = 0.0,
                theta1_ddot: ArrayLike = 0.0, *, branch: Literal[1, -1] = 1) -> RSSRSolution:
        """Output angle, speed and acceleration on one branch.

        With ``Φ(θ1, θ3) = E cos θ3 + F sin θ3 + G``: ``K = -Φ_1 / Φ_3`` and
        ``L = -(Φ_11 + 2 Φ_13 K + Φ_33 K²) / Φ_3`` (differentiating ``Φ = 0`` once and twice
        along the motion), where ``Φ_1 = E' cos θ3 + F' sin θ3``, ``Φ_3 = F cos θ3 -
        E sin θ3``, ``E' = 2 H1 H3 sin θ1`` and ``F' = -2 H1 L3 sin θ1``.

        Parameters
        ----------
        theta1 : float or array_like, shape () or (N,)
            rad.
        theta1_dot, theta1_ddot : float or array_like, broadcast to ``theta1``
            rad/s, rad/s².
        branch : {1, -1}

        Returns
        -------
        RSSRSolution

        Raises
        ------
        AssemblyError
            Where the loop cannot close; the message gives the reachable input range.
        SingularityError
            Exactly where the two branches meet (Φ_3 = 0).

        Examples
        --------
        >>> m = kl.spatial.RSSR(H1=1.0, L1=0.0, L0=1.0, L2=1.0, H3=1.0, L3=0.0)
        >>> sol = m.analyze([0.0, 0.5], theta1_dot=1.0, branch=-1)
        >>> sol.theta3.round(12) + 0.0, sol.K.round(12) + 0.0
        (array([0.        , 0.13021469]), array([0.        , 0.54167751]))
        """
        if isinstance(branch, bool):       # True == 1, but it is not a branch's name
            raise ModelError(f"branch: expected one of 1, -1, got {describe(branch)}")
        check_choice("branch", branch, (1, -1))
        w = as_array("theta1_dot", theta1_dot, limit=rate("rad/s"))
        a = as_array("theta1_ddot", theta1_ddot, limit=rate("rad/s^2"))
        theta1 = as_angles("theta1", theta1)
        theta1, w, a = together(("theta1", theta1, 0), ("theta1_dot", w, 0),
                                ("theta1_ddot", a, 0))
        pos = self.positions(theta1)
        theta1 = pos.theta1
        if not pos.feasible.all():
            bad = ~np.atleast_1d(pos.feasible)
            first = float(np.atleast_1d(theta1)[bad][0])
            reach = self.reachable_inputs()
            where = " ∪ ".join(f"[{lo:.6g}, {hi:.6g}]" for lo, hi in reach) or "empty"
            raise AssemblyError(
                f"RSSR: the loop cannot close at θ1 = {first:.6g} rad (sample(s) "
                f"{indices(bad)}): the coupler L2 = {self.L2:.6g} m cannot join A and B; "
                f"reachable θ1 is {where} rad; narrow the input range",
                loop="A-B (coupler)", gap=float(np.max(pos.gap)), reachable=reach)
        column = 0 if branch == 1 else 1
        theta3 = pos.theta3[..., column]
        c1, s1, c3, s3 = np.cos(theta1), np.sin(theta1), np.cos(theta3), np.sin(theta3)
        E, F = pos.E, pos.F
        Ed, Fd = 2 * self.H1 * self.H3 * s1, -2 * self.H1 * self.L3 * s1
        Edd, Fdd = 2 * self.H1 * self.H3 * c1, -2 * self.H1 * self.L3 * c1
        phi_3 = F * c3 - E * s3
        singular = np.abs(phi_3) <= 1e-12 * np.hypot(E, F)    # the branches meet
        if singular.any():
            first = float(np.atleast_1d(theta1)[np.atleast_1d(singular)][0])
            raise SingularityError(
                f"RSSR: θ1 = {first:.6g} rad is a dead position (the two branches meet, "
                f"∂Φ/∂θ3 = 0): the output speed is unbounded there; keep θ1 strictly inside "
                f"the reachable range")
        phi_1 = Ed * c3 + Fd * s3
        phi_11, phi_13, phi_33 = Edd * c3 + Fdd * s3, Fd * c3 - Ed * s3, -E * c3 - F * s3
        K = -phi_1 / phi_3
        L = -(phi_11 + 2 * phi_13 * K + phi_33 * K**2) / phi_3
        return RSSRSolution(theta1=theta1, theta1_dot=w, theta1_ddot=a, theta3=theta3,
                            theta3_dot=K * w, theta3_ddot=K * a + L * w**2, K=K, L=L,
                            branch=branch)
