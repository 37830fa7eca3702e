"""Errors about input values that keep the values as data, so that a model file's commands
can say them in the file's units and input names (:meth:`saying`), where Python callers read
them in SI with Python's advice."""
from __future__ import annotations

from kinelab.errors import AssemblyError, SingularityError, describe
from kinelab.kinematics._columns import INPUT_SI_UNITS
from kinelab.model import Units

__all__ = ["UnreachableInput", "SingularInput"]


def _values(q, kinds, u: Units, names: tuple[str, ...], digits: int = 6) -> str:
    """``q = 2 rad``, ``q = (2 rad, 0.1 m)``, or with the inputs' names ``'crank' = 114.6 deg``."""
    shown = [f"{float(u.convert(v, INPUT_SI_UNITS[k])):.{digits}g} {u.unit(INPUT_SI_UNITS[k])}"
             for v, k in zip(q, kinds)]
    if names:
        return ", ".join(f"{describe(n)} = {v}" for n, v in zip(names, shown))
    return "q = " + (shown[0] if len(shown) == 1 else f"({', '.join(shown)})")


class UnreachableInput(AssemblyError):
    """Input values where the loops do not close, or where the motion cannot follow from
    the sketch: ``q`` the first such values (SI, one per input), ``kinds`` the inputs'
    kinds ('angle' or 'slide'), ``stalled`` whether the motion stopped at a limit position
    or a singular configuration (else ``loop`` misses by ``gap`` metres), ``reachable`` the
    intervals of a single input that do assemble.  :meth:`saying` words it in a model
    file's units and input names."""

    __module__ = "kinelab.kinematics"      # where users find it
    instead = "a value within reach"        # what a model file's user is asked to give

    def __init__(self, loop: str, q, kinds, *, stalled: bool, gap: float,
                 reachable: list[tuple[float, float]] | None):
        self.q, self.kinds, self.stalled = tuple(float(v) for v in q), tuple(kinds), stalled
        super().__init__("", loop=loop, gap=gap, reachable=reachable)
        self.args = (self.saying() + "; narrow the input range (or pass unreachable='mask')",)

    def saying(self, units: Units | None = None, names: tuple[str, ...] = ()) -> str:
        """The failure, input values and lengths in ``units`` (default SI); with the
        inputs' ``names``, each value is named (``jO2 = 30 deg``), else written ``q = ...``."""
        u = units or Units()
        bounds = [float(u.convert(b, INPUT_SI_UNITS[self.kinds[0]]))
                  for span in self.reachable or () for b in span]
        digits = 6
        if len(self.q) == 1:
            digits = _telling_digits(float(u.convert(self.q[0], INPUT_SI_UNITS[self.kinds[0]])),
                                     bounds)
        at = _values(self.q, self.kinds, u, names, digits)
        if self.stalled:
            text = (f"{self.loop} cannot follow the motion to {at}: the continuation stopped at "
                    "a limit position or a singular configuration")
        else:
            text = (f"{self.loop} cannot close at {at}: it misses by "
                    f"{float(u.convert(self.gap, 'm')):.6g} {u.length}")
        if self.reachable is not None:
            spans = ", ".join(f"[{lo:.{digits}g}, {hi:.{digits}g}]"
                              for lo, hi in zip(bounds[::2], bounds[1::2]))
            who = f"{describe(names[0])} reaches" if names else "reachable q is"
            text += (f"; {who} {spans} {u.unit(INPUT_SI_UNITS[self.kinds[0]])}" if self.reachable
                     else "; it assembles nowhere near the sketch")
        return text


def _telling_digits(value: float, bounds: list[float]) -> int:
    """Significant digits (6 or more) that tell ``value`` apart from each of ``bounds`` in
    print: an input just past a limit position must not read as the limit itself."""
    digits = 6
    while digits < 17 and any(b != value and f"{b:.{digits}g}" == f"{value:.{digits}g}"
                              for b in bounds):
        digits += 1
    return digits


