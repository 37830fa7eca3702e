"""What a refused assembly says: which loop cannot close, by how much, where it does.

The gap is the least distance by which the loop fails to close at the sketch's inputs over
all its branches (``_closure``); the inputs at which it does close come from closing the
loops on a grid of each input (the others held) and narrowing each bound; the nearest value
of the dimension that changed the most at which it closes at the sketch's inputs, from a
grid of that dimension, narrowed the same way.  Everything is computed from the model
alone, in a fixed order: the same message in every run, in the model's own units.
"""
from __future__ import annotations

import math

import numpy as np

from kinelab.errors import AssemblyError
from kinelab.kinematics._closure import SCAN_STARTS
from kinelab.kinematics._columns import INPUT_SI_UNITS
from kinelab.kinematics._input_errors import _telling_digits, _values

__all__ = ["refusal", "loop_through"]

# How finely the inputs and dimensions are searched: closed forms are cheap, Newton groups
# (closed from several starts each time) are searched more coarsely.
_GRID = {True: 721, False: 73}           # values tried for an input over its window
_DIMENSION_GRID = 401                     # values tried for a dimension
_SECTIONS = {True: 64, False: 8}          # each narrowing step cuts an interval in this many
_BOUND_TOL = {True: 1e-10, False: 1e-7}   # bounds to this, relative to a turn or to the size


def refusal(system, closure, closed, near=None) -> AssemblyError:
    """The error of a mechanism that has no configuration at its inputs (``closed``: the
    search over its branches), or that the search did not find near its sketch (``near``:
    the configuration that came nearest, when it does not decompose)."""
    bars = _loop_of_bars(system)
    if bars is not None:
        return bars
    if closure is None or closed is None:
        return _not_found(system, near)
    i = int(np.argmin(closed.gap))
    k = int(closed.failed[i])
    gap = float(closed.gap[i])
    groups = closure.dec.groups
    group = groups[k] if k < len(groups) else None
    m = system.m
    names = m.input_names
    u = system.units
    kinds = system.kinds
    local, fixed, offsets = system.problem(system.at(1.0))
    reach = [_reachable(system, closure, mi, local, fixed, offsets) for mi in range(len(kinds))]
    bounds = [float(u.convert(b, INPUT_SI_UNITS[kinds[0]])) for span in reach[0] for b in span]
    digits = _telling_digits(float(u.convert(system.held[0], INPUT_SI_UNITS[kinds[0]])), bounds) \
        if len(kinds) == 1 else 6
    at = _values(system.held, kinds, u, names, digits)
    loop = ""
    if group is None:
        where = "a joint that no group needs (a redundant one)"
        blame_link = ""
    elif group.kind == "newton":
        where = group.label
        blame_link = group.links[0]
    else:
        points = loop_through(m, group.links[0])
        loop = "-".join(points) if points else ""
        where = f"the loop {loop}" if points else group.label
        blame_link = group.links[0]
    text = f"no assembly at {at}: {where} cannot close there; " + (
        f"it misses by {system.length(gap)}" if math.isfinite(gap) else
        "no configuration of it was found, even cut open")
    detail = closed.detail.get(k)
    if group is not None and detail is not None:
        D, lo, hi = (float(detail[n][i]) for n in ("D", "lo", "hi"))
        if group.kind == "RRR":
            X, _, Z = group.points
            text += (f" ({X} is {system.length(D)} from {Z}, but {_names(group.links)} reach "
                     f"{system.length(lo, False)} to {system.length(hi)})")
        elif group.kind == "RRP":
            X = group.points[0]
            text += (f" ({X} is {system.length(D)} from the line of '{group.joints[1]}', but "
                     f"'{group.links[0]}' reaches {system.length(hi)})")
        elif group.kind == "RPR":
            Z, X = group.points
            text += (f" (the line of '{group.joints[0]}' passes {system.length(lo)} from {Z}, "
                     f"but {X} is {system.length(D)} from {Z})")
    said = []
    for mi, spans in enumerate(reach):
        unit = INPUT_SI_UNITS[kinds[mi]]
        if spans:
            shown = " and ".join(
                f"[{float(u.convert(lo, unit)):.{digits}g}, {float(u.convert(hi, unit)):.{digits}g}]"
                for lo, hi in spans)
            said.append(f"'{names[mi]}' reaches {shown} {u.unit(unit)}")
    others = " with the other inputs as drawn" if len(kinds) > 1 else ""
    advice = []
    if said:
        text += "; " + ", ".join(said) + others
        advice.append(f"draw {_moved_by(m, 0 if len(kinds) == 1 else None)} within "
                      f"{'that range' if sum(len(s) for s in reach) == 1 else 'those ranges'}")
    else:
        text += "; it closes at no value of " + " or ".join(f"'{n}'" for n in names) + others
    blamed = system_blame(system)
    dimension = None
    if blamed is not None:
        dimension = blamed
        value = _nearest_value(system, closure, blamed, local, fixed, offsets)
        if value is not None:
            now, v = value
            word = "at least" if v > now else "at most"
            what = f"'{blamed[1]}'" if blamed[0] == "length" else f"the offset of '{blamed[1]}'"
            advice.append(f"make {what} {word} {system.length(v)}")
        if blamed[0] == "length":
            blame_link = blamed[1]
    text += ("; " + ", or ".join(advice)) if advice else "; check the dimensions"
    err = AssemblyError(text, loop=loop or where, gap=gap, reachable=reach[0] if len(kinds) == 1 else None,
                        link=blame_link)
    err.dimension = dimension
    return err


