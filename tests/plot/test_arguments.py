"""Arguments of the figures: solutions without samples, sample numbers, frames, paths,
results of the wrong kind and sizes beyond the memory budget are refused with a
ModelError (or MemoryBudgetError) that names the argument."""
import dataclasses
import warnings

import matplotlib
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import MemoryBudgetError, ModelError

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FB = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
SOL = kl.analyze(FB, q=np.linspace(0, 6, 30))
EMPTY = kl.analyze(FB, q=np.zeros(0))
P4 = np.array([[0, 0], [1, 0.2], [2, 0.5], [3, 0.3]], float)
P5 = np.vstack([P4, [[4, 0]]])
NOMINAL = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
SAMPLE = r"expected a whole number from 0 to 29 \(or -30 to -1 from the end\), the index of a sample, got "


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def study():
    return kl.sweep.tolerance("fourbar", NOMINAL, {"crank": 1e-3}, n=10)


@pytest.mark.parametrize("draw", [kl.plot.curves, kl.plot.coefficients, kl.plot.transmission,
                                  kl.plot.coupler_curve, kl.plot.mechanism, kl.plot.input_axis])
def test_a_solution_without_samples_is_refused(draw):
    with pytest.raises(ModelError, match=r"^sol: the solution has no samples; analyze at least one input value$"):
        draw(EMPTY)


@pytest.mark.parametrize("draw", [kl.plot.curves, kl.plot.mechanism, kl.plot.coupler_curve])
def test_a_mechanism_is_analyzed_first(draw):
    with pytest.raises(ModelError, match=r"^sol: expected a KinematicSolution, got a Mechanism; analyze it first"):
        draw(FB)


@pytest.mark.parametrize("call, message", [
    (lambda: kl.plot.mechanism(SOL, i=37), "^i: " + SAMPLE + "37$"),
    (lambda: kl.plot.mechanism(SOL, i=1.5), "^i: " + SAMPLE + "1.5$"),
    (lambda: kl.plot.mechanism(SOL, i=None), "^i: " + SAMPLE + "None$"),
    (lambda: kl.plot.mechanism(SOL, i=True), "^i: " + SAMPLE + "true$"),
    (lambda: kl.plot.coupler_curve(SOL, sample=1000), "^sample: " + SAMPLE + "1000$"),
    (lambda: kl.plot.coupler_curve(SOL, sample=2.5), "^sample: " + SAMPLE + "2.5$"),
    (lambda: kl.plot.mechanism(kl.analyze(FB, q=0.5), i=1), r"^i: expected 0 \(one configuration\)"),
])
def test_sample_numbers(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_sample_numbers_from_the_end_and_numpy():
    assert kl.plot.mechanism(SOL, i=-1) is not None
    assert kl.plot.coupler_curve(SOL, sample=np.int64(3)) is not None


def test_one_output_by_name():
    fig = kl.plot.curves(SOL, outputs="rocker")
    assert fig.axes[0].get_ylabel() == "rocker angle [rad]"
    fig = kl.plot.coefficients(SOL, outputs="rocker")
    assert [line.get_label() for line in fig.axes[0].lines if line.get_label() == "rocker"]
    with pytest.raises(ModelError, match=r"^outputs: expected names of links, slides or points, got 5$"):
        kl.plot.curves(SOL, outputs=5)


@pytest.mark.parametrize("options, message", [
    (dict(frames=0), r"^frames: expected a whole number from 1 to 100,000, got 0$"),
    (dict(frames=-1), r"^frames: expected a whole number from 1 to 100,000, got -1$"),
    (dict(frames=2.5), r"^frames: expected a whole number from 1 to 100,000, got 2.5$"),
    (dict(fps=0), r"^fps: expected a whole number from 1 to 1,000, got 0$"),
    (dict(trace=5), r"^trace: expected names of points, got 5$"),
    (dict(trace="bogus"), r"^trace: expected one of 'O2', 'A', 'B', 'O4', 'P', got 'bogus'$"),
    (dict(trace=["P", "Q"]), r"^trace: expected one of .* got 'Q'$"),
    (dict(centers="yes"), r"^centers: expected True or False, got 'yes'$"),
])
def test_animation_options(options, message, tmp_path):
    with pytest.raises(ModelError, match=message):
        kl.plot.animate(SOL, tmp_path / "a.gif", **options)
    assert not (tmp_path / "a.gif").exists()


def test_an_animation_traces_one_point_by_name(tmp_path):
    assert kl.plot.animate(SOL, tmp_path / "a.gif", trace="P", frames=3).stat().st_size > 0


def test_an_animation_of_a_sweep_that_never_assembles(tmp_path):
    sol = kl.analyze(kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5), q=np.linspace(2.5, 3.5, 5),
                     unreachable="mask")
    with pytest.raises(ModelError, match=r"^sol: the mechanism assembles at none of the samples"):
        kl.plot.animate(sol, tmp_path / "a.gif")
    with pytest.raises(ModelError, match=r"^path: expected a file's path"):
        kl.plot.animate(SOL, None)


