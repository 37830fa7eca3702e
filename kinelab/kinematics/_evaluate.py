"""Running the kernel over a batch of inputs: compiled, on threads when the batch is large,
or in its numpy form while the compiled one is not ready (see ``_compiled.py``)."""
from __future__ import annotations

import functools
import os
from typing import TYPE_CHECKING

import numpy as np

from kinelab import _memory as memory
from kinelab.kinematics import _codes as k
from kinelab import _compiled
from kinelab.kinematics._plan import Plan

if TYPE_CHECKING:
    from concurrent.futures import ThreadPoolExecutor

__all__ = ["run", "run_compiled", "entry_point", "warm_up"]

PARALLEL_FROM = 4096       # samples per thread below which a sweep runs on the calling thread
_PIECE = 1 << 16           # samples a thread takes at a time: a thread that the system
                           # slows down leaves more of the sweep to the others


def _threads() -> int:
    import numba
    return max(1, min(numba.get_num_threads(), _cpu_count()))


@functools.cache
def _cpu_count() -> int:
    return os.cpu_count() or 1


@functools.cache
def _pool(workers: int) -> ThreadPoolExecutor:
    from concurrent.futures import ThreadPoolExecutor   # with logging: only for large sweeps
    return ThreadPoolExecutor(max_workers=workers, thread_name_prefix="kinelab")


def entry_point(p: Plan) -> str:
    """The kernel's entry point for a plan (see ``_compiled.ENTRIES``)."""
    kind = "closed_form" if p.groups is None else "continuation"
    return kind + "_one_input" if len(p.input_kinds) == 1 else kind


def run(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None, designs=None):
    """Run the kernel (compiled, or its numpy form until that is ready) over the rows of
    ``q``; see :func:`run_compiled`."""
    if _compiled.ready(entry_point(p)):
        return run_compiled(p, q, qd, qdd, start, ops_f, stored, designs)
    from kinelab.kinematics import _interpreter
    return _interpreter.run(p, q, qd, qdd, start, ops_f, stored, designs)