def _names(links) -> str:
    return " and ".join(f"'{n}'" for n in links)


def _moved_by(m, mi) -> str:
    """What the sketch must show differently for input mi: the link it turns, or its slide."""
    if mi is None:
        return "the inputs"
    inp = m.inputs[mi]
    if inp.joint is not None and m.joint(inp.joint).type == "P":
        return f"the slide '{inp.joint}'"
    a, b = m.joint(inp.joint).links if inp.joint is not None else inp.links
    return f"'{b}'" if b != m.ground.name else f"'{a}'"


def system_blame(system):
    """The dimension that changed the most from the sketch's to the declared (relative):
    ("length", link), ("offset", joint), ("local", link, point), ("pivot", point), or None."""
    best, out = 0.0, None
    L1, L0 = system.dist[2], system.dist_drawn
    for name, a, b in zip(system.dist_links, L1, L0):
        change = abs(a - b) / a
        if change > best:
            best, out = change, ("length", name)
    P0, P1 = system.places
    for (link, p), a, b in zip(system.frame_links, P0, P1):
        change = float(np.max(np.abs(a - b))) / system.scale
        if change > best:
            best, out = change, ("local", link, p)
    for kind, name, data in system.special:
        if kind == "line":
            change = abs(data[3] - data[4]) / system.scale
            if change > best:
                best, out = change, ("offset", name)
    F0, F1 = system.fixed
    for i, a, b in zip(system.fixed_points, F0, F1):
        change = float(np.max(np.abs(a - b))) / system.scale
        if change > best:
            best, out = change, ("pivot", system.m.point_names[i])
    return out if best > 1e-12 else None


def _closes(closure, local, fixed, offsets, q):
    closed = closure.solve(local, fixed, offsets, q, starts=SCAN_STARTS, gaps=False)
    return closed.per_problem(len(q))[0] if len(q) > 0 else np.zeros(0, bool)


def _narrow(closes, a, b, tol, sections):
    """Bounds between a (closing) and b (not) narrowed to |b - a| <= tol, each step cutting
    the interval into ``sections`` parts (one batch of closures per step)."""
    a, b = np.array(a, float), np.array(b, float)
    fractions = np.arange(1, sections) / sections
    for _ in range(60):
        if not len(a) or np.all(np.abs(b - a) <= tol):
            break
        pts = a[:, None] + (b - a)[:, None] * fractions[None, :]
        ok = closes(pts.ravel()).reshape(pts.shape)
        # the last point, from a, that still closes on the first run of closing ones
        first_bad = np.argmax(~ok, axis=1)
        all_ok = ok.all(axis=1)
        last_good = np.where(all_ok, len(fractions) - 1, first_bad - 1)
        new_a = np.where(last_good >= 0, pts[np.arange(len(a)), np.maximum(last_good, 0)], a)
        new_b = np.where(all_ok, b, pts[np.arange(len(a)), np.minimum(first_bad, len(fractions) - 1)])
        a, b = new_a, new_b
    return a


