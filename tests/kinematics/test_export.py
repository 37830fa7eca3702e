"""Results export: named columns with units, degrees at the edge only, atomic CSV."""
import csv

import numpy as np
import pytest

import kinelab as kl


@pytest.fixture(scope="module")
def sol():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.2)
    return kl.analyze(sc, q=np.radians([10.0, 50.0, 90.0]), qd=2.0, qdd=0.5)


def test_columns_have_units_and_values(sol):
    cols = sol.columns()
    assert cols["rod.angle [rad]"] == pytest.approx(sol.angle("rod"))
    assert cols["rod.K [rad/rad]"] == pytest.approx(sol.K("rod"))
    assert cols["slide.slide [m]"] == pytest.approx(sol.slide("slide"))
    assert cols["slide.L [m/(rad*rad)]"] == pytest.approx(sol.L("slide"))
    assert cols["B.ax [m/s^2]"] == pytest.approx(sol.acceleration("B")[:, 0])
    assert cols["B.y.K [m/rad]"] == pytest.approx(sol.K("B")[:, 1])
    assert cols["jO2.q [rad]"] == pytest.approx(np.radians([10.0, 50.0, 90.0]))
    assert cols["singular"].dtype == bool
    assert all(len(v) == 3 for v in cols.values())


def test_degrees_only_change_angle_units(sol):
    deg = sol.columns(degrees=True)
    f = 180 / np.pi
    assert deg["rod.angle [deg]"] == pytest.approx(sol.angle("rod") * f)
    assert deg["rod.omega [deg/s]"] == pytest.approx(sol.omega("rod") * f)
    assert deg["rod.K [deg/deg]"] == pytest.approx(sol.K("rod"))            # dimensionless
    assert deg["slide.K [m/deg]"] == pytest.approx(sol.K("slide") / f)
    assert deg["slide.L [m/(deg*deg)]"] == pytest.approx(sol.L("slide") / f ** 2)
    assert deg["jO2.q [deg]"] == pytest.approx([10.0, 50.0, 90.0])
    assert deg["B.x [m]"] == pytest.approx(sol.position("B")[:, 0])


def test_csv_and_dataframe(sol, tmp_path):
    path = tmp_path / "out" / "run.csv"
    sol.to_csv(path)
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == list(sol.columns())
    assert len(rows) == 4
    assert float(rows[1][rows[0].index("slide.slide [m]")]) == pytest.approx(sol.slide("slide")[0], abs=1e-15)
    assert [p.name for p in path.parent.iterdir()] == ["run.csv"]        # no temporary left behind
    df = sol.to_dataframe(degrees=True)
    assert df.shape == (3, len(sol.columns()))
