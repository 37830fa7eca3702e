"""The twists each pair allows at the sketch, and numerical rank with its tolerance.

A twist is the velocity field of a rigid body, written as the angular velocity and the
velocity of the body point that passes through the origin: ``(wx, wy, wz, vx, vy, vz)``
in space, ``(w, vx, vy)`` in the plane.  A pair allows a subspace of relative twists
(spanned by its *freedom screws*): a rotation about ``u`` through ``p`` is ``(u, p x u)``,
a translation along ``u`` is ``(0, u)``, a screw motion of pitch ``h`` is
``(u, p x u + h u)``.

Lengths are first made dimensionless: the origin moves to the centroid of the sketch and
lengths are divided by the sketch's size, so that angular and linear parts of a twist
are numbers of the same order and one relative rank tolerance serves every model.
"""
from __future__ import annotations

import zlib
from dataclasses import dataclass

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.model import Joint, Mechanism, cam_pair, cam_values, gear_mesh, real

__all__ = ["RTOL", "MIN_RTOL", "MAX_RTOL", "Frame", "annihilator", "checked_rtol",
           "joint_screws", "null_basis", "rank", "row_basis"]

RTOL = 1e-9
"""Relative tolerance on singular values.  A sketch typed or computed in double precision
satisfies a special geometry (parallel axes, Bennett's conditions) to about 1e-15 of its
size, and the constraint matrices are built from it with a few more roundings, so a
dependent row leaves a singular value of about 1e-14 of the largest.  A geometry that is
*not* special but close to it (an axis 1e-6 rad off parallel) leaves one of about its
distance from the special case.  1e-9 sits between the two with five orders of margin
each side."""
MIN_RTOL = 1e-13
"""The smallest ``rtol`` a caller may choose: below it the roundings of the sketch (about
1e-14 of the largest singular value) count as independent constraints, and special geometry
goes unseen."""
MAX_RTOL = 1e-3
"""The largest: beyond it a geometry a thousandth away from special is taken as special,
and the rank loses constraints that are there (a cam contact at 0.1; every one at 1)."""


def checked_rtol(value, name: str = "rtol") -> float:
    """``value`` as a float, or a :class:`ModelError` unless it is a real number from
    :data:`MIN_RTOL` to :data:`MAX_RTOL` (the default :data:`RTOL` sits in between)."""
    v = real(value)
    if v is None or not MIN_RTOL <= v <= MAX_RTOL:
        raise ModelError(f"{name}: expected a relative tolerance from {MIN_RTOL:g} to {MAX_RTOL:g} "
                         f"(default {RTOL:g}), got {describe(value)}; leave it out for the default")
    return v


def _threshold(s: np.ndarray, rtol: float, scale: float | None) -> float:
    # Relative to the largest singular value, or to a given scale when the matrix may be
    # all (numerically) zero, as the velocities of points that do not move.
    ref = s[0] if s.size else 0.0
    return rtol * max(ref, scale or 0.0)


def rank(a: np.ndarray, rtol: float = RTOL, *, scale: float | None = None) -> int:
    """Numerical rank: singular values above ``rtol`` times the largest (or ``scale``)."""
    a = np.atleast_2d(a)
    if a.size == 0:
        return 0
    s = np.linalg.svd(a, compute_uv=False)
    return int(np.sum(s > _threshold(s, rtol, scale)))


def row_basis(a: np.ndarray, rtol: float = RTOL, *, scale: float | None = None) -> np.ndarray:
    """Orthonormal rows spanning the row space of ``a``."""
    a = np.atleast_2d(a)
    if a.size == 0:
        return np.zeros((0, a.shape[1]))
    _, s, vt = np.linalg.svd(a)
    return vt[:int(np.sum(s > _threshold(s, rtol, scale)))]


def null_basis(a: np.ndarray, rtol: float = RTOL, *, scale: float | None = None) -> np.ndarray:
    """Orthonormal columns spanning the null space of ``a`` (all of R^n when ``a`` has no row)."""
    a = np.atleast_2d(a)
    n = a.shape[1]
    if a.shape[0] == 0:
        return np.eye(n)
    _, s, vt = np.linalg.svd(a)
    return vt[int(np.sum(s > _threshold(s, rtol, scale))):].T


def annihilator(screws: np.ndarray, rtol: float = RTOL) -> np.ndarray:
    """Rows ``W`` with ``W @ s = 0`` for every row ``s`` of ``screws``: the constraints."""
    return null_basis(screws, rtol).T


