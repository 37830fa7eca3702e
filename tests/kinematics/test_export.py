"""Results export: named columns item.quantity[unit], units at the edge only, atomic CSV."""
import csv
import math
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError

MM, DEG = 1e-3, math.pi / 180          # SI value of one mm, one degree


@pytest.fixture(scope="module")
def sol():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.2)
    return kl.analyze(sc, q=np.radians([10.0, 50.0, 90.0]), qd=2.0, qdd=0.5)


def test_columns_have_units_and_values(sol):
    cols = sol.columns()
    assert cols["rod.angle[rad]"] == pytest.approx(sol.angle("rod"), rel=0, abs=0)
    assert cols["rod.K[rad/rad]"] == pytest.approx(sol.K("rod"), rel=0, abs=0)
    assert cols["slide.slide[m]"] == pytest.approx(sol.slide("slide"), rel=0, abs=0)
    assert cols["slide.L[m/rad^2]"] == pytest.approx(sol.L("slide"), rel=0, abs=0)
    assert cols["B.ax[m/s^2]"] == pytest.approx(sol.acceleration("B")[:, 0], rel=0, abs=0)
    assert cols["B.y.K[m/rad]"] == pytest.approx(sol.K("B")[:, 1], rel=0, abs=0)
    assert cols["jO2.q[rad]"] == pytest.approx(np.radians([10.0, 50.0, 90.0]), rel=1e-15)
    assert cols["singular"].dtype == bool
    assert all(len(v) == 3 for v in cols.values())


def test_column_names_follow_the_rule(sol):
    # item.quantity[unit]; no spaces; only det_J, singularity, singular go without a unit
    rule = re.compile(r"^[^\s\[\]]+\[[^\s\[\]]+\]$")
    for units in (None, {"length": "mm", "angle": "deg"}, {"length": "in"}):
        names = list(sol.columns(units=units))
        bare = [n for n in names if not rule.match(n)]
        assert bare == ["det_J", "singularity", "singular"], bare


def test_degrees_only_change_angle_units(sol):
    deg = sol.columns(degrees=True)
    f = 180 / np.pi
    assert deg["rod.angle[deg]"] == pytest.approx(sol.angle("rod") * f, rel=1e-15)
    assert deg["rod.omega[deg/s]"] == pytest.approx(sol.omega("rod") * f, rel=1e-15)
    assert deg["rod.K[deg/deg]"] == pytest.approx(sol.K("rod"), rel=1e-15)      # dimensionless
    assert deg["slide.K[m/deg]"] == pytest.approx(sol.K("slide") / f, rel=1e-15)
    assert deg["slide.L[m/deg^2]"] == pytest.approx(sol.L("slide") / f ** 2, rel=1e-15)
    assert deg["jO2.q[deg]"] == pytest.approx([10.0, 50.0, 90.0], rel=1e-15)
    assert deg["B.x[m]"] == pytest.approx(sol.position("B")[:, 0], rel=0, abs=0)
    assert list(deg) == list(sol.columns(units={"angle": "deg"}))


def test_mm_deg_columns_are_the_si_columns_times_the_exact_factors(sol):
    si = sol.columns()
    out = sol.columns(units={"length": "mm", "angle": "deg"})
    assert len(out) == len(si)
    # each SI column, by its SI unit, and the factor worked by hand: length and angle
    # powers of (1 / MM) and (1 / DEG)
    factors = {"m": 1 / MM, "m/s": 1 / MM, "m/s^2": 1 / MM, "rad": 1 / DEG, "rad/s": 1 / DEG,
               "rad/s^2": 1 / DEG, "rad/rad": 1.0, "m/rad": DEG / MM, "m/rad^2": DEG ** 2 / MM}
    names = {"m": "mm", "m/s": "mm/s", "m/s^2": "mm/s^2", "rad": "deg", "rad/s": "deg/s",
             "rad/s^2": "deg/s^2", "rad/rad": "deg/deg", "rad/rad^2": "deg/deg^2",
             "m/rad": "mm/deg", "m/rad^2": "mm/deg^2"}
    factors["rad/rad^2"] = DEG
    for name, values in si.items():
        if "[" not in name:
            np.testing.assert_array_equal(out[name], values)
            continue
        stem, unit = name[:-1].split("[")
        converted = out[f"{stem}[{names[unit]}]"]
        np.testing.assert_allclose(converted, values * factors[unit], rtol=1e-15, atol=0)


