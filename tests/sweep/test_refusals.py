"""The library's side of the sweep's refusals: samples, speed, grids, options, paths, and
no library warning on the way."""
import re
import warnings

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import MemoryBudgetError, ModelError
from tests.sweep.atlases import sobol_atlas

FOURBAR = {"ground": [3.0, 1.0], "crank": [1.0, 2.0], "coupler": [3.0, 1.0], "rocker": [2.5, 1.5]}


@pytest.mark.parametrize("samples", [10 ** 8, 10 ** 20, 3, np.zeros(1_000_001)])
def test_samples_beyond_the_limit_are_refused(samples):
    with pytest.raises(ModelError, match=r"samples: expected .*1,000,000"):
        kl.sweep.run("fourbar", FOURBAR, samples=samples)


def test_samples_are_as_many_as_a_model_files():
    from kinelab.io._modelfile import MAX_SAMPLES
    assert kl.sweep._run.MAX_SAMPLES == MAX_SAMPLES


def test_a_chunk_beyond_the_memory_budget_is_refused():
    old = kl.memory_budget("64M")
    try:
        with pytest.raises(MemoryBudgetError, match=r"1 design\(s\) at 1,000,000 samples each"):
            kl.sweep.run("fourbar", FOURBAR, samples=1_000_000)
    finally:
        kl.memory_budget(old)


@pytest.mark.parametrize("speed, message", [(1e101, "at most 1e\\+100 rad/s"), (float("inf"), "finite"),
                                            (True, "finite"), ("1", "finite")])
def test_speed_is_bounded(speed, message):
    engine = kl.sweep.family(kl.load("examples/engine.toml"), output="slide")
    with pytest.raises(ModelError, match=f"speed: expected .*{message}"):
        kl.sweep.run(engine, {"A.y": [0.05]}, metrics=("peak_torque",), speed=speed)


def test_a_torque_that_overflows_is_a_problem_not_a_silent_nan(monkeypatch):
    import dataclasses

    from kinelab.dynamics import _terms

    real = _terms.evaluate

    def overflowing(*args, **kwargs):       # Kane's terms of the designs, all at once
        out = real(*args, **kwargs)
        return dataclasses.replace(out, inertia=np.full_like(out.inertia, np.inf))
    monkeypatch.setattr(_terms, "evaluate", overflowing)
    engine = kl.sweep.family(kl.load("examples/engine.toml"), output="slide")
    df = kl.sweep.run(engine, {"A.y": [0.05]}, metrics=("peak_torque",), speed=2.0)
    assert "peak_torque: the input torque overflows at 2 rad/s" in df.attrs["problems"][0]


def test_a_grid_is_refused_by_its_product_before_its_axes_are_built():
    with pytest.raises(MemoryBudgetError, match=r"a grid of 1e\+6000 designs"):
        kl.sweep.grid(**{f"p{i}": (1.0, 2.0, 10 ** 300) for i in range(20)})
    with pytest.raises(MemoryBudgetError, match=r"a grid of 100,000,000,000 designs"):
        kl.sweep.grid(crank=(0.5, 1.5, 10 ** 8), rocker=np.arange(1000.0))


def test_sobol_of_any_size_warns_nothing_and_keeps_the_sequence():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ten = kl.sweep.sobol(10, seed=3, crank=(0.5, 1.0))
    sixteen = kl.sweep.sobol(16, seed=3, crank=(0.5, 1.0))
    assert np.array_equal(ten["crank"], sixteen["crank"][:10])    # the first 10 of the same sequence


@pytest.mark.parametrize("kind, options, message", [
    ("fourbar", {"branch": "weird"}, "branch: expected one of 'open', 'crossed', got 'weird'"),
    ("slider_crank", {"branch": "open"}, "branch: expected one of 'right', 'left', got 'open'"),
    ("watt6", {"branch": "open"}, "branch: expected 2 values"),
    ("watt6", {"branch": ("open", "x")}, r"branch\[1\]: expected one of 'open', 'crossed', got 'x'"),
])
def test_options_are_checked_when_the_family_is_made(kind, options, message):
    with pytest.raises(ModelError, match=message):
        kl.sweep.family(kind, **options)


def test_valid_options_are_kept():
    assert kl.sweep.family("fourbar", branch="crossed").options == {"branch": "crossed"}
    assert kl.sweep.family("watt6", branch=("open", "crossed")).options["branch"] == ("open", "crossed")


def test_a_design_off_the_models_places_is_one_error_without_python_advice():
    fam = kl.sweep.family(kl.load("examples/crank_rocker.toml"))
    with pytest.raises(kl.sweep._family.DesignOffModel,
                       match=r"^designs: the design \(B\.x = 1\.5 m\) moves points off") as info:
        kl.sweep.run(fam, {"B.x": [1.5]})
    assert "kl." not in str(info.value)
    assert re.search(r"\('\w+' misses its declared length or place by [0-9.e+-]+ m\)", str(info.value))
    assert kl.sweep.run(fam, {"A.y": [fam.defaults["A.y"]]}, samples=8)["assembles"].tolist() == [True]


