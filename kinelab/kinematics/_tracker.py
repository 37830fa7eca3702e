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
    once, and then answers a configuration in a couple of microseconds (one input given as
    a number, a plan in closed form): dragging an input in an interactive view, the frames
    of an animation, a control loop, stepping a simulation.  Its answers are those of
    ``analyze`` with the same options, to the bit: a configuration that does not assemble
    raises (or, with ``unreachable="mask"``, comes out NaN), a singular one follows
    ``at_singular``.  See docs/kinematics.md, "One configuration at a time".

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
        self._solution_kernel = self._positions_kernel = None
        if self._closed_form:
            tables = self._bmap.variants(np.zeros(1))[1] if self._bmap else [p.ops_f]
            point_items = [i for item in p.point_item.values() for i in (item, item + 1)]
            self._solution_kernel = _Packed(p, tables, p.stored_items, M)
            self._positions_kernel = _Packed(p, tables, np.array(point_items, np.int64), M)
        self._quick = self._closed_form and M == 1      # one input given as a number: no checks
                                                        # but a few comparisons
        self._more_to_do = self._bmap is not None or bool(p.redundant)

    @property
    def mechanism(self) -> Mechanism:
        return self.plan.mechanism

    @property
    def point_names(self) -> tuple[str, ...]:
        """The points, in the order of the rows of :meth:`positions`."""
        return tuple(self.plan.point_item)

    def __call__(self, q: ArrayLike, qd: ArrayLike = 0.0, qdd: ArrayLike = 0.0) -> KinematicSolution:
        """The analysis at ``q`` (with rates ``qd``, ``qdd``), as :func:`analyze` gives it."""
        kernel = self._solution_kernel
        if (self._quick and type(q) in _NUMBERS and type(qd) in _NUMBERS
                and type(qdd) in _NUMBERS and abs(q) <= self._q_limit and abs(qd) <= MAX_RATE
                and abs(qdd) <= MAX_RATE and _compiled.ready("one_sample")):
            # the common call: one input given as three numbers, checked in a few
            # comparisons (NaN fails every one, and goes on to analyze, which names it)
            out = np.empty(kernel.size)
            v = 0 if self._bmap is None else self._variant_at(q)
            if kernel.kernel().run_tracked_one_input(q, qd, qdd, kernel.ints[v], kernel.floats[v],
                                                     out) >= SINGULAR_TOL:
                sol = _new(_OneConfiguration)
                sol.__dict__.update(plan=self.plan, _x=(q, qd, qdd), _kernel_out=out,
                                    _kernel=kernel)
                if self._more_to_do:
                    self._more(sol, q)
                return sol
            return self._analyze(q, qd, qdd)              # its errors and flags, in full
        x = self._one_sample(q, qd, qdd)
        if x is None:
            return self._analyze(q, qd, qdd)
        done = kernel.run(x, self._variant(x))
        if done is None:
            return self._analyze(q, qd, qdd)
        out, measure = done
        if not measure >= SINGULAR_TOL:
            return self._analyze(q, qd, qdd)              # its errors and flags, in full
        return self._answer(out, x, float(x[0, 0]))

    def _answer(self, out: np.ndarray, x, q0: float) -> KinematicSolution:
        """The solution of one configuration from the kernel's output ``out`` at the inputs
        ``x`` ((q, qd, qdd) of one input, or their rows (3, M))."""
        sol = _new(_OneConfiguration)
        sol.__dict__.update(plan=self.plan, _x=x, _kernel_out=out, _kernel=self._solution_kernel)
        return self._more(sol, q0)

    def _more(self, sol: KinematicSolution, q0: float) -> KinematicSolution:
        """A solution with the change points at ``q0``, its redundant joints checked."""
        if self._bmap is not None:
            sol.__dict__["change_points"] = self._bmap.change_points(q0, q0)
        if self.plan.redundant:
            _check_redundant(self.plan, sol)
        return sol

    def positions(self, q: ArrayLike) -> np.ndarray:
        """Position of every point at ``q``, m: shape (P, 2) in the order of
        :attr:`point_names`, or (N, P, 2) for a sweep.  Positions exist at a singular
        configuration: it is not flagged here."""
        kernel = self._positions_kernel
        if (self._quick and type(q) in _NUMBERS and abs(q) <= self._q_limit
                and _compiled.ready("one_sample")):
            out = np.empty(kernel.size)
            done = out, kernel.run_one_input(q, 0.0, 0.0, self._variant_at(q), out)
        else:
            x = self._one_sample(q, 0.0, 0.0)
            done = kernel.run(x, self._variant(x)) if x is not None else None
        if done is None:
            sol = self._analyze(q, at_singular="flag")
            xy = sol.item_jets([i for i in self.plan.point_item.values() for i in (i, i + 1)])
            xy = xy[:, :, 0].reshape(sol.N, -1, 2)
            return xy[0] if sol.single else xy
        out, measure = done
        if measure < 0.0:                                  # it does not assemble
            if self._options["unreachable"] == "raise":
                self._analyze(q)                           # raises, naming the group and the reach
            return np.full((len(self.point_names), 2), np.nan)
        return kernel.values(out).reshape(-1, 2)

    def _one_sample(self, q, qd, qdd) -> np.ndarray | None:
        """(3, M) rows q, q', q'' of one configuration of a plan in closed form, or None
        for anything else (a sweep; a plan with Newton groups), which analyze handles."""
        if not self._closed_form:
            return None
        q2, qd2, qdd2, single = _normalise_q(q, qd, qdd, self.M, self.plan)
        if not single:
            return None
        return np.concatenate([q2, qd2, qdd2])

    def _variant(self, x: np.ndarray) -> int:
        """Which branch table the change points put this input on (0: the sketch's)."""
        return self._variant_at(float(x[0, 0])) if self.M == 1 else 0

    def _variant_at(self, q: float) -> int:
        """:meth:`_variant` of one input's value."""
        if self._bmap is None:
            return 0
        index, _ = self._bmap.variants(np.array([q]))
        return int(index[0])

    def _analyze(self, q, qd=0.0, qdd=0.0, **override) -> KinematicSolution:
        options = {**self._options, **override}
        sol = analyze(self.mechanism, q, qd, qdd, start=self._last, **options)
        if sol.newton_state is not None:
            self._last = sol
        return sol


