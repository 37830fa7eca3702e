"""kinelab polygons, centres, differentiate and animate --centres/--velocities: the numbers
printed are the library's, in the file's units; bad input is one line and exit status 2."""
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
CRANK_ROCKER = str(ROOT / "examples" / "crank_rocker.toml")
SLOTTED = str(ROOT / "examples" / "slotted_link.toml")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def table(output: str) -> dict[str, list[float]]:
    """{row name: numbers} of the printed tables (first occurrence of each name)."""
    rows = {}
    for line in output.splitlines():
        parts = line.split()
        if len(parts) >= 3 and line.startswith("  "):
            try:
                rows.setdefault(parts[0], [float(p) for p in parts[-3:]])
            except ValueError:
                pass
    return rows


def test_polygons_prints_the_library_numbers_in_file_units(tmp_path):
    result = run("polygons", SLOTTED, "--at", "60", "--out", tmp_path, "--format", "png",
                 "--format", "svg")
    assert result.exit_code == 0, result.output
    mf = kl.io.ModelFile.read(SLOTTED)
    m = mf.mechanism
    sol = kl.analyze(m, q=np.radians(60.0), qd=m.inputs[0].speed, qdd=m.inputs[0].acceleration)
    rows = table(result.output)
    to_file = 1.0 / mf.units.length_scale
    ap = kl.kinematics.acceleration_polygon(sol)
    np.testing.assert_allclose(rows["V_A"][:2], sol.velocity("A") * to_file, rtol=1e-5)
    np.testing.assert_allclose(rows["A^c_AA'"][:2], ap.parts["A", "A@lever"]["coriolis"] * to_file,
                               rtol=1e-5)
    np.testing.assert_allclose(rows["A^s_AA'"][:2], ap.parts["A", "A@lever"]["sliding"] * to_file,
                               rtol=1e-5)
    assert "A' is the point of lever under A" in result.output
    for kind in ("velocity_polygon", "acceleration_polygon"):
        for fmt in ("png", "svg"):
            assert (tmp_path / f"slotted_link_{kind}.{fmt}").stat().st_size > 0


def test_centres_and_centrodes(tmp_path):
    result = run("centres", CRANK_ROCKER, "--at", "30", "--centrodes", "--samples", "73",
                 "--out", tmp_path)
    assert result.exit_code == 0, result.output
    mf = kl.io.ModelFile.read(CRANK_ROCKER)
    sol = kl.analyze(mf.mechanism, q=np.radians(30.0))
    rows = {line.split()[0]: line.split() for line in result.output.splitlines()
            if line.startswith("  O")}
    ic = kl.kinematics.instant_centers(sol)
    to_file = 1.0 / mf.units.length_scale
    np.testing.assert_allclose([float(v) for v in rows["O13"][-2:]],
                               ic["ground", "coupler"].position * to_file, rtol=1e-5)
    assert rows["O13"][2:4] == ["Kennedy", "(1)"] and rows["O24"][2:4] == ["Kennedy", "(2)"]
    assert (tmp_path / "crank_rocker_centres.png").stat().st_size > 0
    assert (tmp_path / "crank_rocker_centrodes_coupler.png").stat().st_size > 0


