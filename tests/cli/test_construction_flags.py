"""kinelab polygons --construction, centres --steps and differentiate --construction: the
files written, their numbers the library's, both languages; bad input is one line, exit 2,
and nothing written."""
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
CRANK_ROCKER = str(ROOT / "examples" / "crank_rocker.toml")
SLOTTED = str(ROOT / "examples" / "slotted_link.toml")
OFFSET = str(ROOT / "examples" / "offset_slider_crank.toml")


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def one_line_error(result, *words):
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinelab: error: "), result.output
    for w in words:
        assert w in lines[0], lines[0]


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_polygons_construction_writes_each_velocity_image(tmp_path, lang):
    result = run("polygons", CRANK_ROCKER, "--at", "30", "--construction", "--lang", lang,
                 "--out", tmp_path, "--format", "png", "--format", "svg")
    assert result.exit_code == 0, result.output
    for fmt in ("png", "svg"):
        assert (tmp_path / f"crank_rocker_velocity_image_coupler.{fmt}").stat().st_size > 0
        assert (tmp_path / f"crank_rocker_velocity_polygon.{fmt}").stat().st_size > 0
    svg = (tmp_path / "crank_rocker_velocity_image_coupler.svg").read_text()
    assert ("semelhante" if lang == "pt" else "similar") in svg


def test_polygons_without_construction_writes_no_image(tmp_path):
    result = run("polygons", CRANK_ROCKER, "--at", "30", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    assert not list(tmp_path.glob("*velocity_image*"))


def test_polygons_construction_needs_a_three_point_link(tmp_path):
    result = run("polygons", OFFSET, "--at", "30", "--construction", "--out", tmp_path)
    one_line_error(result, "--construction: expected a moving link with three or more points")
    assert not list(tmp_path.iterdir())


@pytest.mark.parametrize("model, base", [(CRANK_ROCKER, "crank_rocker"), (SLOTTED, "slotted_link")])
def test_centres_steps(tmp_path, model, base):
    result = run("centres", model, "--at", "30", "--steps", "--lang", "pt", "--out", tmp_path,
                 "--format", "svg")
    assert result.exit_code == 0, result.output
    svg = (tmp_path / f"{base}_kennedy_steps.svg").read_text()
    assert "diagrama circular" in svg and "teorema de Kennedy" in svg
    assert (tmp_path / f"{base}_centres.svg").stat().st_size > 0


@pytest.mark.parametrize("args, words", [
    (("--lang", "fr"), ["--lang", "'fr' is not one of 'en', 'pt'"]),
    (("--steps", "--at", "90deg"), []),
])
def test_centres_steps_refusals(tmp_path, args, words):
    if args[-1] == "90deg":
        model = tmp_path / "toggle.toml"
        kl.io.save(kl.mechanisms.slider_crank(crank=1.0, rod=1.0), model)
        result = run("centres", model, *args, "--out", tmp_path)
        one_line_error(result, "change point")
        assert not list(tmp_path.glob("*.png"))
        return
    result = run("centres", CRANK_ROCKER, "--at", "30", "--steps", *args, "--out", tmp_path)
    one_line_error(result, *words)
    assert not list(tmp_path.iterdir())


def write_curve(path, t, x, header="t [s],x [mm]"):
    path.write_text(header + "\n" + "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(t, x)))
    return path


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_differentiate_construction(tmp_path, lang):
    t = np.linspace(0.0, 2 * np.pi / 10.0, 241)
    sol = kl.analyze(kl.mechanisms.slider_crank(crank=0.1, rod=0.3), q=10.0 * t, qd=10.0)
    x = 1000.0 * sol.slide("slide")
    data = write_curve(tmp_path / "stroke.csv", t, x)
    result = run("differentiate", data, "--construction", "--points", "11", "--lang", lang,
                 "--out", tmp_path, "--format", "svg")
    assert result.exit_code == 0, result.output
    import pandas as pd
    table = pd.read_csv(tmp_path / "stroke_construction.csv")
    assert list(table.columns) == ["t [s]", "x [mm]", "slope [mm/s]", "intercept [mm]",
                                   "dx/dt [mm/s]"]
    tc = kl.kinematics.tangent_construction(t, x, points=11)
    np.testing.assert_allclose(table["dx/dt [mm/s]"], tc.derivative, rtol=1e-12)
    np.testing.assert_allclose(table["intercept [mm]"], tc.intercepts, rtol=1e-12)
    # within the chord's truncation error of the exact velocity
    half = tc.every * (t[1] - t[0])
    bound = 1000.0 * 0.1 * 10.0 ** 3 * (1 + 4 * 0.1 / 0.3) * half ** 2 / 6
    exact = 1000.0 * sol.slide_velocity("slide")[tc.index]
    assert np.all(np.abs(table["dx/dt [mm/s]"] - exact) <= bound)
    svg = (tmp_path / "stroke_construction.svg").read_text()
    assert ("distância polar" if lang == "pt" else "polar distance") in svg
    assert (tmp_path / "stroke_derivatives.svg").stat().st_size > 0


def test_differentiate_construction_options(tmp_path):
    t = np.linspace(0.0, 1.0, 101)
    data = write_curve(tmp_path / "c.csv", t, np.sin(3 * t))
    result = run("differentiate", data, "--construction", "--polar-distance", "0.25",
                 "--tangent", "fitted", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    import pandas as pd
    table = pd.read_csv(tmp_path / "c_construction.csv")
    assert len(table) == 12
    np.testing.assert_allclose(table["intercept [mm]"], 0.25 * table["slope [mm/s]"], rtol=1e-12)
    d = kl.solvers.differentiate(t, np.sin(3 * t))
    k = 100 // 13
    np.testing.assert_allclose(table["dx/dt [mm/s]"], d.velocity[k * np.arange(1, 13)], rtol=1e-12)


@pytest.mark.parametrize("args, words", [
    (("--points", "3"), ["--points: only with --construction"]),
    (("--polar-distance", "1"), ["--polar-distance: only with --construction"]),
    (("--tangent", "fitted"), ["--tangent: only with --construction"]),
    (("--construction", "--points", "100"), ["c.csv", "--points: expected at most 18 points for 20 samples"]),
    (("--construction", "--points", "0"), ["--points", "0 is not in the range x>=1"]),
    (("--construction", "--polar-distance", "-1"), ["--polar-distance", "above 0"]),
    (("--construction", "--polar-distance", "nan"), ["--polar-distance", "above 0"]),
    (("--construction", "--tangent", "eye"), ["--tangent", "'eye' is not one of"]),
    (("--construction", "--lang", "es"), ["--lang", "'es' is not one of 'en', 'pt'"]),
])
def test_differentiate_construction_refusals(tmp_path, args, words):
    data = write_curve(tmp_path / "c.csv", np.arange(20.0), np.arange(20.0) ** 2)
    out = tmp_path / "out"
    result = run("differentiate", data, *args, "--out", out)
    one_line_error(result, *words)
    assert not out.exists() or not list(out.iterdir())