def _reachable(system, closure, mi, local, fixed, offsets) -> list[tuple[float, float]]:
    """The intervals of input mi (the others held) where the loops close on some branch:
    angles over one turn centred on the sketch's, slides over +-10 sizes of the mechanism."""
    kind = system.kinds[mi]
    q0 = float(system.held[mi])
    angle = kind == "angle"
    half = math.pi if angle else 10.0 * system.scale
    norm = 1.0 if angle else system.scale
    held = np.array(system.held, float)

    def closes(values):
        Q = np.tile(held, (len(values), 1))
        Q[:, mi] = values
        return _closes(closure, local, fixed, offsets, Q)
    grid = q0 + np.linspace(-half, half, _GRID[closure.exact])
    ok = closes(grid)
    if ok.all():
        return [(q0 - half, q0 + half)]
    if not ok.any():
        return []
    edges = np.flatnonzero(np.diff(ok.astype(np.int8)))
    inside = ok[edges]
    a = np.where(inside, grid[edges], grid[edges + 1])
    b = np.where(inside, grid[edges + 1], grid[edges])
    bound = _narrow(closes, a, b, _BOUND_TOL[closure.exact] * norm * (2 * math.pi if angle else 1.0),
                    _SECTIONS[closure.exact])
    ranges, start = [], (q0 - half if ok[0] else None)
    for e, v in zip(edges, bound):
        if ok[e] and not ok[e + 1]:
            ranges.append((start, float(v)))
            start = None
        else:
            start = float(v)
    if start is not None:
        ranges.append((start, q0 + half))
    if angle and len(ranges) >= 2 and ok[0] and ok[-1]:
        # the window's two ends are one angle: the first and last pieces are one interval
        ranges = [(ranges[-1][0] - 2 * math.pi, ranges[0][1])] + ranges[1:-1]
    if angle:      # each interval from within half a turn of 0
        ranges = [_wrapped(lo, hi) for lo, hi in ranges]
    return [(float(lo), float(hi)) for lo, hi in ranges]


def _wrapped(lo: float, hi: float) -> tuple[float, float]:
    """An angle interval moved by whole turns so that it starts in (-pi, pi]."""
    k = math.floor((lo + math.pi) / (2 * math.pi))
    shift = 2 * math.pi * k
    if lo - shift <= -math.pi:
        shift -= 2 * math.pi
    return lo - shift, hi - shift


def _nearest_value(system, closure, blamed, local, fixed, offsets):
    """(declared value, nearest value that closes the loops at the sketch's inputs) of a
    length or an offset, the others as declared; None when no value on the grid does."""
    kind = blamed[0]
    held = np.array([system.held], float)
    if kind == "length":
        link = blamed[1]
        v0 = float(system.dist[2][system.dist_links.index(link)])
        base = local[link][0]
        pts = system.m.link(link).points
        given = {p: g for (lk, p), g in zip(system.frame_links, system.place_given) if lk == link}

        def problem(values):
            loc = np.repeat(base[None], len(values), axis=0)
            loc[:, 1, 0] = values
            for k, p in enumerate(pts[2:], 2):
                if not given.get(p, True):       # drawn places keep their place relative to
                    loc[:, k] = base[k] * (values / v0)[:, None]    # the first two points
            return {**local, link: loc}, fixed, offsets
        grid = v0 * np.exp(np.linspace(-math.log(1e3), math.log(1e3), _DIMENSION_GRID))
        distance = np.abs(np.log(grid / v0))
    elif kind == "offset":
        joint = blamed[1]
        v0 = float(offsets[joint][0])

        def problem(values):
            return local, fixed, {**offsets, joint: np.asarray(values, float)}
        grid = v0 + system.scale * np.linspace(-10.0, 10.0, _DIMENSION_GRID)
        distance = np.abs(grid - v0)
    else:
        return None

    def closes(values):
        values = np.asarray(values, float)
        lc, fx, of = problem(values)
        return _closes(closure, lc, fx, of, np.repeat(held, len(values), axis=0))
    # outwards from the declared value, a few values at a time: the first that closes
    order = np.argsort(distance, kind="stable")
    best = None
    for chunk in np.array_split(order, 1 if closure.exact else 8):
        ok = closes(grid[chunk])
        if ok.any():
            best = int(chunk[np.flatnonzero(ok)[np.argmin(distance[chunk][ok])]])
            break
    if best is None:
        return None
    centre = int(order[0])
    step = -1 if best > centre else 1
    if best == centre:
        return v0, float(grid[best])
    tol = _BOUND_TOL[closure.exact] * (v0 if kind == "length" else system.scale)
    v = _narrow(closes, [grid[best]], [grid[best + step]], tol, _SECTIONS[closure.exact])
    return v0, float(v[0])


