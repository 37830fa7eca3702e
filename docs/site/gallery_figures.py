"""The figures of the gallery's page (docs/gallery.md), one function per entry, drawn by the
plot directive of both languages' pages as the site is built: Klann's foot path, and each
spatial entry at its sketch beside what kinelab.spatial finds over its motion."""
import matplotlib.pyplot as plt
import numpy as np
from scipy.spatial.transform import Rotation

import kinelab as kl

MM = {"length": "mm", "angle": "deg"}


def _beside(name, height=3.2):
    """A figure: the entry in 3-D on the left, and the axes for its curves on the right."""
    fig = plt.figure(figsize=(6.0, height), layout="constrained")
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    kl.plot.spatial_mechanism(kl.gallery.load(name).mechanism, ax=ax, units=MM)
    curve = fig.add_subplot(1, 2, 2)
    curve.yaxis.tick_right()                 # clear of the 3-D axes' z label
    curve.yaxis.set_label_position("right")
    return ax, curve


def _path(ax, xyz):
    """Draw a path (N, 3), mm, dashed, and widen the 3-D axes' cube to hold it."""
    ax.plot(*xyz.T, "k--", lw=1)
    lows = [min(lim[0], v) for lim, v in zip((ax.get_xlim(), ax.get_ylim(), ax.get_zlim()),
                                               xyz.min(axis=0))]
    highs = [max(lim[1], v) for lim, v in zip((ax.get_xlim(), ax.get_ylim(), ax.get_zlim()),
                                                xyz.max(axis=0))]
    centre, half = (np.array(lows) + highs) / 2, (np.array(highs) - lows).max() / 2
    for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        set_lim(c - half, c + half)


def klann():
    mf = kl.gallery.load("klann")
    ax = kl.plot.coupler_curve(mf.analyze(361), "F", sample=120, units=mf.units)
    ax.set_title("the foot F over a turn of the crank")


def sarrus():
    ax, curve = _beside("sarrus")
    theta = np.radians(np.linspace(5.0, 85.0, 81))
    p = kl.spatial.sarrus(theta, (0.05, 0.05))
    _path(ax, np.c_[0 * theta, 0 * theta, 1000 * p.height])          # the plate centre's path
    curve.plot(np.degrees(theta), 1000 * p.height)
    curve.set_xlabel("lower link angle [deg]")
    curve.set_ylabel("plate's rise [mm]")


def bennett():
    ax, curve = _beside("bennett")
    theta1 = np.linspace(0.0, 2 * np.pi, 181)
    p = kl.spatial.bennett(theta1, 0.1, 0.1 * np.sqrt(3.0), np.radians(30.0), np.radians(60.0))
    _path(ax, 1000 * p.joints()[0][:, 2])                             # the path of J3
    curve.plot(np.degrees(theta1), np.degrees(np.unwrap(p.theta[:, 1])))
    curve.set_xlabel("θ1 [deg]")
    curve.set_ylabel("θ2 [deg]")


def cardan():
    _, curve = _beside("cardan")
    phi1 = np.linspace(0.0, 2 * np.pi, 361)
    beta = np.radians(30.0)
    curve.plot(np.degrees(phi1), kl.spatial.cardan_motion(phi1, beta, phi1_dot=1.0).ratio)
    curve.axhline(np.cos(beta), color="0.6", lw=0.8)
    curve.axhline(1 / np.cos(beta), color="0.6", lw=0.8)
    curve.set_xlabel("input angle [deg]")
    curve.set_ylabel("output / input speed")


def double_cardan():
    _, curve = _beside("double_cardan")
    phi1 = np.linspace(0.0, 2 * np.pi, 361)
    beta = np.radians(30.0)
    m = kl.spatial.double_cardan(phi1, beta, beta, phi1_dot=1.0)
    curve.plot(np.degrees(phi1), np.gradient(m.phi2, phi1), label="middle shaft")
    curve.plot(np.degrees(phi1), m.ratio, label="output")
    curve.set_xlabel("input angle [deg]")
    curve.set_ylabel("speed / input speed")
    curve.legend()


def stewart_platform():
    ax, curve = _beside("stewart_platform")
    m = kl.gallery.load("stewart_platform").mechanism
    at = {p.name: np.array([p.x, p.y, p.z]) for p in m.points}
    base = np.array([at[f"B{k}"] for k in range(1, 7)])
    top = np.array([at[f"T{k}"] for k in range(1, 7)])
    centre = top.mean(axis=0)
    t = np.linspace(0.0, 2 * np.pi, 181)
    position = centre + np.c_[0.05 * np.sin(t), 0 * t, 0.08 * np.sin(2 * t)]
    rotation = Rotation.from_euler("xyz", np.c_[0.1 * np.sin(t), 0.08 * np.cos(t),
                                                0.15 * np.sin(t)])
    legs = kl.spatial.stewart_leg_lengths(base, top - centre, position, rotation)
    _path(ax, 1000 * position)                                       # the platform centre's path
    curve.plot(np.degrees(t), 1000 * legs)
    curve.set_xlabel("phase of the cycle [deg]")
    curve.set_ylabel("leg lengths [mm]")
