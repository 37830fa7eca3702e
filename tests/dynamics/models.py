"""Mechanisms with mass data for the dynamics tests, built in Python (SI units)."""
import numpy as np

import kinelab as kl
from kinelab.model import Input, Joint, Link, Mechanism, Point


def pendulum(length=0.5, mass=2.0, inertia=0.01, arm=1.0):
    """A bar turning about O (input ``pivot``), centre of mass G at ``length`` along it."""
    return Mechanism(
        "pendulum", (Point("O", 0.0, 0.0), Point("G", length, 0.0), Point("E", arm, 0.0)),
        (Link("ground", ("O",), ground=True),
         Link("arm", ("O", "G", "E"), mass=mass, center_of_mass="G", inertia=inertia)),
        (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))


def rp_robot(arm_mass=None, gripper_inertia=None, q=(0.3, 0.6)):
    """*Mecanismos*, §5.5: arm 1 turns about O (q1, ``shoulder``), gripper 2 slides along it
    (q2 = O G2, ``reach``).  Massless by default, as in the notes (add their mass data
    with the arguments; the arm's centre of mass is G1 at 0.4 m)."""
    c, s = np.cos(q[0]), np.sin(q[0])
    arm = (Link("arm", ("O", "E", "G1"), mass=arm_mass, center_of_mass="G1", inertia=0.05)
           if arm_mass else Link("arm", ("O", "E", "G1")))
    grip = (Link("gripper", ("G2",), mass=1.0, center_of_mass="G2", inertia=gripper_inertia)
            if gripper_inertia else Link("gripper", ("G2",)))
    return Mechanism(
        "rp", (Point("O", 0.0, 0.0), Point("E", c, s), Point("G1", 0.4 * c, 0.4 * s),
               Point("G2", q[1] * c, q[1] * s)),
        (Link("ground", ("O",), ground=True), arm, grip),
        (Joint("shoulder", "R", ("ground", "arm"), point="O"),
         Joint("reach", "P", ("arm", "gripper"), point="G2", axis=(c, s), origin="O")),
        (Input(joint="shoulder"), Input(joint="reach")))


def pr_robot(m1=3.0, m2=2.0, length=0.6, inertia=0.08):
    """*Mecanismos*, §5.6: block 1 slides along x (q1 = x of S, ``rail``), arm 2 turns about
    S (q2, ``wrist``) with its centre of mass G at ``length`` from S."""
    return Mechanism(
        "pr", (Point("O", 0.0, 0.0), Point("X", 1.0, 0.0), Point("S", 0.2, 0.0),
               Point("G", 0.2, length)),
        (Link("ground", ("O", "X"), ground=True), Link("block", ("S",), mass=m1, center_of_mass="S"),
         Link("arm", ("S", "G"), mass=m2, center_of_mass="G", inertia=inertia)),
        (Joint("rail", "P", ("ground", "block"), point="S", axis=(1.0, 0.0), origin="O"),
         Joint("wrist", "R", ("block", "arm"), point="S")),
        (Input(joint="rail"), Input(joint="wrist")))


PRRRR = dict(L0=1.0, L2=0.4, L3=0.8, L4=0.9, l2=0.15, m1=2.0, m2=1.5, m3=0.8, m4=1.2,
             I2=0.03, I3=0.05, I4=0.09)


def prrrr(q=(0.2, 1.2), **kw):
    """*Mecanismos*, §5.7: slider 1 on the y axis (q1 = y of G1, ``rail``), crank 2 about
    O2 = (L0, 0) (q2, ``jO2``), bars 3 (G1-P) and 4 (A-P) meeting at P; every link with
    its own (distributed) mass, the bars' centres of mass at their middles."""
    p = {**PRRRR, **kw}
    G1 = np.array([0.0, q[0]])
    A = np.array([p["L0"] + p["L2"] * np.cos(q[1]), p["L2"] * np.sin(q[1])])
    P = np.array(circle_point(G1, A, p["L3"], p["L4"], +1.0))
    G2 = np.array([p["L0"], 0.0]) + p["l2"] / p["L2"] * (A - [p["L0"], 0.0])
    pts = dict(O=(0.0, 0.0), O2=(p["L0"], 0.0), G1=G1, A=A, P=P, G2=G2,
               G3=(G1 + P) / 2, G4=(A + P) / 2)
    return Mechanism(
        "prrrr", tuple(Point(n, float(xy[0]), float(xy[1])) for n, xy in pts.items()),
        (Link("ground", ("O", "O2"), ground=True),
         Link("slider", ("G1",), mass=p["m1"], center_of_mass="G1"),
         Link("crank", ("O2", "A", "G2"), mass=p["m2"], center_of_mass="G2", inertia=p["I2"]),
         Link("bar3", ("G1", "P", "G3"), mass=p["m3"], center_of_mass="G3", inertia=p["I3"]),
         Link("bar4", ("A", "P", "G4"), mass=p["m4"], center_of_mass="G4", inertia=p["I4"])),
        (Joint("rail", "P", ("ground", "slider"), point="G1", axis=(0.0, 1.0), origin="O"),
         Joint("jO2", "R", ("ground", "crank"), point="O2"),
         Joint("jG1", "R", ("slider", "bar3"), point="G1"),
         Joint("jA", "R", ("crank", "bar4"), point="A"),
         Joint("jP", "R", ("bar3", "bar4"), point="P")),
        (Input(joint="rail"), Input(joint="jO2")))


