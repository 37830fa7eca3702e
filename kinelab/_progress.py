"""How far long work has come, for whoever watches it (the web app's progress bar).

Long work (a derivation, a path-generation search, an animation) says where it is with
:func:`report`: a short label and the fraction done.  Nothing is watching unless the thread
runs inside :func:`watching`, so a report costs a lookup and nothing else; library code
never prints progress.  :func:`part` maps the fractions of a step into a share of the whole,
so that work made of steps (a derivation, then its document) reports one fraction from 0
to 1.

>>> seen = []
>>> with watching(lambda label, fraction: seen.append((label, fraction))):
...     with part(0.0, 0.5):
...         report("first half", 0.5)
...     report("second half", 0.75)
>>> seen
[('first half', 0.25), ('second half', 0.75)]
"""
from __future__ import annotations

import contextlib
import threading

__all__ = ["report", "watching", "part"]

_local = threading.local()


def report(label: str, fraction: float | None = None) -> None:
    """Say what the work in this thread is doing (``label``) and, when known, how much of
    it is done (``fraction``, 0 to 1, within the current :func:`part`)."""
    watcher = getattr(_local, "watcher", None)
    if watcher is None:
        return
    if fraction is not None:
        lo, hi = getattr(_local, "span", (0.0, 1.0))
        fraction = lo + (hi - lo) * min(max(float(fraction), 0.0), 1.0)
    watcher(label, fraction)


@contextlib.contextmanager
def watching(watcher):
    """Within the block, this thread's reports go to ``watcher(label, fraction)``."""
    before = getattr(_local, "watcher", None), getattr(_local, "span", (0.0, 1.0))
    _local.watcher, _local.span = watcher, (0.0, 1.0)
    try:
        yield
    finally:
        _local.watcher, _local.span = before


@contextlib.contextmanager
def part(start: float, stop: float):
    """Within the block, a fraction f reported stands for ``start + f (stop - start)`` of
    the enclosing part (parts nest)."""
    lo, hi = getattr(_local, "span", (0.0, 1.0))
    before = (lo, hi)
    _local.span = (lo + (hi - lo) * start, lo + (hi - lo) * stop)
    try:
        yield
    finally:
        _local.span = before
