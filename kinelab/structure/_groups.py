"""Lie groups of rigid displacements (*Mecanismos*, §2.2), held by their Lie algebras.

A subgroup of the displacements of a rigid body (Hervé's classification: translations
T, rotations R, screw motions H, cylindrical C, planar translations T2, planar gliding G,
spherical S, translating screw Y, spatial translations T3, Schoenflies X, all of them D)
is known by its Lie algebra: the subspace of twists it contains.  Two facts make the
method of the notes work:

- a serial leg whose joints generate a subgroup (three parallel R joints generate the
  planar gliding G = {Tx, Tz, Ry}) moves its last link over exactly that subgroup;
- the motions a parallel mechanism allows its end link are the intersection of the
  subgroups of its legs, and the Lie algebra of an intersection is the intersection of
  the Lie algebras.

Twists are ``(w, v)`` with ``v`` the velocity of the body point at the origin, in m/s for
1 rad/s; the label names the translations and rotations they contain, in the notes'
style ``{Tx, Tz, Ry}``.
"""
from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError
from kinelab.structure._screws import RTOL, checked_rtol, null_basis, rank, row_basis

__all__ = ["DisplacementGroup", "displacement_group", "generated_group"]

_AXES = "xyz"


def _bracket(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Lie bracket of two twists: ``(wa x wb, wa x vb - wb x va)``."""
    return np.concatenate([np.cross(a[:3], b[:3]), np.cross(a[:3], b[3:]) - np.cross(b[:3], a[3:])])


def _intersect(a: np.ndarray, b: np.ndarray, rtol: float) -> np.ndarray:
    """Rows spanning the intersection of the row spaces of ``a`` and ``b`` (orthonormal)."""
    if len(a) == 0 or len(b) == 0:
        return np.zeros((0, a.shape[1]))
    x = null_basis(np.vstack([a, -b]).T, rtol, scale=1.0)
    if x.shape[1] == 0:
        return np.zeros((0, a.shape[1]))
    return row_basis((a.T @ x[:len(a)]).T, rtol, scale=1.0)


def _direction_names(u: np.ndarray, kind: str, tol: float) -> list[str]:
    """``['Tx', 'Tz']`` if the rows of ``u`` span coordinate axes, else the directions."""
    axes = [k for k in range(3) if np.linalg.norm(u @ np.eye(3)[k]) > 1 - tol]
    if len(axes) == len(u):
        return [f"{kind}{_AXES[k]}" for k in axes]
    out = []
    for d in u:
        d = d * np.sign(d[np.argmax(np.abs(d))])
        out.append(f"{kind}({', '.join(f'{c:.3g}' for c in d + 0.0)})")
    return out


@dataclass(frozen=True, eq=False)
class DisplacementGroup:
    """A group of rigid displacements, as the subspace of twists it contains.

    Build one with :func:`displacement_group` (from a label such as ``"Tx Tz Ry"``) or
    :func:`generated_group` (from joint screws), or get it from :func:`connectivity`
    and :func:`lie_mobility`.  ``g & h`` is the intersection; ``g <= h`` tests inclusion;
    ``g == h`` tests equality.

    Attributes
    ----------
    twists : ndarray, shape (d, 6)
        Orthonormal basis of the twists (``w``, ``v / length``).
    length : float
        Unit of length of the linear parts (m), so that rotations and translations weigh
        alike; the size of the model the group comes from.
    """

    twists: np.ndarray
    length: float = 1.0

    def __post_init__(self):
        t = np.array(self.twists, dtype=float).reshape(-1, 6)
        t.setflags(write=False)
        object.__setattr__(self, "twists", t)

    # -- in a common unit of length -----------------------------------------------------
    def _in(self, length: float) -> np.ndarray:
        t = self.twists.copy()
        t[:, 3:] *= self.length / length
        return row_basis(t, scale=1.0) if len(t) else t

    def _common(self, other: DisplacementGroup):
        if not isinstance(other, DisplacementGroup):
            raise ModelError(f"expected a DisplacementGroup, got {type(other).__name__}")
        length = max(self.length, other.length)
        return self._in(length), other._in(length), length

    @property
    def dim(self) -> int:
        """Dimension of the group: how many independent displacements it contains."""
        return len(self.twists)

    def __and__(self, other: DisplacementGroup) -> DisplacementGroup:
        a, b, length = self._common(other)
        return DisplacementGroup(_intersect(a, b, RTOL), length)

    def __le__(self, other: DisplacementGroup) -> bool:
        a, b, _ = self._common(other)
        return rank(np.vstack([b, a]), scale=1.0) == len(b) if len(a) else True

    def __eq__(self, other) -> bool:
        if not isinstance(other, DisplacementGroup):
            return NotImplemented
        return self.dim == other.dim and self <= other

    __hash__ = None

    # -- what it contains ----------------------------------------------------------------
    @property
    def translations(self) -> np.ndarray:
        """``(t, 3)``: orthonormal directions of the pure translations it contains."""
        # The basis is orthonormal, so 1 is the scale of every quantity below.
        w = self.twists[:, :3]
        x = null_basis(w.T, scale=1.0) if len(w) else np.zeros((0, 0))
        if x.shape[1] == 0:
            return np.zeros((0, 3))
        return row_basis((self.twists.T @ x).T[:, 3:], scale=1.0)

    @property
    def rotations(self) -> np.ndarray:
        """``(r, 3)``: orthonormal directions of the angular velocities it contains."""
        return row_basis(self.twists[:, :3], scale=1.0) if self.dim else np.zeros((0, 3))

    @property
    def pitch(self) -> float:
        """Pitch (m/rad) of its screw motion when it has one rotation direction, else 0."""
        r, t = self.rotations, self.translations
        if len(r) != 1:
            return 0.0
        w = r[0]
        coef = np.linalg.lstsq(self.twists[:, :3].T, w, rcond=None)[0]
        v = self.twists.T[3:] @ coef
        v = v - t.T @ (t @ v) if len(t) else v
        h = float(w @ v)
        return h * self.length if abs(h) > 1e-9 else 0.0

    @property
    def kind(self) -> str:
        """Hervé's symbol: E, T, R, H, T2, C, T3, G, S, Y, X or D ('' if none fits)."""
        t, r = len(self.translations), len(self.rotations)
        if r == 0:
            return {0: "E", 1: "T", 2: "T2", 3: "T3"}[t]
        helical = self.pitch != 0.0
        table = {(0, 1): "H" if helical else "R", (1, 1): "C", (2, 1): "Y" if helical else "G",
                 (3, 1): "X", (0, 3): "S", (3, 3): "D"}
        return table.get((t, r), "")

    @property
    def label(self) -> str:
        """The displacements it contains, as in the notes: ``'{Tx, Tz, Ry}'``."""
        names = _direction_names(self.translations, "T", 1e-9)
        kind = "H" if self.pitch else "R"
        names += _direction_names(self.rotations, kind, 1e-9)
        return "{" + ", ".join(names) + "}"

    def __repr__(self) -> str:
        return f"DisplacementGroup({self.label!r}, kind={self.kind!r})"


def generated_group(screws: ArrayLike, *, length: float = 1.0,
                    rtol: float = RTOL) -> DisplacementGroup:
    """The smallest group of displacements containing the given twists.

    The twists are closed under the Lie bracket until the subspace stops growing; a leg
    whose joint screws already span a closed subspace moves over exactly that group.

    Parameters
    ----------
    screws : array_like, shape (k, 6)
        Twists ``(w, v)``, ``v`` in units of ``length``.
    length : float, optional
        Unit of length of ``v`` (m).

    Examples
    --------
    Two R joints with parallel axes generate the planar gliding group; two whose axes
    cross at a point generate the rotations about that point.

    >>> from kinelab.structure import generated_group
    >>> generated_group([[0, 1, 0, 0, 0, 0], [0, 1, 0, 1, 0, 0]]).label
    '{Tx, Tz, Ry}'
    >>> generated_group([[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0]]).kind
    'S'
    """
    rtol = checked_rtol(rtol)
    basis = np.asarray(screws, dtype=float).reshape(-1, 6)
    basis = row_basis(basis, rtol) if len(basis) else basis
    while True:
        brackets = [_bracket(a, b) for i, a in enumerate(basis) for b in basis[i + 1:]]
        grown = row_basis(np.vstack([basis, *brackets]), rtol) if brackets else basis
        if len(grown) == len(basis):
            return DisplacementGroup(basis, length)
        basis = grown


_TOKEN = re.compile(r"^([TR])([xyz])$")


def displacement_group(label: str | Sequence[str], *, point: ArrayLike = (0.0, 0.0, 0.0)
                       ) -> DisplacementGroup:
    """A group of displacements from its label, in the notes' notation.

    Parameters
    ----------
    label : str or sequence of str
        Translations ``Tx``, ``Ty``, ``Tz`` and rotations ``Rx``, ``Ry``, ``Rz``, as in
        ``"{Tx, Tz, Ry}"`` or ``"Tx Tz Ry"``.
    point : array_like, shape (3,)
        Where the rotation axes pass (m).

    Raises
    ------
    ModelError
        For an unknown token, or displacements that do not form a group (then the
        message names the group they generate).

    Examples
    --------
    >>> from kinelab.structure import displacement_group
    >>> g = displacement_group("{Tx, Tz, Ry}")
    >>> g.kind, g.dim
    ('G', 3)
    >>> (g & displacement_group("Ty Tz Rx")).label
    '{Tz}'
    """
    tokens = (re.split(r"[\s,{}]+", label) if isinstance(label, str) else list(label))
    tokens = [t for t in tokens if t]
    p = np.asarray(point, dtype=float)
    length = max(1.0, float(np.linalg.norm(p)))  # keeps v of the order of w
    rows = []
    for tok in tokens:
        m = _TOKEN.match(tok)
        if m is None:
            raise ModelError(f"displacement '{tok}': expected Tx, Ty, Tz, Rx, Ry or Rz")
        e = np.eye(3)[_AXES.index(m.group(2))]
        rows.append(np.concatenate([np.zeros(3), e]) if m.group(1) == "T"
                    else np.concatenate([e, np.cross(p, e) / length]))
    rows = np.array(rows).reshape(-1, 6)
    given = DisplacementGroup(row_basis(rows) if len(rows) else rows, length)
    closed = generated_group(rows, length=length)
    if closed.dim != given.dim:
        raise ModelError(f"displacements {given.label} do not form a group: combining them "
                         f"produces {closed.label} ({closed.kind}); use that label, or "
                         "describe the motion by counts for type synthesis")
    return given
