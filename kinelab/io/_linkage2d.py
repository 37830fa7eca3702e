"""Import of linkage2d JSON files (the "Planar Linkage JSON Schema").

There each link has its own frame: its points, directions and lines are given in link
coordinates, and its ``pose`` places the frame in the plane.  Poses need not close the joints:
the file stores a drawing, not an assembly.  So the links are first assembled: starting from
the stored poses, the joints' residuals are brought to zero by least squares (which keeps the
assembly nearest the drawing), and the assembled positions become kinelab's sketch.
"""
from __future__ import annotations

import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from kinelab.errors import ModelError
from kinelab.io._fields import Reader, describe, quoted, shown
from kinelab._files import file_path
from kinelab.io._text import loads, read_text
from kinelab.model import (Input, Joint, Link, Mechanism, Point, angle_problem, coordinate_problem,
                           size_problems)

__all__ = ["from_linkage2d_json"]

_UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}


def _rot(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s], [s, c]])


class _Body:
    """Welded links: one rigid body with a frame (that of its first link)."""

    def __init__(self, links: list[str]):
        self.links = links
        self.local: dict[tuple[str, str], np.ndarray] = {}   # (link, point id) -> body coords
        self.directions: dict[tuple[str, str], float] = {}  # (link, direction id) -> body angle


def _read(source) -> tuple[dict, str]:
    if isinstance(source, Mapping):
        return dict(source), "linkage2d data"
    path = Path(file_path(source, "source"))
    return loads(read_text(path), "JSON", source=path.name), path.name


def from_linkage2d_json(source: str | os.PathLike | Mapping[str, Any], *,
                        input: str | None = None) -> Mechanism:
    """A mechanism from a linkage2d JSON file (or its parsed data).

    Revolute joints become shared points (named after the parent link's point), prismatic
    joints P joints (guide = parent), pin-in-slot joints a P joint with a slider block
    ``<joint>_block`` pinned to the child, and welded links one link.  Gear joints are not
    supported yet.

    Parameters
    ----------
    source : path or mapping
    input : str, optional
        The name (or id) of the joint that drives the mechanism, revolute or prismatic.
        Default: the first revolute joint on the ground link.

    Examples
    --------
    >>> data = {"version": "1.0", "id": "fb", "name": "four-bar", "type": "planar_mechanism",
    ...     "unit_length": "mm", "unit_angle": "deg", "convention": {},
    ...     "links": [
    ...         {"id": "L1", "name": "ground", "isGrounded": True, "pose": {"position": [0, 0], "angle": 0},
    ...          "points": [{"id": "A", "name": "A", "position": [0, 0]},
    ...                     {"id": "D", "name": "D", "position": [300, 0]}]},
    ...         {"id": "L2", "name": "crank", "isGrounded": False, "pose": {"position": [0, 0], "angle": 80},
    ...          "points": [{"id": "A2", "name": "A2", "position": [0, 0]},
    ...                     {"id": "B", "name": "B", "position": [100, 0]}]},
    ...         {"id": "L3", "name": "coupler", "isGrounded": False, "pose": {"position": [20, 100], "angle": 30},
    ...          "points": [{"id": "B3", "name": "B3", "position": [0, 0]},
    ...                     {"id": "C", "name": "C", "position": [300, 0]}]},
    ...         {"id": "L4", "name": "rocker", "isGrounded": False, "pose": {"position": [300, 0], "angle": 100},
    ...          "points": [{"id": "D4", "name": "D4", "position": [0, 0]},
    ...                     {"id": "C4", "name": "C4", "position": [250, 0]}]}],
    ...     "joints": [
    ...         {"id": "R1", "name": "R1", "type": "revolute", "parent": "L1", "point_id_parent": "A", "child": "L2", "point_id_child": "A2"},
    ...         {"id": "R2", "name": "R2", "type": "revolute", "parent": "L2", "point_id_parent": "B", "child": "L3", "point_id_child": "B3"},
    ...         {"id": "R3", "name": "R3", "type": "revolute", "parent": "L3", "point_id_parent": "C", "child": "L4", "point_id_child": "C4"},
    ...         {"id": "R4", "name": "R4", "type": "revolute", "parent": "L1", "point_id_parent": "D", "child": "L4", "point_id_child": "D4"}]}
    >>> m = kl.io.from_linkage2d_json(data)
    >>> m.point_names, m.inputs[0].joint
    (('A', 'B', 'C', 'D'), 'R1')
    >>> round(float(np.hypot(*np.subtract(m.point("C").xy, m.point("D").xy))), 9)   # the rocker
    0.25
    """
    data, where = _read(source)
    r = Reader()
    top = r.table(data, "", ("version", "id", "name", "type", "unit_length", "unit_angle",
                             "convention", "links", "joints"), required=("links", "joints"))
    if top is None or r.problems and not ("links" in top and "joints" in top):
        raise ModelError(r.problems, source=where)
    unit = r.string(top.get("unit_length", "m"), "unit_length", choices=_UNITS)
    angle_unit = r.string(top.get("unit_angle", "rad"), "unit_angle", choices=("deg", "rad"))
    links, joints = (top[k] if isinstance(top[k], list) else [] for k in ("links", "joints"))
    points = sum(len(t["points"]) for t in links      # before the drawing is read and solved
                 if isinstance(t, Mapping) and isinstance(t.get("points"), list))
    r.problems.extend(size_problems(points=points, links=len(links), joints=len(joints)))
    if r.problems:
        raise ModelError(r.problems, source=where)
    ls = _UNITS[unit]
    deg = math.pi / 180 if angle_unit == "deg" else 1.0
    links = _links(r, top["links"], ls, deg)
    joints = _joints(r, top["joints"], links, ls, deg)
    if r.problems:
        raise ModelError(r.problems, source=where)
    try:
        return _build(top, links, joints, ls, deg, input)
    except ModelError as exc:
        raise ModelError(exc.problems, source=where) from None


