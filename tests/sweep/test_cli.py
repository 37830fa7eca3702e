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
    assert list(table.columns) == ["ground[m]", "crank[m]", "coupler[m]", "rocker[m]",
                                   "assembles", "grashof", "transmission_min[deg]",
                                   "transmission_max[deg]", "time_ratio", "swing[deg]"]
    designs = kl.sweep.sobol(64, seed=0, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4), rocker=(1, 4))
    # each row leads back to its design
    assert np.array_equal(table[[f"{c}[m]" for c in designs]].to_numpy(), designs.to_numpy())
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
    assert list(table.columns) == ["A.y[m]", "A.x[m]", "swing[m]", "peak_torque[N m]"]
    assert table["A.y[m]"].tolist() == [0.05, 0.06]
    assert table["swing[m]"].tolist() == pytest.approx([0.1, 0.12], abs=1e-10)


def test_mass_columns_are_labelled_with_their_units(tmp_path):
    designs = tmp_path / "d.csv"
    pd.DataFrame({"crank.mass": [3.0, 1.5], "crank.inertia": [0.004, 0.002]}).to_csv(designs, index=False)
    r = invoke("sweep", "examples/engine.toml", designs, "--metrics", "peak_torque",
               "--output", "slide", "-o", tmp_path / "e.csv")
    assert r.exit_code == 0, r.output
    table = pd.read_csv(tmp_path / "e.csv")
    assert list(table.columns) == ["crank.mass[kg]", "crank.inertia[kg m^2]", "peak_torque[N m]"]
    assert table["peak_torque[N m]"][1] < table["peak_torque[N m]"][0]


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
    # its error: the largest distance from all 60 points of the file to the coupler curve
    best = a.refine(path, k=2)[0]                    # the same search, seeded: the same linkage
    assert best.path_errors.shape == (60,)
    assert f"its coupler curve passes within {best.max_error:.3g} m of all 60 points " in lines[-1]
    assert lines[-1].endswith(", valid")


def test_atlas_find_reports_the_distance_to_every_point_of_the_file(tmp_path):
    """24 jittered points of a coupler curve, 100 m wide: the line gives the largest distance
    from every one of them to the refined linkage's coupler curve, as the Python result does
    (tests/sweep/test_atlas.py checks that against the engine's curve)."""
    atlas = tmp_path / "atlas.parquet"
    assert invoke("atlas", "build", "--sobol", 256, "--seed", 1, *RANGES, *POINT,
                  "-o", atlas).exit_code == 0
    a = kl.sweep.Atlas.from_parquet(atlas)
    row = a.table.iloc[2]
    fb = kl.mechanisms.fourbar(*(float(row[c]) for c in ("ground", "crank", "coupler", "rocker")),
                               coupler_point=(float(row["coupler_point_along"]),
                                              float(row["coupler_point_perpendicular"])))
    P = kl.analyze(fb, np.linspace(0, 2 * np.pi, 24, endpoint=False)).position("P")
    P = (P - P.mean(axis=0)) / np.ptp(P, axis=0).max() * 100.0
    P = P * [1.0, 1.4] + np.random.default_rng(3).normal(scale=3.0, size=P.shape)
    pd.DataFrame(P, columns=["x", "y"]).to_csv(tmp_path / "path.csv", index=False)
    r = invoke("atlas", "find", atlas, tmp_path / "path.csv", "-k", 3, "--refine")
    assert r.exit_code == 0, r.output
    best = a.refine(P, k=3)[0]
    size = np.hypot(*np.ptp(P, axis=0))
    line = r.output.splitlines()[-1]
    share = 100 * best.max_error / size
    assert (f"passes within {best.max_error:.3g} m of all 24 points of {tmp_path / 'path.csv'} "
            f"(the largest distance, {share:.3g} % of the path's size)") in line
    assert best.max_error == best.path_errors.max() and best.max_error > 0.01 * size
    mu = np.degrees(best.min_transmission_angle)
    assert f"min transmission {mu:.3g} deg (meets the 30 deg limit)" in line


def one_line_error(r, *fragments):
    assert r.exit_code == 2, r.output
    lines = r.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: "), r.output
    for f in fragments:
        assert f in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize("command", [["sweep", "fourbar"], ["atlas", "build"]])