class SingularInput(SingularityError):
    """Input values ``q`` (SI; ``kinds`` 'angle' or 'slide') at a singular configuration
    (det J = ``det``, nearly 0), where positions exist but velocities and accelerations do
    not; ``sample`` is its index in a solution, when it is one of several.

    ``kind`` says which: a ``"limit position"`` (a fold: the input cannot go past it, and
    the output's speed grows without bound as it comes near; ``reachable`` holds the
    intervals the input does reach), a ``"change point"`` (two assembly modes of ``links``
    meet and cross: the motion goes on through it on either, with finite speeds along
    each, but which one it takes is not decided at the point itself), or a ``"singular
    configuration"`` of another kind.  ``at`` is the input value of the limit position or
    change point, which ``q`` is at or next to (within the rounding that makes K and L
    untrustworthy there)."""

    __module__ = "kinelab.kinematics"
    instead = "a value off it"

    def __init__(self, q, kinds, *, det: float = float("nan"), sample: int | None = None,
                 kind: str = "singular configuration", links: str = "",
                 reachable: list[tuple[float, float]] | None = None, at: float | None = None,
                 advice: str = "move the input off it, or pass at_singular='flag' to get the "
                               "positions with the sample flagged"):
        self.q, self.kinds = tuple(float(v) for v in q), tuple(kinds)
        self.det, self.sample = det, sample
        self.kind, self.links, self.reachable, self.at = kind, links, reachable, at
        super().__init__(f"{self.saying()}; {advice}")

    def saying(self, units: Units | None = None, names: tuple[str, ...] = ()) -> str:
        """The configuration, input values in ``units`` (default SI), named by ``names``."""
        u = units or Units()
        where = "" if self.sample is None else f"sample {self.sample}: "
        det = "0" if self.det != self.det else f"{self.det + 0.0:.3g}"     # no "-0"
        bounds = [float(u.convert(b, INPUT_SI_UNITS[self.kinds[0]]))
                  for span in self.reachable or () for b in span]
        digits = 6
        if len(self.q) == 1 and bounds:
            digits = _telling_digits(float(u.convert(self.q[0], INPUT_SI_UNITS[self.kinds[0]])),
                                     bounds)
        at = f"{where}{_values(self.q, self.kinds, u, names, digits)}"
        place = f"is a {self.kind}"
        detail = f"det J = {det}"
        if self.kind in ("limit position", "change point") and self.at is not None:
            kind = self.kinds[0]
            # located to about 1e-12: nearer than 1e-9 (rad, or sizes) is at it
            if abs(self.q[0] - self.at) > 1e-9 * max(1.0, abs(self.at)):
                point = float(u.convert(self.at, INPUT_SI_UNITS[kind]))
                value = float(u.convert(self.q[0], INPUT_SI_UNITS[kind]))
                point = 0.0 if abs(point) < 1e-9 * max(1.0, abs(value)) else point
                place = f"is next to a {self.kind}"
                detail = (f"at {point:.{max(digits, _telling_digits(point, [value]))}g} "
                          f"{u.unit(INPUT_SI_UNITS[kind])}; {detail}")
        if self.kind == "limit position":
            spans = ", ".join(f"[{lo:.{digits}g}, {hi:.{digits}g}]"
                              for lo, hi in zip(bounds[::2], bounds[1::2]))
            who = f"{describe(names[0])} reaches" if names else "q reaches"
            return (f"{at} {place} ({detail}): the input cannot go past it, and "
                    "velocities and accelerations are unbounded there; "
                    f"{who} {spans} {u.unit(INPUT_SI_UNITS[self.kinds[0]])}")
        if self.kind == "change point":
            return (f"{at} {place} of {self.links} ({detail}): two assembly modes meet and "
                    "cross there; the motion goes on through it, on the branch a sweep "
                    "follows, but velocities and accelerations are not defined at the point"
                    + ("" if place.startswith("is a") else ", nor computed this near it"))
        return (f"{at} is a singular configuration (det J = {det}): positions exist but "
                "velocities and accelerations are not defined there")
