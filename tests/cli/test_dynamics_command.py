"""``kinelab dynamics`` on model files with a [dynamics] section."""
import csv
import re
from pathlib import Path

import numpy as np

import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.model import Mechanism
from tests.dynamics.models import engine, prrrr


def write(m, tmp_path, units=None):
    path = tmp_path / f"{m.name}.toml"
    kl.io.save(m, path, units=units)
    return str(path)


def test_writes_table_and_figures(tmp_path):
    m = engine()
    m = Mechanism(m.name, m.points, m.links, m.joints,
                  (type(m.inputs[0])(joint="jO2", speed=100.0),),
                  parameters={"dynamics": {"gravity": [0.0, -9.81],
                                           "forces": [{"point": "B", "link": "slider",
                                                       "fx": "-500 * (sin(q) > 0)"}]}})
    path = write(m, tmp_path)
    assert kl.load(path).parameters["dynamics"]["forces"][0]["fx"] == "-500 * (sin(q) > 0)"
    out = tmp_path / "out"
    result = CliRunner().invoke(main, ["dynamics", path, "--out", str(out), "--samples", "73",
                                       "--degrees"])
    assert result.exit_code == 0, result.output
    assert "jO2: peak |effort|" in result.output and "shaking force: peak" in result.output
    for suffix in ("dynamics.csv", "efforts.png", "reactions.png", "shaking.png"):
        assert (out / f"engine_{suffix}").stat().st_size > 0
    with open(out / "engine_dynamics.csv") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 73 and float(rows[-1]["jO2.q[deg]"]) == pytest.approx(360.0, rel=1e-15)
    assert {"jO2.torque[N*m]", "shaking_force.x[N]", "jA.reaction.y[N]",
            "slide.reaction_moment[N*m]", "kinetic_energy[J]", "actuator_power[W]"} <= set(rows[0])
    assert not any(" " in name for name in rows[0])


def test_kinematic_columns_in_file_units_forces_in_si(tmp_path):
    m = engine()
    m = Mechanism(m.name, m.points, m.links, m.joints,
                  (type(m.inputs[0])(joint="jO2", speed=100.0),),
                  parameters={"dynamics": {"gravity": [0.0, -9.81]}})
    path = write(m, tmp_path, units={"length": "mm", "angle": "deg"})
    mf = kl.io.ModelFile.read(path)
    ref = kl.dynamics.inverse(mf.mechanism, *mf.sample_inputs(37))
    for flags, factor, unit in (([], 180 / np.pi, "deg"), (["--si"], 1.0, "rad")):
        out = tmp_path / f"out{len(flags)}"
        result = CliRunner().invoke(main, ["dynamics", path, "--out", str(out), "--samples", "37",
                                           "--no-plots", *flags])
        assert result.exit_code == 0, result.output
        with open(out / "engine_dynamics.csv") as f:
            rows = list(csv.DictReader(f))
        col = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
        # positions and rates: the file's degrees, or rad with --si
        np.testing.assert_allclose(col[f"jO2.q[{unit}]"], ref.q[:, 0] * factor, rtol=1e-15)
        np.testing.assert_allclose(col[f"jO2.qd[{unit}/s]"], ref.qd[:, 0] * factor, rtol=1e-15)
        # efforts, forces, energies: SI whatever the file's units
        np.testing.assert_allclose(col["jO2.torque[N*m]"], ref.input_forces[:, 0], rtol=1e-15)
        np.testing.assert_allclose(col["kinetic_energy[J]"], ref.kinetic_energy, rtol=1e-15)
        assert "t[s]" in col
    # the speed, 100 rad/s, went through the file in deg/s rounded to 12 digits
    assert float(rows[0]["jO2.qd[rad/s]"]) == pytest.approx(100.0, rel=1e-11)


def test_two_inputs_need_ranges(tmp_path):
    m = prrrr()
    result = CliRunner().invoke(main, ["dynamics", write(m, tmp_path), "--out", str(tmp_path),
                                       "--no-plots"])
    assert result.exit_code == 2
    assert "kinelab: error: " in result.output and "range" in result.output
    Input = type(m.inputs[0])
    m2 = Mechanism(m.name, m.points, m.links, m.joints,
                   (Input(joint="rail", range=(0.15, 0.25), speed=0.1),
                    Input(joint="jO2", range=(1.0, 1.4), speed=0.5)))
    result = CliRunner().invoke(main, ["dynamics", write(m2, tmp_path), "--out", str(tmp_path),
                                       "--no-plots", "--gravity", "0,-9.81", "--samples", "5"])
    assert result.exit_code == 0, result.output
    assert "rail: peak |effort|" in result.output and "jO2: peak |effort|" in result.output
    assert not (tmp_path / "prrrr_efforts.png").exists()


