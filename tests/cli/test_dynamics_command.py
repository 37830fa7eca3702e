"""``kinelab dynamics``, run on models built in Python (model files arrive with kinelab.io)."""
import csv

import numpy as np
import pytest
from click.testing import CliRunner

import kinelab.io
from kinelab.cli._dynamics import dynamics_command, sweep_inputs
from kinelab.model import Mechanism
from tests.dynamics.models import engine, prrrr


@pytest.fixture
def model_file(tmp_path, monkeypatch):
    """A file name whose loading gives a Python-built model."""
    def use(m):
        path = tmp_path / f"{m.name}.toml"
        path.write_text("# stands for the model file\n")
        monkeypatch.setattr(kinelab.io, "load", lambda p: m, raising=False)
        return str(path)
    return use


def test_writes_table_and_figures(model_file, tmp_path):
    m = engine()
    m = Mechanism(m.name, m.points, m.links, m.joints,
                  (type(m.inputs[0])(joint="jO2", speed=100.0),),
                  parameters={"dynamics": {"gravity": [0.0, -9.81],
                                           "forces": [{"point": "B", "link": "slider",
                                                       "fx": "-500 * (sin(q) > 0)"}]}})
    out = tmp_path / "out"
    result = CliRunner().invoke(dynamics_command, [model_file(m), "--out", str(out), "--samples", "73",
                                                   "--degrees"])
    assert result.exit_code == 0, result.output
    assert "jO2: peak |effort|" in result.output and "shaking force: peak" in result.output
    for suffix in ("dynamics.csv", "efforts.png", "reactions.png", "shaking.png"):
        assert (out / f"engine_{suffix}").stat().st_size > 0
    with open(out / "engine_dynamics.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 73 and float(rows[-1]["jO2.q [deg]"]) == pytest.approx(360.0)
    assert {"jO2.torque [N m]", "shaking_force.x [N]", "jA.reaction.y [N]",
            "slide.reaction_moment [N m]"} <= set(rows[0])


def test_two_inputs_need_ranges(model_file, tmp_path):
    m = prrrr()
    result = CliRunner().invoke(dynamics_command, [model_file(m), "--out", str(tmp_path), "--no-plots"])
    assert result.exit_code == 1
    assert "inputs[0] ('rail'): range: the sweep needs a range for this input" in result.output
    Input = type(m.inputs[0])
    m2 = Mechanism(m.name, m.points, m.links, m.joints,
                   (Input(joint="rail", range=(0.15, 0.25), speed=0.1),
                    Input(joint="jO2", range=(1.0, 1.4), speed=0.5)))
    result = CliRunner().invoke(dynamics_command, [model_file(m2), "--out", str(tmp_path), "--no-plots",
                                                   "--gravity", "0,-9.81", "--samples", "5"])
    assert result.exit_code == 0, result.output
    assert "rail: peak |effort|" in result.output and "jO2: peak |effort|" in result.output
    q, qd, _, t = sweep_inputs(m2, 5)
    np.testing.assert_allclose(q[:, 1], np.linspace(1.0, 1.4, 5))
    assert not (tmp_path / "prrrr_efforts.png").exists()


def test_missing_masses_and_bad_gravity(model_file, tmp_path):
    import kinelab as kl
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)
    result = CliRunner().invoke(dynamics_command, [model_file(sc), "--out", str(tmp_path)])
    assert result.exit_code == 1 and "link 'crank': mass: missing" in result.output
    result = CliRunner().invoke(dynamics_command, [model_file(sc), "--gravity", "9.81"])
    assert result.exit_code == 2 and "expected GX,GY in m/s^2" in result.output
