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
                               "crank-rocker, got 'nope'; they are 'ground', 'crank'")
    assert list(tmp_path.iterdir()) == []
