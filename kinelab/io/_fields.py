"""Reading untrusted plain data field by field, collecting every problem.

A model file is checked as a whole: each reader method returns the converted value, or
``None`` after recording a one-line problem that names the field (``links[2].points``),
says what was expected and what was found.  Nothing but :class:`ModelError` leaves.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Collection, Iterable, Mapping, Set
from typing import Any

from kinelab.errors import PROBLEMS_SHOWN, describe, quoted, shown, shown_key, suggest
from kinelab.io._text import in_si
from kinelab.model import MAX_NAME, name_problem

__all__ = ["Reader", "quoted", "suggest", "describe", "shown", "shown_key"]


def _is_number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _scaled(value: int | float, scale: float) -> float:
    """``value * scale`` as a float, rounded once from the digits written (see
    :func:`kinelab.io._text.in_si`); inf when a huge integer does not fit one."""
    try:
        return in_si(value, scale)
    except OverflowError:
        return math.inf


def _lookup(options: Iterable[str]) -> Collection[str]:
    """``options`` as a collection with a fast ``in``: a dict or set as it is, else a dict."""
    return options if isinstance(options, (Set, Mapping)) else dict.fromkeys(options)


Check = Callable[[float], "str | None"]     # why a value (SI) is refused, or None


class Reader:
    """Collects problems while converting fields; see the module docstring.

    Each check takes time bounded by the size of what it reads: names are looked up in
    dictionaries, and "did you mean" is worked out only for the problems a message shows.
    """

    def __init__(self) -> None:
        self.problems: list[str] = []

    def fail(self, field: str, message: str) -> None:
        self.problems.append(f"{field}: {message}" if field else message)

    def suggest(self, name: str, choices: Iterable[str]) -> str:
        """:func:`~kinelab.errors.suggest`, for the problems a message shows only."""
        return suggest(name, choices) if len(self.problems) < PROBLEMS_SHOWN else ""

    # -- structure ------------------------------------------------------------------------
    def table(self, value: Any, field: str, allowed: Iterable[str], *,
              required: Iterable[str] = (), reserved: Mapping[str, str] | None = None
              ) -> dict[str, Any] | None:
        """A table with only the ``allowed`` keys (and all the ``required`` ones)."""
        if not isinstance(value, Mapping):
            self.fail(field, f"expected a table, got {describe(value)}")
            return None
        allowed = _lookup(allowed)
        reserved = reserved or {}
        prefix = f"{field}." if field else ""
        for key in value:
            if key in allowed:
                continue
            if key in reserved:
                self.fail(prefix + shown_key(key), reserved[key])
            else:
                self.fail(prefix + shown_key(key), f"unknown field{self.suggest(key, allowed)}; "
                          f"valid fields are {quoted(allowed)}")
        for key in required:
            if key not in value:
                self.fail(prefix + key, "missing; this field is required")
        return {k: v for k, v in value.items() if k in allowed}

    def array(self, value: Any, field: str, what: str) -> list | None:
        if not isinstance(value, (list, tuple)):
            self.fail(field, f"expected a list of {what}, got {describe(value)}")
            return None
        return list(value)

    # -- scalars --------------------------------------------------------------------------
    def _text(self, value: Any, field: str, what: str, options: Iterable[str] | None,
              complaint) -> str | None:
        """Non-empty printable text of at most ``MAX_NAME`` characters, one of ``options``
        when given (else ``complaint(value, options)``)."""
        if name_problem(value) is not None:
            if isinstance(value, str) and len(value) > MAX_NAME:
                self.fail(field, f"expected {what} of at most {MAX_NAME} characters, got "
                          f"{len(value):,}; shorten it")
                return None
            printable = isinstance(value, str) and value.strip()
            self.fail(field, f"expected {what}{' of printable characters' if printable else ''}, "
                      f"got {describe(value)}")
            return None
        if options is None:
            return value
        options = _lookup(options)
        if value in options:
            return value
        self.fail(field, complaint(value, options))
        return None

    def string(self, value: Any, field: str, *, choices: Iterable[str] | None = None) -> str | None:
        return self._text(value, field, "a non-empty text", choices, lambda v, c: (
            f"expected one of {quoted(c)}, got {shown(v)}{self.suggest(v, c)}"))

    def boolean(self, value: Any, field: str) -> bool | None:
        if not isinstance(value, bool):
            self.fail(field, f"expected true or false, got {describe(value)}")
            return None
        return value

    def integer(self, value: Any, field: str, *, low: int, high: int) -> int | None:
        if not (isinstance(value, int) and not isinstance(value, bool)) or not low <= value <= high:
            self.fail(field, f"expected a whole number from {low} to {high:,}, got {describe(value)}")
            return None
        return int(value)

    def number(self, value: Any, field: str, *, scale: float = 1.0, positive: bool = False,
               unit: str = "", check: Check | None = None) -> float | None:
        """A finite number times ``scale`` (the unit's factor to SI), refused when
        ``check`` says why (it is given the SI value)."""
        if not _is_number(value):
            self.fail(field, f"expected a number, got {describe(value)}")
            return None
        v = _scaled(value, scale)
        if not math.isfinite(v):
            self.fail(field, f"expected a finite number, got {describe(value)}")
            return None
        if positive and v <= 0:
            self.fail(field, f"expected a positive {'length' if unit else 'number'}, got "
                      f"{describe(value)}{' ' + unit if unit else ''}")
            return None
        if check is not None and (why := check(v)):
            self.fail(field, f"{why}, got {describe(value)}{' ' + unit if unit else ''}")
            return None
        return v

    def numbers(self, value: Any, field: str, count: int | tuple[int, ...], *, scale: float = 1.0,
                what: str = "numbers", unit: str = "", check: Check | None = None
                ) -> tuple[float, ...] | None:
        counts = (count,) if isinstance(count, int) else count
        shape = what if what not in ("numbers", "coordinates") else " or ".join(
            f"[{', '.join(['x', 'y', 'z'][:n])}]" if what == "coordinates" else f"{n} numbers"
            for n in counts)
        if (not isinstance(value, (list, tuple)) or len(value) not in counts
                or not all(_is_number(v) for v in value)):
            self.fail(field, f"expected {shape}, got {describe(value)}")
            return None
        out = tuple(_scaled(v, scale) for v in value)
        if not all(math.isfinite(x) for x in out):
            self.fail(field, f"expected finite numbers, got {describe(value)}")
            return None
        if check is not None and (why := next(filter(None, map(check, out)), None)):
            self.fail(field, f"{why}, got {describe(value)}{' ' + unit if unit else ''}")
            return None
        return out

    def name(self, value: Any, field: str, known: Iterable[str] | None = None,
             kind: str = "", plural: str | None = None) -> str | None:
        """A name, optionally one of ``known`` (then the message lists them as ``plural``)."""
        return self._text(value, field, "a name", known, lambda v, k: (
            f"expected a declared {kind}, got {shown(v)}{self.suggest(v, k)}; "
            f"{plural or 'declared ' + kind + 's'} are {quoted(k)}"))

    def names(self, value: Any, field: str, known: Iterable[str] | None = None, kind: str = "",
              count: int | None = None, plural: str | None = None) -> tuple[str, ...] | None:
        items = self.array(value, field, f"{kind or 'name'}s")
        if items is None:
            return None
        if count is not None and len(items) != count:
            self.fail(field, f"expected {count} {kind}s, got {describe(items)}")
            return None
        known = None if known is None else _lookup(known)    # once, not once per name
        before = len(self.problems)
        out = tuple(self.name(v, f"{field}[{i}]", known, kind, plural) for i, v in enumerate(items))
        return None if len(self.problems) > before else out