def _links(r: Reader, value, ls: float, deg: float) -> dict[str, dict]:
    out = {}
    for i, t in enumerate(r.array(value, "links", "tables") or []):
        w = f"links[{i}]"
        t = r.table(t, w, ("id", "name", "isGrounded", "pose", "points", "directions", "lines",
                           "circles", "arcs"), required=("id", "points"))
        if t is None:
            continue
        lid = r.name(t["id"], f"{w}.id") if "id" in t else None
        pose = r.table(t.get("pose", {"position": [0, 0], "angle": 0}), f"{w}.pose",
                       ("position", "angle")) or {}
        position = r.numbers(pose.get("position", [0, 0]), f"{w}.pose.position", 2, scale=ls,
                             check=coordinate_problem)
        angle = r.number(pose.get("angle", 0), f"{w}.pose.angle", scale=deg, check=angle_problem)
        points = {}
        for k, p in enumerate(r.array(t.get("points", []), f"{w}.points", "points") or []):
            p = r.table(p, f"{w}.points[{k}]", ("id", "name", "position"), required=("id", "position"))
            if p is not None and "id" in p and "position" in p:
                pid = r.name(p["id"], f"{w}.points[{k}].id")
                xy = r.numbers(p["position"], f"{w}.points[{k}].position", 2, scale=ls,
                               check=coordinate_problem)
                if pid is not None:         # a bad position is already a problem
                    points[pid] = np.array(xy or (0.0, 0.0))
        directions = {}
        for k, d in enumerate(r.array(t.get("directions", []), f"{w}.directions", "directions") or []):
            d = r.table(d, f"{w}.directions[{k}]", ("id", "name", "angle"), required=("id", "angle"))
            if d is not None and "id" in d and "angle" in d:
                a = r.number(d["angle"], f"{w}.directions[{k}].angle", scale=deg, check=angle_problem)
                if isinstance(d["id"], str):        # a bad angle is already a problem
                    directions[d["id"]] = 0.0 if a is None else a
        lines = {}
        for k, ln in enumerate(r.array(t.get("lines", []), f"{w}.lines", "lines") or []):
            ln = r.table(ln, f"{w}.lines[{k}]", ("id", "name", "point_ids"), required=("id", "point_ids"))
            if ln is not None and "id" in ln and "point_ids" in ln:
                ids = r.names(ln["point_ids"], f"{w}.lines[{k}].point_ids", points, "point", count=2)
                if ids is not None and isinstance(ln["id"], str):
                    lines[ln["id"]] = ids
        grounded = r.boolean(t.get("isGrounded", False), f"{w}.isGrounded")
        name = t.get("name", lid)
        if lid is None:
            continue
        # a bad pose is already a problem: the link is kept, so that joints do not call it unknown
        position, angle = position or (0.0, 0.0), 0.0 if angle is None else angle
        if lid in out:
            r.fail(f"{w}.id", f"{shown(lid)} is already the id of another link")
            continue
        out[lid] = dict(name=name if isinstance(name, str) and name.strip() else lid,
                        grounded=bool(grounded), position=np.array(position), angle=angle,
                        points=points, directions=directions, lines=lines, where=w)
    grounded = [k for k, v in out.items() if v["grounded"]]
    if out and not grounded:
        r.fail("links", "expected a link with isGrounded = true, got none")
    return out


