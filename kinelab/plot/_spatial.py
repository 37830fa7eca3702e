"""3-D figures of spherical and spatial mechanisms (matplotlib's mplot3d, imported inside the
functions): a spherical four-bar on its sphere, and any spherical or spatial model as the
links between its points."""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import AssemblyError, ModelError, describe
from kinelab.model import Mechanism, Units
from kinelab.spatial import SphericalFourBar

__all__ = ["spherical_fourbar", "spatial_mechanism"]

_LINKS = (("ground", "O2", "O4"), ("crank", "O2", "A"), ("coupler", "A", "B"),
          ("rocker", "B", "O4"))


def great_arc(u: np.ndarray, v: np.ndarray, n: int = 41) -> np.ndarray:
    """Points (n, 3) on the shorter great-circle arc from unit vector u to unit vector v."""
    angle = np.arctan2(np.linalg.norm(np.cross(u, v)), u @ v)
    t = np.linspace(0.0, 1.0, n)[:, None]
    if angle < 1e-12:
        return np.repeat(u[None, :], n, axis=0)
    return (np.sin((1.0 - t) * angle) * u + np.sin(t * angle) * v) / np.sin(angle)


def spherical_fourbar(fourbar: SphericalFourBar, theta2: float, *,
                      branch: str | None = None, ax=None, wireframe: bool = True):
    """Draw a spherical four-bar at one input angle: the unit sphere as a wireframe, the four
    joint axes from its centre, and each link as the great-circle arc between its two axes.

    Parameters
    ----------
    fourbar : kinelab.spatial.SphericalFourBar
    theta2 : float
        Input angle, rad.
    branch : {"open", "crossed"}, optional
        Default, the four-bar's own.
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        Drawn into a new figure without it.
    wireframe : bool
        Draw the sphere's meridians and parallels.

    Returns
    -------
    mpl_toolkits.mplot3d.Axes3D
        Its lines are labelled: the links by name (``"crank"`` ...), the axes ``"axis O2"`` ...

    Raises
    ------
    ModelError
        Anything but a SphericalFourBar, or a bad angle or branch.
    AssemblyError
        Where the loop cannot close at ``theta2``.
    """
    import matplotlib.pyplot as plt     # lazy: `import kinelab` must not need matplotlib
    if not isinstance(fourbar, SphericalFourBar):
        raise ModelError(f"fourbar: expected a kinelab.spatial.SphericalFourBar, got "
                         f"{describe(fourbar)}")
    if np.ndim(theta2) != 0:
        raise ModelError(f"theta2: expected one angle (rad), got shape {np.shape(theta2)}")
    sol = fourbar.analyze(theta2, branch=branch)
    if not sol.assembled:                  # pragma: no cover - analyze raises first
        raise AssemblyError("theta2: the loop cannot close")
    if ax is None:
        ax = plt.figure(figsize=(6, 6), layout="constrained").add_subplot(projection="3d")
    if wireframe:
        lon, lat = np.meshgrid(np.linspace(0, 2 * np.pi, 25), np.linspace(0, np.pi, 13))
        ax.plot_wireframe(np.cos(lon) * np.sin(lat), np.sin(lon) * np.sin(lat), np.cos(lat),
                          color="0.8", lw=0.5)
    u = {"O2": sol.u_O2, "A": sol.u_A, "B": sol.u_B, "O4": sol.u_O4}
    for name, axis in u.items():
        line = np.stack([-0.15 * axis, 1.25 * axis])
        fixed = name in ("O2", "O4")
        ax.plot(*line.T, color="0.3" if fixed else "0.55", ls="-" if fixed else "--", lw=1.2,
                label=f"axis {name}")
        ax.text(*(1.32 * axis), name)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, (link, a, b) in enumerate(_LINKS):
        arc = great_arc(u[a], u[b])
        ax.plot(*arc.T, lw=4 if link != "ground" else 2.5, label=link,
                color="0.35" if link == "ground" else colors[k % len(colors)])
    ax.scatter(*np.stack(list(u.values())).T, color="k", s=18, depthshade=False)
    ax.set_box_aspect((1, 1, 1))
    for set_lim in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        set_lim(-1.3, 1.3)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")
    ax.set_title(f"θ2 = {np.degrees(float(theta2)):.1f}°, {sol.branch}")
    return ax


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


