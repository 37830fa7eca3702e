"""The exception hierarchy of kinelab.

Every error a user can provoke is one of these, with a message that says where the
problem is, what was expected, what was found and what to do next.

``KinelabError`` is the base.  Errors caused by bad input (a model, an argument, an
input value out of reach) also subclass :class:`ValueError`, so code that already
catches ``ValueError`` keeps working.
"""
from __future__ import annotations

import math
import re
from collections.abc import Collection, Iterable, Mapping
from difflib import get_close_matches
from itertools import islice

__all__ = [
    "KinelabError",
    "ModelError",
    "AssemblyError",
    "ConvergenceError",
    "SingularityError",
    "MemoryBudgetError",
    "TimeLimitError",
    "CancellationError",
]


class KinelabError(Exception):
    """Base class of every kinelab error."""

    def __reduce__(self):
        # pickled as its state, not as arguments to __init__ again (the errors that carry
        # data take other arguments than their message): Dask's workers send them back
        return _rebuilt, (type(self), self.args, self.__dict__)


def _rebuilt(cls: type[KinelabError], args: tuple, state: dict) -> KinelabError:
    exc = cls.__new__(cls)
    exc.args = args
    exc.__dict__.update(state)
    return exc


class ModelError(KinelabError, ValueError):
    """An invalid model, model file or argument.

    ``problems`` holds every problem found (a model is checked as a whole, so a user
    fixing a file sees all the mistakes at once); the message joins them, one per line.
    """

    def __init__(self, problems: str | Iterable[str], *, source: str | None = None):
        if isinstance(problems, str):
            problems = [problems]
        self.problems = tuple(problems)
        self.source = source
        prefix = f"{shown_path(source)}: " if source else ""
        super().__init__("\n".join(prefix + p for p in self.shown_problems()))

    def shown_problems(self) -> tuple[str, ...]:
        """The lines of the message, without the file's name: the first
        :data:`PROBLEMS_SHOWN` problems, then how many more there are."""
        more = len(self.problems) - PROBLEMS_SHOWN
        return self.problems[:PROBLEMS_SHOWN] + (
            (f"and {more:,} more problems; fix these first",) if more > 0 else ())


class AssemblyError(KinelabError, ValueError):
    """The loops of a mechanism cannot close at the requested input.

    Attributes
    ----------
    loop : str
        The group of links (loop) that cannot close.
    gap : float
        By how much it fails to close, in metres.
    reachable : list of (float, float)
        Input intervals where the mechanism does assemble, when they are known.
    link : str
        The link whose length is most likely wrong, when one can be named.
    """

    def __init__(self, message: str, *, loop: str = "", gap: float = float("nan"),
                 reachable: list[tuple[float, float]] | None = None, link: str = ""):
        super().__init__(message)
        self.loop = loop
        self.gap = gap
        self.reachable = reachable
        self.link = link


class MemoryBudgetError(ModelError):
    """A request whose results would not fit in the memory budget
    (:func:`kinelab.memory_budget`); the message gives the estimate and the budget."""


class ConvergenceError(KinelabError, RuntimeError):
    """An iterative solver did not converge."""


class TimeLimitError(KinelabError, ValueError):
    """Work stopped at its time limit (a derivation whose expressions grow too large to
    finish in time); the message says which limit and how to change it.  Like
    :class:`MemoryBudgetError`, a request too large for its bound: a ValueError."""


class CancellationError(KinelabError):
    """Work stopped before its end because whoever asked for it no longer wants it (the
    browser app's *cancel*, or a page that went away); the message says what was stopped."""


class SingularityError(KinelabError, ValueError):
    """A value was asked for exactly at a singular configuration (det J = 0)."""


# -- wording shared by the messages -------------------------------------------------------
# Names and values come from files and callers: a message shows them escaped (no newline,
# control or escape character, no lone surrogate reaches a terminal) and cut, so that it
# stays one line of bounded length whatever it quotes.
NAME_SHOWN = 60       # characters of a name (or value) a message shows, quotes included
NAMES_SHOWN = 20      # names a list of choices shows before "... and N more"
PROBLEMS_SHOWN = 20   # problems a ModelError's message shows before "... and N more problems"
PATH_SHOWN = 400      # characters of a file's path a message shows
SUGGEST_AMONG = 1000  # "did you mean" looks for a close name among at most this many: it
                      # compares the name with each choice, and a message must stay cheap
_ESCAPES = {"\n": "\\n", "\t": "\\t", "\r": "\\r"}
_QUOTED = {**_ESCAPES, "\\": "\\\\", "'": "\\'"}


def _escaped(text: str, limit: int, escapes: Mapping[str, str] = _ESCAPES) -> str:
    """``text`` with every unprintable character escaped as ``repr`` does, cut to ``limit``
    characters with an ellipsis; reads only the characters it shows."""
    out, size = [], 0
    for k, c in enumerate(text):
        e = escapes.get(c) or (c if c.isprintable() else ascii(c)[1:-1])
        if size + len(e) > limit - 1 and (size + len(e) > limit or k < len(text) - 1):
            out.append("\u2026")
            break
        out.append(e)
        size += len(e)
    return "".join(out)