def test_missing_masses_and_bad_gravity(tmp_path):
    path = write(kl.mechanisms.slider_crank(crank=1.0, rod=3.0), tmp_path)
    result = CliRunner().invoke(main, ["dynamics", path, "--out", str(tmp_path)])
    assert result.exit_code == 2 and "link 'crank': mass: missing" in result.output
    result = CliRunner().invoke(main, ["dynamics", path, "--gravity", "9.81"])
    assert result.exit_code == 2 and "expected GX,GY in m/s^2" in result.output


def test_dynamics_section_errors_name_the_file_and_field(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('schema = 1\n[units]\nlength = "m"\nangle = "rad"\n'
                    '[catalogue]\nkind = "slider_crank"\ncrank = 1.0\nrod = 3.0\n'
                    '[dynamics]\ngravity = [0, -9.81]\n[dynamics.actuators]\njA = "__import__(1)"\n')
    with pytest.raises(kl.errors.ModelError) as info:
        kl.load(path)
    text = str(info.value)
    assert text.startswith("bad.toml: dynamics.actuators.jA: the function '__import__' is not "
                           "allowed in the expression '__import__(1)'")


def test_library_calls_use_the_files_dynamics_section(tmp_path):
    """inverse() and simulate() of a loaded model apply its [dynamics] loads and actuators."""
    path = tmp_path / "pendulum.toml"
    path.write_text('schema = 1\nname = "pendulum"\n[units]\nlength = "m"\nangle = "rad"\n'
                    '[points]\nO = [0, 0]\nG = [0.5, 0]\n'
                    '[[links]]\nname = "ground"\npoints = ["O"]\nground = true\n'
                    '[[links]]\nname = "arm"\npoints = ["O", "G"]\nmass = 2.0\ncenter_of_mass = "G"\ninertia = 0.01\n'
                    '[[joints]]\nname = "pivot"\ntype = "R"\nlinks = ["ground", "arm"]\npoint = "O"\n'
                    '[[inputs]]\njoint = "pivot"\n'
                    '[dynamics]\ngravity = [0.0, -10.0]\n[dynamics.actuators]\npivot = 10.0\n')
    m = kl.load(path)
    res = kl.dynamics.inverse(m, q=[0.0, 1.0])
    # tau = m g L cos(theta) (*Mecanismos*, §5), with gravity from the file
    assert res.input_forces[:, 0] == pytest.approx([10.0, 10.0 * np.cos(1.0)], abs=1e-12)
    # held by the file's constant 10 N m at theta = 0, the pendulum stays put
    sim = kl.dynamics.simulate(m, (0.0, 0.5), q0=0.0, qd0=0.0, t_eval=[0.5])
    assert sim.q[-1, 0] == pytest.approx(0.0, abs=1e-9)


ENGINE = Path(__file__).parents[2] / "examples" / "engine.toml"


def engine_with_torque(tmp_path, law):
    """examples/engine.toml with a torque on the crank given by ``law``."""
    path = tmp_path / "engine.toml"
    path.write_text(ENGINE.read_text() + f'\n[[dynamics.torques]]\nlink = "crank"\ntorque = "{law}"\n')
    return str(path)


def ends_with_one_error_line(result, message):
    """Exit status 2 and a last line 'kinelab: error: engine.toml: <field>: <message>', no traceback."""
    lines = result.output.strip().splitlines()
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert [n for n, line in enumerate(lines) if line.startswith("kinelab: error:")] == [len(lines) - 1]
    assert re.match(r"kinelab: error: engine\.toml: dynamics\.torques\[0\]\.torque: " + message,
                    lines[-1]), lines[-1]


@pytest.mark.parametrize("law, message", [
    ("+".join(["1"] * 900), r"the expression '1\+1\+.*' has 1799 numbers, names and operators; "
                            r"expected at most 1000"),
    ("1/0", r"division by zero in the expression '1/0'"),
    ("10**400", r"the expression '10\*\*400' has no variables and evaluates to inf"),
    ("9**9**9", r"the power tower '9\*\*9\*\*9' is not allowed"),
])
@pytest.mark.parametrize("command", ["check", "dynamics"])
def test_laws_beyond_the_bounds_end_in_one_line(tmp_path, command, law, message):
    path = engine_with_torque(tmp_path, law)
    args = [command, path] + (["--out", str(tmp_path), "--no-plots"] if command == "dynamics" else [])
    ends_with_one_error_line(CliRunner().invoke(main, args), message)
    assert not (tmp_path / "engine_dynamics.csv").exists()


@pytest.mark.parametrize("command", ["check", "dynamics"])
def test_a_law_that_is_not_finite_on_the_sweep_is_found(tmp_path, command):
    """1/sin(q) at the crank's first sample, q = 0: 'kinelab check' evaluates the loads
    where 'kinelab dynamics' will."""
    path = engine_with_torque(tmp_path, "1 / sin(q)")
    args = [command, path] + (["--out", str(tmp_path), "--no-plots"] if command == "dynamics" else [])
    ends_with_one_error_line(CliRunner().invoke(main, args),
                             r"the expression '1 / sin\(q\)' gives inf \(an overflow or a division by "
                             r"zero\) at t = 0 s, q = 0, qd = 31.4159; expected a finite value")


@pytest.mark.parametrize("section, message", [
    ('[dynamics.actuators]\n"j\\u001b[31mX\\nY" = 1.0\n',
     r"dynamics\.actuators: 'j\\x1b\[31mX\\nY' is not an input; the inputs are 'crank angle'"),
    ('[dynamics]\nmassless = ["a\\u001b[31mb\\nc"]\n',
     r"massless: expected a link of 'engine', got 'a\\x1b\[31mb\\nc'; its links are"),
    ('[dynamics]\npoint_masses = {"P\\nQ" = 1.0}\n',
     r"point_masses: expected a point of 'engine', got 'P\\nQ'"),
    ('[[dynamics.torques]]\nlink = "c\\nd"\ntorque = 1.0\n',
     r"torques\[0\]: link: expected a link of 'engine', got 'c\\nd'"),
])
@pytest.mark.parametrize("command", ["check", "dynamics"])
def test_names_in_the_dynamics_section_are_shown_escaped_on_one_line(tmp_path, section, message,
                                                                     command):
    """A name the model does not have is quoted in the error as Python would write it: a
    newline or an escape sequence in it cannot split the error or reach the terminal."""
    text = ENGINE.read_text()
    if section.startswith("[dynamics]"):        # the example's own section, with one more key
        text = text.replace("[dynamics]", section.rstrip("\n"), 1)
    else:
        text += "\n" + section
    path = tmp_path / "engine.toml"
    path.write_text(text)
    args = [command, str(path)] + (["--out", str(tmp_path), "--no-plots"] if command == "dynamics" else [])
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len([line for line in lines if line.startswith("kinelab: error:")]) == 1, result.output
    assert "\x1b" not in result.output
    assert re.search(message, lines[-1]), lines[-1]


def test_efforts_that_overflow_are_refused_not_written_as_inf(tmp_path):
    """Each value of the law 1e307 q is finite, but the efforts and powers it makes are not:
    an error, not inf in the table."""
    path = engine_with_torque(tmp_path, "1e307*q")
    result = CliRunner().invoke(main, ["dynamics", path, "--out", str(tmp_path), "--no-plots"])
    assert result.exit_code == 2, result.output
    assert re.search(r"kinelab: error: engine\.toml: the efforts of 'engine' overflow at t = \S+ s, "
                     r"q = \[\S+\]: a load, speed or mass is too large", result.output.splitlines()[-1])
    assert not (tmp_path / "engine_dynamics.csv").exists()


def test_huge_but_finite_efforts_are_summarised_without_overflow(tmp_path):
    """1e300 q' N m at 1800 deg/s (10 pi rad/s): peak and rms are pi 1e301 N m (the rms of
    huge numbers is taken without squaring them into inf)."""
    path = engine_with_torque(tmp_path, "1e300*qd")
    result = CliRunner().invoke(main, ["dynamics", path, "--out", str(tmp_path), "--no-plots"])
    assert result.exit_code == 0, result.output
    assert "crank angle: peak |effort| 3.14159e+301 N m, rms 3.14159e+301 N m" in result.output


def test_a_table_past_the_bound_is_refused_before_the_work(tmp_path):
    from kinelab.cli._dynamics import MAX_VALUES
    path = write(engine(), tmp_path)
    res = CliRunner().invoke(main, ["dynamics", path, "--samples", "1000000", "--out", str(tmp_path)])
    assert res.exit_code == 2
    assert res.output.startswith("kinelab: error: engine.toml: --samples: a table of 1,000,000 "
                                 "samples x ") and res.output.count("\n") == 1
    assert f"writes at most {MAX_VALUES:,}" in res.output
    assert [p.name for p in tmp_path.iterdir()] == ["engine.toml"]
