"""Animations of a sweep: the mechanism moving, with its points' paths traced."""
from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from kinelab import _progress as progress
from kinelab.errors import ModelError, describe, expected_one_of, shown
from kinelab._files import atomic_path, file_path
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._solution import takes_solution
from kinelab.solvers._arguments import flag, whole
from kinelab.model import Units
from kinelab.plot._figures import SINGULAR_LABEL, _regular, _singular_samples, mechanism

__all__ = ["animate", "can_write_mp4"]

MAX_FRAMES = 100_000     # an hour at 30 frames a second


def can_write_mp4() -> bool:
    """Whether matplotlib finds ffmpeg, which MP4 needs."""
    from matplotlib import animation
    return animation.writers.is_available("ffmpeg")


@takes_solution
def animate(sol: KinematicSolution, path: str | os.PathLike, *, trace=None, frames: int = 120,
            fps: int = 30, units: Units | Mapping[str, str] | None = None,
            centers: bool = False, velocities: bool = False) -> Path:
    """Write an animation of the mechanism moving through the sweep, the paths of the
    ``trace`` points drawn as they go.

    Parameters
    ----------
    sol : KinematicSolution
        A sweep; at most ``frames`` of its samples are shown, evenly spaced.
    path : str or path-like
        ``.gif`` (Pillow) or ``.mp4`` (needs ffmpeg); written to a temporary file, then renamed.
    trace : list of str, optional
        Points whose paths are traced (default: the points carried by one moving link only,
        such as coupler points; else every moving point).
    frames, fps : int
    units : Units or mapping, optional
        ``{"length": "mm"}``: the unit of the axes (default SI).  Traced paths leave out the
        singular samples, which are marked.
    centers : bool
        Overlay every instant centre (Kennedy's construction), labelled as the notes do
        (O13); centres at infinity and far off the view are left out of a frame.
    velocities : bool
        Overlay each moving point's velocity as an arrow, at one scale for the whole
        animation (stated in the legend).

    Returns
    -------
    Path

    Examples
    --------
    >>> import tempfile, pathlib
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> sol = kl.analyze(fb, q=np.linspace(0, 2 * np.pi, 25))
    >>> path = kl.plot.animate(sol, pathlib.Path(tempfile.mkdtemp()) / "fb.gif", frames=12)
    >>> path.stat().st_size > 0
    True
    >>> path = kl.plot.animate(sol, pathlib.Path(tempfile.mkdtemp()) / "fb.gif", frames=4,
    ...                        centers=True, velocities=True)
    >>> path.stat().st_size > 0
    True
    """
    import matplotlib.pyplot as plt
    from matplotlib import animation

    path = file_path(path)
    suffix = path.suffix.lower()
    if suffix not in (".gif", ".mp4"):
        raise ModelError(f"path: expected a .gif or .mp4 file name, got {shown(path.name)}")
    if suffix == ".mp4" and not can_write_mp4():
        raise ModelError("path: MP4 needs ffmpeg, which is not installed; write a .gif instead")
    if sol.single or sol.N < 2:
        raise ModelError("sol: an animation needs a sweep of at least two samples")
    frames, fps = whole("frames", frames, 1, MAX_FRAMES), whole("fps", fps, 1, 1000)
    centers, velocities = flag("centers", centers), flag("velocities", velocities)
    if isinstance(trace, str):
        trace = [trace]         # one point
    if trace is not None:
        if not isinstance(trace, (list, tuple)):
            raise ModelError(f"trace: expected names of points, got {describe(trace)}")
        for name in trace:
            if name not in sol.point_item:
                raise ModelError(f"trace: {expected_one_of(name, sol.point_names)}")
    m = sol.mechanism
    if trace is None:
        from kinelab.io import default_outputs
        trace = [n for n in default_outputs(m) if n in sol.point_item]
        if not trace:
            ground = set(m.ground.points)
            trace = [p for p in sol.point_names if p not in ground][-1:]
    u = Units.resolve(units)
    idx = np.unique(np.linspace(0, sol.N - 1, min(frames, sol.N)).round().astype(int))

    def position(p):
        return u.convert(sol.position(p), "m")
    all_xy = np.concatenate([position(p) for p in sol.point_names])
    all_xy = all_xy[np.isfinite(all_xy).all(axis=1)]
    if not len(all_xy):
        raise ModelError("sol: the mechanism assembles at none of the samples: nothing to "
                         "animate; analyze a range where it does")
    lo, hi = all_xy.min(axis=0), all_xy.max(axis=0)
    pad = 0.08 * max(hi - lo) + 1e-9
    fig = plt.figure(figsize=(5, 5), dpi=90)
    ax = fig.add_axes((0.17, 0.1, 0.8, 0.82))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.grid(True, alpha=0.3)
    ax.set_title(sol.mechanism.name)
    paths = {p: _regular(sol, position(p)) for p in trace}
    for p, xy in paths.items():
        ax.plot(xy[:, 0], xy[:, 1], lw=0.8, color="0.75", zorder=1)
    traced = {p: ax.plot([], [], lw=1.6, color="black", zorder=1, label=f"path of {p}")[0]
              for p in paths}
    singular = _singular_samples(sol)
    for k, p in enumerate(trace if singular else ()):
        ax.plot(*position(p)[singular].T, "x", color="tab:red", ms=7, zorder=2,
                label=SINGULAR_LABEL if k == 0 else None)
    artists: dict = {}
    mechanism(sol, int(idx[0]), ax=ax, artists=artists, units=u)
    overlays = []
    if centers:
        overlays.append(_centre_overlay(ax, sol, u, (lo - pad, hi + pad)))
    if velocities:
        overlays.append(_velocity_overlay(ax, sol, u, float(max(hi - lo))))
    for overlay in overlays:
        overlay(int(idx[0]))
    if traced or singular or velocities:
        ax.legend(fontsize="small", loc="upper right")
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)

    def draw(k):
        i = int(idx[k])
        mechanism(sol, i, ax=ax, artists=artists, units=u)
        for p, line in traced.items():
            line.set_data(paths[p][:i + 1, 0], paths[p][:i + 1, 1])
        moved = [a for overlay in overlays for a in overlay(i)]
        return list(artists.values()) + list(traced.values()) + moved

    writer = (animation.PillowWriter(fps=fps) if suffix == ".gif"
              else animation.FFMpegWriter(fps=fps))
    try:
        with atomic_path(path, suffix=suffix) as tmp:     # the writer goes by the suffix
            anim = animation.FuncAnimation(fig, draw, frames=len(idx), blit=False)
            anim.save(tmp, writer=writer, progress_callback=lambda k, n: progress.report(
                f"frame {k + 1} of {n}", k / n))
    finally:
        plt.close(fig)
    return path


