"""Running the kernel over a batch of inputs: compiled, on threads when the batch is large,
or in its numpy form while the compiled one is not ready (see ``_compiled.py``)."""
from __future__ import annotations

import functools
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from kinelab import _memory as memory
from kinelab.kinematics import _codes as k
from kinelab import _compiled
from kinelab.kinematics._plan import Plan

__all__ = ["run", "run_compiled", "entry_point", "warm_up"]

_PARALLEL_FROM = 4096      # samples per thread below which a sweep runs on the calling thread
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
    return ThreadPoolExecutor(max_workers=workers, thread_name_prefix="kinelab")


def entry_point(p: Plan) -> str:
    """The kernel's entry point for a plan (see ``_compiled.ENTRIES``)."""
    kind = "closed_form" if p.groups is None else "continuation"
    return kind + "_one_input" if len(p.input_kinds) == 1 else kind


def run(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None):
    """Run the kernel (compiled, or its numpy form until that is ready) over the rows of
    ``q``; see :func:`run_compiled`."""
    if _compiled.ready(entry_point(p)):
        return run_compiled(p, q, qd, qdd, start, ops_f, stored)
    from kinelab.kinematics import _interpreter
    return _interpreter.run(p, q, qd, qdd, start, ops_f, stored)


def outputs(p: Plan, q, ops_f=None, stored=None) -> tuple[np.ndarray, np.ndarray, dict]:
    """The operation parameters and stored items of a run (the plan's unless given), and
    its outputs allocated for the rows of ``q`` (N, M), within the memory budget."""
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
    return ops_f, stored, out


def run_compiled(p: Plan, q, qd, qdd, start=None, ops_f=None, stored=None):
    """Run the compiled kernel over the rows of ``q`` (N, M) with rates ``qd``, ``qdd`` (N, M) or (1, M).

    ``start`` = (q, group state) to continue Newton groups from instead of the sketch;
    ``ops_f`` replaces the plan's operation parameters (another assembly mode of its dyads);
    ``stored`` the items written out (default the plan's ``stored_items``; an empty array
    when only the status is wanted).  Returns the kernel's outputs: jets, rates (of the
    stored items), diag (det J and the singularity measure), status and fail per sample, and
    the Newton state at the end.  Refuses results beyond the memory budget.
    """
    from kinelab.kinematics import _kernel
    ops_f, stored, out = outputs(p, q, ops_f, stored)
    N, M = q.shape
    tail = (out["jets"], out["rates"], out["diag"], out["status"], out["fail"])
    if p.groups is None:
        plan_args = (p.ops_i, ops_f, p.const_items, p.const_values, p.n_items, p.n_angles,
                     stored, *tail)
        if M == 1:
            def piece(lo, hi):
                _kernel.run_closed_form_one_input(q, qd, qdd, lo, hi, *plan_args)
        else:
            def piece(lo, hi):
                _kernel.run_closed_form(q, qd, qdd, lo, hi, *plan_args, M)
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
        state = np.empty(len(x0) + M)
        args = (q, qd, qdd, np.array(q0, float), k.input_units(p.input_kinds, p.scale), p.ops_i, ops_f, p.const_items,
                p.const_values, p.n_items, p.n_angles, stored, groups_i, con_i, con_f,
                np.array(x0, float), p.scale, *tail, state)
        if M == 1:
            _kernel.run_continuation_one_input(*args)
        else:
            _kernel.run_continuation(*args, M)
        out["state"] = (state[len(x0):].copy(), state[:len(x0)].copy())
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
    elif name == "closed_form":
        run_compiled(plan(fivebar), two, two, two)
    elif name == "continuation_one_input":
        run_compiled(plan(fourbar, method="newton"), one, one, one)
    elif name == "continuation":
        run_compiled(plan(fivebar, method="newton"), two, two, two)
    else:
        from kinelab.kinematics._tracker import Tracker
        Tracker(fourbar)._positions_kernel.run_compiled(np.zeros((3, 1)), 0)
