"""What one request may cost the server, known before the work starts.

- **Estimates.**  A sweep's cost is its samples times its columns: the engine's arrays, the
  columns in the model's units, and the answer's text (and, for the page's study, the lists
  of numbers that become it).  :func:`sweep_cost` gives it in bytes from the model and the
  samples alone; :func:`check_sweep` refuses
  (:class:`~kinelab.errors.MemoryBudgetError`, 413) what exceeds the memory budget
  (:func:`kinelab.memory_budget`), and an answer of more values than a CSV or JSON table may
  hold (:data:`kinelab.io._results.MAX_TABLE_VALUES`, about 30 s of work; :class:`TooLarge`,
  413).
- **Requests in flight.**  Within a request (:func:`request`), what :func:`require` allows is
  also reserved from the budget, which the requests running at once share: one that does not
  fit waits for others to end, and after :data:`WAIT` seconds is answered 503
  (:class:`Busy`).  So the server holds at most the budget in answers being made, however
  many come.
- **Sweeps kept.**  :class:`Kept` keeps the sweeps the drags that follow a study need, least
  recently used first out, within :func:`cache_bytes`.
"""
from __future__ import annotations

import contextlib
import threading
import time
from collections import OrderedDict

import numpy as np

from kinelab import _memory as memory
from kinelab._files import byte_size
from kinelab._tables import BLOCK_VALUES
from kinelab.errors import KinelabError, ModelError

__all__ = ["TooLarge", "Busy", "sweep_cost", "check_sweep", "require", "request", "Kept",
           "cache_bytes", "nbytes", "WAIT"]

WAIT = 30.0
"""Seconds a request waits for the memory that requests running before it hold."""

_VALUE_TEXT = 25        # bytes of a number's JSON or CSV text, with its separator
_TEXT_COPIES = 3        # the blocks of text, the text joined, and the bytes sent
_PYTHON_FLOAT = 32      # a float in a list: the object and the list's pointer to it
_BLOCK = BLOCK_VALUES * 128     # a block of a table's text, as Python strings


class TooLarge(ModelError):
    """A request for an answer larger than the server makes (413)."""


class Busy(KinelabError):
    """The memory a request needs is held by other requests for longer than :data:`WAIT`
    seconds (503)."""


def sweep_cost(mf, samples: int | None, answer: str) -> tuple[int, int, int]:
    """``(bytes, rows, columns)`` of a sweep of ``mf`` (``samples`` per input, default the
    file's) and its ``answer``: ``"none"`` (a sweep kept for the drags), ``"rows"`` (the JSON
    rows of ``kinelab analyze``), ``"csv"`` (its CSV) or ``"columns"`` (the page's study:
    lists of numbers, then their JSON)."""
    from kinelab import kinematics
    from kinelab.io._modelfile import errors_from
    from kinelab.kinematics._columns import table_width

    with errors_from(mf):
        p = kinematics.plan(mf.mechanism)
    rows = mf.sample_count(samples)
    columns = table_width(p) + 1
    M, n = len(p.input_kinds), len(p.stored_items)
    engine = rows * (8 * n * (3 + M + M * M) + 24 * M + 41)
    if answer == "none":
        return engine, rows, columns
    if answer == "columns":             # and the transmission angles, one per dyad at most
        columns += len(mf.mechanism.links)
    cells = rows * columns
    text = {"rows": _VALUE_TEXT + _name_text(p), "csv": _VALUE_TEXT,
            "columns": _VALUE_TEXT}[answer]
    per_cell = 2 * 8 + _TEXT_COPIES * text + (_PYTHON_FLOAT if answer == "columns" else 0)
    return engine + cells * per_cell + _BLOCK, rows, columns


def _name_text(p) -> int:
    """At least the length of a column's name in a row of JSON: the longest item's name,
    and 30 for the quantity, the unit, the quotes, the colon and the space."""
    names = list(p.link_item) + list(p.slide_item) + list(p.point_item)
    longest = max((len(s) for s in names), default=8)
    return longest + 30


