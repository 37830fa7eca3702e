"""Models shared by the structure tests, each built from its defining geometry."""
from __future__ import annotations

import numpy as np
from scipy.optimize import least_squares

from kinelab.model import Joint, Link, Mechanism, Point


def _R(name, a, b, point, axis=None):
    return Joint(name, "R", (a, b), point=point, axis=None if axis is None else tuple(axis))


def fourbar(*, sketch=((0, 0), (0, 1), (3, 2), (3, 0))):
    o2, a, b, o4 = sketch
    pts = (Point("O2", *o2), Point("A", *a), Point("B", *b), Point("O4", *o4))
    links = (Link("ground", ("O2", "O4"), ground=True), Link("crank", ("O2", "A")),
             Link("coupler", ("A", "B")), Link("rocker", ("O4", "B")))
    joints = (_R("jO2", "ground", "crank", "O2"), _R("jA", "crank", "coupler", "A"),
              _R("jB", "coupler", "rocker", "B"), _R("jO4", "ground", "rocker", "O4"))
    return Mechanism("four-bar", pts, links, joints)


def triangle():
    pts = (Point("A", 0, 0), Point("B", 2, 0), Point("C", 0.7, 1.3))
    links = (Link("ground", ("A", "B"), ground=True), Link("l2", ("B", "C")),
             Link("l3", ("C", "A")))
    joints = (_R("jA", "ground", "l3", "A"), _R("jB", "ground", "l2", "B"),
              _R("jC", "l2", "l3", "C"))
    return Mechanism("triangle", pts, links, joints)


def parallelogram_fivebar(angle=1.1, spacing=(0.0, 2.0, 3.5)):
    """Three equal parallel cranks on one coupler: a four-bar parallelogram plus a
    redundant crank."""
    c, s = np.cos(angle), np.sin(angle)
    pts, links, joints = [], [Link("ground", ("O1", "O2", "O3"), ground=True)], []
    for k, x in enumerate(spacing, start=1):
        pts += [Point(f"O{k}", x, 0.0), Point(f"A{k}", x + c, s)]
        links.append(Link(f"crank{k}", (f"O{k}", f"A{k}")))
        joints += [_R(f"jO{k}", "ground", f"crank{k}", f"O{k}"),
                   _R(f"jA{k}", f"crank{k}", "coupler", f"A{k}")]
    links.append(Link("coupler", ("A1", "A2", "A3")))
    return Mechanism("parallelogram five-bar", pts, links, joints)


def slider_crank():
    pts = (Point("O2", 0, 0), Point("A", 0.6, 0.8), Point("B", 3.4, 0.0))
    links = (Link("ground", ("O2",), ground=True), Link("crank", ("O2", "A")),
             Link("rod", ("A", "B")), Link("slider", ("B",)))
    joints = (_R("jO2", "ground", "crank", "O2"), _R("jA", "crank", "rod", "A"),
              _R("jB", "rod", "slider", "B"),
              Joint("slide", "P", ("ground", "slider"), point="B", axis=(1.0, 0.0)))
    return Mechanism("slider-crank", pts, links, joints)


def disk_cam_flat_follower():
    """*Mecanismos*, Ex. 2.2: a disk cam turning about O2 lifts a flat-faced follower that
    slides vertically; the cam touches the face at C, whose normal is vertical."""
    pts = (Point("O2", 0, 0), Point("K", 0.3, 0.2), Point("F", 0.1, 1.5),
           Point("G", 0.1, 2.5), Point("C", 0.25, 1.0))
    links = (Link("ground", ("O2",), ground=True), Link("cam", ("O2", "K")),
             Link("follower", ("F", "G", "C")))
    joints = (_R("jO2", "ground", "cam", "O2"),
              Joint("guide", "P", ("ground", "follower"), point="F", axis=(0.0, 1.0)),
              Joint("contact", "cam", ("cam", "follower"), point="C", axis=(0.0, 1.0)))
    return Mechanism("disk cam, flat-faced follower", pts, links, joints)


def sarrus(elbows=((1.6, 0.3, 0.4), (0.2, 1.7, 0.6))):
    """*Mecanismos*, §2.2, Fig. 12: plate 4 on two legs of three parallel R joints, axes along
    y (links 1-2-3-4) and along x (links 1-5-6-4)."""
    (ax, ay, az), (bx, by, bz) = elbows
    pts = (Point("A1", 1.0, 0.0, 0.0), Point("A2", ax, ay, az), Point("A3", 1.1, -0.2, 1.0),
           Point("B1", 0.0, 1.0, 0.0), Point("B2", bx, by, bz), Point("B3", -0.1, 1.2, 1.0))
    links = (Link("1", ("A1", "B1"), ground=True), Link("2", ("A1", "A2")),
             Link("3", ("A2", "A3")), Link("4", ("A3", "B3")), Link("5", ("B1", "B2")),
             Link("6", ("B2", "B3")))
    y, x = (0.0, 1.0, 0.0), (1.0, 0.0, 0.0)
    joints = (_R("12", "1", "2", "A1", y), _R("23", "2", "3", "A2", y),
              _R("34", "3", "4", "A3", y), _R("15", "1", "5", "B1", x),
              _R("56", "5", "6", "B2", x), _R("64", "6", "4", "B3", x))
    return Mechanism("RRRRRR (Sarrus)", pts, links, joints, space="spatial")


