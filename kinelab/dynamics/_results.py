"""What the results of inverse and forward dynamics share: names, kinds, export."""
from __future__ import annotations

import math
import os

import numpy as np

from kinelab.kinematics import plan
from kinelab.model import Mechanism


class MotionResult:
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

    def _motion_columns(self, degrees: bool) -> dict[str, np.ndarray]:
        """Time, each input's q, qd, qdd and its actuator's effort, with units."""
        cols: dict[str, np.ndarray] = {"t [s]": self.t}
        for i, (name, kind) in enumerate(zip(self.input_names, self.input_kinds)):
            u, s = (("deg", 180.0 / math.pi) if degrees else ("rad", 1.0)) if kind == "angle" else ("m", 1.0)
            cols[f"{name}.q [{u}]"] = self.q[:, i] * s
            cols[f"{name}.qd [{u}/s]"] = self.qd[:, i] * s
            cols[f"{name}.qdd [{u}/s^2]"] = self.qdd[:, i] * s
            cols[f"{name}.{'torque [N m]' if kind == 'angle' else 'force [N]'}"] = self.input_forces[:, i]
        return cols

    def columns(self, degrees: bool = False) -> dict[str, np.ndarray]:   # pragma: no cover
        raise NotImplementedError

    def to_dataframe(self, degrees: bool = False):
        """A pandas DataFrame of :meth:`columns`, one row per sample."""
        import pandas as pd
        return pd.DataFrame(self.columns(degrees=degrees))

    def to_csv(self, path: str | os.PathLike, degrees: bool = False) -> None:
        """Write :meth:`columns` as CSV (to a temporary file, then renamed)."""
        from kinelab._files import write_csv
        write_csv(self.columns(degrees=degrees), path)
