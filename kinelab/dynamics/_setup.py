"""The ``[dynamics]`` section of a model file: loads, actuator laws, mass declarations."""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from kinelab.dynamics._loads import Law, Loads
from kinelab.dynamics._masses import MassProperties, _positive, declaration_problems
from kinelab.errors import ModelError, describe, shown, shown_key
from kinelab.model import Mechanism

__all__ = ["DynamicsSetup"]

_LOAD_KEYS = ("gravity", "forces", "torques", "springs", "dampers", "friction", "torsional_springs",
              "torsional_dampers")
_KEYS = _LOAD_KEYS + ("actuators", "massless", "point_masses")


@dataclass(frozen=True, eq=False)
class DynamicsSetup:
    """Everything a model file says about dynamics besides the links' own mass data.

    Parameters
    ----------
    loads : Loads
    actuators : mapping of str to Law
        Actuator law of each driven input, by input name (for :func:`simulate`).
    massless : tuple of str
        Moving links without mass.
    point_masses : mapping of str to float
        Lumped masses at named points, kg.

    Examples
    --------
    >>> setup = DynamicsSetup.from_dict({
    ...     "gravity": [0.0, -9.81],
    ...     "actuators": {"jO2": "5 - 0.01 * qd"},
    ...     "forces": [{"point": "B", "fx": "-200 * (sin(q) > 0)", "fy": 0.0}]})
    >>> setup.loads.gravity, sorted(setup.actuators)
    ((0.0, -9.81), ['jO2'])
    >>> DynamicsSetup.from_dict(setup.to_dict()).to_dict() == setup.to_dict()
    True
    """

    loads: Loads = field(default_factory=Loads)
    actuators: Mapping[str, Law] = field(default_factory=dict)
    massless: tuple[str, ...] = ()
    point_masses: Mapping[str, float] = field(default_factory=dict)

    def masses(self, model: Mechanism) -> MassProperties:
        """The model's mass properties with this section's massless links and point masses."""
        return MassProperties.from_model(model, massless=self.massless, point_masses=self.point_masses)

    def inputs(self) -> dict[str, Law]:
        """The actuator laws, for ``simulate(..., inputs=setup.inputs())``."""
        return dict(self.actuators)

    def to_dict(self) -> dict[str, Any]:
        """Plain data for a model file (numbers, expressions and tables only)."""
        out = self.loads.to_dict()
        if self.actuators:
            out["actuators"] = {k: law.to_data() for k, law in self.actuators.items()}
        if self.massless:
            out["massless"] = list(self.massless)
        if self.point_masses:
            out["point_masses"] = dict(self.point_masses)
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any] | None, *, where: str = "dynamics") -> DynamicsSetup:
        """Read a ``[dynamics]`` section (plain data, SI units); every problem at once.

        The format is described in ``docs/dynamics.md``.  Expressions are parsed, never
        executed.
        """
        if data is None:
            return cls()
        if not isinstance(data, Mapping):
            raise ModelError(f"{where}: expected a table, got {describe(data)}")
        problems: list[str] = []
        unknown = set(data) - set(_KEYS)
        if unknown:
            problems.append(f"{where}: unknown key(s) {', '.join(sorted(map(repr, unknown)))}; "
                            f"expected some of {', '.join(map(repr, _KEYS))}")
        loads = Loads()
        try:
            loads = Loads.from_dict({k: v for k, v in data.items() if k in _LOAD_KEYS}, where=where)
        except ModelError as exc:
            problems.extend(exc.problems)
        actuators: dict[str, Law] = {}
        raw = data.get("actuators", {})
        if not isinstance(raw, Mapping):
            problems.append(f"{where}.actuators: expected a table of input name = law, got {describe(raw)}")
        else:
            for name, law in raw.items():
                try:
                    actuators[str(name)] = Law(law, f"{where}.actuators.{shown_key(name)}")
                except ModelError as exc:
                    problems.extend(exc.problems)
        massless = data.get("massless", ())
        if not isinstance(massless, (list, tuple)) or not all(isinstance(n, str) for n in massless):
            problems.append(f"{where}.massless: expected a list of link names, got {describe(massless)}")
            massless = ()
        lumps = data.get("point_masses", {})
        if not isinstance(lumps, Mapping):
            problems.append(f"{where}.point_masses: expected a table of point = mass (kg), got {describe(lumps)}")
            lumps = {}
        for p, mass in lumps.items():
            if not _positive(mass):
                problems.append(f"{where}.point_masses.{shown_key(p)}: expected a positive mass (kg), got {describe(mass)}")
        if problems:
            raise ModelError(problems)
        return cls(loads=loads, actuators=actuators, massless=tuple(massless),
                   point_masses={str(k): float(v) for k, v in lumps.items()})

    @classmethod
    def from_model(cls, model: Mechanism) -> DynamicsSetup:
        """The section a model file carried, kept by :func:`kinelab.load` in
        ``model.parameters["dynamics"]`` (an empty setup when there is none)."""
        return cls.from_dict(model.parameters.get("dynamics"), where="dynamics")

    def check(self, model: Mechanism) -> None:
        """Raise a ModelError listing every name the model does not have (and a massless
        link that has a mass, or a point mass that is not positive)."""
        problems = self.loads.problems(model) + declaration_problems(model, self.massless,
                                                                      self.point_masses)
        for name in self.actuators:
            if name not in model.input_names:
                what = ("is a joint but not an input" if name in model.joint_names
                        else "is not an input")
                problems.append(f"dynamics.actuators: {shown(name)} {what}; the inputs are "
                                f"{', '.join(map(repr, model.input_names))}")
        if problems:
            raise ModelError(problems, source=f"mechanism '{model.name}'")