@pytest.fixture(scope="module")
def atlas():
    return sobol_atlas(256)


def ellipse(n=60):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([2.0 * np.cos(t) + 0.3, np.sin(t) - 0.2])


@pytest.mark.parametrize("scale", [1e300, 1.7e307, 1e-5, 1e-8])
def test_nearest_does_not_depend_on_the_paths_size(atlas, scale):
    near, scaled = atlas.nearest(ellipse(), 4), atlas.nearest(scale * ellipse(), 4)
    assert scaled.index.tolist() == near.index.tolist()
    # the same shape to rounding: the descriptors of a path scaled to 1 first
    assert np.allclose(scaled["distance"], near["distance"], rtol=0, atol=1e-12)


@pytest.mark.parametrize("path, extent", [(np.ones((50, 2)), "0"), (1e-300 * ellipse(), "4e-300"),
                                          (1e-10 * ellipse(), "4e-10")])
def test_a_path_with_no_extent_is_refused(atlas, path, extent):
    with pytest.raises(ModelError, match=f"path: its points span {extent} m, expected a closed "
                                         "path at least 1e-09 m across"):
        atlas.nearest(path)


@pytest.mark.parametrize("samples", [10 ** 7, 10 ** 400])
def test_tolerance_samples_are_capped_too(samples):
    with pytest.raises(ModelError, match="samples: expected a whole number from 4 to 1,000,000"):
        kl.sweep.tolerance("fourbar", dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5),
                           {"crank": 1e-3}, n=10, samples=samples)


@pytest.mark.parametrize("transmission, message", [
    (("coupler", "coupler"), r"^transmission: expected two different links .* got \('coupler', 'coupler'\)$"),
    (5, r"^transmission: expected two different links .* got 5$"),
    (("coupler",), r"^transmission: expected two different links"),
    (("coupler", "rokker"), r"^transmission\[1\]: expected one of .*'rocker', got 'rokker' \(did you mean 'rocker'\?\)$"),
])
def test_a_transmission_pair_is_two_different_links(transmission, message):
    with pytest.raises(ModelError, match=message):
        kl.sweep.family("fourbar", transmission=transmission)


def test_a_models_output_and_point_are_its_own():
    m = kl.load("examples/engine.toml")
    with pytest.raises(ModelError, match=r"^output: expected one of .*'slide', got 'slid'"):
        kl.sweep.family(m, output="slid")
    with pytest.raises(ModelError, match=r"^point: expected one of .*'G3', got 'Q'$"):
        kl.sweep.family(m, point="Q")
    assert kl.sweep.family(m, output="slide", point="G3").point == "G3"


# -- refusals in the study's terms, never the engine's (a q the user never gave) ----------------
FIVEBAR = dict(ground=[2.0], crank1=[1.0], coupler1=[1.5], coupler2=[1.5], crank2=[1.0])


def test_a_family_with_two_inputs_is_refused_in_the_studys_terms():
    with pytest.raises(ModelError) as info:
        kl.sweep.run("fivebar", FIVEBAR, samples=8)
    assert str(info.value) == ("family: the mechanisms of 'fivebar' have 2 inputs, but a sweep "
                               "turns one input through its samples; sweep a family with one "
                               "input (a model file of it with one input, say)")


@pytest.mark.parametrize("family, wanted", [
    ("fourbar", "the family 'fourbar' takes ground, crank, coupler, rocker, coupler_point_along, "
                "coupler_point_perpendicular"),
    ("watt6", "the family 'watt6' has no numeric parameters to vary"),
])
def test_a_table_without_columns_says_which_it_takes(family, wanted):
    with pytest.raises(ModelError, match=rf"^designs: expected a column for each parameter to vary, "
                                         rf"got none; {re.escape(wanted)}$"):
        kl.sweep.run(family, {}, samples=8)


def test_a_design_whose_catalogue_mechanism_cannot_be_drawn_says_so_in_its_lengths():
    """A Whitworth design whose rod cannot reach the ram line where the catalogue first
    assembles it: the row's reason speaks of the rod and the crank angle, not of a sketch."""
    df = kl.sweep.run("whitworth", dict(crank=[1.0], distance=[0.5], lever=[1.0], rod=[0.1]),
                      samples=8)
    reason = df.attrs["problems"][0]
    assert reason.startswith("rod: expected more than ") and "sketch" not in reason
    assert reason.endswith("got 0.1 m; lengthen it (a rod longer than lever + |ram_height| = 1 m "
                           "reaches the ram line at every crank angle)")
