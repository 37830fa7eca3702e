"""Independent checks of a kinematic solution, shared by the tests.

Nothing here uses the engine's own formulas: closure is measured on the output points,
derivatives by central differences of the engine's positions.
"""
import numpy as np

import kinelab as kl


def wrap(a):
    return np.angle(np.exp(1j * np.asarray(a)))


def closure_residual(sol):
    """Largest violation of the model's constraints over the samples, in metres.

    Every link keeps the distances between its points; every prismatic joint keeps its
    point on the guide's line and the two links' relative angle.
    """
    m = sol.mechanism
    xy = {p.name: np.array([p.x, p.y]) for p in m.points}
    worst = 0.0
    for link in m.links:
        pts = link.points
        for a, b in zip(pts, pts[1:]):
            d = np.linalg.norm(sol.position(a) - sol.position(b), axis=-1)
            worst = max(worst, float(np.max(np.abs(d - np.linalg.norm(xy[a] - xy[b])))))
        if len(pts) >= 2:
            # orientation of the link follows its first two points
            v = sol.position(pts[1]) - sol.position(pts[0])
            ang = np.arctan2(v[..., 1], v[..., 0])
            worst = max(worst, float(np.max(np.abs(wrap(ang - sol.angle(link.name))))))
    for j in m.joints:
        if j.type != "P":
            continue
        g, s = j.links
        sketch_rel = _sketch_link_angle(m, s) - _sketch_link_angle(m, g)
        rel = wrap(sol.angle(s) - sol.angle(g) - sketch_rel)
        worst = max(worst, float(np.max(np.abs(rel))))
        axis0 = np.arctan2(j.axis[1], j.axis[0]) - _sketch_link_angle(m, g)
        th = sol.angle(g) + axis0
        origin = j.origin or m.link(g).points[0]
        d = sol.position(j.point) - sol.position(origin)
        normal = -np.sin(th) * d[..., 0] + np.cos(th) * d[..., 1]
        d0 = xy[j.point] - xy[origin]
        normal0 = -np.sin(axis0 + _sketch_link_angle(m, g)) * d0[0] + np.cos(axis0 + _sketch_link_angle(m, g)) * d0[1]
        worst = max(worst, float(np.max(np.abs(normal - normal0))))
        along = np.cos(th) * d[..., 0] + np.sin(th) * d[..., 1]
        worst = max(worst, float(np.max(np.abs(along - sol.slide(j.name)))))
    return worst


def _sketch_link_angle(m, link):
    pts = m.link(link).points
    if len(pts) >= 2:
        a, b = m.point(pts[0]), m.point(pts[1])
        return np.arctan2(b.y - a.y, b.x - a.x)
    if m.link(link).ground:
        return 0.0
    # a block: the axis of the joint it slides in, else of the one it guides
    slides = [j for j in m.joints_of(link) if j.type == "P"]
    j = next((j for j in slides if j.links[1] == link), slides[0])
    return np.arctan2(j.axis[1], j.axis[0])


def names(sol):
    return sol.link_names, sol.point_names, sol.slide_names


def values(sol, name):
    """The position-level value of a link angle, point or slide."""
    if name in sol.link_names:
        return sol.angle(name)
    if name in sol.point_names:
        return sol.position(name)
    return sol.slide(name)


def finite_difference_errors(m, q, h=1e-5):
    """Max relative error of K and L against central differences, per input direction."""
    sol = kl.analyze(m, q=q)
    M = len(m.inputs)
    q = np.asarray(q, float)
    worst_K = worst_L = 0.0
    for a in range(M):
        dq = np.zeros(M)
        dq[a] = h
        step = dq if M > 1 else h
        sp, sm = kl.analyze(m, q=q + step), kl.analyze(m, q=q - step)
        for name in sol.link_names + sol.point_names + sol.slide_names:
            diff = values(sp, name) - values(sm, name)
            if name in sol.link_names:
                diff = wrap(diff)
            fd_K = diff / (2 * h)
            fd_L = (sp.K(name) - sm.K(name)) / (2 * h)
            K = sol.K(name) if M == 1 else sol.K(name)[..., a]
            L = sol.L(name) if M == 1 else sol.L(name)[..., a, :]
            scale_K = 1.0 + np.max(np.abs(K))
            scale_L = 1.0 + np.max(np.abs(L))
            worst_K = max(worst_K, float(np.max(np.abs(fd_K - K))) / scale_K)
            worst_L = max(worst_L, float(np.max(np.abs(fd_L - L))) / scale_L)
    return worst_K, worst_L


def engine_difference(m, q):
    """Largest difference between the closed-form plan and the general Newton engine."""
    a = kl.analyze(m, q=q)
    b = kl.analyze(m, q=q, method="newton")
    worst = 0.0
    for name in a.link_names + a.point_names + a.slide_names:
        d = values(a, name) - values(b, name)
        if name in a.link_names:
            d = wrap(d)
        worst = max(worst, float(np.max(np.abs(d))),
                    float(np.max(np.abs(a.K(name) - b.K(name)))),
                    float(np.max(np.abs(a.L(name) - b.L(name)))))
    return worst
