"""The certificate of velocity and acceleration polygons.

A polygon's vertices are the points' velocities (accelerations) from the analysis, its sides
their differences, each acceleration side split into named parts.  Here every vertex comes
again from the other engine (the Newton engine, or the closed form for a Newton analysis;
the symbolic derivation where both are one engine), every side again from the rigid-body
and sliding formulas with that engine's omega, alpha, positions and slide rates --
``omega k x r`` and ``s' u``; ``-omega^2 r + alpha k x r`` and ``2 omega k x v_rel + s'' u``,
with the relative velocity ``v_rel = v_P - (v_O + omega k x r)`` of the slider's point over
the guide's point under it -- and each polygon must close: every side the difference of its
vertices, every part adding up to its side, the ground's points at the pole.
"""
from __future__ import annotations

import math

import numpy as np

from kinelab import kinematics
from kinelab.errors import ModelError, describe
from kinelab.kinematics import KinematicSolution
from kinelab.verify._certificate import Certificate, Comparison, Quantity
from kinelab.verify._kinematics import AMPLIFIED, BRANCH_GAP, ENGINE_FLOOR, route_name

__all__ = ["certify_polygon"]

CLOSURE = 1e-13
"""Relative to the polygon's largest vector: a side is the difference of two vertices, a
part sum of two or three vectors: rounding."""


def _k_cross(v: np.ndarray) -> np.ndarray:
    return np.array([-v[1], v[0]])