def _joints(r: Reader, value, links: dict[str, dict], ls: float, deg: float) -> list[dict]:
    kinds = {"revolute": ("parent", "child", "point_id_parent", "point_id_child"),
             "prismatic": ("parent", "child", "axis_parent", "axis_child"),
             "pin-in-slot": ("parent", "child", "line_id_parent", "point_id_child"),
             "weld": ("parent", "child", "relative_pos", "relative_angle"),
             "gear": ("parent", "child", "ratio", "phase_offset")}
    out: list[dict] = []
    ids: dict[str, str] = {}          # a joint's id -> the joint that has it
    same: dict[tuple, str] = {}       # what a joint joins -> the joint that joins it
    for i, t in enumerate(r.array(value, "joints", "tables") or []):
        w = f"joints[{i}]"
        if not isinstance(t, Mapping):
            r.fail(w, f"expected a table, got {describe(t)}")
            continue
        kind = r.string(t.get("type"), f"{w}.type", choices=kinds)
        if kind is None:
            continue
        t = r.table(t, w, ("id", "name", "type", "limits", "teeth_parent", "teeth_child")
                    + kinds[kind], required=("id",) + kinds[kind])
        if t is None or any(k not in t for k in ("id",) + kinds[kind]):
            continue
        if kind == "gear":
            r.fail(w, "gear joints are not supported yet; remove the gear or replace it")
            continue
        parent = r.name(t["parent"], f"{w}.parent", links, "link")
        child = r.name(t["child"], f"{w}.child", links, "link")
        if parent is None or child is None:
            continue
        j = dict(kind=kind, id=t["id"], name=t.get("name") or t["id"], parent=parent,
                 child=child, where=w)
        P, C = links[parent], links[child]
        if kind == "revolute":
            j["p"] = r.name(t["point_id_parent"], f"{w}.point_id_parent", P["points"], "point")
            j["c"] = r.name(t["point_id_child"], f"{w}.point_id_child", C["points"], "point")
        elif kind == "prismatic":
            for side, L in (("parent", P), ("child", C)):
                ax = r.table(t[f"axis_{side}"], f"{w}.axis_{side}", ("point_id", "direction_id"),
                             required=("point_id", "direction_id"))
                if ax is not None and "point_id" in ax and "direction_id" in ax:
                    j[side[0]] = r.name(ax["point_id"], f"{w}.axis_{side}.point_id",
                                        L["points"], "point")
                    j[side[0] + "d"] = r.name(ax["direction_id"], f"{w}.axis_{side}.direction_id",
                                              L["directions"], "direction")
        elif kind == "pin-in-slot":
            j["line"] = r.name(t["line_id_parent"], f"{w}.line_id_parent", P["lines"], "line")
            j["c"] = r.name(t["point_id_child"], f"{w}.point_id_child", C["points"], "point")
        else:
            j["rel"] = r.numbers(t["relative_pos"], f"{w}.relative_pos", 2, scale=ls,
                                 check=coordinate_problem)
            j["rel_angle"] = r.number(t["relative_angle"], f"{w}.relative_angle", scale=deg,
                                      check=angle_problem)
        if not all(v is not None for v in j.values()):
            continue
        jid, key = str(j["id"]), _joint_key(j)
        if jid in ids:
            r.fail(f"{w}.id", f"{shown(jid)} is already the id of {ids[jid]}; give each joint "
                   "its own id")
            continue
        if key in same:
            r.fail(w, f"joins the same links at the same places as {same[key]}; remove one")
            continue
        ids[jid] = same[key] = w
        out.append(j)
    return out


def _joint_key(j: dict) -> tuple:
    """What a joint joins, whatever it is called and whichever link is its parent."""
    sides = {"revolute": (("parent", "p"), ("child", "c")),
             "prismatic": (("parent", "p", "pd"), ("child", "c", "cd")),
             "pin-in-slot": (("parent", "line"), ("child", "c")),
             "weld": (("parent",), ("child",))}[j["kind"]]
    ends = frozenset(tuple(str(j[k]) for k in side) for side in sides)
    return (j["kind"], ends, (tuple(j["rel"]), j["rel_angle"]) if j["kind"] == "weld" else ())


