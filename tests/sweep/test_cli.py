"""``kinelab sweep`` and ``kinelab atlas``: tables with units, one-line errors, exit status 2."""
import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main

RANGES = ["--range", "ground=1:4", "--range", "crank=0.3:1", "--range", "coupler=1:4",
          "--range", "rocker=1:4"]
POINT = ["--range", "coupler_point_along=-1:2", "--range", "coupler_point_perpendicular=-1:1"]


def invoke(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def test_sweep_writes_the_library_table_with_units(tmp_path):
    out = tmp_path / "s.parquet"
    r = invoke("sweep", "fourbar", "--sobol", 64, *RANGES, "--degrees", "-o", out)
    assert r.exit_code == 0, r.output
    assert "64 designs in" in r.output
    table = pd.read_parquet(out)
    assert list(table.columns) == ["assembles", "grashof", "transmission_min[deg]",
                                   "transmission_max[deg]", "time_ratio", "swing[deg]"]
    designs = kl.sweep.sobol(64, seed=0, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4), rocker=(1, 4))
    df = kl.sweep.run("fourbar", designs)
    assert np.allclose(table["transmission_min[deg]"], np.degrees(df["transmission_min"]), equal_nan=True)
    assert table["grashof"].tolist() == df["grashof"].tolist()


def test_sweep_of_a_model_file_with_masses(tmp_path):
    designs = tmp_path / "d.csv"
    pd.DataFrame({"A.y": [0.05, 0.06], "A.x": [0.0, 0.0]}).to_csv(designs, index=False)
    r = invoke("sweep", "examples/engine.toml", designs, "--metrics", "swing,peak_torque",
               "--output", "slide", "-o", tmp_path / "e.csv")
    assert r.exit_code == 0, r.output
    table = pd.read_csv(tmp_path / "e.csv")
    assert list(table.columns) == ["swing[m]", "peak_torque[N m]"]
    assert table["swing[m]"].tolist() == pytest.approx([0.1, 0.12], abs=1e-10)


def test_bad_rows_are_warnings(tmp_path):
    designs = tmp_path / "d.csv"
    pd.DataFrame({"ground": [3.0, 3.0], "crank": [1.0, -1.0], "coupler": [3.0, 3.0],
                  "rocker": [2.5, 2.5]}).to_csv(designs, index=False)
    r = CliRunner().invoke(main, ["sweep", "fourbar", str(designs), "-o", str(tmp_path / "s.csv")])
    assert r.exit_code == 0
    assert "kinelab: warning: design 1: crank: expected a length from 1e-09 m to 1e+09 m, got -1" in r.output


@pytest.mark.parametrize("args, message", [
    (["sweep", "fourbarr", "--sobol", "4", "--range", "ground=1:2"], "FAMILY: expected a catalogue kind"),
    (["sweep", "fourbar", "--sobol", "4", "--range", "ground=1"], "--range: expected NAME=LOW:HIGH"),
    (["sweep", "fourbar", "--sobol", "4", "--grid", "--range", "ground=1:2"], "give exactly one of"),
    (["sweep", "fourbar", "--sobol", "4", *RANGES, "--metrics", "speed"], "metrics: expected one of"),
    (["sweep", "fourbar", "missing.csv"], "missing.csv: no such file"),
    (["sweep", "fourbar", "--sobol", "4", *RANGES, "--scheduler", "tcp://127.0.0.1:9"],
     "scheduler: cannot reach 'tcp://127.0.0.1:9'"),
    (["atlas", "find", "nothing.parquet", "path.csv"], "cannot read an atlas"),
])
def test_errors_are_one_line_with_status_2(args, message, tmp_path):
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: ") and message in lines[0]


def test_atlas_build_and_find(tmp_path):
    atlas = tmp_path / "atlas.parquet"
    r = invoke("atlas", "build", "--sobol", 512, *RANGES, *POINT, "-o", atlas)
    assert r.exit_code == 0, r.output
    a = kl.sweep.Atlas.from_parquet(atlas)
    row = a.table.iloc[3]
    fb = kl.mechanisms.fourbar(*(float(row[c]) for c in ("ground", "crank", "coupler", "rocker")),
                               coupler_point=(float(row["coupler_point_along"]),
                                              float(row["coupler_point_perpendicular"])))
    path = kl.analyze(fb, np.linspace(0, 2 * np.pi, 60, endpoint=False)).position("P") + [2.0, 1.0]
    pd.DataFrame(path, columns=["x", "y"]).to_csv(tmp_path / "path.csv", index=False)
    r = invoke("atlas", "find", atlas, tmp_path / "path.csv", "-k", 2, "--refine")
    assert r.exit_code == 0, r.output
    lines = r.output.splitlines()
    assert lines[1].split()[0] == "3" and lines[-1].startswith("refined: A0 = ")
