"""Running the compiled kernel over a batch of inputs, on threads when the batch is large."""
from __future__ import annotations

import functools
import os
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np

from kinelab import _memory as memory
from kinelab.kinematics import _kernel as k
from kinelab.kinematics._plan import Plan

__all__ = ["run"]

_CONTINUATION_STEP = 0.05  # largest continuation step of a Newton group, rad (or m / scale)
_PARALLEL_FROM = 4096      # samples per thread below which a sweep runs on the calling thread
_PIECE = 1 << 16           # samples a thread takes at a time: a thread that the system
                           # slows down leaves more of the sweep to the others


def _threads() -> int:
    return max(1, min(numba.get_num_threads(), _cpu_count()))


@functools.cache
def _cpu_count() -> int:
    return os.cpu_count() or 1


@functools.cache
def _pool(workers: int) -> ThreadPoolExecutor:
    return ThreadPoolExecutor(max_workers=workers, thread_name_prefix="kinelab")


def run(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None):
    """Run the kernel over the rows of ``q`` (N, M) with rates ``qd``, ``qdd`` (N, M) or (1, M).

    ``start`` = (q, group state) to continue Newton groups from instead of the sketch;
    ``ops_f`` replaces the plan's operation parameters (another assembly mode of its dyads);
    ``stored`` the items written out (default the plan's ``stored_items``; an empty array
    when only the status is wanted).  Returns the kernel's outputs: jets, rates (of the
    stored items), diag (det J and the singularity measure), status and fail per sample, and
    the Newton state at the end.  Refuses results beyond the memory budget.
    """
    ops_f = p.ops_f if ops_f is None else ops_f
    stored = p.stored_items if stored is None else np.asarray(stored, np.int64)
    N, M = q.shape
    n = len(stored)
    memory.require(N * (8 * n * (3 + M + M * M) + 41),
                   f"the results of {N:,} samples ({n} coordinates each, with K, L and rates)",
                   "analyse fewer samples at a time (a sweep in pieces continues with start=)")
    out = dict(jets=memory.empty((N, n, 1 + M + M * M)), rates=memory.empty((N, n, 2)),
               diag=memory.empty((N, 2)), status=memory.empty((N,), np.int8),
               fail=memory.empty((N, 2)))
    tail = (out["jets"], out["rates"], out["diag"], out["status"], out["fail"])
    if p.groups is None:
        plan_args = (p.ops_i, ops_f, p.const_items, p.const_values, p.n_items, p.n_angles,
                     stored, *tail)
        if M == 1:
            def piece(lo, hi):
                k.run_closed_form_one_input(q, qd, qdd, lo, hi, *plan_args)
        else:
            def piece(lo, hi):
                k.run_closed_form(q, qd, qdd, lo, hi, *plan_args, M)
        workers = min(_threads(), N // _PARALLEL_FROM) if N >= 2 * _PARALLEL_FROM else 1
        if workers <= 1:
            piece(0, N)
        else:   # the kernel releases the GIL: threads take pieces of the sweep in turn
            pieces = max(workers, N // _PIECE)
            bounds = np.linspace(0, N, pieces + 1).astype(int)
            list(_pool(workers).map(piece, bounds[:-1], bounds[1:]))
    else:
        groups_i, con_i, con_f, x0 = p.groups
        q0 = p.q_sketch
        if start is not None:
            q0, x0 = start
        # continuation steps of at most 0.05 rad (or 0.05 sizes of the mechanism for slides)
        max_step = _CONTINUATION_STEP * (1.0 if all(kd == "angle" for kd in p.input_kinds)
                                         else min(1.0, p.scale))
        state = np.empty(len(x0) + M)
        args = (q, qd, qdd, np.array(q0, float), max_step, p.ops_i, ops_f, p.const_items,
                p.const_values, p.n_items, p.n_angles, stored, groups_i, con_i, con_f,
                np.array(x0, float), p.scale, *tail, state)
        if M == 1:
            k.run_continuation_one_input(*args)
        else:
            k.run_continuation(*args, M)
        out["state"] = (state[len(x0):].copy(), state[:len(x0)].copy())
    return out
