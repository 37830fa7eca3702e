"""``kinelab check`` and ``kinelab analyze`` on model files with gear joints (type ``G``)."""
from pathlib import Path

import pytest
from click.testing import CliRunner

from kinelab.cli import main

EX = Path(__file__).parents[2] / "examples"
TRAIN = (EX / "gear_train.toml").read_text()


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


@pytest.mark.parametrize("stem", ["gear_train", "compound_gear_train", "planetary",
                                  "rack_and_pinion", "geared_fivebar"])
def test_check_and_analyze_take_gear_joints(stem, tmp_path):
    result = run("check", EX / f"{stem}.toml")
    assert result.exit_code == 0, result.output
    assert "geared to" in result.output or "driven by pinion" in result.output
    result = run("analyze", EX / f"{stem}.toml", "--out", tmp_path, "-q")
    assert result.exit_code == 0, result.output
    assert (tmp_path / f"{stem}.csv").exists()


def test_train_value_in_the_table(tmp_path):
    result = run("analyze", EX / "gear_train.toml", "--out", tmp_path)
    assert result.exit_code == 0, result.output
    line = next(s for s in result.output.splitlines() if s.strip().startswith("gear3.omega"))
    assert line.split()[1] == "180"           # deg/s: 360 deg/s times e = +20/40


# one bad gear field each: (change to the simple train's file, the one-line message)
BAD = [
    ("teeth = [20, 30]", "teeth = [0, 30]",
     "joints[3].teeth: expected positive numbers of teeth, got (0, 30); a gear has at least one tooth"),
    ("teeth = [20, 30]", "teeth = [-20, 30]", "joints[3].teeth: expected positive numbers of teeth"),
    ("teeth = [20, 30]", "teeth = [20.5, 30]", "joints[3].teeth: expected two whole numbers of teeth"),
    ("teeth = [20, 30]\n", "",
     "joints[3].ratio: an external gear pair needs its ratio: give one of ratio (N_b / N_a), "
     "radii = [r_a, r_b] (m) or teeth = [N_a, N_b]"),
    ("teeth = [20, 30]", "radii = [20]", "joints[3].radii: expected two pitch radii [r_a, r_b], got [20]"),
    ("teeth = [20, 30]", "radii = [20, -30]", "joints[3].radii: expected a length from"),
    ("teeth = [20, 30]", "ratio = 0", "joints[3].ratio: expected a positive number"),
    ('links = ["gear1", "idler"]', 'links = ["idler", "idler"]',
     "joints[3]: joins link 'idler' to itself; a joint joins two different links"),
    ("teeth = [20, 30]", 'teeth = [20, 30]\nmesh = "inside"',
     "joints[3].mesh: expected one of 'external', 'internal', 'rack', got 'inside'"),
    ("teeth = [20, 30]", 'teeth = [20, 30]\ncarrier = "arm"',
     "joints[3].carrier: expected a declared link, got 'arm'"),
    ("teeth = [20, 30]", 'teeth = [20, 30]\nmesh = "rack"',
     "joints[3].teeth: a rack and pinion is set by radius"),
]


@pytest.mark.parametrize("old, new, message", BAD, ids=[b[2].split(":")[0] + b[1][:12] for b in BAD])
def test_bad_gear_fields_exit_2_with_one_line(old, new, message, tmp_path):
    assert old in TRAIN
    model = tmp_path / "train.toml"
    model.write_text(TRAIN.replace(old, new, 1))
    for command in (["check", model], ["analyze", model, "--out", tmp_path / "out"]):
        result = run(*command)
        assert result.exit_code == 2, result.output
        lines = result.output.strip().splitlines()
        assert any(line.startswith("kinelab: error: train.toml: ") and message in line
                   for line in lines), result.output
    assert not (tmp_path / "out").exists()