@dataclass(frozen=True)
class Frame:
    """Where the dimensionless frame of a model sits: origin and unit of length (m)."""

    center: np.ndarray
    scale: float

    @classmethod
    def of(cls, model: Mechanism) -> Frame:
        xyz = np.array([(p.x, p.y, p.z) for p in model.points], dtype=float)
        center = xyz.mean(axis=0)
        size = float(np.max(np.linalg.norm(xyz - center, axis=1))) if len(xyz) else 0.0
        return cls(center, size if size > 0.0 else 1.0)

    def point(self, model: Mechanism, name: str) -> np.ndarray:
        p = model.point(name)
        return (np.array([p.x, p.y, p.z]) - self.center) / self.scale


def _rng(joint: Joint) -> np.random.Generator:
    # Reproducible "generic" geometry: the same joint name always draws the same numbers.
    return np.random.default_rng(zlib.crc32(joint.name.encode()))


def _unit(v, where: str, dim: int) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    if v.shape != (dim,) or not np.all(np.isfinite(v)) or np.linalg.norm(v) == 0.0:
        raise ModelError(f"{where}: expected {dim} finite numbers, not all zero, got {list(v)}")
    return v / np.linalg.norm(v)


def _rot(u: np.ndarray, p: np.ndarray) -> np.ndarray:
    return np.concatenate([u, np.cross(p, u)])


def _trans(u: np.ndarray) -> np.ndarray:
    return np.concatenate([np.zeros(3), u])


def _perpendicular(n: np.ndarray) -> np.ndarray:
    """Two unit vectors completing ``n`` to an orthonormal basis."""
    return np.linalg.svd(n[None, :])[2][1:]


def pair_screws(kind: str, p: np.ndarray | None, u: np.ndarray | None,
                u2: np.ndarray | None = None, pitch: float = 0.0) -> list[np.ndarray]:
    """Freedom screws (spatial twists, one per freedom) of a lower pair: at point ``p``,
    with axis (or, for E, plane normal) ``u``; ``u2`` the second axis of a U, ``pitch``
    (per rad, in the frame's length unit) that of an H."""
    if kind == "R":
        return [_rot(u, p)]
    if kind == "P":
        return [_trans(u)]
    if kind == "H":
        return [_rot(u, p) + _trans(pitch * u)]
    if kind == "C":
        return [_rot(u, p), _trans(u)]
    if kind == "U":
        return [_rot(u, p), _rot(u2, p)]
    if kind == "S":
        return [_rot(e, p) for e in np.eye(3)]
    if kind == "E":
        return [_rot(u, p)] + [_trans(e) for e in _perpendicular(u)]
    raise ValueError(f"pair_screws: no lower pair {kind!r}")


def _gear_screws(model: Mechanism, joint: Joint, frame: Frame) -> list[np.ndarray]:
    """Freedom screws of a gear joint ``G`` at the sketch: a rotation about the pitch point
    (the instant centre of the two gears' relative motion) and a translation across the
    pitch line (the mesh holds no distance; the carrier's joints do).  The pitch point divides
    the line of centres in the ratio of the radii: ``(r_b O_a + r_a O_b) / (r_a + r_b)``
    outside it for an external pair, ``(r_b O_a - r_a O_b) / (r_b - r_a)`` for an internal
    one; a rack's lies ``r`` from the pinion's centre, to the right of the rack's axis."""
    g = gear_mesh(model, joint)
    z = np.array([0.0, 0.0, 1.0])
    oa = frame.point(model, g.centre_a)
    if g.mesh == "rack":
        u = _unit(model.joint(g.slide).axis, f"joint '{g.slide}': axis", 2)
        right = np.array([u[1], -u[0], 0.0])
        p = oa + g.k / frame.scale * right
        return [_rot(z, p), _trans(right)]
    ob = frame.point(model, g.centre_b)
    k = g.k                 # theta_b' = k theta_a': the pitch point moves with neither
    p = (oa - k * ob) / (1.0 - k)
    across = (ob - oa) / np.linalg.norm(ob - oa)
    return [_rot(z, p), _trans(across)]


def _cam_screws(model: Mechanism, joint: Joint, frame: Frame) -> list[np.ndarray]:
    """Freedom screws of a cam joint ``C`` at the sketch: a rotation about the instant centre
    of the cam's and the follower's relative motion and a translation along their line of
    centres, as a gear pair's, with the program's ``k = S'(theta)`` at the sketch for the
    ratio.  A translating follower's centre is at infinity across its slide: the instant
    centre lies ``S'`` from the cam's centre along ``-(k x u)``."""
    c = cam_pair(model, joint)
    z = np.array([0.0, 0.0, 1.0])
    theta = _sketch_theta(model, c)
    k = float(cam_values(c.table, theta)[1])
    o = frame.point(model, model.joint(c.pivot).point)
    f = model.joint(c.follower_joint)
    if c.motion == "translating":
        u = _unit(f.axis, f"joint '{f.name}': axis", 2)
        n = np.array([-u[1], u[0], 0.0])
        return [_rot(z, o - k / frame.scale * n), _trans(n)]
    a = frame.point(model, f.point)
    across = (a - o) / np.linalg.norm(a - o)
    if abs(1.0 - k) <= 1e-12:       # the follower turns with the cam: no centre in reach
        return [_trans(np.cross(z, across)), _trans(across)]
    return [_rot(z, (o - k * a) / (1.0 - k)), _trans(across)]


