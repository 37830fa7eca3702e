"""What a mechanism is: points, links, joints and inputs (plain, validated data), and the
units of lengths and angles it may be written in (:class:`Units`)."""
from kinelab.model._cams import CamPair, cam_pair, cam_values
from kinelab.model._gears import GEAR_MESHES, GearMesh, gear_mesh
from kinelab.model._joints import JOINT_TYPES, JointType
from kinelab.model._mechanism import SPACES, Input, Joint, Link, Mechanism, Point
from kinelab.model._places import SIDE_WORDS, exact_places, place_problems
from kinelab.model._units import ANGLE_UNITS, LENGTH_UNITS, Units
from kinelab.model._values import (MAX_INERTIA, MAX_JOINTS, MAX_LENGTH, MAX_LINKS, MAX_MASS,
                                   MAX_NAME, MAX_POINTS, MAX_RATE, MAX_TURNS, MIN_LENGTH, angle_problem,
                                   coordinate_problem, is_real, length_problem, name_problem,
                                   range_problem, rate_problem, real, real_array,
                                   size_problems)

__all__ = ["CamPair", "cam_pair", "cam_values", "GEAR_MESHES", "GearMesh", "gear_mesh", "Mechanism", "Point", "Link", "Joint", "Input", "JointType", "JOINT_TYPES", "SPACES",
           "Units", "LENGTH_UNITS", "ANGLE_UNITS", "MIN_LENGTH", "MAX_LENGTH", "MAX_RATE",
           "MAX_TURNS", "MAX_MASS", "MAX_INERTIA", "MAX_LINKS", "MAX_JOINTS", "MAX_POINTS", "MAX_NAME",
           "is_real", "real", "real_array", "length_problem", "coordinate_problem",
           "angle_problem", "rate_problem", "range_problem", "name_problem", "size_problems",
           "SIDE_WORDS", "exact_places", "place_problems"]
