"""Planar geometry shared by the plan builder and the results."""
from __future__ import annotations

import math

import numpy as np

from kinelab.model import Mechanism


def sketch_angle(m: Mechanism, link: str) -> float:
    """Angle of a link in the sketch, rad: the direction from its first point to its second.

    A moving link with one point (a slider block) takes the direction of the axis of the
    prismatic joint it slides in (as the joint's second link), else of the one it guides,
    whatever order the joints are listed in; a ground with one point is the frame itself,
    angle 0.
    """
    lk = m.link(link)
    if len(lk.points) >= 2:
        a, b = m.point(lk.points[0]), m.point(lk.points[1])
        return math.atan2(b.y - a.y, b.x - a.x)
    if lk.ground:
        return 0.0
    prismatic = sorted((j for j in m.joints_of(link) if j.type == "P"),
                       key=lambda j: j.links[1] != link)       # the joints it slides in first
    return math.atan2(prismatic[0].axis[1], prismatic[0].axis[0]) if prismatic else 0.0


def k_cross(v: np.ndarray) -> np.ndarray:
    """``k x v`` for planar vectors along the last axis: v turned by +90 degrees."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)
