"""The exception hierarchy of kinelab.

Every error a user can provoke is one of these, with a message that says where the
problem is, what was expected, what was found and what to do next.

``KinelabError`` is the base.  Errors caused by bad input (a model, an argument, an
input value out of reach) also subclass :class:`ValueError`, so code that already
catches ``ValueError`` keeps working.
"""
from __future__ import annotations

from collections.abc import Iterable
from difflib import get_close_matches

__all__ = [
    "KinelabError",
    "ModelError",
    "AssemblyError",
    "ConvergenceError",
    "SingularityError",
    "MemoryBudgetError",
]


class KinelabError(Exception):
    """Base class of every kinelab error."""


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
        prefix = f"{source}: " if source else ""
        super().__init__("\n".join(prefix + p for p in self.problems))


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


class SingularityError(KinelabError, ValueError):
    """A value was asked for exactly at a singular configuration (det J = 0)."""


# -- wording shared by the messages -------------------------------------------------------
def quoted(names: Iterable[str]) -> str:
    """``'a', 'b', 'c'``: the choices a message lists."""
    return ", ".join(f"'{n}'" for n in names)


def suggest(name: str, choices: Iterable[str]) -> str:
    """`` (did you mean 'x'?)`` when one of ``choices`` is close to ``name``, else ''."""
    close = get_close_matches(str(name), [str(c) for c in choices], n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def check_choice(name: str, value, choices) -> None:
    """Raise a :class:`ModelError` unless ``value`` is one of ``choices``."""
    if value not in choices:
        raise ModelError(f"{name}: expected one of {', '.join(repr(c) for c in choices)}, "
                         f"got {value!r}")
