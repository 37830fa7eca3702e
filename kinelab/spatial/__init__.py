"""Spatial kinematics: 3-D transforms, spatial mechanisms (Cardan joints, RSSR, Bennett's and
Sarrus's linkages) and serial/parallel robots.

*Mecanismos*, §4.2, §4.8 and §7.  Everything takes one configuration or a batch of N along
axis 0, in SI units and radians.
"""
from kinelab.spatial._transforms import (
    AngularMotion, AxisAngle, PointMotion, TransformRates, axis_angle, compose,
    euler_angles, euler_parameters, euler_rates, euler_rotation, homogeneous, invert,
    planar_transform, point_motion, rotation, rotation_from_euler_parameters, skew,
    transform_points, transform_rates, translation,
)
from kinelab.spatial._robots import (
    JointRates, RobotJoint, SerialRobot, ToolMotion, pr, prr, rp, rr, rrr,
)
from kinelab.spatial._cardan import (
    CardanMotion, DoubleCardanMotion, cardan_motion, cardan_output, cardan_velocity_ratio,
    double_cardan,
)
from kinelab.spatial._rssr import RSSR, RSSRPositions, RSSRSolution
from kinelab.spatial._bennett import BennettPositions, bennett
from kinelab.spatial._sarrus import SarrusPositions, sarrus
from kinelab.spatial._stewart import (
    StewartPose, stewart_forward, stewart_inverse_jacobian, stewart_leg_lengths,
)

__all__ = [
    "CardanMotion", "DoubleCardanMotion", "cardan_motion", "cardan_output",
    "cardan_velocity_ratio", "double_cardan",
    "RSSR", "RSSRPositions", "RSSRSolution",
    "BennettPositions", "bennett", "SarrusPositions", "sarrus",
    "StewartPose", "stewart_forward", "stewart_inverse_jacobian", "stewart_leg_lengths",
    "JointRates", "RobotJoint", "SerialRobot", "ToolMotion", "pr", "prr", "rp", "rr", "rrr",
    "AngularMotion", "AxisAngle", "PointMotion", "TransformRates", "axis_angle", "compose",
    "euler_angles", "euler_parameters", "euler_rates", "euler_rotation", "homogeneous",
    "invert", "planar_transform", "point_motion", "rotation",
    "rotation_from_euler_parameters", "skew", "transform_points", "transform_rates",
    "translation",
]
