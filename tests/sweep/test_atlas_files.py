"""Atlas and design files read within bounds and checked for what they hold: metadata that
agrees with the columns, lengths that are lengths, tables that fit the memory budget."""
import math

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import MemoryBudgetError, ModelError
from tests.sweep.test_atlas import _rewritten, small_atlas_file  # noqa: F401 (a fixture)


@pytest.fixture
def atlas_file(small_atlas_file):
    return small_atlas_file


def rewritten(source, tmp_path, attrs=None, change=None):
    return _rewritten(source, tmp_path, "bad.parquet", attrs, change)


def circle(tmp_path):
    """A path CSV of 40 points around the unit circle."""
    path = tmp_path / "p.csv"
    t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
    pd.DataFrame({"x": np.cos(t), "y": np.sin(t)}).to_csv(path, index=False)
    return path


def _set(column, row, value):
    def change(df):
        df = df.copy()
        df[column] = df[column].astype(float)
        df.loc[row, column] = value
        return df
    return change


@pytest.mark.parametrize("attrs, change, message", [
    # the metadata says 2 harmonics while the columns hold 8
    ({"harmonics": 2}, None, "not an atlas of 2 harmonics, as its metadata says: it also has the "
                             "column(s) 'fd+3', 'fd-3', 'fd+4', 'fd-4' and 8 more"),
    (None, lambda df: df.assign(extra=1.0), "not an atlas of 8 harmonics, as its metadata says: "
                                            "it also has the column(s) 'extra'"),
    (None, _set("crank", 3, -0.5), "column 'crank': expected lengths from 1e-09 m to 1e+09 m, got "
                                   "-0.5 in row 3"),
    (None, _set("rocker", 0, 0.0), "column 'rocker': expected lengths from 1e-09 m to 1e+09 m, got "
                                   "0.0 in row 0"),
    (None, _set("ground", 5, 1e300), "column 'ground': expected lengths from 1e-09 m to 1e+09 m, got "
                                     "1e+300 in row 5"),
    (None, _set("coupler_point_along", 1, -1e10), "column 'coupler_point_along': expected "
                                                  "coordinates of at most 1e+09 m in size, got "
                                                  "-10000000000.0 in row 1"),
    (None, _set("coupler", 2, math.inf), "column 'coupler': expected finite numbers, got inf in row 2"),
    (None, _set("fd-8", 4, -math.inf), "column 'fd-8': expected finite numbers, got -inf in row 4"),
    # a descriptor far away left the nearest designs' search no finite distance
    (None, _set("fd+3", 1, 1e300), "column 'fd+3': expected descriptors from 0 to 1 (magnitudes of "
                                   "harmonics over their norm), got 1e+300 in row 1"),
    (None, _set("fd-1", 0, -0.5), "column 'fd-1': expected descriptors from 0 to 1"),
    (None, lambda df: df.assign(crank="a"), "column 'crank': expected finite numbers, got 'a' in row 0"),
])
def test_an_atlas_that_is_not_what_its_metadata_says_is_refused(atlas_file, tmp_path, attrs,
                                                                change, message):
    bad = rewritten(atlas_file, tmp_path, attrs, change)
    with pytest.raises(ModelError) as info:
        kl.sweep.Atlas.from_parquet(bad)
    assert str(info.value).startswith(f"{bad}: {message}")
    assert str(info.value).endswith("; rebuild it with kinelab atlas")
    r = CliRunner().invoke(main, ["atlas", "find", str(bad), str(circle(tmp_path))])
    assert r.exit_code == 2 and r.stderr == f"kinelab: error: {info.value}\n"


def test_an_atlas_with_no_rows_is_read_and_said_empty_by_find(atlas_file, tmp_path):
    bad = rewritten(atlas_file, tmp_path, change=lambda df: df.iloc[:0])
    assert len(kl.sweep.Atlas.from_parquet(bad)) == 0
    r = CliRunner().invoke(main, ["atlas", "find", str(bad), str(circle(tmp_path))])
    assert r.exit_code == 2
    assert r.stderr == (f"kinelab: error: {bad}: it holds no design that turns its crank fully; "
                        "build it from more or other designs\n")


def test_a_table_that_unpacks_beyond_the_memory_budget_is_refused_before_it_is(tmp_path):
    """A column of one value compresses to a few bytes; its metadata says what it unpacks to."""
    path = tmp_path / "bomb.parquet"
    pd.DataFrame({"ground": np.ones(1_000_000)}).to_parquet(path)
    assert path.stat().st_size < 100_000
    kl.memory_budget("4M")
    with pytest.raises(MemoryBudgetError, match=r"bomb\.parquet: reading it \(.* unpacking to "
                                                r"7\.63 MiB\) would take about"):
        kl.sweep.read_parquet(path)


