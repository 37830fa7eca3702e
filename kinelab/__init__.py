"""kinelab: analysis and synthesis of mechanisms.

>>> import kinelab as kl
>>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
>>> sol = kl.analyze(fb, q=np.radians(np.arange(0, 360, 0.5)), qd=10.0)
>>> sol.angle("coupler").shape, sol.position("B").shape
((720,), (720, 2))
"""
from importlib import import_module as _import_module

__all__ = ["errors", "model", "solvers", "mechanisms", "kinematics", "cams", "gears", "spatial", "structure",
           "synthesis", "dynamics", "derive", "verify", "sweep", "io",
           "plot", "gallery", "analyze", "load",
           "Mechanism", "KinematicSolution", "reuse_result_memory", "memory_budget"]

# Every name is loaded on first use (PEP 562), rooms included: `import kinelab` costs next to
# nothing, and a command imports only the rooms it works with (`kinelab --help` none of them).
_ROOMS = ("errors", "model", "solvers", "mechanisms", "kinematics", "cams", "gears", "spatial", "structure",
          "synthesis", "dynamics", "derive", "verify", "sweep", "io", "plot", "gallery")
_NAMES = {"analyze": "kinelab.verify", "load": "kinelab.io",
          "Mechanism": "kinelab.model", "KinematicSolution": "kinelab.kinematics",
          "reuse_result_memory": "kinelab._memory", "memory_budget": "kinelab._memory"}


def __getattr__(name):
    if name in _ROOMS:
        value = _import_module(f"kinelab.{name}")
    elif name in _NAMES:
        value = getattr(_import_module(_NAMES[name]), name)
    else:
        raise AttributeError(f"module 'kinelab' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted({n for n in globals() if not n.startswith("_")} | set(__all__))
