"""Serial robots described by their joint sequence: forward and inverse kinematics, rates.

A robot is a chain of revolute (R) and prismatic (P) joints.  Link ``j`` carries the
frame of joint ``j + 1``: ``(j-1)_T_j = Trans(offset_j) · Motion_j(q_j)``, where the motion is
``Rot(axis_j, q_j)`` for R and ``Trans(q_j axis_j)`` for P (*Mecanismos*, §4.3 and §7.5 build
their robots this way), and the tool point is fixed in the last link.

Closed forms (half-angle method, *Mecanismos*, §4.5) give every inverse solution of the
catalogue robots (:func:`rr`, :func:`rp`, :func:`pr`, :func:`rrr`, :func:`prr`); any other
chain is inverted by batched Newton-Raphson.
"""
from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import (AssemblyError, ConvergenceError, ModelError, SingularityError,
                            check_choice, describe, shown)
from kinelab.solvers import half_angle, wrap_angle
from kinelab.solvers._arguments import flag, reals
from kinelab.spatial._common import (ANGLE, LENGTH, as_array, as_directions, as_length,
                                     as_vectors, check_size, indices, rate, robot_name)
from kinelab.spatial._transforms import rotation

__all__ = ["RobotJoint", "SerialRobot", "ToolMotion", "JointRates",
           "rr", "rp", "pr", "rrr", "prr"]

# Relative tolerances.  _SINGULAR: smallest/largest singular value of J below which a
# pose counts as singular (J is then rank-deficient to ~10 significant digits).
# _FREE: a tool point closer than this (relative to the robot's size) to an axis about
# which a joint angle becomes arbitrary is *on* that axis.
_SINGULAR = 1e-10
_FREE = 1e-12
_NEWTON_TOL = 1e-12
# Newton solutions (rad, or scale-m) closer than this are one solution: a regular root is
# reached to about 1e-12 from every start, a double root (edge of the workspace) to 1e-6.
_SAME = 1e-5
# A Newton solution whose tool point is closer than this (relative to the robot's size) to
# a revolute joint's axis leaves that joint's angle arbitrary.
_ON_AXIS = 1e-9


@dataclass(frozen=True)
class RobotJoint:
    """One joint of a serial robot.

    Parameters
    ----------
    kind : {'R', 'P'}
        Revolute (q in rad) or prismatic (q in m).
    axis : array_like, shape (3,)
        Rotation axis (R) or slide direction (P) in the frame of the previous link;
        normalised here.
    offset : array_like, shape (3,)
        Where this joint's frame sits in the previous link's frame (m), before the joint
        moves.
    """

    kind: Literal["R", "P"]
    axis: tuple[float, float, float]
    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)

    def __post_init__(self):
        check_choice("kind", self.kind, ("R", "P"))
        axis = as_directions("axis", self.axis, batch=False)
        object.__setattr__(self, "axis", tuple(float(a) for a in axis))
        offset = as_array("offset", self.offset, (3,), batch=False, limit=LENGTH)
        object.__setattr__(self, "offset", tuple(float(o) for o in offset))


@dataclass(frozen=True)
class ToolMotion:
    """Position, velocity and acceleration of a robot's tool point.

    Attributes
    ----------
    position : ndarray, shape (d,) or (N, d), m
    velocity : ndarray, shape (d,) or (N, d), m/s
        ``J q̇``.
    acceleration : ndarray, shape (d,) or (N, d), m/s²
        ``J q̈ + J̇ q̇``.
    """

    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


@dataclass(frozen=True)
class JointRates:
    """Joint rates that give a tool velocity and acceleration (*Mecanismos*, eq. 51).

    Attributes
    ----------
    qd : ndarray, shape (n,) or (N, n)
        rad/s (R) or m/s (P).
    qdd : ndarray, shape (n,) or (N, n)
        rad/s² or m/s².
    singular : ndarray of bool, shape () or (N,)
        The Jacobian is singular there; ``qd`` and ``qdd`` are then the least-squares
        (minimum-norm) rates, which need not produce the asked tool motion.
    attainable : ndarray of bool, shape () or (N,)
        The tool velocity asked for is one the tool can have at that pose (in the range
        of the Jacobian): always where the Jacobian is regular.  At a singular pose it
        tells two things apart: ``False``, no joint rates give that velocity (the pose
        is a limit of that motion, such as the edge of the workspace for a tool moving
        out of it); ``True``, many do (the pose is where branches of the inverse
        solution meet, such as elbow up and elbow down with the arm stretched, and a
        path through it goes on along either; ``qd`` is then the minimum-norm one,
        exact, but not in general that of either branch).
    """

    qd: np.ndarray
    qdd: np.ndarray
    singular: np.ndarray
    attainable: np.ndarray


@dataclass(frozen=True)
class _Branches:
    """What a closed-form inverse returns for N tool points (private protocol)."""

    q: np.ndarray            # (N, B, n) joint coordinates, branch by branch
    distinct: np.ndarray     # (N, B) bool: branch b is not a repeat of an earlier one
    gap: np.ndarray          # (N,) m outside the workspace, 0 where reachable
    free: np.ndarray         # (N,) bool: infinitely many solutions
    workspace: str           # the reachable set, for messages
    free_reason: str         # why a joint is arbitrary where ``free``


