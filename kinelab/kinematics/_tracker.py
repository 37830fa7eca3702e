"""Analysis one configuration at a time: an input dragged in an interactive view, a loop
that steps a simulation."""
from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import check_choice
from kinelab.kinematics import _codes as k
from kinelab import _compiled
from kinelab.kinematics._analyze import (Q_LIMITS, SINGULAR_TOL, _branch_map, _check_redundant,
                                         _normalise_q, analyze, plan)
from kinelab.kinematics._solution import KinematicSolution
from kinelab.model import MAX_RATE, Mechanism

__all__ = ["Tracker"]


class Tracker:
    """A mechanism prepared for analysis one configuration at a time.

    Each call of :func:`analyze` checks its arguments and arranges the kernel's; for a
    sweep that is nothing, for one configuration it is most of the call.  A tracker does it
    once, and then answers a configuration in a few microseconds: dragging an input in an
    interactive view, or stepping a simulation.  Its answers are those of ``analyze`` with
    the same options: a configuration that does not assemble raises (or, with
    ``unreachable="mask"``, comes out NaN), a singular one follows ``at_singular``.

    Newton groups go on from the configuration of the previous call, as
    ``analyze(start=...)`` does, so a drag stays on the branch it is on; closed-form groups
    follow the change points as ``analyze`` does.

    Parameters
    ----------
    mechanism : Mechanism
    method, at_change_point, unreachable, at_singular
        As in :func:`analyze`.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> drag = kl.kinematics.Tracker(fb)
    >>> drag.point_names
    ('O2', 'A', 'B', 'O4')
    >>> drag.positions(np.pi / 2).round(6)          # every point, m
    array([[0.      , 0.      ],
           [0.      , 1.      ],
           [2.615062, 2.470187],
           [3.      , 0.      ]])
    >>> float(drag(np.pi / 2, qd=10.0).omega("rocker")) == float(kl.analyze(fb, np.pi / 2, 10.0).omega("rocker"))
    True
    """

    def __init__(self, mechanism: Mechanism, *, method: Literal["auto", "newton"] = "auto",
                 at_change_point: Literal["smooth", "switch"] = "smooth",
                 unreachable: Literal["raise", "mask"] = "raise",
                 at_singular: Literal["auto", "raise", "flag"] = "auto"):
        self.plan = p = plan(mechanism, method=method)
        check_choice("at_change_point", at_change_point, ("smooth", "switch"))
        check_choice("unreachable", unreachable, ("raise", "mask"))
        check_choice("at_singular", at_singular, ("auto", "raise", "flag"))
        self._options = dict(method=method, at_change_point=at_change_point,
                             unreachable=unreachable, at_singular=at_singular)
        self.M = M = len(mechanism.inputs)
        self._q_limit = Q_LIMITS[p.input_kinds[0]]        # of the fast path's one input
        self._bmap = _branch_map(p, M, at_change_point)
        self._last: KinematicSolution | None = None       # where Newton groups go on from
        self._closed_form = p.groups is None
        if self._closed_form:
            tables = self._bmap.variants(np.zeros(1))[1] if self._bmap else [p.ops_f]
            point_items = [i for item in p.point_item.values() for i in (item, item + 1)]
            self._solution_kernel = _Packed(p, tables, p.stored_items, M)
            self._positions_kernel = _Packed(p, tables, np.array(point_items, np.int64), M)

    @property
    def mechanism(self) -> Mechanism:
        return self.plan.mechanism

    @property
    def point_names(self) -> tuple[str, ...]:
        """The points, in the order of the rows of :meth:`positions`."""
        return tuple(self.plan.point_item)

    def __call__(self, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0) -> KinematicSolution:
        """The analysis at ``q`` (with rates ``qd``, ``qdd``), as :func:`analyze` gives it."""
        x = self._one_sample(q, qd, qdd)
        if x is None:
            return self._analyze(q, qd, qdd)
        kernel = self._solution_kernel
        done = kernel.run(x, self._variant(x))
        if done is None:
            return self._analyze(q, qd, qdd)
        out, status = done
        jets, rates, diag, _, _ = kernel.views(out)
        if status != k.ST_OK or diag[1] < SINGULAR_TOL:
            return self._analyze(q, qd, qdd)          # its errors and flags, in full
        sol = KinematicSolution(
            plan=self.plan, q=x[0:1], qd=x[1:2], qdd=x[2:3], stored_jets=jets,
            stored_rates=rates, det_J=diag[0:1], singularity=diag[1:2], singular=_NO,
            assembled=_YES, single=True,
            change_points=self._bmap.change_points(x[0, 0], x[0, 0]) if self._bmap else ())
        if self.plan.redundant:
            _check_redundant(self.plan, sol)
        return sol

    def positions(self, q: ArrayLike) -> np.ndarray:
        """Position of every point at ``q``, m: shape (P, 2) in the order of
        :attr:`point_names`, or (N, P, 2) for a sweep.  Positions exist at a singular
        configuration: it is not flagged here."""
        x = self._one_sample(q, 0.0, 0.0)
        kernel = self._positions_kernel if x is not None else None
        done = kernel.run(x, self._variant(x)) if kernel is not None else None
        if done is None:
            sol = self._analyze(q, at_singular="flag")
            xy = sol.item_jets([i for i in self.plan.point_item.values() for i in (i, i + 1)])
            xy = xy[:, :, 0].reshape(sol.N, -1, 2)
            return xy[0] if sol.single else xy
        out, status = done
        if status != k.ST_OK:
            if self._options["unreachable"] == "raise":
                self._analyze(q)                           # raises, naming the group and the reach
            return np.full((len(self.point_names), 2), np.nan)
        return kernel.values(out).reshape(-1, 2)

    def _one_sample(self, q, qd, qdd) -> np.ndarray | None:
        """(3, M) rows q, q', q'' of one configuration of a plan in closed form, or None
        for anything else (a sweep; a plan with Newton groups), which analyze handles."""
        if not self._closed_form:
            return None
        if self.M == 1 and type(q) is float and type(qd) is float and type(qdd) is float:
            if abs(q) <= self._q_limit and abs(qd) <= MAX_RATE and abs(qdd) <= MAX_RATE:
                x = np.empty((3, 1))
                x[0, 0] = q
                x[1, 0] = qd
                x[2, 0] = qdd
                return x
        q2, qd2, qdd2, single = _normalise_q(q, qd, qdd, self.M, self.plan)
        if not single:
            return None
        return np.concatenate([q2, qd2, qdd2])

    def _variant(self, x: np.ndarray) -> int:
        """Which branch table the change points put this input on (0: the sketch's)."""
        if self._bmap is None:
            return 0
        index, _ = self._bmap.variants(x[0])
        return int(index[0])

    def _analyze(self, q, qd=0.0, qdd=0.0, **override) -> KinematicSolution:
        options = {**self._options, **override}
        sol = analyze(self.mechanism, q, qd, qdd, start=self._last, **options)
        if sol.newton_state is not None:
            self._last = sol
        return sol


