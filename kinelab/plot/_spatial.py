"""A spherical or spatial model drawn in 3-D: its links between their points."""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError
from kinelab.model import Mechanism, Units

__all__ = ["spatial_mechanism"]


def spatial_mechanism(model: Mechanism, positions: Mapping[str, ArrayLike] | None = None, *,
                      ax=None, units: Units | Mapping[str, str] | None = None):
    """Draw a spherical or spatial model in 3-D: each moving link as the bars between its
    points (a closed outline for three or more), the ground's points as grey triangles.

    Parameters
    ----------
    model : Mechanism
        With ``space`` ``"spherical"`` or ``"spatial"``.
    positions : mapping of str to array_like, shape (3,), optional
        Where to draw points, m, by name (as a spatial analysis places them); the others
        at the sketch.  Default: every point at the sketch.
    ax : matplotlib 3-D Axes, optional
        Default: a new figure's.
    units : Units or mapping, optional
        Lengths on the axes (default SI).

    Returns
    -------
    mpl_toolkits.mplot3d.axes3d.Axes3D

    Examples
    --------
    >>> import matplotlib; matplotlib.use("Agg")
    >>> ax = kl.plot.spatial_mechanism(kl.gallery.load("bennett").mechanism,
    ...                                units={"length": "mm", "angle": "deg"})
    >>> ax.get_xlabel(), ax.name
    ('x [mm]', '3d')
    """
    import matplotlib.pyplot as plt   # lazy: `import kinelab` must not need matplotlib

    if not isinstance(model, Mechanism) or model.space == "planar":
        got = "a planar one" if isinstance(model, Mechanism) else type(model).__name__
        raise ModelError(f"model: expected a spherical or spatial Mechanism, got {got}; draw "
                         f"planar models with kinelab.plot.mechanism")
    u = Units.resolve(units)
    at = {p.name: np.array([p.x, p.y, p.z]) for p in model.points}
    for name, xyz in (positions or {}).items():
        if name not in at:
            raise ModelError(f"positions: expected a point of the model, got {name!r}")
        at[name] = np.asarray(xyz, float)
    at = {n: u.convert(v, "m") for n, v in at.items()}
    if ax is None:
        ax = plt.figure(figsize=(6, 5), layout="constrained").add_subplot(projection="3d")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    moving = [link for link in model.links if not link.ground]
    for k, link in enumerate(moving):
        xyz = np.array([at[p] for p in link.points])
        if len(xyz) > 2:
            xyz = np.vstack([xyz, xyz[:1]])
        ax.plot(*xyz.T, "-o", color=colors[k % len(colors)], lw=2, ms=3, label=link.name)
    ground = np.array([at[p] for p in model.ground.points])
    ax.plot(*ground.T, "^", color="0.35", ms=9, ls="none")
    every = np.array(list(at.values()))
    centre, half = every.mean(axis=0), np.ptp(every, axis=0).max() / 2 or 1.0
    for set_lim, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        set_lim(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.set_zlabel(f"z [{u.length}]")
    return ax
