"""Large result arrays: a memory budget for them, and memory that earlier results no
longer use.

Before a large allocation kinelab estimates the bytes it needs and refuses, with the
estimate and how to change the budget, when they exceed :func:`memory_budget` (2 GiB by
default, or the environment variable ``KINELAB_MEMORY_BUDGET``, e.g. ``8G``).


The operating system hands out fresh memory as pages it zeroes on first touch.  For a
sweep of a million configurations, writing a few hundred megabytes of results, that zeroing
costs about as much as the analysis itself.  So the memory of large results is kept when
they are dropped and given to the next result that fits, up to a limit
(:func:`reuse_result_memory`).

A block is reused only when nothing references it any more: every numpy view of an array
keeps a reference to the array that owns the memory, so a block whose owner is referenced
only by this pool has no live view anywhere.
"""
from __future__ import annotations

import math
import sys
import threading

import numpy as np

from kinelab._files import byte_size
from kinelab.errors import MemoryBudgetError, ModelError, describe

SMALLEST = 1 << 20                  # smaller arrays come from the allocator's own free lists
_DEFAULT_LIMIT = 1 << 30


def _reference_counts(blocks: list[np.ndarray]) -> list[int]:
    return [sys.getrefcount(b) for b in blocks]


_UNREFERENCED = _reference_counts([np.empty(1, np.uint8)])[0]   # held by the pool alone


class _Pool:
    def __init__(self, limit: int):
        self.limit = limit
        self._blocks: list[np.ndarray] = []     # 1-D uint8 arrays that own their memory
        self._lock = threading.Lock()

    def empty(self, shape: tuple[int, ...], dtype=float) -> np.ndarray:
        dtype = np.dtype(dtype)
        nbytes = math.prod(shape) * dtype.itemsize
        if nbytes < SMALLEST or nbytes > self.limit:
            return np.empty(shape, dtype)
        with self._lock:
            block = self._take(nbytes)
        return block[:nbytes].view(dtype).reshape(shape)

    def _free(self) -> list[int]:
        return [i for i, n in enumerate(_reference_counts(self._blocks)) if n == _UNREFERENCED]

    def _take(self, nbytes: int) -> np.ndarray:
        """A free block of at least nbytes, or a new one (kept if the limit allows)."""
        free = self._free()
        fits = [i for i in free if self._blocks[i].nbytes >= nbytes]
        if fits:
            return self._blocks[min(fits, key=lambda i: self._blocks[i].nbytes)]
        self._drop(free, self.limit - nbytes)
        block = np.empty(nbytes, np.uint8)
        if self.held() + nbytes <= self.limit:
            self._blocks.append(block)
        return block

    def _drop(self, free: list[int], keep: int) -> None:
        """Let go of free blocks, largest first, until the pool holds at most ``keep`` bytes."""
        held = self.held()
        drop = set()
        for i in sorted(free, key=lambda i: -self._blocks[i].nbytes):
            if held <= keep:
                break
            held -= self._blocks[i].nbytes
            drop.add(i)
        self._blocks = [b for i, b in enumerate(self._blocks) if i not in drop]

    def held(self) -> int:
        return sum(b.nbytes for b in self._blocks)

    def set_limit(self, limit: int) -> None:
        with self._lock:
            self.limit = limit
            self._drop(self._free(), limit)


_pool = _Pool(_DEFAULT_LIMIT)
empty = _pool.empty


def reuse_result_memory(max_bytes: int) -> int:
    """Set how much memory of dropped results kinelab keeps for the next ones; return the old limit.

    Fresh memory costs a first-touch zeroing by the operating system, which for a large sweep
    takes about as long as the analysis.  kinelab therefore keeps the memory of large result
    arrays (1 MiB and over) once nothing references them, up to ``max_bytes`` in all (1 GiB
    by default), and writes later results into it.  ``reuse_result_memory(0)`` hands all of
    it back and turns reuse off.  A result you hold, or any numpy view of it, keeps its
    memory; a raw pointer does not (turn reuse off before handing results to C code that
    keeps their address after the arrays are dropped).

    >>> old = kl.reuse_result_memory(0)           # off: every result in fresh memory
    >>> kl.reuse_result_memory(old)
    0
    """
    if isinstance(max_bytes, bool) or not isinstance(max_bytes, int | np.integer) or max_bytes < 0:
        raise ModelError(f"max_bytes: expected a whole number of bytes >= 0, got {describe(max_bytes)}")
    old = _pool.limit
    _pool.set_limit(int(max_bytes))
    return old


_UNITS = {"": 1, "K": 1 << 10, "M": 1 << 20, "G": 1 << 30, "T": 1 << 40}
DEFAULT_BUDGET = 2 << 30


def parse_size(text: str, where: str) -> int:
    """``"8G"``, ``"512M"``, ``"1.5G"``, ``"2000000000"`` (bytes; K, M, G, T are powers of 1024)."""
    t = str(text).strip().upper().removesuffix("B").removesuffix("I")
    number, unit = (t[:-1], t[-1]) if t and t[-1] in _UNITS else (t, "")
    try:
        value = float(number)
    except ValueError:
        value = math.nan
    if not (math.isfinite(value) and value * _UNITS[unit] >= 1):
        raise ModelError(f"{where}: expected a size such as 8G, 512M or a number of bytes (at "
                         f"least 1), got {describe(str(text)[:40])}")
    return int(value * _UNITS[unit])


def _budget_from_environment() -> int:
    import os
    text = os.environ.get("KINELAB_MEMORY_BUDGET")
    return parse_size(text, "KINELAB_MEMORY_BUDGET") if text else DEFAULT_BUDGET


_budget: int | None = None


def memory_budget(max_bytes: int | str | None = None) -> int:
    """The memory budget of one large result, bytes; with ``max_bytes``, set it and return
    the old one.

    A sweep's results, a grid of inputs, an export's columns: before allocating them kinelab
    estimates their size and refuses, saying the estimate and the budget, when it is larger.
    The default is 2 GiB (or ``KINELAB_MEMORY_BUDGET``, e.g. ``8G``); the command line takes
    ``kinelab --memory-budget 8G ...``.

    >>> old = kl.memory_budget("8G")
    >>> kl.memory_budget(old) == 8 * 2**30
    True
    """
    global _budget
    if _budget is None:
        _budget = _budget_from_environment()
    old = _budget
    if max_bytes is not None:
        if isinstance(max_bytes, bool) or not isinstance(max_bytes, (int, np.integer, str)):
            raise ModelError(f"max_bytes: expected a number of bytes or a size such as '8G', got "
                             f"{describe(max_bytes)}")
        _budget = parse_size(max_bytes, "max_bytes")
    return old


def require(nbytes: float, what: str, instead: str, *, source: str | None = None) -> None:
    """Refuse (MemoryBudgetError) an allocation of ``nbytes`` beyond the budget, saying
    ``what`` needs it and what to do ``instead`` (and naming ``source``, the file it is for)."""
    budget = memory_budget()
    if nbytes > budget:
        raise MemoryBudgetError(
            f"{what} would take about {byte_size(nbytes)}, more than the memory budget of "
            f"{byte_size(budget)}; {instead}, or raise the budget (kinelab.memory_budget('8G'), "
            "the environment variable KINELAB_MEMORY_BUDGET, or kinelab --memory-budget 8G)",
            source=source)
