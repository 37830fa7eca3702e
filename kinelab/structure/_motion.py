"""Moving a mechanism a little along its motion, to look past a singular sketch.

At a singular configuration (a slider-crank at a dead centre, a four-bar folded flat)
the constraint Jacobian loses rank, and the motions it allows *at that instant* are more
than the mechanism has.  To tell the two apart the mechanism is moved: a small step along
one of the instantaneous motions, then Gauss-Newton back onto the constraints, which are
written for finite displacements.  Each link's displacement from its sketch pose is a
rigid motion ``g = (Rot, t)``; a pair whose allowed relative displacements form a group
(R, P, H, C, S, E) requires ``log(g_a^-1 g_b)`` to lie in the span of its freedom screws;
a U joint is a spherical joint that also keeps the angle between its two axes; a pin in
a slot keeps the pin on the slot's line.  Cam, gear and rolling contacts depend on
profiles the model does not describe, so mechanisms with them are not moved.
"""
from __future__ import annotations

import numpy as np

from kinelab.model import Joint, Mechanism, Point
from kinelab.structure._screws import _perpendicular, annihilator, null_basis, pair_screws
from kinelab.structure._system import ConstraintSystem

__all__ = ["moved"]

_GROUP_PAIRS = ("R", "P", "H", "C", "S", "E")
_PLANAR = [2, 3, 4]  # (wz, vx, vy) among the spatial twist's components
_CONVERGED = 1e-12   # residual in sketch sizes: rounding of a closed loop


