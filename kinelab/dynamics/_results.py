"""What the results of inverse and forward dynamics share: names, kinds, export."""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab.kinematics import plan
from kinelab.kinematics._columns import Columns, TableExport
from kinelab.model import Mechanism, Units


class MotionResult(TableExport):
    """Base of the dynamics results: a motion (``t``, ``q``, ``qd``, ``qdd``, (N, M)) with
    the actuators' ``input_forces`` and its ``kinematics``; subclasses add their columns."""

    @property
    def mechanism(self) -> Mechanism:
        return self.kinematics.mechanism

    @property
    def q(self) -> np.ndarray:
        return self.kinematics.q

    @property
    def qd(self) -> np.ndarray:
        return self.kinematics.qd

    @property
    def qdd(self) -> np.ndarray:
        return self.kinematics.qdd

    @property
    def N(self) -> int:
        return self.q.shape[0]

    @property
    def input_names(self) -> tuple[str, ...]:
        return self.mechanism.input_names

    @property
    def input_kinds(self) -> tuple[str, ...]:
        """"angle" (effort a torque, N m) or "slide" (a force, N) for each input."""
        return plan(self.mechanism).input_kinds

    def _motion_columns(self, units: Units) -> Columns:
        """Time, each input's q, qd, qdd (in ``units``) and its actuator's effort (SI)."""
        cols = Columns(units)
        cols.add("t", "", "s", self.t)
        cols.add_inputs(self.input_names, self.input_kinds, self.q, self.qd, self.qdd)
        for i, (name, kind) in enumerate(zip(self.input_names, self.input_kinds)):
            effort = ("torque", "N*m") if kind == "angle" else ("force", "N")
            cols.add(name, *effort, self.input_forces[:, i], convert=False)
        return cols

    def _columns(self, units: Units) -> Columns:   # pragma: no cover
        raise NotImplementedError

    def columns(self, degrees: bool = False, *,
                units: Units | Mapping[str, str] | None = None) -> dict[str, np.ndarray]:
        """Named (N,) columns ``item.quantity[unit]``: time, the inputs' q, qd, qdd in
        ``units`` (default SI; ``degrees=True`` for angles in degrees), and the dynamic
        results, which stay in SI: forces in N, torques and moments in N*m, energies in J,
        powers in W."""
        return dict(self._columns(Units.resolve(units, degrees=degrees)))
