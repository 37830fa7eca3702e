"""Units of length and angle: the tables, and the conversion of SI results at the edges.

kinelab works in SI (m, rad, s) inside.  A model file declares the units it is written in;
its results go out in those units (or in SI when asked).  :class:`Units` is the one place
where an SI value and the name of its unit are converted: results export, summaries, printed
configurations and figures all call :meth:`Units.convert` and :meth:`Units.unit`.

A unit is named by its SI spelling, a product of powers of base units over another one:
``"m"``, ``"rad/s^2"``, ``"m/rad^2"``, ``"m/(rad*m)"``, ``"N*m"``.  Lengths (``m``) and
angles (``rad``) convert; seconds (``s``) stay.  Forces, torques, energies and powers stay
in SI (N, N*m, J, W) and are not converted here.
"""
from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Literal

import numpy as np

from kinelab.errors import ModelError, describe, expected_one_of, quoted, suggest

__all__ = ["LENGTH_UNITS", "ANGLE_UNITS", "Units"]

LENGTH_UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
"""Metres per length unit."""
ANGLE_UNITS = {"rad": 1.0, "deg": math.pi / 180.0}
"""Radians per angle unit."""

_FACTOR = re.compile(r"^(m|rad|s)(?:\^(\d+))?$")


@dataclass(frozen=True)
class Units:
    """The units of lengths and angles: those a model file is written in, or those results
    are asked for.

    ``Units()`` is SI (m, rad).  Time is always in seconds; forces, torques, energies and
    powers stay in SI (N, N*m, J, W).

    Examples
    --------
    >>> u = Units("mm", "deg")
    >>> u.length_scale                              # metres per file unit
    0.001
    >>> u.unit("m/rad^2"), float(u.convert(0.5, "m/s"))      # L of a point; a speed
    ('mm/deg^2', 500.0)
    >>> float(u.convert(math.pi, "rad/s"))           # half a turn per second
    180.0
    """

    length: Literal["m", "cm", "mm", "in"] = "m"
    angle: Literal["rad", "deg"] = "rad"

    def __post_init__(self):
        problems = []
        for attr, table in (("length", LENGTH_UNITS), ("angle", ANGLE_UNITS)):
            v = getattr(self, attr)
            if not isinstance(v, str) or v not in table:
                problems.append(f"units.{attr}: {expected_one_of(v, table)}")
        if problems:
            raise ModelError(problems)

    @classmethod
    def resolve(cls, units: Units | Mapping[str, str] | None = None, *,
                degrees: bool = False) -> Units:
        """The units a caller asks for with the keywords ``units=`` and ``degrees=``.

        Parameters
        ----------
        units : Units or mapping, optional
            ``{"length": "mm", "angle": "deg"}`` (a key left out stays SI); default SI.
        degrees : bool
            Angles in degrees: shorthand for ``angle="deg"``.

        Raises
        ------
        ModelError
            An unknown key or unit, naming it and the allowed ones; ``degrees=True`` with
            another angle unit.

        Examples
        --------
        >>> Units.resolve({"length": "mm"}, degrees=True)
        Units(length='mm', angle='deg')
        >>> Units.resolve({"length": "km"})
        Traceback (most recent call last):
        ...
        kinelab.errors.ModelError: units.length: expected one of 'm', 'cm', 'mm', 'in', got 'km' (did you mean 'm'?)
        """
        if units is None:
            u = cls()
        elif isinstance(units, Units):
            u = units
        elif isinstance(units, Mapping):
            unknown = [str(k) for k in units if k not in ("length", "angle")]
            if unknown:
                raise ModelError(f"units: expected the keys 'length' and 'angle', got "
                                 f"{quoted(unknown)}{suggest(unknown[0], ('length', 'angle'))}")
            u = cls(**units)
        else:
            raise ModelError(f"units: expected a mapping such as {{'length': 'mm', 'angle': "
                             f"'deg'}} or a kinelab Units, got {describe(units)}")
        if not isinstance(degrees, (bool, np.bool_)):
            raise ModelError(f"degrees: expected True or False, got {describe(degrees)}")
        if degrees:
            asked = units.get("angle") if isinstance(units, Mapping) else (
                units.angle if isinstance(units, Units) else None)
            if asked not in (None, "deg"):
                raise ModelError(f"units.angle: degrees=True asks for 'deg', got {describe(asked)}; "
                                 "drop one of them")
            u = cls(u.length, "deg")
        return u

    @property
    def length_scale(self) -> float:
        """Metres per length unit."""
        return LENGTH_UNITS[self.length]

    @property
    def angle_scale(self) -> float:
        """Radians per angle unit."""
        return ANGLE_UNITS[self.angle]

    @property
    def si(self) -> bool:
        """Whether these are SI units (m, rad)."""
        return self.length == "m" and self.angle == "rad"

    # -- conversion of SI values ---------------------------------------------------------
    def scale(self, si_unit: str) -> float:
        """SI value of one of these units of the quantity ``si_unit`` names.

        >>> Units("mm", "deg").scale("m/rad")       # 1 mm/deg in m/rad
        0.057295779513082325
        """
        num, den = _parse(si_unit)
        return _product(self._scale, num) / _product(self._scale, den)

    def unit(self, si_unit: str) -> str:
        """The name, in these units, of the unit ``si_unit`` names in SI.

        >>> Units("in", "deg").unit("m/(rad*m)"), Units().unit("rad/rad")
        ('in/(deg*in)', 'rad/rad')
        """
        num, den = _parse(si_unit)
        top = _spell([self._name(b) for b in num]) or "1"
        if not den:
            return top
        bottom = _spell([self._name(b) for b in den])
        return f"{top}/{bottom}" if len(set(den)) == 1 else f"{top}/({bottom})"

    def convert(self, values, si_unit: str):
        """SI ``values`` of the quantity ``si_unit`` names, expressed in these units.

        A scalar gives a float, an array an array of the same shape; SI units give the
        values back unchanged.
        """
        s = self.scale(si_unit)
        return values if s == 1.0 else values / s

    def _scale(self, base: str) -> float:
        return {"m": self.length_scale, "rad": self.angle_scale}.get(base, 1.0)

    def _name(self, base: str) -> str:
        return {"m": self.length, "rad": self.angle}.get(base, base)


@functools.lru_cache(maxsize=256)
def _parse(si_unit: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """``"m/(rad*rad)"`` -> (("m",), ("rad", "rad")): base units over base units."""
    top, _, bottom = si_unit.partition("/")
    if bottom.startswith("(") and bottom.endswith(")"):
        bottom = bottom[1:-1]
    return _factors(top, si_unit), _factors(bottom, si_unit) if bottom else ()


def _factors(text: str, whole: str) -> tuple[str, ...]:
    out: list[str] = []
    for part in text.split("*"):
        match = _FACTOR.match(part)
        if not match:
            raise ValueError(f"not an SI unit kinelab converts: {whole!r}")
        out += [match.group(1)] * int(match.group(2) or 1)
    return tuple(out)


def _product(scale, bases) -> float:
    return math.prod(scale(b) for b in bases)


def _spell(names: list[str]) -> str:
    """``["deg", "deg", "mm"]`` -> ``"deg^2*mm"``, in order of first appearance."""
    counts = {n: names.count(n) for n in dict.fromkeys(names)}
    return "*".join(n if k == 1 else f"{n}^{k}" for n, k in counts.items())
