"""The result of a kinematic analysis: named arrays, with accessors by name."""
from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from kinelab import _compiled
from kinelab.errors import ModelError, describe, expected_one_of, quoted, shown
from kinelab.kinematics._columns import TableExport, solution_columns
from kinelab.kinematics._geometry import k_cross
from kinelab.kinematics._plan import Plan
from kinelab.model import Mechanism, Units
from kinelab.solvers._angles import wrapped_angles


@dataclass(frozen=True)
class AccelerationComponents:
    """The acceleration of a point that slides along a turning link, split into its parts.

    With r = p - o (o the slide's origin point on the guide), u the slide direction, s the
    slide and omega, alpha the guide's angular velocity and acceleration::

        a_p = a_o  +  alpha k x r  -  omega^2 r  +  2 omega k x (s' u)  +  s'' u
              origin   tangential     normal        Coriolis              sliding

    Each field has the shape of a point acceleration, (2,) or (N, 2), in m/s^2.
    """

    origin: np.ndarray
    tangential: np.ndarray
    normal: np.ndarray
    coriolis: np.ndarray
    sliding: np.ndarray

    @property
    def total(self) -> np.ndarray:
        return self.origin + self.tangential + self.normal + self.coriolis + self.sliding


@dataclass(frozen=True)
class GuidePoint:
    """The point of a prismatic joint's guide under the slider's point, at every sample.

    At each instant the guide (the joint's first link) has a point G in the same place as
    the joint's point P, which the slider carries: in the slotted link, the point of the
    lever under the crank pin.  G moves with the guide as a rigid body; P moves along the
    slide on top of it.  With u the slide's direction, s its slide and omega the guide's
    angular velocity::

        v_P = v_G + s' u
        a_P = a_G + 2 omega k x (s' u) + s'' u          (Coriolis, then sliding)

    and, with O the slide's origin (a point of the guide) and r = P - O,
    ``v_G = v_O + omega k x r`` and ``a_G = a_O + alpha k x r - omega^2 r``.

    Attributes
    ----------
    joint : str
        The prismatic joint.
    guide : str
        The link G belongs to (the joint's first link).
    point : str
        The joint's point P, which G lies under.
    position : ndarray, shape (2,) or (N, 2)
        m; the position of P.
    velocity : ndarray, shape (2,) or (N, 2)
        m/s.
    acceleration : ndarray, shape (2,) or (N, 2)
        m/s^2.
    """

    joint: str
    guide: str
    point: str
    position: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


class _SlideMotion(NamedTuple):
    """A prismatic joint's point P seen from its guide, per sample: r = P - O (O the slide's
    origin, a point of the guide), O's velocity and acceleration, the guide's omega and alpha
    (N, 1), the unit axis u and the slide's rates s', s'' (N, 1)."""

    point: np.ndarray
    r: np.ndarray
    v_origin: np.ndarray
    a_origin: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    u: np.ndarray
    sd: np.ndarray
    sdd: np.ndarray

    @property
    def tangential(self) -> np.ndarray:
        """alpha k x r: the guide's angular acceleration at P."""
        return self.alpha * k_cross(self.r)

    @property
    def normal(self) -> np.ndarray:
        """-omega^2 r: towards the origin, as the guide turns."""
        return -(self.omega ** 2) * self.r


