"""Planar geometry shared by the plan builder and the results."""
from __future__ import annotations

import math

import numpy as np

from kinelab.model import Mechanism


def sketch_angle(m: Mechanism, link: str) -> float:
    """Angle of a link in the sketch, rad: the direction from its first point to its second;
    for a one-point slider, the direction of its first prismatic joint's axis."""
    pts = m.link(link).points
    if len(pts) >= 2:
        a, b = m.point(pts[0]), m.point(pts[1])
        return math.atan2(b.y - a.y, b.x - a.x)
    for j in m.joints_of(link):
        if j.type == "P":
            return math.atan2(j.axis[1], j.axis[0])
    return 0.0



def k_cross(v: np.ndarray) -> np.ndarray:
    """``k x v`` for planar vectors along the last axis: v turned by +90 degrees."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)
