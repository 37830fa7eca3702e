"""Gear trains: simple, compound, reverted and epicyclic (planetary).

:func:`train` takes a train as a machine designer writes it — its meshes (driver, driven,
their numbers of teeth, external or internal), the gears that share a shaft, the gears an arm
carries, the members held still, the input and its speed — and returns a
:class:`TrainSolution`: the train value, every member's speed and acceleration, the output.
The pairs are the planar engine's gear joints (``G``, see the model format): the train is
built as a :class:`~kinelab.model.Mechanism` and analysed by
:func:`kinelab.kinematics.analyze`, which solves gear pairs exactly.
"""
from kinelab._lazy import exports

__getattr__, __dir__ = exports(__name__, {
    "kinelab.gears._train": ("MESH_KINDS", "FRAME", "TrainSolution", "train"),
})

__all__ = ["MESH_KINDS", "FRAME", "TrainSolution", "train"]
