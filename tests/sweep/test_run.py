"""A study's table: rows in order, bad rows reported, chunks and memory, Parquet, progress."""
import math

import numpy as np
import pandas as pd
import pytest

import kinelab as kl
from kinelab.errors import ModelError

LINKS = ("ground", "crank", "coupler", "rocker")
METRICS = ("assembles", "grashof", "transmission_min", "transmission_max", "time_ratio", "swing")


def table(n, seed=1):
    return kl.sweep.random(n, seed=seed, **{k: (0.3, 3.0) for k in LINKS})


def test_outside_contract_columns_and_types():
    df = kl.sweep.run("fourbar", {"ground": [3.0], "crank": [1.0], "coupler": [3.0], "rocker": [2.5]})
    assert list(df.columns) == list(METRICS)
    assert df["assembles"].dtype == bool and df["grashof"][0] == "crank-rocker"
    assert 0 < df["transmission_min"][0] <= df["transmission_max"][0] <= np.pi / 2


def test_bad_rows_are_reported_not_fatal():
    t = table(6)
    t.loc[1, "crank"] = np.nan
    t.loc[4, "rocker"] = -1.0
    df = kl.sweep.run("fourbar", t, metrics=METRICS)
    assert set(df.attrs["problems"]) == {1, 4}
    assert df.attrs["problems"][4] == "rocker: expected a length from 1e-09 m to 1e+09 m, got -1"
    assert "crank: expected a length from 1e-09 m to 1e+09 m, got nan" == df.attrs["problems"][1]
    assert not df.loc[[1, 4], "assembles"].any() and df.loc[[1, 4], "grashof"].isna().all()
    assert df.loc[[1, 4], ["transmission_min", "time_ratio"]].isna().all().all()
    good = kl.sweep.run("fourbar", t.drop(index=[1, 4]), metrics=METRICS)
    pd.testing.assert_frame_equal(df.drop(index=[1, 4]), good)



@pytest.mark.parametrize("chunk_size", [None, 1])
def test_a_models_bad_rows_are_reported_not_fatal(chunk_size):
    """A design of a model's family that cannot be built or planned (a straight dyad in its
    sketch, a link of no length, a NaN) is its row's problem, even in a chunk where no
    design can be built."""
    fam = kl.sweep.family(kl.load("examples/engine.toml"), output="slide")
    d = {"A.y": [0.05, 1e9, 0.0, math.nan, 0.06]}
    df = kl.sweep.run(fam, d, metrics=("assembles", "time_ratio", "swing"), chunk_size=chunk_size)
    problems = df.attrs["problems"]
    assert set(problems) == {1, 2, 3}
    assert "singular (straight) position" in problems[1]
    assert "'O2' and 'A' coincide" in problems[2]
    assert problems[3] == "A.y: expected a finite number, got nan"
    assert df["assembles"].tolist() == [True, False, False, False, True]
    assert df.loc[[1, 2, 3], ["time_ratio", "swing"]].isna().all().all()
    assert df["swing"][4] == pytest.approx(0.12, abs=1e-10)      # crank 60 mm: stroke 120 mm
    for row in ([0.0], [math.nan]):                           # every row bad
        alone = kl.sweep.run(fam, {"A.y": row}, metrics=("assembles", "swing"))
        assert alone["assembles"].tolist() == [False] and set(alone.attrs["problems"]) == {0}


def test_a_catalogue_familys_chunk_of_bad_rows_only():
    df = kl.sweep.run("slider_crank", {"crank": [math.nan, 1.0], "rod": [3.0, 3.0]}, chunk_size=1)
    assert df["assembles"].tolist() == [False, True] and set(df.attrs["problems"]) == {0}
    assert math.isnan(df["swing"][0]) and df["swing"][1] == pytest.approx(2.0, abs=1e-10)

def test_order_and_index_are_kept():
    t = table(9).set_index(pd.Index(list("abcdefghi")))
    df = kl.sweep.run("fourbar", t.iloc[::-1], metrics=("grashof",))
    assert list(df.index) == list("ihgfedcba")
    one = kl.sweep.run("fourbar", t.loc[["c"]], metrics=("grashof",))
    assert df.loc["c", "grashof"] == one.loc["c", "grashof"]


def test_an_array_table_takes_the_family_parameters_in_order():
    a = table(5).to_numpy()
    with pytest.raises(ModelError, match=r"expected a DataFrame, a mapping of columns or an array of "
                                         r"shape \(D, 4\) to \(D, 6\)"):
        kl.sweep.run("fourbar", a[:, :3])
    df = kl.sweep.run("fourbar", a, metrics=("grashof", "transmission_min"))
    assert df["grashof"].tolist() == kl.mechanisms.grashof_kinds(*a.T).tolist()
    full = np.column_stack([a, np.full((5, 2), 0.5)])
    same = kl.sweep.run("fourbar", full, metrics=("grashof", "transmission_min"))
    pd.testing.assert_frame_equal(df, same)


def test_chunks_do_not_change_the_results():
    t = table(50)
    whole = kl.sweep.run("fourbar", t, metrics=METRICS + ("reachable",))
    pd.testing.assert_frame_equal(whole, kl.sweep.run("fourbar", t, metrics=METRICS + ("reachable",),
                                                       chunk_size=7))