@pytest.mark.parametrize("samples", ["100000000", "99999999999999999999"])
def test_samples_are_capped_as_in_other_commands(command, samples, tmp_path):
    out = tmp_path / "s.parquet"
    r = invoke(*command, "--sobol", 16, *RANGES, "--samples", samples, "-o", out)
    one_line_error(r, "--samples", "1000000")
    assert not out.exists()


def test_samples_beyond_the_memory_budget_are_refused_before_the_work(tmp_path):
    r = invoke("--memory-budget", "100M", "sweep", "fourbar", "--sobol", 16, *RANGES,
               "--samples", 1_000_000, "-o", tmp_path / "s.csv")
    one_line_error(r, "1,000,000 samples", "memory budget of 100 MiB", "fewer samples")


@pytest.mark.parametrize("command", [["sweep", "fourbar"], ["atlas", "build"]])
@pytest.mark.parametrize("spec", ["crank=1:2:nan", "crank=1:2:inf", "crank=1:2:1e400",
                                  "crank=-inf:2:3", "crank=1:nan"])
def test_ranges_must_be_finite(command, spec, tmp_path):
    r = invoke(*command, "--grid", "--range", spec, "-o", tmp_path / "s.parquet")
    one_line_error(r, "--range: expected finite numbers", repr(spec))


@pytest.mark.parametrize("ranges, message", [
    (["ground=1:4:10000000", "crank=0.3:1:1000"], "a grid of 10,000,000,000 designs would take about"),
    (["ground=1:4:1e300", "crank=0.3:1:1e300"], "a grid of 1e+600 designs would take more bytes"),
])
def test_a_grid_beyond_the_budget_is_refused_by_its_product(ranges, message, tmp_path):
    args = [a for spec in ranges for a in ("--range", spec)]
    r = invoke("sweep", "fourbar", "--grid", *args, "-o", tmp_path / "s.csv")
    one_line_error(r, message, "memory budget")


@pytest.fixture
def engine_designs(tmp_path):
    path = tmp_path / "eng1.csv"
    path.write_text("A.y\n0.05\n")
    return path


@pytest.mark.parametrize("speed, message", [
    ("1e160", "speed: expected at most 1e+100 rad/s in size"),
    ("-1e101", "speed: expected at most 1e+100 rad/s in size"),
    # what is not a number by the one rule of numbers is refused by the option itself
    ("nan", "'--speed': expected a finite number in decimal or scientific notation"),
    ("inf", "'--speed': expected a finite number in decimal or scientific notation"),
    ("1_000", "'--speed': expected a finite number in decimal or scientific notation"),
    ("\uff11", "'--speed': expected a finite number in decimal or scientific notation"),
])
def test_speed_is_bounded(engine_designs, speed, message, tmp_path):
    out = tmp_path / "e.csv"
    r = invoke("sweep", "examples/engine.toml", engine_designs, "--metrics", "peak_torque",
               "--speed", speed, "-o", out)
    one_line_error(r, message)
    assert not out.exists()


def test_peak_torque_at_the_largest_speed_is_finite_and_scales_with_its_square(engine_designs, tmp_path):
    # At 1e50 rad/s and more, gravity is negligible: the torque is c * speed^2 exactly.
    values = []
    for speed in ("1e50", "1e100"):
        out = tmp_path / f"e{speed}.csv"
        r = invoke("sweep", "examples/engine.toml", engine_designs, "--metrics", "peak_torque",
                   "--speed", speed, "-o", out)
        assert r.exit_code == 0, r.output
        values.append(pd.read_csv(out)["peak_torque[N m]"][0])
    assert np.isfinite(values).all()
    assert values[1] / values[0] == pytest.approx(1e100, rel=1e-12)
    assert values[1] == pytest.approx(2.0944e197, rel=1e-4)      # 2.0944e-3 N m s^2 x speed^2


def test_sobol_of_any_size_leaves_no_library_warning(tmp_path):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")          # a warning would fail the command
        r = invoke("sweep", "fourbar", "--sobol", 10, *RANGES, "-o", tmp_path / "s.csv")
    assert r.exit_code == 0, r.output
    assert r.output.strip().splitlines() == [r.output.strip().splitlines()[-1]]
    assert r.output.startswith("10 designs in")


