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
from kinelab.plot._figures import SINGULAR_LABEL, _regular, _singular_samples, mechanism, plain
from kinelab.plot._words import checked_language, decimal_commas, number, words

__all__ = ["animate", "can_write_mp4"]

MAX_FRAMES = 100_000     # an hour at 30 frames a second


def can_write_mp4() -> bool:
    """Whether matplotlib finds ffmpeg, which MP4 needs."""
    from matplotlib import animation
    return animation.writers.is_available("ffmpeg")


@takes_solution
def animate(sol: KinematicSolution, path: str | os.PathLike, *, trace=None, frames: int = 120,
            fps: int = 30, units: Units | Mapping[str, str] | None = None,
            centers: bool = False, velocities: bool = False, lang: str = "en") -> Path:
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
    lang : str
        Language of the legend, ``"en"`` or ``"pt"`` (decimal commas).  The legend is
        below the drawing, where it covers nothing.

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
    w = words(checked_language(lang))
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
    ax.set_title(plain(sol.mechanism.name))
    paths = {p: _regular(sol, position(p)) for p in trace}
    for p, xy in paths.items():
        ax.plot(xy[:, 0], xy[:, 1], lw=0.8, color="0.75", zorder=1)
    traced = {p: ax.plot([], [], lw=1.6, color="black", zorder=1, label=plain(w["path of"].format(point=p)))[0]
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
        overlays.append(_velocity_overlay(ax, sol, u, float(max(hi - lo)), lang))
    for overlay in overlays:
        overlay(int(idx[0]))
    if traced or singular or velocities:
        _legend_below(fig, ax)
    decimal_commas(fig, lang)
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

    try:
        with atomic_path(path, suffix=suffix) as tmp:     # the writer goes by the suffix
            if suffix == ".gif":
                _write_gif(tmp, _reported(_frames(fig, ax, draw, len(idx)), len(idx)), fps)
            else:
                writer = animation.FFMpegWriter(fps=fps)
                with writer.saving(fig, tmp, fig.dpi):
                    for k in range(len(idx)):
                        draw(k)
                        writer.grab_frame()
                        progress.report(f"frame {k + 1} of {len(idx)}", (k + 1) / len(idx))
    finally:
        plt.close(fig)
    return path


def _legend_below(fig, ax) -> None:
    """The legend below the drawing, where it covers nothing: the figure grows by the
    legend's rows, the drawing keeps its size (5 inches square, with its axes' labels)."""
    entries = len(ax.get_legend_handles_labels()[1])
    columns = 2 if entries <= 8 else 3
    rows = -(-entries // columns)
    below = 0.2 * rows + 0.25              # inches
    height = 5.0 + below
    fig.set_size_inches(5.0, height)
    ax.set_position((0.17, (below + 0.5) / height, 0.8, 4.1 / height))
    ax.legend(fontsize="small", loc="upper center", ncols=columns,
              bbox_to_anchor=(0.5, (below + 0.05) / height), bbox_transform=fig.transFigure)


def _reported(frames, n: int):
    """The frames, each reported as done (to whoever watches this thread's work)."""
    for k, frame in enumerate(frames):
        progress.report(f"frame {k + 1} of {n}", k / n)
        yield frame


def _frames(fig, ax, draw, n: int):
    """The pixels (H, W, 4) of each of the ``n`` frames, ``draw(k)`` moving the artists of
    frame k and returning them: the same pixels as drawing the whole figure each time, for a
    fraction of the work.

    The figure is drawn once without the moving artists, and kept.  Each frame starts from
    that copy and draws, in matplotlib's order (by z-order, then as the axes hold them), the
    moving artists and the fixed ones that must go over them: a fixed artist (a path, a
    marker, the legend, a grid line) is drawn again each frame when, in some frame, an
    artist drawn before it there may cover some of its pixels; otherwise it is in the copy.
    The ticks, their labels and the title are in the copy: nothing moving reaches them.
    The frames are those of drawing the whole figure each time, pixel for pixel, but where
    the legend goes over something moving: there it is laid over as a layer drawn once,
    within two units (of 255) of each colour channel of drawing it again."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
    canvas.draw()                       # lays out the legend and places the ticks
    renderer = canvas.get_renderer()
    moving = draw(0)
    lowest = min(a.get_zorder() for a in moving)
    children = ax.get_children()
    rank = {id(a): (a.get_zorder(), k) for k, a in enumerate(children)}
    for axis in (ax.xaxis, ax.yaxis):   # grid lines are drawn with their axis
        rank.update({id(g): rank[id(axis)] for g in axis.get_gridlines()})
    grid = [g for axis in (ax.xaxis, ax.yaxis) for g in axis.get_gridlines() if g.get_visible()]
    fixed = [a for a in (*ax.lines, *ax.collections, *ax.patches, *ax.texts, ax.get_legend(),
                         *grid, *ax.spines.values())
             if a is not None and a not in moving and a.get_visible()
             and rank.get(id(a), (a.get_zorder(),))[0] >= lowest]
    layers = sorted({id(a): a for a in (*moving, *fixed)}.values(),
                    key=lambda a: rank.get(id(a), (a.get_zorder(), len(children))))
    # the pixels each artist may draw on in each frame (fixed ones: the same in all)
    still = {id(a): _extent(a, renderer) for a in fixed}
    reach = []
    for k in range(n):
        draw(k)
        reach.append({**still, **{id(a): _extent(a, renderer) for a in moving}})
    again = []                          # drawn in every frame, in order
    for a in layers:
        if id(a) in still and not any(_may_overlap(still[id(a)], boxes[id(b)])
                                      for boxes in reach for b in again):
            continue                    # in the copy
        again.append(a)
    # the legend lays itself out again on each draw, which takes longer than all the rest
    # of a frame: drawn once alone, on a transparent layer, it is laid over each frame
    legend = ax.get_legend()
    layer = _layer(canvas, legend) if legend in again else None
    hidden = [(a, a.get_visible()) for a in again]
    for a in again:
        a.set_animated(True)            # left out of the copy (grid lines: hidden)
        if a in grid:
            a.set_visible(False)
    canvas.draw()
    background = canvas.copy_from_bbox(fig.bbox)
    for a, visible in hidden:
        a.set_visible(visible)
    for k in range(n):
        draw(k)
        canvas.restore_region(background)
        for a in again:
            if a is legend:
                _lay_over(np.asarray(canvas.buffer_rgba()), *layer)
            else:
                a.draw(renderer)
        yield np.asarray(canvas.buffer_rgba())


def _layer(canvas, artist):
    """The artist drawn alone on a transparent canvas: the rows and columns of the canvas's
    pixels it covers, and its pixels there (RGB, and alpha from 0 to 1)."""
    renderer = canvas.get_renderer()
    height, width = renderer.height, renderer.width
    (x0, y0), (x1, y1) = artist.get_window_extent(renderer).padded(2).get_points()
    rows = slice(max(0, int(np.floor(height - y1))), min(height, int(np.ceil(height - y0))))
    cols = slice(max(0, int(np.floor(x0))), min(width, int(np.ceil(x1))))
    renderer.clear()
    artist.draw(renderer)
    pixels = np.asarray(canvas.buffer_rgba())[rows, cols].astype(float)
    return rows, cols, pixels[..., :3], pixels[..., 3:] / 255.0


def _lay_over(frame: np.ndarray, rows: slice, cols: slice, rgb: np.ndarray, alpha: np.ndarray):
    """Lay a layer from :func:`_layer` over the frame's pixels (H, W, 4), in place."""
    under = frame[rows, cols, :3]
    under[...] = np.rint(under + (rgb - under) * alpha)


def _extent(artist, renderer):
    """The box of display pixels the artist may draw on, with a margin for line widths and
    antialiasing; "empty" when it draws nothing; None when not known."""
    if not artist.get_visible():
        return "empty"
    from matplotlib.legend import Legend
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    from matplotlib.text import Text

    dpi = artist.get_figure(root=True).dpi
    if isinstance(artist, Line2D):
        margin = (artist.get_linewidth() + artist.get_markeredgewidth()) * dpi / 72 + 2
    elif isinstance(artist, Patch):
        margin = artist.get_linewidth() * dpi / 72 + 2
    elif isinstance(artist, (Text, Legend)):
        margin = 2
    else:
        return None
    box = artist.get_window_extent(renderer)
    points = box.get_points()
    if np.isnan(points).any():
        return None
    if not (points[1] >= points[0]).all():
        return "empty"                  # no data (a path not begun)
    return box.padded(margin)


def _may_overlap(a, b) -> bool:
    if a == "empty" or b == "empty":
        return False
    if a is None or b is None:
        return True
    return bool(a.overlaps(b))


def _write_gif(path, frames, fps: int) -> None:
    """A looping GIF of the frames (H, W, 4), each shown 1/fps s.

    GIF has 256 colours a frame.  The palette is one for the whole animation, the median cut
    (Pillow's) of a sample of its frames, and each pixel takes the nearest colour in it:
    about as close to the frames as a palette cut for each frame (matplotlib's Pillow
    writer), in a third of the time, and with no colour that changes from frame to frame.
    Frames with transparency are written as matplotlib's writer writes them."""
    from PIL import Image

    frames = [f.copy() for f in frames]     # the canvas reuses its buffer
    if any(f[..., 3].min() < 255 for f in frames):      # as matplotlib's Pillow writer
        images = [Image.fromarray(f, "RGBA") if f[..., 3].min() < 255
                  else Image.fromarray(f[..., :3].copy(), "RGB") for f in frames]
    else:
        colours = [f.view("<u4")[..., 0] & 0xFFFFFF for f in frames]      # 0xBBGGRR
        sample = np.concatenate([c[::2] for c in colours[::max(1, len(colours) // 8)]])
        cut = Image.fromarray(_rgb(sample).astype(np.uint8)).quantize(256)
        palette = np.array(cut.getpalette()[:768], np.int64).reshape(-1, 3)
        nearest = _nearest(colours, palette)
        flat = palette.astype(np.uint8).ravel().tolist()
        images = []
        for c in colours:
            im = Image.fromarray(nearest[c], "P")
            im.putpalette(flat)
            images.append(im)
    images[0].save(path, format="GIF", save_all=True, append_images=images[1:],
                   duration=int(1000 / fps), loop=0)


def _rgb(colours: np.ndarray) -> np.ndarray:
    """0xBBGGRR values (...) as (..., 3) integers, red first."""
    return np.stack([colours & 255, (colours >> 8) & 255, (colours >> 16) & 255],
                    axis=-1).astype(np.int64)


def _nearest(colours: list[np.ndarray], palette: np.ndarray) -> np.ndarray:
    """A table of every 0xBBGGRR value to the index of its nearest palette colour (exact
    for the colours of ``colours``; 0 for the others)."""
    seen = np.zeros(1 << 24, bool)
    for c in colours:
        seen[c.ravel()] = True
    present = np.flatnonzero(seen)
    rgb = _rgb(present)
    table = np.zeros(1 << 24, np.uint8)
    for lo in range(0, len(present), 4096):
        d = ((rgb[lo:lo + 4096, None, :] - palette[None, :, :]) ** 2).sum(axis=2)
        table[present[lo:lo + 4096]] = d.argmin(axis=1)
    return table


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


def _velocity_overlay(ax, sol: KinematicSolution, u: Units, span: float, lang: str = "en"):
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
                       zorder=5, label=words(lang)["velocities legend"].format(
                           length=u.length, scale=number(1 / seconds, ".3g", lang),
                           unit=u.unit("m/s")))

    def place(i):
        arrows.set_offsets(np.where(np.isfinite(xy[i]), xy[i], 0.0))
        arrows.set_UVC(v[i, :, 0], v[i, :, 1])
        return [arrows]
    return place
