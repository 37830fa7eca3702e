"""Position, velocity and acceleration analysis of any planar mechanism.

The notes' method (Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*;
*Mecanismos*, §4.4-4.8): position equations Phi(q, S) = 0, Jacobian
J = dPhi/dS and Q = dPhi/dq, velocity coefficients K = -J^-1 Q and acceleration
coefficients L = dK/dq, singular configurations where det J = 0.

The graphical methods (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de
Velocidades*, §4.6; Badan (IFG), *Análise de aceleração*) as data:
:func:`acceleration_difference`, :func:`relative_acceleration`, :func:`velocity_polygon`,
:func:`acceleration_polygon`, :func:`kennedy_construction`, :func:`centrodes`,
:func:`velocity_ratio`, and :func:`differentiate` for measured curves; the constructions
step by step: :func:`tangent_construction`, :func:`velocity_image`, :func:`kennedy_steps`.
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.kinematics._analyze": ("SINGULAR_TOL", "AssemblyStatus", "analyze", "analyze_designs",
                                    "assembly_status", "change_points", "plan", "reachable_ranges",
                                    "turns_fully"),
    "kinelab.kinematics._assemble": ("Assembly", "SketchNotAssembled", "assemble", "pose",
                                     "reassemble"),
    "kinelab.kinematics._branches": ("ChangePoint",),
    "kinelab.kinematics._constructions": ("KennedyDrawingStep", "KennedyLine", "KennedySteps",
                                          "TangentConstruction", "VelocityImage", "kennedy_steps",
                                          "tangent_construction", "velocity_image"),
    "kinelab.kinematics._dead_centres": ("DeadCentres", "Toggle", "ToggleLocus",
                                         "dead_centres", "toggles", "input_span"),
    "kinelab.kinematics._centrodes": ("Centrodes", "KennedyConstruction", "KennedyStep",
                                      "centrodes", "kennedy_construction", "velocity_ratio"),
    "kinelab.kinematics._input_errors": ("SingularInput", "UnreachableInput"),
    "kinelab.kinematics._instant_centers": ("InstantCenter", "InstantCenters", "instant_center",
                                            "instant_centers"),
    "kinelab.kinematics._measures": ("TimeRatio", "time_ratio", "transmission_angle"),
    "kinelab.kinematics._plan": ("Plan", "Step"),
    "kinelab.kinematics._polygons": ("AccelerationDifference", "AccelerationPolygon", "LinkImage",
                                     "RelativeAcceleration", "Side", "VelocityPolygon",
                                     "acceleration_difference", "acceleration_polygon",
                                     "relative_acceleration", "velocity_polygon"),
    "kinelab.kinematics._solution": ("AccelerationComponents", "DesignSolution", "GuidePoint",
                                     "KinematicSolution"),
    "kinelab.kinematics._tracker": ("Tracker",),
    "kinelab.solvers": ("Derivatives", "differentiate"),
})

__all__ = ["analyze", "analyze_designs", "DesignSolution", "plan", "reachable_ranges", "turns_fully",
           "KinematicSolution", "AccelerationComponents",
           "GuidePoint",
           "Plan", "Step", "SINGULAR_TOL", "transmission_angle", "time_ratio", "TimeRatio",
           "instant_center", "instant_centers", "InstantCenter", "InstantCenters", "change_points",
           "ChangePoint", "assemble", "reassemble", "Assembly", "SketchNotAssembled", "pose", "assembly_status",
           "AssemblyStatus", "UnreachableInput", "SingularInput",
           "Tracker", "acceleration_difference", "AccelerationDifference", "relative_acceleration",
           "RelativeAcceleration", "velocity_polygon", "VelocityPolygon", "acceleration_polygon",
           "AccelerationPolygon", "Side", "LinkImage", "kennedy_construction",
           "KennedyConstruction", "KennedyStep", "centrodes", "Centrodes", "velocity_ratio",
           "differentiate", "Derivatives", "dead_centres", "DeadCentres", "toggles", "Toggle", "ToggleLocus",
           "input_span", "tangent_construction", "TangentConstruction", "velocity_image",
           "VelocityImage", "kennedy_steps", "KennedySteps", "KennedyDrawingStep", "KennedyLine"]
