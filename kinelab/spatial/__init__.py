"""Spatial kinematics: 3-D transforms, spatial mechanisms and serial/parallel robots."""
