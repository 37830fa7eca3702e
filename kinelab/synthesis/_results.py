"""A list of solutions that can say why it is empty."""
from __future__ import annotations

__all__ = ["SolutionList"]


class SolutionList(list):
    """A plain list of solutions, with ``reason``: why it is empty or why some candidates
    were left out (empty when there is nothing to say).

    Examples
    --------
    >>> s = SolutionList([], reason="no real root")
    >>> len(s), s.reason
    (0, 'no real root')
    """

    def __init__(self, items=(), reason: str = ""):
        super().__init__(items)
        self.reason = reason

    def __repr__(self) -> str:
        body = super().__repr__()
        return f"SolutionList({body}, reason={self.reason!r})" if self.reason else body