def shown(name: object) -> str:
    """``'name'``: a name as a message shows it, quoted, escaped and cut.

    Examples
    --------
    >>> shown("coupler"), shown("a\\nb\\x1b[31m")
    ("'coupler'", "'a\\\\nb\\\\x1b[31m'")
    >>> len(shown("x" * 10_000)) <= NAME_SHOWN
    True
    """
    if not isinstance(name, str):
        return describe(name)
    return f"'{_escaped(name, NAME_SHOWN - 2, _QUOTED)}'"


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


def shown_path(path: object) -> str:
    """A file's path as a message shows it: as given, unquoted, with unprintable characters
    escaped and cut (a path is the user's own text, but a newline in it would split a
    one-line message).

    Examples
    --------
    >>> shown_path("out/engine.csv"), shown_path("a\\nb.toml")
    ('out/engine.csv', 'a\\\\nb.toml')
    """
    return _escaped(str(path), PATH_SHOWN)


def one_line(text: object, limit: int = 2000) -> str:
    """A message from elsewhere (a library, the command-line parser) made one line: every
    unprintable character escaped, cut to ``limit`` characters.

    Examples
    --------
    >>> one_line("Invalid value for 'MODEL':\\n  File 'a' does not exist.")
    "Invalid value for 'MODEL':\\\\n  File 'a' does not exist."
    """
    return _escaped(str(text), limit)


def shown_key(key: object) -> str:
    """A key of a file as a field name shows it (``points.A``): bare when it is a short
    word, else as :func:`shown` shows a name (``points.'my point'``)."""
    if isinstance(key, str) and len(key) <= NAME_SHOWN and _BARE_KEY.fullmatch(key):
        return key
    return shown(key)


def describe(value: object, _depth: int = 0) -> str:
    """A short, one-line rendering of a value found in a file or given by a caller.

    Examples
    --------
    >>> describe([1.5, "a\\nb", {"k": 1}]), describe(np.array([[1.0, 2.0], [3.0, 4.0]]))
    ("[1.5, 'a\\\\nb', a table]", '[[1.0, 2.0], [3.0, 4.0]]')
    >>> describe(np.arange(10**6)), describe(np.float64(0.5)), describe(object())
    ('[0, 1, 2, 3, ...]', '0.5', 'an object')
    """
    if type(value).__module__ == "numpy" and hasattr(value, "tolist"):
        # an array or a numpy number: its plain numbers, as few as are shown (not a repr)
        ndim = getattr(value, "ndim", 0)
        value = value[(slice(0, 5),) * ndim].tolist() if ndim else value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return shown(value)
    if isinstance(value, Mapping):
        return "a table"
    if isinstance(value, int) and abs(value).bit_length() > 128:
        # too long to show (and to turn into text at all, past Python's 4300 digits)
        digits = int(math.log10(abs(value))) + 1
        digits -= 10 ** (digits - 1) > abs(value)     # log10 rounds up just below a power of 10
        return f"a whole number of {digits} digits"
    if isinstance(value, (list, tuple)):
        if _depth >= 2:
            return "[...]"
        inner = ", ".join(describe(v, _depth + 1) for v in value[:4])
        left, right = "()" if isinstance(value, tuple) else "[]"
        return f"{left}{inner}{', ...' if len(value) > 4 else ''}{right}"
    kind = type(value).__name__
    by_type = f"{'an' if kind[:1].lower() in 'aeiou' else 'a'} {kind}"
    if type(value).__repr__ is object.__repr__:     # no repr of its own: an address, no value
        return _escaped(by_type, NAME_SHOWN)
    try:
        text = repr(value)
    except Exception:       # a caller's object whose repr fails: name its type
        text = by_type
    return _escaped(text, NAME_SHOWN)


def quoted(names: Iterable[str], *, limit: int = NAMES_SHOWN) -> str:
    """``'a', 'b', 'c'``: the choices a message lists, at most ``limit`` of them
    (``..., and 7 more``); ``none`` when there are none."""
    if not isinstance(names, Collection):
        names = list(names)
    first = [shown(n) for n in islice(names, limit)]
    if not first:
        return "none"
    more = len(names) - len(first)
    return ", ".join(first) + (f" and {more:,} more" if more > 0 else "")


def suggest(name: str, choices: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` when one of ``choices`` is close to ``name``, else ''
    (also when there are more than ``SUGGEST_AMONG`` choices or ``name`` is long)."""
    if not isinstance(choices, Collection):
        choices = list(choices)
    if len(choices) > SUGGEST_AMONG or len(str(name)) > NAME_SHOWN:
        return ""
    close = get_close_matches(str(name), [c for c in map(str, choices) if len(c) <= NAME_SHOWN], n=1)
    return f" (did you mean {shown(close[0])}?)" if close else ""


def expected_one_of(value: object, choices: Iterable[str]) -> str:
    """``expected one of 'a', 'b', got 'x' (did you mean 'a'?)``, or, with no choices,
    ``got 'x', but there is nothing to choose from``."""
    if not isinstance(choices, Collection):
        choices = list(choices)
    if not choices:
        return f"got {describe(value)}, but there is nothing to choose from"
    hint = suggest(value, choices) if isinstance(value, str) else ""
    return f"expected one of {quoted(choices)}, got {describe(value)}{hint}"


def check_choice(name: str, value, choices) -> None:
    """Raise a :class:`ModelError` unless ``value`` is one of ``choices``."""
    try:
        ok = value in choices
    except TypeError:         # an unhashable value is none of them
        ok = False
    if not ok:
        raise ModelError(f"{name}: {expected_one_of(value, choices)}")