def test_rows_with_nan_leave_no_runtime_warning(tmp_path):
    import warnings

    designs = tmp_path / "d.csv"
    designs.write_text("ground,crank,coupler,rocker,coupler_point_along,coupler_point_perpendicular\n"
                       "3,1,3,2.5,1,0.5\n,1,3,2.5,1,0.5\n3,1,3,2.5,,\n2,1,1,2,1,1\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = invoke("sweep", "fourbar", designs, "--metrics", ",".join(kl.sweep.METRICS[:-1]),
                   "--degrees", "-o", tmp_path / "s.csv")
    assert r.exit_code == 0, r.output
    assert "design 1: ground: expected a length from 1e-09 m to 1e+09 m, got nan" in r.output


@pytest.mark.parametrize("command, out, accepted", [
    (["sweep", "fourbar"], "sw.txt", ".parquet or .csv"),
    (["sweep", "fourbar"], "sw", ".parquet or .csv"),
    (["atlas", "build"], "x.csv", ".parquet,"),
    (["atlas", "build"], "x.txt", ".parquet,"),
])
def test_unknown_output_suffixes_are_refused(command, out, accepted, tmp_path):
    path = tmp_path / out
    r = invoke(*command, "--sobol", 4, *RANGES, *POINT, "-o", path)
    line = one_line_error(r, "--out: expected a file name ending in ")
    assert line.split("ending in ")[1].startswith(accepted.rstrip(","))
    assert not path.exists()


@pytest.mark.parametrize("command", [["sweep", "fourbar"], ["atlas", "build"]])
def test_branch_is_checked_the_same_way(command, tmp_path):
    r = invoke(*command, "--sobol", 4, *RANGES, *POINT, "--branch", "weird", "-o", tmp_path / "s.parquet")
    one_line_error(r, "branch: expected one of 'open', 'crossed', got 'weird'")


def test_crossed_branch_sweeps_the_crossed_four_bar(tmp_path):
    out = tmp_path / "s.csv"
    r = invoke("sweep", "fourbar", "--sobol", 16, *RANGES, "--branch", "crossed", "-o", out)
    assert r.exit_code == 0, r.output
    designs = kl.sweep.sobol(16, seed=0, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4), rocker=(1, 4))
    df = kl.sweep.run(kl.sweep.family("fourbar", branch="crossed"), designs)
    assert np.allclose(pd.read_csv(out)["swing[rad]"], df["swing"], rtol=1e-12, equal_nan=True)


def test_a_design_off_the_models_places_says_what_to_do_on_the_command_line(tmp_path):
    r = invoke("sweep", "examples/crank_rocker.toml", "--random", 3, "--range", "B.x=1:2",
               "-o", tmp_path / "s.csv")
    line = one_line_error(r, "examples/crank_rocker.toml: designs: the design (B.x = ",
                          "'coupler' misses its declared length or place by",
                          "kinelab check examples/crank_rocker.toml")
    assert "kl." not in line and "assemble(" not in line


@pytest.fixture(scope="module")
def atlas_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("atlas") / "a.parquet"
    r = invoke("atlas", "build", "--sobol", 256, *RANGES, *POINT, "-o", path)
    assert r.exit_code == 0, r.output
    return path


def circle_file(path, scale, n=50):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    pd.DataFrame(scale * np.column_stack([np.cos(t), np.sin(t)]), columns=["x", "y"]).to_csv(path, index=False)
    return path


def test_atlas_find_is_scale_invariant(atlas_file, tmp_path):
    found = []
    for scale in (1.0, 1e300, 1.5e307):
        r = invoke("atlas", "find", atlas_file, circle_file(tmp_path / "c.csv", scale), "-k", 3)
        assert r.exit_code == 0, r.output
        found.append(r.output)
    assert found[1] == found[0] and found[2] == found[0]


@pytest.mark.parametrize("points, message", [
    (np.ones((50, 2)), "path: its points span 0 m"),
    (None, "path: its points span 2e-300 m"),
])
def test_atlas_find_refuses_a_path_with_no_extent(atlas_file, points, message, tmp_path):
    path = tmp_path / "p.csv"
    if points is None:
        circle_file(path, 1e-300)
    else:
        pd.DataFrame(points, columns=["x", "y"]).to_csv(path, index=False)
    r = invoke("atlas", "find", atlas_file, path)
    one_line_error(r, message, "at least 1e-09 m across")


def test_atlas_find_refine_refuses_a_path_beyond_the_models_lengths(atlas_file, tmp_path):
    r = invoke("atlas", "find", atlas_file, circle_file(tmp_path / "c.csv", 1e300), "--refine")
    one_line_error(r, "path: a linkage through it needs points within 1e+09 m")