def _centre_overlay(ax, sol: KinematicSolution, u: Units, view):
    """A function of the sample that moves a marker and a label to each finite instant
    centre inside ``view`` ((lo, hi) corners), and hides the others."""
    from kinelab.kinematics import kennedy_construction
    kc = kennedy_construction(sol)
    lo, hi = view
    marks, labels = {}, {}
    for pair in kc.centers:
        primary = pair in kc.primary
        marks[pair] = ax.plot([], [], "o", ms=5, color="tab:red", zorder=6,
                              mfc="tab:red" if primary else "white")[0]
        labels[pair] = ax.text(0, 0, kc.label(pair), fontsize=7, color="tab:red", zorder=6,
                               visible=False)

    def place(i):
        for pair, c in kc.centers.items():
            xy = np.asarray(u.convert(c.position[i], "m"), float)
            show = (not bool(c.at_infinity[i]) and bool(np.isfinite(xy).all())
                    and bool(np.all((xy >= lo) & (xy <= hi))))
            marks[pair].set_data([xy[0]] if show else [], [xy[1]] if show else [])
            labels[pair].set_visible(show)
            if show:
                labels[pair].set_position(xy)
        return [*marks.values(), *labels.values()]
    return place


def _velocity_overlay(ax, sol: KinematicSolution, u: Units, span: float):
    """A function of the sample that sets a velocity arrow on each moving point, at one
    scale: the fastest point's arrow is a quarter of the view."""
    ground = set(sol.mechanism.ground.points)
    points = [p for p in sol.point_names if p not in ground]
    xy = np.stack([u.convert(sol.position(p), "m") for p in points], axis=1)      # (N, k, 2)
    v = np.stack([u.convert(sol.velocity(p), "m/s") for p in points], axis=1)
    v = np.where(np.isfinite(v), v, 0.0)
    fastest = float(np.max(np.linalg.norm(v, axis=2))) or 1.0
    seconds = 0.25 * span / fastest          # an arrow's length is the velocity times this
    arrows = ax.quiver(xy[0, :, 0], xy[0, :, 1], v[0, :, 0], v[0, :, 1], angles="xy",
                       scale_units="xy", scale=1.0 / seconds, color="tab:blue", width=0.006,
                       zorder=5, label=f"velocities: 1 {u.length} = {1 / seconds:.3g} "
                                       f"{u.unit('m/s')}")

    def place(i):
        arrows.set_offsets(np.where(np.isfinite(xy[i]), xy[i], 0.0))
        arrows.set_UVC(v[i, :, 0], v[i, :, 1])
        return [arrows]
    return place
