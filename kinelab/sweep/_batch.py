"""The kinematics of many designs at many inputs: arrays of shape (D, S).

Two ways to fill them: the kernel, over a chunk's designs and samples in one call
(:func:`kinelab.kinematics.analyze_designs`), for any family, and closed forms vectorised
over designs and samples for the catalogue four-bar (:class:`FourbarBatch`).
"""
from __future__ import annotations

import functools

import numpy as np

from kinelab.errors import ModelError, expected_one_of
from kinelab.kinematics import SINGULAR_TOL, analyze, analyze_designs
# the engine's own closure test for an RRR dyad: the closed form assembles exactly where
# kinelab.analyze does (change-point four-bars included)
from kinelab.kinematics._interpreter import arms_fold, rrr_closure
from kinelab.solvers import wrap_angle
from kinelab.synthesis import coupler_curves

__all__ = ["Batch", "DesignsBatch", "FourbarBatch"]


def _pick(table: dict[str, np.ndarray], name: str, what: str, nan_shape=None) -> np.ndarray:
    try:
        return table[name]
    except (KeyError, TypeError):
        if nan_shape is not None:       # no design of the chunk was built: nothing to check
            return np.full(nan_shape, np.nan)
        raise ModelError(f"{what}: {expected_one_of(name, table)}") from None


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
        good = np.array([not p for p in designs.problems], bool) & (self.template is not None)
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

    def position(self, point):
        return self._gather("position", point, self._names("position"), "point")

    def slide(self, joint):
        return self._gather("slide", joint, self._names("slide"), "prismatic joint")

    def value(self, name):
        return self.angle(name) if name in self._names("angle") else self.slide(name)


