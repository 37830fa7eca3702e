"""Dynamics by Gibbs-Appell / Kane: inverse and forward dynamics of planar mechanisms.

The notes' equations ``C^T D f = 0`` (*Mecanismos*, §5) in the independent coordinates q:
C is the engine's velocity-coefficient matrix K (with the identity rows of the inputs)
and its time derivative comes from the acceleration coefficients L, so every term is a
vectorised product of K, L and the mass data over the samples.

- :func:`inverse` -- actuator efforts, joint reactions and shaking force over a motion;
- :func:`simulate` -- the motion under given actuator laws and loads, one run or a batch;
- :class:`Loads` -- gravity, point forces, torques, springs, dampers, Coulomb friction in
  joints, torsional springs and dampers;
- :class:`MassProperties` -- the links' masses and inertias, point masses, lumping;
- :class:`DynamicsSetup` -- a model file's ``[dynamics]`` section (loads, actuator laws);
- :func:`flywheel` -- flywheel sizing from a torque curve;
- :func:`equations_of_motion` -- the equations in symbols (sympy), for open chains.
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab._expressions": ("parse_expression", "parse_table", "to_sympy"),
    "kinelab.dynamics._flywheel": ("Flywheel", "flywheel"),
    "kinelab.dynamics._forward": ("Simulation", "SimulationBatch", "simulate"),
    "kinelab.dynamics._inverse": ("InverseDynamics", "inverse"),
    "kinelab.dynamics._loads": ("STANDARD_GRAVITY", "Damper", "Law", "Loads", "PointForce",
                                "Spring", "Torque", "Friction", "TorsionalSpring",
                                "TorsionalDamper"),
    "kinelab.dynamics._masses": ("LinkMass", "MassProperties", "PointMass"),
    "kinelab.dynamics._setup": ("DynamicsSetup",),
    "kinelab.dynamics._symbolic": ("EquationsOfMotion", "equations_of_motion"),
})

__all__ = ["inverse", "InverseDynamics", "simulate", "Simulation", "SimulationBatch", "Loads", "PointForce", "Torque", "Spring", "Damper",
           "Friction", "TorsionalSpring", "TorsionalDamper", "Law", "STANDARD_GRAVITY", "MassProperties", "LinkMass", "PointMass",
           "DynamicsSetup", "flywheel", "Flywheel", "equations_of_motion", "EquationsOfMotion",
           "parse_expression", "parse_table", "to_sympy"]