def animate_spherical_fourbar(fourbar: SphericalFourBar, path, theta2: ArrayLike | None = None,
                              *, branch: str | None = None, frames: int = 48, fps: int = 20,
                              size: float = 4.0, dpi: int = 80):
    """Write an animation of a spherical four-bar moving over its input: the sphere, the
    fixed axes and the links' arcs, the path of B traced (GIF by Pillow, or MP4 with
    ffmpeg, as :func:`animate` writes them).

    Parameters
    ----------
    fourbar : kinelab.spatial.SphericalFourBar
    path : str or path-like
        ``.gif`` or ``.mp4``; written to a temporary file, then renamed.
    theta2 : array_like, shape (N,), optional
        Input angles, rad; at most ``frames`` of them, evenly spaced, are drawn.  Default:
        a full turn when the crank turns fully, else its first reachable interval there
        and back (just inside the limit positions).
    branch : {"open", "crossed"}, optional
        Default, the four-bar's own.
    frames, fps : int
        Frames drawn and frames per second.
    size, dpi : float, int
        Figure size (inches, square) and resolution: small and fast by default.

    Returns
    -------
    pathlib.Path

    Raises
    ------
    ModelError
        Anything but a SphericalFourBar, a bad argument or a suffix other than .gif and
        .mp4.
    AssemblyError
        An input angle where the loop cannot close.
    """
    import matplotlib
    import matplotlib.pyplot as plt
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from kinelab._files import atomic_path, file_path
    from kinelab.plot._animate import MAX_FRAMES, _write_gif
    from kinelab.solvers._arguments import whole

    if not isinstance(fourbar, SphericalFourBar):
        raise ModelError(f"fourbar: expected a kinelab.spatial.SphericalFourBar, got "
                         f"{describe(fourbar)}")
    path = file_path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ModelError(f"path: expected a name ending in .gif or .mp4, got {path.name!r}")
    frames = whole("frames", frames, 2, MAX_FRAMES)
    fps = whole("fps", fps, 1, 120)
    if theta2 is None:
        reach = fourbar.reachable_inputs()
        if not reach:
            raise AssemblyError("spherical four-bar: the loop closes at no input angle",
                                loop="O2-A-B-O4", reachable=[])
        lo, hi = reach[0]
        if (lo, hi) == (-np.pi, np.pi):
            theta2 = np.linspace(0.0, 2 * np.pi, frames, endpoint=False)
        else:
            pad = 1e-6 * (hi - lo)
            half = np.linspace(lo + pad, hi - pad, frames // 2 + 1)
            theta2 = np.concatenate([half, half[-2:0:-1]])
    theta2 = np.asarray(theta2, float)
    if theta2.ndim != 1 or theta2.size < 2:
        raise ModelError(f"theta2: expected input angles of shape (N,), N >= 2, got shape "
                         f"{theta2.shape}")
    idx = np.unique(np.round(np.linspace(0, theta2.size - 1, min(frames, theta2.size)))
                    .astype(int))
    sol = fourbar.analyze(theta2[idx], branch=branch)
    fig = matplotlib.figure.Figure(figsize=(size, size), dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_subplot(projection="3d")
    lon, lat = np.meshgrid(np.linspace(0, 2 * np.pi, 19), np.linspace(0, np.pi, 10))
    ax.plot_wireframe(np.cos(lon) * np.sin(lat), np.sin(lon) * np.sin(lat), np.cos(lat),
                      color="0.85", lw=0.4)
    for name, axis in (("O2", sol.u_O2[0]), ("O4", sol.u_O4[0])):
        ax.plot(*np.stack([-0.15 * axis, 1.25 * axis]).T, color="0.3", lw=1.0)
        ax.text(*(1.32 * axis), name)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    lines = {}
    for k, (link, _, _) in enumerate(_LINKS):
        (lines[link],) = ax.plot([], [], [], lw=3 if link != "ground" else 2, label=link,
                                 color="0.35" if link == "ground" else colors[k % len(colors)])
    (trace,) = ax.plot([], [], [], ":", color="0.4", lw=1, label="path of B")
    ax.set_box_aspect((1, 1, 1))
    for set_lim in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        set_lim(-1.1, 1.1)
    ax.set_axis_off()
    ax.legend(loc="lower left", fontsize="small")
    title = ax.set_title("")

    def draw(k):
        u = {"O2": sol.u_O2[k], "A": sol.u_A[k], "B": sol.u_B[k], "O4": sol.u_O4[k]}
        for link, a, b in _LINKS:
            arc = great_arc(u[a], u[b], 25)
            lines[link].set_data_3d(*arc.T)
        trace.set_data_3d(*sol.u_B[:k + 1].T)
        title.set_text(f"θ2 = {np.degrees(sol.theta2[k]):.0f}°")
        canvas.draw()
        return np.asarray(canvas.buffer_rgba())

    with atomic_path(path, suffix=suffix) as tmp:
        if suffix == ".gif":
            _write_gif(tmp, (draw(k) for k in range(len(idx))), fps)
        else:
            from matplotlib import animation
            writer = animation.FFMpegWriter(fps=fps)
            with writer.saving(fig, tmp, fig.dpi):
                for k in range(len(idx)):
                    draw(k)
                    writer.grab_frame()
    return path
