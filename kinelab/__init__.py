"""kinelab: analysis and synthesis of mechanisms.

>>> import kinelab as kl
>>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
>>> sol = kl.analyze(fb, q=np.radians(np.arange(0, 360, 0.5)), qd=10.0)
>>> sol.angle("coupler").shape, sol.position("B").shape
((720,), (720, 2))
"""
from kinelab import (derive, dynamics, errors, io, kinematics, mechanisms, model, plot, solvers,
                     spatial, structure, synthesis)
from kinelab._memory import memory_budget, reuse_result_memory
from kinelab.io import load
from kinelab.kinematics import KinematicSolution, analyze
from kinelab.model import Mechanism

__all__ = ["errors", "model", "solvers", "mechanisms", "kinematics", "spatial", "structure",
           "synthesis", "dynamics", "derive", "io",
           "plot", "analyze", "load",
           "Mechanism", "KinematicSolution", "reuse_result_memory", "memory_budget"]