def test_inches_multi_input_and_whitespace_in_names():
    mf = kl.io.ModelFile.read("examples/fivebar.toml")
    sol = kl.analyze(mf.mechanism, *mf.sample_inputs(5))
    cols = sol.columns(units={"length": "in", "angle": "deg"})
    a, b = sol.input_names
    assert cols["P.x[in]"] == pytest.approx(sol.position("P")[:, 0] / 0.0254, rel=1e-15)
    K = sol.K("P")                                     # (N, 2, M)
    assert cols[f"P.y.K.{a}[in/deg]"] == pytest.approx(K[:, 1, 0] * DEG / 0.0254, rel=1e-15)
    L = sol.L("coupler1")                              # (N, M, M)
    assert cols[f"coupler1.L.{a}.{b}[deg/deg^2]"] == pytest.approx(L[:, 0, 1] * DEG, rel=1e-15)


def test_whitespace_becomes_underscore_and_a_clash_is_refused():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    named = kl.model.Mechanism(fb.name, fb.points, fb.links, fb.joints,
                               (kl.model.Input(joint=fb.inputs[0].joint, name="crank angle"),))
    cols = kl.analyze(named, q=[0.0, 1.0]).columns(degrees=True)
    assert "crank_angle.q[deg]" in cols and not any(" " in n for n in cols)
    # a crank named 'rocker_arm' and a rocker named 'rocker arm': one column name for both
    text = open("examples/crank_rocker.toml").read()
    text = text.replace('"rocker"', '"rocker arm"').replace('"crank"', '"rocker_arm"')
    clash = kl.io.from_toml(text)
    with pytest.raises(ModelError, match=r"^columns: 'rocker_arm' and 'rocker arm' both give the "
                                         r"column 'rocker_arm\.angle\[rad\]' \(whitespace becomes "
                                         r"'_' in column names\); rename one$"):
        kl.analyze(clash, q=[0.0, 1.0]).columns()


@pytest.mark.parametrize("units, message", [
    ({"length": "furlong"}, r"units\.length: expected one of 'm', 'cm', 'mm', 'in', got 'furlong'"),
    ({"angle": "gon"}, r"units\.angle: expected one of 'rad', 'deg', got 'gon'"),
    ({"time": "min"}, r"units: expected the keys 'length' and 'angle', got 'time'"),
])
def test_unknown_units_are_refused_and_nothing_is_written(sol, tmp_path, units, message):
    with pytest.raises(ModelError, match=message):
        sol.columns(units=units)
    with pytest.raises(ModelError, match=message):
        kl.io.write_results(sol, tmp_path / "r.csv", units=units)
    with pytest.raises(ModelError, match=message):
        sol.to_dataframe(units=units)
    assert list(tmp_path.iterdir()) == []


def test_csv_round_trip_in_mm_and_deg(sol, tmp_path):
    path = tmp_path / "out" / "run.csv"
    sol.to_csv(path, units={"length": "mm", "angle": "deg"})
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == list(sol.columns(units={"length": "mm", "angle": "deg"}))
    assert len(rows) == 4
    col = {name: np.array([float(r[k]) for r in rows[1:]]) for k, name in enumerate(rows[0])}
    # back to SI by hand: the text round trip loses nothing (repr of floats)
    np.testing.assert_allclose(col["slide.slide[mm]"] * MM, sol.slide("slide"), rtol=1e-15)
    np.testing.assert_allclose(col["rod.alpha[deg/s^2]"] * DEG, sol.alpha("rod"), rtol=1e-15)
    np.testing.assert_allclose(col["B.y.L[mm/deg^2]"] * MM / DEG ** 2, sol.L("B")[:, 1], rtol=1e-15)
    assert [p.name for p in path.parent.iterdir()] == ["run.csv"]        # no temporary left behind
    df = sol.to_dataframe(units={"length": "cm"})
    assert df.shape == (3, len(sol.columns()))
    assert df["B.vx[cm/s]"].to_numpy() == pytest.approx(sol.velocity("B")[:, 0] * 100, rel=1e-15)


@pytest.mark.parametrize("fmt", ["json", "parquet"])
def test_json_and_parquet_in_units(sol, tmp_path, fmt):
    pd = pytest.importorskip("pandas")
    if fmt == "parquet":
        pytest.importorskip("pyarrow")
    path = kl.io.write_results(sol, tmp_path / f"r.{fmt}", units={"length": "mm", "angle": "deg"})
    frame = pd.read_json(path) if fmt == "json" else pd.read_parquet(path)
    assert list(frame.columns) == list(sol.columns(units={"length": "mm", "angle": "deg"}))
    np.testing.assert_allclose(frame["B.x[mm]"], sol.position("B")[:, 0] / MM, rtol=1e-15)
    np.testing.assert_allclose(frame["rod.omega[deg/s]"], sol.omega("rod") / DEG, rtol=1e-15)