def test_a_small_memory_budget_makes_smaller_chunks_not_a_refusal():
    from kinelab.sweep._run import chunk_size_for
    old = kl.memory_budget("4M")
    try:
        assert chunk_size_for(72, 10_000) == (4 << 20) // 4 // (8 * 48 * 72)
        seen = []
        df = kl.sweep.run("fourbar", table(200), metrics=("assembles",),
                          progress=lambda done, total: seen.append((done, total)))
    finally:
        kl.memory_budget(old)
    assert len(df) == 200 and len(seen) == math.ceil(200 / 37) and seen[-1] == (200, 200)


def test_no_progress_bar_when_not_a_terminal(capsys):
    kl.sweep.run("fourbar", table(5), metrics=("assembles",))
    assert capsys.readouterr().err == ""


def test_parquet_round_trip(tmp_path):
    t = table(8)
    t.loc[2, "ground"] = np.nan
    df = kl.sweep.run("fourbar", t, path=tmp_path / "study.parquet")
    back = pd.read_parquet(tmp_path / "study.parquet")
    pd.testing.assert_frame_equal(back, df, check_dtype=False)    # text may come back as str dtype
    assert back.attrs["problems"] == {"2": "ground: expected a length from 1e-09 m to 1e+09 m, got nan"}
    assert df.attrs["problems"] == {2: "ground: expected a length from 1e-09 m to 1e+09 m, got nan"}
    assert type(next(iter(df.attrs["problems"]))) is int     # a Python number, not numpy's


@pytest.mark.parametrize("index, label", [
    (pd.MultiIndex.from_tuples([(1, "a"), (1, "b"), (2, "a")]), "(2, 'a')"),
    (pd.date_range("2020-01-01", periods=3), "2020-01-03 00:00:00"),
    (pd.Index(["x", "y", "z"]), "z"),
])
def test_parquet_of_any_index(index, label, tmp_path, recwarn):
    t = pd.DataFrame(table(3)).set_axis(index)
    t.iloc[2, t.columns.get_loc("crank")] = -1.0
    df = kl.sweep.run("fourbar", t, path=tmp_path / "study.parquet")
    back = pd.read_parquet(tmp_path / "study.parquet")
    pd.testing.assert_frame_equal(back, df, check_dtype=False, check_freq=False)
    assert back.attrs["problems"] == {label: "crank: expected a length from 1e-09 m to 1e+09 m, got -1"}
    assert not recwarn.list


@pytest.mark.parametrize("frame, message", [
    (pd.DataFrame({"x": pd.Series([1, "a"], dtype=object)}),
     r"^df: column 'x': expected numbers, booleans or text to write as Parquet, got mixed-integer values"),
    (pd.DataFrame({"x": [1 + 2j]}), r"^df: column 'x': .* got complex values"),
])
def test_parquet_refuses_columns_it_cannot_hold(frame, message, tmp_path):
    with pytest.raises(ModelError, match=message):
        kl.sweep.write_parquet(frame, tmp_path / "t.parquet")
    assert not (tmp_path / "t.parquet").exists()


def test_parquet_refuses_attrs_it_cannot_hold(tmp_path):
    frame = pd.DataFrame({"x": [1.0]})
    frame.attrs["when"] = object()
    with pytest.raises(ModelError, match=r"^df.attrs: expected plain data"):
        kl.sweep.write_parquet(frame, tmp_path / "t.parquet")


@pytest.mark.parametrize("call, message", [
    (lambda: kl.sweep.run("fourbars", {}), r"family: expected one of 'fourbar', .* got 'fourbars' \(did you mean 'fourbar'\?\)"),
    (lambda: kl.sweep.run("fourbar", table(2), metrics=("grashoff",)), r"metrics: expected one of 'assembles', .* got 'grashoff'"),
    (lambda: kl.sweep.run("fourbar", {**table(2), "crank_length": [1, 2]}), r"designs: column 'crank_length': expected one of"),
    (lambda: kl.sweep.run("fourbar", {"ground": [1.0]}), r"designs: missing column\(s\) 'crank', 'coupler', 'rocker'"),
    (lambda: kl.sweep.run("slider_crank", {"crank": [1.0], "rod": [3.0]}, metrics=("grashof",)),
     r"metrics: 'grashof' is defined for four-bars"),
    (lambda: kl.sweep.run("fourbar", table(2), metrics=("descriptors",)), r"needs the family's coupler point"),
    (lambda: kl.sweep.run("fourbar", table(2), samples=2), r"samples: expected at least 4"),
    (lambda: kl.sweep.run("fourbar", table(2), client=3), r"client: expected a dask.distributed.Client"),
    (lambda: kl.sweep.family("fourbar", branch="crossed", colour=1), r"fourbar: option 'colour': expected one of 'branch'"),
    (lambda: kl.sweep.sobol(8, crank=(2.0, 1.0)), r"crank: expected a finite range with low <= high"),
])
def test_bad_input_says_what_to_do(call, message):
    with pytest.raises(ModelError, match=message):
        call()


def test_design_generators():
    g = kl.sweep.grid(crank=[1.0, 2.0], rocker=(2.0, 3.0, 3))
    assert g.values.tolist() == [[1.0, 2.0], [1.0, 2.5], [1.0, 3.0], [2.0, 2.0], [2.0, 2.5], [2.0, 3.0]]
    s = kl.sweep.sobol(64, seed=4, crank=(1.0, 2.0), rocker=(0.0, 1.0))
    counts = np.histogram(s["crank"], bins=8, range=(1.0, 2.0))[0]
    assert counts.tolist() == [8] * 8                       # a scrambled Sobol net is balanced
    r = kl.sweep.random(1000, seed=4, crank=(1.0, 2.0))
    assert r["crank"].between(1.0, 2.0).all() and r["crank"].std() > 0.25