def _bodies(links: dict[str, dict], joints: list[dict]) -> dict[str, tuple[str, np.ndarray, float]]:
    """Each link's body (its root link) and the link's frame in the body's: (root, offset, angle)."""
    frame = {}
    welds: dict[str, list[tuple[dict, str, int]]] = {}    # link -> (weld, other link, sign)
    for j in joints:
        if j["kind"] == "weld":
            welds.setdefault(j["parent"], []).append((j, j["child"], 1))
            welds.setdefault(j["child"], []).append((j, j["parent"], -1))
    for root in links:
        if root in frame:
            continue
        frame[root] = (root, np.zeros(2), 0.0)
        todo = [root]
        while todo:
            a = todo.pop()
            for j, y, sign in welds.get(a, ()):
                if y not in frame:
                    _, off, ang = frame[a]
                    rel, rel_angle = np.array(j["rel"]), j["rel_angle"]
                    if sign > 0:     # child frame = parent frame + (rel, rel_angle)
                        o, t = off + _rot(ang) @ rel, ang + rel_angle
                    else:
                        t = ang - rel_angle
                        o = off - _rot(t) @ rel
                    frame[y] = (root, o, t)
                    todo.append(y)
    return frame


_ROWS = {"revolute": 2, "prismatic": 2, "pin-in-slot": 1}   # residuals a joint adds


def _sparsity(joints, frame, slot, ground, bodies: int):
    """Which poses (x, y, angle of each moving body) each residual of ``_build`` depends on:
    a joint's rows on its two bodies alone.  With it the solver differentiates a few
    columns at a time and solves sparsely, instead of one residual per pose (a drawing of
    a hundred links took minutes)."""
    from scipy.sparse import lil_matrix
    rows = sum(_ROWS.get(j["kind"], 0) for j in joints)
    A = lil_matrix((max(rows, 1), 3 * bodies), dtype=np.int8)
    r = 0
    for j in joints:
        k = _ROWS.get(j["kind"], 0)
        for link in (j["parent"], j["child"]):
            body = frame[link][0]
            if k and body != ground:
                A[r:r + k, 3 * slot[body]:3 * slot[body] + 3] = 1
        r += k
    return A


