"""Cam pairs as joints of a planar model: what a ``C`` joint says and what it must satisfy.

A cam joint ``C`` joins a *cam* ``a`` and a *follower* ``b``, both jointed to a third link,
the *guide* ``g`` (the frame, or a carrier that moves): the cam turns on the guide in an R
joint, and the follower either slides on it in a P joint (a translating follower) or turns
on it in an R joint (an oscillating follower).  The follower's displacement relative to the
guide, its slide ``s_f`` (m) or its angle ``phi_f = theta_b - theta_g`` (rad), is the cam's
motion program at the cam's angle relative to the guide:

    s_f = s_f0 + S(theta),    theta = theta_a - theta_g

``theta_a`` the cam's angle (from its first point to its second; CCW from +x when the guide
is the frame) and ``S`` the program's displacement (:class:`kinelab.cams.MotionProgram`,
whose ``V`` and ``A`` are derivatives with respect to the cam angle).  ``s_f0``, the
follower's place where ``S = 0``, comes from the sketch: the sketch draws the follower at
``S(theta)`` of the cam's angle there.

The program is evaluated from a table of *pieces* (``program.pieces()``), each
``f(x) = sum(c_i (x - x0)**i) + B sin(k x + phase)`` on a part of a segment, which the
compiled kernel and its numpy form evaluate alike (:func:`cam_values`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kinelab.errors import describe, shown

__all__ = ["CAM_FIELDS", "PIECE_WIDTH", "CamPair", "cam_pair", "cam_problems", "cam_values"]

CAM_FIELDS = ("program",)
"""The fields of a joint that only a cam joint ``C`` has (with ``carrier``, the guide)."""

# one row of a program's table of pieces: where the piece starts (rad), the segment's start
# and width (rad), the piece's x0, the segment's level and height (S = level + h f(x)), the
# sine term's B, k, phase, then the polynomial's coefficients c_0 .. c_14
PIECE_WIDTH = 24
PIECE_HEAD = 9
MAX_DEGREE = PIECE_WIDTH - PIECE_HEAD - 1
TURN = 2.0 * math.pi


@dataclass(frozen=True)
class CamPair:
    """A cam joint resolved against its model.

    Attributes
    ----------
    joint : str
    cam, follower, guide : str
        The links: the cam, its follower, and the link both are jointed to.
    motion : {'translating', 'oscillating'}
    pivot : str
        The cam's R joint on the guide.
    follower_joint : str
        The follower's P joint (translating) or R joint (oscillating) on the guide.
    table : np.ndarray, shape (pieces, PIECE_WIDTH)
        The program's pieces (see the module docstring).
    """

    joint: str
    cam: str
    follower: str
    guide: str
    motion: str
    pivot: str
    follower_joint: str
    table: np.ndarray


def cam_values(table: np.ndarray, theta) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``S, dS/dtheta, d2S/dtheta2`` of a program's table of pieces at cam angles ``theta``
    (rad, any shape; taken modulo a turn).  An angle where two pieces meet takes the values
    of the one that starts there, as :meth:`kinelab.cams.MotionProgram.svaj` does."""
    theta = np.asarray(theta, float)
    t = np.mod(theta, TURN)
    idx = np.clip(np.searchsorted(table[:, 0], t, side="right") - 1, 0, len(table) - 1)
    row = table[idx]
    start, beta, x0, level, h, B, kk, ph = (row[..., c] for c in range(1, PIECE_HEAD))
    x = (t - start) / beta
    u = x - x0
    c = row[..., PIECE_HEAD:]
    f = np.zeros_like(u)
    f1 = np.zeros_like(u)
    f2 = np.zeros_like(u)
    for i in range(c.shape[-1] - 1, -1, -1):     # Horner, with the first two derivatives
        f2 = f2 * u + 2.0 * f1
        f1 = f1 * u + f
        f = f * u + c[..., i]
    arg = kk * x + ph
    sa, ca = np.sin(arg), np.cos(arg)
    f = f + B * sa
    f1 = f1 + B * kk * ca
    f2 = f2 - B * kk * kk * sa
    return level + h * f, h * f1 / beta, h * f2 / (beta * beta)


def _joint_to(m, link: str, guide: str, kinds=("R", "P")):
    """The R or P joint joining ``link`` and ``guide`` (a P joint's guide first), or None."""
    for j in m.joints:
        if j.type not in kinds or not isinstance(j.links, (tuple, list)):
            continue
        if set(j.links) == {link, guide} and (j.type == "R" or tuple(j.links) == (guide, link)):
            return j
    return None


def cam_problems(m, j, links) -> list[str]:
    """Every problem of cam joint ``j`` of mechanism ``m`` (its links already checked to be
    two different declared links), each a one-line message naming the field."""
    out: list[str] = []
    where = f"joint {shown(j.name)}"
    cam, follower = j.links
    p = j.program
    if p is None:
        out.append(f"{where}: program: a cam joint needs its motion program: give [[joints."
                   "segments]] (kind, law, from, to, lift) in a model file, or program = "
                   "kinelab.cams.MotionProgram(...)")
    elif not (hasattr(p, "pieces") and hasattr(p, "discontinuities")):
        out.append(f"{where}: program: expected a kinelab.cams.MotionProgram, got {describe(p)}")
    else:
        jumps = [d for d in p.discontinuities if d.error]
        for d in jumps:
            out.append(f"{where}: program: {d}; a follower cannot jump: make the program close "
                       "over the turn (its rises equal to its returns) with S and V continuous")
        if not jumps:
            try:
                p.pieces()
            except Exception as exc:         # a polynomial of too high a degree
                out.append(f"{where}: program: {exc}")
    guide = j.carrier if j.carrier is not None else m.ground.name
    if not isinstance(guide, str) or guide not in links:
        out.append(f"{where}: carrier: expected a declared link (the guide both cam and follower "
                   f"are jointed to; the ground by default), got {describe(j.carrier)}")
        return out
    if guide in (cam, follower):
        out.append(f"{where}: carrier: the guide {shown(guide)} cannot be the cam or the "
                   "follower; name the link both turn or slide on (the ground, or a carrier)")
        return out
    if _joint_to(m, cam, guide, ("R",)) is None:
        out.append(f"{where}: links: the cam {shown(cam)} (the first link) must turn on the guide "
                   f"{shown(guide)}; add an R joint between {shown(cam)} and {shown(guide)} at "
                   "the cam's centre")
    if _joint_to(m, follower, guide) is None:
        out.append(f"{where}: links: the follower {shown(follower)} (the second link) must slide "
                   f"on the guide {shown(guide)} (a P joint with links = [{shown(guide)}, "
                   f"{shown(follower)}]) or turn on it (an R joint at its pivot); add one")
    return out


def cam_pair(m, j) -> CamPair:
    """The cam joint ``j`` of a checked mechanism ``m``, resolved."""
    cam, follower = j.links
    guide = j.carrier if j.carrier is not None else m.ground.name
    fj = _joint_to(m, follower, guide)
    return CamPair(j.name, cam, follower, guide,
                   "translating" if fj.type == "P" else "oscillating",
                   _joint_to(m, cam, guide, ("R",)).name, fj.name,
                   np.asarray(j.program.pieces(), float))