class Numbers:
    """The numbers a run takes, per design (a leading axis of D): the operations' parameters,
    the constants, and for Newton groups their constraints' numbers, their start (inputs and
    unknowns) and the mechanism's size; ``starts`` (D + 1) bounds each design's rows of q.
    One design: the plan's own numbers (or ``ops_f`` in their place, another assembly mode
    of its dyads; ``start`` = (q, group state) to continue Newton groups from)."""

    def __init__(self, p: Plan, N: int, ops_f=None, start=None, designs=None):
        M = len(p.input_kinds)
        if designs is None:
            self.D = 1
            self.ops_f = (p.ops_f if ops_f is None else ops_f)[None]
            self.const_values = p.const_values[None]
            self.starts = np.array([0, N], np.int64)
            self.scale = np.array([p.scale])
            if p.groups is not None:
                q0, x0 = (p.q_sketch, p.groups[3]) if start is None else start
                self.con_f = p.groups[2][None]
                self.x0 = np.asarray(x0, float).reshape(1, -1)
                self.q0 = np.asarray(q0, float).reshape(1, M)
        else:
            self.D = len(designs)
            if N % self.D:
                raise ValueError("the samples of D designs are D equal blocks of rows")
            self.ops_f, self.const_values = designs.ops_f, designs.const_values
            self.starts = np.arange(0, N + 1, N // self.D, dtype=np.int64)
            self.scale = designs.scale
            if p.groups is not None:
                self.con_f, self.x0 = designs.group_f, designs.group_x0
                self.q0 = designs.q_sketch if start is None else np.asarray(start[0], float)
                if start is not None:
                    self.x0 = np.asarray(start[1], float)
        if p.groups is not None:
            self.q_unit = np.stack([k.input_units(p.input_kinds, s) for s in self.scale])


def outputs(p: Plan, q, ops_f=None, stored=None) -> tuple[np.ndarray, np.ndarray, dict]:
    """The operation parameters and stored items of a run (the plan's unless given), and
    its outputs allocated for the rows of ``q`` (N, M), within the memory budget."""
    ops_f = p.ops_f if ops_f is None else ops_f
    stored = p.stored_items if stored is None else np.asarray(stored, np.int64)
    N, M = q.shape
    n = len(stored)
    nbytes = N * (8 * n * (3 + M + M * M) + 41)
    if nbytes > memory.memory_budget():          # (the message only then)
        memory.require(nbytes, f"the results of {N:,} samples ({n} coordinates each, with K, "
                       "L and rates)", "analyse fewer samples at a time (a sweep in pieces "
                       "continues with start=)")
    empty = np.empty if nbytes < memory.SMALLEST else memory.empty    # small: no reuse
    out = dict(jets=empty((N, n, 1 + M + M * M)), rates=empty((N, n, 2)),
               diag=empty((N, 2)), status=empty((N,), np.int8), fail=empty((N, 2)))
    return ops_f, stored, out


def run_compiled(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None, designs=None):
    """Run the compiled kernel over the rows of ``q`` (N, M) with rates ``qd``, ``qdd`` (N, M) or (1, M).

    ``start`` = (q, group state) to continue Newton groups from instead of the sketch;
    ``ops_f`` replaces the plan's operation parameters (another assembly mode of its dyads);
    ``stored`` the items written out (default the plan's ``stored_items``; an empty array
    when only the status is wanted); ``designs`` (:class:`~kinelab.kinematics._plan.Designs`,
    D of them) the numbers of D designs of the plan's topology, whose samples are D equal
    blocks of the rows of q.  Returns the kernel's outputs: jets, rates (of the stored
    items), diag (det J and the singularity measure), status and fail per sample, and the
    Newton state at the end (per design, with ``designs``).  Refuses results beyond the
    memory budget.
    """
    from kinelab.kinematics import _kernel
    _, stored, out = outputs(p, q, ops_f, stored)
    N, M = q.shape
    if p.groups is None and designs is None and M == 1 and N < 2 * PARALLEL_FROM:
        # a small sweep of one design: on this thread, with the plan's own numbers
        _kernel.run_closed_form_one_input(
            q, qd, qdd, np.array([0, N], np.int64), 0, 1, p.ops_i,
            (p.ops_f if ops_f is None else ops_f)[None], p.const_items, p.const_values[None],
            p.n_items, p.n_angles, stored, out["jets"], out["rates"], out["diag"],
            out["status"], out["fail"])
        return out
    nums = Numbers(p, N, ops_f, start, designs)
    tail = (out["jets"], out["rates"], out["diag"], out["status"], out["fail"])
    if p.groups is None:
        plan_args = (p.ops_i, nums.ops_f, p.const_items, nums.const_values, p.n_items,
                     p.n_angles, stored, *tail)
        run = _kernel.run_closed_form_one_input if M == 1 else _kernel.run_closed_form
        more = () if M == 1 else (M,)

        def piece(starts, d0, d1):
            run(q, qd, qdd, starts, d0, d1, *plan_args, *more)
        workers = min(_threads(), N // PARALLEL_FROM) if N >= 2 * PARALLEL_FROM else 1
        if workers <= 1:
            piece(nums.starts, 0, nums.D)
        elif nums.D == 1:   # the kernel releases the GIL: threads take pieces of the sweep in turn
            pieces = max(workers, N // _PIECE)
            bounds = np.linspace(0, N, pieces + 1).astype(np.int64)
            list(_pool(workers).map(lambda lo, hi: piece(np.array([lo, hi]), 0, 1),
                                    bounds[:-1], bounds[1:]))
        else:               # ... pieces of the designs
            pieces = min(nums.D, max(workers, N // _PIECE))
            bounds = np.linspace(0, nums.D, pieces + 1).astype(np.int64)
            list(_pool(workers).map(lambda d0, d1: piece(nums.starts, d0, d1),
                                    bounds[:-1], bounds[1:]))
    else:
        groups_i, con_i = p.groups[:2]
        nx = nums.x0.shape[1]
        state = np.empty((nums.D, nx + M))
        args = (q, qd, qdd, nums.starts, nums.q0, nums.q_unit, p.ops_i, nums.ops_f,
                p.const_items, nums.const_values, p.n_items, p.n_angles, stored, groups_i,
                con_i, nums.con_f, nums.x0, nums.scale, *tail, state)
        if M == 1:
            _kernel.run_continuation_one_input(*args)
        else:
            _kernel.run_continuation(*args, M)
        out["state"] = ((state[0, nx:].copy(), state[0, :nx].copy()) if designs is None
                        else (state[:, nx:].copy(), state[:, :nx].copy()))
    return out


def warm_up(name: str) -> None:
    """Run an entry point of the kernel once on a small mechanism, with the argument types
    of every call (see ``kinelab._compiled``)."""
    from kinelab import mechanisms
    from kinelab.kinematics._analyze import plan

    fourbar = mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    fivebar = mechanisms.fivebar(3.0, 1.0, 2.5, 2.5, 1.0)
    one, two = np.array([[0.1], [0.2]]), np.array([[1.2, 1.9], [1.25, 1.95]])
    if name == "closed_form_one_input":
        run_compiled(plan(fourbar), one, one, one)
        from kinelab.kinematics._analyze import run_small
        run_small(plan(fourbar), np.array([0.1, 0.2]), 0.1, 0.1)
    elif name == "driven_angles":
        from kinelab.kinematics import _kernel
        _kernel.driven_angles(two, 1, -1.0, np.empty(2))
    elif name == "closed_form":
        run_compiled(plan(fivebar), two, two, two)
    elif name == "continuation_one_input":
        run_compiled(plan(fourbar, method="newton"), one, one, one)
    elif name == "continuation":
        run_compiled(plan(fivebar, method="newton"), two, two, two)
    else:
        from kinelab.kinematics._tracker import Tracker
        one = Tracker(fourbar)._solution_kernel
        one.run_one_input(0.1, 0.2, 0.3, 0, np.empty(one.size))
        Tracker(fivebar)._solution_kernel.run_compiled(np.repeat(two[0:1], 3, axis=0), 0)