@pytest.mark.parametrize("figure, path, message", [
    ("fig", "f.xyz", r"^path: expected a file name ending in one of .*'.png'.*, got 'f.xyz'$"),
    (None, "f.png", r"^figure: expected a matplotlib Figure \(ax.figure for the axes of a plot\), got None$"),
    ("fig", None, r"^path: expected a file's path"),
])
def test_save_checks_its_arguments(figure, path, message, tmp_path):
    figure = plt.figure() if figure == "fig" else figure
    with pytest.raises(ModelError, match=message):
        kl.plot.save(figure, tmp_path / path if path else path)
    assert kl.plot.save(plt.figure(), tmp_path / "f.svg").stat().st_size > 0


def test_burmester_curves_without_a_valid_point():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")       # the curves' own computation
        curves = kl.synthesis.burmester_curves(kl.synthesis.Positions(P4, [0, 0, 0, 0]))
    with pytest.raises(ModelError, match=r"^curves: no point of the centre-point curve is valid"):
        kl.plot.burmester_curves(curves)


@pytest.mark.parametrize("call, message", [
    (lambda: kl.plot.motion_solution(None), r"^sol: expected a MotionSolution \(from kinelab.synthesis"),
    (lambda: kl.plot.motion_solution(FB), r"^sol: expected a MotionSolution"),
    (lambda: kl.plot.structural_error(None), r"^sol: expected a FunctionSolution"),
    (lambda: kl.plot.path_solution(None), r"^sol: expected a PathSolution"),
    (lambda: kl.plot.limit_positions(None), r"^design: expected a CrankRocker or QuickReturn"),
    (lambda: kl.plot.tolerance_band(None), r"^study: expected a ToleranceStudy \(from kinelab.sweep.tolerance\), got None$"),
    (lambda: kl.plot.error_histogram(5), r"^study: expected a ToleranceStudy"),
    (lambda: kl.plot.burmester_curves(None), r"^curves: expected BurmesterCurves"),
    (lambda: kl.plot.burmester_curves(kl.synthesis.burmester_curves(kl.synthesis.Positions(P4, [0, 0.2, 0.4, 0.6])),
                                      solutions=[1, 2]), r"^solutions\[0\]: expected a MotionSolution"),
    (lambda: kl.plot.burmester_curves(kl.synthesis.burmester_curves(kl.synthesis.Positions(P4, [0, 0.2, 0.4, 0.6])),
                                      positions="x"), r"^positions: expected the four Positions"),
    (lambda: kl.plot.five_positions(kl.synthesis.Positions(P4, [0, 0.2, 0.4, 0.6])),
     r"^positions: expected five positions, got 4"),
    (lambda: kl.plot.five_positions(None), r"^positions: expected five Positions"),
])
def test_results_of_the_wrong_kind(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_a_limit_position_needs_a_design_not_a_motion_solution():
    sol = kl.synthesis.three_positions(kl.synthesis.Positions(P4[:3], [0, 0.2, 0.4]),
                                       A0=(0.0, -1.0), B0=(3.0, -1.0))
    with pytest.raises(ModelError, match=r"^design: expected a CrankRocker or QuickReturn .* got "):
        kl.plot.limit_positions(sol)


@pytest.mark.parametrize("bins, message", [
    (0, r"^bins: expected a whole number from 1 to 1,000,000,000, got 0$"),
    (-1, r"^bins: expected a whole number from 1 to 1,000,000,000, got -1$"),
    (2.5, r"^bins: expected a whole number from 1 to 1,000,000,000, got 2.5$"),
])
def test_histogram_bins(study, bins, message):
    with pytest.raises(ModelError, match=message):
        kl.plot.error_histogram(study, bins=bins)


def test_a_histogram_of_a_study_where_nothing_assembles(study):
    none = dataclasses.replace(study, errors=np.full_like(study.errors, np.nan))
    with pytest.raises(ModelError, match=r"^study: no drawn design assembles over the cycle"):
        kl.plot.error_histogram(none)


@pytest.mark.parametrize("call, what", [
    (lambda s: kl.plot.error_histogram(s, bins=10 ** 9), r"a histogram of 1,000,000,000 bins"),
    (lambda s: kl.plot.five_positions(kl.synthesis.Positions(P5, [0, 0.2, 0.4, 0.6, 0.8]), samples=10 ** 9),
     r"two centre-point curves of 1,000,000,000 samples"),
])
def test_sizes_beyond_the_memory_budget(study, call, what):
    with pytest.raises(MemoryBudgetError, match=f"^{what} would take about .* more than the memory budget"):
        call(study)
