"""Figures and animations: files written and not empty, axes labelled with units."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from PIL import Image  # noqa: E402

import kinelab as kl  # noqa: E402
from kinelab.errors import ModelError  # noqa: E402


@pytest.fixture(scope="module")
def fb():
    m = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    return kl.analyze(m, q=np.linspace(0, 2 * np.pi, 73), qd=2.0)


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def test_curves_have_labelled_axes(fb):
    fig = kl.plot.curves(fb, ["coupler", "rocker"], degrees=True)
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["angle [deg]", "angular velocity [deg/s]", "angular acceleration [deg/s²]"]
    assert fig.axes[-1].get_xlabel() == "jO2 [deg]"
    line = fig.axes[0].lines[1]          # the rocker, unwrapped, in degrees
    np.testing.assert_allclose(line.get_ydata(), np.degrees(np.unwrap(fb.angle("rocker"))),
                               rtol=0, atol=1e-12)


def test_curves_of_slides_and_links_side_by_side():
    sc = kl.mechanisms.slider_crank(1.0, 3.0)
    sol = kl.analyze(sc, q=np.linspace(0, 2 * np.pi, 37), qd=1.0)
    fig = kl.plot.curves(sol, ["rod", "slide"])
    assert [ax.get_ylabel() for ax in fig.axes] == [
        "rod angle [rad]", "slide [m]", "rod angular velocity [rad/s]", "slide velocity [m/s]",
        "rod angular acceleration [rad/s²]", "slide acceleration [m/s²]"]


def test_coefficients_and_transmission(fb):
    fig = kl.plot.coefficients(fb, ["rocker"])
    assert [ax.get_ylabel() for ax in fig.axes] == ["K = dS/dq [rad/rad]", "L = dK/dq [rad/rad²]"]
    np.testing.assert_allclose(fig.axes[0].lines[0].get_ydata(), fb.K("rocker"), rtol=0, atol=0)
    ax = kl.plot.transmission(fb)
    assert ax.get_ylabel() == "transmission angle [deg]"
    mu = ax.lines[0].get_ydata()
    assert 0 < mu.min() and mu.max() <= 90


def test_coupler_curve_draws_path_and_mechanism(fb):
    ax = kl.plot.coupler_curve(fb, "P")
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [m]", "y [m]")
    path = [ln for ln in ax.lines if ln.get_label() == "path of P"][0]
    np.testing.assert_array_equal(path.get_xydata(), fb.position("P"))
    assert {"crank", "coupler", "rocker"} <= {ln.get_label() for ln in ax.lines}


def test_multi_input_plots_against_the_first_input():
    mf = kl.io.ModelFile.read("examples/fivebar.toml")
    sol = kl.analyze(mf.mechanism, *mf.sample_inputs(19))
    fig = kl.plot.curves(sol, ["coupler1"])
    assert fig.axes[-1].get_xlabel() == "jO2 [rad]"


@pytest.mark.parametrize("suffix", ["png", "svg"])
def test_save_writes_a_file(fb, tmp_path, suffix):
    path = kl.plot.save(kl.plot.curves(fb), tmp_path / f"f.{suffix}")
    assert path.stat().st_size > 1000
    if suffix == "png":
        assert Image.open(path).size[0] > 500
    else:
        assert path.read_text().lstrip().startswith("<?xml")
    assert [p.name for p in tmp_path.iterdir()] == [f"f.{suffix}"]


def test_animate_writes_a_gif_with_the_frames(fb, tmp_path):
    path = kl.plot.animate(fb, tmp_path / "fb.gif", frames=10, fps=10)
    im = Image.open(path)
    assert im.n_frames == 10
    assert [p.name for p in tmp_path.iterdir()] == ["fb.gif"]


def test_animate_refuses_what_it_cannot_write(fb, tmp_path):
    with pytest.raises(ModelError, match=r"path: expected a \.gif or \.mp4 file name, got 'fb\.avi'"):
        kl.plot.animate(fb, tmp_path / "fb.avi")
    with pytest.raises(ModelError, match="an animation needs a sweep"):
        kl.plot.animate(kl.analyze(kl.mechanisms.slider_crank(1.0, 3.0), q=0.5), tmp_path / "x.gif")
    with pytest.raises(ModelError, match="outputs: expected links, slides or points"):
        kl.plot.curves(fb, ["nope"])


MM_DEG = {"length": "mm", "angle": "deg"}


def visible_ticks(axis):
    lo, hi = sorted(axis.get_view_interval())
    return [float(t) for t in axis.get_ticklocs() if lo - 1e-9 <= t <= hi + 1e-9]


def test_curves_in_mm_and_degrees():
    sc = kl.mechanisms.slider_crank(0.1, 0.3)
    sol = kl.analyze(sc, q=np.linspace(0, 2 * np.pi, 37), qd=2.0)
    fig = kl.plot.curves(sol, ["rod", "slide"], units=MM_DEG)
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["rod angle [deg]", "slide [mm]", "rod angular velocity [deg/s]",
                      "slide velocity [mm/s]", "rod angular acceleration [deg/s²]",
                      "slide acceleration [mm/s²]"]
    assert [ax.get_xlabel() for ax in fig.axes[-2:]] == ["jO2 [deg]", "jO2 [deg]"]
    # the data themselves are in mm and deg: the SI values times the exact factors
    np.testing.assert_allclose(fig.axes[0].lines[0].get_xdata(), np.linspace(0, 360, 37), rtol=1e-15)
    np.testing.assert_allclose(fig.axes[1].lines[0].get_ydata(), sol.slide("slide") * 1000, rtol=1e-15)
    np.testing.assert_allclose(fig.axes[3].lines[0].get_ydata(),
                               sol.slide_velocity("slide") * 1000, rtol=1e-15)
    np.testing.assert_allclose(fig.axes[4].lines[0].get_ydata(), np.degrees(sol.alpha("rod")),
                               rtol=1e-15)
    # a full turn in degrees: ticks at 0, 90, 180, 270, 360
    assert visible_ticks(fig.axes[-1].xaxis) == [0.0, 90.0, 180.0, 270.0, 360.0]
    fig = kl.plot.coefficients(sol, ["rod", "slide"], units=MM_DEG)
    assert [ax.get_ylabel() for ax in fig.axes] == ["K = dS/dq [deg/deg | mm/deg]",
                                                    "L = dK/dq [deg/deg² | mm/deg²]"]
    K_slide = [ln for ln in fig.axes[0].lines if ln.get_label() == "slide"][0].get_ydata()
    np.testing.assert_allclose(K_slide, sol.K("slide") * 1000 * np.pi / 180, rtol=1e-15)
    ax = kl.plot.coupler_curve(sol, "B", units=MM_DEG)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [mm]", "y [mm]")
    path = [ln for ln in ax.lines if ln.get_label() == "path of B"][0]
    np.testing.assert_allclose(path.get_xydata(), sol.position("B") * 1000, rtol=1e-15)


def test_singular_samples_are_gaps_and_marked():
    # crank = rod: det J = 0 at q = 90 and 270 deg (samples 18 and 54)
    sol = kl.analyze(kl.mechanisms.slider_crank(1.0, 1.0), q=np.linspace(0, 2 * np.pi, 73),
                     qd=1.0, at_singular="flag")
    singular = np.flatnonzero(sol.singular)
    assert singular.tolist() == [18, 54]
    fig = kl.plot.curves(sol, ["rod"], degrees=True)
    def curve(ax, label):
        return np.asarray([ln for ln in ax.lines if ln.get_label() == label][0].get_ydata())

    for ax in fig.axes:
        y = curve(ax, "rod")
        assert np.isnan(y[singular]).all() and np.isfinite(y[[17, 19, 53, 55]]).all()
        vertical = [ln for ln in ax.lines if ln.get_label() != "rod"]
        assert sorted(float(ln.get_xdata()[0]) for ln in vertical) == pytest.approx([90.0, 270.0],
                                                                                    abs=1e-12)
        assert all(np.ptp(ln.get_xdata()) == 0 for ln in vertical)
    legend = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert legend == ["rod", "singular (det J = 0)"]
    # positions too: the angle is defined there, but a figure shows no value at a singular sample
    assert np.isfinite(sol.angle("rod")[singular]).all()
    fig = kl.plot.coefficients(sol, ["rod"])
    assert np.isnan(curve(fig.axes[0], "rod")[singular]).all()
    ax = kl.plot.transmission(sol)
    assert np.isnan(curve(ax, "rod-slider")[singular]).all()
    ax = kl.plot.coupler_curve(sol, "B")
    path = [ln for ln in ax.lines if ln.get_label() == "path of B"][0]
    assert np.isnan(path.get_xydata()[singular]).all()
    marked = [ln for ln in ax.lines if ln.get_label() == "singular (det J = 0)"][0]
    np.testing.assert_array_equal(marked.get_xydata(), sol.position("B")[singular])


def test_plot_and_animate_commands(tmp_path):
    from click.testing import CliRunner
    from kinelab.cli import main
    r = CliRunner().invoke(main, ["plot", "examples/crank_rocker.toml", "--out", str(tmp_path),
                                  "--samples", "37", "--degrees"])
    assert r.exit_code == 0, r.output
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == sorted(f"crank_rocker_{k}.{s}" for k in ("motion", "coefficients", "path_P",
                                                             "transmission") for s in ("png", "svg"))
    assert all((tmp_path / n).stat().st_size > 1000 for n in names)
    r = CliRunner().invoke(main, ["animate", "examples/crank_rocker.toml", "--out", str(tmp_path),
                                  "--samples", "13", "--frames", "6", "--format", "gif"])
    assert r.exit_code == 0, r.output
    assert Image.open(tmp_path / "crank_rocker.gif").n_frames == 6


def test_plot_command_refuses_unknown_outputs(tmp_path):
    from click.testing import CliRunner
    from kinelab.cli import main
    r = CliRunner().invoke(main, ["plot", "examples/crank_rocker.toml", "--out", str(tmp_path),
                                  "--samples", "9", "--outputs", "rocker,nope"])
    assert r.exit_code == 2
    assert r.stderr.startswith("kinelab: error: --outputs: expected links, slides or points of "
                               "'crank-rocker', got 'nope'; they are 'ground', 'crank'")
    assert list(tmp_path.iterdir()) == []


def _circle_positions(n):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([2 * np.cos(t), np.sin(t)]), 0.3 * t


def test_poles_of_many_positions_are_one_artist_and_unnamed():
    """n positions have n (n - 1) / 2 poles: one artist for their marks, so that a figure
    of hundreds of positions takes a second, not minutes."""
    points, angles = _circle_positions(300)
    ax = kl.plot.prescribed_positions(points, angles)
    poles = kl.synthesis.poles(kl.synthesis.Positions(points, angles))
    marks = [line for line in ax.lines if line.get_marker() == "x"]
    assert len(marks) == 1 and len(marks[0].get_xdata()) == int(poles.finite.sum()) > 40_000
    assert not any(t.get_text().startswith("P") for t in ax.texts)
    assert len(ax.lines) == 301


def test_poles_of_few_positions_are_named():
    points, angles = _circle_positions(4)
    ax = kl.plot.prescribed_positions(points, angles)
    names = sorted(t.get_text() for t in ax.texts if t.get_text().startswith("P"))
    assert names == ["P12", "P13", "P14", "P23", "P24", "P34"]
    marks = [line for line in ax.lines if line.get_marker() == "x"]
    assert len(marks) == 1 and len(marks[0].get_xdata()) == 6


# names that mathtext would read as commands ($...$, a backslash, a brace): a figure shows
# them as the file writes them
MATH_NAMES = {"crank-rocker": "$m$ {", "P": "a$b", "coupler": "$x$", "B": "\\frac{",
              "crank angle": "$\\alpha{$"}


def _renamed(data, names):
    if isinstance(data, dict):
        return {names.get(k, k): _renamed(v, names) for k, v in data.items()}
    if isinstance(data, list):
        return [_renamed(v, names) for v in data]
    return names.get(data, data) if isinstance(data, str) else data


def _shown(text):
    """A text as matplotlib shows it, None when it would read it as mathtext."""
    from matplotlib import cbook
    return None if cbook.is_math_text(text) else text.replace(r"\$", "$")


def test_names_that_mathtext_would_read_are_drawn_as_they_are():
    import tomllib
    from matplotlib.text import Text
    from kinelab.io import ModelFile
    data = tomllib.loads(open("examples/crank_rocker.toml").read())
    mf = ModelFile.from_dict(_renamed(data, MATH_NAMES))
    sol = mf.analyze(19)
    one = kl.analyze(mf.mechanism, q=np.radians(30.0), qd=1.0)
    figures = [kl.plot.curves(sol, ["$x$", "rocker"]), kl.plot.coefficients(sol, ["$x$"]),
               kl.plot.coupler_curve(sol, "a$b").figure, kl.plot.transmission(sol).figure,
               kl.plot.velocity_polygon(one), kl.plot.acceleration_polygon(one),
               kl.plot.instant_centers(one), kl.plot.centrodes(sol, "$x$", 3).figure]
    for fig in figures:
        fig.canvas.draw()                       # mathtext would fail here
        shown = [_shown(t.get_text()) for t in fig.findobj(Text)]
        assert any(s and "$m$ {" in s for s in shown), shown          # in the title
    assert _shown(figures[2].axes[0].get_title()) == "$m$ {: path of a$b"
    legend = [_shown(t.get_text()) for t in figures[2].axes[0].get_legend().get_texts()]
    assert "$x$" in legend and "path of a$b" in legend
    assert _shown(figures[0].axes[-1].get_xlabel()) == "$\\alpha{$ [rad]"
    assert "\\frac{" in [_shown(t.get_text()) for t in figures[4].axes[0].texts]


def test_spatial_mechanism_draws_each_moving_link_at_the_given_places():
    m = kl.gallery.load("sarrus").mechanism
    ax = kl.plot.spatial_mechanism(m, {"T": [0.0, 0.0, 0.07]}, units={"length": "mm", "angle": "deg"})
    lines = {line.get_label(): line for line in ax.get_lines()}
    assert {link.name for link in m.links if not link.ground} <= set(lines)
    x, y, z = lines["plate"].get_data_3d()
    assert len(z) == 4 and 70.0 in np.round(z, 9)          # A3, B3, T (moved) and back, mm
    assert ax.get_zlabel() == "z [mm]"


def test_spatial_mechanism_refuses_a_planar_model_and_unknown_points():
    with pytest.raises(ModelError, match=r"expected a spherical or spatial Mechanism, got a "
                                         r"planar one; draw planar models with"):
        kl.plot.spatial_mechanism(kl.gallery.load("hoeken").mechanism)
    with pytest.raises(ModelError, match=r"positions: expected a point of the model, got 'Z'"):
        kl.plot.spatial_mechanism(kl.gallery.load("sarrus").mechanism, {"Z": [0, 0, 0]})