def _loop_of_bars(system) -> AssemblyError | None:
    """A loop of bars (revolute joints only) whose longest bar is longer than the others
    together cannot close in any configuration, and misses by exactly that excess: such a
    loop is named, the first in the order of the links, with its inequality."""
    m = system.m
    local, fixed, _ = system.problem(system.at(1.0))
    for link in m.links:
        if link.ground:
            continue
        found = _loop_joints(m, link.name)
        if found is None:
            continue
        joints, sides = found
        if any(j.type != "R" for j in joints):
            continue
        bars = {}
        for (j1, j2), side in zip(zip(joints, joints[1:] + joints[:1]), sides):
            if j1.point == j2.point:          # two joints at one point: no bar between them
                continue
            if side in bars:
                bars = None
                break
            loc = local[side][0]
            slot = {p: k for k, p in enumerate(m.link(side).points)}
            bars[side] = float(np.hypot(*(loc[slot[j1.point]] - loc[slot[j2.point]])))
        if not bars or len(bars) < 3:
            continue
        longest = max(bars, key=bars.get)
        rest = {k: v for k, v in bars.items() if k != longest}
        excess = bars[longest] - sum(rest.values())
        if excess > 0:
            loop = [j.point for j in joints]
            text = (f"no assembly: the loop {'-'.join(loop)} cannot close; it misses by "
                    f"{system.length(excess)}: its longest bar is longer than the others "
                    f"together: {longest} {system.length(bars[longest])} > "
                    + " + ".join(f"{k} {system.length(v, unit=False)}" for k, v in rest.items())
                    + f" = {system.length(sum(rest.values()))}; shorten {longest} to at most "
                    f"{system.length(sum(rest.values()))} or lengthen the others")
            err = AssemblyError(text, loop="-".join(loop), gap=excess, link=longest)
            err.dimension = ("length", longest) if longest in system.dist_links else None
            return err
    return None


def _not_found(system, near) -> AssemblyError:
    """No configuration found near the sketch (a mechanism the search over branches does
    not cover): the constraint the nearest attempt missed the most."""
    m = system.m
    name, gap = system.worst(near)
    loop = loop_through(m, name) if name in m.link_names else None
    where = f"the loop {'-'.join(loop)}" if loop else f"'{name}'"
    text = (f"no assembly found near the sketch: {where} cannot close; the nearest configuration "
            f"found misses by {system.length(gap)} at {'link' if name in m.link_names else 'joint'} "
            f"'{name}'; check the lengths, or draw the sketch closer to an assembly")
    err = AssemblyError(text, loop="-".join(loop) if loop else name, gap=gap,
                        link=name if name in m.link_names else "")
    err.dimension = ("length", name) if name in system.dist_links else None
    return err


def _loop_joints(m, link: str):
    """The joints of the shortest loop of the linkage through ``link`` (a path from one of
    its joints back to another without using the link itself, breadth first), and the link
    each side of the loop lies on; None when there is none."""
    joints = [j for j in m.joints if j.point is not None]
    own = [j for j in joints if link in j.links]
    if len(own) < 2:
        return None
    start, goal = own[0], own[1]
    by_link: dict[str, list] = {}
    for j in joints:
        for n in j.links:
            by_link.setdefault(n, []).append(j)
    previous = {start.name: (None, None)}
    todo = [start]
    while todo:
        j = todo.pop(0)
        if j.name == goal.name:
            path, sides = [], []
            while j is not None:
                path.append(j)
                j, side = previous[j.name]
                if side is not None:
                    sides.append(side)
            path, sides = path[::-1], sides[::-1]
            return path, sides + [link]
        for n in j.links:
            if n == link:
                continue
            for k in by_link[n]:
                if k.name not in previous:
                    previous[k.name] = (j, n)
                    todo.append(k)
    return None


def loop_through(m, link: str) -> list[str] | None:
    """The joint points of the shortest loop of the linkage through ``link`` (a point where
    two joints act, as a slider's pin, once)."""
    found = _loop_joints(m, link)
    if found is None:
        return None
    points = [j.point for j in found[0]]
    return [p for k, p in enumerate(points) if p != points[k - 1]] or points[:1]