def require(nbytes: float, what: str, instead: str) -> None:
    """Refuse ``nbytes`` past the memory budget; within a :func:`request`, also reserve them
    from what the requests in flight share, waiting up to :data:`WAIT` seconds for it."""
    memory.require(nbytes, what, instead)
    scope = getattr(_local, "scope", None)
    if scope is not None:
        scope.reserve(int(nbytes), what)


def check_sweep(mf, samples: int | None, answer: str, what: str) -> None:
    """Refuse, before the work, a sweep and its ``answer`` (see :func:`sweep_cost`) past the
    memory budget or, as text, past the values a CSV or JSON table may hold; reserve the
    rest for the request."""
    from kinelab.io._results import table_too_large
    nbytes, rows, columns = sweep_cost(mf, samples, answer)
    if answer != "none":
        problem = table_too_large("csv" if answer == "csv" else "json", rows, columns)
        if problem:
            raise TooLarge(f"samples: {what}: {problem}; or write the table with kinelab "
                           "analyze (as Parquet, a million samples)")
    require(nbytes, f"{what} ({rows:,} samples x {columns:,} columns)", "ask for fewer samples")


class _InFlight:
    """The bytes the requests running now have reserved, within the memory budget."""

    def __init__(self):
        self.held = 0
        self._changed = threading.Condition()

    def reserve(self, nbytes: int, what: str) -> None:
        deadline = time.monotonic() + WAIT
        with self._changed:
            while self.held + nbytes > memory.memory_budget() and self.held:
                left = deadline - time.monotonic()
                if left <= 0:
                    raise Busy(f"{what}: the server is busy with other large requests "
                               f"(they hold {byte_size(self.held)} of its memory budget of "
                               f"{byte_size(memory.memory_budget())}); try again in a "
                               "moment")
                self._changed.wait(left)
            self.held += nbytes

    def release(self, nbytes: int) -> None:
        with self._changed:
            self.held -= nbytes
            self._changed.notify_all()


_in_flight = _InFlight()
_local = threading.local()


class _Scope:
    def __init__(self):
        self.reserved = 0

    def reserve(self, nbytes: int, what: str) -> None:
        _in_flight.reserve(nbytes, what)
        self.reserved += nbytes


@contextlib.contextmanager
def request():
    """The work of one request, in the thread that does it: what it reserves is given back
    at the end."""
    scope = _local.scope = _Scope()
    try:
        yield scope
    finally:
        _local.scope = None
        _in_flight.release(scope.reserved)


def in_flight() -> int:
    """Bytes the requests running now have reserved."""
    return _in_flight.held


# -- the sweeps kept --------------------------------------------------------------------------
def cache_bytes() -> int:
    """The most the kept sweeps may hold: an eighth of the memory budget."""
    return memory.memory_budget() // 8


def nbytes(obj, depth: int = 3) -> int:
    """The bytes of the numpy arrays an object holds in its attributes, dictionaries, lists
    and tuples, ``depth`` levels down (each array counted once)."""
    seen: set[int] = set()

    def walk(x, level: int) -> int:
        if isinstance(x, np.ndarray):
            if id(x) in seen:
                return 0
            seen.add(id(x))
            return x.nbytes
        if level == 0:
            return 0
        if isinstance(x, dict):
            return sum(walk(v, level - 1) for v in x.values())
        if isinstance(x, (list, tuple)):
            return sum(walk(v, level - 1) for v in x)
        attrs = getattr(x, "__dict__", None)
        return walk(attrs, level) if isinstance(attrs, dict) else 0
    return walk(obj, depth)


class Kept:
    """Values by key, the least recently used dropped first once their bytes (``size`` of
    each) pass :func:`cache_bytes` or their count ``most``."""

    def __init__(self, most: int = 16):
        self.most = most
        self._items: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, key):
        with self._lock:
            item = self._items.get(key)
            if item is None:
                return None
            self._items.move_to_end(key)
            return item[0]

    def put(self, key, value, size: int) -> None:
        limit = cache_bytes()
        with self._lock:
            self._items.pop(key, None)
            if size > limit:
                return
            self._items[key] = (value, size)
            while len(self._items) > self.most or self.held() > limit:
                self._items.popitem(last=False)

    def held(self) -> int:
        return sum(size for _, size in self._items.values())

    def __len__(self) -> int:
        return len(self._items)

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