@dataclass(frozen=True, eq=False)
class KinematicSolution(TableExport):
    """Positions, velocities, accelerations, K and L of every link, point and slide.

    Use the accessors, which take names and follow the shape rule of the input: a single
    configuration (``q`` of shape ``()`` for one input, ``(M,)`` for M inputs) gives
    values without the sample axis; with one input the input axes of K and L are dropped.

    Attributes
    ----------
    plan : Plan
        How the mechanism was solved (``plan.steps``), and where each coordinate is.
    mechanism : Mechanism
    q, qd, qdd : ndarray, shape (N, M)
        Inputs (rad or m), their rates and accelerations.  A rate given as one value for
        all samples is a read-only view of that value, broadcast to (N, M).
    jets : ndarray, shape (N, n, 1 + M + M*M)
        For each coordinate (link angles, then x and y of each point, then slides):
        value, K, and L flattened.  Built on first use from the stored items (below) and
        the fixed ones; prefer the accessors, which read the stored arrays directly.
    rates : ndarray, shape (N, n, 2)
        First and second time derivatives of each coordinate, built like ``jets``.
    stored_jets, stored_rates : ndarray, shape (N, len(plan.stored_items), ...)
        ``jets`` and ``rates`` of the coordinates the plan solves, ``plan.stored_items``.
        The others are not repeated per sample: the ground's angle and points keep
        ``plan.fixed_values`` (K = L = 0); a link turned from the ground by input m has the
        angle ``sign q[:, m]`` (``plan.driven_items``: item -> (m, sign)).
    det_J : ndarray, shape (N,)
        Determinant of the Jacobian J = dPhi/dS of the position equations, written group
        by group as in the notes (for a four-bar ``L3 L4 sin(theta3 - theta4)``; for the
        slotted link ``-B``).  Newton groups contribute the determinant of their own
        system in absolute coordinates.
    singularity : ndarray, shape (N,)
        A distance from singularity in [0, 1] that no unit changes, the smallest over the
        groups: for a dyad, |det| over the product of its arms' lengths (the sine of the
        angle between them, of the transmission kind); for a group solved by Newton-Raphson,
        the smallest singular value of its Jacobian made dimensionless (lengths in sizes of
        the mechanism, angles in rad) with its columns and rows scaled to unit norm, the
        relative distance to the nearest singular Jacobian (about half the sine, for a
        dyad; estimated by inverse iteration, which is exact near a singular configuration
        and may be a few times high far from one).  Below ``SINGULAR_TOL`` (5e-3) a sample
        is flagged ``singular``.
    singular : ndarray of bool, shape (N,)
        ``singularity`` is below ``SINGULAR_TOL``: det J = 0 to within what rounding
        lets K and L be trusted, velocities undefined.  At those
        samples K, L, velocities and accelerations are NaN; positions are valid.
    assembled : ndarray of bool, shape (N,)
        False where the loops cannot close (only with ``unreachable="mask"``; every value
        of such a sample is NaN).
    change_points : tuple of ChangePoint
        The change points between the smallest and the largest input of the sweep, where
        two assembly modes of a dyad meet (see ``analyze(at_change_point=...)``); a sweep
        over more than 10,000 turns lists none (``kinelab.kinematics.change_points`` lists
        them a part at a time).
    certificate : kinelab.verify.Certificate or None
        With ``kl.analyze(..., verify=True)``: every number above computed again by
        independent routes, and how far apart they came (see :mod:`kinelab.verify`).
    """

    plan: Plan
    q: np.ndarray
    qd: np.ndarray
    qdd: np.ndarray
    stored_jets: np.ndarray
    stored_rates: np.ndarray
    det_J: np.ndarray
    singularity: np.ndarray
    singular: np.ndarray
    assembled: np.ndarray
    single: bool = False
    newton_state: tuple[np.ndarray, np.ndarray] | None = None   # (q, groups' unknowns) at
                                                                # the end, for analyze(start=)
    change_points: tuple = ()
    certificate: Mapping | None = None
    constants: np.ndarray | None = None      # (D, constants): each design's own values of
                                             # the plan's constants, its samples D equal
                                             # blocks of the N (designs), else the plan's

    @classmethod
    def _made(cls, **fields) -> KinematicSolution:
        """The solution with these fields (every one without a default), as ``cls(**fields)``
        makes it, in a fraction of the time: a frozen dataclass's ``__init__`` sets each
        field through ``object.__setattr__``, which counts in an analysis of a few samples."""
        sol = object.__new__(cls)
        sol.__dict__.update(fields)
        return sol

    # -- what was solved -----------------------------------------------------------------
    @property
    def mechanism(self) -> Mechanism:
        return self.plan.mechanism

    @property
    def link_item(self) -> dict[str, int]:
        """Item of each link's angle in ``jets`` and ``rates``."""
        return self.plan.link_item

    @property
    def point_item(self) -> dict[str, int]:
        """Item of each point's x (y is the next) in ``jets`` and ``rates``."""
        return self.plan.point_item

    @property
    def slide_item(self) -> dict[str, int]:
        """Item of each prismatic joint's slide in ``jets`` and ``rates``."""
        return self.plan.slide_item

    # -- shape rule ---------------------------------------------------------------------
    @property
    def M(self) -> int:
        return self.q.shape[1]

    @property
    def N(self) -> int:
        return self.q.shape[0]

    @property
    def input_names(self) -> tuple[str, ...]:
        return self.mechanism.input_names

    @property
    def link_names(self) -> tuple[str, ...]:
        return tuple(self.link_item)

    @property
    def point_names(self) -> tuple[str, ...]:
        return tuple(self.point_item)

    @property
    def slide_names(self) -> tuple[str, ...]:
        return tuple(self.slide_item)

    def _out(self, a: np.ndarray) -> np.ndarray:
        return a[0] if self.single else a

    # -- coordinates by item --------------------------------------------------------------
    def item_jets(self, items) -> np.ndarray:
        """``jets[:, items]`` without building ``jets``: shape (N, len(items), 1 + M + M*M)."""
        return self._gather(items, self.stored_jets, values=True)

    def item_rates(self, items) -> np.ndarray:
        """``rates[:, items]`` without building ``rates``: shape (N, len(items), 2)."""
        return self._gather(items, self.stored_rates, values=False)

    def _gather(self, items, stored: np.ndarray, values: bool) -> np.ndarray:
        c = self.plan.item_columns(items)
        if c.contiguous is not None:
            return stored[:, c.contiguous]                  # a view
        if not len(c.others):
            return stored[:, c.slots]
        out = np.zeros((self.N, len(c.slots), stored.shape[2]))
        signs, inputs = c.driven_signs, c.driven_inputs
        if len(c.solved_cols):
            out[:, c.solved_cols] = stored[:, c.slots[c.solved_cols]]
        if values:
            if self.constants is None:
                out[:, c.fixed_cols, 0] = c.fixed_values
            else:                    # each design's block of samples, its own constants
                D = len(self.constants)
                blocks = out.reshape((D, self.N // D) + out.shape[1:])
                for col, const in zip(c.fixed_cols, c.fixed_constants):
                    blocks[:, :, col, 0] = self.constants[:, const, None]
            if len(c.driven_cols):
                out[:, c.driven_cols, 0] = wrapped_angles(self.q[:, inputs] * signs)
                out[:, c.driven_cols, 1 + inputs] = signs        # K = sign, L = 0
        elif len(c.driven_cols):
            out[:, c.driven_cols, 0] = self.qd[:, inputs] * signs
            out[:, c.driven_cols, 1] = self.qdd[:, inputs] * signs
        return self._masked(out, c.others, values)

    def _masked(self, out: np.ndarray, others: np.ndarray, values: bool) -> np.ndarray:
        """Gathered items ``others`` (columns of ``out``) by the same rule as the solved
        items: nothing where the loops do not close, no derivatives at a singular
        configuration."""
        not_assembled, singular = self._flags()
        if not_assembled:
            out[np.ix_(~self.assembled, others)] = np.nan
        if singular:
            derivatives = np.arange(1 if values else 0, out.shape[2])
            out[np.ix_(self.singular, others, derivatives)] = np.nan
        return out

    @functools.cached_property
    def jets(self) -> np.ndarray:
        return self.item_jets(np.arange(self.plan.n_out))

    @functools.cached_property
    def rates(self) -> np.ndarray:
        return self.item_rates(np.arange(self.plan.n_out))

    @classmethod
    def concatenate(cls, parts: list[KinematicSolution]) -> KinematicSolution:
        """One solution from the analyses of consecutive pieces of a sweep."""
        if not isinstance(parts, (list, tuple)) or not parts or not all(
                isinstance(s, KinematicSolution) for s in parts):
            raise ModelError(f"parts: expected a list of KinematicSolution, got {describe(parts)}")
        if any(s.plan is not parts[0].plan for s in parts):
            raise ModelError("parts: expected analyses of one mechanism by one method, got "
                             "several; concatenate the pieces of each sweep on their own")
        join = {name: np.concatenate([getattr(s, name) for s in parts])
                for name in ("q", "qd", "qdd", "stored_jets", "stored_rates", "det_J",
                             "singularity", "singular", "assembled")}
        seen = {c.q: c for s in parts for c in s.change_points}
        return cls(plan=parts[0].plan, single=False, newton_state=parts[-1].newton_state,
                   change_points=tuple(seen[q] for q in sorted(seen)), **join)

    def _find(self, name: str, kinds: str) -> tuple[int, int]:
        """(first item, number of items) of a link ("l"), point ("p") or slide ("s")."""
        return self._where(name, kinds)[:2]

    def _where(self, name: str, kinds: str) -> tuple[int, int, int, tuple | None]:
        """(first item, number of items, first stored column, drive) of a link ("l"), point
        ("p") or slide ("s"): the column is -1 unless all its items are stored, in
        consecutive columns; drive is (input, sign) for a link turned by an input from the
        ground, else None.  Kept on the plan: the accessors ask for the same names again and
        again."""
        found = self.plan._found
        if type(name) is str:
            hit = found.get((name, kinds))
            if hit is not None:
                return hit
        tables = {"l": (self.link_item, 1, "link"), "p": (self.point_item, 2, "point"),
                  "s": (self.slide_item, 1, "prismatic joint")}
        for kind in kinds:
            items, width, _ = tables[kind]
            if name in items:
                i = items[name]
                c = self.plan.item_columns(range(i, i + width))
                column = c.contiguous.start if c.contiguous is not None else -1
                drive = self.plan.driven_items.get(i) if width == 1 else None
                found[(name, kinds)] = hit = (i, width, column, drive)
                return hit
        names = [n for kind in kinds for n in tables[kind][0]]
        label = " or ".join(tables[kind][2] for kind in kinds)
        if not names:
            raise ModelError(f"{label}: got {shown(name)}, but the mechanism has no {label}")
        raise ModelError(f"{label}: {expected_one_of(name, names)}")

    def _gathered(self, i: int, w: int, jets: bool) -> np.ndarray:
        """``item_jets`` (or ``item_rates``) of the items i .. i + w - 1 that are not all
        stored (fixed points), gathered on first use and kept: the accessors hand out
        copies of it."""
        kept = self.__dict__.get("_blocks")
        if kept is None:
            kept = self.__dict__["_blocks"] = {}
        key = (i, w, jets)
        block = kept.get(key)
        if block is None:
            block = kept[key] = self._gather(range(i, i + w), self.stored_jets if jets
                                             else self.stored_rates, values=jets)
        return block

    def _driven(self, drive: tuple[int, float], what: str) -> np.ndarray:
        """A quantity of a link turned by input m from the ground with the sign s, (N, ...)
        as ``item_jets`` and ``item_rates`` give it: its angle wrap(s q_m), its rates s q_m'
        and s q_m'', K = s (for input m), L = 0."""
        m, sign = drive
        if what == "angle":
            q = self.q
            if q.flags.c_contiguous and q.dtype == np.float64 and _compiled.ready("driven_angles"):
                from kinelab.kinematics import _kernel
                a = _kernel.driven_angles(q, m, sign, np.empty(self.N))     # the same, to the bit
            else:
                a = wrapped_angles(q[:, m] * sign)
        elif what == "rate":
            a = self.qd[:, m] * sign
        elif what == "second":
            a = self.qdd[:, m] * sign
        elif what == "K":
            if self.M == 1:
                a = np.full(self.N, sign)
            else:
                a = np.zeros((self.N, self.M))
                a[:, m] = sign
        else:
            a = np.zeros(self.N if self.M == 1 else (self.N, self.M, self.M))
        flags = self._flags()
        if flags[0]:
            a[~self.assembled] = np.nan
        if flags[1] and what != "angle":
            a[self.singular] = np.nan
        return a

    def _flags(self) -> tuple[bool, bool]:
        """Whether some sample is not assembled, and whether some is singular."""
        flags = self.__dict__.get("_status")
        if flags is None:
            flags = self.__dict__["_status"] = (np.count_nonzero(self.assembled) < self.N,
                                                np.count_nonzero(self.singular) > 0)
        return flags

    def _value(self, name: str, kinds: str, column: int, source: str = "jets") -> np.ndarray:
        i, w, stored, drive = self._where(name, kinds)
        if stored >= 0:                           # a view of the stored arrays
            a = self.stored_jets if source == "jets" else self.stored_rates
            if self.single:
                return a[0, stored, column] if w == 1 else a[0, stored:stored + w, column]
            return self._out(a[:, stored, column] if w == 1 else a[:, stored:stored + w, column])
        if drive is not None:
            return self._out(self._driven(drive, "angle" if source == "jets" else
                                          "rate" if column == 0 else "second"))
        block = self._gathered(i, w, source == "jets")
        return self._out((block[:, 0, column] if w == 1 else block[:, :, column]).copy())

    # -- links --------------------------------------------------------------------------
    def angle(self, link: str) -> np.ndarray:
        """Angle of a link, rad, CCW from +x, in (-pi, pi]; shape () or (N,)."""
        return self._value(link, "l", 0)

    def omega(self, link: str) -> np.ndarray:
        """Angular velocity, rad/s; shape () or (N,)."""
        return self._value(link, "l", 0, "rates")

    def alpha(self, link: str) -> np.ndarray:
        """Angular acceleration, rad/s^2; shape () or (N,)."""
        return self._value(link, "l", 1, "rates")

    # -- points -------------------------------------------------------------------------
    def position(self, point: str) -> np.ndarray:
        """Position of a point, m; shape (2,) or (N, 2)."""
        return self._value(point, "p", 0)

    def velocity(self, point: str) -> np.ndarray:
        """Velocity of a point, m/s; shape (2,) or (N, 2)."""
        return self._value(point, "p", 0, "rates")

    def acceleration(self, point: str) -> np.ndarray:
        """Acceleration of a point, m/s^2; shape (2,) or (N, 2)."""
        return self._value(point, "p", 1, "rates")

    # -- slides -------------------------------------------------------------------------
    def slide(self, joint: str) -> np.ndarray:
        """Slide of a prismatic joint, m: ``axis . (point - origin)``; shape () or (N,)."""
        return self._value(joint, "s", 0)

    def slide_velocity(self, joint: str) -> np.ndarray:
        """Rate of the slide, m/s; shape () or (N,)."""
        return self._value(joint, "s", 0, "rates")

    def slide_acceleration(self, joint: str) -> np.ndarray:
        """Second derivative of the slide, m/s^2; shape () or (N,)."""
        return self._value(joint, "s", 1, "rates")

    # -- coefficients -------------------------------------------------------------------
    def K(self, name: str) -> np.ndarray:
        """Velocity coefficients dS/dq of a link angle, a slide or a point.

        Shape: () or (N,) for an angle or slide with one input, (M,) or (N, M) with M
        inputs; a point adds an axis of 2 before the input axis: (2,), (N, 2), (N, 2, M).
        Units: rad/rad, rad/m, m/rad or m/m.
        """
        i, w, stored, drive = self._where(name, "lsp")
        M = self.M
        if stored >= 0:                           # a view of the stored jets
            j = self.stored_jets
            if M == 1:
                a = j[:, stored, 1] if w == 1 else j[:, stored:stored + w, 1]
            else:
                a = j[:, stored, 1:1 + M] if w == 1 else j[:, stored:stored + w, 1:1 + M]
            return self._out(a)
        if drive is not None:
            return self._out(self._driven(drive, "K"))
        block = self._gathered(i, w, True)
        if M == 1:
            a = block[:, 0, 1] if w == 1 else block[:, :, 1]
        else:
            a = block[:, 0, 1:1 + M] if w == 1 else block[:, :, 1:1 + M]
        return self._out(a.copy())

    def L(self, name: str) -> np.ndarray:
        """Acceleration coefficients d2S/dq2 = dK/dq, shaped like :meth:`K` with one more
        input axis when M > 1; then ``S'' = K q'' + q'^T L q'``."""
        i, w, stored, drive = self._where(name, "lsp")
        M = self.M
        if drive is not None:
            return self._out(self._driven(drive, "L"))
        if stored >= 0 and M == 1:               # a view of the stored jets
            j = self.stored_jets
            return self._out(j[:, stored, 2] if w == 1 else j[:, stored:stored + w, 2])
        block = self.stored_jets[:, stored:stored + w] if stored >= 0 else self._gathered(i, w, True)
        if M == 1:
            a = block[:, 0, 2] if w == 1 else block[:, :, 2]
        else:
            a = block[:, :, 1 + M:].reshape(self.N, w, M, M)
            a = a if w > 1 else a[:, 0]
        return self._out(a.copy() if stored < 0 else a)

    def acceleration_components(self, point: str, joint: str | None = None) -> AccelerationComponents:
        """Normal, tangential, Coriolis and sliding parts of the acceleration of a point that
        slides along a turning link (Badan (IFG), *Análise de aceleração* (after Norton, ch. 7)).

        Parameters
        ----------
        point : str
            The point of a prismatic joint (carried by the slider).
        joint : str, optional
            The prismatic joint, when the point belongs to more than one.

        Returns
        -------
        AccelerationComponents
            Each part has shape (2,) for one configuration, (N, 2) for N.

        Examples
        --------
        The slotted link at q = 0 (pin A at (3, 0), lever along +x) and qd = 3 rad/s: the
        pin does not slide yet (s' = 0, no Coriolis part) but accelerates along the slot,
        s'' = -6 m/s^2:

        >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
        >>> parts = kl.analyze(sl, q=0.0, qd=3.0).acceleration_components("A")
        >>> bool(np.allclose(parts.coriolis, 0.0)), bool(np.allclose(parts.sliding, [-6.0, 0.0]))
        (True, True)
        >>> bool(np.allclose(parts.total, kl.analyze(sl, q=0.0, qd=3.0).acceleration("A")))
        True
        """
        m = self.mechanism
        joints = [j for j in m.joints if j.type == "P" and j.point == point
                  and (joint is None or j.name == joint)]
        if not joints:
            names = quoted([j.name for j in m.joints if j.type == "P"])
            raise ModelError(f"point {shown(point)}: expected the point of a prismatic joint"
                             + (f" {shown(joint)}" if joint else "") + f"; prismatic joints are "
                             f"{names}; for the normal and tangential parts of a point of a "
                             "pinned link, use kinelab.kinematics.acceleration_difference(sol, "
                             "point, reference)")
        if len(joints) > 1:
            raise ModelError(f"point {shown(point)} slides in {len(joints)} joints; name one with "
                             "joint=")
        s = self._slide_motion(joints[0].name)
        parts = dict(origin=s.a_origin, tangential=s.tangential, normal=s.normal,
                     coriolis=2.0 * s.omega * k_cross(s.sd * s.u), sliding=s.sdd * s.u)
        return AccelerationComponents(**{k: self._out(v) for k, v in parts.items()})

    def guide_point(self, joint: str) -> GuidePoint:
        """Position, velocity and acceleration of the guide's point under the slider's point
        (see :class:`GuidePoint`), at every sample.

        Parameters
        ----------
        joint : str
            A prismatic joint.

        Returns
        -------
        GuidePoint
            Its arrays have shape (2,) for one configuration, (N, 2) for N.

        Examples
        --------
        In the slotted link at q = 0 the pin A is at (3, 0) and the lever lies along +x; at
        qd = 3 rad/s the lever turns at omega = qd R / B = 1 rad/s, alpha = 0:

        >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
        >>> sol = kl.analyze(sl, q=0.0, qd=3.0)
        >>> g = sol.guide_point("slot")
        >>> g.velocity, g.acceleration.round(12)         # omega k x r, -omega^2 r
        (array([0., 3.]), array([-3.,  0.]))
        >>> sol.acceleration("A")             # -R qd^2: the rest is s'' u, s'' = -6 m/s^2
        array([-9.,  0.])
        """
        s = self._slide_motion(joint)
        j = self.mechanism.joint(joint)
        velocity = s.v_origin + s.omega * k_cross(s.r)
        acceleration = s.a_origin + s.tangential + s.normal
        return GuidePoint(joint, j.links[0], j.point, *(self._out(a) for a in
                                                        (s.point, velocity, acceleration)))

    def slide_axes(self, joint: str) -> np.ndarray:
        """Unit direction of a prismatic joint's slide, which turns with the guide (the
        joint's first link); shape (2,) or (N, 2).

        Examples
        --------
        >>> sl = kl.mechanisms.slotted_link(crank=1.0, distance=2.0)
        >>> kl.analyze(sl, q=np.pi / 2).slide_axes("slot").round(12)   # from O4 towards A = (2, 1)
        array([0.89442719, 0.4472136 ])
        >>> kl.analyze(sl, q=[0.0, np.pi / 2]).slide_axes("slot").shape
        (2, 2)
        """
        return self._out(self._slide_motion(joint).u)

    def _slide_motion(self, joint: str) -> _SlideMotion:
        """The motion of a prismatic joint's point relative to its guide, (N, ...) arrays."""
        self._find(joint, "s")
        j = self.mechanism.joint(joint)
        guide = j.links[0]
        origin = j.origin or self.mechanism.link(guide).points[0]
        gi = self.link_item[guide]
        oi, pi = self.point_item[origin], self.point_item[j.point]
        jets = self.item_jets([pi, pi + 1, oi, oi + 1, gi])
        rates = self.item_rates([gi, self.slide_item[joint], oi, oi + 1])
        theta = jets[:, 4, 0] + (math.atan2(j.axis[1], j.axis[0]) - self.plan.sketch_angles[gi])
        return _SlideMotion(
            point=jets[:, 0:2, 0], r=jets[:, 0:2, 0] - jets[:, 2:4, 0],
            v_origin=rates[:, 2:4, 0], a_origin=rates[:, 2:4, 1],
            omega=rates[:, 0:1, 0], alpha=rates[:, 0:1, 1],
            u=np.stack([np.cos(theta), np.sin(theta)], axis=-1),
            sd=rates[:, 1:2, 0], sdd=rates[:, 1:2, 1])

    # -- export -------------------------------------------------------------------------
    def columns(self, degrees: bool = False, *,
                units: Units | Mapping[str, str] | None = None) -> dict[str, np.ndarray]:
        """Every result as a named (N,) column ``item.quantity[unit]``, in chosen units.

        Inputs ``<input>.q``, ``.qd``, ``.qdd``; links ``<link>.angle``, ``.omega``,
        ``.alpha``, ``.K``, ``.L``; slides ``<joint>.slide``, ``.slide_velocity``,
        ``.slide_acceleration``, ``.K``, ``.L``; points ``<P>.x``, ``.y``, ``.vx``, ``.vy``,
        ``.ax``, ``.ay`` and ``<P>.x.K``, ``.x.L``, ``.y.K``, ``.y.L``; then ``det_J``,
        ``singularity``, ``singular`` (and ``assembled`` when some samples do not close),
        which have no unit.  With several inputs K and L name them: ``.K.<input>``,
        ``.L.<input>.<input>``.  Whitespace in a name becomes ``_``.  K and L carry the
        ratio of their units (``rocker.K[deg/deg]``, ``P.x.L[mm/deg^2]``).

        Parameters
        ----------
        degrees : bool
            Angles in degrees: shorthand for ``units={"angle": "deg"}``.
        units : Units or mapping, optional
            ``{"length": "mm", "angle": "deg"}``: lengths and angles in these units (rates
            per second, K and L in the ratios of these units); default SI (m, rad).

        Raises
        ------
        ModelError
            An unknown unit or key in ``units``, naming the allowed ones.

        Examples
        --------
        >>> sc = kl.mechanisms.slider_crank(crank=0.1, rod=0.3)
        >>> cols = kl.analyze(sc, q=np.radians([0.0, 90.0]), qd=1.0).columns(
        ...     units={"length": "mm", "angle": "deg"})
        >>> list(cols)[:4]
        ['jO2.q[deg]', 'jO2.qd[deg/s]', 'jO2.qdd[deg/s^2]', 'ground.angle[deg]']
        >>> cols["B.x[mm]"].round(6)                     # r + l; sqrt(l^2 - r^2)
        array([400.      , 282.842712])
        >>> round(float(cols["slide.K[mm/deg]"][1]), 6)  # dx/dq = -r = -100 mm/rad at 90 deg
        -1.745329
        """
        return dict(solution_columns(self, Units.resolve(units, degrees=degrees)))

    # to_dataframe(degrees=, units=) and to_csv(path, degrees=, units=): see TableExport

    def __repr__(self) -> str:
        sing = int(self.singular.sum())
        return (f"KinematicSolution('{self.mechanism.name}', N={self.N}, inputs="
                f"{list(self.input_names)}, singular samples={sing})")


def takes_solution(function):
    """``function`` with its first argument checked to be a :class:`KinematicSolution` (a
    mechanism given instead is the usual slip: the message says to analyze it first)."""
    @functools.wraps(function)
    def checked(sol, *args, **kwargs):
        if not isinstance(sol, KinematicSolution):
            hint = ("; analyze it first: kl.analyze(mechanism, q)" if isinstance(sol, Mechanism)
                    else "; get one from kinelab.analyze")
            got = (describe(sol) if sol is None or isinstance(sol, (str, int, float))
                   else f"a {type(sol).__name__}")
            raise ModelError(f"sol: expected a KinematicSolution, got {got}{hint}")
        return function(sol, *args, **kwargs)
    return checked


@dataclass(frozen=True, eq=False)
class DesignSolution(KinematicSolution):
    """The analysis of D designs of one mechanism's topology over N samples each
    (:func:`kinelab.kinematics.analyze_designs`).

    Its accessors are those of :class:`KinematicSolution`, with one more leading axis:
    ``angle(link)``, ``omega``, ``alpha``, ``slide(joint)`` ... have shape (D, N), a point's
    ``position`` (D, N, 2), ``K`` of an angle (D, N) or (D, N, M) with M inputs, and so on.
    ``q`` and the arrays of the samples (``singular``, ``assembled``, ``singularity``,
    ``det_J``) keep the D designs' samples one after the other, (D N, ...); reshape them with
    ``by_design``.

    Attributes
    ----------
    designs : int
        D.
    valid : ndarray of bool, shape (D,)
        The designs whose sketch the mechanism's plan takes (see ``Plan.designs``); the
        others' samples are not assembled (NaN).
    """

    designs: int = 1
    valid: np.ndarray | None = None

    @property
    def samples(self) -> int:
        """N, the samples of each design."""
        return self.q.shape[0] // self.designs

    def by_design(self, a: np.ndarray) -> np.ndarray:
        """An array over every design's samples, (D N, ...), as (D, N, ...)."""
        return np.reshape(a, (self.designs, self.samples) + np.shape(a)[1:])

    def _out(self, a: np.ndarray) -> np.ndarray:
        return self.by_design(a)

    def __repr__(self) -> str:
        return (f"DesignSolution('{self.mechanism.name}', designs={self.designs}, "
                f"N={self.samples}, inputs={list(self.input_names)}, "
                f"singular samples={int(self.singular.sum())})")
