"""Animations drawn frame by frame from a kept copy of the figure: the frames are those of
drawing the whole figure each time, and the GIF holds them."""
import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

import kinelab as kl  # noqa: E402
from kinelab.plot import _animate  # noqa: E402


def _whole_figure_each_time(fig, ax, draw, n):
    """The frames as matplotlib's writers make them: the whole figure drawn for each."""
    for k in range(n):
        draw(k)
        fig.canvas.draw()
        yield np.asarray(fig.canvas.buffer_rgba())


def _frames_of(sol, monkeypatch, tmp_path, drawing=None, **options):
    """The frames (N, H, W, 4) that animate draws for the GIF (``drawing``: a stand-in for
    the way they are drawn)."""
    caught = []

    def catch(path, pixels, fps):
        caught.extend(f.copy() for f in pixels)
        Image.new("RGB", (1, 1)).save(path, format="GIF")

    with monkeypatch.context() as m:
        m.setattr(_animate, "_write_gif", catch)
        if drawing is not None:
            m.setattr(_animate, "_frames", drawing)
        kl.plot.animate(sol, tmp_path / "a.gif", **options)
    return np.stack(caught)


CASES = [
    (lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)), {}),
    (lambda: kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
     {"centers": True, "velocities": True}),
    (lambda: kl.mechanisms.slotted_link(crank=1.0, distance=2.0), {"velocities": True}),
    (lambda: kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5), {"trace": ["A", "B"]}),
]


@pytest.mark.parametrize("make, options", CASES, ids=["four-bar", "centres and velocities",
                                                     "slotted link", "offset slider-crank"])
def test_frames_are_those_of_drawing_the_whole_figure(make, options, monkeypatch, tmp_path):
    """Pixel for pixel, but where the legend, laid over as a layer drawn once, covers
    something: there within 2 of 255 in each colour channel."""
    sol = kl.analyze(make(), q=np.linspace(0, 2 * np.pi, 49), qd=3.0)
    fast = _frames_of(sol, monkeypatch, tmp_path, frames=30, **options)
    whole = _frames_of(sol, monkeypatch, tmp_path, _whole_figure_each_time, frames=30, **options)
    assert fast.shape == whole.shape and fast.shape[0] == 30 and fast.shape[2:] == (450, 4)
    assert fast.shape[1] > 450       # the drawing, 450 pixels square, and its legend below
    difference = np.abs(fast.astype(int) - whole.astype(int))
    assert difference.max() <= 2
    assert (difference.max(axis=3) > 0).mean() < 0.02       # the legend's box at most


def test_the_gif_holds_the_frames(monkeypatch, tmp_path):
    """One palette for the whole animation: the frames' own colours where they are
    common (white, the links' colours), the nearest of 256 elsewhere (edges)."""
    m = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    sol = kl.analyze(m, q=np.linspace(0, 2 * np.pi, 73), qd=3.0)
    drawn = _frames_of(sol, monkeypatch, tmp_path, frames=20)
    path = kl.plot.animate(sol, tmp_path / "b.gif", frames=20, fps=25)
    gif = Image.open(path)
    assert gif.n_frames == len(drawn) == 20 and gif.size == drawn.shape[2:0:-1]
    assert gif.info["loop"] == 0 and gif.info["duration"] == 40
    shown = []
    for k in range(gif.n_frames):
        gif.seek(k)
        shown.append(np.asarray(gif.convert("RGB"), int))
    difference = np.abs(np.stack(shown) - drawn[..., :3].astype(int)).max(axis=3)
    assert difference.mean() < 0.2
    assert np.percentile(difference, 99) <= 2
    white = (drawn[..., :3] == 255).all(axis=3)
    assert (difference[white] == 0).all()