def test_a_parquet_file_that_is_not_one_is_said_so(tmp_path):
    path = tmp_path / "d.parquet"
    path.write_bytes(b"PAR1" + b"\x00" * 100 + b"PAR1")
    with pytest.raises(ModelError, match=r"d\.parquet: cannot read a table: not a Parquet file "):
        kl.sweep.read_parquet(path)


def _invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_a_parquet_design_table_is_read_within_bounds(tmp_path):
    path = tmp_path / "d.parquet"
    pd.DataFrame({"ground": [3.0], "crank": [1.0], "coupler": [3.0], "rocker": [2.5]}).to_parquet(path)
    r = _invoke("sweep", "fourbar", path, "-o", tmp_path / "s.csv")
    assert r.exit_code == 0, r.output
    r = _invoke("--memory-budget", "1K", "sweep", "fourbar", path, "-o", tmp_path / "s.csv")
    assert r.exit_code == 2 and r.stderr.startswith(f"kinelab: error: {path}: reading it (")


@pytest.mark.parametrize("args, option", [
    (["sweep", "fourbar", "--sobol", "0"], "--sobol"),
    (["sweep", "fourbar", "--random", "-3"], "--random"),
    (["sweep", "fourbar", "--sobol", "1" + "0" * 12], "--sobol"),
    (["sweep", "fourbar", "--sobol", "4", "--chunk-size", "0"], "--chunk-size"),
    (["sweep", "fourbar", "--sobol", "4", "--seed", "-1"], "--seed"),
    (["sweep", "fourbar", "--sobol", "4", "--seed", str(2 ** 32)], "--seed"),
    (["atlas", "find", "a.parquet", "p.csv", "-k", "0"], "-k"),
    (["atlas", "find", "a.parquet", "p.csv", "-k", "1" + "0" * 30], "-k"),
])
def test_counts_are_refused_by_their_options(args, option):
    r = _invoke(*args)
    assert r.exit_code == 2 and r.stderr.count("\n") == 1, r.output
    assert r.stderr.startswith(f"kinelab: error: Invalid value for '{option}'"), r.stderr


def test_errors_about_a_table_name_it(tmp_path):
    designs = tmp_path / "d.csv"
    designs.write_text("ground,crank\n3,1\n")
    r = _invoke("sweep", "fourbar", designs, "-o", tmp_path / "s.csv")
    assert r.stderr == (f"kinelab: error: {designs}: designs: missing column(s) 'coupler', "
                        "'rocker' of family 'fourbar'; add them to the table\n")
    r = _invoke("atlas", "build", designs, "-o", tmp_path / "a.parquet")
    assert r.exit_code == 2 and r.stderr.startswith(f"kinelab: error: {designs}: designs: missing")
    designs.write_text("ground,crank,coupler,rocker\n3,1,3,2.5\n")
    r = _invoke("sweep", "fourbar", designs, "--metrics", "descriptors", "-o", tmp_path / "s.csv")
    assert r.exit_code == 2 and r.stderr.startswith(f"kinelab: error: {designs}: metrics: "
                                                    "'descriptors' needs the family's coupler point")


def test_errors_about_a_family_file_name_it(tmp_path):
    r = _invoke("sweep", "examples/fivebar.toml", "--sobol", 4, "--range", "A.x=0:0.01",
                "-o", tmp_path / "s.csv")
    assert r.exit_code == 2
    assert r.stderr.startswith("kinelab: error: examples/fivebar.toml: family: the mechanisms of "
                               "'five-bar' have 2 inputs")


def test_errors_about_a_path_name_it(atlas_file, tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("x,y\n0,0\n1,0\n")
    r = _invoke("atlas", "find", atlas_file, path)
    assert r.exit_code == 2
    assert r.stderr.startswith(f"kinelab: error: {path}: path: expected more than 16 finite points")
    path.write_text("x,y\n0,0\n1,\n")
    r = _invoke("atlas", "find", atlas_file, path)
    assert r.stderr == (f"kinelab: error: {path}: line 3, column 'y': expected a finite number, "
                        "got nothing; write it in decimal or scientific notation in ASCII digits "
                        "(1000, -0.5, 1.5e3), or remove the row\n")
