"""kinelab: analysis and synthesis of mechanisms.

>>> import kinelab as kl
>>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
>>> sol = kl.analyze(fb, q=np.radians(np.arange(0, 360, 0.5)), qd=10.0)
>>> sol.angle("coupler").shape, sol.position("B").shape
((720,), (720, 2))
"""
from importlib import import_module as _import_module

from kinelab import errors, io, kinematics, mechanisms, model, solvers, verify
from kinelab._memory import memory_budget, reuse_result_memory
from kinelab.io import load
from kinelab.kinematics import KinematicSolution
from kinelab.verify import analyze
from kinelab.model import Mechanism

__all__ = ["errors", "model", "solvers", "mechanisms", "kinematics", "spatial", "structure",
           "synthesis", "dynamics", "derive", "verify", "sweep", "io",
           "plot", "analyze", "load",
           "Mechanism", "KinematicSolution", "reuse_result_memory", "memory_budget"]

# the rooms that bring in sympy, scipy.spatial, matplotlib or dask load on first use (kl.derive, ...),
# so that a command that does not need them starts quicker
_ON_FIRST_USE = ("derive", "dynamics", "plot", "spatial", "structure", "sweep", "synthesis")


def __getattr__(name):
    if name in _ON_FIRST_USE:
        return _import_module(f"kinelab.{name}")
    raise AttributeError(f"module 'kinelab' has no attribute {name!r}")


def __dir__():
    return sorted({n for n in globals() if not n.startswith("_")} | set(_ON_FIRST_USE))