_NUMBERS = (float, np.float64)     # inputs a tracker takes as they are, on its quick path
_new = object.__new__
_KERNEL = []                       # the compiled kernel's module, once imported
_YES = np.ones(1, bool)
_YES.flags.writeable = False
_NO = np.zeros(1, bool)
_NO.flags.writeable = False


class _FromKernel:
    """A field of :class:`_OneConfiguration` made from the kernel's output on first use."""

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, sol, owner=None):
        if sol is None:
            return self
        d = sol.__dict__
        packed, out, x = d["_kernel"], d["_kernel_out"], d["_x"]
        if self.name in ("q", "qd", "qdd"):
            row = ("q", "qd", "qdd").index(self.name)
            value = (np.array([[x[row]]]) if type(x) is tuple else x[row:row + 1])
        elif self.name == "stored_jets":
            value = packed.jets(out)
        elif self.name == "stored_rates":
            value = packed.rates(out)
        else:
            value = packed.diag(out)[0:1] if self.name == "det_J" else packed.diag(out)[1:2]
        d[self.name] = value
        return value


class _OneConfiguration(KinematicSolution):
    """A tracker's answer: a :class:`KinematicSolution` of one configuration whose arrays are
    made from the kernel's output when first asked for (a few accessors are all most
    callers read of it).  Assembled, not singular (the others come from ``analyze``)."""

    q = _FromKernel()
    qd = _FromKernel()
    qdd = _FromKernel()
    stored_jets = _FromKernel()
    stored_rates = _FromKernel()
    det_J = _FromKernel()
    singularity = _FromKernel()
    singular = _NO
    assembled = _YES
    single = True

    # The accessors of one input's stored items, read from the kernel's output directly (a
    # value, or a point's two, as the general accessors give them); the rest as theirs.
    def _value(self, name: str, kinds: str, column: int, source: str = "jets"):
        i, w, stored, drive = self._where(name, kinds)
        d = self.__dict__
        if stored < 0 or type(d.get("_x")) is not tuple:
            return super()._value(name, kinds, column, source)
        width = d["_kernel"].width
        at = (stored if source == "jets" else d["_kernel"].n + stored) * width + column
        out = d["_kernel_out"]
        return out[at] if w == 1 else out[at:at + w * width:width]

    def K(self, name: str):
        return self._coefficient(name, 1)

    def L(self, name: str):
        return self._coefficient(name, 2)

    def _coefficient(self, name: str, column: int):
        i, w, stored, drive = self._where(name, "lsp")
        d = self.__dict__
        if stored < 0 or type(d.get("_x")) is not tuple:
            return super().K(name) if column == 1 else super().L(name)
        width = d["_kernel"].width
        at = stored * width + column
        out = d["_kernel_out"]
        return out[at] if w == 1 else out[at:at + w * width:width]