def _hat(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _v_matrix(w: np.ndarray) -> np.ndarray:
    th = np.linalg.norm(w)
    k = _hat(w)
    if th < 1e-8:
        return np.eye(3) + 0.5 * k + k @ k / 6.0
    return (np.eye(3) + (1 - np.cos(th)) / th**2 * k + (th - np.sin(th)) / th**3 * k @ k)


def _exp(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    w = xi[:3]
    th, k = np.linalg.norm(w), _hat(w)
    if th < 1e-8:
        rot = np.eye(3) + k + 0.5 * k @ k
    else:  # Rodrigues
        rot = np.eye(3) + np.sin(th) / th * k + (1 - np.cos(th)) / th**2 * k @ k
    return rot, _v_matrix(w) @ xi[3:]


def _log(rot: np.ndarray, t: np.ndarray) -> np.ndarray:
    # the displacements met here turn by far less than pi, where this is well conditioned
    axis = 0.5 * np.array([rot[2, 1] - rot[1, 2], rot[0, 2] - rot[2, 0], rot[1, 0] - rot[0, 1]])
    th = np.arctan2(np.linalg.norm(axis), 0.5 * (np.trace(rot) - 1.0))
    w = axis * (1.0 + th**2 / 6.0 if th < 1e-6 else th / np.sin(th))
    return np.concatenate([w, np.linalg.solve(_v_matrix(w), t)])


def _jl_inverse(xi: np.ndarray) -> np.ndarray:
    """Inverse left Jacobian of SE(3): log(exp(eta) exp(xi)) = xi + J^-1 eta + O(eta^2).

    Its Bernoulli series, to the fourth power of ``ad(xi)``; the steps taken here keep
    ``|xi|`` below 0.2, where the next term is below 1e-9."""
    a = np.zeros((6, 6))
    a[:3, :3] = a[3:, 3:] = _hat(xi[:3])
    a[3:, :3] = _hat(xi[3:])
    a2 = a @ a
    return np.eye(6) - a / 2 + a2 / 12 - a2 @ a2 / 720


def _adjoint(rot: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.zeros((6, 6))
    out[:3, :3] = out[3:, 3:] = rot
    out[3:, :3] = _hat(t) @ rot
    return out


class _Loop:
    """Finite-displacement constraints of a model, on the links' rigid motions."""

    def __init__(self, system: ConstraintSystem):
        self.system = system
        # spatial twist of each unknown block (the plane embeds in space)
        self.embed = np.eye(6)[:, _PLANAR] if system.planar else np.eye(6)

    def pose(self, poses, link):
        return poses.get(link, (np.eye(3), np.zeros(3)))

    def cols(self, link, rows: np.ndarray) -> np.ndarray:
        """``rows`` acting on a link's spatial twist, as rows on all the unknowns."""
        out = np.zeros((len(rows), self.system.unknowns))
        block = self.system.block(link)
        if block is not None:
            out[:, block] = rows @ self.embed
        return out

    def equations(self, poses) -> tuple[np.ndarray, np.ndarray]:
        """Residuals and their Jacobian on the twist increments of the moving links."""
        res, jac = [], []
        model, frame = self.system.model, self.system.frame
        for j in model.joints:
            a, b = j.links
            (ra, ta), (rb, tb) = self.pose(poses, a), self.pose(poses, b)
            if j.type in _GROUP_PAIRS or j.type == "U":
                if j.type == "U":  # a spherical joint about its point ...
                    p = frame.point(model, j.point)
                    w = annihilator(np.array(pair_screws("S", p, None)))
                else:
                    w = self.system.constraints[j.name] @ self.embed.T
                xi = _log(ra.T @ rb, ra.T @ (tb - ta))
                res.append(w @ xi)
                ad = w @ _jl_inverse(xi) @ _adjoint(ra.T, -ra.T @ ta)
                jac.append(self.cols(b, ad) - self.cols(a, ad))
                if j.type == "U":  # ... that keeps the angle between its axes
                    u1, u2 = ra @ np.asarray(j.axis, float), rb @ np.asarray(j.axis2, float)
                    res.append(np.array([u1 @ u2 - np.dot(j.axis, j.axis2)]))
                    c = np.concatenate([np.cross(u1, u2), np.zeros(3)])[None]
                    jac.append(self.cols(a, c) - self.cols(b, c))
            else:  # pin in slot: the pin's centre stays on the slot's line
                p = frame.point(model, j.point)
                u = np.asarray(j.axis, float)
                u = np.append(u, 0.0) if self.system.planar else u
                normals = ([np.array([-u[1], u[0], 0.0])] if self.system.planar
                           else list(_perpendicular(u)))
                xa, xb = ra @ p + ta, rb @ p + tb
                for n0 in normals:
                    n = ra @ n0
                    res.append(np.array([n @ (xb - xa)]))
                    # d(n.(xb - xa)) = n.(vb + wb x xb) - n.(va + wa x xa) + (wa x n).(xb - xa)
                    row_b = np.concatenate([np.cross(xb, n), n])[None]
                    row_a = np.concatenate([np.cross(xa, n) - np.cross(n, xb - xa), n])[None]
                    jac.append(self.cols(b, row_b) - self.cols(a, row_a))
        if not res:
            return np.zeros(0), np.zeros((0, self.system.unknowns))
        return np.concatenate(res), np.vstack(jac)

    def step(self, poses, delta: np.ndarray):
        out = dict(poses)
        for link in self.system.moving:
            d = self.embed @ delta[self.system.block(link)]
            rot, t = self.pose(poses, link)
            er, et = _exp(d)
            out[link] = (er @ rot, er @ t + et)
        return out


def _moved_model(system: ConstraintSystem, poses) -> Mechanism:
    model, frame = system.model, system.frame
    where = {}
    for link in model.links:
        rot, t = poses.get(link.name, (np.eye(3), np.zeros(3)))
        for p in link.points:
            where.setdefault(p, frame.center + frame.scale * (rot @ frame.point(model, p) + t))
    points = tuple(Point(p.name, *((where[p.name][:2] if model.space == "planar"
                                    else where[p.name]) if p.name in where else (p.x, p.y, p.z)))
                   for p in model.points)

    def turned(vec, link):
        if vec is None:
            return None
        v = np.asarray(vec, float)
        rot = poses.get(link, (np.eye(3), None))[0]
        return tuple(rot[:2, :2] @ v) if len(v) == 2 else tuple(rot @ v)
    joints = tuple(Joint(j.name, j.type, j.links, point=j.point,
                         axis=turned(j.axis, j.links[0]), origin=j.origin,
                         axis2=turned(j.axis2, j.links[1]), pitch=j.pitch) for j in model.joints)
    return Mechanism(model.name, points, model.links, joints, model.inputs, model.space,
                     model.parameters)


def moved(system: ConstraintSystem, *, step: float = 0.05, trials: int = 3,
          seed: int = 0) -> list[Mechanism] | None:
    """The model moved by about ``step`` sketch sizes along random instantaneous motions.

    Returns one model per trial that reached a configuration ``step / 4`` or more away
    (a motion that cannot go that far is only infinitesimal); ``None`` when the model
    has pairs that cannot be moved without their profiles, or geometry it does not give.
    """
    model = system.model
    usable = all(j.type in _GROUP_PAIRS or (j.type == "U" and j.axis and j.axis2)
                 or (j.type == "pin_in_slot" and j.point and j.axis) for j in model.joints)
    if not usable or system.notes:
        return None
    loop = _Loop(system)
    r0, jac0 = loop.equations({})
    motions = null_basis(jac0)
    if motions.shape[1] == 0:
        return []
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(trials):
        d = motions @ rng.standard_normal(motions.shape[1])
        poses = loop.step({}, step * d / np.linalg.norm(d))
        for _ in range(30):
            r, jac = loop.equations(poses)
            if np.max(np.abs(r)) < _CONVERGED:
                break
            # constraints that repeat others (special geometry) leave tiny singular
            # values; dropping them keeps the step from blowing up along them
            poses = loop.step(poses, -np.linalg.lstsq(jac, r, rcond=1e-8)[0])
        else:
            continue
        far = max(np.linalg.norm(_log(*poses[k])) for k in system.moving)
        if far >= step / 4:
            out.append(_moved_model(system, poses))
    return out