def _dh(theta, a, alpha):
    ct, st, ca, sa = np.cos(theta), np.sin(theta), np.cos(alpha), np.sin(alpha)
    return np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                     [0, sa, ca, 0], [0, 0, 0, 1.0]])


def closed_4r(lengths, twists, theta1=1.0):
    """A spatial 4R loop (Denavit-Hartenberg, offsets zero) closed at joint angle theta1,
    the other three angles found by least squares; returns the model and the residual."""
    def frames(th):
        f = [np.eye(4)]
        for t, a, al in zip(th, lengths, twists):
            f.append(f[-1] @ _dh(t, a, al))
        return f

    def gap(rest):
        return (frames([theta1, *rest])[-1] - np.eye(4))[:3].ravel()
    best = min((least_squares(gap, x0, xtol=1e-15, ftol=1e-15, gtol=1e-15)
                for x0 in ([2.0, -1.0, -2.0], [-2.0, 1.0, 2.0], [1.0, 1.0, 1.0])),
               key=lambda r: r.cost)
    f = frames([theta1, *best.x])
    pts = tuple(Point(f"J{k + 1}", *f[k][:3, 3]) for k in range(4))
    links = (Link("ground", ("J4", "J1"), ground=True), Link("l2", ("J1", "J2")),
             Link("l3", ("J2", "J3")), Link("l4", ("J3", "J4")))
    pairs = [("ground", "l2"), ("l2", "l3"), ("l3", "l4"), ("l4", "ground")]
    joints = tuple(_R(f"j{k + 1}", *pairs[k], f"J{k + 1}", f[k][:3, 2]) for k in range(4))
    return Mechanism("4R", pts, links, joints, space="spatial"), float(np.max(np.abs(gap(best.x))))


def bennett(b=np.sqrt(3.0)):
    """Bennett's linkage: a = 1, alpha = 30 deg, beta = 60 deg, and b / sin(beta) =
    a / sin(alpha) when b = sqrt(3)."""
    return closed_4r((1.0, b, 1.0, b), (np.pi / 6, np.pi / 3, np.pi / 6, np.pi / 3))


def rssr(with_extra_coupler_point=False):
    pts = [Point("O1", 0, 0, 0), Point("A", 0.3, 0.9, 0.2), Point("B", 2.1, 1.4, 1.1),
           Point("O4", 2.5, 0.2, 0.8)]
    coupler = ("A", "B")
    if with_extra_coupler_point:
        pts.append(Point("W", 1.0, 1.6, 0.2))
        coupler += ("W",)
    links = (Link("ground", ("O1", "O4"), ground=True), Link("crank", ("O1", "A")),
             Link("coupler", coupler), Link("rocker", ("O4", "B")))
    joints = (_R("jO1", "ground", "crank", "O1", (0.1, 0.2, 1.0)),
              Joint("jA", "S", ("crank", "coupler"), point="A"),
              Joint("jB", "S", ("coupler", "rocker"), point="B"),
              _R("jO4", "ground", "rocker", "O4", (1.0, 0.3, -0.2)))
    return Mechanism("RSSR", tuple(pts), links, joints, space="spatial")


def double_wishbone(wheel_centre=True):
    """*Mecanismos*, Ex. 2.3: chassis 1, upper arm 2, knuckle 3, lower arm 4; R pairs 12 and
    14 along the car, S pairs 23 and 34 (the ball joints)."""
    pts = [Point("U1", 0.0, 0.30, 0.0), Point("U2", 0.0, 0.30, 0.50), Point("L1", 0.0, 0.0, -0.10),
           Point("L2", 0.0, 0.0, 0.40), Point("BU", 0.35, 0.33, 0.20),
           Point("BL", 0.45, -0.02, 0.18)]
    knuckle = ("BU", "BL")
    if wheel_centre:
        pts.append(Point("W", 0.55, 0.15, 0.25))
        knuckle += ("W",)
    links = (Link("chassis", ("U1", "U2", "L1", "L2"), ground=True),
             Link("upper", ("U1", "BU")), Link("knuckle", knuckle), Link("lower", ("L1", "BL")))
    along = (0.0, 0.0, 1.0)
    joints = (_R("12", "chassis", "upper", "U1", along), _R("14", "chassis", "lower", "L1", along),
              Joint("23", "S", ("upper", "knuckle"), point="BU"),
              Joint("34", "S", ("knuckle", "lower"), point="BL"))
    return Mechanism("double wishbone", tuple(pts), links, joints, space="spatial")