def test_centre_at_infinity_is_printed_as_a_direction(tmp_path):
    result = run("centres", SLOTTED, "--at", "60", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    line = next(x for x in result.output.splitlines() if x.startswith("  O34"))
    assert "joint slot" in line and "at infinity" in line and "direction" in line


def write_curve(path, t, x, header="t [s],x [mm]"):
    path.write_text(header + "\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t, x)))
    return path


def test_differentiate_writes_derivatives_holding_the_exact_ones(tmp_path):
    t = np.sort(np.random.default_rng(5).uniform(0.0, 2 * np.pi / 10.0, 241))
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    x = 1000.0 * sol.slide("slide") + 0.01 * np.random.default_rng(6).standard_normal(t.size)
    data = write_curve(tmp_path / "stroke.csv", t, x)
    result = run("differentiate", data, "--out", tmp_path)
    assert result.exit_code == 0, result.output
    import re
    noise = float(re.search(r"noise about ([0-9.e-]+) mm", result.output).group(1))
    assert 0.007 < noise < 0.013
    import pandas as pd
    table = pd.read_csv(tmp_path / "stroke_derivatives.csv")
    assert list(table.columns) == ["t [s]", "x [mm]", "x.smoothed [mm]", "dx/dt [mm/s]",
                                   "dx/dt.error [mm/s]", "d2x/dt2 [mm/s^2]", "d2x/dt2.error [mm/s^2]"]
    exact_v = 1000.0 * sol.slide_velocity("slide")
    exact_a = 1000.0 * sol.slide_acceleration("slide")
    assert np.all(np.abs(table["dx/dt [mm/s]"] - exact_v) <= table["dx/dt.error [mm/s]"])
    assert np.all(np.abs(table["d2x/dt2 [mm/s^2]"] - exact_a) <= table["d2x/dt2.error [mm/s^2]"])
    assert (tmp_path / "stroke_derivatives.png").stat().st_size > 0


@pytest.mark.parametrize("rows, match", [
    ("t,x\n" + "".join(f"{k},{k}\n" for k in range(5)), r"expected at least 15 samples, got 5"),
    ("t,x\n" + "".join(f"{k},{k}\n" for k in range(20)) + "21,abc\n",
     r"line 22, column 'x': expected a finite number, got 'abc'"),
    ("t,x\n" + "".join(f"{k},{k}\n" for k in range(20)) + "21,nan\n",
     r"line 22, column 'x': expected a finite number, got 'nan'"),
    ("t,x\n" + "".join(f"{k},{k}\n" for k in range(20)) + "3,1\n",
     r"line 22, column 't': expected abscissae that increase, got 3 after 19"),
    ("1,2\n3,4\n", r"line 1: expected a header row"),
    ("", r"expected a header row and samples, got an empty file"),
])
def test_differentiate_bad_data(tmp_path, rows, match):
    import re
    data = tmp_path / "bad.csv"
    data.write_text(rows)
    result = run("differentiate", data, "--out", tmp_path)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: ") and "bad.csv" in lines[0]
    assert re.search(match, lines[0]), lines[0]
    assert not list(tmp_path.glob("bad_derivatives*"))


def test_differentiate_unknown_column(tmp_path):
    data = write_curve(tmp_path / "c.csv", np.arange(20.0), np.arange(20.0) ** 2)
    result = run("differentiate", data, "--y", "z")
    assert result.exit_code == 2
    assert "y: expected a column of the file, by name or number from 1, got 'z'; the columns are 't', 'x'" \
        in result.output


def _rows(pairs):
    return "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in pairs)


@pytest.mark.parametrize("text, match", [
    ("t [s],x [mm]\n" + _rows((k * 1e-200, k) for k in range(15)),
     r"y: expected the acceleration d2y/dx2 within float64's range \(up to 1.8e\+308\), got "
     r"beyond it; express y in a larger unit or x in a smaller one$"),
    ("t [s],x [mm]\n" + _rows((k if k < 8 else 1e9 + k, k) for k in range(15)),
     r"x\[8\]: expected samples spread over each local fit, got a gap from x\[7\] = 7.0 to "
     r"x\[8\] = 1000000008.0"),
    ("t [s],x [mm]\n" + _rows((k, 1e308 * (-1) ** k) for k in range(30)),
     r"y: expected the velocity's error band within float64's range"),
    ("t [s],x [mm]\n" + _rows((k, 1e308 * (-1) ** k) for k in range(15)),
     r"y: expected the velocity's error band within float64's range"),
    ("t [parsec],x [\x1b[31mfoo]\n" + _rows((k, k * k) for k in range(20)),
     r"header: column 'x \[\\x1b\[31mfoo\]': expected printable characters in a column's name "
     r"and unit, got '\\x1b'; remove it$"),
    ("t\x07 [s],x\n" + _rows((k, k * k) for k in range(20)),
     r"header: column 't\\x07 \[s\]': expected printable characters"),
])
def test_differentiate_refuses_what_float64_cannot_hold_in_one_line(tmp_path, text, match):
    import re
    data = tmp_path / "bad.csv"
    data.write_text(text)
    result = run("differentiate", data, "--out", tmp_path)
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: ") and "bad.csv" in lines[0]
    assert re.search(match, lines[0]), lines[0]
    assert "\x1b" not in result.output and "\x07" not in result.output
    assert not list(tmp_path.glob("bad_derivatives*"))


def test_differentiate_at_any_scale_writes_finite_right_numbers(tmp_path):
    """t = 1e200 k, x = k: dx/dt = 1e-200 exactly; the data column is the file's."""
    import pandas as pd
    data = write_curve(tmp_path / "far.csv", 1e200 * np.arange(15.0), np.arange(15.0))
    result = run("differentiate", data, "--out", tmp_path)
    assert result.exit_code == 0, result.output
    table = pd.read_csv(tmp_path / "far_derivatives.csv")
    assert np.all(np.isfinite(table.to_numpy()))
    np.testing.assert_allclose(table["dx/dt [mm/s]"], 1e-200, rtol=1e-12)
    assert list(table["x [mm]"]) == list(np.arange(15.0))


def test_differentiate_scaled_sine(tmp_path):
    """x = 1e-3 sin(t / 1e6) mm, t up to 2e6 s: the velocity and acceleration against
    1e-9 cos(t / 1e6) and -1e-15 sin(t / 1e6), to the fit's own error (evenly sampled, 401
    samples, no noise: well under 1e-4 of each amplitude)."""
    import pandas as pd
    t = np.linspace(0.0, 2e6, 401)
    data = write_curve(tmp_path / "slow.csv", t, 1e-3 * np.sin(t / 1e6))
    result = run("differentiate", data, "--out", tmp_path, "--window", "21")
    assert result.exit_code == 0, result.output
    table = pd.read_csv(tmp_path / "slow_derivatives.csv")
    assert np.max(np.abs(table["dx/dt [mm/s]"] - 1e-9 * np.cos(t / 1e6))) < 1e-4 * 1e-9
    assert np.max(np.abs(table["d2x/dt2 [mm/s^2]"] + 1e-15 * np.sin(t / 1e6))) < 1e-4 * 1e-15


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_differentiate_refuses_too_many_rows_as_it_parses_them(tmp_path, monkeypatch, end):
    """Rows are counted as they are parsed, whatever ends their lines (a CR alone ends one)."""
    from kinelab.io import _curves
    monkeypatch.setattr(_curves, "MAX_SAMPLES", 100)
    data = tmp_path / "long.csv"
    data.write_bytes(("# logged\nt [s],x [mm]\n\n" + _rows((k, k) for k in range(100)))
                     .replace("\n", end).encode())
    assert run("differentiate", data, "--out", tmp_path).exit_code == 0
    data.write_bytes(("t [s],x [mm]\n" + _rows((k, k) for k in range(101))).replace("\n", end)
                     .encode())
    result = run("differentiate", data, "--out", tmp_path)
    assert result.exit_code == 2
    assert result.output == (f"kinelab: error: {data}: line 102: expected at most 100 samples, "
                             "got more; cut the curve into pieces, or keep every k-th sample\n")


@pytest.mark.parametrize("command", ["polygons", "centres"])
def test_singular_input_is_refused_in_one_line(tmp_path, command):
    model = tmp_path / "toggle.toml"
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=1.0)
    kl.io.save(sc, model)
    result = run(command, model, "--at", "90deg", "--out", tmp_path)
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    # B meets O2 at 90 deg, where the slider's two assembly modes cross
    assert len(lines) == 1 and "is a change point of dyad 'rod'-'slider'" in lines[0]
    assert not list(tmp_path.glob("*.png"))


def test_polygons_needs_at():
    result = run("polygons", CRANK_ROCKER)
    assert result.exit_code == 2 and "--at" in result.output


def test_animate_with_centres_and_velocities(tmp_path):
    result = run("animate", CRANK_ROCKER, "--centres", "--velocities", "--frames", "4",
                 "--samples", "20", "--format", "gif", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    assert (tmp_path / "crank_rocker.gif").stat().st_size > 0
