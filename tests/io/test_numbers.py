"""One rule of what a number is (kinelab.io._text.NUMBER): ASCII digits in decimal or
scientific notation, the same in model files, task files, Pyslvs expressions, CSV tables
(tests/io/test_csv.py) and the numbers typed on the command line."""
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.errors import ModelError
from kinelab.io._text import number

EXAMPLE = "examples/crank_rocker.toml"
RULE = "expected a number in decimal or scientific notation in ASCII digits"


@pytest.mark.parametrize("text, value", [
    ("0", 0.0), ("-12", -12.0), ("+1.5", 1.5), (".5", 0.5), ("5.", 5.0), ("1e3", 1000.0),
    ("1.5E-3", 0.0015), (" 7 ", 7.0), ("\t7", 7.0), ("1e999", float("inf")),
    ("1_000", None), ("0x10", None), ("0o17", None), ("0b1", None), ("nan", None),
    ("inf", None), ("Infinity", None), ("\uff11\uff12", None), ("\u0661\u0662", None),
    ("\u00b2", None), ("1e", None), ("e1", None), (".", None), ("", None), ("1 000", None),
    ("1,5", None), ("7\n", None), ("\u00a07", None),
])
def test_what_a_number_is(text, value):
    assert number(text) == value


def test_a_long_run_of_digits_is_decided_at_once():
    """A regular expression that could match digits two ways would take minutes on this."""
    assert number("1" * 200_000 + "x") is None
    assert number("1" * 200_000) == float("inf")


@pytest.mark.parametrize("value", ["300_0", "0x12c", "0o454", "0b100101100", "3e0_2", "+3_00"])
def test_a_model_file_writes_numbers_plainly(tmp_path, value):
    text = open(EXAMPLE).read().replace("O4 = [300, 0]", f"O4 = [{value}, 0]")
    path = tmp_path / "m.toml"
    path.write_text(text)
    line = text[:text.index(value)].count("\n") + 1
    with pytest.raises(ModelError) as info:
        kl.load(path)
    assert str(info.value) == (f"m.toml: line {line}, column 7: {RULE} (1000, -0.5, 1.5e3), got "
                               f"'{value}'; write it in plain digits")


def test_keys_and_text_may_hold_what_numbers_may_not(tmp_path):
    """Names with digits and underscores, and text, are not numbers."""
    text = (open(EXAMPLE).read().replace("O2", "O_2").replace('description = "', 'description = '
                                                                '"1_000 0x10 ')
            .replace('name = "coupler"', 'name = "coupler_1"').replace('"coupler"', '"coupler_1"'))
    path = tmp_path / "m.toml"
    path.write_text(text)
    m = kl.load(path)
    assert "O_2" in m.point_names and "coupler_1" in m.link_names


def test_a_task_file_writes_numbers_plainly(tmp_path):
    task = tmp_path / "t.toml"
    task.write_text('task = "crank-rocker"\n[units]\nangle = "deg"\n'
                    "[crank_rocker]\nground = 1_0\nswing = 45\ntime_ratio = 1.25\n")
    with pytest.raises(ModelError, match=rf"t\.toml: line 5, column 10: {RULE}.*got '1_0'"):
        kl.io.load_task(task)
    r = CliRunner().invoke(main, ["synth", str(task), "--no-figures", "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and r.stderr.count("\n") == 1 and "t.toml: line 5, column 10" in r.stderr


@pytest.mark.parametrize("digits", ["\uff10", "\u0660", "1_0"])
def test_a_pyslvs_expression_writes_numbers_plainly(digits):
    with pytest.raises(ModelError, match=r"expression: character \d+: "):
        kl.io.from_pyslvs(f"M[J[R, P[0, {digits}], L[ground, a]], J[R, P[0, 1], L[a, ground]]]")


@pytest.mark.parametrize("option, value", [("--range", "crank=1_0:2"), ("--range", "crank=1:\uff12"),
                                           ("--speed", "1_0")])
def test_sweep_options_follow_the_rule(option, value, tmp_path):
    args = ["sweep", "fourbar", "--sobol", "4", "--range", "ground=2:3", option, value,
            "-o", str(tmp_path / "s.csv")]
    r = CliRunner().invoke(main, args)
    assert r.exit_code == 2 and r.stderr.count("\n") == 1, r.output
    assert "decimal or scientific notation in ASCII digits" in r.stderr


@pytest.mark.parametrize("option, value", [("--width", "1_0"), ("--hole", "\uff11"),
                                           ("--width", "nan"), ("--width", "-1")])
def test_export_numbers_follow_the_rule(option, value, tmp_path):
    r = CliRunner().invoke(main, ["export", EXAMPLE, "--to", "svg", option, value, "--out",
                                  str(tmp_path)])
    assert r.exit_code == 2 and r.stderr.count("\n") == 1, r.output
    assert f"Invalid value for '{option}'" in r.stderr
