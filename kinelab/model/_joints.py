"""The kinematic pairs kinelab knows, with the freedoms each allows.

A pair that allows ``j`` relative freedoms is of class ``P{j}`` in the notes (*Mecanismos*,
§1): the revolute pair is P1, the cylindrical pair P2, the spherical pair P3.  In the
plane (lambda = 3) a pair removes ``3 - j`` freedoms; in space (lambda = 6) ``6 - j``.
"""
from __future__ import annotations

from dataclasses import dataclass

__all__ = ["JointType", "JOINT_TYPES"]


@dataclass(frozen=True)
class JointType:
    """One kind of kinematic pair.

    Attributes
    ----------
    symbol : str
        The name used in models and files (``"R"``, ``"P"``, ``"cam"`` ...).
    freedoms : int
        Relative freedoms the pair allows (its class ``P_j``), counted in the space the
        pair is meant for: in the plane for the planar higher pairs, in space otherwise.
    planar : bool
        Whether the pair can join two links of a planar mechanism.
    higher : bool
        A higher pair (point or line contact) rather than a lower pair (surface contact).
    needs_point : bool
        Whether the joint must name the point where it acts.
    needs_axis : bool
        Whether the joint must give an axis (slide direction, rotation axis).
    description : str
        A short description for people.
    spatial_freedoms : int, optional
        Freedoms the pair allows when it joins two links of a spatial mechanism, where
        they differ from ``freedoms`` (the planar higher pairs); ``None`` means the same.
    """

    symbol: str
    freedoms: int
    planar: bool
    higher: bool
    needs_point: bool
    needs_axis: bool
    description: str
    spatial_freedoms: int | None = None


JOINT_TYPES: dict[str, JointType] = {t.symbol: t for t in (
    JointType("R", 1, True, False, True, False, "revolute (pin, hinge)"),
    JointType("P", 1, True, False, True, True, "prismatic (slider)"),
    JointType("H", 1, False, False, True, True, "helical (screw)"),
    # C: a cylindrical pair in space; in a planar mechanism, a cam and its follower, which
    # the planar engine solves (kinelab.model._cams): two freedoms in both.
    JointType("C", 2, True, False, True, True, "cylindrical; in the plane, cam and follower"),
    JointType("U", 2, False, False, True, True, "universal (Hooke, Cardan)"),
    JointType("S", 3, False, False, True, False, "spherical (ball)"),
    JointType("E", 3, False, False, False, True, "planar pair (flat contact)"),
    # In space: cam and gear teeth touch at a point (P5), a rolling contact without slip
    # leaves the three rotations about the contact point (P3), and a pin in a slot is a
    # ball whose centre stays on the slot's line (P4).
    JointType("cam", 2, True, True, False, False, "cam and follower (rolling and sliding contact)", 5),
    JointType("gear", 2, True, True, False, False, "gear mesh", 5),
    # A gear pair of fixed ratio (spur, internal, rack and pinion) that the planar engine
    # solves: its pitch circles roll without slip (kinelab.model._gears).
    JointType("G", 2, True, True, False, False, "gear pair (spur, internal, rack and pinion)", 5),
    JointType("rolling", 1, True, True, False, False, "rolling contact without slip", 3),
    JointType("pin_in_slot", 2, True, True, True, True, "pin in slot", 4),
)}
