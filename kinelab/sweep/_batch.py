"""The kinematics of many designs at many inputs: arrays of shape (D, S), filled by one call
of the kernel over a chunk's designs and samples (:func:`kinelab.kinematics.analyze_designs`),
for every family, the four-bar as the others.
"""
from __future__ import annotations

import numpy as np

from kinelab.errors import ModelError, expected_one_of
from kinelab.kinematics import analyze, analyze_designs
from kinelab.solvers import wrap_angle

__all__ = ["Batch", "DesignsBatch"]


class Batch:
    """Kinematics of D designs at S input values each, the named accessors of
    :class:`~kinelab.KinematicSolution` with a leading design axis.

    Attributes
    ----------
    q : ndarray, shape (D, S)
        The input of each design at each sample, rad.
    assembled : ndarray of bool, shape (D, S)
        Whether the design closes its loops there; elsewhere every value is NaN.
    singular : ndarray of bool, shape (D, S)
        Whether it is singular there, as :func:`kinelab.analyze` flags it.

    Angles come in (-pi, pi]; ``K`` is the velocity coefficient d(angle or slide)/dq.
    """

    q: np.ndarray
    assembled: np.ndarray
    singular: np.ndarray

    def angle(self, link: str) -> np.ndarray:
        """Angle of a link, rad, (D, S)."""
        raise NotImplementedError

    def K(self, name: str) -> np.ndarray:
        """Velocity coefficient of a link's angle or a prismatic joint's slide, (D, S)."""
        raise NotImplementedError

    def L(self, name: str) -> np.ndarray:
        """Acceleration coefficient d2(angle or slide)/dq2 = dK/dq, (D, S)."""
        raise NotImplementedError

    def position(self, point: str) -> np.ndarray:
        """Position of a point, m, (D, S, 2)."""
        raise NotImplementedError

    def slide(self, joint: str) -> np.ndarray:
        """Slide of a prismatic joint, m, (D, S)."""
        raise NotImplementedError

    def value(self, name: str) -> np.ndarray:
        """A link's angle or a prismatic joint's slide, whichever ``name`` is."""
        raise NotImplementedError

    def transmission(self, links: tuple[str, str]) -> np.ndarray:
        """Acute angle between two links, rad, in [0, pi/2], (D, S)."""
        mu = np.abs(wrap_angle(self.angle(links[0]) - self.angle(links[1])))
        return np.minimum(mu, np.pi - mu)

    def transmission_range(self, links: tuple[str, str]) -> tuple[np.ndarray, np.ndarray]:
        """Smallest and largest transmission angle over the samples, (D,) each (NaN for a
        design that does not assemble at every sample)."""
        mu = self.transmission(links)
        return mu.min(axis=1), mu.max(axis=1)

    @property
    def shape(self) -> tuple[int, int]:
        return self.q.shape


class DesignsBatch(Batch):
    """A chunk of designs at their samples, from one call of the kernel for all of them
    (:func:`kinelab.kinematics.analyze_designs`), and one :func:`kinelab.analyze` for each
    design whose sketch the family's plan cannot take; NaN where a design could not be
    built or does not assemble.  Each quantity is gathered when first asked."""

    def __init__(self, designs, q: np.ndarray):
        self.q = q
        D, S = q.shape
        self.template = designs.template
        good = designs.usable() & (self.template is not None)
        self._rows = np.flatnonzero(good)
        self._sol = None
        self._alone: dict[int, object] = {}
        self.assembled = np.zeros((D, S), bool)
        self.singular = np.zeros((D, S), bool)
        if len(self._rows):
            axes = {n: a[good] for n, a in designs.axes.items()}
            sol = analyze_designs(self.template, designs.points[good], q[good], axes=axes or None)
            self._sol = sol
            self.assembled[good] = sol.by_design(sol.assembled)
            self.singular[good] = sol.by_design(sol.singular)
            for d in self._rows[~sol.valid]:
                mech = designs.mechanism(d)
                if mech is not None:
                    alone = analyze(mech, q[d], unreachable="mask", at_singular="flag")
                    self._alone[d] = alone
                    self.assembled[d], self.singular[d] = alone.assembled, alone.singular
        self._cache: dict[tuple[str, str], np.ndarray] = {}

    def _gather(self, kind: str, name: str, names, what: str) -> np.ndarray:
        key = (kind, name)
        if key not in self._cache:
            tail = (2,) if kind == "position" else ()
            if self.template is not None and name not in names:
                raise ModelError(f"{what}: {expected_one_of(name, names)}")
            out = np.full(self.q.shape + tail, np.nan)
            if self._sol is not None:
                out[self._rows] = getattr(self._sol, kind)(name)
            for d, alone in self._alone.items():
                out[d] = getattr(alone, kind)(name)
            self._cache[key] = wrap_angle(out) if kind == "angle" else out
        return self._cache[key]

    def _names(self, kind: str) -> tuple[str, ...]:
        t = self.template
        if t is None:
            return ()
        slides = tuple(j.name for j in t.joints if j.type == "P")
        return {"angle": t.link_names, "K": t.link_names + slides, "position": t.point_names,
                "slide": slides}[kind]

    def angle(self, link):
        return self._gather("angle", link, self._names("angle"), "link")

    def K(self, name):
        return self._gather("K", name, self._names("K"), "link or prismatic joint")

    def L(self, name):
        return self._gather("L", name, self._names("K"), "link or prismatic joint")

    def position(self, point):
        return self._gather("position", point, self._names("position"), "point")

    def slide(self, joint):
        return self._gather("slide", joint, self._names("slide"), "prismatic joint")

    def value(self, name):
        return self.angle(name) if name in self._names("angle") else self.slide(name)