_YES = np.ones(1, bool)
_YES.flags.writeable = False
_NO = np.zeros(1, bool)
_NO.flags.writeable = False


class _Packed:
    """A closed-form plan packed for the one-sample kernel, writing out the items ``stored``;
    with the parameters of each of its branches (``tables``, see BranchMap.variants)."""

    def __init__(self, p, tables: list[np.ndarray], stored: np.ndarray, M: int):
        packed = [k.pack_plan(p.ops_i, ops_f, p.const_items, p.const_values, p.n_items,
                              p.n_angles, stored) for ops_f in tables]
        self.plan_i = packed[0][0]
        self.plan_f = [f for _, f in packed]
        self.n = len(stored)
        self.jets, self.rates, self.diag, self.fail, self.status, self.size = \
            k.one_sample_layout(self.n, M)
        self.width = 1 + M + M * M

    def run(self, x: np.ndarray, variant: int) -> tuple[np.ndarray, int] | None:
        """The kernel's output and status at the sample ``x`` (3, M) on a branch, or None
        while the compiled kernel is not ready (see ``kinelab._compiled``)."""
        if not _compiled.ready("one_sample"):
            return None
        return self.run_compiled(x, variant)

    def run_compiled(self, x: np.ndarray, variant: int) -> tuple[np.ndarray, int]:
        from kinelab.kinematics import _kernel
        out = np.empty(self.size)
        status = _kernel.run_one_sample(x, self.plan_i, self.plan_f[variant], out)
        return out, status

    def views(self, out: np.ndarray):
        """The jets (1, n, w), rates (1, n, 2), diag (2,), fail (2,) and status of ``out``."""
        return (out[self.jets].reshape(1, self.n, self.width), out[self.rates].reshape(1, self.n, 2),
                out[self.diag], out[self.fail], out[self.status])

    def values(self, out: np.ndarray) -> np.ndarray:
        """The values of the stored items (n,), a view of ``out``."""
        return out[0:self.jets.stop:self.width]