@dataclass(frozen=True)
class SerialRobot:
    """A serial (open-chain) robot and its tool point.

    Parameters
    ----------
    name : str
    joints : sequence of RobotJoint
    tool : array_like, shape (3,)
        The tool point P in the frame of the last link, m.
    planar : bool
        A robot of the xy plane (R axes along z, P axes, offsets and tool in the plane):
        its points, velocities and Jacobian rows are 2-D.
    branches : tuple of str
        Names of the closed-form inverse solutions (set by the catalogue constructors).

    Notes
    -----
    Shapes: with n joints and d = 2 (planar) or 3, ``q`` of shape (n,) gives points of
    shape (d,) and Jacobians (d, n); ``q`` of shape (N, n) gives (N, d) and (N, d, n).

    Examples
    --------
    The RR robot of :func:`rr`, joint by joint (without its closed-form inverse, so
    :meth:`inverse` uses Newton-Raphson):

    >>> from kinelab.spatial import RobotJoint, SerialRobot
    >>> arm = SerialRobot("RR by hand", (RobotJoint("R", (0, 0, 1)),
    ...                                  RobotJoint("R", (0, 0, 1), offset=(1.0, 0, 0))),
    ...                   tool=(1.0, 0.0, 0.0), planar=True)
    >>> arm.forward([0.0, np.pi / 2]).round(12)
    array([1., 1.])
    >>> len(arm.inverse([1.0, 1.0]))
    2
    """

    name: str
    joints: tuple[RobotJoint, ...]
    tool: tuple[float, float, float]
    planar: bool = False
    branches: tuple[str, ...] = ()
    _solver: Callable[[np.ndarray], _Branches] | None = field(
        default=None, repr=False, compare=False)

    def __post_init__(self):
        who = robot_name(self.name)
        try:
            joints = tuple(self.joints)
        except TypeError:
            joints = None
        if not joints or not all(isinstance(j, RobotJoint) for j in joints):
            raise ModelError(f"robot {who}: joints: expected one or more RobotJoint, got "
                             f"{describe(self.joints)}")
        object.__setattr__(self, "joints", joints)
        tool = as_array("tool", self.tool, (3,), batch=False, limit=LENGTH)
        object.__setattr__(self, "tool", tuple(float(t) for t in tool))
        object.__setattr__(self, "planar", flag("planar", self.planar))
        if self.planar:
            problems = [f"joints[{i}]: a planar robot turns about z and slides in the "
                        f"xy plane, got a {j.kind} joint with axis {j.axis}"
                        for i, j in enumerate(self.joints)
                        if (abs(j.axis[2]) != 1.0 if j.kind == "R" else j.axis[2] != 0.0)]
            problems += [f"joints[{i}].offset: expected z = 0 in a planar robot, got "
                         f"{j.offset}" for i, j in enumerate(self.joints) if j.offset[2]]
            if self.tool[2]:
                problems.append(f"tool: expected z = 0 in a planar robot, got {self.tool}")
            if problems:
                raise ModelError(problems, source=f"robot {who}")

    # -- sizes ------------------------------------------------------------------------------
    @property
    def n(self) -> int:
        """Number of joints."""
        return len(self.joints)

    @property
    def dim(self) -> int:
        """2 for a planar robot, 3 otherwise: the length of a tool point."""
        return 2 if self.planar else 3

    @property
    def revolute(self) -> np.ndarray:
        """(n,) bool: which joints are revolute (their coordinates are angles)."""
        return np.array([j.kind == "R" for j in self.joints])

    @property
    def scale(self) -> float:
        """A length for tolerances: the sum of the fixed link lengths (at least 1 m)."""
        size = sum(np.linalg.norm(j.offset) for j in self.joints) + np.linalg.norm(self.tool)
        return float(max(size, 1.0))

    # -- kinematics -------------------------------------------------------------------------
    def forward(self, q: ArrayLike) -> np.ndarray:
        """Tool point for joint coordinates ``q``.

        Parameters
        ----------
        q : array_like, shape (n,) or (N, n)
            rad (R joints), m (P joints).

        Returns
        -------
        ndarray, shape (d,) or (N, d), m

        Examples
        --------
        >>> robot = kl.spatial.rr(1.0, 1.0)
        >>> robot.forward([[0.0, 0.0], [np.pi / 2, -np.pi / 2]]).round(12) + 0.0
        array([[2., 0.],
               [1., 1.]])
        """
        q, single = self._joint_array("q", q)
        # From the tool back to the base, x <- Trans(offset_j) Motion_j(q_j) x: vectors
        # only, no products of rotation matrices.
        x = np.broadcast_to(np.asarray(self.tool), (q.shape[0], 3))
        for j in range(self.n - 1, -1, -1):
            joint = self.joints[j]
            if joint.kind == "R":
                x = np.einsum("nij,nj->ni", _joint_rotation(joint, q[:, j]), x)
            else:
                x = x + np.asarray(joint.axis) * q[:, j, None]
            x = x + np.asarray(joint.offset)
        point = x[:, :self.dim]
        return point[0] if single else point

    def jacobian(self, q: ArrayLike) -> np.ndarray:
        """``J = ∂P/∂q``, shape (d, n) or (N, d, n).

        Column j is ``a_j × (P - p_j)`` for a revolute joint (axis ``a_j`` through
        ``p_j``) and ``a_j`` for a prismatic one.

        Examples
        --------
        The RR robot stretched along x: both joints move P along y, by 2 and 1 m/rad.

        >>> kl.spatial.rr(1.0, 1.0).jacobian([0.0, 0.0])
        array([[0., 0.],
               [2., 1.]])
        """
        q, single = self._joint_array("q", q)
        J = self._jacobian(*self._chain(q))
        return J[0] if single else J

    def motion(self, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0) -> ToolMotion:
        """Tool position, velocity ``J q̇`` and acceleration ``J q̈ + J̇ q̇``.

        ``J̇ q̇`` is analytic: each joint axis turns with the link that carries it
        (``ȧ_j = ω_(j-1) × a_j``) and each joint centre moves with it.

        Parameters
        ----------
        q, qd, qdd : array_like, shape (n,) or (N, n)
            Joint coordinates and their first and second time derivatives; ``qd`` and
            ``qdd`` broadcast to the shape of ``q``.

        Returns
        -------
        ToolMotion

        Examples
        --------
        The RP arm turning at 1 rad/s while the tool slides out at 1 m/s, 2 m out along x:
        velocity (1, 2), acceleration (-2, 2) (centripetal -q2 θ̇1², Coriolis 2 θ̇1 q̇2).

        >>> m = kl.spatial.rp().motion([0.0, 2.0], [1.0, 1.0])
        >>> m.velocity, m.acceleration
        (array([1., 2.]), array([-2.,  2.]))
        """
        q, single = self._joint_array("q", q)
        qd, qdd = _like(q, "qd", qd), _like(q, "qdd", qdd)
        chain = self._chain(q)
        J = self._jacobian(*chain)
        velocity = np.einsum("nij,nj->ni", J, qd)
        acceleration = np.einsum("nij,nj->ni", J, qdd) + self._bias(*chain, qd)
        result = (chain[2][:, :self.dim], velocity, acceleration)
        return ToolMotion(*(r[0] if single else r for r in result))

    # -- inverse rates (*Mecanismos*, eq. 51) ---------------------------------------------------
    def inverse_rates(self, q: ArrayLike, velocity: ArrayLike, acceleration: ArrayLike = 0.0,
                      *, on_singular: Literal["raise", "flag"] = "raise") -> JointRates:
        """Joint rates ``q̇ = J⁻¹ v`` and ``q̈ = J⁻¹ (a - J̇ q̇)`` for a tool velocity and
        acceleration at pose ``q``.

        Parameters
        ----------
        q : array_like, shape (n,) or (N, n)
        velocity, acceleration : array_like, shape (d,) or (N, d)
            Of the tool point, m/s and m/s².
        on_singular : {'raise', 'flag'}
            At a singular pose (``J`` loses rank, smallest singular value below 1e-10
            of the largest) raise :class:`SingularityError`, or return least-squares
            rates there with ``singular`` set (and ``attainable``: whether the velocity
            asked for is one the tool can have there).

        Raises
        ------
        SingularityError
            With ``on_singular='raise'``, naming the singular samples, and saying whether
            the tool cannot move that way there (a limit of the motion) or can, with
            joint rates that are not unique (branches of the inverse solution meet).
        ModelError
            If the robot does not have as many joints as tool coordinates.

        Examples
        --------
        To move the tip of the stretched-out-and-folded RR arm (θ2 = 90°) at 1 m/s along
        +x, only the elbow turns:

        >>> robot = kl.spatial.rr(1.0, 1.0)
        >>> robot.inverse_rates([0.0, np.pi / 2], [1.0, 0.0]).qd.round(12) + 0.0
        array([ 0., -1.])
        """
        check_choice("on_singular", on_singular, ("raise", "flag"))
        if self.n != self.dim:
            raise ModelError(f"robot {shown(self.name)}: inverse_rates needs as many joints as "
                             f"tool coordinates, got {self.n} joints for {self.dim}")
        q, single = self._joint_array("q", q)
        v = self._tool_rates("velocity", velocity, q, "m/s")
        a = self._tool_rates("acceleration", acceleration, q, "m/s^2")
        chain = self._chain(q)
        J = self._jacobian(*chain)
        sv = np.linalg.svd(J, compute_uv=False)
        singular = sv[:, -1] <= _SINGULAR * sv[:, 0]
        # At a singular pose, the part of v along the directions J cannot give (its left
        # null space): none, and v is attainable with rates that are not unique.
        off = np.zeros(len(q))
        if singular.any():
            U, s, _ = np.linalg.svd(J[singular])
            lost = s <= _SINGULAR * s[:, :1]
            off[singular] = np.linalg.norm(np.einsum("nij,ni->nj", U, v[singular]) * lost,
                                           axis=-1)
        attainable = off <= _SINGULAR * np.linalg.norm(v, axis=-1)
        if singular.any() and on_singular == "raise":
            raise self._singular_error(q, singular, attainable, off)
        qd = _solve(J, v, singular)
        qdd = _solve(J, a - self._bias(*chain, qd), singular)
        if single:
            return JointRates(qd=qd[0], qdd=qdd[0], singular=singular[0],
                              attainable=attainable[0])
        return JointRates(qd=qd, qdd=qdd, singular=singular, attainable=attainable)

    def _singular_error(self, q, singular, attainable, off) -> SingularityError:
        """What inverse_rates says at singular poses: a limit of the motion asked for, or a
        pose where branches meet."""
        blocked = singular & ~attainable
        at = blocked if blocked.any() else singular
        first = int(np.flatnonzero(at)[0])
        where = (f"robot {shown(self.name)}: the Jacobian is singular at sample(s) "
                 f"{indices(at)} (q = {np.round(q[first], 6).tolist()})")
        flag_it = "pass on_singular='flag' for least-squares rates with those samples flagged"
        if blocked.any():
            return SingularityError(
                f"{where} and the tool velocity asked for has a part of {off[first]:.6g} m/s "
                f"that no joint rates give: the tool cannot move that way from this pose (a "
                f"limit of that motion, such as the edge of the workspace); change the "
                f"velocity or move off that pose, or {flag_it}")
        return SingularityError(
            f"{where}: the tool can move with the velocity asked for, but not with unique "
            f"joint rates, as branches of the inverse solution meet at this pose and the "
            f"rates depend on the branch the motion is on; move off that pose, or {flag_it} "
            f"(the minimum-norm ones)")

    # -- inverse position -------------------------------------------------------------------
    def inverse(self, point: ArrayLike, *, branch: str | None = None,
                guess: ArrayLike | None = None) -> np.ndarray:
        """Joint coordinates that put the tool at ``point``.

        Parameters
        ----------
        point : array_like, shape (d,) or (N, d)
            m.
        branch : str, optional
            One of :attr:`branches` (closed-form robots): return that solution only.
        guess : array_like, shape (n,) or (N, n), optional
            Start Newton-Raphson here and return the solution it reaches.

        Returns
        -------
        ndarray
            - ``guess`` or ``branch`` given: shape (n,) or (N, n).
            - Otherwise, for one point, **all** solutions, shape (K, n): the distinct
              branches in the order of :attr:`branches` (a branch that coincides with an
              earlier one, at the edge of the workspace, is left out).  For N points,
              shape (N, B, n) with every branch, repeats included.
            - A robot without a closed form and no guess: Newton from a grid of 3ⁿ starts
              keeps every distinct solution it reaches (one point only).  This needs
              isolated solutions: no more joints than tool coordinates, joints that move
              the tool independently, and a point off every revolute axis.

            Revolute coordinates are in (-π, π].

        Raises
        ------
        AssemblyError
            A point out of reach (the message says by how much and what is reachable).
        SingularityError
            A point with infinitely many solutions (a joint angle is arbitrary there).
        ConvergenceError
            Newton did not converge from ``guess``.
        ModelError
            Without a closed form and a guess, a robot whose solutions form a continuum
            (more joints than tool coordinates, or joints that do not move the tool
            independently).

        Examples
        --------
        >>> robot = kl.spatial.rr(1.0, 1.0)
        >>> np.degrees(robot.inverse([1.0, 1.0])).round(9) + 0.0          # up, down
        array([[ 90., -90.],
               [  0.,  90.]])
        >>> np.degrees(robot.inverse([1.0, 1.0], guess=[0.1, 1.2])).round(9) + 0.0
        array([ 0., 90.])
        """
        points, single = self._point_array(point)
        if guess is not None:
            if branch is not None:
                raise ModelError("inverse: give branch or guess, not both")
            q0, single_guess = self._joint_array("guess", guess)
            if len(q0) != len(points) and 1 not in (len(q0), len(points)):
                raise ModelError(f"guess: {len(q0)} guesses for {len(points)} points; give "
                                 f"one guess, or one for each point")
            single = single and single_guess
            N = len(points) if len(q0) == 1 else len(q0)
            points = np.broadcast_to(points, (N, self.dim))
            q, ok, residual = self._newton(points, np.broadcast_to(q0, (N, self.n)))
            if not ok.all():
                raise ConvergenceError(
                    f"robot {shown(self.name)}: Newton did not converge for sample(s) "
                    f"{indices(~ok)} (residual {residual[~ok].max():.3g} m); the point may "
                    f"be out of reach, or start nearer a solution")
            return q[0] if single else q
        if self._solver is None:
            if branch is not None:
                raise ModelError(f"robot {shown(self.name)}: branch: this robot has no closed-form "
                                 f"branches; pass guess= to follow one solution")
            if not single:
                raise ModelError(f"robot {shown(self.name)}: point: without a closed form, give "
                                 f"one point (shape ({self.dim},)) or a guess for N points")
            return self._newton_all(points[0])
        if branch is not None:
            check_choice("branch", branch, self.branches)
        solved = self._solver(points)
        self._check_reach(points, solved)
        if branch is not None:
            q = solved.q[:, self.branches.index(branch)]
            return q[0] if single else q
        return solved.q[0][solved.distinct[0]] if single else solved.q

    def reachable(self, point: ArrayLike) -> np.ndarray:
        """Whether each point is inside the workspace (closed-form robots).

        Returns
        -------
        ndarray of bool, shape () or (N,)

        Examples
        --------
        >>> kl.spatial.rrr(1.0, 1.0).reachable([[0.0, 1.0, 1.0], [0.0, 2.0, 1.0]])
        array([ True, False])
        """
        points, single = self._point_array(point)
        if self._solver is None:
            raise ModelError(f"robot {shown(self.name)}: reachable needs a closed-form robot")
        gap = self._solver(points).gap
        return gap[0] == 0.0 if single else gap == 0.0

    # -- internals --------------------------------------------------------------------------
    def _joint_array(self, name: str, q: ArrayLike) -> tuple[np.ndarray, bool]:
        q = as_array(name, q, (self.n,))
        revolute = self.revolute
        check_size(name, np.where(revolute, q, 0.0), ANGLE)
        check_size(name, np.where(revolute, 0.0, q), LENGTH)
        return np.atleast_2d(q), q.ndim == 1

    def _point_array(self, point: ArrayLike) -> tuple[np.ndarray, bool]:
        p = as_array("point", point, (self.dim,), limit=LENGTH)
        return np.atleast_2d(p), p.ndim == 1

    def _tool_rates(self, name: str, value: ArrayLike, q: np.ndarray, unit: str) -> np.ndarray:
        """A tool velocity or acceleration, shape (d,) or (N, d), as (N, d) like ``q``."""
        v = as_vectors(name, value, self.dim, limit=rate(unit))
        if v.ndim > 2 or (v.ndim == 2 and len(v) != len(q)):
            raise ModelError(f"{name}: expected shape ({self.dim},) or ({len(q)}, {self.dim}) "
                             f"like q, got {v.shape}")
        return np.broadcast_to(v, (len(q), self.dim))

    def _chain(self, q: np.ndarray):
        """World axes (n, N, 3), joint centres (n, N, 3) and tool point (N, 3)."""
        N = q.shape[0]
        R = np.broadcast_to(np.eye(3), (N, 3, 3))
        p = np.zeros((N, 3))
        axes, centres = [], []
        for j, joint in enumerate(self.joints):
            p = p + R @ np.asarray(joint.offset)
            a = R @ np.asarray(joint.axis)
            axes.append(a)
            centres.append(p)
            if joint.kind == "R":
                R = R @ _joint_rotation(joint, q[:, j])
            else:
                p = p + a * q[:, j, None]
        return np.stack(axes), np.stack(centres), p + R @ np.asarray(self.tool)

    def _columns(self, axes, centres, x, upto: int) -> list[np.ndarray]:
        """Velocity of point x per unit rate of each of the first ``upto`` joints."""
        return [np.cross(axes[j], x - centres[j]) if joint.kind == "R" else axes[j]
                for j, joint in enumerate(self.joints[:upto])]

    def _jacobian(self, axes, centres, tool) -> np.ndarray:
        J = np.stack(self._columns(axes, centres, tool, self.n), axis=-1)
        return J[:, :self.dim]

    def _bias(self, axes, centres, tool, qd) -> np.ndarray:
        """``J̇ q̇`` (N, d): the tool acceleration at zero joint accelerations."""
        tool_velocity = sum(c * qd[:, i, None] for i, c in
                            enumerate(self._columns(axes, centres, tool, self.n)))
        # the link carrying joint j moves as v(x) = omega x x + v0 (summed over the joints
        # before it), so every joint centre's velocity comes in one pass
        omega = np.zeros_like(tool)
        v0 = np.zeros_like(tool)
        bias = np.zeros_like(tool)
        for j, joint in enumerate(self.joints):
            a_dot = np.cross(omega, axes[j])
            rate = axes[j] * qd[:, j, None]
            if joint.kind == "R":
                centre_velocity = np.cross(omega, centres[j]) + v0
                column_dot = (np.cross(a_dot, tool - centres[j])
                              + np.cross(axes[j], tool_velocity - centre_velocity))
                omega = omega + rate
                v0 = v0 - np.cross(rate, centres[j])
            else:
                column_dot = a_dot
                v0 = v0 + rate
            bias = bias + column_dot * qd[:, j, None]
        return bias[:, :self.dim]

    def _newton(self, targets: np.ndarray, q0: np.ndarray,
                max_iter: int = 50) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Batched Newton-Raphson on ``P(q) = target`` (least squares steps at singular J)."""
        revolute = self.revolute
        size = np.where(revolute, 1.0, self.scale)      # step measure: rad and scale-m
        tol = _NEWTON_TOL * (self.scale + np.linalg.norm(targets, axis=-1))
        q = np.array(q0, dtype=float)
        for _ in range(max_iter):
            chain = self._chain(q)
            residual = chain[2][:, :self.dim] - targets
            error = np.linalg.norm(residual, axis=-1)
            active = error > tol
            if not active.any():
                break
            J = self._jacobian(*chain)[active]
            step = -np.einsum("nij,nj->ni", np.linalg.pinv(J), residual[active])
            length = np.linalg.norm(step / size, axis=-1, keepdims=True)
            q[active] += step * np.minimum(1.0, 0.5 / np.maximum(length, 1e-300))
        else:
            error = np.linalg.norm(self._chain(q)[2][:, :self.dim] - targets, axis=-1)
        q[:, revolute] = wrap_angle(q[:, revolute])
        return q, error <= tol, error

    def _newton_all(self, target: np.ndarray) -> np.ndarray:
        """Distinct Newton solutions from a 3ⁿ grid of starts (one target).

        Only isolated solutions can be listed, so this refuses a robot with more joints
        than tool coordinates, or whose joints do not move the tool independently anywhere
        on the grid (its Jacobian loses rank at every start); n <= 3 then, and the grid
        has at most 27 starts."""
        who = f"robot {shown(self.name)}"
        advice = ("pass guess= to get the solution Newton reaches from it")
        if self.n > self.dim:
            raise ModelError(f"{who}: inverse: {self.n} joints for {self.dim} tool coordinates, "
                             f"so the solutions form a continuum, not a list; {advice}, or "
                             f"use a robot with at most {self.dim} joints")
        values = [(-2 * np.pi / 3, 0.0, 2 * np.pi / 3) if j.kind == "R"
                  else (-0.5 * self.scale, 0.0, 0.5 * self.scale) for j in self.joints]
        starts = np.array(list(itertools.product(*values)))
        sv = np.linalg.svd(self._jacobian(*self._chain(starts)), compute_uv=False)
        rank = int(((sv > _SINGULAR * sv[:, :1]) & (sv > 0.0)).sum(axis=1).max())
        if rank == 0:
            raise ModelError(f"{who}: inverse: no joint moves the tool (it lies on every "
                             f"joint axis), so every joint angle is arbitrary; give the "
                             f"robot links, or a tool point off its axes")
        if rank < self.n:
            raise ModelError(f"{who}: inverse: its {self.n} joints do not move the tool "
                             f"independently (the Jacobian has rank {rank} at every start), "
                             f"so the solutions form a continuum, not a list; {advice}, or "
                             f"remove a joint that repeats another's motion")
        q, ok, _ = self._newton(np.broadcast_to(target, (len(starts), self.dim)), starts)
        if not ok.any():
            raise AssemblyError(f"{who}: Newton reached no solution for point "
                                f"{target.tolist()} from {len(starts)} starts; the point is "
                                f"probably out of reach")
        q = q[ok]
        columns = self._jacobian(*self._chain(q))               # (K, d, n)
        on_axis = (np.linalg.norm(columns, axis=1) <= _ON_AXIS * self.scale) & self.revolute
        if on_axis.any():
            joint = int(np.flatnonzero(on_axis.any(axis=0))[0])
            raise SingularityError(
                f"{who}: point {np.round(target, 6).tolist()} has infinitely many solutions: "
                f"it lies on the axis of joints[{joint}], so that joint's angle is arbitrary; "
                f"move the point off it, or {advice}")
        return self._distinct(q)

    def _distinct(self, q: np.ndarray) -> np.ndarray:
        """The rows of ``q`` that differ (by more than _SAME, revolute coordinates modulo a
        turn) from every earlier row.  Rows are filed by cell of side _SAME, so each row is
        compared only with the rows of its own and the neighbouring cells: linear work."""
        revolute = self.revolute
        unit = np.where(revolute, 1.0, self.scale) * _SAME
        turn = np.where(revolute, 2.0 * np.pi, 0.0)
        cells: dict[tuple[int, ...], list[int]] = {}
        kept: list[np.ndarray] = []
        near_offsets = list(itertools.product((-1, 0, 1), repeat=self.n))
        for row in q:
            # a revolute angle near ±π is also looked for a turn away
            shifts = [(0.0,) if not r or abs(x) < np.pi - 2 * u else (0.0, -t, t)
                      for r, x, u, t in zip(revolute, row, unit, turn)]
            known = False
            for shift in itertools.product(*shifts):
                home = np.floor((row + np.array(shift)) / unit).astype(np.int64)
                for offset in near_offsets:
                    for k in cells.get(tuple((home + offset).tolist()), ()):
                        gap = np.where(revolute, wrap_angle(row - kept[k]), row - kept[k])
                        known = known or bool((np.abs(gap) <= unit).all())
            if not known:
                cells.setdefault(tuple(np.floor(row / unit).astype(np.int64).tolist()),
                                 []).append(len(kept))
                kept.append(row)
        return np.array(kept)

    def _check_reach(self, points: np.ndarray, solved: _Branches) -> None:
        out = solved.gap > 0.0
        if out.any():
            first = int(np.flatnonzero(out)[0])
            raise AssemblyError(
                f"robot {shown(self.name)}: point(s) at index {indices(out)} out of reach: "
                f"{np.round(points[first], 6).tolist()} lies {solved.gap[first]:.6g} m "
                f"outside the workspace ({solved.workspace}); choose points inside it "
                f"(robot.reachable(points) tells which are)", loop=self.name,
                gap=float(solved.gap.max()))
        if solved.free.any():
            first = int(np.flatnonzero(solved.free)[0])
            raise SingularityError(
                f"robot {shown(self.name)}: point(s) at index {indices(solved.free)} have "
                f"infinitely many solutions: {np.round(points[first], 6).tolist()} lies "
                f"{solved.free_reason}; move the point off it, or pass guess= to pick one "
                f"solution by Newton")


def _like(q: np.ndarray, name: str, value: ArrayLike) -> np.ndarray:
    """Joint rates broadcast to the shape of ``q`` (N, n)."""
    rates = reals(name, value)
    try:
        rates = np.broadcast_to(rates, q.shape)
    except ValueError:
        raise ModelError(f"{name}: expected a number or shape ({q.shape[1]},) or "
                         f"({q.shape[0]}, {q.shape[1]}) like q, got {rates.shape}") from None
    unit = "per s" if name == "qd" else "per s^2"
    return as_array(name, rates, (q.shape[1],), limit=rate(unit))


def _joint_rotation(joint: RobotJoint, angle: np.ndarray) -> np.ndarray:
    """Rotation matrices (N, 3, 3) of a revolute joint; a coordinate axis takes scipy's
    faster single-axis path."""
    axis = np.asarray(joint.axis)
    for letter, unit in zip("xyz", np.eye(3)):
        if np.array_equal(np.abs(axis), unit):
            return rotation(letter, angle * float(axis @ unit)).as_matrix()
    return rotation(axis, angle).as_matrix()


def _solve(J: np.ndarray, b: np.ndarray, singular: np.ndarray) -> np.ndarray:
    """``J x = b`` per sample: LU where regular, least squares (pinv) where singular."""
    x = np.empty(b.shape[:1] + J.shape[2:])
    regular = ~singular
    if regular.any():
        x[regular] = np.linalg.solve(J[regular], b[regular][..., None])[..., 0]
    if singular.any():
        # the same threshold as the flag: the minimum-norm rates, not a near-singular inverse
        x[singular] = np.einsum("nij,nj->ni", np.linalg.pinv(J[singular], rcond=_SINGULAR),
                                b[singular])
    return x


# -- closed forms ---------------------------------------------------------------------------

def _two_link(u: np.ndarray, v: np.ndarray, a: float, b: float):
    """Planar 2R: angles that put the end of links a, b at (u, v) from the first axis.

    The first angle solves ``E cos θa + F sin θa + G = 0`` with ``E = -2ua``, ``F = -2va``,
    ``G = u² + v² + a² - b²`` (*Mecanismos*, eq. 79, there for the RRR robot); then
    ``θa + θb = atan2(v - a sin θa, u - a cos θa)``.  Column 0 (``∂Φ/∂θa > 0``) has the
    elbow on the left of the line from the first axis to the point (counter-clockwise
    side), column 1 on the right.

    Returns θa (N, 2), θb (N, 2), count (N,), gap (N,) in m, free (N,) bool.
    """
    E, F, G = -2.0 * u * a, -2.0 * v * a, u * u + v * v + a * a - b * b
    _roots = half_angle(E, F, G)
    theta_a, count = _roots.theta, _roots.count
    elbow = a * np.stack([np.cos(theta_a), np.sin(theta_a)])
    theta_b = wrap_angle(np.arctan2(v[:, None] - elbow[1], u[:, None] - elbow[0]) - theta_a)
    d = np.hypot(u, v)
    tol = _FREE * (a + b)
    free = (d <= tol) & (abs(a - b) <= tol)
    outside = np.maximum(d - (a + b), abs(a - b) - d)
    gap = np.where((count > 0) | free, 0.0, np.maximum(outside, tol))
    return theta_a, theta_b, count, gap, free


def _two_link_workspace(a: float, b: float, where: str) -> str:
    return f"{where} between {abs(a - b):.6g} m and {a + b:.6g} m"


def rr(l1: float, l2: float) -> SerialRobot:
    """The planar RR robot of *Mecanismos*, Ex. 4.1: links ``l1``, ``l2`` (m).

    ``P = (l1 cos θ1 + l2 cos(θ1 + θ2), l1 sin θ1 + l2 sin(θ1 + θ2))`` (eq. 21): joint 1 at
    the origin, joint 2 at the end of link 1, θ1 from +x, θ2 from link 1, both
    counter-clockwise.

    Branches: ``"up"`` has the elbow on the left of the line from the origin to P
    (θ2 <= 0), ``"down"`` on the right (θ2 >= 0).

    Examples
    --------
    >>> robot = kl.spatial.rr(1.0, 1.0)
    >>> robot.forward(np.radians([30.0, 60.0]))           # (√3/2, 1.5)
    array([0.8660254, 1.5      ])
    >>> np.degrees(robot.inverse([np.sqrt(3) / 2, 1.5])).round(9)
    array([[ 90., -60.],
           [ 30.,  60.]])
    """
    l1, l2 = as_length("l1", l1, positive=True), as_length("l2", l2, positive=True)

    def solve(points):
        t1, t2, count, gap, free = _two_link(points[:, 0], points[:, 1], l1, l2)
        return _Branches(np.stack([t1, t2], axis=-1), _distinct(count), gap, free,
                         _two_link_workspace(l1, l2, "distance from the origin"),
                         "at the origin, so θ1 is arbitrary (l1 = l2)")

    return SerialRobot("RR", (RobotJoint("R", (0, 0, 1)), RobotJoint("R", (0, 0, 1), (l1, 0, 0))),
                       tool=(l2, 0.0, 0.0), planar=True, branches=("up", "down"), _solver=solve)


def rp() -> SerialRobot:
    """The planar RP robot of *Mecanismos*, §5.5: an arm turning by θ1 about the origin, with
    the tool sliding along it by q2: ``P = q2 (cos θ1, sin θ1)``.

    Branches: ``"positive"`` (q2 >= 0, the arm points at P) and ``"negative"`` (q2 <= 0,
    the arm points away and the slide is negative).

    Examples
    --------
    >>> kl.spatial.rp().inverse([0.0, 2.0], branch="positive")
    array([1.57079633, 2.        ])
    """
    def solve(points):
        r = np.hypot(points[:, 0], points[:, 1])
        theta = np.arctan2(points[:, 1], points[:, 0])
        q = np.stack([np.stack([theta, r], -1), np.stack([wrap_angle(theta + np.pi), -r], -1)], 1)
        free = r <= _FREE
        return _Branches(q, np.stack([np.ones_like(free), ~free], -1), np.zeros_like(r),
                         free, "the whole plane", "at the origin, so θ1 is arbitrary")

    return SerialRobot("RP", (RobotJoint("R", (0, 0, 1)), RobotJoint("P", (1, 0, 0))),
                       tool=(0.0, 0.0, 0.0), planar=True, branches=("positive", "negative"),
                       _solver=solve)


def pr(L: float) -> SerialRobot:
    """The planar PR robot of *Mecanismos*, §5.6: a block sliding by q1 along x carries an arm
    of length ``L`` (m) turning by θ2: ``P = (q1 + L cos θ2, L sin θ2)``.

    Branches: ``"forward"`` (cos θ2 >= 0, the arm points along +x) and ``"backward"``.

    Examples
    --------
    >>> robot = kl.spatial.pr(1.0)
    >>> robot.inverse([2.0, 0.5])            # θ2 = 30° or 150°
    array([[1.1339746 , 0.52359878],
           [2.8660254 , 2.61799388]])
    """
    L = as_length("L", L, positive=True)

    def solve(points):
        x, y = points[:, 0], points[:, 1]
        _roots = half_angle(0.0, L, -y)       # L sin θ2 = y
        theta, count, gap = _roots.theta, _roots.count, _roots.gap
        q1 = x[:, None] - L * np.cos(theta)
        return _Branches(np.stack([q1, theta], -1), _distinct(count), gap,
                         np.zeros_like(x, dtype=bool), f"the strip |y| <= {L:.6g} m", "")

    return SerialRobot("PR", (RobotJoint("P", (1, 0, 0)), RobotJoint("R", (0, 0, 1))),
                       tool=(L, 0.0, 0.0), planar=True, branches=("forward", "backward"),
                       _solver=solve)


def rrr(L2: float, L3: float) -> SerialRobot:
    """The spatial RRR (articulated) robot of *Mecanismos*, §7.5, with H = 0.

    ``0_T_1 = Rot(z, θ1)``, ``1_T_2 = Rot(x, θ2)``, ``2_T_3 = Trans(0, L2, 0) Rot(x, θ3)``
    and ``3_r_P = (0, L3, 0)`` (eq. 77), so, with ``ρ = L2 cos θ2 + L3 cos(θ2 + θ3)``::

        P = (-ρ sin θ1,  ρ cos θ1,  L2 sin θ2 + L3 sin(θ2 + θ3))

    θ1 turns the arm about the vertical z axis (θ1 = 0 points it along +y); θ2 raises the
    upper arm L2 from the horizontal; θ3 turns the forearm L3 relative to the upper arm.
    The shoulder is at the origin (no base height).

    Branches, in this order: ``"front-up"``, ``"front-down"``, ``"back-up"``,
    ``"back-down"``.  *Front*: the arm plane points at P (ρ > 0); *back*: θ1 turned by
    180° and the arm bent over backwards (ρ < 0).  *Up*: the elbow lies above the line
    from the shoulder to P.  Front-up has θ3 <= 0, back-up θ3 >= 0.

    A point on the z axis (x = y = 0) leaves θ1 arbitrary: :meth:`~SerialRobot.inverse`
    raises :class:`~kinelab.errors.SingularityError` there.

    Parameters
    ----------
    L2, L3 : float
        Upper arm and forearm, m.

    Examples
    --------
    *Mecanismos*, eq. 78: θ = (-45°, 60°, 30°) puts P at (√2/4, √2/4, 1 + √3/2):

    >>> robot = kl.spatial.rrr(1.0, 1.0)
    >>> robot.forward(np.radians([-45.0, 60.0, 30.0]))
    array([0.35355339, 0.35355339, 1.8660254 ])

    and back again, all four solutions (the notes print the two front ones):

    >>> np.degrees(robot.inverse([np.sqrt(2) / 4, np.sqrt(2) / 4, 1 + np.sqrt(3) / 2])).round(9)
    array([[-45.,  90., -30.],
           [-45.,  60.,  30.],
           [135.,  90.,  30.],
           [135., 120., -30.]])
    """
    L2, L3 = as_length("L2", L2, positive=True), as_length("L3", L3, positive=True)

    def solve(points):
        x, y, z = points.T
        r = np.hypot(x, y)
        free = r <= _FREE * (L2 + L3)
        front = np.arctan2(-x, y)
        t2, t3, count, gap, _ = _two_link(r, z, L2, L3)     # columns: up, down
        # Shoulder back: θ1 + π turns the arm plane round, and θ2 -> π - θ2, θ3 -> -θ3
        # mirror the arm within it, which puts the elbow back where it was (so "up"
        # stays up).
        back = wrap_angle(front + np.pi)
        q = np.empty((len(r), 4, 3))
        q[:, :2, 0], q[:, 2:, 0] = front[:, None], back[:, None]
        q[:, :2, 1], q[:, 2:, 1] = t2, wrap_angle(np.pi - t2)
        q[:, :2, 2], q[:, 2:, 2] = t3, -t3
        distinct = np.concatenate([_distinct(count)] * 2, axis=-1)
        return _Branches(q, distinct, gap, free & (gap == 0),
                         _two_link_workspace(L2, L3, "distance from the shoulder"),
                         "on the θ1 axis (x = y = 0), so θ1 is arbitrary")

    joints = (RobotJoint("R", (0, 0, 1)), RobotJoint("R", (1, 0, 0)),
              RobotJoint("R", (1, 0, 0), (0, L2, 0)))
    return SerialRobot("RRR", joints, tool=(0.0, L3, 0.0),
                       branches=("front-up", "front-down", "back-up", "back-down"),
                       _solver=solve)


def prr(L1: float, L2: float, D: float = 0.0, H: float = 0.0, V: float = 0.0) -> SerialRobot:
    """A PRR robot (*Mecanismos*, Ex. 6.1): a vertical slide d1 carrying a horizontal
    two-link arm (θ2, θ3 about vertical axes).

    The exercise's figure is not in the notes' text, so kinelab fixes the geometry:
    the column slides by d1 along z; the first revolute axis is parallel to z, offset
    by ``D`` along x and raised by ``H`` above the slider; links ``L1`` and ``L2`` turn in
    the horizontal plane; the tool point hangs ``V`` below the end of ``L2``::

        P = (D + L1 cos θ2 + L2 cos(θ2 + θ3),  L1 sin θ2 + L2 sin(θ2 + θ3),  d1 + H - V)

    q = (d1, θ2, θ3), m and rad.  Branches: ``"left"`` (elbow on the left of the line from
    the first revolute axis to P, seen from above, θ3 <= 0) and ``"right"``.

    Examples
    --------
    Ex. 6.1 (d): d1 = 0.7 m, θ2 = 60°, θ3 = 30°, D = H = V = 0.1 m, L1 = L2 = 1 m:

    >>> robot = kl.spatial.prr(1.0, 1.0, D=0.1, H=0.1, V=0.1)
    >>> robot.forward([0.7, np.radians(60.0), np.radians(30.0)])
    array([0.6      , 1.8660254, 0.7      ])
    """
    L1, L2 = as_length("L1", L1, positive=True), as_length("L2", L2, positive=True)
    D, H, V = as_length("D", D), as_length("H", H), as_length("V", V)

    def solve(points):
        x, y, z = points.T
        t2, t3, count, gap, free = _two_link(x - D, y, L1, L2)
        d1 = np.broadcast_to((z - H + V)[:, None], t2.shape)
        return _Branches(np.stack([d1, t2, t3], -1), _distinct(count), gap, free,
                         _two_link_workspace(L1, L2, "horizontal distance from the first "
                                             "revolute axis"),
                         "on the first revolute axis, so θ2 is arbitrary (L1 = L2)")

    joints = (RobotJoint("P", (0, 0, 1)), RobotJoint("R", (0, 0, 1), (D, 0, H)),
              RobotJoint("R", (0, 0, 1), (L1, 0, 0)))
    return SerialRobot("PRR", joints, tool=(L2, 0.0, -V), branches=("left", "right"),
                       _solver=solve)


def _distinct(count: np.ndarray) -> np.ndarray:
    """(N, 2) bool for a pair of half-angle branches: the second is new only if count == 2."""
    return np.stack([np.ones(count.shape, dtype=bool), count == 2], axis=-1)