def _build(top, links, joints, ls, deg, input_name) -> Mechanism:
    from scipy.optimize import least_squares

    frame = _bodies(links, joints)
    roots = list(dict.fromkeys(f[0] for f in frame.values()))
    grounded = {frame[k][0] for k, v in links.items() if v["grounded"]}
    if len(grounded) != 1:
        raise ModelError(f"links: expected one grounded body, got {len(grounded)}")
    ground = grounded.pop()
    moving = [b for b in roots if b != ground]
    slot = {b: k for k, b in enumerate(moving)}     # where a body's pose is in x

    def local(link, pid):                 # point in its body's frame
        _, off, ang = frame[link]
        return off + _rot(ang) @ links[link]["points"][pid]

    def body_angle(link, did):
        return frame[link][2] + links[link]["directions"][did]

    def pose(x, body):
        if body == ground:
            return links[body]["position"], links[body]["angle"]
        k = slot[body]
        return x[3 * k:3 * k + 2], x[3 * k + 2]

    def world(x, link, pid):
        p, a = pose(x, frame[link][0])
        return p + _rot(a) @ local(link, pid)

    def residual(x):
        out = []
        for j in joints:
            P, C = j["parent"], j["child"]
            if j["kind"] == "revolute":
                out.extend(world(x, P, j["p"]) - world(x, C, j["c"]))
            elif j["kind"] == "prismatic":
                ap = pose(x, frame[P][0])[1] + body_angle(P, j["pd"])
                ac = pose(x, frame[C][0])[1] + body_angle(C, j["cd"])
                d = world(x, C, j["c"]) - world(x, P, j["p"])
                out.append(-math.sin(ap) * d[0] + math.cos(ap) * d[1])
                out.append(math.sin(ac - ap) * scale)
            elif j["kind"] == "pin-in-slot":
                a, b = links[P]["lines"][j["line"]]
                e = world(x, P, b) - world(x, P, a)
                d = world(x, C, j["c"]) - world(x, P, a)
                out.append((e[0] * d[1] - e[1] * d[0]) / max(np.hypot(*e), 1e-300))
        return np.array(out) if out else np.zeros(1)

    allp = [links[k]["position"] for k in links] + [v for k in links for v in links[k]["points"].values()]
    scale = float(max(np.ptp(np.array(allp), axis=0).max(), 1e-3))
    x0 = np.concatenate([np.r_[links[b]["position"], links[b]["angle"]] for b in moving]) if moving else np.zeros(0)
    if moving:
        sol = least_squares(residual, x0, method="trf", xtol=1e-15, ftol=1e-15, gtol=1e-15,
                            x_scale=np.tile([scale, scale, 1.0], len(moving)),
                            jac_sparsity=_sparsity(joints, frame, slot, ground, len(moving)))
        x = sol.x
    else:
        x = x0
    gap = float(np.abs(residual(x)).max())
    if gap > 1e-9 * scale:
        worst = int(np.argmax(np.abs(residual(x))))
        raise ModelError(f"joints: the links cannot be assembled (a joint stays open by "
                         f"{gap / ls:.4g} {top.get('unit_length', 'm')}, residual {worst}); check "
                         "the link geometry")
    # -- kinelab names: pinned points become one; names unique across points, links, joints
    taken: set[str] = set()

    def unique(name: str) -> str:
        base, k = str(name), 2
        while name in taken:
            name = f"{base}_{k}"
            k += 1
        taken.add(name)
        return name

    body_name = {b: unique(links[b]["name"]) for b in roots}
    point_of: dict[tuple[str, str], str] = {}
    positions: dict[str, np.ndarray] = {}
    carried: dict[str, dict[str, None]] = {b: {} for b in roots}   # body -> its points, in order

    def point(link, pid):
        if (link, pid) not in point_of:
            name = unique(pid)
            point_of[(link, pid)] = name
            positions[name] = world(x, link, pid)
        n = point_of[(link, pid)]
        body = frame[link][0]
        carried[body][n] = None
        return n

    for j in joints:                          # pins first: the parent's point names both
        if j["kind"] == "revolute":
            n = point(j["parent"], j["p"])
            point_of[(j["child"], j["c"])] = n
            point(j["child"], j["c"])
    for link, v in links.items():
        for pid in v["points"]:
            point(link, pid)
    kl_joints, extra_links = [], []
    ground_name = body_name[ground]
    for j in joints:
        bp, bc = body_name[frame[j["parent"]][0]], body_name[frame[j["child"]][0]]
        jname = unique(j["name"] if isinstance(j["name"], str) else str(j["id"]))
        if j["kind"] == "revolute":
            if bp == bc:
                continue
            pair = (bp, bc) if bc != ground_name else (bc, bp)
            kl_joints.append(Joint(jname, "R", pair, point=point_of[(j["parent"], j["p"])]))
        elif j["kind"] == "prismatic":
            a = pose(x, frame[j["parent"]][0])[1] + body_angle(j["parent"], j["pd"])
            kl_joints.append(Joint(jname, "P", (bp, bc), point=point_of[(j["child"], j["c"])],
                                   axis=(math.cos(a), math.sin(a)),
                                   origin=point_of[(j["parent"], j["p"])]))
        elif j["kind"] == "pin-in-slot":
            a, b = links[j["parent"]]["lines"][j["line"]]
            e = world(x, j["parent"], b) - world(x, j["parent"], a)
            pin = point_of[(j["child"], j["c"])]
            block = unique(f"{jname}_block")
            extra_links.append(Link(block, (pin,)))
            kl_joints.append(Joint(jname, "P", (bp, block), point=pin, axis=tuple(e / np.hypot(*e)),
                                   origin=point_of[(j["parent"], a)]))
            kl_joints.append(Joint(unique(f"{jname}_pin"), "R", (block, bc), point=pin))
    on_ground = set(carried[ground])
    kl_links = [Link(body_name[b], tuple(sorted(carried[b], key=lambda p: p not in on_ground)),
                     ground=(b == ground)) for b in roots] + extra_links
    inputs = _input(kl_joints, joints, ground_name, input_name)
    return Mechanism(name=str(top.get("name") or top.get("id") or "linkage2d"),
                     points=tuple(Point(n, float(p[0]), float(p[1])) for n, p in positions.items()),
                     links=tuple(kl_links), joints=tuple(kl_joints), inputs=inputs)


def _input(kl_joints: list[Joint], joints: list[dict], ground: str, wanted: str | None):
    if wanted is None:
        for j in kl_joints:
            if j.type == "R" and j.links[0] == ground:
                return (Input(joint=j.name),)
        return ()
    names = {j.name for j in kl_joints}
    by_id = {str(j["id"]): j["name"] for j in joints}
    name = wanted if wanted in names else by_id.get(wanted)
    if name not in names:
        raise ModelError(f"input: expected the name or id of a joint, got {shown(wanted)}; the "
                         f"joints are {quoted(sorted(names))}")
    return (Input(joint=name),)
