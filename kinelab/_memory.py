"""Large result arrays, taken from memory that earlier results no longer use.

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

from kinelab.errors import ModelError

_SMALLEST = 1 << 20                 # smaller arrays come from the allocator's own free lists
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
        if nbytes < _SMALLEST or nbytes > self.limit:
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
        raise ModelError(f"max_bytes: expected a whole number of bytes >= 0, got {max_bytes!r}")
    old = _pool.limit
    _pool.set_limit(int(max_bytes))
    return old