class _Packed:
    """A closed-form plan packed for the kernel's one-sample entries, writing out the items
    ``stored``; with the parameters of each of its branches (``tables``, see
    BranchMap.variants) and the scratch space of its samples."""

    def __init__(self, p, tables: list[np.ndarray], stored: np.ndarray, M: int):
        packed = [k.pack_tracked(p.ops_i, ops_f, p.const_items, p.const_values, p.n_items,
                                 p.n_angles, stored, M) for ops_f in tables]
        self.ints = [i for i, _ in packed]
        self.floats = [f for _, f in packed]
        self.n = n = len(stored)
        self.width, self.size = k.tracked_layout(n, M)

    @staticmethod
    def kernel():
        """The compiled kernel (imported on first use: importing numba takes a while)."""
        if not _KERNEL:
            from kinelab.kinematics import _kernel
            _KERNEL.append(_kernel)
        return _KERNEL[0]

    def run(self, x: np.ndarray, variant: int) -> tuple[np.ndarray, float] | None:
        """The kernel's output and the singularity measure (-1 where the sample does not
        assemble) at the sample ``x`` (3, M) on a branch, or None while the compiled kernel
        is not ready (see ``kinelab._compiled``)."""
        if not _compiled.ready("one_sample"):
            return None
        return self.run_compiled(x, variant)

    def run_compiled(self, x: np.ndarray, variant: int) -> tuple[np.ndarray, float]:
        out = np.empty(self.size)
        measure = self.kernel().run_tracked(np.ascontiguousarray(x, float), self.ints[variant],
                                            self.floats[variant], out)
        return out, measure

    def run_one_input(self, q: float, qd: float, qdd: float, variant: int,
                      out: np.ndarray) -> float:
        """The singularity measure (-1 where the sample does not assemble) at one input q
        with rates qd, qdd, the kernel's output written to ``out``; the compiled kernel
        must be ready."""
        return self.kernel().run_tracked_one_input(q, qd, qdd, self.ints[variant],
                                                   self.floats[variant], out)

    # the kernel's output, as the fields of a solution (see _codes.tracked_layout)
    def jets(self, out: np.ndarray) -> np.ndarray:
        return out[:self.n * self.width].reshape(1, self.n, self.width)

    def rates(self, out: np.ndarray) -> np.ndarray:
        return out[self.n * self.width:2 * self.n * self.width].reshape(1, self.n, self.width)[:, :, :2]

    def diag(self, out: np.ndarray) -> np.ndarray:
        """det J and the singularity measure (2,)."""
        return out[2 * self.n * self.width:2 * self.n * self.width + 2]

    def values(self, out: np.ndarray) -> np.ndarray:
        """The values of the stored items (n,), a view of ``out``."""
        return out[0:self.n * self.width:self.width]
