"""Arguments of the sweep functions: numbers beyond floats, seeds, chunks given by hand,
percentiles, descriptors and refine's options are refused with a ModelError that names
the argument."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

NOMINAL = dict(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
D = {k: [v] for k, v in NOMINAL.items()}
FAMILY = kl.sweep.family("fourbar")
COLUMNS = {k: np.array(v) for k, v in D.items()}
HUGE = 10 ** 400
NO_SEED = r"^seed: expected a whole number from 0 to 4,294,967,295, got "


@pytest.mark.parametrize("call, message", [
    (lambda: kl.sweep.evaluate_chunk(FAMILY, COLUMNS, ["", ""], samples=36, metrics={"a": "assembles"}),
     r"^problems: expected one text a design \(.* for a good one\), 1 in all, got \['', ''\]$"),
    (lambda: kl.sweep.evaluate_chunk(FAMILY, {k: v for k, v in COLUMNS.items() if k != "rocker"}, [""],
                                     samples=36, metrics={"a": "assembles"}),
     r"designs: missing column\(s\) 'rocker'"),
    (lambda: kl.sweep.evaluate_chunk(FAMILY, COLUMNS, [""], samples=36, metrics={"x": "bogus"}),
     r"^metrics: expected one of 'assembles', .* got 'bogus'"),
    (lambda: kl.sweep.evaluate_chunk(FAMILY, COLUMNS, [""], samples=0, metrics={"a": "assembles"}),
     r"^samples: expected at least 4 .* got 0$"),
    (lambda: kl.sweep.evaluate_chunk(FAMILY, COLUMNS, [""], samples="x", metrics={"a": "assembles"}),
     r"^samples: expected a number of samples .* got 'x'$"),
    (lambda: kl.sweep.evaluate_chunk(FAMILY, None, [""], samples=36, metrics={"a": "assembles"}),
     r"^columns: expected a mapping of parameter to values"),
])
def test_evaluate_chunk_checks_its_arguments(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_evaluate_chunk_takes_a_family_by_name_and_finds_bad_rows():
    out = kl.sweep.evaluate_chunk("fourbar", {**COLUMNS, "crank": np.array([-1.0])}, [""],
                                  samples=36, metrics={"assembles": "assembles"})
    assert out["assembles"].tolist() == [False]
    assert out["_problems"].tolist() == ["crank: expected a length from 1e-09 m to 1e+09 m, got -1"]


@pytest.mark.parametrize("call, message", [
    (lambda: kl.sweep.random(3, crank=(0, HUGE)), r"^crank: range: expected a finite number, got a whole number of 401 digits$"),
    (lambda: kl.sweep.sobol(4, crank=(0, HUGE)), r"^crank: range: expected a finite number"),
    (lambda: kl.sweep.grid(crank=(0, HUGE, 3)), r"^crank: range: expected a finite number"),
    (lambda: kl.sweep.grid(crank=[1, HUGE]), r"^crank: expected real numbers, got \[1, a whole number of 401 digits\]$"),
    (lambda: kl.sweep.random(3, crank=(-1e308, 1e308)), r"^crank: expected a range within 1e\+09 m of 0"),
    (lambda: kl.sweep.sobol(4, crank=(-1e308, 1e308)), r"^crank: expected a range within 1e\+09 m of 0"),
    (lambda: kl.sweep.grid(crank=[1.0, 1e300]), r"^crank: expected values within 1e\+09 m of 0"),
    (lambda: kl.sweep.grid(crank=None), r"^crank: expected values or \(low, high, count\), got None$"),
    (lambda: kl.sweep.grid(crank=[1.0, np.nan]), r"^crank: expected finite numbers, got nan at index \(1,\)$"),
    (lambda: kl.sweep.grid(crank=[True, False]), r"^crank: expected real numbers"),
    (lambda: kl.sweep.run("fourbar", {**D, "crank": [HUGE]}), r"^designs: column 'crank': expected real numbers, got \[a whole number of 401 digits\]$"),
    (lambda: kl.sweep.run("fourbar", {**D, "crank": [1 + 0j]}), r"^designs: column 'crank': expected real numbers, got \[\(1\+0j\)\]$"),
    (lambda: kl.sweep.run("fourbar", D, speed=HUGE), r"^speed: expected a finite input speed \(rad/s\), got a whole number of 401 digits$"),
    (lambda: kl.sweep.run("fourbar", D, samples=[1e308] * 5), r"^samples: expected angles within 1000 turns of 0"),
    (lambda: kl.sweep.run("fourbar", D, progress=5), r"^progress: expected True, False or a function progress\(done, total\), got 5$"),
    (lambda: kl.sweep.tolerance("fourbar", {**NOMINAL, "crank": HUGE}, {"crank": 1e-3}, n=5),
     r"^nominal: crank: expected a finite number, got a whole number of 401 digits$"),
    (lambda: kl.sweep.tolerance("fourbar", {**NOMINAL, "crank": "x"}, {"crank": 1e-3}, n=5), r"^nominal: crank: expected a finite number, got 'x'$"),
    (lambda: kl.sweep.tolerance("fourbar", {**NOMINAL, "crank_": 1.0}, {"crank": 1e-3}, n=5), r"^nominal: expected one of .* got 'crank_'"),
    (lambda: kl.sweep.tolerance("fourbar", None, {"crank": 1e-3}, n=5), r"^nominal: expected a mapping of parameter to value \(m\)"),
    (lambda: kl.sweep.tolerance("fourbar", [1, 2], {"crank": 1e-3}, n=5), r"^nominal: expected a mapping"),
    (lambda: kl.sweep.tolerance("fourbar", NOMINAL, ["crank"], n=5), r"^tolerances: expected a mapping of parameter to tolerance"),
    (lambda: kl.sweep.tolerance("fourbar", NOMINAL, {"crank": HUGE}, n=5), r"^tolerances: crank: expected a tolerance >= 0 and at most 1e\+09 m, got a whole"),
    (lambda: kl.sweep.tolerance("fourbar", NOMINAL, {"crank": True}, n=5), r"^tolerances: crank: expected a tolerance >= 0"),
])
def test_numbers_of_the_wrong_kind_are_refused(call, message):
    with pytest.raises(ModelError, match=message):
        call()


@pytest.mark.parametrize("seed", [-1, 2.5, "a", float("nan"), True, 2 ** 32])
@pytest.mark.parametrize("call", [
    lambda s: kl.sweep.random(3, seed=s, crank=(1, 2)),
    lambda s: kl.sweep.sobol(4, seed=s, crank=(1, 2)),
    lambda s: kl.sweep.tolerance("fourbar", NOMINAL, {"crank": 1e-3}, n=5, seed=s),
], ids=["random", "sobol", "tolerance"])
def test_seeds_are_whole_numbers_from_0(call, seed):
    with pytest.raises(ModelError, match=NO_SEED):
        call(seed)


def test_seeds_of_numpy_and_none_are_taken():
    a = kl.sweep.random(3, seed=np.int64(3), crank=(1, 2))
    assert a.equals(kl.sweep.random(3, seed=3, crank=(1, 2)))
    assert kl.sweep.random(3, seed=None, crank=(1, 2)).shape == (3, 1)


@pytest.fixture(scope="module")
def study():
    return kl.sweep.tolerance("fourbar", NOMINAL, {"crank": 1e-3}, n=20)


@pytest.mark.parametrize("p, message", [
    (-1, r"^p: expected percentiles from 0 to 100, got -1$"),
    (101, r"^p: expected percentiles from 0 to 100, got 101$"),
    ([5, 150], r"^p: expected percentiles from 0 to 100, got \[5, 150\]$"),
    (float("nan"), r"^p: expected finite numbers, got nan$"),
    ("a", r"^p: expected real numbers, got 'a'$"),
    (None, r"^p: expected real numbers, got None$"),
    (HUGE, r"^p: expected real numbers, got a whole number of 401 digits$"),
])
def test_percentiles_are_from_0_to_100(study, p, message):
    with pytest.raises(ModelError, match=message):
        study.percentile(p)


def test_percentiles_in_range(study):
    assert study.percentile([0, 100]).shape == (2, 72)
    np.testing.assert_array_equal(study.percentile(50), np.percentile(study.errors, 50, axis=0))


RING = np.random.default_rng(0).random((3, 300, 2))


@pytest.mark.parametrize("args, message", [
    ((RING, 2.5), r"^harmonics: expected a whole number >= 1, got 2.5$"),
    ((RING, None), r"^harmonics: expected a whole number >= 1, got None$"),
    ((RING, 0), r"^harmonics: expected a whole number >= 1, got 0$"),
    ((RING, -1), r"^harmonics: expected a whole number >= 1, got -1$"),
    (("abc",), r"^points: expected real numbers, got 'abc'$"),
    ((RING + 0j,), r"^points: expected real numbers"),
])
def test_descriptors_check_their_arguments(args, message):
    with pytest.raises(ModelError, match=message):
        kl.sweep.descriptors(*args)


def test_harmonics_beyond_the_samples_say_so():
    designs = {**D, "coupler_point_along": [1.0], "coupler_point_perpendicular": [0.5]}
    with pytest.raises(ModelError, match=r"^harmonics: 100 harmonics of the coupler curve need at "
                                         r"least 201 samples, got 72; ask for more samples or fewer harmonics$"):
        kl.sweep.run("fourbar", designs, metrics=("descriptors",), harmonics=100)


@pytest.fixture(scope="module")
def atlas():
    from tests.sweep.atlases import sobol_atlas
    return sobol_atlas(64)


T = np.linspace(0, 2 * np.pi, 40, endpoint=False)
PATH = np.column_stack([2 + np.cos(T), 1 + 0.5 * np.sin(T)])


@pytest.mark.parametrize("options, message", [
    (dict(bogus=1), r"^'bogus': unknown option of refine; its options are k, points, 'runs', "),
    (dict(maxiters=1), r"^'maxiters': unknown option of refine \(did you mean 'maxiter'\?\)"),
    (dict(initial=[1]), r"^'initial': unknown option of refine; refine starts from the atlas's nearest designs"),
    (dict(seed=-1), NO_SEED + "-1$"),
    (dict(seed=None), NO_SEED + "None$"),
])
def test_refine_options(atlas, options, message):
    with pytest.raises(ModelError, match=message):
        atlas.refine(PATH, **options)


def test_a_complex_path_is_refused(atlas):
    with pytest.raises(ModelError, match=r"^path: expected more than 16 finite points, shape \(n, 2\)"):
        atlas.nearest(PATH + 0j)


def test_refine_fits_the_paths_own_points_and_refuses_one_place_twice(atlas):
    """Refine fits points of the path as given, in order (never points between them, which
    on a path that goes back over itself could fall on one place): a place given twice is
    refused in the path's terms, with the numbers of its points."""
    there_and_back = np.column_stack([np.r_[np.linspace(0, 3, 12), np.linspace(3, 0, 12)[1:-1]],
                                      np.ones(22)])
    with pytest.raises(ModelError, match=r"^path: points 2 and 22 are the same place "
                                         r"\(0\.272727273, 1\), which refine cannot fit twice "
                                         r"\(it fits the path's points in order\); give each "
                                         r"place once, or another number of points$"):
        atlas.refine(there_and_back)
