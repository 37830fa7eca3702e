"""What a mechanism is: points, links, joints and inputs (plain, validated data)."""
from kinelab.model._joints import JOINT_TYPES, JointType
from kinelab.model._mechanism import SPACES, Input, Joint, Link, Mechanism, Point

__all__ = ["Mechanism", "Point", "Link", "Joint", "Input", "JointType", "JOINT_TYPES", "SPACES"]