def certify_polygon(polygon, solution: KinematicSolution | None) -> Certificate:
    """The certificate of a :class:`~kinelab.kinematics.VelocityPolygon` or
    :class:`~kinelab.kinematics.AccelerationPolygon` drawn from ``solution``."""
    if not isinstance(solution, KinematicSolution):
        raise ModelError(f"solution: expected the KinematicSolution the polygon was drawn from "
                         f"(certify(polygon, solution=sol)), got {describe(solution)}")
    i = polygon.sample
    if not (0 <= i < solution.N) or not np.array_equal(solution.q[i], polygon.q):
        raise ModelError("solution: the polygon was not drawn from this solution (its sample "
                         f"{i} is at another input); pass the one given to velocity_polygon")
    acceleration = type(polygon).__name__ == "AccelerationPolygon"
    m = solution.mechanism
    newton = solution.plan is kinematics.plan(m, method="newton")
    other = kinematics.analyze(m, *_at(solution, i), at_singular="flag",
                               method="auto" if newton else "newton")
    name = route_name(other.plan)
    notes = []
    gap = max(float(np.linalg.norm(other.position(p) - np.reshape(solution.position(p), (-1, 2))[i]))
              for p in m.point_names)
    if gap > BRANCH_GAP * solution.plan.scale:
        raise ModelError(f"the {name} reaches this input on another assembly mode (from the "
                         "sketch it crossed a limit position), so it cannot check this polygon; "
                         "verify a configuration nearer the sketch")
    second = name != route_name(solution.plan) and not other.singular[0]
    if not second:
        why_not = (f"every group is solved by the {name} either way" if not other.singular[0]
                   else f"the {name} flags this configuration singular (its own measure of "
                        "its groups)")
        notes.append(f"no second engine: {why_not}; the sides and parts are checked by their "
                     "formulas with the analysis' own omega, alpha and slide rates")
        other = kinematics.analyze(m, *_at(solution, i), at_singular="flag",
                                   method="newton" if newton else "auto")
        name = "the analysis"
    s = float(solution.singularity[i])
    bound = max(ENGINE_FLOOR, AMPLIFIED / s ** (3 if acceleration else 2))
    why = (f"the engines' convergence and rounding, amplified near a singular configuration "
           f"(singularity {s:.2g})")

    def pos(p):
        return other.position(p)

    def rate(p):
        return other.acceleration(p) if acceleration else other.velocity(p)

    omega = {lk: float(other.omega(lk)) for lk in other.link_names}
    alpha = {lk: float(other.alpha(lk)) for lk in other.link_names}
    # the guide's point under each slider's point, from its origin as a point of the guide
    guide_point, rel_v, slide_axis = {}, {}, {}
    for j in m.joints:
        if j.type != "P":
            continue
        g = j.links[0]
        origin = j.origin or m.link(g).points[0]
        r = pos(j.point) - pos(origin)
        w, al = omega[g], alpha[g]
        v_g = other.velocity(origin) + w * _k_cross(r)
        a_g = other.acceleration(origin) + al * _k_cross(r) - w ** 2 * r
        key = f"{j.point}@{g}"
        guide_point[key] = a_g if acceleration else v_g
        rel_v[key] = other.velocity(j.point) - v_g
        turn = float(other.angle(g)) - other.plan.sketch_angles[other.plan.link_item[g]]
        axis = np.array([math.cos(turn) * j.axis[0] - math.sin(turn) * j.axis[1],
                         math.sin(turn) * j.axis[0] + math.cos(turn) * j.axis[1]])
        slide_axis[key] = axis / np.linalg.norm(axis)
    vertices = {**polygon.vertices, **polygon.coincident}
    theirs = {**{p: rate(p) for p in polygon.vertices}, **guide_point}
    scale = max(max((float(np.linalg.norm(v)) for v in vertices.values()), default=0.0), 1e-300)
    if scale <= 1e-300:
        scale = 1.0
    vertex_miss = _most(vertices[k] - theirs[k] for k in vertices) / scale
    side_miss, close_miss = 0.0, 0.0
    parts_miss: dict[str, float] = {}
    for (p, ref), side in polygon.sides.items():
        close_miss = _most([side.vector - (vertices[p] - vertices[ref]),
                            side.vector - sum(side.parts.values()) if side.parts else 0.0],
                           close_miss)
        if side.kind == "difference":
            r = _at_point(p, pos) - _at_point(ref, pos)       # a guide's point: under P
            w, al = omega[side.link], alpha[side.link]
            expected = {"normal": -w ** 2 * r, "tangential": al * _k_cross(r)} if acceleration \
                else {"": w * _k_cross(r)}
        else:
            j = m.joint(side.link)
            key = f"{j.point}@{j.links[0]}"
            u, w = slide_axis[key], omega[j.links[0]]
            if acceleration:
                expected = {"coriolis": 2 * w * _k_cross(rel_v[key]),
                            "sliding": float(other.slide_acceleration(j.name)) * u}
                if "coriolis" not in side.parts:
                    expected.pop("coriolis")
                    parts_miss["coriolis"] = _most([2 * w * _k_cross(rel_v[key])],
                                                   parts_miss.get("coriolis", 0.0))
            else:
                expected = {"": float(other.slide_velocity(j.name)) * u}
        total = sum(expected.values())
        side_miss = _most([side.vector - total], side_miss)
        for part, v in expected.items():
            if part:
                parts_miss[part] = _most([side.parts[part] - v], parts_miss.get(part, 0.0))
    for p in polygon.vertices:       # the ground's points stay at the pole
        if all(lk == m.ground.name for lk in m.links_carrying(p)):
            close_miss = _most([vertices[p]], close_miss)
    what = "acceleration" if acceleration else "velocity"
    unit = f"the polygon's largest vector, {scale:.6g} m/s" + ("^2" if acceleration else "")
    n_vert, n_side = len(vertices), len(polygon.sides)
    comparisons = [Comparison(f"{name} (vertices)", n_vert, vertex_miss, bound, why)] if second \
        else []
    comparisons += [
        Comparison(f"{name}'s rigid-body and sliding formulas (sides)", n_side,
                   side_miss / scale, bound, why),
        Comparison("closure (sides, parts, pole)", n_side, close_miss / scale, CLOSURE,
                   "a difference or sum of a few vectors: rounding")]
    quantities = [Quantity(f"{what} polygon", "analysis", unit, tuple(comparisons))]
    for part, miss in parts_miss.items():
        route = ("2 omega x v_rel, v_rel independent" if part == "coriolis"
                 else f"{name}'s formula")
        label = "Coriolis" if part == "coriolis" else part
        quantities.append(Quantity(f"{label} part", "analysis", unit, (
            Comparison(route, n_side, miss / scale, bound, why),)))
    images = _most(abs(_image(omega[lk], alpha[lk], acceleration) - complex(
        img.scale * math.cos(img.turn), img.scale * math.sin(img.turn)))
                   for lk, img in polygon.images.items())
    rot_scale = max(max((img.scale for img in polygon.images.values()), default=0.0), 1e-300)
    quantities.append(Quantity(f"{what} images", "analysis",
                               f"the largest image scale, {rot_scale:.6g} 1/s"
                               + ("^2" if acceleration else ""), (
        Comparison(f"{name}'s omega and alpha", len(polygon.images),
                   images / (rot_scale if rot_scale > 1e-300 else 1.0), bound, why),)))
    q = ", ".join(f"{v:.6g}" for v in polygon.q)
    return Certificate(f"{what} polygon of '{m.name}' at q = {q}", tuple(quantities), tuple(notes))


def _most(vectors, start: float = 0.0) -> float:
    """The largest norm of ``vectors`` (and ``start``); NaN if any is NaN (it fails)."""
    out = start
    for v in vectors:
        n = float(np.linalg.norm(v))
        if math.isnan(n) or math.isnan(out):
            return math.nan
        out = max(out, n)
    return out


def _image(omega: float, alpha: float, acceleration: bool) -> complex:
    """Multiplication by i omega (velocity) or -omega^2 + i alpha (acceleration)."""
    return complex(-omega ** 2, alpha) if acceleration else complex(0.0, omega)


def _at_point(name: str, pos) -> np.ndarray:
    return pos(name.split("@")[0])


def _at(sol: KinematicSolution, i: int):
    if sol.M > 1:
        return sol.q[i], sol.qd[i], sol.qdd[i]
    return float(sol.q[i, 0]), float(sol.qd[i, 0]), float(sol.qdd[i, 0])

