"""Grashof's criterion and Barker's classification of four-bar linkages."""
from __future__ import annotations

import math
from dataclasses import dataclass

from kinelab.errors import ModelError

__all__ = ["Grashof", "grashof"]


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
        Barker's code: GCRR, GCCC, GRCR, GRRC; RRR1 ... RRR4 (the longest link is 1 ground,
        2 crank, 3 coupler, 4 rocker); CP for change-point linkages.
    grashof : bool
        s + l <= p + q: some link turns fully relative to the others.
    crank_rotates, rocker_rotates : bool
        Whether the input and the output turn full circle relative to the ground.
    margin : float
        (p + q) - (s + l), m: positive Grashof, zero change-point, negative non-Grashof.
    """

    kind: str
    barker: str
    grashof: bool
    crank_rotates: bool
    rocker_rotates: bool
    margin: float


def grashof(ground: float, crank: float, coupler: float, rocker: float, *,
            rtol: float = 1e-12) -> Grashof:
    """Classify a four-bar by Grashof's criterion (s + l vs p + q) and Barker's classes.

    Examples
    --------
    >>> kl.mechanisms.grashof(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5).kind
    'crank-rocker'
    >>> kl.mechanisms.grashof(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5).barker
    'RRR2'
    """
    lengths = {"ground": ground, "crank": crank, "coupler": coupler, "rocker": rocker}
    bad = [f"{k}: expected a positive length (m), got {v!r}" for k, v in lengths.items()
           if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0)]
    if bad:
        raise ModelError(bad)
    values = list(lengths.values())
    s, l_ = min(values), max(values)
    margin = (sum(values) - s - l_) - (s + l_)
    tol = rtol * sum(values)
    shortest = min(lengths, key=lengths.get)
    if abs(margin) <= tol:
        crank_ok = shortest in ("crank", "ground")
        rocker_ok = shortest in ("rocker", "ground")
        return Grashof("change-point", "CP", True, crank_ok, rocker_ok, 0.0)
    if margin > 0:
        kind, code = {"ground": ("double-crank", "GCCC"), "crank": ("crank-rocker", "GCRR"),
                      "coupler": ("double-rocker", "GRCR"), "rocker": ("rocker-crank", "GRRC")}[shortest]
        return Grashof(kind, code, True, shortest in ("ground", "crank"),
                       shortest in ("ground", "rocker"), margin)
    longest = max(lengths, key=lengths.get)
    code = "RRR" + str(list(lengths).index(longest) + 1)
    return Grashof("triple-rocker", code, False, False, False, margin)
