"""Position, velocity and acceleration analysis of any planar mechanism.

The notes' method (Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*;
*Mecanismos*, §4.4-4.8): position equations Phi(q, S) = 0, Jacobian
J = dPhi/dS and Q = dPhi/dq, velocity coefficients K = -J^-1 Q and acceleration
coefficients L = dK/dq, singular configurations where det J = 0.

The graphical methods (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de
Velocidades*, §4.6; Badan (IFG), *Análise de aceleração*) as data:
:func:`acceleration_difference`, :func:`relative_acceleration`, :func:`velocity_polygon`,
:func:`acceleration_polygon`, :func:`kennedy_construction`, :func:`centrodes`,
:func:`velocity_ratio`, and :func:`differentiate` for measured curves.
"""
from kinelab.kinematics._analyze import (SINGULAR_TOL, AssemblyStatus, analyze, assembly_status,
                                         change_points, plan, reachable_ranges, turns_fully)
from kinelab.kinematics._assemble import (Assembly, SketchNotAssembled, assemble, pose,
                                          reassemble)
from kinelab.kinematics._branches import ChangePoint
from kinelab.kinematics._centrodes import (Centrodes, KennedyConstruction, KennedyStep, centrodes,
                                          kennedy_construction, velocity_ratio)
from kinelab.kinematics._input_errors import SingularInput, UnreachableInput
from kinelab.kinematics._instant_centers import (InstantCenter, InstantCenters, instant_center,
                                                 instant_centers)
from kinelab.kinematics._measures import TimeRatio, time_ratio, transmission_angle
from kinelab.kinematics._plan import Plan, Step
from kinelab.kinematics._polygons import (AccelerationDifference, AccelerationPolygon, LinkImage,
                                         RelativeAcceleration, Side, VelocityPolygon,
                                         acceleration_difference, acceleration_polygon,
                                         relative_acceleration, velocity_polygon)
from kinelab.kinematics._solution import AccelerationComponents, GuidePoint, KinematicSolution
from kinelab.kinematics._tracker import Tracker
from kinelab.solvers import Derivatives, differentiate

__all__ = ["analyze", "plan", "reachable_ranges", "turns_fully", "KinematicSolution", "AccelerationComponents",
           "GuidePoint",
           "Plan", "Step", "SINGULAR_TOL", "transmission_angle", "time_ratio", "TimeRatio",
           "instant_center", "instant_centers", "InstantCenter", "InstantCenters", "change_points",
           "ChangePoint", "assemble", "reassemble", "Assembly", "SketchNotAssembled", "pose", "assembly_status",
           "AssemblyStatus", "UnreachableInput", "SingularInput",
           "Tracker", "acceleration_difference", "AccelerationDifference", "relative_acceleration",
           "RelativeAcceleration", "velocity_polygon", "VelocityPolygon", "acceleration_polygon",
           "AccelerationPolygon", "Side", "LinkImage", "kennedy_construction",
           "KennedyConstruction", "KennedyStep", "centrodes", "Centrodes", "velocity_ratio",
           "differentiate", "Derivatives"]