def _sketch_theta(model: Mechanism, c) -> float:
    """The cam's angle relative to its guide in the sketch (from each link's first point to
    its second; the frame's is 0)."""
    def angle(link: str) -> float:
        pts = model.link(link).points
        if link == model.ground.name or len(pts) < 2:
            return 0.0
        a, b = model.point(pts[0]), model.point(pts[1])
        return float(np.arctan2(b.y - a.y, b.x - a.x))
    return angle(c.cam) - angle(c.guide)


def joint_screws(model: Mechanism, joint: Joint, frame: Frame,
                 planar: bool) -> tuple[np.ndarray, list[str]]:
    """Freedom screws of a joint at the sketch, one per row, in the frame's units.

    Returns the screws, shape ``(f, 3)`` in the plane or ``(f, 6)`` in space, and notes
    on geometry that had to be assumed (a missing axis or contact point is taken in
    general position, drawn reproducibly from the joint's name).
    """
    notes: list[str] = []
    where = f"joint '{joint.name}'"

    def point() -> np.ndarray:
        if joint.point is not None:
            return frame.point(model, joint.point)
        pts = [frame.point(model, q) for link in joint.links for q in model.link(link).points]
        notes.append(f"{where} names no contact point; one in general position near its "
                     "links was assumed")
        p = np.mean(pts, axis=0) + 0.3 * _rng(joint).standard_normal(3)
        if planar:
            p[2] = 0.0
        return p

    def axis(attr: str = "axis") -> np.ndarray:
        given = getattr(joint, attr)
        if given is not None:
            u = _unit(given, f"{where}: {attr}", 2 if planar else 3)
            return np.append(u, 0.0) if planar else u
        if model.space == "spherical" and attr == "axis" and joint.point is not None:
            p = model.point(joint.point)
            radial = np.array([p.x, p.y, p.z])
            if np.linalg.norm(radial) > 0.0:
                notes.append(f"{where} gives no axis; it was taken through the origin, the "
                             "centre of the spherical mechanism")
                return radial / np.linalg.norm(radial)
        notes.append(f"{where} gives no {attr}; one in general position was assumed")
        u = _rng(joint).standard_normal((2, 3))[0 if attr == "axis" else 1]
        if planar:
            u[2] = 0.0
        return u / np.linalg.norm(u)

    t = joint.type
    if planar:
        if t in ("R", "rolling"):
            rows = [_rot(np.array([0, 0, 1.0]), point())]
        elif t == "P":
            rows = [_trans(axis())]
        elif t in ("cam", "gear"):
            p, n = point(), axis()
            rows = [_rot(np.array([0, 0, 1.0]), p), _trans(np.array([-n[1], n[0], 0.0]))]
        elif t == "pin_in_slot":
            rows = [_rot(np.array([0, 0, 1.0]), point()), _trans(axis())]
        elif t == "G":
            rows = _gear_screws(model, joint, frame)
        elif t == "C":
            rows = _cam_screws(model, joint, frame)
        else:  # pragma: no cover - the model rejects non-planar pairs in planar models
            raise ModelError(f"{where}: a {t} joint cannot join links of a planar mechanism")
        # planar twist (w, vx, vy): the z rotation and the x, y velocity of the origin point
        return np.array(rows)[:, [2, 3, 4]], notes
    if t in ("R", "H", "C"):
        u, p = axis(), point()
        rows = pair_screws(t, p, u, pitch=(joint.pitch or 0.0) / frame.scale)
        if t == "H" and joint.pitch is None:
            notes.append(f"{where} gives no pitch; a pitch of zero (a revolute) was assumed")
    elif t == "P":
        rows = pair_screws(t, None, axis())
    elif t == "U":
        p, u1, u2 = point(), axis(), axis("axis2")
        rows = pair_screws(t, p, u1, u2)
    elif t in ("S", "rolling"):
        rows = pair_screws("S", point(), None)
    elif t == "E":      # any point of the plane: the two in-plane translations span the rest
        rows = pair_screws(t, np.zeros(3), axis())
    elif t in ("cam", "gear"):
        p, n = point(), axis()
        rows = [_rot(e, p) for e in np.eye(3)] + [_trans(e) for e in _perpendicular(n)]
    elif t == "pin_in_slot":
        p, u = point(), axis()
        rows = [_rot(e, p) for e in np.eye(3)] + [_trans(u)]
    else:  # pragma: no cover - every type of JOINT_TYPES is handled above
        raise ModelError(f"{where}: unknown joint type '{t}'")
    return np.array(rows), notes