def circle_point(X, Z, lx, lz, sigma):
    """The intersection of circles (X, lx) and (Z, lz) to the left (sigma = +1) of X->Z;
    works on arrays of centres, shape (..., 2)."""
    X, Z = np.asarray(X, float), np.asarray(Z, float)
    d = Z - X
    D = np.linalg.norm(d, axis=-1)
    a = (lx ** 2 - lz ** 2 + D ** 2) / (2 * D)
    h = np.sqrt(lx ** 2 - a ** 2)
    e = d / D[..., None]
    return X + a[..., None] * e + sigma * h[..., None] * np.stack([-e[..., 1], e[..., 0]], axis=-1)


ENGINE = dict(crank=0.05, rod=0.18, offset=0.0, crank_mass=3.0, crank_cg=0.01, crank_inertia=0.004,
              rod_mass=1.2, rod_cg=0.06, rod_inertia=0.0045, piston_mass=0.8, bore=0.08)


def engine(**kw):
    """A single-cylinder engine: the catalogue slider-crank with distributed masses.  The
    crank's centre of mass G2 sits ``crank_cg`` past O2 on the side of the pin (a
    counterweight would make it negative), the rod's G3 ``rod_cg`` from the crank pin A."""
    p = {**ENGINE, **kw}
    sc = kl.mechanisms.slider_crank(crank=p["crank"], rod=p["rod"], offset=p["offset"])
    A, B = np.array(sc.point("A").xy), np.array(sc.point("B").xy)
    G2 = A * p["crank_cg"] / p["crank"]
    G3 = A + (B - A) * p["rod_cg"] / p["rod"]
    links = (Link("ground", ("O2",), ground=True),
             Link("crank", ("O2", "A", "G2"), mass=p["crank_mass"], center_of_mass="G2",
                  inertia=p["crank_inertia"]),
             Link("rod", ("A", "B", "G3"), mass=p["rod_mass"], center_of_mass="G3",
                  inertia=p["rod_inertia"]),
             Link("slider", ("B",), mass=p["piston_mass"], center_of_mass="B"))
    return Mechanism("engine", sc.points + (Point("G2", *G2), Point("G3", *G3)), links,
                     sc.joints, sc.inputs)


def fourbar(**kw):
    """A crank-rocker with every link's centre of mass off its line (points G2, G3, G4)."""
    fb = kl.mechanisms.fourbar(ground=0.3, crank=0.1, coupler=0.25, rocker=0.2, coupler_point=(0.1, 0.05))
    xy = {p.name: np.array(p.xy) for p in fb.points}
    G2 = xy["O2"] + 0.5 * (xy["A"] - xy["O2"]) + [0.0, 0.01]
    G3 = xy["P"]
    G4 = xy["O4"] + 0.6 * (xy["B"] - xy["O4"]) + [0.005, 0.0]
    links = (Link("ground", ("O2", "O4"), ground=True),
             Link("crank", ("O2", "A", "G2"), mass=0.5, center_of_mass="G2", inertia=1e-3),
             Link("coupler", ("A", "B", "P"), mass=1.0, center_of_mass="P", inertia=6e-3),
             Link("rocker", ("O4", "B", "G4"), mass=0.8, center_of_mass="G4", inertia=3e-3))
    return Mechanism("fourbar", fb.points + (Point("G2", *G2), Point("G4", *G4)), links,
                     fb.joints, fb.inputs)
