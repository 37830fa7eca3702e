"""Synthesis figures: drawn off screen (Agg) and written to files."""
import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import kinelab as kl  # noqa: E402
from kinelab import plot  # noqa: E402

P7 = np.array([(0, 0), (5, 8), (10, 15), (18, 20)]) * 0.01
POS7 = kl.synthesis.Positions(P7, [10, 20, 30], degrees=True)


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def _written(ax, path):
    ax.figure.savefig(path)
    assert path.stat().st_size > 5000          # a real picture, not an empty canvas
    return path


def test_positions_and_poles(tmp_path):
    ax = plot.prescribed_positions(POS7)
    # one marker per position, and the poles (six of them, all finite here) as one set
    positions = [line for line in ax.lines if line.get_marker() == "o"]
    poles = [line for line in ax.lines if line.get_marker() == "x"]
    assert len(positions) == 4 and [len(line.get_xdata()) for line in poles] == [6]
    _written(ax, tmp_path / "positions.png")


def test_solution_in_each_position(tmp_path):
    sols = kl.synthesis.four_positions(POS7, None, -0.20195, -0.29167)
    ax = plot.motion_solution(next(s for s in sols if s.valid))
    _written(ax, tmp_path / "solution.png")
    # a defective solution is drawn too (positions where the engine cannot close are left out)
    ax = plot.motion_solution(next(s for s in sols if not s.valid))
    _written(ax, tmp_path / "defective.png")


def test_burmester_curves(tmp_path):
    cur = kl.synthesis.burmester_curves(POS7, samples=721)
    sols = kl.synthesis.four_positions(POS7, None, -0.20195, -0.29167)
    ax = plot.burmester_curves(cur, positions=POS7, solutions=sols)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels[:2] == ["centre points (A0)", "circle points (A1)"]
    _written(ax, tmp_path / "curves.png")


def test_structural_error_and_path(tmp_path):
    f = kl.synthesis.function_generation(np.log10, (1, 2), (90, 150), (0, 90), degrees=True)
    _written(plot.structural_error(f), tmp_path / "error.png")
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                               coupler_point=(1.5, 1.0))
    pts = kl.analyze(fb, q=np.radians([0, 60, 120, 180, 240])).position("P")
    sols = kl.synthesis.path_generation(pts, runs=1, maxiter=20, seed=0)
    _written(plot.path_solution(sols[0]), tmp_path / "path.png")


def test_import_kinelab_does_not_need_matplotlib():
    import subprocess
    import sys
    code = ("import sys; import kinelab, kinelab.synthesis; "
            "print('matplotlib' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_figures_in_the_units_asked_for():
    cm = {"length": "cm"}
    ax = plot.prescribed_positions(POS7, units=cm)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("x [cm]", "y [cm]")
    points = [line.get_xydata()[0] for line in ax.lines if line.get_marker() == "o"]
    np.testing.assert_allclose(points, P7 * 100, rtol=1e-15, atol=1e-15)   # the task's cm
    sols = kl.synthesis.four_positions(POS7, None, -0.20195, -0.29167)
    cur = kl.synthesis.burmester_curves(POS7, samples=181)
    ax = plot.burmester_curves(cur, positions=POS7, solutions=sols, units=cm)
    fixed = [line for line in ax.lines if line.get_marker() == "^"][0].get_xydata()
    np.testing.assert_allclose(fixed, np.array([sols[0].A0, sols[0].B0]) * 100, rtol=1e-15)
    assert ax.get_xlabel() == "x [cm]"
    ax = plot.motion_solution(next(s for s in sols if s.valid), units=cm)
    squares = [line.get_xydata()[0] for line in ax.lines if line.get_marker() == "s"]
    np.testing.assert_allclose(squares, P7 * 100, rtol=1e-15, atol=1e-15)


def test_limit_positions_of_a_crank_rocker(tmp_path):
    """The rocker drawn at its two limit positions: its pins are where the engine puts B at
    the dead centres (in mm), 45 deg apart about O4."""
    cr = kl.synthesis.crank_rocker(0.1, 45, 1.25, degrees=True)
    ax = plot.limit_positions(cr, units={"length": "mm"})
    links = [line.get_xydata() for line in ax.lines if line.get_marker() == "o"]
    rocker = [seg for seg in links if np.linalg.norm(seg - [100, 0], axis=1).min() < 1e-9]
    assert len(links) == 6 and len(rocker) == 2        # crank, coupler, rocker, twice
    B = kl.analyze(cr.model, q=np.radians(cr.dead_centres)).position("B") * 1000
    ends = np.array([seg[np.argmax(np.linalg.norm(seg - [100, 0], axis=1))] for seg in rocker])
    np.testing.assert_allclose(ends, B, atol=1e-9)
    u, v = B - [100, 0]
    assert np.degrees(np.arccos(u @ v / np.linalg.norm(u) / np.linalg.norm(v))) == pytest.approx(45)
    assert "time ratio 1.25" in ax.get_title() and ax.get_xlabel() == "x [mm]"
    _written(ax, tmp_path / "crank_rocker.png")
    for design in (kl.synthesis.offset_slider_crank(0.1, 1.4), kl.synthesis.slotted_lever(2.0, 0.5),
                   kl.synthesis.whitworth(2.0, 0.05, 0.3)):
        ax = plot.limit_positions(design)
        assert ax.get_title().startswith(design.kind)
        _written(ax, tmp_path / "quick_return.png")


def test_five_positions_with_their_centre_point_curves(tmp_path):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    s = kl.analyze(fb, q=np.radians([0, 40, 80, 120, 160]))
    pos = kl.synthesis.Positions(s.position("P"), s.angle("coupler"))
    sols = kl.synthesis.five_positions(pos)
    ax = plot.five_positions(pos, sols, samples=361)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["centre points of positions 1-4", "centre points of positions 1, 2, 3, 5"]
    fixed = np.vstack([line.get_xydata() for line in ax.lines if line.get_marker() == "^"])
    centers, _ = kl.synthesis.burmester_points(pos)
    # every Burmester point is marked, and only they
    assert {tuple(p) for p in np.round(fixed, 9)} == {tuple(p) for p in np.round(centers, 9)}
    _written(ax, tmp_path / "five.png")
