"""What a mechanism is: points, links, joints and inputs (plain, validated data), and the
units of lengths and angles it may be written in (:class:`Units`)."""
from kinelab.model._joints import JOINT_TYPES, JointType
from kinelab.model._mechanism import SPACES, Input, Joint, Link, Mechanism, Point
from kinelab.model._units import ANGLE_UNITS, LENGTH_UNITS, Units

__all__ = ["Mechanism", "Point", "Link", "Joint", "Input", "JointType", "JOINT_TYPES", "SPACES",
           "Units", "LENGTH_UNITS", "ANGLE_UNITS"]
