"""The velocity constraints of a model at its sketch, in absolute coordinates.

Every moving link has a twist (3 unknowns in the plane, 6 in space; the ground's is
zero).  A joint between links ``a`` and ``b`` lets the relative twist ``t_b - t_a`` lie
only in the span of its freedom screws; the rows annihilating that span are its
constraint equations (``lambda - j`` of them for a pair of class ``Pj``).  Stacked, they
form the constraint Jacobian ``C``, and the motions the mechanism allows at the sketch are
its null space.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kinelab.model import Mechanism
from kinelab.structure._screws import Frame, annihilator, joint_screws

__all__ = ["ConstraintSystem"]


@dataclass(frozen=True, eq=False)
class ConstraintSystem:
    """Freedom screws and constraint rows of every joint of a model, at its sketch.

    Attributes
    ----------
    model : Mechanism
    planar : bool
        Planar twists ``(w, vx, vy)`` rather than spatial ones (spherical models are
        treated in space).
    dim : int
        3 or 6, the size of a twist.
    moving : tuple of str
        The moving links, in the order of the unknowns.
    frame : Frame
        The dimensionless frame the twists are written in.
    screws, constraints : dict of str to ndarray
        Per joint: freedom screws ``(f, dim)`` and constraint rows ``(dim - f, dim)``.
    notes : tuple of str
        Geometry that had to be assumed.
    """

    model: Mechanism
    planar: bool
    dim: int
    moving: tuple[str, ...]
    frame: Frame
    screws: dict
    constraints: dict
    notes: tuple[str, ...]

    @classmethod
    def of(cls, model: Mechanism) -> ConstraintSystem:
        planar = model.space == "planar"
        frame = Frame.of(model)
        screws, constraints, notes = {}, {}, []
        for j in model.joints:
            s, n = joint_screws(model, j, frame, planar)
            screws[j.name], constraints[j.name] = s, annihilator(s)
            notes += n
        moving = tuple(link.name for link in model.links if not link.ground)
        return cls(model, planar, 3 if planar else 6, moving, frame, screws, constraints,
                   tuple(notes))

    @property
    def unknowns(self) -> int:
        return self.dim * len(self.moving)

    def block(self, link: str) -> slice | None:
        """Columns of a link's twist among the unknowns (``None`` for the ground)."""
        if link not in self.moving:
            return None
        k = self.moving.index(link)
        return slice(self.dim * k, self.dim * (k + 1))

    def relative(self, a: str, b: str) -> np.ndarray:
        """``(dim, unknowns)``: the map from the unknowns to the twist of ``b`` relative to ``a``."""
        out = np.zeros((self.dim, self.unknowns))
        for link, sign in ((b, 1.0), (a, -1.0)):
            cols = self.block(link)
            if cols is not None:
                out[:, cols] += sign * np.eye(self.dim)
        return out

    def rows(self, joint: str) -> np.ndarray:
        """The joint's constraint equations on the unknowns."""
        a, b = self.model.joint(joint).links
        return self.constraints[joint] @ self.relative(a, b)

    def matrix(self) -> np.ndarray:
        """The constraint Jacobian ``C``, ``(sum of lambda - j, unknowns)``."""
        rows = [self.rows(j.name) for j in self.model.joints]
        return np.vstack(rows) if rows else np.zeros((0, self.unknowns))

    def point_velocity(self, point: str) -> np.ndarray:
        """``(d, dim)``: the velocity of a point carried by a body, from the body's twist."""
        p = self.frame.point(self.model, point)
        if self.planar:
            return np.array([[-p[1], 1.0, 0.0], [p[0], 0.0, 1.0]])
        px = np.array([[0.0, -p[2], p[1]], [p[2], 0.0, -p[0]], [-p[1], p[0], 0.0]])
        return np.hstack([-px, np.eye(3)])