class FourbarBatch(Batch):
    """The catalogue four-bar in closed form (O2 at the origin, O4 at (ground, 0), q the crank
    angle), vectorised over designs and samples; each quantity is computed when first asked.

    ``lengths`` are (D, 1) columns ground, crank, coupler, rocker; ``point`` the coupler point
    (along AB, to its left) as (D, 1) columns or None; ``sigma`` +1 "open", -1 "crossed".
    """

    _LINKS = ("ground", "crank", "coupler", "rocker")

    def __init__(self, q, lengths, point, sigma: float):
        self.q = q
        self.r1, self.r2, self.r3, self.r4 = lengths
        self.point = point
        self.sigma = sigma

    @functools.cached_property
    def _pivot_distance2(self):
        """|O4 A|^2, (D, S): every assembly question is a question about it.  Computed as the
        engine computes it, from A's coordinates, so that a design at a change point
        (s + l = p + q) assembles, or not, exactly where kinelab.analyze says."""
        q = self.q
        # the same samples for every design (a broadcast view): one row of cosines and sines
        row = q[:1] if q.strides[0] == 0 else q
        dx = self.r1 - self.r2 * np.cos(row)
        dy = self.r2 * np.sin(row)
        return dx * dx + dy * dy

    @functools.cached_property
    def _cos_mu(self):
        """Cosine of the angle at B between BA and BO4 (law of cosines)."""
        return (self.r3 ** 2 + self.r4 ** 2 - self._pivot_distance2) / (2 * self.r3 * self.r4)

    @functools.cached_property
    def assembled(self):
        # the engine's test for an RRR dyad (coupler, rocker) across |O4 A|
        folded, _, _, _, fail = rrr_closure(self.r3, self.r4, self._pivot_distance2)
        return ~fail & (~folded | arms_fold(self.r3, self.r4))

    @functools.cached_property
    def singular(self):
        """Where the transmission angle's sine falls below SINGULAR_TOL, as the engine flags."""
        return self.assembled & (np.sqrt(np.maximum(1.0 - self._cos_mu ** 2, 0.0)) < SINGULAR_TOL)

    def passes_singular(self) -> np.ndarray:
        """Whether the turn of each design passes a singular configuration (D,): the
        transmission angle's sine (the engine's singularity measure) falls below
        kinelab.kinematics.SINGULAR_TOL somewhere, as it does at a change point.  |cos mu|
        is largest at q = 0 or pi, where |O4 A| is smallest or largest."""
        worst = np.zeros(len(self.r1))
        for d in (np.abs(self.r1 - self.r2), self.r1 + self.r2):
            c = (self.r3 ** 2 + self.r4 ** 2 - d * d) / (2 * self.r3 * self.r4)
            worst = np.maximum(worst, np.abs(c[:, 0]))
        return np.sqrt(np.maximum(1.0 - worst * worst, 0.0)) < SINGULAR_TOL

    @functools.cached_property
    def _curves(self):
        D, S = self.q.shape
        zeros = np.zeros(D)
        u, v = (zeros, zeros) if self.point is None else (self.point[0][:, 0], self.point[1][:, 0])
        designs = np.column_stack([zeros, zeros, self.r1[:, 0], zeros, self.r2[:, 0], self.r3[:, 0],
                                   self.r4[:, 0], u, v, np.full(D, self.sigma)])
        P, A, B, ok = coupler_curves(designs, self.q)
        # where the engine closes the dyad at its straight position and rounding does not
        missing = ~(self.assembled & (self._pivot_distance2 > 0))[..., None]
        return {"A": A, "B": np.where(missing, np.nan, B), "P": np.where(missing, np.nan, P)}

    @functools.cached_property
    def _angles(self):
        A, B = self._curves["A"], self._curves["B"]
        theta3 = np.arctan2(B[..., 1] - A[..., 1], B[..., 0] - A[..., 0])
        theta4 = np.arctan2(B[..., 1], B[..., 0] - self.r1)
        return {"ground": np.where(self.assembled, 0.0, np.nan),
                "crank": np.where(self.assembled, wrap_angle(self.q), np.nan),
                "coupler": theta3, "rocker": theta4}

    @functools.cached_property
    def _K(self):
        # From the derivative of the loop r2 e2 + r3 e3 - r4 e4 - r1 = 0, projected on the
        # normals of the coupler and the rocker.
        t2, t3, t4 = self.q, self._angles["coupler"], self._angles["rocker"]
        s34 = np.sin(t3 - t4)
        return {"ground": np.where(self.assembled, 0.0, np.nan),
                "crank": np.where(self.assembled, 1.0, np.nan),
                "coupler": self.r2 * np.sin(t4 - t2) / (self.r3 * s34),
                "rocker": self.r2 * np.sin(t3 - t2) / (self.r4 * s34)}

    def angle(self, link):
        return _pick(self._angles, link, "link")

    def K(self, name):
        return _pick(self._K, name, "link")

    def position(self, point):
        if point == "O2":
            return np.where(self.assembled[..., None], 0.0, np.nan) * np.ones(2)
        if point == "O4":
            return np.where(self.assembled[..., None],
                            np.stack([self.r1 + 0 * self.q, 0 * self.q], -1), np.nan)
        names = ("O2", "A", "B", "O4") + (("P",) if self.point is not None else ())
        if point not in names:
            raise ModelError(f"point: {expected_one_of(point, names)}")
        if point == "A":
            return np.where(self.assembled[..., None], self._curves["A"], np.nan)
        return self._curves[point]

    def slide(self, joint):
        raise ModelError(f"prismatic joint: the four-bar has none, got {joint!r}")

    def value(self, name):
        return self.angle(name)

    def transmission(self, links):
        if tuple(links) in (("coupler", "rocker"), ("rocker", "coupler")):
            return np.where(self.assembled, np.arccos(np.minimum(np.abs(self._cos_mu), 1.0)), np.nan)
        return super().transmission(links)

    def transmission_range(self, links):
        if tuple(links) in (("coupler", "rocker"), ("rocker", "coupler")):
            # the acute angle is arccos |cos mu|, decreasing in |cos mu|: two arccos per design
            c = np.where(self.assembled, np.abs(self._cos_mu), np.nan)
            return np.arccos(np.minimum(c.max(axis=1), 1.0)), np.arccos(c.min(axis=1))
        return super().transmission_range(links)
