"""Grashof's criterion and Barker's classification of four-bar linkages."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe
from kinelab.mechanisms._catalogue import _positive
from kinelab.model import MAX_LENGTH, MIN_LENGTH, real, real_array

__all__ = ["Grashof", "grashof", "grashof_kinds"]

# Lengths are equal within rtol times their sum: beyond 1% a crank-rocker would pass for a
# change-point linkage.
MAX_RTOL = 1e-2


def _rtol(value: object) -> float:
    x = real(value)
    if x is None or not 0.0 <= x <= MAX_RTOL:
        raise ModelError(f"rtol: expected a number from 0 to {MAX_RTOL:g}, got {describe(value)}")
    return x


@dataclass(frozen=True)
class Grashof:
    """Grashof class of a four-bar.

    Attributes
    ----------
    kind : str
        ``"crank-rocker"`` (shortest link the crank), ``"double-crank"`` (shortest the
        ground; drag link), ``"double-rocker"`` (Grashof, shortest the coupler),
        ``"rocker-crank"`` (shortest the rocker), ``"change-point"`` (s + l = p + q) or
        ``"triple-rocker"`` (non-Grashof, s + l > p + q).
    barker : str
        Barker's code: GCCC, GCRR, GRCR, GRRC (Grashof, the shortest link 1 ground, 2 crank,
        3 coupler, 4 rocker); RRR1 ... RRR4 (non-Grashof, the longest link 1 ... 4); CCC,
        CRR, RCR, RRC (change-point, the shortest link 1 ... 4), S2X (change-point with two
        pairs of equal links) and S3X (all four equal).
    grashof : bool
        s + l <= p + q: some link turns fully relative to the others.
    crank_rotates, rocker_rotates : bool
        Whether the input and the output can turn full circle relative to the ground (on
        at least one assembly mode: see :func:`grashof`).
    margin : float
        (p + q) - (s + l), m: positive Grashof, zero change-point, negative non-Grashof.
    form : str or None
        ``"parallelogram"`` (opposite sides equal in pairs: ground = coupler and crank =
        rocker), ``"kite"`` (adjacent sides equal in pairs), ``"rhombus"`` (all four equal),
        else None.
    """

    kind: str
    barker: str
    grashof: bool
    crank_rotates: bool
    rocker_rotates: bool
    margin: float
    form: str | None = None


def grashof(ground: float, crank: float, coupler: float, rocker: float, *,
            rtol: float = 1e-12) -> Grashof:
    """Classify a four-bar by Grashof's criterion (s + l vs p + q) and Barker's classes.

    With s and l the shortest and longest links and p, q the others, a Grashof linkage
    (s + l < p + q) has a link that turns fully relative to the others, the shortest; the
    crank turns fully relative to the ground when it or the ground is the shortest, and so
    does the rocker.  A non-Grashof linkage (s + l > p + q) has none.

    In a change-point linkage (s + l = p + q) the four pivots come into line once or twice a
    turn, where the two assembly modes meet; kinelab's analysis goes on along the mode whose
    motion continues smoothly (:func:`kinelab.kinematics.change_points`).  Followed so, a
    link turns fully relative to the ground when it, or the ground, is among the shortest
    links.

    Lengths with two equal pairs (Barker's S2X and S3X) make different linkages on the two
    assembly modes, as :func:`fourbar` builds them:

    - a parallelogram (ground = coupler, crank = rocker) is the parallelogram on "open":
      the rocker turns with the crank, at its angle, and the coupler keeps its direction.
      On "crossed" it is the antiparallelogram: crank and rocker both turn fully, in
      opposite senses when the ground and coupler are the longer pair (the coupler rocks),
      in the same sense when they are the shorter pair (the coupler turns fully too, twice
      per turn of the crank);
    - a rhombus (all four equal) is the parallelogram on "open"; on "crossed" it folds: B
      stays on O2, the rocker stands still and the coupler turns with the crank;
    - a kite with ground = crank turns its crank fully when that pair is the shorter one;
      then the rocker turns fully too, once per two turns of the crank, on either mode;
    - a kite with ground = rocker folds as the rhombus does on "crossed" (B on O2, the
      rocker still); on "open" the rocker rocks when that pair is the longer one, and turns
      fully, twice per turn of the crank, when it is the shorter one.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths O2O4, O2A, AB, O4B, m (from 1e-9 m to 1e9 m, as every length of a
        model).
    rtol : float
        Lengths, and s + l against p + q, are taken as equal within ``rtol`` times the sum
        of the four lengths; from 0 to 0.01.

    Returns
    -------
    Grashof

    References
    ----------
    C. R. Barker, "A complete classification of planar four-bar linkages", *Mechanism and
    Machine Theory* 20 (6), 1985, pp. 535-554; R. L. Norton, *Design of Machinery*, ch. 2.

    Examples
    --------
    >>> kl.mechanisms.grashof(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5).kind
    'crank-rocker'
    >>> kl.mechanisms.grashof(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5).barker
    'RRR2'
    >>> g = kl.mechanisms.grashof(ground=100, crank=60, coupler=100, rocker=60)
    >>> g.kind, g.barker, g.form, g.crank_rotates, g.rocker_rotates
    ('change-point', 'S2X', 'parallelogram', True, True)
    """
    _positive(ground=ground, crank=crank, coupler=coupler, rocker=rocker)
    rtol = _rtol(rtol)
    lengths = {"ground": float(ground), "crank": float(crank), "coupler": float(coupler),
               "rocker": float(rocker)}
    values = list(lengths.values())
    s, l_ = min(values), max(values)
    margin = (sum(values) - s - l_) - (s + l_)
    tol = rtol * sum(values)
    shortest = {k for k, v in lengths.items() if v - s <= tol}     # ties only with two equal pairs
    only = min(lengths, key=lengths.get)

    def equal(a, b):
        return abs(lengths[a] - lengths[b]) <= tol
    opposite = equal("ground", "coupler") and equal("crank", "rocker")
    adjacent = ((equal("ground", "crank") and equal("coupler", "rocker"))
                or (equal("ground", "rocker") and equal("crank", "coupler")))
    form = ("rhombus" if opposite and adjacent else "parallelogram" if opposite
            else "kite" if adjacent else None)
    if form is not None or abs(margin) <= tol:
        if form is not None:
            code = "S3X" if form == "rhombus" else "S2X"
        else:
            code = {"ground": "CCC", "crank": "CRR", "coupler": "RCR", "rocker": "RRC"}[only]
        return Grashof("change-point", code, True, bool(shortest & {"crank", "ground"}),
                       bool(shortest & {"rocker", "ground"}), 0.0, form)
    if margin > 0:
        kind, code = {"ground": ("double-crank", "GCCC"), "crank": ("crank-rocker", "GCRR"),
                      "coupler": ("double-rocker", "GRCR"), "rocker": ("rocker-crank", "GRRC")}[only]
        return Grashof(kind, code, True, only in ("ground", "crank"),
                       only in ("ground", "rocker"), margin)
    longest = max(lengths, key=lengths.get)
    code = "RRR" + str(list(lengths).index(longest) + 1)
    return Grashof("triple-rocker", code, False, False, False, margin)


_GRASHOF_BY_SHORTEST = np.array(["double-crank", "crank-rocker", "double-rocker", "rocker-crank"],
                                object)


def grashof_kinds(ground: ArrayLike, crank: ArrayLike, coupler: ArrayLike, rocker: ArrayLike, *,
                  rtol: float = 1e-12) -> np.ndarray:
    """:attr:`Grashof.kind` of many four-bars at once: arrays of link lengths (broadcast
    together, m) in, an object array of the class names out (None where a length is not a
    positive number from 1e-9 m to 1e9 m, as NaN).  Anything but real numbers, or arrays
    that do not broadcast together, raise a ModelError.

    Examples
    --------
    >>> kl.mechanisms.grashof_kinds([3.0, 1.0, 1.0], 1.0, [3.0, 1.0, 2.0], [2.5, 1.0, 1.5]).tolist()
    ['crank-rocker', 'change-point', 'triple-rocker']
    """
    rtol = _rtol(rtol)
    arrays = {}
    for name, value in (("ground", ground), ("crank", crank), ("coupler", coupler),
                        ("rocker", rocker)):
        arrays[name] = real_array(value)
        if arrays[name] is None:
            raise ModelError(f"{name}: expected real numbers (lengths, m), got {describe(value)}")
    try:
        lengths = np.stack(np.broadcast_arrays(*arrays.values()))    # (4, ...)
    except ValueError:
        shapes = ", ".join(f"{k} {v.shape}" for k, v in arrays.items())
        raise ModelError(f"ground, crank, coupler, rocker: expected arrays of shapes that "
                         f"broadcast together, got {shapes}") from None
    with np.errstate(invalid="ignore"):
        good = ((lengths >= MIN_LENGTH) & (lengths <= MAX_LENGTH)).all(axis=0)
    lengths = np.where(good, lengths, 1.0)                          # None there, below
    total = lengths.sum(axis=0)
    s, l_ = lengths.min(axis=0), lengths.max(axis=0)
    margin = (total - s - l_) - (s + l_)
    tol = rtol * total

    def equal(a, b):
        return np.abs(lengths[a] - lengths[b]) <= tol
    opposite = equal(0, 2) & equal(1, 3)
    adjacent = (equal(0, 1) & equal(2, 3)) | (equal(0, 3) & equal(1, 2))
    change = opposite | adjacent | (np.abs(margin) <= tol)
    kinds = np.where(change, "change-point",
                     np.where(margin > 0, _GRASHOF_BY_SHORTEST[np.argmin(lengths, axis=0)],
                              "triple-rocker")).astype(object)
    kinds[~good] = None
    return kinds