def stewart(leg="UPS"):
    """A Gough-Stewart platform, six legs base -> platform (6-UPS or 6-SPS)."""
    base = [(np.cos(t), np.sin(t), 0.0) for t in np.radians([0, 50, 120, 170, 240, 290])]
    top = [(0.5 * np.cos(t), 0.5 * np.sin(t), 1.0) for t in np.radians([25, 95, 145, 215, 265, 335])]
    pts, links, joints = [], [], []
    bnames, tnames = [f"b{k}" for k in range(6)], [f"t{k}" for k in range(6)]
    for k in range(6):
        b, t = np.array(base[k]), np.array(top[k])
        m, n = b + 0.55 * (t - b), b + 0.45 * (t - b)
        pts += [Point(bnames[k], *b), Point(tnames[k], *t), Point(f"m{k}", *m), Point(f"n{k}", *n)]
        links += [Link(f"cyl{k}", (bnames[k], f"m{k}")), Link(f"rod{k}", (f"n{k}", tnames[k]))]
        d = tuple(t - b)
        if leg == "UPS":
            u1 = np.cross(d, (0.0, 0.0, 1.0))
            joints.append(Joint(f"U{k}", "U", ("base", f"cyl{k}"), point=bnames[k],
                                axis=tuple(u1), axis2=tuple(np.cross(d, u1))))
        else:
            joints.append(Joint(f"Sb{k}", "S", ("base", f"cyl{k}"), point=bnames[k]))
        joints += [Joint(f"P{k}", "P", (f"cyl{k}", f"rod{k}"), point=f"n{k}", axis=d),
                   Joint(f"S{k}", "S", (f"rod{k}", "platform"), point=tnames[k])]
    links = [Link("base", tuple(bnames), ground=True), *links, Link("platform", tuple(tnames))]
    return Mechanism(f"6-{leg}", tuple(pts), tuple(links), tuple(joints), space="spatial")


def spherical_fourbar(concurrent=True):
    dirs = np.array([[1.0, 0.2, 0.3], [0.3, 1.0, 0.4], [-0.2, 0.4, 1.0], [0.6, -0.5, 0.8]])
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    shift = np.zeros(3) if concurrent else np.array([0.0, 0.0, 0.2])
    pts = tuple(Point(f"J{k + 1}", *(dirs[k] + (shift if k == 2 else 0))) for k in range(4))
    links = (Link("ground", ("J4", "J1"), ground=True), Link("l2", ("J1", "J2")),
             Link("l3", ("J2", "J3")), Link("l4", ("J3", "J4")))
    pairs = [("ground", "l2"), ("l2", "l3"), ("l3", "l4"), ("l4", "ground")]
    joints = tuple(_R(f"j{k + 1}", *pairs[k], f"J{k + 1}", dirs[k]) for k in range(4))
    return Mechanism("spherical four-bar", pts, links, joints, space="spherical")


def parallel(chains, space, seed=0):
    """A mechanism with the given chains (strings of pair types, base to platform) between
    a base and a platform, every pair in general position (spherical: every axis through
    the origin)."""
    rng = np.random.default_rng(seed)
    dim = 2 if space == "planar" else 3

    def unit():
        u = rng.standard_normal(dim)
        return tuple(u / np.linalg.norm(u))
    pts, links, joints = [], [], []
    carried = {"base": [], "platform": []}
    for k, chain in enumerate(chains):
        names = ["base"] + [f"c{k}l{i}" for i in range(1, len(chain))] + ["platform"]
        for n in names[1:-1]:
            carried[n] = []
        for i, t in enumerate(chain):
            p = rng.standard_normal(dim)
            if space == "spherical":
                p = 1.5 * p / np.linalg.norm(p)
            pname = f"c{k}p{i}"
            pts.append(Point(pname, *p))
            a, b = names[i], names[i + 1]
            carried[b].append(pname)
            if t in ("R", "S", "U"):  # the model hinges shared points with these only
                carried[a].append(pname)
            axis = (tuple(p / np.linalg.norm(p)) if space == "spherical" else unit())
            kw = {}
            if t in ("R", "P", "C", "H") and (space != "planar" or t == "P"):
                kw["axis"] = axis
            if t == "U":
                kw["axis"], kw["axis2"] = axis, unit()
            if t == "H":
                kw["pitch"] = 0.1
            joints.append(Joint(f"c{k}j{i}", t, (a, b), point=pname, **kw))
    for n, ps in carried.items():
        while len(ps) < 2:  # a guide of a P pair carries a point of its own
            extra = f"{n}x{len(ps)}"
            pts.append(Point(extra, *rng.standard_normal(dim)))
            ps.append(extra)
    links = [Link(n, tuple(ps), ground=(n == "base")) for n, ps in carried.items()]
    return Mechanism("+".join(chains), tuple(pts), tuple(links), tuple(joints), space=space)
